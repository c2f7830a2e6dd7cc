// The spherical format: loops of rotations about axes through one point, each loop's product
// of factors being the identity.
//
//   kind = "spherical"
//   name = "wrist"
//   description = "..."                                   # optional
//   joints = ["phi1", "phi2", "phi3"]
//   [[loops]]
//   name = "wrist"                                        # optional, default "loop N"
//   factors = [
//     { joint = "phi1", axis = [0, 0, 1] },               # joint: rotation by the joint angle
//     { axis = [1, 0, 0], angle = "pi/2" },               # fixed rotation, angle in radians
//     { quaternion = ["0.0196", 0.098, 0.65, -0.74] },    # constant quaternion (w, x, y, z)
//   ]
//   [[outputs]]                                           # optional
//   name = "R"
//   rotation = [ { joint = "phi1", axis = [0, 0, 1] } ]   # rotation matrix of the product
//
// Any factor may add `inverse = true`: a joint or fixed rotation then turns the other way
// (axis negated / angle negated), a quaternion is conjugated. Axes need not be unit.
#include "input/spherical_file.hpp"

#include "input/toml_reader.hpp"

#include <algorithm>
#include <map>
#include <string>
#include <vector>

namespace linkbox::input {

namespace {

bool is_exact_zero(const Interval& x) { return x.lower() == 0 && x.upper() == 0; }

class SphericalReader {
 public:
  explicit SphericalReader(const TomlReader& r) : r_(r) {}

  SphericalCase read(const toml::table& root) {
    r_.only_keys(root, {"kind", "name", "description", "joints", "loops", "outputs"}, "a spherical case");
    SphericalCase c;
    c.file = r_.file();
    c.name = r_.string(r_.required(root, "name", "case name"), "name");
    read_joints(r_.required(root, "joints", "joints"), c);

    for (auto& t : r_.loops(root, "factors"))
      c.loops.push_back({t.name, read_factors(*t.items, "factors of loop '" + t.name + "'"), t.line});

    if (const toml::node* outputs = root.get("outputs")) {
      std::map<std::string, int> output_lines;
      for (auto& n : r_.array(*outputs, "outputs")) {
        const toml::table& t = r_.table(n, "an output");
        r_.only_keys(t, {"name", "rotation"}, "an output");
        RotationOutput out;
        out.line = TomlReader::line_of(t);
        out.name = r_.string(r_.required(t, "name", "output name"), "output name");
        unique(output_lines, out.name, out.line, "output");
        const std::string what = "rotation of output '" + out.name + "'";
        out.factors = read_factors(r_.required(t, "rotation", what), what);
        c.outputs.push_back(std::move(out));
      }
    }
    return c;
  }

 private:
  void read_joints(const toml::node& n, SphericalCase& c) {
    const toml::array& joints = r_.array(n, "joints");
    if (joints.empty()) r_.fail(joints, "no joints");
    for (auto& j : joints) {
      Joint joint{r_.string(j, "joint name"), TomlReader::line_of(j)};
      if (joint.name.empty()) r_.fail(j, "empty joint name");
      auto [it, fresh] = joint_index_.emplace(joint.name, static_cast<int>(c.joints.size()));
      if (!fresh)
        r_.fail(j, "duplicate joint '" + joint.name + "' (first declared on line " +
                       std::to_string(c.joints[it->second].line) + ")");
      c.joints.push_back(std::move(joint));
    }
  }

  // Fails when `name` was already declared (`lines` maps names to their declaration lines).
  void unique(std::map<std::string, int>& lines, const std::string& name, int line, const char* what) {
    auto [it, fresh] = lines.emplace(name, line);
    if (!fresh)
      r_.fail(line, std::string("duplicate ") + what + " name '" + name + "' (first declared on line " +
                        std::to_string(it->second) + ")");
  }

  std::vector<Factor> read_factors(const toml::node& n, const std::string& what) {
    const toml::array& a = r_.array(n, what);
    if (a.empty()) r_.fail(a, what + ": no factors");
    std::vector<Factor> factors;
    for (auto& f : a) factors.push_back(read_factor(f));
    return factors;
  }

