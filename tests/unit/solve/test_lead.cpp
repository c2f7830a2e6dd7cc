// The race's choice of its leader, on standings made up to isolate each part of the rule.
#include "solve/lead.hpp"

#include <catch2/catch.hpp>

#include <vector>

using namespace linkbox::solve;

TEST_CASE("a challenger is compared with the holder's share after the same work", "[race]") {
  // The holder resolved half the tree in 1000 work, a quarter by 500 (interpolated).
  const Progress holder{{200, 0.1}, {1000, 0.5}};
  CHECK(ahead_of(holder, {500, 0.3}) == Approx(0.05));
  CHECK(ahead_of(holder, {500, 0.2}) == Approx(-0.05));
  CHECK(ahead_of(holder, {100, 0.06}) == Approx(0.01));  // from (0, 0) to the first point
  CHECK(ahead_of(holder, {3000, 0.5}) == Approx(0));     // the last point holds beyond it
  // A challenger with half the holder's share now, at a fifth of its work: behind the holder's
  // share now, ahead of it at equal work, and 2.5 times cheaper: it takes the lead.
  const std::vector<Standing> now{{1000, 0.5}, {200, 0.25}};
  CHECK(cheaper(now[0], now[1]));
  CHECK(choose_lead(0, now, holder) == 1);
}

TEST_CASE("the lead passes only 2x cheaper and not behind, to the one furthest ahead", "[race]") {
  const Progress holder{{1000, 0.2}, {9000, 0.2}};  // stuck on a hard part
  const Standing held{9000, 0.2};
  SECTION("behind at equal work, however cheap its projection") {
    CHECK(choose_lead(0, {held, {1000, 0.19}}, holder) == 0);
  }
  SECTION("level and 2x cheaper: it may take the lead") { CHECK(choose_lead(0, {held, {1500, 0.2}}, holder) == 1); }
  SECTION("ahead but not 2x cheaper") { CHECK(choose_lead(0, {held, {8000, 0.3}}, holder) == 0); }
  SECTION("of two that qualify, the one further ahead, in either order") {
    const Standing level{1500, 0.2001}, ahead{4000, 0.25};
    CHECK(choose_lead(0, {held, level, ahead}, holder) == 2);
    CHECK(choose_lead(0, {held, ahead, level}, holder) == 1);
    CHECK(choose_lead(2, {level, ahead, held}, holder) == 1);
  }
}

TEST_CASE("a candidate with no work counted never takes the lead", "[race]") {
  // Work 0 and no tree would otherwise project to 0 work, level with a holder that has
  // resolved nothing either.
  const Progress holder{{500, 0.0}};
  CHECK(choose_lead(0, {{500, 0.0}, {0, 0.0}}, holder) == 0);
  CHECK(choose_lead(0, {{500, 0.0}, {0, 0.0}, {600, 0.5}}, holder) == 2);
}

TEST_CASE("below a hundredth of the tree on both sides, the lead stays", "[race]") {
  // SjirkBoon's second choice: the challenger is ahead at equal work and projected 2.8 times
  // cheaper, on shares below 0.001 (papers/decisions/solve-driver.md).
  const Progress holder{{500, 0.000244}, {8500, 0.000901}};
  const Standing held{8500, 0.000901};
  const Standing challenger{1660, 0.000494};
  CHECK(ahead_of(holder, challenger) > 0);
  CHECK(cheaper(held, challenger));
  CHECK(choose_lead(0, {held, challenger}, holder) == 0);
  // The same standings scaled up past the threshold: it takes the lead.
  const Progress scaled{{500, 0.0244}, {8500, 0.0901}};
  CHECK(choose_lead(0, {{8500, 0.0901}, {1660, 0.0494}}, scaled) == 1);
}
