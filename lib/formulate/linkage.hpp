#pragma once
// Loop linkages of revolute and prismatic joints in the vector model of the iterated-LP
// paper (Porta, Ros, Thomas, Section II): per joint a unit axis d, per link a unit normal a,
// and per loop equations (1)-(4)
//   |a_i| = |d_i| = 1,  sum_i d_i d_i + a_i a_i = 0,  d_i x d_{i+1} = sin(alpha_i) a_i,
//   d_i . d_{i+1} = cos(alpha_i),
// in the Denavit-Hartenberg convention  prod_i Rz(theta_i) Tz(d_i) Tx(a_i) Rx(alpha_i) = I:
// d_i = z_{i-1} is the axis of joint i, a_i = x_i the common normal from joint i to joint
// i+1, theta_i the angle from a_{i-1} to a_i about d_i. A prismatic joint fixes theta_i
// (a_{i-1} . a_i = cos theta_i, a_{i-1} x a_i = sin theta_i d_i) and lets d_i vary.
// Only what a case needs is modelled: the ground link's vectors are constants, normals of
// zero-length links are left out (see LinkageOptions), coordinates that a linear equation in
// one variable fixes, or in two variables ties to another without adding products, are
// substituted, equations left constant are dropped; the rest is lifted to L/P/H (to_lph).
#include "formulate/formulation.hpp"
#include "input/linkage_file.hpp"

#include <array>
#include <iosfwd>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace linkbox::formulate {

struct ModelSize {
  int primary = 0, dummy = 0, linear = 0, parabolic = 0, hyperbolic = 0;
  bool operator==(const ModelSize&) const = default;
};
std::string to_string(const ModelSize& s);  // "23 primary + 44 dummy; 28 L, 21 P, 23 H"
std::ostream& operator<<(std::ostream& os, const ModelSize& s);

struct LinkageOptions {
  // A link of length 0 between revolute joints occurs in no loop closure: its normal a_i is
  // fixed by d_i x d_{i+1} / sin(alpha_i) and its norm follows from (1) and (4), so it is
  // left out of the model (recovered for the joint angles). True keeps it, as the paper does.
  bool keep_free_normals = false;
};

class LinkageFormulation final : public Formulation {
 public:
  // Validates and builds the model; throws input::InputError for an invalid case, and when
  // the ground alone contradicts an equation (the linkage cannot be assembled).
  explicit LinkageFormulation(input::LinkageCase c, LinkageOptions options = {});

  std::string kind() const override { return "linkage"; }
  size_t subproblem_count() const override { return 1; }
  SubProblem subproblem(size_t) const override { return sub_; }
  // One per joint (theta for revolute, the offset d for prismatic joints), measured in the
  // first loop through the joint; a revolute joint that further loops see between other
  // normals adds "joint@loop" for each. Where an angle constraint ties the orientations of
  // two loops, the turn that places the later loop is an output too: "turn[link@loop]" is
  // the angle about the joint the loop shares with those placed before it, from the normal
  // of the link before that joint in the loop it is placed from to its normal in `loop`.
  std::vector<std::string> output_names() const override;
  // Angles in (-pi, pi]; an enclosure across the cut at pi is reported around pi.
  Box to_output(size_t index, const Box& box) const override;
  bool outputs_are_angles() const override { return !has_prismatic_; }

  // Certification (linkage_natural.cpp): the natural unknowns are the outputs (half-angle
  // tangents of the angles in a chart of half-turn shifts, prismatic offsets as they are);
  // the equations are the DH loop closure of each loop (loop_closure.hpp), then one per
  // angle constraint, between axes placed from the ground link's frame through the turns.
  // Loops are placed one after another, each sharing exactly one joint with those placed
  // before it; other patterns have no natural system (NaturalSystem::missing says why).
  std::uint64_t chart_for(const Box& output_hull) const override;
  // With joint limits, one inequality per limited joint (see limit_inequality).
  NaturalSystem natural_system(std::uint64_t chart) const override;
  std::vector<std::string> model_notes() const override;
  Box output_to_natural(std::uint64_t chart, const Box& output) const override;
  Box natural_to_output(std::uint64_t chart, const Box& natural) const override;

  const input::LinkageCase& linkage_case() const { return case_; }
  // The natural unknown of each entry of loop `l` (an output index), in the loop's order.
  const std::vector<int>& loop_unknowns(size_t l) const { return unknown_of_entry_.at(l); }
  ModelSize model_size() const;

  // Where the model keeps each coordinate of a vector: value + scale * v[variable], v being
  // the sub-problem's variables, or the rigorous constant `value` when variable < 0 (ground
  // frame, substituted, or unconstrained: then its domain). A coordinate that is a variable
  // of its own has scale 1 and value 0; others were eliminated through a linear equation.
  struct Coordinate {
    int variable = -1;
    Interval scale{1.0};
    Interval value{0.0};
    bool is_variable() const;  // variable >= 0 with scale exactly 1 and value exactly 0
    Interval at(const Box& box) const;
  };
  using VectorModel = std::array<Coordinate, 3>;

