#pragma once
// Shared by the readers of the peers' formats; internal to lib/input. A peer's declarations
// and constraints, as trees (peer_syntax.hpp), into the same raw system a TOML polynomial
// case becomes (model/lifting.hpp): functions of variables are kept as applications and
// lifted at the end, so anything the TOML reader accepts, a peer's reader accepts. Powers of
// sums are read as written (input::Powers), as the peers evaluate them. Every failure is an
// InputError at the source line.
#include <string>
#include <vector>

#include "input/expression.hpp"
#include "input/peer_case.hpp"
#include "input/peer_syntax.hpp"
#include "input/source_lines.hpp"

namespace linkbox::input::peer {

// A peer's case while it is read; finish() lifts it into PeerCase::system.
struct Draft {
  PeerCase c;
  model::RawSystem raw;
  SourceLines lines;
  // Inequalities are parsed after every equation, in the order the TOML reader reads a
  // converted case, so both give the same unknowns in the same order.
  struct Comparison {
    NodePtr lhs;
    std::string op;
    NodePtr rhs;
    int line;
    std::string label;
  };
  std::vector<Comparison> inequalities;
};

// `what` names the value in messages ("bound of variable 'x'", "constant 'a'"). With
// `intervals`, interval constants are allowed and listed there.
Interval constant_value(const Node& n, const std::string& what, const std::string& file,
                        IntervalConstants* intervals = nullptr);

// An exact integer constant in [min, max] (vector sizes and indices).
long integer_value(const Node& n, long min, long max, const std::string& what, const std::string& file);

// Declares a variable (name already checked unique); `line` is its declaration.
void add_variable(Draft& d, const std::string& name, const Node& lower, const Node& upper, int line,
                  const std::string& file);

// Adds "lhs = rhs"; `label` names it in messages ("constraint 3").
void add_equation(Draft& d, const NodePtr& lhs, const NodePtr& rhs, int line, const std::string& label,
                  const std::string& file);

// Adds "lhs op rhs" (op: <=, >=, < or >), parsed by finish().
void add_inequality(Draft& d, const NodePtr& lhs, const std::string& op, const NodePtr& rhs, int line,
                    const std::string& label);

// Parses the inequalities and lifts the system (what cannot be lifted fails at its line).
PeerCase finish(Draft&& d, const std::string& file);

// Fails unless `name` can be used as a variable in linkbox's equations.
void check_variable_name(const std::string& name, int line, const std::string& file);

// Fails at `line`: variable `name`'s domain has an infinite end (a null `lower` or `upper`),
// written `infinity` in the peer's format ("oo", "INF").
// An infinite end (null) becomes the default bound, recorded in d.raw.assumed_bounds
// (input/unbounded_domain.hpp).
void complete_unbounded(Draft& d, const std::string& name, NodePtr& lower, NodePtr& upper, int line,
                        const std::string& file);

}  // namespace linkbox::input::peer
