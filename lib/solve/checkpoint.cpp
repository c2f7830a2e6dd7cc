#include "solve/checkpoint.hpp"

#include "interval/box_json.hpp"
#include "solve/output_file.hpp"

#include <nlohmann/json.hpp>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace linkbox::solve {

using nlohmann::json;

namespace {

constexpr int kFormat = 2;

json num(double x) { return exact_json(x); }
double num(const json& j) { return exact_double(j); }
json box_out(const Box& b) { return exact_json(b); }
Box box_in(const json& j) { return exact_box(j); }

json stats_out(const Stats& s) {
  return {s.processed, s.empty, s.solution, s.split, s.shrinks, s.certified, s.certify_calls, num(s.seconds)};
}
Stats stats_in(const json& j) {
  Stats s;
  s.processed = j.at(0);
  s.empty = j.at(1);
  s.solution = j.at(2);
  s.split = j.at(3);
  s.shrinks = j.at(4);
  s.certified = j.at(5);
  s.certify_calls = j.at(6);
  s.seconds = num(j.at(7));
  return s;
}

json counters_out(const std::vector<prune::Counters>& cs) {
  json j = json::array();
  for (auto& c : cs) {
    json x = {c.calls, c.emptied, num(c.seconds), num(c.volume_removed), c.lps_solved, c.lp_iterations, num(c.operations)};
    if (c.lp_paths.any())
      x.push_back({c.lp_paths.basis, c.lp_paths.repaired, c.lp_paths.farkas, c.lp_paths.fallback, c.lp_paths.pivots});
    j.push_back(x);
  }
  return j;
}
std::vector<prune::Counters> counters_in(const json& j) {
  std::vector<prune::Counters> cs;
  for (auto& x : j) {
    prune::Counters c;
    c.calls = x.at(0);
    c.emptied = x.at(1);
    c.seconds = num(x.at(2));
    c.volume_removed = num(x.at(3));
    c.lps_solved = x.at(4);
    c.lp_iterations = x.at(5);
    c.operations = num(x.at(6));
    if (x.size() > 7) {
      const json& p = x.at(7);
      c.lp_paths = {p.at(0).get<long>(), p.at(1).get<long>(), p.at(2).get<long>(), p.at(3).get<long>(), p.at(4).get<long>()};
    }
    cs.push_back(c);
  }
  return cs;
}

json node_out(const SearchState::Node& n) { return {n.path, n.backoff.level, n.backoff.skip, box_out(n.box)}; }
SearchState::Node node_in(const json& n) {
  return {box_in(n.at(3)), n.at(0).get<std::string>(), {n.at(1).get<int>(), n.at(2).get<int>()}};
}

json search_out(const SearchState& s) {
  json pending = json::array(), found = json::array();
  for (auto& n : s.pending) pending.push_back(node_out(n));
  for (auto& f : s.solutions) found.push_back({f.path, f.certified, box_out(f.box)});
  json j = {{"pending", pending}, {"solutions", found}, {"stats", stats_out(s.stats)},
            {"work", num(s.work)}, {"volume_done", num(s.volume_done)}};
  if (!s.records.empty()) {
    json records = json::array();
    for (auto& r : s.records)
      records.push_back({r.path, std::string(1, r.outcome), num(r.work), num(r.volume), stats_out(r.stats), box_out(r.box),
                         r.dim, r.backoff.level, r.backoff.skip});
    j["records"] = std::move(records);
  }
  return j;
}
SearchState search_in(const json& j) {
  SearchState s;
  for (auto& n : j.at("pending")) s.pending.push_back(node_in(n));
  for (auto& f : j.at("solutions")) s.solutions.push_back({f.at(0).get<std::string>(), box_in(f.at(2)), f.at(1).get<bool>()});
  if (j.contains("records"))
    for (auto& r : j.at("records")) {
      SearchState::Record x;
      x.path = r.at(0).get<std::string>();
      const std::string outcome = r.at(1).get<std::string>();
      if (outcome.size() != 1 || std::string("escx").find(outcome[0]) == std::string::npos)
        throw std::invalid_argument("a box record with outcome '" + outcome + "'");
      x.outcome = outcome[0];
      x.work = num(r.at(2));
      x.volume = num(r.at(3));
      x.stats = stats_in(r.at(4));
      x.box = box_in(r.at(5));
      x.dim = r.at(6).get<int>();
      x.backoff = {r.at(7).get<int>(), r.at(8).get<int>()};
      s.records.push_back(std::move(x));
    }
  s.stats = stats_in(j.at("stats"));
  s.work = num(j.at("work"));
  s.volume_done = num(j.at("volume_done"));
  return s;
}

json boxes_out(const std::vector<Box>& boxes) {
  json j = json::array();
  for (auto& b : boxes) j.push_back(box_out(b));
  return j;
}
std::vector<Box> boxes_in(const json& j) {
  std::vector<Box> r;
  for (auto& b : j) r.push_back(box_in(b));
  return r;
}

// Format 1 stores a strategy as its names, with "/" between stages (none: no names).
json strategy_out(const Strategy& s) {
  json names = json::array();
  for (size_t k = 0; k < s.stages().size(); ++k) {
    if (k > 0) names.push_back("/");
    for (ContractorKind c : s.stages()[k]) names.push_back(name_of(c));
  }
  return names;
}
Strategy strategy_in(const json& names) {
  std::string text;
  for (const std::string name : names) text += (name == "/" || text.empty() || text.back() == '/' ? "" : ",") + name;
  return names.empty() ? Strategy() : Strategy::parse(text);
}

json result_out(const SubResult& r) {
  json residuals = json::array(), race = json::array();
  for (double x : r.residuals) residuals.push_back(num(x));
  for (auto& [name, work] : r.race) race.push_back({name, num(work)});
  return {{"index", r.index},
          {"label", r.label},
          {"equations", r.equations},
          {"variables", r.variables},
          {"solutions", boxes_out(r.solutions)},
          {"residuals", residuals},
          {"certified", std::vector<int>(r.certified.begin(), r.certified.end())},
          {"stats", stats_out(r.stats)},
          {"complete", r.complete},
          {"pending", boxes_out(r.pending)},
          {"volume_left", num(r.volume_left)},
          {"unrefined", r.unrefined},
          {"counters", counters_out(r.counters)},
          {"narrow_counters", counters_out(r.narrow_counters)},
          {"strategy", strategy_out(r.strategy)},
          {"bisect", r.bisect},
          {"race", race},
          {"race_choices", r.race_choices}};
}
SubResult result_in(const json& j) {
  SubResult r;
  r.index = j.at("index");
  r.label = j.at("label");
  r.equations = j.at("equations");
  r.variables = j.at("variables");
  r.solutions = boxes_in(j.at("solutions"));
  for (auto& x : j.at("residuals")) r.residuals.push_back(num(x));
  for (int c : j.at("certified").get<std::vector<int>>()) r.certified.push_back(static_cast<char>(c != 0));
  r.stats = stats_in(j.at("stats"));
  r.complete = j.at("complete");
  r.pending = boxes_in(j.at("pending"));
  r.volume_left = num(j.at("volume_left"));
  r.unrefined = j.value("unrefined", 0L);
  r.counters = counters_in(j.at("counters"));
  if (j.contains("narrow_counters")) r.narrow_counters = counters_in(j.at("narrow_counters"));
  r.strategy = strategy_in(j.at("strategy"));
  r.bisect = j.at("bisect");
  for (auto& x : j.at("race")) r.race.push_back({x.at(0).get<std::string>(), num(x.at(1))});
  r.race_choices = j.value("race_choices", std::vector<std::string>{});
  if (r.solutions.size() != r.residuals.size() || r.solutions.size() != r.certified.size())
    throw std::invalid_argument("inconsistent solution lists");
  return r;
}

const char* phase_name(SubCheckpoint::Phase p) {
  switch (p) {
    case SubCheckpoint::Phase::not_started: return "not started";
    case SubCheckpoint::Phase::searching: return "searching";
    case SubCheckpoint::Phase::finished: return "finished";
  }
  return "?";
}

SubCheckpoint sub_in(const json& j) {
  SubCheckpoint s;
  const std::string phase = j.at("phase");
  if (phase == phase_name(SubCheckpoint::Phase::not_started)) return s;
  if (phase == phase_name(SubCheckpoint::Phase::finished)) {
    s.phase = SubCheckpoint::Phase::finished;
    s.result = result_in(j.at("result"));
    return s;
  }
  if (phase != phase_name(SubCheckpoint::Phase::searching)) throw std::invalid_argument("unknown phase '" + phase + "'");
  s.phase = SubCheckpoint::Phase::searching;
  for (auto& x : j.at("searches")) s.searches.push_back(search_in(x));
  for (auto& x : j.at("counters")) s.counters.push_back(counters_in(x));
  const json& r = j.at("race");
  s.race = {num(r.at("turn")), r.at("next").get<size_t>(), r.at("lead").get<size_t>(), num(r.at("target")),
            r.at("winner").get<int>(), r.value("choices", std::vector<std::string>{}), {}};
  if (r.contains("progress"))
    for (auto& one : r.at("progress")) {
      s.race.progress.emplace_back();
      for (auto& point : one) s.race.progress.back().push_back({num(point.at(0)), num(point.at(1))});
    }
  if (s.searches.empty() || s.counters.size() != s.searches.size() || s.race.next >= s.searches.size() ||
      s.race.lead >= s.searches.size() || s.race.winner >= static_cast<int>(s.searches.size()) ||
      (!s.race.progress.empty() && s.race.progress.size() != s.searches.size()))
    throw std::invalid_argument("inconsistent search state");
  return s;
}

}  // namespace

