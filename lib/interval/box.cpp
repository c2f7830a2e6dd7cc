#include "interval/box.hpp"

#include <sstream>

namespace linkbox {

namespace {
template <class F>
void for_dims(size_t n, std::span<const int> dims, F&& f) {
  if (dims.empty())
    for (size_t i = 0; i < n; ++i) f(static_cast<int>(i));
  else
    for (int d : dims) f(d);
}
}  // namespace

// One rounding guard for all sides: a guard per side (width_up) costs two mode switches each.
double max_width(const Box& box, std::span<const int> dims) {
  RoundingGuard up;
  double w = 0;
  for_dims(box.size(), dims, [&](int i) { w = std::max(w, up.sub_up(box[i].upper(), box[i].lower())); });
  return w;
}

int widest_dimension(const Box& box, std::span<const int> dims) {
  RoundingGuard up;
  int best = -1;
  double bw = -1;
  for_dims(box.size(), dims, [&](int i) {
    const double w = up.sub_up(box[i].upper(), box[i].lower());
    if (w > bw) bw = w, best = i;
  });
  return best;
}

double volume_ratio(const Box& before, const Box& after, std::span<const int> dims) {
  double r = 1;
  for_dims(before.size(), dims, [&](int i) {
    double wb = before[i].upper() - before[i].lower(), wa = after[i].upper() - after[i].lower();
    if (wb > 0) r *= wa / wb;
  });
  return r;
}

Box centre_box(const Box& box) {
  Box c(box.size());
  const NearestScope nearest;
  for (size_t i = 0; i < box.size(); ++i) c[i] = Interval(nearest.median(box[i]));
  return c;
}

std::pair<Box, Box> bisect(const Box& box, int dim) {
  Box a = box, b = box;
  double m = median(box[dim]);
  a[dim] = Interval(box[dim].lower(), m);
  b[dim] = Interval(m, box[dim].upper());
  return {std::move(a), std::move(b)};
}

Box hull(const Box& a, const Box& b) {
  Box h(a.size());
  for (size_t i = 0; i < a.size(); ++i) h[i] = hull(a[i], b[i]);
  return h;
}

bool overlaps(const Box& a, const Box& b) {
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i].upper() < b[i].lower() || b[i].upper() < a[i].lower()) return false;
  return true;
}

bool contains(const Box& outer, const Box& inner) {
  for (size_t i = 0; i < outer.size(); ++i)
    if (inner[i].lower() < outer[i].lower() || inner[i].upper() > outer[i].upper()) return false;
  return true;
}

std::string to_string(const Box& box) {
  std::ostringstream os;
  os.precision(17);
  os << '[';
  for (size_t i = 0; i < box.size(); ++i)
    os << (i ? ", " : "") << '[' << box[i].lower() << ", " << box[i].upper() << ']';
  os << ']';
  return os.str();
}

}  // namespace linkbox
