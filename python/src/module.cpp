// The extension module `_linkbox`: the pipeline of `linkbox solve` (load -> solve -> verify ->
// the result JSON) for the pure-Python package python/linkbox, which builds its objects from
// that JSON. Bad input raises linkbox.CaseError with the CLI's "file:line: message".
#include "formulate/load.hpp"
#include "input/case_hash.hpp"
#include "input/input_error.hpp"
#include "report/json.hpp"
#include "solve/solve_case.hpp"
#include "verify/certify_case.hpp"
#include "verify/check.hpp"

#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>

#include <atomic>
#include <chrono>
#include <exception>
#include <future>
#include <initializer_list>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>

namespace py = pybind11;
using namespace linkbox;

namespace {

// The stop flags of the runs in progress: linkbox.interrupt() raises each by one, as a signal
// does to the CLI's (1: the search stops at the next box; 2: verification is skipped too).
std::mutex runs_mutex;
std::set<std::atomic<int>*> running;

struct Registered {
  std::atomic<int> flag{0};
  Registered() {
    std::lock_guard lock(runs_mutex);
    running.insert(&flag);
  }
  ~Registered() {
    std::lock_guard lock(runs_mutex);
    running.erase(&flag);
  }
};

void interrupt() {
  std::lock_guard lock(runs_mutex);
  for (auto* f : running) f->fetch_add(1);
}

// The options of Case.solve; an unset one is taken from the case's [solve] table, else the
// library's default, as the CLI does for a flag not given.
struct SolveArgs {
  std::optional<std::string> prune, bisect, order, lp, arith;
  std::optional<double> sigma, rho, time_limit;
  long max_boxes = 0;
  int threads = 1;
  bool progress = false, verify = true;
};

// The value named `text` among `choices`, as the CLI's flag of that name takes it.
template <class T>
T choose(const std::string& text, const char* option, std::initializer_list<std::pair<const char*, T>> choices) {
  std::string names;
  for (auto& [name, value] : choices) {
    if (text == name) return value;
    names += names.empty() ? name : std::string(" or ") + name;
  }
  throw std::invalid_argument(std::string(option) + ": expected " + names + ", got '" + text + "'");
}

void settle(solve::RunOptions& o, const SolveArgs& a, const input::SolveSettings& s, const std::string& file) {
  auto pick = [&](const char* name, const auto& given, const auto& from_case, auto apply) {
    try {
      if (given) {
        apply(*given);
        o.setting_source[name] = "flag";
      } else if (from_case) {
        apply(*from_case);
        o.setting_source[name] = "case file";
      }
    } catch (const std::invalid_argument& e) {
      if (given) throw std::invalid_argument(std::string(name) + ": " + e.what());
      throw input::InputError(file, s.line, std::string("[solve] ") + name + ": " + e.what());
    }
  };
  pick("sigma", a.sigma, s.sigma, [&](double x) { o.params.sigma = x; });
  pick("rho", a.rho, s.rho, [&](double x) { o.params.rho = x; });
  pick("time_limit", a.time_limit, s.time_limit, [&](double x) { o.params.time_limit = x; });
  pick("prune", a.prune, s.prune, [&](const std::string& x) { o.strategy.prune = solve::Strategy::parse(x); });
  pick("bisect", a.bisect, s.bisect, [&](const std::string& x) { o.bisect = solve::parse_bisect(x); });
  using solve::Order;
  using prune::lp::LpBackend;
  if (a.order) o.params.order = choose<Order>(*a.order, "order", {{"dfs", Order::depth_first}, {"bfs", Order::breadth_first}});
  if (a.lp) o.strategy.lp = choose<LpBackend>(*a.lp, "lp", {{"safe", LpBackend::safe}, {"exact", LpBackend::exact}});
  if (a.arith)
    o.strategy.arith = choose<Arith>(*a.arith, "arith", {{"verified", Arith::verified}, {"float", Arith::float_unverified}});
  o.params.max_boxes = a.max_boxes;
  o.threads = a.threads;
  o.progress = a.progress;
}

class Case {
 public:
  explicit Case(formulate::LoadedCase c) : c_(std::move(c)) {}
  const std::string& name() const { return c_.name; }
  const std::string& kind() const { return c_.kind; }
  const std::string& file() const { return c_.file; }
  std::vector<std::string> variables() const { return c_.formulation->output_names(); }

