#pragma once
// CuikSuite's .cuik equation files: the polynomial subset, read as a polynomial system (the
// subset is described in cuik_file.cpp). Anything outside it is an InputError
// "file:line: message" naming the construct, never a reading with another meaning.
#include <string>
#include <string_view>

#include "input/peer_case.hpp"

namespace linkbox::input {

PeerCase read_cuik(std::string_view text, const std::string& file);

}  // namespace linkbox::input
