#pragma once
// The converter behind `linkbox convert`: a model in a peer's format (.bch, .cuik) as a TOML
// polynomial case that read_case reads back to the same system (same variables, domains and
// equations, coefficient for coefficient). Constants are written out where they are used,
// decimals as written and interval constants as "[a, b]", so the TOML case is exactly as
// rigorous as the source; a rounded double could not be.
#include <string>
#include <string_view>

#include "input/peer_case.hpp"

namespace linkbox::input {

// Reads `path` (a .bch or .cuik file) and returns the TOML text. Throws InputError
// "file:line: message" for anything wrong with the file, and (line 0) for a file that is not
// in a peer's format.
std::string convert_to_toml(const std::string& path);

// Same from text in memory; `file` names it in messages and its extension picks the format.
std::string convert_text_to_toml(std::string_view text, const std::string& file);

// The TOML text of a case already read from `file` (named in the header), called `name`.
std::string to_toml(const PeerCase& c, const std::string& name, const std::string& file);

}  // namespace linkbox::input
