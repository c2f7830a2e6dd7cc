#include "distributed/pieces.hpp"

#include "solve/checkpoint.hpp"

#include <utility>
#include <vector>

namespace linkbox::distributed {

using solve::Piece;
using solve::SubCheckpoint;

std::string piece_text(const Piece& p) {
  SubCheckpoint c;
  c.phase = SubCheckpoint::Phase::searching;
  c.searches = {p.state};
  c.counters = {p.counters};
  return solve::to_json_text(c);
}

std::string result_text(const solve::SubResult& s) {
  SubCheckpoint c;
  c.phase = SubCheckpoint::Phase::finished;
  c.result = s;
  return solve::to_json_text(c);
}

Piece piece_from(const Message& m) {
  SubCheckpoint c = solve::sub_checkpoint_from_text(m.payload);
  Piece p;
  p.subproblem = m.head.at("sub");
  p.strategy = solve::Strategy::parse(m.head.at("strategy").get<std::string>());
  p.race = m.head.value("race", std::vector<std::pair<std::string, double>>{});
  p.race_choices = m.head.value("race_choices", std::vector<std::string>{});
  p.state = std::move(c.searches.at(0));
  p.counters = std::move(c.counters.at(0));
  return p;
}

nlohmann::json piece_head(const char* type, const Piece& p) {
  return {{"t", type}, {"sub", p.subproblem}, {"strategy", p.strategy.text()}, {"race", p.race},
          {"race_choices", p.race_choices}};
}

}  // namespace linkbox::distributed
