#pragma once
// Internal to model::lift (lifting.hpp), which runs a Lifter: lifter_angles.cpp finds the
// angles, their units, the expansions of sin and cos into their cos and sin, and their
// charts; lifter.cpp builds the lifted system from them; lifter_divisors.cpp clears the
// divisors that may be 0.
#include "model/lifting.hpp"

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace linkbox::model::detail {

std::string format(double x);  // "%.6g"
Polynomial one();
// The k with x in [k*period + shift, (k+1)*period + shift] (closed), if one exists.
bool within_one(const Interval& x, const Interval& shift, const Interval& period, long& k);

// cos and sin of an angle as one complex value: products are angle sums.
struct Complex {
  Polynomial re, im;
  friend Complex operator*(const Complex& a, const Complex& b) {
    return {a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re};
  }
};

class Lifter {
 public:
  explicit Lifter(const RawSystem& raw) : raw_(raw), n_(static_cast<int>(raw.variables.size())) {}

  System run();

 private:
  using Function = Application::Function;
  using Chart = Lifting::Chart;

  struct AngleUse {
    Lifting::Angle angle;
    std::vector<int> applications;  // trig applications it occurs in
  };

  [[noreturn]] void fail_variable(int v, const std::string& m) const { throw LiftError(m, v, -1); }
  [[noreturn]] void fail_application(int k, const std::string& m) const { throw LiftError(m, -1, k); }
  const std::string& name(int v) const { return raw_.variables[v].name; }
  const std::string& text(int k) const { return raw_.applications[k].text; }
  Box raw_domain() const;
  std::string pole_message(int k, const Interval& range) const;

  // The angles (lifter_angles.cpp), in this order.
  void find_linked();
  bool is_angle_use(int k) const;  // application k is sin, cos or tan of angles
  void find_angles();
  void choose_unit(size_t j);
  void expand();
  void choose_chart(size_t j);
  static Interval coefficient(const Polynomial& arg, int v);
  static long multiple_of(const Interval& a, const Interval& unit);
  // The multiple of angle variable v's unit that coefficient a is (choose_unit made sure).
  long multiple(int v, const Interval& a) const { return multiple_of(a, angles_[angle_of_[v]].angle.unit); }

  // The lifted system (lifter.cpp): build runs the steps below it.
  void build();
  void add_declared_unknowns();
  void add_angle_unknowns(int j);
  void add_application_unknowns();
  bool multiplied(int k) const;
  void add_trig_unknown(int k, const Polynomial& expansion);
  void add_tan_unknown(int k, const Polynomial& x);
  void add_sqrt_unknown(int k, const Polynomial& x);
  void add_reciprocal_unknown(int k, const Polynomial& x);
  void add_base_unknown(int k, const Polynomial& x);
  void add_atan2_unknown(int k, int t);
  void add_inequality(const Polynomial& g, bool strict, const std::string& name);
  Polynomial substituted(const Polynomial& p, int application, int equation = -1, int inequality = -1) const;
  // The divisors that may be 0 (lifter_divisors.cpp).
  void find_cleared();
  void add_cleared_divisor(int k);
  Polynomial clear(Polynomial p, bool even, int application) const;
  void add_link_unknown(int k, Elementary f, int y);
  int argument_unknown(int k, Elementary f, const Interval& range);
  void add_typed_constraints();
  void add_angle_constraints();
  std::string add_circle(const Lifting::Angle& a);
  void add_variable(const std::string& name, const Interval& domain, Lifting::Source source);
  std::string angle_name(const Lifting::Angle& a, const char* f) const;
  Interval argument_range(int k) const;
  Box values_before(int k) const;  // the declared domain and the applications before k

  const RawSystem& raw_;
  const int n_;
  std::vector<int> angle_of_;  // per declared variable: its angle, or -1
  std::vector<bool> linked_;   // per application: a sin or cos that is a link
  std::vector<AngleUse> angles_;
  std::vector<Complex> expansions_;  // per application: cos + i sin of its argument (trig only)
  // While building: the lifted polynomial of cos(u_j), sin(u_j) (symbol 2j, 2j + 1), of each
  // declared variable and application (image n + k), which applications have their unknown,
  // and the equations that define the applications' unknowns, each with its name.
  std::vector<Polynomial> symbol_;
  std::vector<Polynomial> image_;
  std::vector<bool> done_;
  std::vector<std::pair<Polynomial, std::string>> definitions_;
  // Per application: a reciprocal whose divisor is cleared (no unknown), and that divisor
  // over the lifted unknowns and the earlier cleared quotients.
  std::vector<bool> cleared_;
  std::vector<bool> expanded_;  // per application: a base that holds a cleared divisor
  std::vector<Polynomial> divisors_;
  System out_;
  Lifting* lifting_ = nullptr;
};

}  // namespace linkbox::model::detail
