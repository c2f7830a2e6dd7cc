#pragma once
// Spherical mechanisms as loops of rotations about unit axes through one point (the
// spherical paper, Sections 2-3). Each loop q_1 ... q_r = 1 with q_i = (1 + t_i p_i) up to
// scale gives the 3 multi-affine vector-part equations in the half-angle tangents t_i.
#include "formulate/formulation.hpp"
#include "input/spherical_file.hpp"

#include <array>
#include <string>
#include <vector>

namespace linkbox::formulate {

using Vec3 = input::Vec3;
using Quaternion = input::Quaternion;

// Rotation helpers (interval arithmetic, outward rounded).
Quaternion axis_angle(const Vec3& axis, const Interval& angle);  // unit quaternion, rigorous
Vec3 normalized(const Vec3& v);  // throws std::invalid_argument on a zero vector
// Rotation matrix of a non-zero quaternion (divides by its squared norm).
std::vector<std::vector<Interval>> rotation_matrix(const Quaternion& q);

class SphericalFormulation final : public Formulation {
 public:
  // Validates the case (input::validate; throws input::InputError).
  explicit SphericalFormulation(input::SphericalCase c);
  std::string kind() const override { return "spherical"; }
  // 2^r sub-problems: bit j of the index shifts joint j by a half turn.
  size_t subproblem_count() const override { return size_t{1} << case_.joints.size(); }
  SubProblem subproblem(size_t index) const override;
  std::vector<std::string> output_names() const override;
  Box to_output(size_t index, const Box& box) const override;
  std::vector<MatrixOutput> declared_outputs(size_t index, const Box& box) const override;
  bool outputs_are_angles() const override { return true; }
  // Chart = half-turn shift mask, as for sub-problems: joint j shifted when |phi_j| > pi/2.
  std::uint64_t chart_for(const Box& output_hull) const override;
  NaturalSystem natural_system(std::uint64_t chart) const override;
  Box output_to_natural(std::uint64_t chart, const Box& output) const override;
  Box natural_to_output(std::uint64_t chart, const Box& natural) const override { return to_output(chart, natural); }
  std::vector<MatrixOutput> natural_outputs(std::uint64_t chart, const Box& natural) const override {
    return declared_outputs(chart, natural);
  }

  const input::SphericalCase& spherical_case() const { return case_; }
  // The 3 vector-part polynomials of one loop for a shift mask, over all joints' t variables.
  std::array<model::Polynomial, 3> loop_equations(size_t loop, size_t shift_mask) const;

 private:
  // A loop's equations depend only on the shifts of its own joints: expanded once per
  // pattern of those shifts (2^k per loop instead of 2^r per loop).
  struct LoopCache {
    std::vector<int> joints;  // loop-local bit -> joint index
    std::vector<std::array<model::Polynomial, 3>> by_local_shift;
  };
  std::array<model::Polynomial, 3> expand_loop(size_t loop, size_t shift_mask) const;

  input::SphericalCase case_;
  std::vector<LoopCache> cache_;
};

}  // namespace linkbox::formulate
