#include "model/polynomial.hpp"

#include "interval/rigorous.hpp"
#include "model/exact_coefficients.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace linkbox::model {

namespace {
Powers multiply(const Powers& a, const Powers& b) {
  Powers r;
  size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    if (j == b.size() || (i < a.size() && a[i].first < b[j].first)) r.push_back(a[i++]);
    else if (i == a.size() || b[j].first < a[i].first) r.push_back(b[j++]);
    else r.emplace_back(a[i].first, a[i].second + b[j].second), ++i, ++j;
  }
  return r;
}
bool is_exact_zero(const Interval& c) { return c.lower() == 0 && c.upper() == 0; }
bool is_point(const Interval& c) { return c.lower() == c.upper(); }
std::optional<Rational> point_value(const Interval& c) {
  if (!is_point(c) || !std::isfinite(c.lower())) return std::nullopt;
  return Rational(c.lower());
}
}  // namespace

ExactCoefficients& Polynomial::exact_for_write() {
  if (!exact_) exact_ = std::make_shared<ExactCoefficients>();
  else if (exact_.use_count() > 1) exact_ = std::make_shared<ExactCoefficients>(*exact_);
  return *exact_;
}

Polynomial Polynomial::constant(const Interval& c) {
  Polynomial p;
  p.add_term({}, c);
  return p;
}

Polynomial Polynomial::variable(int index) {
  Polynomial p;
  p.add_term({{index, 1}}, Interval(1.0));
  return p;
}

Polynomial Polynomial::monomial(const Powers& powers, const Interval& coefficient) {
  Polynomial p;
  p.add_term(powers, coefficient);
  return p;
}

Polynomial Polynomial::decimal(std::string_view literal) {
  const Interval x = rigorous::decimal(literal);
  Polynomial p;
  if (is_point(x)) {
    p.add_term({}, x);
    return p;
  }
  std::optional<ExactValue> v;
  if (auto q = exact_decimal(literal)) v.emplace(ExactValue{*q});
  p.add_term({}, x, v ? &*v : nullptr);
  return p;
}

bool Polynomial::is_constant() const {
  return terms_.empty() || (terms_.size() == 1 && terms_.begin()->first.empty());
}

Interval Polynomial::constant_term() const {
  auto it = terms_.find(Powers{});
  return it == terms_.end() ? Interval(0.0) : it->second;
}

// The exact value of a term is held only where its enclosure is not a point; the rational
// arithmetic runs only where a sum or product leaves a point's enclosure.
void Polynomial::add_term(const Powers& p, const Interval& c, const ExactValue* q) {
  if (is_exact_zero(c)) return;
  auto [it, inserted] = terms_.emplace(p, c);
  if (inserted) {
    if (q && !is_point(c)) hold(it, *q);
    return;
  }
  const Interval before = it->second;
  it->second += c;
  const bool held = exact_ && exact_->values.count(p);
  const bool known = (is_point(before) || held) && (is_point(c) || q);
  const auto old_value = known && !is_point(it->second) ? exact_coefficient(*this, p, before) : std::nullopt;
  if (held) exact_for_write().values.erase(p);
  if (is_point(it->second)) {  // a point enclosure is its own exact value
    if (is_exact_zero(it->second)) terms_.erase(it);
    return;
  }
  const auto added = q ? std::optional<Rational>(q->q) : point_value(c);
  if (!old_value || !added) return;
  const ExactValue sum{*old_value + *added};
  if (sum.q == 0 && boost::numeric::zero_in(it->second)) terms_.erase(it);  // an exact cancellation
  else hold(it, sum);
}

// The term's enclosure becomes the tightest one of its exact value, which the old enclosure
// holds, so it only narrows; a value that is not a double is held beside it. A value outside
// the old enclosure cannot be the term's: it is not held.
void Polynomial::hold(std::map<Powers, Interval>::iterator it, const ExactValue& value) {
  const Interval tight = enclosure(value.q);
  if (tight.lower() < it->second.lower() || tight.upper() > it->second.upper()) {
    if (exact_ && exact_->values.count(it->first)) exact_for_write().values.erase(it->first);
    return;
  }
  it->second = tight;
  if (is_point(it->second)) {
    if (exact_ && exact_->values.count(it->first)) exact_for_write().values.erase(it->first);
  } else {
    exact_for_write().values[it->first] = value.q;
  }
}

