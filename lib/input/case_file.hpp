#pragma once
// Case files (TOML) -> what the user described, validated. Every bad input becomes an
// InputError naming the file and line; nothing in a case file can crash the reader. The
// kinds and their formats: polynomial_file, spherical_file and linkage_file.
#include "input/input_error.hpp"
#include "input/linkage_file.hpp"
#include "input/polynomial_file.hpp"
#include "input/spherical_file.hpp"

#include <optional>
#include <string>
#include <string_view>
#include <variant>

namespace linkbox::input {

// The settings a case recommends (its optional `[solve]` table): a curve wants a coarse
// sigma, a hard system a strategy. Command-line flags override them. Names (prune, bisect) are
// checked where they are understood; `line` lets that check name the place.
struct SolveSettings {
  std::optional<double> sigma, rho, time_limit;
  std::optional<std::string> prune, bisect;
  int line = 0;
};

struct Case {
  std::string kind, name, file;
  std::variant<model::System, SphericalCase, LinkageCase> description;
  SolveSettings solve;
};

// By extension: .bch (Minibex) and .cuik (CuikSuite) files are read as polynomial cases
// (input/peer_case.hpp); anything else as a TOML case.
Case read_case(const std::string& path);
// Same from text already in memory; `file` names it in messages.
Case read_case_text(std::string_view text, const std::string& file);

}  // namespace linkbox::input
