// HC4 must never remove a root: random polynomial systems (squares, products, interval
// coefficients) with planted roots, some on faces.
#include "prune/acid.hpp"
#include "prune/hc4.hpp"

#include <catch2/catch.hpp>

#include <random>

using namespace linkbox;
using model::Polynomial;

namespace {

// Random systems with a planted root (some on a face of the box), powers up to max_power.
struct Planted {
  Box box;
  std::vector<double> root;
  std::vector<Polynomial> eqs;
};

Planted planted(std::mt19937& rng, int c, int max_power) {
  std::uniform_real_distribution<double> u(-1, 1), w(1e-9, 3);
  const int n = 1 + c % 4;
  Planted p{Box(n), std::vector<double>(n), {}};
  for (int i = 0; i < n; ++i) {
    double lo = u(rng), width = w(rng);
    p.box[i] = Interval(lo, lo + width);
    p.root[i] = rng() % 4 == 0 ? p.box[i].lower() : lo + width * std::uniform_real_distribution<double>(0, 1)(rng);
    p.root[i] = std::min(p.root[i], p.box[i].upper());
  }
  Box at;
  for (double r : p.root) at.push_back(Interval(r));
  for (int e = 0; e < 1 + c % 3; ++e) {
    Polynomial q;
    for (int t = 0; t < 4; ++t) {
      Polynomial m = Polynomial::constant(Interval(u(rng)));
      for (int i = 0; i < n; ++i)
        if (rng() % 2) m = m * Polynomial::variable(i).pow(1 + static_cast<int>(rng() % max_power));
      q += m;
    }
    p.eqs.push_back(q - Polynomial::constant(q.eval(at)));
  }
  return p;
}

}  // namespace

TEST_CASE("hc4 and acid never remove a planted root, powers up to 5", "[hc4][acid]") {
  std::mt19937 rng(7);
  int shrunk = 0, acid_shrunk = 0;
  for (int c = 0; c < 1500; ++c) {
    const Planted p = planted(rng, c, 5);
    std::vector<int> dims(p.box.size());
    for (size_t i = 0; i < dims.size(); ++i) dims[i] = static_cast<int>(i);
    prune::Hc4 h(p.eqs);
    prune::Acid acid(std::make_unique<prune::Hc4>(p.eqs), dims);
    Box b = p.box, a = p.box;
    for (int pass = 0; pass < 4; ++pass) {
      const auto o = h.contract(b);
      REQUIRE(o != prune::Outcome::empty);
      shrunk += o == prune::Outcome::shrunk;
      const auto oa = acid.contract(a);
      REQUIRE(oa != prune::Outcome::empty);
      acid_shrunk += oa == prune::Outcome::shrunk;
      for (size_t i = 0; i < p.root.size(); ++i) {
        REQUIRE(contains(b[i], p.root[i]));
        REQUIRE(contains(a[i], p.root[i]));
      }
    }
  }
  CHECK(shrunk > 100);
  CHECK(acid_shrunk > shrunk);  // shaving contracts where one propagation pass cannot
}

TEST_CASE("hc4 projects odd and even powers above 2 onto their real roots", "[hc4]") {
  const Polynomial x = Polynomial::variable(0);
  prune::Hc4 cube({x.pow(3) + Polynomial::constant(Interval(8.0))});  // x = -2
  Box b{Interval(-10, 10)};
  REQUIRE(cube.contract(b) == prune::Outcome::shrunk);
  CHECK(contains(b[0], -2.0));
  CHECK(width(b[0]) < 1e-12);
  prune::Hc4 fourth({x.pow(4) - Polynomial::constant(Interval(16.0))});  // x = +-2
  Box c{Interval(-1, 10)};
  REQUIRE(fourth.contract(c) == prune::Outcome::shrunk);
  CHECK(contains(c[0], 2.0));
  CHECK(width(c[0]) < 1e-12);
  Box d{Interval(-1.5, 1.5)};
  CHECK(fourth.contract(d) == prune::Outcome::empty);
  Box e{Interval(-10, 10)};  // both roots: only their hull
  REQUIRE(fourth.contract(e) == prune::Outcome::shrunk);
  CHECK(contains(e[0], -2.0));
  CHECK(contains(e[0], 2.0));
  CHECK(e[0].upper() < 2 + 1e-12);
}

