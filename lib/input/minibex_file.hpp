#pragma once
// IbexSolve's Minibex (.bch): the subset polynomial benchmark files use, read as a polynomial
// system (the subset is described in minibex_file.cpp). Anything outside it is an InputError
// "file:line: message" naming the construct, never a reading with another meaning.
#include <string>
#include <string_view>

#include "input/peer_case.hpp"

namespace linkbox::input {

PeerCase read_minibex(std::string_view text, const std::string& file);

}  // namespace linkbox::input