  Factor read_factor(const toml::node& n) {
    const toml::table& t = r_.table(n, "a factor");
    r_.only_keys(t, {"joint", "axis", "angle", "quaternion", "inverse"}, "a factor");
    Factor f;
    f.line = TomlReader::line_of(t);
    const bool joint = t.contains("joint"), angle = t.contains("angle"), quaternion = t.contains("quaternion");
    if (joint + angle + quaternion == 0) {
      const std::string forms =
          "a factor is a joint { joint, axis }, a fixed rotation { axis, angle } or a constant { quaternion }";
      r_.fail(t, t.contains("axis") ? "factor has an axis but neither 'joint' nor 'angle'; " + forms : forms);
    }
    if (joint + angle + quaternion > 1) {
      std::vector<std::string> present;
      if (joint) present.push_back("'joint'");
      if (angle) present.push_back("'angle'");
      if (quaternion) present.push_back("'quaternion'");
      std::string list = present[0];
      for (size_t i = 1; i < present.size(); ++i)
        list += (i + 1 == present.size() ? " and " : ", ") + present[i];
      r_.fail(t, "factor mixes " + list + "; use exactly one of 'joint', 'angle' and 'quaternion'");
    }
    const bool inverse = t.contains("inverse") && r_.boolean(*t.get("inverse"), "inverse");

    if (quaternion) {
      if (t.contains("axis")) r_.fail(t, "a quaternion factor takes no 'axis'");
      f.kind = Factor::Kind::constant;
      const std::vector<Interval> q = r_.numbers(*t.get("quaternion"), 4, "quaternion (w, x, y, z)");
      if (std::all_of(q.begin(), q.end(), is_exact_zero)) r_.fail(t, "quaternion is zero");
      f.q = {q[0], inverse ? -q[1] : q[1], inverse ? -q[2] : q[2], inverse ? -q[3] : q[3]};
      return f;
    }
    f.axis = read_axis(t);
    if (joint) {
      f.kind = Factor::Kind::joint;
      const toml::node& name_node = *t.get("joint");
      const std::string name = r_.string(name_node, "joint");
      auto it = joint_index_.find(name);
      if (it == joint_index_.end()) r_.fail(name_node, "unknown joint '" + name + "' (not in 'joints')");
      f.joint = it->second;
      if (inverse)
        for (auto& c : f.axis) c = -c;
    } else {
      f.kind = Factor::Kind::fixed_rotation;
      f.angle = r_.number(*t.get("angle"), "angle");
      if (inverse) f.angle = -f.angle;
    }
    return f;
  }

  Vec3 read_axis(const toml::table& t) {
    const std::vector<Interval> v = r_.numbers(r_.required(t, "axis", "axis"), 3, "axis");
    if (std::all_of(v.begin(), v.end(), is_exact_zero)) r_.fail(t, "axis of zero length");
    return {v[0], v[1], v[2]};
  }

  const TomlReader& r_;
  std::map<std::string, int> joint_index_;
};

}  // namespace

SphericalCase read_spherical(const toml::table& root, const TomlReader& r) {
  SphericalCase c = SphericalReader(r).read(root);
  validate(c);
  return c;
}

SphericalCase read_spherical(const toml::table& root, const std::string& file, std::string_view text) {
  return read_spherical(root, TomlReader(file, text));
}

void validate(const SphericalCase& c) {
  auto fail = [&](int line, const std::string& m) { throw InputError(c.file, line, m); };
  if (c.loops.empty()) fail(0, "no loops: nothing to solve");
  if (c.joints.empty()) fail(0, "no joints: nothing to solve");
  if (c.joints.size() > 20) fail(c.joints[0].line, "more than 20 joints (2^r sub-problems)");
  std::vector<bool> used(c.joints.size(), false);
  auto check_factor = [&](const Factor& f) {
    auto zero = [](auto& v) { return std::all_of(v.begin(), v.end(), is_exact_zero); };
    if (f.kind == Factor::Kind::constant) {
      if (zero(f.q)) fail(f.line, "constant quaternion is zero");
      return;
    }
    // As formulate's normalisation needs it: |axis|^2 provably positive.
    if (!((square(f.axis[0]) + square(f.axis[1]) + square(f.axis[2])).lower() > 0)) fail(f.line, "axis of zero length");
    if (f.kind == Factor::Kind::joint && (f.joint < 0 || f.joint >= static_cast<int>(c.joints.size())))
      fail(f.line, "joint index out of range");
  };
  for (auto& loop : c.loops) {
    std::vector<bool> in_loop(c.joints.size(), false);
    for (auto& f : loop.factors) {
      check_factor(f);
      if (f.kind != Factor::Kind::joint) continue;
      if (in_loop[f.joint])
        fail(f.line, "joint '" + c.joints[f.joint].name + "' appears twice in loop '" + loop.name +
                         "' (the loop equations would not be multi-affine)");
      in_loop[f.joint] = used[f.joint] = true;
    }
  }
  for (size_t j = 0; j < used.size(); ++j)
    if (!used[j]) fail(c.joints[j].line, "joint '" + c.joints[j].name + "' is used in no loop");
  for (auto& out : c.outputs) {
    if (out.name == "box" || out.name == "search_box" || out.name == "subproblem" || out.name.empty())
      fail(out.line, "output name '" + out.name + "' is reserved or empty");
    for (auto& f : out.factors) check_factor(f);
  }
}

}  // namespace linkbox::input
