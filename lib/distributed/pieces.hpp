#pragma once
// Pieces of a search (solve/share.hpp) and sub-problem results as messages: they travel as the
// checkpoint writes sub-problem states (exact doubles, infinities, paths and backoffs), one
// format to keep right.
#include "distributed/wire.hpp"
#include "solve/share.hpp"

#include <string>

namespace linkbox::distributed {

std::string piece_text(const solve::Piece& p);
std::string result_text(const solve::SubResult& s);
// The piece a message carries: its payload, and its sub-problem, strategy and race in the head.
solve::Piece piece_from(const Message& m);
// A head of type `type` naming `p`'s sub-problem, strategy and race.
nlohmann::json piece_head(const char* type, const solve::Piece& p);

}  // namespace linkbox::distributed
