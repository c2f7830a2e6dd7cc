#include "verify/cluster.hpp"

#include "interval/rigorous.hpp"

#include <boost/pending/disjoint_sets.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace linkbox::verify {

namespace {

bool is_periodic(const std::vector<bool>& periodic, size_t d) {
  return d < periodic.size() && periodic[d];
}

bool has_nan(const Box& b) {
  for (auto& x : b)
    if (std::isnan(x.lower()) || std::isnan(x.upper())) return true;
  return false;
}

// Float centre. Boost's median() switches the rounding mode on every call, too slow here.
double centre(const Interval& x) { return 0.5 * x.lower() + 0.5 * x.upper(); }

// Closed arcs a and b on a circle of circumference `period` (an enclosure) meet.
bool arcs_touch(const Interval& a, const Interval& b, const Interval& period) {
  if (!is_finite(a) || !is_finite(b)) return true;  // an infinite side wraps all the way
  // Float pre-test: decides all but near-contacts without touching the rounding mode.
  const double ma = centre(a), mb = centre(b), p = centre(period);
  const double gap = std::fabs(std::remainder(ma - mb, p)) -
                     0.5 * ((a.upper() - a.lower()) + (b.upper() - b.lower()));
  const double tol = 1e-12 * (2 + std::fabs(ma) + std::fabs(mb));
  if (gap > tol) return false;
  if (gap < -tol) return true;
  double total;
  {
    RoundingGuard up;  // scoped: nearbyint below must round to nearest
    total = up.add_up(up.sub_up(a.upper(), a.lower()), up.sub_up(b.upper(), b.lower()));
  }
  if (total >= period.lower()) return true;  // two arcs this long cannot be disjoint
  // Arcs shorter than a period meet for at most the shift nearest to their centres' offset;
  // one shift either side absorbs the float error of that estimate.
  double k0 = std::nearbyint((ma - mb) / p);
  for (double k = k0 - 1; k <= k0 + 1; ++k) {
    Interval shifted = b + Interval(k) * period;
    if (a.lower() <= shifted.upper() && shifted.lower() <= a.upper()) return true;
  }
  return false;
}

// One interval of a box in the sweep dimension, possibly shifted by a period.
struct Entry {
  double lo, hi;
  int id;
};

// Sweep input for one dimension: sorted entries, the slack that makes float-computed
// periodic positions a superset of true contacts, and boxes that wrap the whole circle.
struct Sweep {
  std::vector<Entry> entries;
  std::vector<int> wrapping;
  double slack = 0;
  std::int64_t cost = 0;  // comparisons the sweep will make
};

Sweep make_sweep(const std::vector<Box>& boxes, const std::vector<int>& ids, size_t d,
                 bool periodic) {
  Sweep s;
  s.entries.reserve(ids.size() * (periodic ? 2 : 1));
  if (!periodic) {
    for (int id : ids) s.entries.push_back({boxes[id][d].lower(), boxes[id][d].upper(), id});
  } else {
    Interval period = two_pi();
    double p = centre(period), max_abs = 0;
    for (int id : ids) {
      const Interval& x = boxes[id][d];
      if (!is_finite(x) || x.upper() - x.lower() >= period.lower()) {
        s.wrapping.push_back(id);
        continue;
      }
      max_abs = std::max({max_abs, std::fabs(x.lower()), std::fabs(x.upper())});
      double w = x.upper() - x.lower();
      double r = x.lower() - std::floor(x.lower() / p) * p;  // position on [0, p)
      if (r < 0) r += p;
      if (r >= p) r -= p;
      s.entries.push_back({r, r + w, id});
      s.entries.push_back({r + p, r + p + w, id});  // the copy one turn on catches wrap-around
    }
    // Covers the reduction error (grows with the number of turns) and the width of the
    // period enclosure that boxes_touch allows for. Only candidates depend on it.
    s.slack = 1e-12 * (max_abs + p) * (2 + max_abs / p);
  }
  std::sort(s.entries.begin(), s.entries.end(),
            [](const Entry& a, const Entry& b) { return a.lo < b.lo || (a.lo == b.lo && a.id < b.id); });
  // Each entry is compared with the later entries starting before it ends.
  for (size_t i = 0; i < s.entries.size(); ++i) {
    double reach = s.entries[i].hi + s.slack;
    auto end = std::upper_bound(s.entries.begin() + i + 1, s.entries.end(), reach,
                                [](double v, const Entry& e) { return v < e.lo; });
    s.cost += end - (s.entries.begin() + i + 1);
  }
  s.cost += static_cast<std::int64_t>(s.wrapping.size()) * static_cast<std::int64_t>(ids.size());
  return s;
}

}  // namespace

