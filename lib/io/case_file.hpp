#pragma once
// Case files (TOML) -> formulations. Every bad input becomes a CaseError naming the file and
// line; nothing in a case file can crash the loader. The formats are documented at the top of
// case_file.cpp (polynomial), spherical_file.cpp (spherical) and linkage_file.cpp (linkage).
#include "formulate/formulation.hpp"
#include "formulate/spherical.hpp"

#include <toml++/toml.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

namespace linkbox::io {

// what() == "file:line: message"; line 0 means the file as a whole (e.g. it does not exist).
struct CaseError : std::runtime_error {
  std::string file;
  int line;
  std::string message;
  CaseError(std::string file, int line, const std::string& message);
};

struct LoadedCase {
  std::string kind, name, file;
  std::unique_ptr<formulate::Formulation> formulation;
};

LoadedCase load_case(const std::string& path);
// Same from text already in memory; `file` names it in messages.
LoadedCase load_case_text(std::string_view text, const std::string& file);

// The per-kind readers, for callers that parsed the TOML themselves. `text` is the document's
// source: with it, float literals are enclosed as the decimals written; without it (empty),
// each float is widened by one ulp on each side of the double toml++ parsed.
model::System load_polynomial(const toml::table& root, const std::string& file, std::string_view text = {});
formulate::SphericalCase load_spherical(const toml::table& root, const std::string& file,
                                        std::string_view text = {});

}  // namespace linkbox::io
