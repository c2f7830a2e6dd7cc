#pragma once
// The "polynomial" case kind: named variables with domains and equations typed as text (the
// format is described in polynomial_file.cpp).
#include "model/polynomial.hpp"

#include <toml++/toml.h>

#include <string>
#include <string_view>

namespace linkbox::input {

class TomlReader;

// Reads the system; every problem is an InputError "file:line: message". `text` is the
// document's source (see read_spherical).
model::System read_polynomial(const toml::table& root, const TomlReader& r);
model::System read_polynomial(const toml::table& root, const std::string& file, std::string_view text = {});

}  // namespace linkbox::input