namespace {
// The value `p` holds for a coefficient, as an ExactValue for add_term: `slot` holds it. A
// Rational is built only where a value is held (GMP allocates).
const ExactValue* value_of(const Polynomial& p, const Powers& powers, const Interval& c,
                           std::optional<ExactValue>& slot) {
  if (!p.exact() || is_point(c)) return nullptr;
  auto it = p.exact()->values.find(powers);
  if (it == p.exact()->values.end()) return nullptr;
  return &slot.emplace(ExactValue{it->second});
}
}  // namespace

Polynomial& Polynomial::operator+=(const Polynomial& o) {
  std::optional<ExactValue> slot;
  for (auto& [p, c] : o.terms_) add_term(p, c, value_of(o, p, c, slot));
  return *this;
}

Polynomial& Polynomial::operator-=(const Polynomial& o) {
  std::optional<ExactValue> slot;
  for (auto& [p, c] : o.terms_) {
    const ExactValue* q = value_of(o, p, c, slot);
    if (q) slot->q = -slot->q;
    add_term(p, -c, q);
  }
  return *this;
}

Polynomial& Polynomial::operator*=(const Interval& c) {
  if (is_exact_zero(c)) {
    terms_.clear();
    exact_.reset();
    return *this;
  }
  if (!exact_ && !is_point(c)) {  // no exact value survives an interval factor
    for (auto& [p, v] : terms_) v *= c;
    return *this;
  }
  *this = *this * constant(c);
  return *this;
}

Polynomial& Polynomial::operator/=(const Polynomial& d) {
  const Interval dc = d.constant_term();
  const auto dq = exact_coefficient(d, {}, dc);
  Polynomial r;
  for (auto& [p, c] : terms_) {
    const Interval quotient = c / dc;
    std::optional<ExactValue> q;
    const auto cq = is_point(quotient) ? std::nullopt : exact_coefficient(*this, p, c);
    if (cq && dq && *dq != 0) q.emplace(ExactValue{*cq / *dq});
    r.add_term(p, quotient, q ? &*q : nullptr);
  }
  return *this = std::move(r);
}

Polynomial operator*(const Polynomial& a, const Polynomial& b) {
  Polynomial r;
  for (auto& [pa, ca] : a.terms_)
    for (auto& [pb, cb] : b.terms_) {
      const Interval product = ca * cb;
      std::optional<ExactValue> q;
      if (!is_point(product) && (a.exact_ || b.exact_ || (is_point(ca) && is_point(cb)))) {
        const auto qa = exact_coefficient(a, pa, ca), qb = exact_coefficient(b, pb, cb);
        if (qa && qb) q.emplace(ExactValue{*qa * *qb});
      }
      r.add_term(multiply(pa, pb), product, q ? &*q : nullptr);
    }
  return r;
}

Polynomial Polynomial::operator-() const {
  Polynomial r = *this;
  for (auto& [p, c] : r.terms_) c = -c;
  if (r.exact_) {
    auto& values = r.exact_for_write().values;
    for (auto& [p, q] : values) q = -q;
  }
  return r;
}

Polynomial Polynomial::constant_power(int exponent) const {
  const Interval c = constant_term();
  Polynomial r;
  const Interval power = boost::numeric::pow(c, exponent);
  const auto q = is_point(power) ? std::nullopt : exact_coefficient(*this, {}, c);
  std::optional<ExactValue> v;
  if (q) v.emplace(ExactValue{Rational(1)});
  for (int k = 0; q && k < exponent; ++k) v->q *= *q;
  r.add_term({}, power, v ? &*v : nullptr);
  return r;
}

Polynomial Polynomial::pow(int exponent) const {
  Polynomial r = constant(Interval(1.0)), base = *this;
  for (; exponent > 0; exponent >>= 1) {
    if (exponent & 1) r = r * base;
    if (exponent > 1) base = base * base;
  }
  return r;
}

Interval Polynomial::eval(const Box& box) const {
  Interval s(0.0);
  for (auto& [p, c] : terms_) {
    Interval t = c;
    for (auto [v, e] : p) t *= (e == 1 ? box[v] : boost::numeric::pow(box[v], e));
    s += t;
  }
  return s;
}

double residual_bound(const std::vector<Polynomial>& f, const Box& box) {
  Box mid(box.size());
  for (size_t i = 0; i < box.size(); ++i) mid[i] = Interval(median(box[i]));
  double r = 0;
  for (auto& p : f) r = std::max(r, norm(p.eval(mid)));  // norm: the larger |bound|
  return r;
}

