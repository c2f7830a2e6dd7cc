#pragma once
// What a contractor did during a run: plain data, read by solve's results and the reports.
namespace linkbox::prune {

struct Counters {
  long calls = 0;
  long emptied = 0;
  double seconds = 0;
  double volume_removed = 0;  // sum over calls of (1 - volume ratio) on the split dimensions
  long lps_solved = 0;        // LP-based contractors: LPs solved (a min or a max each)
  long lp_iterations = 0;     // and the simplex iterations they took

  Counters& operator+=(const Counters& o);
};

}  // namespace linkbox::prune