std::string to_json_text(const SubCheckpoint& s) {
  json j = {{"phase", phase_name(s.phase)}};
  if (s.phase == SubCheckpoint::Phase::finished) j["result"] = result_out(s.result);
  if (s.phase == SubCheckpoint::Phase::searching) {
    json searches = json::array(), counters = json::array();
    for (auto& x : s.searches) searches.push_back(search_out(x));
    for (auto& c : s.counters) counters.push_back(counters_out(c));
    j["searches"] = searches;
    j["counters"] = counters;
    j["race"] = {{"turn", num(s.race.turn)}, {"next", s.race.next}, {"lead", s.race.lead},
                 {"target", num(s.race.target)}, {"winner", s.race.winner}, {"choices", s.race.choices}};
    json progress = json::array();
    for (auto& one : s.race.progress) {
      json points = json::array();
      for (auto& [work, tree] : one) points.push_back({num(work), num(tree)});
      progress.push_back(points);
    }
    j["race"]["progress"] = progress;
  }
  return j.dump();
}

SubCheckpoint sub_checkpoint_from_text(const std::string& text) {
  try {
    return sub_in(json::parse(text));
  } catch (const json::exception& e) {
    throw std::invalid_argument(std::string("a damaged sub-problem state: ") + e.what());
  }
}

