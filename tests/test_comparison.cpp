// The comparison behind `shadelab compare`: the pass rule, its defaults, ULPs, NaN, integers
// and their bits, standard errors, and the tolerance rules by array name.
#include "ToleranceRules.h"
#include "ValueComparison.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace
{
using namespace shadelab;

ArrayValues reals(ValueType type, std::vector<double> values, int components = 1)
{
  ArrayValues array;
  array.type = type;
  array.components = components;
  array.reals = std::move(values);
  return array;
}

ArrayValues integers(std::vector<std::int64_t> values)
{
  ArrayValues array;
  array.type = ValueType::Integer;
  array.integers = std::move(values);
  return array;
}

ValueRule defaultRule(ValueType type)
{
  ValueRule rule;
  rule.relative = defaultRelativeTolerance(type);
  return rule;
}

TEST(Comparison, TheDefaultAllowsFourUnitsInTheLastPlaceOfTheType)
{
  EXPECT_EQ(defaultRelativeTolerance(ValueType::Float32), 4 * 0x1.0p-23);
  EXPECT_EQ(defaultRelativeTolerance(ValueType::Float64), 4 * 0x1.0p-52);
  EXPECT_EQ(defaultRelativeTolerance(ValueType::Integer), 0.0);
  // At 1, where one unit in the last place above is 2^-52: 4 of them pass, 5 do not (and with
  // atol 0, a value passes at 0 only if it is 0).
  const double x = 1.0, ulp = 0x1.0p-52;
  const ArrayDifference d = compareArrays(reals(ValueType::Float64, { x, x, 0.0, 0.0 }),
    reals(ValueType::Float64, { x + 4 * ulp, x + 5 * ulp, 0.0, 1e-300 }), defaultRule(ValueType::Float64));
  EXPECT_EQ(d.values, 4u);
  EXPECT_EQ(d.failing, 2u);
  EXPECT_EQ(d.worst, 1u);
  EXPECT_EQ(d.largest, 5 * ulp);
  EXPECT_EQ(d.tuplePasses, (std::vector<unsigned char>{ 1, 0, 1, 0 }));
}

TEST(Comparison, AValuePassesWithinTheLargerOfItsRelativeAndAbsoluteTolerances)
{
  ValueRule rule;
  rule.absolute = 1e-6;
  rule.relative = 1e-3;
  // 0 against 1e-7: within atol. 1 against 1.0005: within rtol (1.0005e-3). 1 against 1.01 and
  // 100 against 100.5: neither.
  const ArrayDifference d = compareArrays(reals(ValueType::Float64, { 0, 1, 1, 100 }),
    reals(ValueType::Float64, { 1e-7, 1.0005, 1.01, 100.5 }), rule);
  EXPECT_EQ(d.failing, 2u);
  EXPECT_EQ(d.worst, 3u);
  EXPECT_DOUBLE_EQ(d.largest, 0.5);
  EXPECT_DOUBLE_EQ(d.sumOfSquares, 1e-14 + 0.0005 * 0.0005 + 0.01 * 0.01 + 0.25);
  EXPECT_DOUBLE_EQ(d.rms(), std::sqrt(d.sumOfSquares / 4));
  EXPECT_DOUBLE_EQ(d.l2(), std::sqrt(d.sumOfSquares));
  // Tuples pass only if every component does.
  const ArrayDifference byTuple = compareArrays(reals(ValueType::Float64, { 0, 1, 1, 100 }, 2),
    reals(ValueType::Float64, { 1e-7, 1.0005, 1.01, 100.5 }, 2), rule);
  EXPECT_EQ(byTuple.tuplePasses, (std::vector<unsigned char>{ 1, 0 }));
}

TEST(Comparison, NanEqualsNanOnlyWhereBothAreNan)
{
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const ArrayDifference d = compareArrays(reals(ValueType::Float32, { nan, nan, 1, inf, inf, -inf }),
    reals(ValueType::Float32, { nan, 1, nan, inf, 1, inf }), defaultRule(ValueType::Float32));
  EXPECT_EQ(d.nanInBoth, 1u);
  EXPECT_EQ(d.nanInOne, 2u);
  EXPECT_EQ(d.failing, 4u); // the two NaNs in one file, inf against 1, -inf against inf
  EXPECT_EQ(d.worst, 1u);   // a NaN against a number is the worst difference there is
  EXPECT_EQ(d.largest, inf);
}

TEST(Comparison, UlpDistanceCountsTheNumbersOfTheTypeBetween)
{
  const float one = 1.0f;
  EXPECT_EQ(ulpDistance(one, std::nextafter(one, 2.0f), ValueType::Float32), 1);
  EXPECT_EQ(ulpDistance(1.0, std::nextafter(1.0, 2.0), ValueType::Float64), 1);
  EXPECT_EQ(ulpDistance(1.0, std::nextafter(1.0, 2.0), ValueType::Float32), 0); // the same float
  EXPECT_EQ(ulpDistance(-0.0, 0.0, ValueType::Float64), 0);
  const float tiny = std::numeric_limits<float>::denorm_min();
  EXPECT_EQ(ulpDistance(-tiny, tiny, ValueType::Float32), 2);
  EXPECT_EQ(ulpDistance(std::nan(""), 1.0, ValueType::Float64), 1ll << 62);
  EXPECT_EQ(ulpDistance(-std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), ValueType::Float64), 1ll << 62);

  ValueRule rule;
  rule.ulps = 2;
  const float x = 3.0f;
  const ArrayDifference d = compareArrays(reals(ValueType::Float32, { x, x, x }),
    reals(ValueType::Float32, { std::nextafter(x, 4.0f), std::nextafter(std::nextafter(x, 4.0f), 4.0f),
      std::nextafter(std::nextafter(std::nextafter(x, 4.0f), 4.0f), 4.0f) }), rule);
  EXPECT_EQ(d.failing, 1u);
  EXPECT_EQ(d.worst, 2u);
}

