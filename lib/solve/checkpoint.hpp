#pragma once
// A run's state on disk, so that a stopped, interrupted or crashed run resumes where it was
// and ends with the boxes an unbroken run gives. Per sub-problem: not started, searching (each
// raced candidate's search state and the race's position), or finished (its result).
// Written with solve/output_file.hpp: atomically where the file is a regular one.
#include "prune/counters.hpp"
#include "solve/search_state.hpp"
#include "solve/result.hpp"

#include <optional>
#include <string>
#include <vector>

namespace linkbox::solve {

// Where a race between candidate strategies stands (see solve_case.cpp).
struct RacePosition {
  double turn = 0;
  size_t next = 0;     // the candidate whose run is under way or next
  size_t lead = 0;     // the candidate with the best projection this round
  double target = -1;  // the work the running candidate runs up to; < 0: not yet set
  int winner = -1;     // >= 0: the race is over; the winner's result is being refined
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

}  // namespace linkbox::solve