std::string checkpoint_text(const std::string& header, const std::vector<std::string>& subproblems) {
  // Assembled as text: the pieces are already JSON, and re-parsing them would double the cost.
  std::string t = "{\"linkbox_checkpoint\":" + std::to_string(kFormat) + ",\"header\":" + header + ",\"subproblems\":[";
  for (size_t i = 0; i < subproblems.size(); ++i) t += (i ? ",\n" : "\n") + subproblems[i];
  return t + "]}\n";
}

Checkpoint read_checkpoint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument("cannot read checkpoint " + path + ": " + std::strerror(errno));
  try {
    const json j = json::parse(in);
    if (j.is_object() && j.contains("subproblem_stats") && !j.contains("linkbox_checkpoint"))
      throw std::invalid_argument("a result, not a checkpoint: its pending boxes lack the search's state (their "
                                  "order, the race); run the case with --checkpoint FILE, then resume FILE");
    if (!j.is_object() || !j.contains("linkbox_checkpoint"))
      throw std::invalid_argument("not a linkbox checkpoint");
    if (j.at("linkbox_checkpoint") != kFormat)
      throw std::invalid_argument("checkpoint format " + j.at("linkbox_checkpoint").dump() + ", this linkbox reads " +
                                  std::to_string(kFormat));
    Checkpoint c;
    c.header = j.at("header").dump();
    for (auto& s : j.at("subproblems")) c.subproblems.push_back(sub_in(s));
    return c;
  } catch (const json::exception& e) {
    throw std::invalid_argument("checkpoint " + path + " is damaged: " + e.what());
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("checkpoint " + path + ": " + e.what());
  }
}

Checkpointer::Checkpointer(std::string path, double every, std::string header, size_t subproblems)
    : path_(std::move(path)), every_(every), header_(std::move(header)) {
  if (enabled()) slots_.assign(subproblems, {to_json_text(SubCheckpoint{}), 0, false});
}

void Checkpointer::deposit(size_t i, const SubCheckpoint& state, bool running) {
  if (!enabled()) return;
  std::string text = to_json_text(state);
  std::lock_guard lock(m_);
  slots_[i] = {std::move(text), generation_.load(), running};
  write_when_ready();
}

void Checkpointer::tick(double elapsed) {
  if (!enabled() || elapsed < next_) return;
  next_ = elapsed + every_;
  std::lock_guard lock(m_);
  ++generation_;
  write_when_ready();
}

void Checkpointer::final_write() {
  if (!enabled()) return;
  std::lock_guard lock(m_);
  write(true);
}

void Checkpointer::write_when_ready() {
  if (written_ == generation_.load()) return;
  for (auto& s : slots_)
    if (s.running && s.generation < generation_.load()) return;
  written_ = generation_.load();
  write(false);
}

void Checkpointer::write(bool last) {
  std::vector<std::string> texts;
  for (auto& s : slots_) texts.push_back(s.text);
  try {
    write_output(path_, checkpoint_text(header_, texts));
  } catch (const std::runtime_error& e) {
    if (last) throw;
    std::fprintf(stderr, "linkbox: checkpoint not written (the run goes on): %s\n", e.what());
  }
}

}  // namespace linkbox::solve
