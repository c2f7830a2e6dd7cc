#include "cli/ending.hpp"

#include "cli/interrupts.hpp"

#include <cstdio>
#include <string>

namespace linkbox::cli {

namespace {

std::string number(double x) {
  char t[32];
  std::snprintf(t, sizeof t, "%g", x);
  return t;
}

// A run stopped by a limit or an interrupt: where to go on from.
std::string go_on(const SolveCommand& cmd, const formulate::LoadedCase& c, const solve::CaseResult& r) {
  if (!cmd.checkpoint.empty()) return "to go on from where it stopped: linkbox resume " + cmd.checkpoint;
  if (!cmd.kept_checkpoint.empty()) return "to go on from where it stopped: linkbox resume " + cmd.json_out;
  std::string again = "to go on next time from where a run stops, add --checkpoint FILE (then: linkbox resume FILE)";
  const double t = cmd.options.params.time_limit;
  const long n = cmd.options.params.max_boxes;
  if (r.stop_reason == "time limit reached" && t > 0)
    return again + "; or search longer: linkbox solve " + c.file + " --time-limit " + number(4 * t);
  const double cpu = cmd.options.params.cpu_limit;
  if (r.stop_reason == "CPU time limit reached" && cpu > 0)
    return again + "; or search longer: linkbox solve " + c.file + " --cpu-limit " + number(4 * cpu);
  if (r.stop_reason == "box limit reached" && n > 0)
    return again + "; or search further: linkbox solve " + c.file + " --max-boxes " + std::to_string(10 * n);
  return again;
}

// The run again with four times its time limits.
std::string longer(const SolveCommand& cmd, const formulate::LoadedCase& c) {
  const double t = cmd.options.params.time_limit, cpu = cmd.options.params.cpu_limit;
  return "linkbox solve " + c.file + (t > 0 ? " --time-limit " + number(4 * t) : "") +
         (cpu > 0 ? " --cpu-limit " + number(4 * cpu) : "") + " (with your other flags)";
}

bool any_reason(const verify::VerifyReport& v, const char* words) {
  for (auto& cl : v.clusters)
    if (cl.status == verify::ClusterStatus::unverified && cl.reason.find(words) != std::string::npos) return true;
  return false;
}

bool inexact_in_maps(const verify::VerifyReport& v) {
  for (auto& cl : v.clusters)
    if (cl.map && !cl.map->proved && cl.map->inexact_coefficients) return true;
  return false;
}

// A complete run whose count is not exact: the hint that fits the clusters' reasons
// (docs/verification.md says what each means).
std::string settle(const SolveCommand& cmd, const formulate::LoadedCase& c, const solve::CaseResult& r,
                   const verify::VerifyReport& v) {
  const std::string smaller =
      "linkbox solve " + c.file + " --sigma " + number(cmd.options.params.sigma / 100) + " (with your other flags)";
  if (!r.rigorous) return "--arith float never proves a count: run it again without --arith float";
  if (any_reason(v, "inflation failed"))
    return "inflation failed: a smaller --sigma may separate close roots (not those closer than floating point "
           "resolves): " + smaller;
  if (any_reason(v, "no exact value") || inexact_in_maps(v))
    return "exact arithmetic, which proves singular points and the exact roots of overdetermined systems, needs "
           "coefficients with exact rational values: write the case's constants as integers or decimals, not as "
           "pi, functions of constants (sqrt(2), sin(1)) or interval constants; see docs/verification.md";
  if (any_reason(v, "singular"))
    return "a singular root (a multiple root, a singular point) is not certified by refining; see docs/verification.md";
  if (any_reason(v, "not square") || any_reason(v, "overdetermined"))
    return "the natural system is not square, so its roots cannot be certified; see docs/verification.md";
  if (v.curves && !v.maps_proved)
    return "a smaller --sigma gives the curve map finer arcs to prove: " + smaller;
  return "see docs/verification.md for what each reason means; a smaller --sigma may settle it: " + smaller;
}

}  // namespace

int end_of_run(const SolveCommand& cmd, const formulate::LoadedCase& c, const solve::CaseResult& r,
               const verify::VerifyReport* v, bool speaks) {
  int code = exit_exact;
  std::string next;
  if (const int signalled = interrupt_exit_code()) {
    code = signalled;
    next = go_on(cmd, c, r);
  } else if (!r.complete) {
    code = exit_incomplete;
    next = go_on(cmd, c, r);
  } else if (r.unrefined && !(v && v->exact)) {
    code = exit_incomplete;
    next = "a limit stopped the refinement of the solution boxes; " + go_on(cmd, c, r);
  } else if (v && v->timed_out) {
    code = exit_incomplete;
    next = "verification reached its time limit (as long as the search's) with clusters left: " + longer(cmd, c);
  } else if (v && !v->exact) {
    code = exit_unresolved;
    next = settle(cmd, c, r, *v);
  }
  if (speaks && !next.empty()) std::fprintf(stderr, "linkbox: next: %s\n", next.c_str());
  return code;
}

}  // namespace linkbox::cli
