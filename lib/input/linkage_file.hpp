#pragma once
// The "linkage" case kind: loops of links in the Denavit-Hartenberg convention (the format is
// described in linkage_file.cpp), and what a linkage must satisfy before it is modelled.
#include "input/input_error.hpp"
#include "interval/interval.hpp"

#include <toml++/toml.h>

#include <string>
#include <string_view>
#include <vector>

namespace linkbox::input {

class TomlReader;

// Entry i of a loop: joint i (axis d_i), then link i, which runs along the common normal
// a_i from joint i to joint i+1 (the next entry's joint; the last entry wraps around).
struct LoopLink {
  std::string link;
  std::string joint;
  bool prismatic = false;
  Interval a;      // link length along a_i (may be 0: the axes meet)
  Interval alpha;  // twist: angle from d_i to d_{i+1} about a_i, radians
  Interval d;      // revolute: offset along d_i from a_{i-1} to a_i; prismatic: its range
  Interval theta;  // prismatic only: the fixed angle from a_{i-1} to a_i about d_i, radians
  // a, alpha, d and theta as TomlReader::exact_key gives them (compare with same_real).
  struct Keys {
    std::string a, alpha, d, theta;
  } exact;
  int line = 0;
};

// Two exact keys (TomlReader::exact_key) of the same real: equal and known.
inline bool same_real(const std::string& x, const std::string& y) { return !x.empty() && x == y; }
// Two loop entries with the same joint type and the same parameters, as reals.
inline bool same_link(const LoopLink& x, const LoopLink& y) {
  return x.prismatic == y.prismatic && same_real(x.exact.a, y.exact.a) && same_real(x.exact.d, y.exact.d) &&
         same_real(x.exact.alpha, y.exact.alpha) && (!x.prismatic || same_real(x.exact.theta, y.exact.theta));
}

struct LinkageLoop {
  std::string name;
  std::vector<LoopLink> links;
  int line = 0;
};

// d_{joint1} . d_{joint2} = cos(angle): ties axes of different loops (e.g. the third bond of
// a bridgehead atom in bicyclohexane).
struct AngleConstraint {
  std::string name;
  std::string joint1, joint2;
  Interval angle;
  std::string exact_angle;  // TomlReader::exact_key of the angle
  int line = 0;
};

// The angle of a revolute joint (as reported: in its first loop, from the normal before it
// to the normal after it) kept in [lower, upper] modulo 2 pi: an arc of at most a full turn.
struct JointLimit {
  std::string joint;
  Interval lower, upper;  // enclosures of the bounds as written
  int line = 0;
};

struct LinkageCase {
  std::string name;
  std::string file;    // for messages
  std::string ground;  // the link whose frame is the world frame
  int ground_line = 0;
  std::vector<LinkageLoop> loops;
  std::vector<AngleConstraint> angle_constraints;
  std::vector<JointLimit> joint_limits;
};

// Names, topology and parameters (see linkage_validate.cpp); throws InputError.
void validate(const LinkageCase& c);

// Reads and validates a linkage case. `text` is the document's source (see read_spherical).
LinkageCase read_linkage(const toml::table& root, const TomlReader& r);
LinkageCase read_linkage(const toml::table& root, const std::string& file, std::string_view text = {});

}  // namespace linkbox::input
