// The comparison behind `shadelab compare`: the pass rule, its defaults, ULPs, NaN, integers
// and their bits, standard errors and the noise checks of Monte Carlo arrays, and the
// tolerance rules by array name.
#include "NoiseTest.h"
#include "ToleranceRules.h"
#include "ValueComparison.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <random>

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
  const ArrayDifference d = compareArrays(
    reals(ValueType::Float64, { 0, 1, 1, 100 }), reals(ValueType::Float64, { 1e-7, 1.0005, 1.01, 100.5 }), rule);
  EXPECT_EQ(d.failing, 2u);
  EXPECT_EQ(d.worst, 3u);
  EXPECT_DOUBLE_EQ(d.largest, 0.5);
  EXPECT_DOUBLE_EQ(d.sumOfSquares, 1e-14 + 0.0005 * 0.0005 + 0.01 * 0.01 + 0.25);
  EXPECT_DOUBLE_EQ(d.rms(), std::sqrt(d.sumOfSquares / 4));
  EXPECT_DOUBLE_EQ(d.l2(), std::sqrt(d.sumOfSquares));
  // Tuples pass only if every component does.
  const ArrayDifference byTuple = compareArrays(
    reals(ValueType::Float64, { 0, 1, 1, 100 }, 2), reals(ValueType::Float64, { 1e-7, 1.0005, 1.01, 100.5 }, 2), rule);
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
  EXPECT_EQ(ulpDistance(-std::numeric_limits<double>::max(), std::numeric_limits<double>::max(), ValueType::Float64),
    1ll << 62);

  ValueRule rule;
  rule.ulps = 2;
  const float x = 3.0f;
  const ArrayDifference d = compareArrays(reals(ValueType::Float32, { x, x, x }),
    reals(ValueType::Float32,
      { std::nextafter(x, 4.0f), std::nextafter(std::nextafter(x, 4.0f), 4.0f),
        std::nextafter(std::nextafter(std::nextafter(x, 4.0f), 4.0f), 4.0f) }),
    rule);
  EXPECT_EQ(d.failing, 1u);
  EXPECT_EQ(d.worst, 2u);
}

TEST(Comparison, IntegersMustBeEqualAndTheirDifferingBitsAreCounted)
{
  const ArrayDifference d =
    compareArrays(integers({ 0, 64, 5, 7, 1ll << 40 }), integers({ 64, 64, 1, 7, 0 }), ValueRule{});
  EXPECT_EQ(d.failing, 3u);
  EXPECT_EQ(d.bitCounts[6], 1u);  // 0 against 64
  EXPECT_EQ(d.bitCounts[2], 1u);  // 5 against 1
  EXPECT_EQ(d.bitCounts[40], 1u); // 2^40 against 0
  EXPECT_EQ(d.bitCounts[0], 0u);
  EXPECT_EQ(d.worst, 4u);
  EXPECT_EQ(d.largest, std::ldexp(1.0, 40));
  // Values of another sign differ in the top bit too.
  const ArrayDifference signs =
    compareArrays(integers({ -1, 0 }), integers({ 1, std::numeric_limits<std::int64_t>::min() }), ValueRule{});
  EXPECT_EQ(signs.failing, 2u);
  EXPECT_EQ(signs.bitCounts[63], 2u);
  EXPECT_EQ(signs.bitCounts[1], 1u);
  // Large 64-bit values are compared exactly, not as doubles.
  const std::int64_t big = (1ll << 62) + 1;
  EXPECT_EQ(compareArrays(integers({ big }), integers({ big - 1 }), ValueRule{}).failing, 1u);
}

