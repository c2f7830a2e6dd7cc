#include "interval/rigorous.hpp"

#include <mpfi.h>

#include <stdexcept>
#include <string>

namespace linkbox::rigorous {

namespace {

constexpr mpfr_prec_t kPrec = 128;

// RAII holder of one MPFI value.
struct Mp {
  mpfi_t v;
  Mp() { mpfi_init2(v, kPrec); }
  explicit Mp(const Interval& x) : Mp() { mpfi_interv_d(v, x.lower(), x.upper()); }
  ~Mp() { mpfi_clear(v); }
  Mp(const Mp&) = delete;
  Mp& operator=(const Mp&) = delete;
  Interval get() const {
    double lo = mpfr_get_d(&v->left, MPFR_RNDD), hi = mpfr_get_d(&v->right, MPFR_RNDU);
    return Interval(lo, hi);
  }
};

template <class F>
Interval apply(const Interval& x, F f) {
  Mp a(x), r;
  f(r.v, a.v);
  if (mpfi_nan_p(r.v)) throw std::domain_error("argument out of the function's domain");
  return r.get();
}

}  // namespace

Interval decimal(std::string_view text) {
  std::string s(text);
  Mp r;
  if (s.empty() || mpfi_set_str(r.v, s.c_str(), 10) != 0 || mpfi_nan_p(r.v))
    throw std::invalid_argument("not a decimal number: '" + s + "'");
  return r.get();
}

Interval pi() {
  Mp r;
  mpfi_const_pi(r.v);
  return r.get();
}

Interval sin(const Interval& x) { return apply(x, mpfi_sin); }
Interval cos(const Interval& x) { return apply(x, mpfi_cos); }
Interval tan(const Interval& x) {
  Interval r = apply(x, mpfi_tan);
  if (!is_finite(r)) throw std::domain_error("tan: argument meets a pole");
  return r;
}
Interval asin(const Interval& x) {
  if (x.lower() < -1 || x.upper() > 1) throw std::domain_error("asin: argument outside [-1, 1]");
  return apply(x, mpfi_asin);
}
Interval acos(const Interval& x) {
  if (x.lower() < -1 || x.upper() > 1) throw std::domain_error("acos: argument outside [-1, 1]");
  return apply(x, mpfi_acos);
}
Interval atan(const Interval& x) { return apply(x, mpfi_atan); }
void release_thread_caches() { mpfr_free_cache2(MPFR_FREE_LOCAL_CACHE); }

Interval atan2(const Interval& y, const Interval& x) {
  Mp a(y), b(x), r;
  mpfi_atan2(r.v, a.v, b.v);
  if (mpfi_nan_p(r.v)) throw std::domain_error("atan2: not a number");
  return r.get();
}
Interval sqrt(const Interval& x) {
  if (x.lower() < 0) throw std::domain_error("sqrt: negative argument");
  return apply(x, mpfi_sqrt);
}
Interval exp(const Interval& x) { return apply(x, mpfi_exp); }
Interval log(const Interval& x) {
  if (x.lower() <= 0) throw std::domain_error("log: argument not positive");
  return apply(x, mpfi_log);
}

Interval sinh(const Interval& x) { return apply(x, mpfi_sinh); }
Interval cosh(const Interval& x) { return apply(x, mpfi_cosh); }
Interval tanh(const Interval& x) { return apply(x, mpfi_tanh); }
Interval asinh(const Interval& x) { return apply(x, mpfi_asinh); }
Interval acosh(const Interval& x) {
  if (x.lower() < 1) throw std::domain_error("acosh: argument below 1");
  return apply(x, mpfi_acosh);
}
Interval atanh(const Interval& x) {
  if (x.lower() < -1 || x.upper() > 1) throw std::domain_error("atanh: argument outside [-1, 1]");
  return apply(x, mpfi_atanh);
}

Interval angle_from_half_tangent(const Interval& t, int half_turns) {
  Mp a(t), r, p;
  mpfi_atan(r.v, a.v);
  mpfi_mul_si(r.v, r.v, 2);
  mpfi_const_pi(p.v);
  mpfi_mul_si(p.v, p.v, half_turns);
  mpfi_add(r.v, r.v, p.v);
  return r.get();
}

}  // namespace linkbox::rigorous
