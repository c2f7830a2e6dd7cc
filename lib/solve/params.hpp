#pragma once
// The settings of one search: when a box is a solution, when shrinking stops, the order boxes
// are taken in, and the run's limits.
#include <atomic>

namespace linkbox::solve {

enum class Order { depth_first, breadth_first };

struct Params {
  double sigma = 1e-4;  // a box whose longest split side is <= sigma is a solution box
  double rho = 0;  // split when volume(after)/volume(before) > rho; in RunOptions 0: not given (settings_for)
  Order order = Order::depth_first;
  double time_limit = 0;  // seconds; 0 = none
  double cpu_limit = 0;   // seconds of the process's CPU time (every thread); 0 = none
  long max_boxes = 0;     // processed boxes over the whole run; 0 = none
  // > 0: after a complete search, uncertified solution boxes are narrowed to this width
  // (solve/narrow.hpp), for a curve map that needs narrow pieces.
  double narrow = 0;
  // When set and non-zero (a signal arrived), the run stops as if a limit were reached, with
  // stop reason "interrupted".
  const std::atomic<int>* interrupt = nullptr;
};

// rho when the user gave none: the papers' value on the spherical formulation (their method
// and tables), a smaller one elsewhere: a pass of propagation and Newton that removes little of
// the box costs more than the bisection it delays (see papers/decisions/search.md).
constexpr double kPapersRho = 0.99;
constexpr double kAutoRho = 0.8;
inline double rho_for(double rho, bool spherical) { return rho > 0 ? rho : spherical ? kPapersRho : kAutoRho; }

}  // namespace linkbox::solve