TEST(Comparison, WithStandardErrorsTheValuesOutsideKAreCountedAndTheExactOnesJudgedByTheRule)
{
  ValueRule rule = defaultRule(ValueType::Float64);
  rule.standardErrors = 3;
  // Combined errors: sqrt(0.06^2 + 0.08^2) = 0.1. Gaps 0.05, -0.15, 0.35 and -0.35: z = 0.5,
  // -1.5, 3.5 and -3.5, two of them outside 3. The last two values have no error: 1 against
  // 1.01 fails the rule, 2 against 2 passes it.
  const ArrayValues errorsA = reals(ValueType::Float64, { 0.06, 0.06, 0.06, 0.06, 0, 0 });
  const ArrayValues errorsB = reals(ValueType::Float64, { 0.08, 0.08, 0.08, 0.08, 0, 0 });
  const ArrayDifference d = compareArrays(reals(ValueType::Float64, { 1, 1, 1, 1, 1, 2 }),
    reals(ValueType::Float64, { 1.05, 0.85, 1.35, 0.65, 1.01, 2 }), rule, &errorsA, &errorsB);
  EXPECT_EQ(d.withStandardError, 4u);
  EXPECT_EQ(d.withinStandardErrors[0], 1u);
  EXPECT_EQ(d.withinStandardErrors[1], 2u);
  EXPECT_EQ(d.withinStandardErrors[2], 2u);
  EXPECT_EQ(d.exactValues, 2u);
  EXPECT_EQ(d.failing, 1u); // 1.01 where there is no error; the noisy values are judged together
  EXPECT_EQ(d.worst, 4u);
  EXPECT_EQ(d.tuplePasses, (std::vector<unsigned char>{ 1, 1, 0, 0, 0, 1 }));
  ASSERT_EQ(d.noise.size(), 1u);
  const NoiseCheck& noise = d.noise[0];
  EXPECT_EQ(noise.values, 4u);
  EXPECT_EQ(noise.outside, 2u);
  const double p = std::erfc(3 / std::sqrt(2.0)); // 2 P(Z > 3)
  EXPECT_DOUBLE_EQ(noise.expected, 4 * p);
  // P(X > 1) = 1 - (1 - p)^4 - 4 p (1 - p)^3 = 4.4e-5 is within each check's 0.0005, P(X > 0)
  // = 0.011 is not: 1 value outside is allowed, 2 are not.
  EXPECT_EQ(noise.allowed, 1u);
  EXPECT_FALSE(noise.countPasses());
  // The mean difference (0.05 - 0.15 + 0.35 - 0.35) / 4, its standard error sqrt(4 * 0.1^2) / 4.
  EXPECT_NEAR(noise.meanDifference, -0.025, 1e-15);
  EXPECT_NEAR(noise.meanDifferenceError, 0.05, 1e-15);
  EXPECT_DOUBLE_EQ(noise.meanDifferenceLimit, normalUpperQuantile(0.001 / 4) * noise.meanDifferenceError);
  EXPECT_TRUE(noise.biasPasses());
  EXPECT_FALSE(d.passes());
  // Without the failing exact value, and with k = 4 (no value outside), the array passes.
  rule.standardErrors = 4;
  const ArrayValues fourA = reals(ValueType::Float64, { 0.06, 0.06, 0.06, 0.06 });
  const ArrayValues fourB = reals(ValueType::Float64, { 0.08, 0.08, 0.08, 0.08 });
  const ArrayDifference four = compareArrays(reals(ValueType::Float64, { 1, 1, 1, 1 }),
    reals(ValueType::Float64, { 1.05, 0.85, 1.35, 0.65 }), rule, &fourA, &fourB);
  EXPECT_TRUE(four.passes());
}

TEST(Comparison, WithStandardErrorsAValueWithinTheRuleAgrees)
{
  // float32 values 1 ULP apart under a standard error of 1e-12: their rounding, not noise.
  ValueRule rule = defaultRule(ValueType::Float32);
  rule.standardErrors = 3;
  const ArrayValues errors = reals(ValueType::Float32, { 1e-12, 1e-12 });
  const ArrayDifference d = compareArrays(reals(ValueType::Float32, { 0.5, 0.5 }),
    reals(ValueType::Float32, { std::nextafter(0.5f, 1.0f), 0.5 }), rule, &errors, &errors);
  ASSERT_EQ(d.noise.size(), 1u);
  EXPECT_EQ(d.noise[0].values, 2u);
  EXPECT_EQ(d.noise[0].outside, 0u);
  EXPECT_EQ(d.noise[0].meanDifference, 0.0);
  EXPECT_TRUE(d.passes());
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
  EXPECT_EQ(
    messageOf([] { parseUlps("2.5"); }), "'2.5' is not a count of units in the last place: write a whole number >= 0");
}

