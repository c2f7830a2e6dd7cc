#include "prune/counters.hpp"

namespace linkbox::prune {

Counters& Counters::operator+=(const Counters& o) {
  calls += o.calls;
  emptied += o.emptied;
  seconds += o.seconds;
  volume_removed += o.volume_removed;
  lps_solved += o.lps_solved;
  lp_iterations += o.lp_iterations;
  operations += o.operations;
  lp_paths += o.lp_paths;
  return *this;
}

LpPaths& LpPaths::operator+=(const LpPaths& o) {
  basis += o.basis, repaired += o.repaired, farkas += o.farkas, fallback += o.fallback, pivots += o.pivots;
  return *this;
}

LpPaths& LpPaths::operator-=(const LpPaths& o) {
  basis -= o.basis, repaired -= o.repaired, farkas -= o.farkas, fallback -= o.fallback, pivots -= o.pivots;
  return *this;
}

}  // namespace linkbox::prune