TEST_CASE("acid shaves what one propagation pass cannot see", "[acid]") {
  // x + y = 0 and x - y = 0 in [-1, 3]^2: one HC4 pass keeps [-1, 1] for both, while shaving
  // x's slices proves all but the one holding 0 empty.
  const Polynomial x = Polynomial::variable(0), y = Polynomial::variable(1);
  const std::vector<Polynomial> eqs{x + y, x - y};
  prune::Acid acid(std::make_unique<prune::Hc4>(eqs), {0, 1});
  Box b{Interval(-1, 3), Interval(-1, 3)};
  prune::Hc4 h(eqs);
  Box once = b;
  h.contract(once);
  REQUIRE(acid.contract(b) == prune::Outcome::shrunk);
  CHECK(contains(b[0], 0.0));
  CHECK(contains(b[1], 0.0));
  CHECK(width(b[0]) < width(once[0]));
  Box none{Interval(0.5, 3), Interval(-1, 3)};
  CHECK(acid.contract(none) == prune::Outcome::empty);
}

TEST_CASE("hc4 never removes a planted root", "[hc4]") {
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(-1, 1), w(1e-9, 3);
  int emptied = 0, shrunk = 0;
  for (int c = 0; c < 2000; ++c) {
    const int n = 1 + c % 4;
    Box box(n);
    std::vector<double> root(n);
    for (int i = 0; i < n; ++i) {
      double lo = u(rng), width = w(rng);
      box[i] = Interval(lo, lo + width);
      root[i] = rng() % 4 == 0 ? box[i].lower() : lo + width * std::uniform_real_distribution<double>(0, 1)(rng);
      root[i] = std::min(root[i], box[i].upper());
    }
    Box at;
    for (double r : root) at.push_back(Interval(r));
    std::vector<Polynomial> eqs;
    for (int e = 0; e < 1 + c % 3; ++e) {
      Polynomial p;
      for (int t = 0; t < 4; ++t) {
        Polynomial m = Polynomial::constant(Interval(u(rng)));
        for (int i = 0; i < n; ++i)
          if (rng() % 2) m = m * Polynomial::variable(i).pow(1 + rng() % 2);
        p += m;
      }
      eqs.push_back(p - Polynomial::constant(p.eval(at)));
    }
    prune::Hc4 h(eqs);
    Box b = box;
    for (int pass = 0; pass < 4; ++pass) {
      auto o = h.contract(b);
      if (o == prune::Outcome::empty) {
        ++emptied;
        break;
      }
      shrunk += o == prune::Outcome::shrunk;
      for (int i = 0; i < n; ++i) REQUIRE(contains(b[i], root[i]));
    }
  }
  CHECK(emptied == 0);
  CHECK(shrunk > 100);  // it does contract
}

TEST_CASE("hc4 proves a box empty and narrows x^2 = 4 to its two roots' hull", "[hc4]") {
  Polynomial f = Polynomial::variable(0).pow(2) - Polynomial::constant(Interval(4.0));
  prune::Hc4 h({f});
  Box b{Interval(-1, 1)};
  CHECK(h.contract(b) == prune::Outcome::empty);
  Box c{Interval(0, 10)};
  REQUIRE(h.contract(c) == prune::Outcome::shrunk);
  CHECK(contains(c[0], 2.0));
  CHECK(width(c[0]) < 1e-12);
}

TEST_CASE("hc4 proves nothing from a sum with NaN bounds", "[hc4]") {
  // x - y at x = y = +inf sums inf - inf: both bounds are NaN, which is no proof of emptiness.
  const Polynomial f = Polynomial::variable(0) - Polynomial::variable(1);
  prune::Hc4 h({f});
  Box b{Interval(kInf, kInf), Interval(kInf, kInf)};
  CHECK(h.contract(b) != prune::Outcome::empty);
}
