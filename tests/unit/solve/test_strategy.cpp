// The --prune value: parsed once, written back as the same canonical text, asked what it uses.
#include "solve/strategy.hpp"

#include <catch2/catch.hpp>

#include <stdexcept>
#include <string>

using namespace linkbox;
using solve::ContractorKind;
using solve::Strategy;

TEST_CASE("a strategy's text is canonical: parsing it gives the same strategy", "[strategies]") {
  for (const char* text : {"auto", "hc4,newton", "hc4,newton/lp", "trapezoid", "hc4/newton", "hc4//lp", "/hc4",
                           "acid,newton,lp"}) {
    INFO(text);
    const Strategy s = Strategy::parse(text);
    CHECK(s.text() == text);
    CHECK(Strategy::parse(s.text()) == s);
  }
  CHECK(Strategy::parse(" hc4 , newton/ lp,").text() == "hc4,newton/lp");  // spaces and empty names dropped
  CHECK(Strategy::parse("auto").is_auto());
  CHECK(Strategy::automatic() == Strategy::parse(" auto "));
  CHECK(Strategy().empty());
  CHECK(Strategy().text().empty());
}

TEST_CASE("a strategy says which contractors it uses and in which stages", "[strategies]") {
  const Strategy s = Strategy::parse("hc4,newton/lp");
  CHECK(s.uses(ContractorKind::newton));
  CHECK(s.uses(ContractorKind::lp));
  CHECK_FALSE(s.uses(ContractorKind::trapezoid));
  REQUIRE(s.stages().size() == 2);
  CHECK(s.stages()[0] == Strategy::Stage{ContractorKind::hc4, ContractorKind::newton});
  CHECK(s.stages()[1] == Strategy::Stage{ContractorKind::lp});
  CHECK_FALSE(Strategy::automatic().uses(ContractorKind::newton));  // auto names no contractor itself
}

TEST_CASE("a bad strategy is refused with the names that are known", "[strategies]") {
  try {
    Strategy::parse("hc4,hc5");
    FAIL("hc5 accepted");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()) == "unknown pruning strategy 'hc5' (known: auto, " + solve::contractor_names() + ")");
  }
  CHECK(solve::contractor_names() == "trapezoid, lp, hc4, acid, newton, taylor");
  CHECK_THROWS_WITH(Strategy::parse("/"), "no pruning strategy given");
  CHECK_THROWS_WITH(Strategy::parse(""), "no pruning strategy given");
  CHECK_THROWS_AS(Strategy::parse("auto,lp"), std::invalid_argument);
  CHECK_THROWS_AS(Strategy::parse("auto/"), std::invalid_argument);
}
