#include "input/linkage_file.hpp"

#include "interval/rigorous.hpp"

#include <boost/pending/disjoint_sets.hpp>

#include <map>
#include <tuple>

namespace linkbox::input {

namespace {

std::string quote(const std::string& s) { return "'" + s + "'"; }
std::string at_line(int line) { return " (line " + std::to_string(line) + ")"; }

struct JointUse {
  const LinkageLoop* loop;
  const LoopLink* entry;
  std::string prev, next;
};
struct LinkUse {
  const LinkageLoop* loop;
  const LoopLink* entry;
  std::string in, out;
};

// validate's checks, in the order they run (the first failure throws), and what the loops
// seen so far use of each joint, link and normal.
class Validator {
 public:
  explicit Validator(const LinkageCase& c) : c_(c) {}

  void run() {
    if (c_.loops.empty()) fail(0, "no loops");
    for (size_t l = 0; l < c_.loops.size(); ++l) {
      check_loop(c_.loops[l]);
      for (size_t i = 0; i < c_.loops[l].links.size(); ++i) check_entry(l, i);
    }
    const int ground = check_ground();
    check_angle_constraints();
    check_joint_limits();
    check_tied_to_ground(ground);
  }

 private:
  [[noreturn]] void fail(int line, const std::string& m) const { throw InputError(c_.file, line, m); }

  // A loop on its own: its name, its size, and each entry's names and parameters.
  void check_loop(const LinkageLoop& loop) {
    if (loop.name.empty()) fail(loop.line, "empty loop name");
    if (auto [it, fresh] = loop_lines_.emplace(loop.name, loop.line); !fresh)
      fail(loop.line, "duplicate loop name " + quote(loop.name) + " (first declared on line " +
                          std::to_string(it->second) + ")");
    const size_t n = loop.links.size();
    if (n < 3)
      fail(loop.line, "loop " + quote(loop.name) + " has " + std::to_string(n) +
                          " link(s); a loop needs at least 3 (joints and links alternate around it)");
    std::map<std::string, int> joints_here, links_here;
    for (const LoopLink& e : loop.links) {
      if (e.link.empty()) fail(e.line, "empty link name");
      if (e.joint.empty()) fail(e.line, "empty joint name");
      if (auto [it, fresh] = joints_here.emplace(e.joint, e.line); !fresh)
        fail(e.line, "joint " + quote(e.joint) + " appears twice in loop " + quote(loop.name) + " (also on line " +
                         std::to_string(it->second) + "): a loop passes each joint once");
      if (auto [it, fresh] = links_here.emplace(e.link, e.line); !fresh)
        fail(e.line, "link " + quote(e.link) + " appears twice in loop " + quote(loop.name) + " (also on line " +
                         std::to_string(it->second) + "): a loop passes each link once");
      for (const Interval* v : {&e.a, &e.alpha, &e.d})
        if (!is_finite(*v)) fail(e.line, "parameter of link " + quote(e.link) + " is not finite");
      if (e.prismatic && !is_finite(e.theta)) fail(e.line, "theta of joint " + quote(e.joint) + " is not finite");
      if (e.prismatic && !(e.d.lower() <= e.d.upper()))
        fail(e.line, "empty range of the offset d of prismatic joint " + quote(e.joint));
    }
  }

  // Entry i of loop l against what the loops before it (and its earlier entries) use of its
  // joint, its link and its normal; then recorded.
  void check_entry(size_t l, size_t i) {
    const LinkageLoop& loop = c_.loops[l];
    const size_t n = loop.links.size();
    const LoopLink& e = loop.links[i];
    const std::string& prev = loop.links[(i + n - 1) % n].link;
    const std::string& next_joint = loop.links[(i + 1) % n].joint;
    loops_of_joint_[e.joint].push_back(static_cast<int>(l));
    loop_of_link_.emplace(e.link, static_cast<int>(l));
    check_joint(loop, e, prev);
    check_link(loop, e, next_joint);
    check_normal(e, next_joint);
  }

  void check_joint(const LinkageLoop& loop, const LoopLink& e, const std::string& prev) {
    if (auto [it, fresh] = joints_.emplace(e.joint, JointUse{&loop, &e, prev, e.link}); !fresh) {
      const JointUse& u = it->second;
      const std::string there = " in loop " + quote(u.loop->name) + at_line(u.entry->line);
      if (u.entry->prismatic != e.prismatic)
        fail(e.line, "joint " + quote(e.joint) + " is " + (e.prismatic ? "prismatic" : "revolute") + " here but " +
                         (u.entry->prismatic ? "prismatic" : "revolute") + there);
      if (u.prev != prev || u.next != e.link)
        fail(e.line, "joint " + quote(e.joint) + " joins links " + quote(prev) + " -> " + quote(e.link) +
                         " here but " + quote(u.prev) + " -> " + quote(u.next) + there +
                         ": a joint joins the same two links in every loop, passed in the same direction");
      if (e.prismatic && (!same_bounds(e.theta, u.entry->theta) || !same_bounds(e.d, u.entry->d)))
        fail(e.line, "prismatic joint " + quote(e.joint) + " has another theta or range than" + there);
    }
  }

  void check_link(const LinkageLoop& loop, const LoopLink& e, const std::string& next_joint) {
    if (auto [it, fresh] = links_.emplace(e.link, LinkUse{&loop, &e, e.joint, next_joint}); !fresh) {
      const LinkUse& u = it->second;
      if (u.in != e.joint && u.out != next_joint)
        fail(e.line, "link " + quote(e.link) + " runs from joint " + quote(e.joint) + " to " + quote(next_joint) +
                         " here but from " + quote(u.in) + " to " + quote(u.out) + " in loop " +
                         quote(u.loop->name) + at_line(u.entry->line) +
                         ": a link shared by loops must keep one of its joints in all of them");
    }
  }

