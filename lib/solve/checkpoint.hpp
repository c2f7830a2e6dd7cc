#pragma once
// A run's state on disk, so that a stopped, interrupted or crashed run resumes where it was
// and ends with the boxes an unbroken run gives. Per sub-problem: not started, searching (each
// raced candidate's search state and the race's position), or finished (its result).
// Written with solve/output_file.hpp: atomically where the file is a regular one.
#include "prune/counters.hpp"
#include "solve/search_state.hpp"
#include "solve/result.hpp"

#include <atomic>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace linkbox::solve {

// Where a race between candidate strategies stands (see solve/race.hpp).
struct RacePosition {
  double turn = 0;
  size_t next = 0;     // the position, in this round's order (the lead first), of the run under way or next
  size_t lead = 0;     // the candidate with the best projection this round
  double target = -1;  // the work the running candidate runs up to; < 0: not yet set
  int winner = -1;     // >= 0: the race is over; the winner's result is being refined
  std::vector<std::string> choices;  // each choice of the lead, with its reasons (race.cpp)
  // Per candidate: its (work, share of the tree resolved) at each choice of the lead.
  std::vector<std::vector<std::pair<double, double>>> progress;
};

struct SubCheckpoint {
  enum class Phase { not_started, searching, finished };
  Phase phase = Phase::not_started;
  // searching: per candidate
  std::vector<SearchState> searches;
  std::vector<std::vector<prune::Counters>> counters;
  RacePosition race;
  // finished
  SubResult result;
};

struct Checkpoint {
  std::string header;  // JSON object text: what the run was (case, settings); compared on resume
  std::vector<SubCheckpoint> subproblems;
};

// JSON text of one sub-problem's state (what solve_case deposits as it goes) and of a whole
// checkpoint from such pieces.
std::string to_json_text(const SubCheckpoint& s);
std::string checkpoint_text(const std::string& header, const std::vector<std::string>& subproblems);
// The reverse of to_json_text (distributed/ sends sub-problem states between processes as such
// text). Throws std::invalid_argument.
SubCheckpoint sub_checkpoint_from_text(const std::string& text);

// Throws std::invalid_argument naming the file for anything that is not a linkbox checkpoint.
Checkpoint read_checkpoint(const std::string& path);

// Collects each sub-problem's state as it goes and writes the checkpoint. A running search
// deposits its state whenever a new checkpoint generation starts (it pauses between two boxes
// for that); a sub-problem that is not running (not started, refining, finished) keeps its
// last deposit. The file is written once every running one has deposited for the generation,
// by whichever deposits last.
class Checkpointer {
 public:
  Checkpointer() = default;  // writes nothing
  // Every `every` seconds to `path`, with `header` (Checkpoint::header), for `subproblems`.
  Checkpointer(std::string path, double every, std::string header, size_t subproblems);
  bool enabled() const { return !path_.empty(); }
  int generation() const { return generation_.load(); }
  // running: the state changes and must be deposited again for every new generation.
  void deposit(size_t i, const SubCheckpoint& state, bool running);
  void tick(double elapsed);  // the run's clock: starts a generation when one is due
  void final_write();         // throws when the file cannot be written

 private:
  struct Slot {
    std::string text;
    int generation;
    bool running;
  };
  void write_when_ready();
  void write(bool last);
  std::string path_;
  double every_ = 0;
  std::string header_;
  std::atomic<int> generation_{0};
  int written_ = 0;
  double next_ = 0;
  std::mutex m_;
  std::vector<Slot> slots_;
};

}  // namespace linkbox::solve
