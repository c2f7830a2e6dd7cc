#pragma once
// What `--prune` (or a case's `[solve] prune`) names: "auto", or stages of contractors. A
// stage is a comma-separated list; '/' starts a stage that runs only when the stages before it
// stall ("hc4,newton/lp": the LP relaxation only where propagation and Newton no longer shrink
// the box). The text is parsed once, where it comes in; reports and the messages between
// processes carry the canonical text. The contractors and their names are one table, in
// strategy.cpp: the parser, the help text, the error messages and the factory
// (solve/pruning.hpp) all read it.
#include <string>
#include <vector>

namespace linkbox::solve {

enum class ContractorKind { trapezoid, lp, hc4, acid, newton, taylor };

const char* name_of(ContractorKind kind);
// The contractors' names, as the help text and the error messages list them: "trapezoid, lp, ...".
std::string contractor_names();

class Strategy {
 public:
  using Stage = std::vector<ContractorKind>;

  Strategy() = default;  // none: what a sub-problem that no search reached ran (text "")
  explicit Strategy(std::vector<Stage> stages) : stages_(std::move(stages)) {}
  static Strategy automatic();
  // "hc4,newton/lp"; spaces are ignored. std::invalid_argument for an unknown name, for no
  // contractor at all, and for "auto" beside other names ("auto" chooses the whole strategy).
  static Strategy parse(const std::string& text);

  bool is_auto() const { return auto_; }
  bool empty() const;  // none (see above)
  bool uses(ContractorKind kind) const;
  // In order. A stage may be empty ("hc4//lp" keeps its text): it runs as no stage at all.
  const std::vector<Stage>& stages() const { return stages_; }
  std::string text() const;  // canonical: parse(text()) == *this

  friend bool operator==(const Strategy&, const Strategy&) = default;

 private:
  bool auto_ = false;
  std::vector<Stage> stages_;
};

// What narrows a curve's boxes after the search (solve/narrow.hpp), whatever the search ran:
// around a smooth arc a box's solutions lie near a line, which a linear relaxation in the
// system's own variables encloses tightly and propagation, one variable at a time, does not.
Strategy narrowing_strategy();

}  // namespace linkbox::solve