  // Joints in order of first appearance.
  const std::vector<std::string>& joint_names() const { return joint_names_; }
  const VectorModel& axis(size_t joint) const { return vectors_.at(joint); }
  // The normal a_i of entry `position` of loop `loop`; nullptr when left out of the model.
  const VectorModel* normal(size_t loop, size_t position) const;
  // The offset of a prismatic joint (std::out_of_range for a revolute one).
  const Coordinate& offset(size_t joint) const;

 private:
  struct Normal {
    int joint_in, joint_out;  // indices of the joints it runs between
    std::string name;         // "a[link]" (or "a[link@loop]" when the link has several)
    Interval a, alpha;
    bool ground = false, modelled = true;
    bool negative_sine = false;  // sin(alpha) < 0: a = -(d_in x d_out) / |...|
    int line = 0;
  };
  struct Output {
    std::string name;
    int joint;
    int normal_in = -1, normal_out = -1;  // revolute: theta from a_in to a_out about d
    bool turn = false;                     // a loop's turn about `joint` (an angle even there)
    bool is_offset(const std::vector<bool>& prismatic) const { return prismatic[joint] && !turn; }
  };
  // Loop `loop` is placed from loop `parent` through the joint they share, at entry
  // `entry` of this loop and `parent_entry` of the parent: the frame of the link before it
  // here is that of the parent's link before it turned about the joint by the output `turn`
  // (-1 when no equation needs it: the loop's orientation about the joint then matters to
  // no output). The ground's loop has parent -1 and is placed at the ground link.
  struct Placement {
    int loop = -1, parent = -1, entry = -1, parent_entry = -1, turn = -1;
  };
  // A factor of the rotation chain from the world frame to a link frame: Rz of the joint
  // (revolute: its unknown; prismatic: its theta) or Rx(alpha) of entry `entry` of `loop`,
  // or the turn placing `loop`; walked backwards round a loop it is inverted.
  struct ChainFactor {
    enum Kind { joint, twist, turn } kind;
    int loop, entry;
    bool inverse;
    bool operator==(const ChainFactor&) const = default;
  };
  void index_case();  // joints, normals and outputs (index_joints, index_normals, list_outputs)
  void index_joints();
  void index_normals();
  void list_outputs();
  void ground_frame();
  class ModelBuilder;  // build_model's steps (linkage_model.cpp)
  void build_model();
  void plan_natural();  // placements_, turn outputs, unknown_of_entry_, or no_natural_
  std::vector<ChainFactor> frame_chain(int loop, int position) const;
  std::vector<ChainFactor> axis_chain(int joint) const;  // to a frame whose z is the axis
  model::Polynomial angle_equation(const input::AngleConstraint& ac, std::uint64_t chart) const;
  std::uint64_t angle_outputs() const;  // bit k: output k is an angle (not an offset)
  std::array<Interval, 3> vector_value(int vector, const Box& box) const;
  std::array<model::Polynomial, 3> vector_polynomial(int vector) const;  // over the primary variables

  // A joint limit as the arc |theta - mid| <= half (modulo 2 pi), i.e. cos(theta - mid) >=
  // cos(half): linear in (cos theta, sin theta), so polynomial both in the vector model
  // (a_in . a_out and (a_in x a_out) . d) and in a half-angle tangent (times 1 + t^2 > 0).
  struct Limit {
    int output;             // the joint's output (and natural unknown)
    Interval mid, half;
    std::string name;       // "theta1 in [-pi/2, pi/2]" as written
  };
  model::Inequality limit_inequality(const Limit& l, std::uint64_t chart) const;  // natural unknowns

  input::LinkageCase case_;
  LinkageOptions options_;
  std::vector<std::string> joint_names_;
  std::map<std::string, int> joint_index_;
  std::vector<bool> prismatic_;
  std::vector<std::vector<int>> loop_normals_;  // [loop][position] -> normal index
  std::vector<Normal> normals_;
  // Vectors: joint axes (by joint index), then normals (joint count + normal index).
  std::vector<VectorModel> vectors_;
  std::vector<bool> constant_;  // vector fixed by the ground frame
  std::vector<Coordinate> offsets_;  // by joint; prismatic joints only
  std::vector<Output> outputs_;
  bool has_prismatic_ = false;
  SubProblem sub_;
  int ground_loop_ = -1, ground_entry_ = -1;
  std::vector<Placement> placements_;  // in placement order, the ground's loop first
  std::vector<std::vector<int>> unknown_of_entry_;  // [loop][entry] -> output index
  std::string no_natural_;  // why there is no natural system (empty: there is one)
  std::vector<Limit> limits_;  // joint limits of less than a full turn
};

}  // namespace linkbox::formulate
