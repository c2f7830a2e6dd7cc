// HC4 must never remove a root: random polynomial systems (squares, products, interval
// coefficients) with planted roots, some on faces.
#include "prune/hc4.hpp"

#include <catch2/catch.hpp>

#include <random>

using namespace linkbox;
using model::Polynomial;

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
