// The linkage format: loops of links in the Denavit-Hartenberg convention
//
//   prod_i Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i) = I      (i = 1..n around the loop)
//
// so joint i turns (revolute) or slides (prismatic) about/along d_i = z_{i-1}; link i runs
// along the common normal a_i = x_i from joint i to joint i+1, with d_i x d_{i+1} =
// sin(alpha_i) a_i and d_i . d_{i+1} = cos(alpha_i); theta_i is the angle from a_{i-1} to a_i
// about d_i (reported in (-pi, pi]). Entry n wraps around to entry 1.
//
//   kind = "linkage"
//   name = "6r-rigid"
//   description = "..."                      # optional
//   ground = "L6"                            # the grounded link: its frame is the world
//                                            # frame (x = its a, z = the next joint's d)
//   [[loops]]
//   name = "ring"                            # optional, default "loop N"
//   links = [                                # entry i: joint i, then link i
//     { joint = "theta1", link = "L1", a = 0.3, d = 0.0106, alpha = "pi/2" },
//     { joint = "s2", type = "prismatic", theta = 0, d = [0.5, 2], link = "L2", a = 1, alpha = 0.3 },
//     ...
//   ]
//   [[angle_constraints]]                    # optional: d_joint1 . d_joint2 = cos(angle)
//   name = "bridgehead"                      # optional
//   joints = ["c2-c3", "c2-c7"]
//   angle = 1.91
//   [joint_limits]                           # optional: revolute joint angles, radians
//   theta1 = ["-pi/2", "pi/2"]               # theta1 in [-pi/2, pi/2]
//   theta4 = [2.5, 3.8]                      # modulo 2 pi: an arc through pi
//
// Per entry: `a` the link length (any real: a negative one runs along -a_i), `alpha` the twist (radians), `d` the
// offset along the joint axis from a_{i-1} to a_i. `type` is "revolute" (default: theta is
// the unknown) or "prismatic": then `theta` is fixed (required) and `d = [lo, hi]` is the
// range the offset slides in. Numbers are TOML integers, floats (enclosed as the decimal
// written: 0.0175 is not a double) or constant expressions ("pi/2").
//
// Several loops share joints and links by name. A shared joint has one axis vector: it must
// join the same two links, in the same direction, in every loop through it. A link between the
// same two joints in several loops has one normal; a link that leads to different joints in
// different loops (a bridgehead atom) is tied only by the angle constraints given, as in the
// paper's bicyclohexane. The joint angle of a shared joint is measured in the first loop.
//
// A joint limit [lo, hi] keeps a revolute joint's angle (the one reported, in (-pi, pi]) on
// the arc from lo to hi, modulo 2 pi: lo <= hi, hi - lo at most a full turn. Only
// configurations within every limit are roots; the search prunes with the limits and
// verification proves each certified root within them (or says it is on a limit). A
// prismatic joint is limited by its range d = [lo, hi].
#include "input/linkage_file.hpp"

#include "input/toml_reader.hpp"

