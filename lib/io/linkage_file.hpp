#pragma once
// The "linkage" case format (loops of Denavit-Hartenberg links; described in
// linkage_file.cpp) -> formulate::LinkageCase.
#include "formulate/formulation.hpp"
#include "formulate/linkage.hpp"

#include <toml++/toml.h>

#include <memory>
#include <string>
#include <string_view>

namespace linkbox::io {

class TomlReader;

// Reads and validates (formulate::validate) a linkage case; every problem is a CaseError
// "file:line: message". `text` is the document's source (see load_polynomial).
formulate::LinkageCase load_linkage(const toml::table& root, const std::string& file, std::string_view text = {});
formulate::LinkageCase load_linkage(const toml::table& root, const TomlReader& r);

// Reader + LinkageFormulation, for load_case's kind table: a linkage that the model finds
// cannot be assembled is a CaseError too.
std::unique_ptr<formulate::Formulation> linkage_formulation(const toml::table& root, const TomlReader& r);

}  // namespace linkbox::io