TEST(NoiseTest, TheNormalTailAndItsQuantileAgreeWithPublishedValues)
{
  // To 1e-15 of the value: erfc's own accuracy.
  EXPECT_NEAR(normalUpperTail(3), 0.0013498980316300946, 1e-15 * 0.0013498980316300946);
  EXPECT_NEAR(normalUpperTail(1), 0.15865525393145705, 1e-15 * 0.15865525393145705);
  EXPECT_EQ(normalUpperTail(0), 0.5);
  EXPECT_NEAR(normalUpperTail(-2) + normalUpperTail(2), 1.0, 1e-15);
  EXPECT_NEAR(normalUpperQuantile(0.025), 1.959963984540054, 1e-13);
  EXPECT_NEAR(normalUpperQuantile(0.0005), 3.2905267314918948, 1e-13);
  EXPECT_NEAR(normalUpperQuantile(0.00025), 3.4807564043462128, 1e-13);
  EXPECT_NEAR(normalUpperQuantile(0.5), 0.0, 1e-15);
  for (const double z : { 0.5, 2.0, 5.0, 10.0, 30.0 })
  {
    EXPECT_NEAR(normalUpperQuantile(normalUpperTail(z)), z, 1e-13 * z) << z;
  }
}

/// The binomial quantile by another method: the pmf summed upwards from P(X = 0) = (1 - p)^n
/// by the ratio P(X = k + 1) / P(X = k) = (n - k) p / ((k + 1) (1 - p)), in long double.
std::size_t quantileByRecurrence(std::size_t n, long double p, long double tail)
{
  long double term = std::pow(1 - p, static_cast<long double>(n)), atMost = term;
  std::size_t c = 0;
  while (1 - atMost > tail && c < n)
  {
    term *= static_cast<long double>(n - c) * p / (static_cast<long double>(c + 1) * (1 - p));
    ++c;
    atMost += term;
  }
  return c;
}

TEST(NoiseTest, TheBinomialQuantileAgreesWithThePmfSummedByItsRecurrence)
{
  const double threeSigma = 2 * normalUpperTail(3); // 0.0027
  EXPECT_NEAR(6002 * threeSigma, 16.2042, 1e-4);
  EXPECT_EQ(binomialUpperQuantile(6002, threeSigma, 0.0005), 31u);
  for (const std::size_t n : std::vector<std::size_t>{ 1, 4, 37, 6002 })
  {
    for (const double p : { threeSigma, 0.01, 0.3, 0.5 })
    {
      for (const double tail : { 0.1, 0.0005, 1e-6, 1e-12 })
      {
        EXPECT_EQ(binomialUpperQuantile(n, p, tail), quantileByRecurrence(n, p, tail)) << n << " " << p << " " << tail;
      }
    }
  }
  for (const double tail : { 0.0005, 1e-12 })
  {
    EXPECT_EQ(binomialUpperQuantile(1000000, threeSigma, tail), quantileByRecurrence(1000000, threeSigma, tail));
  }
  // Closed forms: Binomial(2, 1/2) exceeds 0 with 3/4, 1 with 1/4, 2 never.
  EXPECT_EQ(binomialUpperQuantile(2, 0.5, 0.8), 0u);
  EXPECT_EQ(binomialUpperQuantile(2, 0.5, 0.3), 1u);
  EXPECT_EQ(binomialUpperQuantile(2, 0.5, 0.2), 2u);
  EXPECT_EQ(binomialUpperQuantile(100, 0.0, 1e-12), 0u);
  EXPECT_EQ(binomialUpperQuantile(100, 1.0, 1e-12), 100u);
  EXPECT_NEAR(std::exp(binomialLogProbability(3, 0.5, 1)), 3.0 / 8, 1e-15);
  double total = 0;
  for (std::size_t k = 0; k <= 50; ++k)
  {
    total += std::exp(binomialLogProbability(50, 0.3, k));
  }
  EXPECT_NEAR(total, 1.0, 1e-13);
}

