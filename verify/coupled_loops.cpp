#include "verify/coupled_loops.hpp"

#include "formulate/linkage.hpp"
#include "newton/certify.hpp"
#include "newton/interval_eigen.hpp"
#include "newton/square_system.hpp"
#include "verify/check_proofs.hpp"
#include "verify/symmetric_loop.hpp"
#include "verify/twin_loops.hpp"

#include <Eigen/LU>

#include <cmath>
#include <optional>
#include <stdexcept>

namespace linkbox::verify {

using newton::IMatrix;
using newton::IVector;

namespace {

std::string quote(const std::string& s) { return "'" + s + "'"; }

// The Newton image of a loop's own closure over its unknowns' part of x, when it proves one
// root there inside `within`, and the box where that root is the only one.
std::optional<RigidRoot> rigid_root(const formulate::NaturalSystem& sys, std::pair<int, int> rows,
                                    const std::vector<int>& vars, const Box& x, const Box& within) {
  std::vector<model::Polynomial> eqs(sys.equations.begin() + rows.first, sys.equations.begin() + rows.second);
  if (eqs.size() != vars.size()) return std::nullopt;
  const newton::SquareSystem s(eqs, vars, x);
  for (const Box* hull : {&x, &within}) {
    const newton::Certificate c = newton::certify_root(s, s.restrict(*hull));
    if (c.status == newton::Status::certified && contains(s.restrict(within), c.image))
      return RigidRoot{c.image, c.box};
    if (&x == &within) break;
  }
  return std::nullopt;
}

// The square system in y = (each curve loop's u, the unknowns of no loop), the rigid loops'
// roots held in `params`.
struct Reduced {
  const formulate::Formulation& f;
  std::uint64_t chart;
  const formulate::NaturalSystem& sys;
  Box params;                           // natural unknowns; rigid loops' parts are their roots
  Box param_angles;                     // params in the output variables
  std::vector<SymmetricLoop> loops;     // curve loops
  std::vector<std::vector<int>> outs;   // their six unknowns, in loop order
  std::vector<int> free;                // natural unknowns of no loop
  std::vector<int> rows;                // equations of no loop
  std::vector<std::vector<model::Polynomial>> d;  // d[q][k]: rows[q] differentiated in unknown k

  int unknowns() const { return static_cast<int>(3 * loops.size() + free.size()); }
  int equations() const { return static_cast<int>(2 * loops.size() + rows.size()); }
  Box u_of(const Box& y, size_t c) const { return Box(y.begin() + 3 * c, y.begin() + 3 * c + 3); }

  // The natural box at y: a curve loop's entries i and i + 3 both at angle u_i (v = 0).
  Box natural(const Box& y) const {
    Box angles = param_angles;
    for (size_t c = 0; c < loops.size(); ++c)
      for (int i = 0; i < 3; ++i) angles[outs[c][i]] = angles[outs[c][i + 3]] = y[3 * c + i];
    const Box t = f.output_to_natural(chart, angles);
    Box z = params;
    for (auto& o : outs)
      for (int k : o) z[k] = t[k];
    for (size_t j = 0; j < free.size(); ++j) z[free[j]] = y[3 * loops.size() + j];
    return z;
  }

  IVector values(const Box& y) const {
    IVector g(equations());
    const Box z = natural(y);
    for (size_t c = 0; c < loops.size(); ++c) g.segment(2 * c, 2) = loops[c].r_values(u_of(y, c));
    for (size_t q = 0; q < rows.size(); ++q) g(2 * loops.size() + q) = sys.equations[rows[q]].eval(z);
    return g;
  }