namespace linkbox::input {

namespace {

LoopLink read_entry(const TomlReader& r, const toml::node& n, const std::string& loop) {
  const toml::table& t = r.table(n, "a link of loop '" + loop + "'");
  r.only_keys(t, {"joint", "link", "a", "d", "alpha", "type", "theta"}, "a loop entry");
  LoopLink e;
  e.line = TomlReader::line_of(t);
  e.link = r.string(r.required(t, "link", "link name"), "link");
  e.joint = r.string(r.required(t, "joint", "joint name of link '" + e.link + "'"), "joint");
  if (e.link.empty()) r.fail(t, "empty link name");
  if (e.joint.empty()) r.fail(t, "empty joint name");
  const std::string of = " of link '" + e.link + "'";
  if (const toml::node* type = t.get("type")) {
    const std::string s = r.string(*type, "type");
    if (s != "revolute" && s != "prismatic")
      r.fail(*type, "unknown joint type '" + s + "' (known: revolute, prismatic)");
    e.prismatic = s == "prismatic";
  }
  const toml::node &a = r.required(t, "a", "length 'a'" + of), &alpha = r.required(t, "alpha", "twist 'alpha'" + of);
  e.a = r.number(a, "a");
  e.alpha = r.number(alpha, "alpha");
  e.exact.a = r.exact_key(a);
  e.exact.alpha = r.exact_key(alpha);
  const toml::node& d = r.required(t, "d", "offset 'd'" + of);
  if (e.prismatic) {
    const std::string what = "range 'd' of prismatic joint '" + e.joint + "'";
    const std::vector<Interval> range = r.numbers(d, 2, what);
    if (range[0].lower() > range[1].upper()) r.fail(d, "empty " + what + ": lower bound exceeds upper bound");
    e.d = Interval(range[0].lower(), range[1].upper());
    const std::string lower = r.exact_key(*d.as_array()->get(0)), upper = r.exact_key(*d.as_array()->get(1));
    e.exact.d = lower.empty() || upper.empty() ? "" : lower + " " + upper;
    const toml::node& theta = r.required(t, "theta", "fixed angle 'theta' of prismatic joint '" + e.joint + "'");
    e.theta = r.number(theta, "theta");
    e.exact.theta = r.exact_key(theta);
  } else {
    if (d.as_array())
      r.fail(d, "offset 'd'" + of + " is a range, but joint '" + e.joint +
                    "' is revolute (add type = \"prismatic\" for a sliding joint)");
    e.d = r.number(d, "d");
    e.exact.d = r.exact_key(d);
    if (t.contains("theta"))
      r.fail(*t.get("theta"), "joint '" + e.joint + "' is revolute: its theta is the unknown (a fixed theta needs "
                              "type = \"prismatic\")");
  }
  return e;
}

}  // namespace

LinkageCase read_linkage(const toml::table& root, const TomlReader& r) {
  r.only_keys(root, {"kind", "name", "description", "ground", "loops", "angle_constraints", "joint_limits"},
              "a linkage case");
  LinkageCase c;
  c.file = r.file();
  c.name = r.string(r.required(root, "name", "case name"), "name");
  const toml::node& ground = r.required(root, "ground", "grounded link");
  c.ground = r.string(ground, "ground");
  c.ground_line = TomlReader::line_of(ground);

  for (auto& t : r.loops(root, "links")) {
    LinkageLoop loop{t.name, {}, t.line};
    for (auto& e : *t.items) loop.links.push_back(read_entry(r, e, loop.name));
    c.loops.push_back(std::move(loop));
  }

  if (const toml::node* constraints = root.get("angle_constraints")) {
    for (auto& n : r.array(*constraints, "angle_constraints")) {
      const toml::table& t = r.table(n, "an angle constraint");
      r.only_keys(t, {"name", "joints", "angle"}, "an angle constraint");
      AngleConstraint a;
      a.line = TomlReader::line_of(t);
      if (const toml::node* name = t.get("name")) a.name = r.string(*name, "angle constraint name");
      const toml::node& joints = r.required(t, "joints", "the two joints of the angle constraint");
      const toml::array* pair = joints.as_array();
      if (!pair || pair->size() != 2)
        r.fail(joints, "'joints' of an angle constraint must be an array of 2 joint names");
      a.joint1 = r.string(*pair->get(0), "joint name");
      a.joint2 = r.string(*pair->get(1), "joint name");
      const toml::node& angle = r.required(t, "angle", "angle of the angle constraint");
      a.angle = r.number(angle, "angle");
      a.exact_angle = r.exact_key(angle);
      c.angle_constraints.push_back(std::move(a));
    }
  }

  if (const toml::node* limits = root.get("joint_limits")) {
    const toml::table& t = r.table(*limits, "joint_limits (a table: joint = [lower, upper])");
    for (auto&& [key, value] : t) {
      JointLimit l;
      l.joint = std::string(key.str());
      l.line = TomlReader::line_of(value);
      const std::vector<Interval> b = r.numbers(value, 2, "joint limit of '" + l.joint + "'");
      l.lower = b[0];
      l.upper = b[1];
      c.joint_limits.push_back(std::move(l));
    }
  }

  validate(c);
  return c;
}

LinkageCase read_linkage(const toml::table& root, const std::string& file, std::string_view text) {
  return read_linkage(root, TomlReader(file, text));
}

}  // namespace linkbox::input