TEST(NoiseTest, EachCheckTakesItsShareOfTheSignificance)
{
  EXPECT_EQ(significancePerCheck(0.001, 1), 0.0005);
  EXPECT_EQ(significancePerCheck(0.003, 3), 0.0005);
  // 6002 values of standard error 1: the mean difference has standard error 1 / sqrt(6002).
  NoiseTally tally;
  tally.values = 6002;
  tally.outside = 31;
  tally.sumOfDifferences = 0.0449 * 6002;
  tally.sumOfVariances = 6002;
  const NoiseCheck check = checkNoise(tally, 3, 0.0005);
  EXPECT_NEAR(check.expected, 16.2042, 1e-4);
  EXPECT_EQ(check.allowed, 31u);
  EXPECT_NEAR(check.meanDifferenceError, 1 / std::sqrt(6002.0), 1e-15);
  EXPECT_NEAR(check.meanDifferenceLimit, 3.4807564043462128 / std::sqrt(6002.0), 1e-15);
  EXPECT_TRUE(check.passes()); // 31 outside, a mean difference of 0.0449 within 0.04493
  tally.outside = 32;
  EXPECT_FALSE(checkNoise(tally, 3, 0.0005).countPasses());
  tally.sumOfDifferences = -0.0450 * 6002;
  EXPECT_FALSE(checkNoise(tally, 3, 0.0005).biasPasses());
  EXPECT_TRUE(checkNoise(NoiseTally{}, 3, 0.0005).passes());
}

/// Two Monte Carlo runs of the same values, float32 as shade writes them: the first with 32
/// samples, the second with 256 (standard errors sqrt(8) times smaller), each estimate its
/// true value plus a normal error of its standard error.
struct TwoRuns
{
  ArrayValues a, b, errorsA, errorsB;

  double combinedError(std::size_t i) const { return std::hypot(errorsA.reals[i], errorsB.reals[i]); }
};

TwoRuns twoRuns(std::mt19937_64& random, std::size_t values, int components = 1)
{
  std::uniform_real_distribution<double> truth(0.2, 0.8), spread(0.005, 0.05);
  std::normal_distribution<double> normal;
  TwoRuns runs{ reals(ValueType::Float32, {}, components), reals(ValueType::Float32, {}, components),
    reals(ValueType::Float32, {}, components), reals(ValueType::Float32, {}, components) };
  for (std::size_t i = 0; i < values * static_cast<std::size_t>(components); ++i)
  {
    const double mean = truth(random), errorA = spread(random), errorB = errorA / std::sqrt(8.0);
    runs.a.reals.push_back(static_cast<float>(mean + errorA * normal(random)));
    runs.b.reals.push_back(static_cast<float>(mean + errorB * normal(random)));
    runs.errorsA.reals.push_back(static_cast<float>(errorA));
    runs.errorsB.reals.push_back(static_cast<float>(errorB));
  }
  return runs;
}

ArrayDifference compareRuns(const TwoRuns& runs)
{
  ValueRule rule = defaultRule(ValueType::Float32);
  rule.standardErrors = 3;
  rule.significance = 0.001;
  return compareArrays(runs.a, runs.b, rule, &runs.errorsA, &runs.errorsB);
}

constexpr int trials = 200;
constexpr std::size_t homerVertices = 6002;

TEST(NoiseTest, TwoHonestRunsPassInAtLeast198Of200Trials)
{
  std::mt19937_64 random(44);
  int passed = 0;
  std::size_t fewest = homerVertices, most = 0;
  for (int trial = 0; trial < trials; ++trial)
  {
    const ArrayDifference d = compareRuns(twoRuns(random, homerVertices));
    passed += d.passes() ? 1 : 0;
    fewest = std::min(fewest, d.noise[0].outside);
    most = std::max(most, d.noise[0].outside);
    EXPECT_EQ(d.noise[0].allowed, 31u);
  }
  EXPECT_GE(passed, 198);
  std::cout << "honest runs: " << passed << " of " << trials << " trials pass; " << fewest << " to " << most << " of "
            << homerVertices << " values outside 3 standard errors (16.2 expected, at most 31 allowed)\n";
}