  // Angles enter the other equations through t = tan((theta - s pi) / 2): dt/dtheta = (1 + t^2) / 2.
  IMatrix jacobian(const Box& y) const {
    IMatrix j = IMatrix::Constant(equations(), unknowns(), Interval(0.0));
    const Box z = natural(y);
    const size_t l = loops.size();
    for (size_t c = 0; c < l; ++c) j.block(2 * c, 3 * c, 2, 3) = loops[c].r_jacobian(u_of(y, c));
    for (size_t q = 0; q < rows.size(); ++q) {
      const int e = static_cast<int>(2 * l + q);
      for (size_t c = 0; c < l; ++c)
        for (int i = 0; i < 3; ++i)
          for (int k : {outs[c][i], outs[c][i + 3]})
            j(e, 3 * c + i) += d[q][k].eval(z) * (1.0 + boost::numeric::square(z[k])) / 2.0;
      for (size_t k = 0; k < free.size(); ++k) j(e, 3 * l + k) = d[q][free[k]].eval(z);
    }
    return j;
  }

  // Krawczyk from y, the box grown by a tenth of its image's width each round while the image
  // is not inside; the box whose image is, if one is found with its natural box in `within`.
  std::optional<Box> root(Box y, const Box& within) const {
    for (int round = 0; round < 8; ++round) {
      Box mid = y;
      for (auto& m : mid) m = Interval(median(m));
      const IMatrix j = jacobian(y);
      const Eigen::MatrixXd jm = newton::midpoint(j);
      if (!jm.allFinite()) return std::nullopt;
      const Eigen::PartialPivLU<Eigen::MatrixXd> lu(jm);
      if (!(lu.rcond() > 1e-14)) return std::nullopt;
      const Eigen::MatrixXd c = lu.inverse();
      const IVector k = newton::to_ivector(mid) - newton::multiply(c, values(mid)) +
                        newton::multiply(newton::identity_minus(c, j), newton::to_ivector(y) - newton::to_ivector(mid));
      bool inside = true;
      for (int i = 0; i < k.size(); ++i)
        inside = inside && is_finite(k(i)) && y[i].lower() < k(i).lower() && k(i).upper() < y[i].upper();
      if (inside) return contains(within, natural(y)) ? std::optional(y) : std::nullopt;
      for (int i = 0; i < k.size(); ++i) {
        if (!is_finite(k(i))) return std::nullopt;
        const double r = 0.1 * width_up(k(i)) + 1e-15 * (1 + std::fabs(median(k(i))));
        y[i] = hull(k(i), y[i]) + Interval(-r, r);
      }
      if (!contains(within, natural(y))) return std::nullopt;
    }
    return std::nullopt;
  }
};

std::string count(int n, const std::string& what) { return std::to_string(n) + " " + what + (n == 1 ? "" : "s"); }

std::string names(const std::vector<std::string>& list) {
  std::string s;
  for (auto& n : list) s += (s.empty() ? "" : ", ") + quote(n);
  return s;
}

}  // namespace

CoupledRoom coupled_room(const std::vector<model::Polynomial>& f, const Box& start, const newton::Certificate& c) {
  Box grown = c.box;
  for (auto& w : grown) w += Interval(-1.0, 1.0) * (1e3 * width_up(w) + 1e-12 * (1 + std::fabs(median(w))));
  CoupledRoom room{hull(start, grown), false, true};
  room.unique = unique_over(f, room.box, c);
  if (!room.unique) {
    room = {grown, false, false};
    room.unique = unique_over(f, room.box, c);
  }
  return room;
}

CoupledLoops coupled_loops_root(const formulate::Formulation& f, std::uint64_t chart, const Box& x,
                                const Box& within) {
  CoupledLoops out;
  const auto* linkage = dynamic_cast<const formulate::LinkageFormulation*>(&f);
  if (!linkage) return out;
  const formulate::NaturalSystem& sys = f.natural(chart);
  const auto& loops = linkage->linkage_case().loops;
  const size_t n = sys.unknowns.size();
  if (sys.loop_rows.size() != loops.size() || !sys.links.empty() || x.size() != n || within.size() != n) return out;
  Reduced r{f, chart, sys, x, {}, {}, {}, {}, {}, {}};
  std::vector<bool> in_loop(n, false), row_in_loop(sys.equations.size(), false);
  std::vector<std::string> rigid, curve;
  std::vector<std::optional<RigidRoot>> roots(loops.size());
  for (size_t l = 0; l < loops.size(); ++l) {
    const std::vector<int>& vars = linkage->loop_unknowns(l);
    for (int k : vars) {
      if (k < 0 || k >= static_cast<int>(n) || in_loop[k]) return out;
      in_loop[k] = true;
    }
    for (int e = sys.loop_rows[l].first; e < sys.loop_rows[l].second; ++e) row_in_loop[e] = true;
    if ((roots[l] = rigid_root(sys, sys.loop_rows[l], vars, x, within))) {
      for (size_t i = 0; i < vars.size(); ++i) r.params[vars[i]] = roots[l]->image[i];
      rigid.push_back(loops[l].name);
    } else if (auto s = SymmetricLoop::of_loop(*linkage, l, vars)) {
      r.loops.push_back(std::move(*s));
      r.outs.push_back(vars);
      curve.push_back(loops[l].name);
    } else {
      out.how = "loop " + quote(loops[l].name) + " is neither rigid in the box nor a symmetric six-joint loop";
      return out;
    }
  }
  for (size_t k = 0; k < n; ++k)
    if (!in_loop[k]) r.free.push_back(static_cast<int>(k));
  for (size_t e = 0; e < sys.equations.size(); ++e)
    if (!row_in_loop[e]) r.rows.push_back(static_cast<int>(e));
  std::string twin;
  if (r.equations() > r.unknowns())
    if (const auto t = twin_constraint(*linkage, chart, roots)) {
      std::erase(r.rows, t->implied_row);
      twin = t->how + ", ";
    }
  out.equations = r.equations();
  out.unknowns = r.unknowns();
  if (r.unknowns() != r.equations() || r.unknowns() == 0) {
    out.how = (curve.empty() ? "every loop is rigid (" + names(rigid) + ")"
                             : "loops " + names(curve) + " on their symmetric curves") +
              ", and the " + std::to_string(r.rows.size()) + " equations of no loop leave " +
              count(r.equations(), "equation") + " in " + count(r.unknowns(), "unknown");
    return out;
  }
  for (int e : r.rows) {
    r.d.emplace_back();
    for (size_t k = 0; k < n; ++k) r.d.back().push_back(sys.equations[e].derivative(static_cast<int>(k)));
  }
  try {
    r.param_angles = f.natural_to_output(chart, r.params);
    const Box angles = f.natural_to_output(chart, x);
    Box y;
    for (auto& o : r.outs)
      for (int i = 0; i < 3; ++i) {
        Interval u;
        if (!intersect(angles[o[i]], angles[o[i + 3]], u)) return out;
        y.push_back(u);
      }
    for (int k : r.free) y.push_back(x[k]);
    const auto root = r.root(y, within);
    if (!root) {
      out.how = "the Newton test of the loops' coupling fails";
      return out;
    }
    out.box = r.natural(*root);
  } catch (const std::domain_error&) {
    return out;
  }
  for (auto& e : sys.equations)
    if (!zero_in(e.eval(out.box))) return out;  // the parts' conventions disagree: nothing proved
  out.proved = true;
  out.how = (rigid.empty() ? "" : "loop" + std::string(rigid.size() > 1 ? "s " : " ") + names(rigid) +
                                        " rigid (interval Newton on its own closure), ") +
            (curve.empty() ? "" : "loop" + std::string(curve.size() > 1 ? "s " : " ") + names(curve) +
                                      " on its symmetric curve (v = 0, R(u) = 0), ") +
            twin + "and " + count(static_cast<int>(r.rows.size()), "equation") +
            " of no loop: interval Newton on the coupled system";
  return out;
}

}  // namespace linkbox::verify