Polynomial Polynomial::derivative(int index) const {
  Polynomial r;
  for (auto& [p, c] : terms_) {
    for (size_t k = 0; k < p.size(); ++k) {
      if (p[k].first != index) continue;
      Powers q = p;
      int e = q[k].second;
      if (e == 1) q.erase(q.begin() + k);
      else q[k].second = e - 1;
      const Interval scaled = c * Interval(static_cast<double>(e));
      const auto value = is_point(scaled) ? std::nullopt : exact_coefficient(*this, p, c);
      std::optional<ExactValue> v;
      if (value) v.emplace(ExactValue{*value * e});
      r.add_term(q, scaled, v ? &*v : nullptr);
    }
  }
  return r;
}

std::vector<int> Polynomial::variables() const {
  std::vector<int> v;
  for (auto& [p, c] : terms_)
    for (auto [i, e] : p) v.push_back(i);
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

int Polynomial::degree_in(int index) const {
  int d = 0;
  for (auto& [p, c] : terms_)
    for (auto [i, e] : p)
      if (i == index) d = std::max(d, e);
  return d;
}

int Polynomial::total_degree() const {
  int d = 0;
  for (auto& [p, c] : terms_) {
    int s = 0;
    for (auto [i, e] : p) s += e;
    d = std::max(d, s);
  }
  return d;
}

bool Polynomial::is_multi_affine() const {
  for (auto& [p, c] : terms_)
    for (auto [i, e] : p)
      if (e != 1) return false;
  return true;
}

std::string Polynomial::to_string(const std::vector<std::string>& names) const {
  if (terms_.empty()) return "0";
  std::ostringstream os;
  os.precision(17);
  bool first = true;
  for (auto& [p, c] : terms_) {
    os << (first ? "" : " + ");
    first = false;
    if (singleton(c)) os << c.lower();
    else os << '[' << c.lower() << ", " << c.upper() << ']';
    for (auto [i, e] : p) {
      os << '*' << names.at(i);
      if (e != 1) os << '^' << e;
    }
  }
  return os.str();
}

namespace {

// The arc's side by the angle phi of the box's circle points from the arc's centre: inside
// when |phi| <= half throughout, outside when half < |phi| <= pi throughout.
Side side_of_arc(const Inequality::Arc& a, const Box& box) {
  const Interval &c = box[a.c], &s = box[a.s];
  const Interval x = c * a.cos_centre + s * a.sin_centre, y = s * a.cos_centre - c * a.sin_centre;
  const Interval h = a.half;
  if (x.lower() > 0) {  // phi in (-pi/2, pi/2)
    const Interval phi = rigorous::atan(y / x);
    if (phi.lower() >= -h.lower() && phi.upper() <= h.lower()) return Side::inside;
    if (phi.lower() > h.upper() || phi.upper() < -h.upper()) return Side::outside;
    return Side::boundary;
  }
  if (x.upper() < 0) {  // |phi| = pi - |atan(y / x)|, in (pi/2, pi]
    const Interval phi = rigorous::pi() - boost::numeric::abs(rigorous::atan(y / x));
    if (phi.upper() <= h.lower()) return Side::inside;
    if (phi.lower() > h.upper()) return Side::outside;
  }
  return Side::boundary;
}

}  // namespace

Side side_of(const Inequality& c, const Box& box) {
  const Interval g = c.g.eval(box);
  if (c.strict ? g.upper() < 0 : g.upper() <= 0) return Side::inside;
  if (c.strict ? g.lower() >= 0 : g.lower() > 0) return Side::outside;
  return c.arc && !c.strict ? side_of_arc(*c.arc, box) : Side::boundary;
}

const char* to_string(Side s) {
  switch (s) {
    case Side::inside: return "inside";
    case Side::outside: return "outside";
    case Side::boundary: return "boundary";
  }
  return "?";
}

Box System::domain() const {
  Box b;
  for (auto& v : variables) b.push_back(v.domain);
  return b;
}

bool System::is_multi_affine() const {
  for (auto& e : equations)
    if (!e.is_multi_affine()) return false;
  return true;
}

int System::index_of(const std::string& name) const {
  for (size_t i = 0; i < variables.size(); ++i)
    if (variables[i].name == name) return static_cast<int>(i);
  return -1;
}

std::vector<std::string> System::names() const {
  std::vector<std::string> n;
  for (auto& v : variables) n.push_back(v.name);
  return n;
}

}  // namespace linkbox::model