TEST(Comparison, IntegersMustBeEqualAndTheirDifferingBitsAreCounted)
{
  const ArrayDifference d = compareArrays(integers({ 0, 64, 5, 7, 1ll << 40 }), integers({ 64, 64, 1, 7, 0 }), ValueRule{});
  EXPECT_EQ(d.failing, 3u);
  EXPECT_EQ(d.bitCounts[6], 1u);  // 0 against 64
  EXPECT_EQ(d.bitCounts[2], 1u);  // 5 against 1
  EXPECT_EQ(d.bitCounts[40], 1u); // 2^40 against 0
  EXPECT_EQ(d.bitCounts[0], 0u);
  EXPECT_EQ(d.worst, 4u);
  EXPECT_EQ(d.largest, std::ldexp(1.0, 40));
  // Values of another sign differ in the top bit too.
  const ArrayDifference signs = compareArrays(integers({ -1, 0 }), integers({ 1, std::numeric_limits<std::int64_t>::min() }), ValueRule{});
  EXPECT_EQ(signs.failing, 2u);
  EXPECT_EQ(signs.bitCounts[63], 2u);
  EXPECT_EQ(signs.bitCounts[1], 1u);
  // Large 64-bit values are compared exactly, not as doubles.
  const std::int64_t big = (1ll << 62) + 1;
  EXPECT_EQ(compareArrays(integers({ big }), integers({ big - 1 }), ValueRule{}).failing, 1u);
}

