#include "targets.hpp"

#include "formulate/load.hpp"
#include "input/case_file.hpp"
#include "input/cuik_file.hpp"
#include "input/expression.hpp"
#include "input/minibex_file.hpp"
#include "input/to_toml.hpp"
#include "verify/check.hpp"

#include <nlohmann/json.hpp>

#include <fstream>
#include <iterator>
#include <stdexcept>

#ifndef LINKBOX_SOURCE_DIR
#error "LINKBOX_SOURCE_DIR must name the source tree (the check target reads bundled cases)"
#endif

namespace linkbox::fuzz {

namespace {

// A TOML case as `linkbox solve` reads it: the reader, then the formulation. Both promise an
// InputError (a std::invalid_argument) for anything wrong with the file. formulate::load_case
// would turn any other exception into an InputError too ("internal error while loading"), so
// the target calls the two steps itself: such an exception is a defect and must escape.
void case_toml(std::string_view text) {
  try {
    const input::Case c = input::read_case_text(text, "fuzz.toml");
    const auto formulation = formulate::formulate(c);
    (void)formulation->subproblem_count();
  } catch (const std::invalid_argument&) {
  }
}

// The expression grammar (input/expression.hpp), in every entry point: a polynomial in x, y
// and z, a constant, an equation and an inequality (functions of variables lifted).
void expression(std::string_view text) {
  const std::vector<std::string> variables = {"x", "y", "z"};
  try {
    const model::Polynomial p = input::parse_polynomial(text, variables);
    (void)p.eval(Box(3, Interval(-1, 1)));
  } catch (const input::ParseError&) {
  }
  try {
    (void)input::parse_constant(text);
  } catch (const input::ParseError&) {
  }
  try {
    std::vector<model::Application> applications;
    (void)input::parse_equation(text, variables, applications);
  } catch (const input::ParseError&) {
  }
  try {
    std::vector<model::Application> applications;
    (void)input::parse_inequality(text, variables, applications);
  } catch (const input::ParseError&) {
  }
}

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("fuzz: cannot read " + path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// `linkbox check` on a result JSON, against a fixed small case picked by the JSON's "case"
// name (so that seeds are plain result files): wrist (spherical, charts), gimbal-lock
// (curve crossings) or circle-line (polynomial). The formulation is built afresh per input:
// natural systems are cached per chart, and a shared one would grow with every chart tried.
void check_json(std::string_view text) {
  static const std::string dir = std::string(LINKBOX_SOURCE_DIR) + "/cases/";
  static const std::string wrist = read_file(dir + "spherical/wrist.toml");
  static const std::string gimbal = read_file(dir + "hard/gimbal-lock.toml");
  static const std::string circle = read_file(dir + "polynomial/circle-line.toml");
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception&) {
    return;  // the CLI: "not a linkbox result", exit 2
  }
  if (!j.contains("clusters")) return;  // the CLI: "no certificates", exit 2
  const nlohmann::json* name = j.contains("case") ? &j["case"] : nullptr;
  const std::string& toml = name && *name == "wrist"         ? wrist
                            : name && *name == "gimbal-lock" ? gimbal
                                                             : circle;
  const formulate::LoadedCase c = formulate::load_case_text(toml, "fixed.toml");
  try {
    const verify::CheckOutcome out = verify::check_certificates(j, *c.formulation);
    (void)out;
  } catch (const nlohmann::json::exception&) {  // the CLI: "malformed certificate data", exit 2
  } catch (const std::invalid_argument&) {
  }
}

// A peer's model file (.bch or .cuik) as `linkbox solve` and `linkbox convert` read it: the
// reader, then the converter's TOML, which must read back (to_toml.hpp promises it).
void peer(std::string_view text, input::PeerCase (*read)(std::string_view, const std::string&),
          const std::string& file) {
  input::PeerCase c;
  try {
    c = read(text, file);
  } catch (const std::invalid_argument&) {
    return;
  }
  const std::string toml = input::to_toml(c, "fuzz", file);
  const input::Case back = input::read_case_text(toml, "converted.toml");  // must not throw
  const auto* system = std::get_if<model::System>(&back.description);
  if (!system || system->variables.size() != c.system.variables.size() ||
      system->equations.size() != c.system.equations.size() ||
      system->inequalities.size() != c.system.inequalities.size() ||
      system->interval_constants != c.system.interval_constants)
    throw std::logic_error("fuzz: the converted TOML reads back as another system");
}

void minibex(std::string_view text) { peer(text, input::read_minibex, "fuzz.bch"); }
void cuik(std::string_view text) { peer(text, input::read_cuik, "fuzz.cuik"); }

}  // namespace

const std::vector<Target>& targets() {
  static const std::vector<Target> all = {
      {"case_toml", case_toml}, {"expression", expression}, {"check_json", check_json},
      {"minibex", minibex},     {"cuik", cuik},
  };
  return all;
}

const Target* find_target(std::string_view name) {
  for (auto& t : targets())
    if (name == t.name) return &t;
  return nullptr;
}

}  // namespace linkbox::fuzz
