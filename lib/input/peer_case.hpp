#pragma once
// Models written for the peers (IbexSolve's Minibex .bch, CuikSuite's .cuik), read as a
// polynomial case, functions of variables lifted as in TOML cases (model/lifting.hpp). Next to
// the system the readers keep its text in linkbox's expression grammar, which the converter
// (to_toml.hpp) writes out: TOML cases stay rigorous only if decimals are written as decimals.
#include <string>
#include <string_view>
#include <vector>

#include "model/polynomial.hpp"

namespace linkbox::input {

struct PeerCase {
  std::string format;  // "Minibex" or "CuikSuite"
  model::System system;
  // The case's own variables, in order, with the domain's ends as constant expressions.
  struct Bounds {
    std::string name, lower, upper;
  };
  std::vector<Bounds> bounds;
  // The case's equations as written, each "expression" (= 0), and its inequalities
  // ("lhs <= rhs"; >=, < or >).
  std::vector<std::string> equations;
  std::vector<std::string> inequalities;
  // Said once in the converted file's header (how vector elements were named, ...).
  std::vector<std::string> notes;
};

using PeerReader = PeerCase (*)(std::string_view text, const std::string& file);

// The reader for `file`'s extension (.bch: Minibex, .cuik: CuikSuite, any case), or nullptr.
PeerReader peer_reader_for(std::string_view file);

// The case name of a peer's file: its file name without folders and extension.
std::string peer_case_name(std::string_view file);

}  // namespace linkbox::input