TEST(Comparison, WithStandardErrorsAValueAlsoPassesWithinKOfTheirCombinedError)
{
  ValueRule rule = defaultRule(ValueType::Float64);
  rule.standardErrors = 3;
  // Combined errors: sqrt(0.06^2 + 0.08^2) = 0.1. Gaps 0.05, 0.15, 0.25 and 0.35: within
  // 1, 2, 3 and none; the last fails. A value with no error passes only by the rule.
  const ArrayValues errorsA = reals(ValueType::Float64, { 0.06, 0.06, 0.06, 0.06, 0 });
  const ArrayValues errorsB = reals(ValueType::Float64, { 0.08, 0.08, 0.08, 0.08, 0 });
  const ArrayDifference d = compareArrays(reals(ValueType::Float64, { 1, 1, 1, 1, 1 }),
    reals(ValueType::Float64, { 1.05, 1.15, 1.25, 1.35, 1.01 }), rule, &errorsA, &errorsB);
  EXPECT_EQ(d.withStandardError, 4u);
  EXPECT_EQ(d.withinStandardErrors[0], 1u);
  EXPECT_EQ(d.withinStandardErrors[1], 2u);
  EXPECT_EQ(d.withinStandardErrors[2], 3u);
  EXPECT_EQ(d.failing, 2u); // 1.35, and 1.01 where there is no error
  EXPECT_EQ(d.worst, 3u);
}

TEST(Comparison, ARangeIsTheBaselinesLargestFiniteValueLessItsSmallest)
{
  EXPECT_EQ(reals(ValueType::Float64, { 2, -1, 5, NAN, INFINITY }, 1).range(), 6.0);
  EXPECT_EQ(integers({ 3, 10 }).range(), 7.0);
  EXPECT_EQ(reals(ValueType::Float64, { NAN }).range(), 0.0);
}

TEST(ToleranceRules, TheLastMatchingRuleWins)
{
  PatternRules<double> rules;
  rules.add("*", 1);
  rules.add("*_cos_incidence", 2);
  rules.add("key_*", 3);
  EXPECT_EQ(rules.find("total"), 1.0);
  EXPECT_EQ(rules.find("fill_cos_incidence"), 2.0);
  EXPECT_EQ(rules.find("key_cos_incidence"), 3.0);
  PatternRules<double> none;
  none.add("total", 1);
  EXPECT_FALSE(none.find("totals"));
  EXPECT_TRUE(wildcardMatches("key_[ds]*", "key_specular"));
  EXPECT_FALSE(wildcardMatches("key_[ds]*", "key_visibility"));
}

TEST(ToleranceRules, ARuleIsAPatternAColonAndAValue)
{
  EXPECT_EQ(splitRule("1e-6"), (std::pair<std::string, std::string>{ "*", "1e-6" }));
  EXPECT_EQ(splitRule("total:1e-6"), (std::pair<std::string, std::string>{ "total", "1e-6" }));
  EXPECT_EQ(splitRule("a:b:2"), (std::pair<std::string, std::string>{ "a:b", "2" }));
  const ToleranceValue plain = parseToleranceValue("2.5e-3");
  EXPECT_EQ(plain.value, 2.5e-3);
  EXPECT_FALSE(plain.timesRange);
  const ToleranceValue ranged = parseToleranceValue("1e-3*range");
  EXPECT_TRUE(ranged.timesRange);
  EXPECT_EQ(ranged.of(40.0), 1e-3 * 40.0);
  EXPECT_EQ(parseUlps("4"), 4);
  auto messageOf = [](auto parse)
  {
    try
    {
      parse();
    }
    catch (const std::invalid_argument& error)
    {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(messageOf([] { parseToleranceValue("-1"); }),
    "'-1' is not a tolerance: write a number >= 0 (1e-6), or one times the array's range (1e-3*range)");
  EXPECT_EQ(messageOf([] { parseToleranceValue("1e-3*max"); }),
    "'1e-3*max' is not a tolerance: write a number >= 0 (1e-6), or one times the array's range (1e-3*range)");
  EXPECT_EQ(messageOf([] { parseToleranceValue("*range"); }),
    "'*range' is not a tolerance: write a number >= 0 (1e-6), or one times the array's range (1e-3*range)");
  EXPECT_EQ(messageOf([] { parseUlps("2.5"); }), "'2.5' is not a count of units in the last place: write a whole number >= 0");
}
}