TEST(NoiseTest, FivePercentOfTheValuesShiftedByFourStandardErrorsFailEveryTrial)
{
  // Every 20th value moved by 4 combined standard errors, up and down in turn: the mean
  // difference hardly moves, the count of values outside 3 does.
  std::mt19937_64 random(45);
  int failed = 0;
  std::size_t fewest = homerVertices;
  for (int trial = 0; trial < trials; ++trial)
  {
    TwoRuns runs = twoRuns(random, homerVertices);
    for (std::size_t i = 0; i < homerVertices; i += 20)
    {
      const double sign = i % 40 == 0 ? 1.0 : -1.0;
      runs.b.reals[i] = static_cast<float>(runs.b.reals[i] + sign * 4 * runs.combinedError(i));
    }
    const ArrayDifference d = compareRuns(runs);
    failed += d.noise[0].countPasses() ? 0 : 1;
    fewest = std::min(fewest, d.noise[0].outside);
  }
  EXPECT_EQ(failed, trials);
  std::cout << "5% shifted by 4 standard errors: " << failed << " of " << trials << " trials fail the count; at least "
            << fewest << " values outside 3 standard errors\n";
}

TEST(NoiseTest, ABiasOfATenthOfAStandardErrorEverywhereIsFoundByTheMeanDifference)
{
  // Within 3 standard errors nearly as often as before, but the mean difference is 0.1 of the
  // mean standard error, 7 of its own standard errors (0.1 sqrt(6002) times the mean over the
  // RMS of the errors, 0.9 here), beyond 3.48.
  std::mt19937_64 random(46);
  int failed = 0;
  for (int trial = 0; trial < trials; ++trial)
  {
    TwoRuns runs = twoRuns(random, homerVertices);
    for (std::size_t i = 0; i < homerVertices; ++i)
    {
      runs.b.reals[i] = static_cast<float>(runs.b.reals[i] + 0.1 * runs.combinedError(i));
    }
    failed += compareRuns(runs).noise[0].biasPasses() ? 0 : 1;
  }
  EXPECT_GE(failed, 198);
  std::cout << "a bias of 0.1 standard errors: " << failed << " of " << trials << " trials fail the mean difference\n";
}

TEST(NoiseTest, EachComponentOfAnRgbArrayIsJudgedOnItsOwn)
{
  // Component 1 of every 20th tuple moved by 4 standard errors: that component fails, the
  // others pass; each of the 6 checks at 0.001 / 6.
  std::mt19937_64 random(47);
  TwoRuns runs = twoRuns(random, homerVertices, 3);
  for (std::size_t tuple = 0; tuple < homerVertices; tuple += 20)
  {
    const std::size_t i = 3 * tuple + 1;
    runs.b.reals[i] = static_cast<float>(runs.b.reals[i] + (tuple % 40 == 0 ? 4 : -4) * runs.combinedError(i));
  }
  const ArrayDifference d = compareRuns(runs);
  ASSERT_EQ(d.noise.size(), 3u);
  EXPECT_EQ(d.noise[0].values, homerVertices);
  EXPECT_EQ(d.noise[0].allowed, binomialUpperQuantile(homerVertices, 2 * normalUpperTail(3), 0.001 / 6));
  EXPECT_DOUBLE_EQ(d.noise[0].meanDifferenceLimit, normalUpperQuantile(0.001 / 12) * d.noise[0].meanDifferenceError);
  EXPECT_TRUE(d.noise[0].passes());
  EXPECT_FALSE(d.noise[1].countPasses());
  EXPECT_TRUE(d.noise[2].passes());
  EXPECT_FALSE(d.passes());
}
}