  void check_normal(const LoopLink& e, const std::string& next_joint) {
    if (auto [it, fresh] = normals_.emplace(std::make_tuple(e.joint, e.link, next_joint), &e); !fresh) {
      const LoopLink& u = *it->second;
      if (!same_bounds(u.a, e.a) || !same_bounds(u.alpha, e.alpha))
        fail(e.line, "link " + quote(e.link) + " between joints " + quote(e.joint) + " and " + quote(next_joint) +
                         " has other a or alpha than on line " + std::to_string(u.line));
    }
  }

  // The first loop through the ground link.
  int check_ground() const {
    if (c_.ground.empty()) fail(c_.ground_line, "no ground link");
    auto ground = loop_of_link_.find(c_.ground);
    if (ground == loop_of_link_.end())
      fail(c_.ground_line, "unknown ground link " + quote(c_.ground) + " (in no loop)");
    return ground->second;
  }

  void check_angle_constraints() {
    std::map<std::string, int> constraint_lines;
    for (const AngleConstraint& a : c_.angle_constraints) {
      if (!a.name.empty())
        if (auto [it, fresh] = constraint_lines.emplace(a.name, a.line); !fresh)
          fail(a.line, "duplicate angle constraint name " + quote(a.name) + " (first declared on line " +
                           std::to_string(it->second) + ")");
      for (const std::string* j : {&a.joint1, &a.joint2})
        if (!joints_.count(*j)) fail(a.line, "angle constraint names unknown joint " + quote(*j));
      if (a.joint1 == a.joint2) fail(a.line, "angle constraint between joint " + quote(a.joint1) + " and itself");
      if (!is_finite(a.angle)) fail(a.line, "angle constraint angle is not finite");
    }
  }

  void check_joint_limits() const {
    std::map<std::string, int> limit_lines;
    const Interval turn = Interval(2.0) * rigorous::pi();
    for (const JointLimit& l : c_.joint_limits) {
      auto j = joints_.find(l.joint);
      if (j == joints_.end()) fail(l.line, "joint limit for unknown joint " + quote(l.joint));
      if (j->second.entry->prismatic)
        fail(l.line, "joint " + quote(l.joint) + " is prismatic: its range is its offset d = [lower, upper], not a joint limit");
      if (auto [it, fresh] = limit_lines.emplace(l.joint, l.line); !fresh)
        fail(l.line, "second joint limit for joint " + quote(l.joint) + " (first on line " + std::to_string(it->second) + ")");
      if (!is_finite(l.lower) || !is_finite(l.upper)) fail(l.line, "joint limit of " + quote(l.joint) + " is not finite");
      if (l.lower.lower() > l.upper.upper())
        fail(l.line, "joint limit of " + quote(l.joint) + ": lower bound exceeds upper bound (an arc through pi is written "
                     "with upper > pi, e.g. [2.5, 3.8])");
      if ((Interval(l.upper.lower()) - Interval(l.lower.upper())).lower() > turn.upper())
        fail(l.line, "joint limit of " + quote(l.joint) + " spans more than a full turn (2*pi): angles are reported modulo "
                     "2*pi, so give at most one turn, e.g. [-pi, pi] for no limit");
    }
  }

  // Loops are tied through the joints they share and through angle constraints.
  void check_tied_to_ground(int ground) {
    boost::disjoint_sets_with_storage<> tied(c_.loops.size());
    auto unite = [&](int a, int b) { tied.union_set(a, b); };
    for (auto& [joint, loops] : loops_of_joint_)
      for (int l : loops) unite(l, loops.front());
    for (const AngleConstraint& a : c_.angle_constraints)
      unite(loops_of_joint_[a.joint1].front(), loops_of_joint_[a.joint2].front());
    for (size_t l = 0; l < c_.loops.size(); ++l)
      if (tied.find_set(static_cast<int>(l)) != tied.find_set(ground))
        fail(c_.loops[l].line, "loop " + quote(c_.loops[l].name) + " is not tied to the ground link " + quote(c_.ground) +
                                   ": it shares no joint (nor an angle constraint) with the loops through it, so it "
                                   "could turn freely as a whole");
  }

  const LinkageCase& c_;
  std::map<std::string, int> loop_lines_;
  std::map<std::string, JointUse> joints_;
  std::map<std::string, LinkUse> links_;
  std::map<std::tuple<std::string, std::string, std::string>, const LoopLink*> normals_;
  std::map<std::string, std::vector<int>> loops_of_joint_;
  std::map<std::string, int> loop_of_link_;  // first loop through each link
};

}  // namespace

// What a case must satisfy before it is modelled:
//  - at least one loop, unique loop names, at least 3 links per loop, non-empty names;
//  - a loop passes each joint and each link at most once;
//  - a joint joins the same two links, in the same direction, in every loop through it (its
//    axis d is one vector), and has the same type (and for a prismatic joint the same theta
//    and range) everywhere;
//  - a link seen between the same two joints in several loops has the same a and alpha there,
//    and a link in several loops keeps one of its joints in all of them (otherwise nothing in
//    the vector model would tie the two appearances together);
//  - parameters finite, prismatic ranges non-empty;
//  - the ground link exists; angle constraints name two different known joints;
//  - every loop is tied to the ground's loops through shared joints or angle constraints
//    (a loop tied to nothing could turn freely as a whole);
//  - joint limits name a known revolute joint once, with lower <= upper and at most a full
//    turn between them.
void validate(const LinkageCase& c) { Validator(c).run(); }

}  // namespace linkbox::input