  // The result JSON's text, and whether a KeyboardInterrupt stopped the run. `poll` is called
  // with the GIL about ten times a second while the run goes on, on the calling thread; an
  // exception from it, or a signal's, interrupts the run, which then ends as the CLI's does on
  // a signal. A KeyboardInterrupt is then told by the flag, anything else raised again.
  std::pair<std::string, bool> solve(const SolveArgs& a, const std::function<void()>& poll) const {
    solve::RunOptions o;
    settle(o, a, c_.solve, c_.file);
    auto run = std::make_shared<Registered>();
    o.params.interrupt = &run->flag;
    auto work = std::async(std::launch::async, [this, o, a, run] { return pipeline(o, a.verify, run->flag); });
    std::optional<py::error_already_set> raised;
    {
      py::gil_scoped_release released;
      while (work.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready) {
        py::gil_scoped_acquire held;
        try {
          if (PyErr_CheckSignals() != 0) throw py::error_already_set();
          poll();
        } catch (py::error_already_set& e) {
          if (!raised) raised = std::move(e);
          run->flag.fetch_add(1);
        }
      }
    }
    std::string out = work.get();
    if (raised && !raised->matches(PyExc_KeyboardInterrupt)) throw std::move(*raised);
    return {std::move(out), raised.has_value()};
  }

  // `linkbox check`: the failures of the result's certificates (empty: all hold), and how
  // many were checked.
  std::pair<int, std::vector<std::string>> check(const std::string& result_json) const {
    const auto j = nlohmann::json::parse(result_json);
    py::gil_scoped_release released;
    const auto out = verify::check_certificates(j, *c_.formulation, input::case_sha256(c_.file));
    return {out.checked, out.failures};
  }

 private:
  std::string pipeline(const solve::RunOptions& o, bool verifying, const std::atomic<int>& flag) const {
    const solve::CaseResult r = solve::solve_case(*c_.formulation, o);
    nlohmann::json j = report::result_json(c_.name, c_.file, *c_.formulation, o, r);
    if (verifying && flag.load() < 2) {  // a second interrupt before verification skips it, as in the CLI
      verify::VerifyOptions vo;
      vo.skip_rest = [&flag] { return flag.load() >= 2; };
      vo.threads = o.threads;
      vo.progress = o.progress;
      report::add_verification(j, *c_.formulation, verify::verify_case(*c_.formulation, r, vo));
    }
    return j.dump(1);
  }

  formulate::LoadedCase c_;
};

}  // namespace

PYBIND11_MODULE(_linkbox, m) {
  m.doc() = "linkbox's library: load, solve and verify a case (see the package linkbox)";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const input::InputError& e) {
      py::object error = py::module_::import("linkbox._errors").attr("CaseError")(e.what(), e.file, e.line, e.message);
      PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(error.ptr())), error.ptr());
    }
  });
  py::class_<SolveArgs>(m, "SolveArgs")
      .def(py::init<>())
      .def_readwrite("prune", &SolveArgs::prune)
      .def_readwrite("bisect", &SolveArgs::bisect)
      .def_readwrite("sigma", &SolveArgs::sigma)
      .def_readwrite("rho", &SolveArgs::rho)
      .def_readwrite("time_limit", &SolveArgs::time_limit)
      .def_readwrite("order", &SolveArgs::order)
      .def_readwrite("lp", &SolveArgs::lp)
      .def_readwrite("arith", &SolveArgs::arith)
      .def_readwrite("max_boxes", &SolveArgs::max_boxes)
      .def_readwrite("threads", &SolveArgs::threads)
      .def_readwrite("progress", &SolveArgs::progress)
      .def_readwrite("verify", &SolveArgs::verify);
  py::class_<Case>(m, "Case")
      .def_property_readonly("name", &Case::name)
      .def_property_readonly("kind", &Case::kind)
      .def_property_readonly("file", &Case::file)
      .def_property_readonly("variables", &Case::variables)
      .def("solve", &Case::solve, py::arg("args"), py::arg("poll"))
      .def("check", &Case::check, py::arg("result_json"));
  m.def("load", [](const std::string& path) { return Case(formulate::load_case(path)); }, py::arg("path"));
  m.def("load_text", [](const std::string& text, const std::string& file) {
    return Case(formulate::load_case_text(text, file));
  }, py::arg("text"), py::arg("file"));
  m.def("contractor_names", &solve::contractor_names, "The contractors a prune strategy may name.");
  m.def("interrupt", &interrupt, "Interrupts every run in progress, as a signal does the CLI's.");
}