Interval two_pi() {
  static const Interval value = Interval(2.0) * rigorous::pi();  // exact doubling
  return value;
}

Box unwrap(const Box& b, const Box& ref, bool angles) {
  if (!angles || b.size() != ref.size()) return b;
  Box r = b;
  for (size_t i = 0; i < b.size(); ++i) {
    const double turns = std::round((median(ref[i]) - median(b[i])) / (2 * M_PI));
    if (turns != 0) r[i] += two_pi() * Interval(turns);
  }
  return r;
}

bool boxes_touch(const Box& a, const Box& b, const std::vector<bool>& periodic) {
  if (a.size() != b.size()) return false;
  for (size_t d = 0; d < a.size(); ++d) {
    const Interval &x = a[d], &y = b[d];
    if (std::isnan(x.lower()) || std::isnan(x.upper()) || std::isnan(y.lower()) || std::isnan(y.upper()))
      return false;
    if (is_periodic(periodic, d)) {
      if (!arcs_touch(x, y, two_pi())) return false;
    } else if (!(x.lower() <= y.upper() && y.lower() <= x.upper())) {
      return false;
    }
  }
  return true;
}

double farthest_distance(const Box& a, const Box& b, const std::vector<bool>& periodic) {
  if (a.size() != b.size()) throw std::invalid_argument("farthest_distance: boxes of different dimension");
  double d = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    Interval bi = b[i];
    if (is_periodic(periodic, i)) {
      const double turns = std::nearbyint((centre(a[i]) - centre(b[i])) / (2 * M_PI));
      if (turns != 0) bi += two_pi() * Interval(turns);
    }
    d = std::max(d, norm(a[i] - bi));  // sup |x - y| over x in a[i], y in bi, rounded up
  }
  return d;
}

namespace {
// The sets of `sets` over 0..n-1, each sorted ascending, ordered by their smallest member:
// independent of the order in which unions happened.
std::vector<std::vector<int>> groups(boost::disjoint_sets_with_storage<>& sets, int n) {
  std::vector<int> slot(n, -1);
  std::vector<std::vector<int>> out;
  for (int i = 0; i < n; ++i) {
    const int r = sets.find_set(i);
    if (slot[r] < 0) slot[r] = static_cast<int>(out.size()), out.emplace_back();
    out[slot[r]].push_back(i);
  }
  return out;
}
}  // namespace

std::vector<std::vector<int>> cluster_boxes(const std::vector<Box>& boxes,
                                            const std::vector<bool>& periodic) {
  const int n = static_cast<int>(boxes.size());
  if (n == 0) return {};
  boost::disjoint_sets_with_storage<> sets(n);
  const size_t dim = boxes[0].size();
  for (auto& b : boxes)
    if (b.size() != dim) throw std::invalid_argument("cluster_boxes: boxes of different dimensions");
  if (!periodic.empty() && periodic.size() != dim)
    throw std::invalid_argument("cluster_boxes: one periodic flag per dimension expected");

  std::vector<int> ids;  // NaN boxes touch nothing and stay alone
  for (int i = 0; i < n; ++i)
    if (!has_nan(boxes[i])) ids.push_back(i);

  auto join = [&](int a, int b) {
    if (a != b && sets.find_set(a) != sets.find_set(b) && boxes_touch(boxes[a], boxes[b], periodic))
      sets.union_set(a, b);
  };

  if (dim == 0) {
    for (size_t k = 1; k < ids.size(); ++k) join(ids[0], ids[k]);
    return groups(sets, n);
  }

  // Sweep along the dimension where the fewest boxes overlap in projection.
  Sweep best;
  best.cost = -1;
  for (size_t d = 0; d < dim; ++d) {
    Sweep s = make_sweep(boxes, ids, d, is_periodic(periodic, d));
    if (best.cost < 0 || s.cost < best.cost) best = std::move(s);
  }

  for (int w : best.wrapping)
    for (int id : ids) join(w, id);
  std::vector<Entry> active;
  for (const Entry& e : best.entries) {
    size_t kept = 0;
    for (const Entry& a : active) {
      if (a.hi + best.slack < e.lo) continue;  // ended before e starts: gone for good
      active[kept++] = a;
      join(a.id, e.id);
    }
    active.resize(kept);
    active.push_back(e);
  }
  return groups(sets, n);
}

}  // namespace linkbox::verify
