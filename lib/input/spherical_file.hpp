#pragma once
// The "spherical" case kind: loops of rotations about axes through one point (the spherical
// paper, Sections 2-3), each loop's product of factors being the identity. The format is
// described in spherical_file.cpp.
#include "input/input_error.hpp"
#include "interval/interval.hpp"
#include "model/vector_algebra.hpp"

#include <toml++/toml.h>

#include <string>
#include <string_view>
#include <vector>

namespace linkbox::input {

class TomlReader;

using Vec3 = model::Vec3<Interval>;
using Quaternion = model::Quaternion<Interval>;

struct Factor {
  enum class Kind { joint, fixed_rotation, constant };
  Kind kind = Kind::joint;
  Vec3 axis{};          // joint, fixed_rotation: need not be unit (normalised rigorously)
  int joint = -1;       // joint: index into SphericalCase::joints
  Interval angle;       // fixed_rotation: radians
  Quaternion q{};       // constant: any non-zero quaternion (only its direction matters)
  int line = 0;         // source line, for messages
};

struct Loop {
  std::string name;
  std::vector<Factor> factors;  // product factors[0] * factors[1] * ... = 1
  int line = 0;
};

struct Joint {
  std::string name;
  int line = 0;
};

// A declared output: the rotation given by a product of factors (e.g. a platform).
struct RotationOutput {
  std::string name;
  std::vector<Factor> factors;
  int line = 0;
};

struct SphericalCase {
  std::string name;
  std::string file;
  std::vector<Joint> joints;
  std::vector<Loop> loops;
  std::vector<RotationOutput> outputs;
};

// Every joint used, no joint twice in one loop (the equations would not be multi-affine),
// non-zero axes and quaternions, at most 20 joints (2^r sub-problems), output names not
// reserved. Throws InputError.
void validate(const SphericalCase& c);

// Reads and validates. `text` is the document's source: with it, float literals are enclosed
// as the decimals written; without it (empty), each float is widened by one ulp on each side
// of the double toml++ parsed.
SphericalCase read_spherical(const toml::table& root, const TomlReader& r);
SphericalCase read_spherical(const toml::table& root, const std::string& file, std::string_view text = {});

}  // namespace linkbox::input
