#include "ValueComparison.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace shadelab
{
double ArrayValues::range() const
{
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (std::size_t i = 0; i < size(); ++i)
  {
    const double v = type == ValueType::Integer ? static_cast<double>(integers[i]) : reals[i];
    if (std::isfinite(v))
    {
      low = std::min(low, v);
      high = std::max(high, v);
    }
  }
  return low <= high ? high - low : 0.0;
}

double defaultRelativeTolerance(ValueType type)
{
  switch (type)
  {
    case ValueType::Float32: return 4.0 * std::numeric_limits<float>::epsilon();
    case ValueType::Float64: return 4.0 * std::numeric_limits<double>::epsilon();
    case ValueType::Integer: break;
  }
  return 0.0;
}

bool ArrayDifference::passes() const
{
  return failing == 0 &&
    std::all_of(noise.begin(), noise.end(), [](const NoiseCheck& check) { return check.passes(); });
}

double ArrayDifference::rms() const
{
  const std::size_t counted = values - nanInBoth - nanInOne;
  return counted > 0 ? std::sqrt(sumOfSquares / static_cast<double>(counted)) : 0.0;
}

double ArrayDifference::l2() const
{
  return std::sqrt(sumOfSquares);
}

namespace
{
/// Bits of a float of the type, ordered as the numbers are (-0 and +0 both at 0).
std::int64_t orderedBits(double x, ValueType type)
{
  if (type == ValueType::Float32)
  {
    const float f = static_cast<float>(x);
    std::int32_t bits;
    std::memcpy(&bits, &f, sizeof bits);
    return bits < 0 ? -static_cast<std::int64_t>(bits & 0x7fffffff) : bits;
  }
  std::int64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  return bits < 0 ? -(bits & 0x7fffffffffffffffll) : bits;
}
}

long long ulpDistance(double a, double b, ValueType type)
{
  constexpr long long far = 1ll << 62;
  if (std::isnan(a) || std::isnan(b))
  {
    return far;
  }
  // Halved first, so that the difference of two 64-bit patterns cannot overflow.
  const std::int64_t x = orderedBits(a, type), y = orderedBits(b, type);
  const std::int64_t half = x / 2 - y / 2;
  if (std::abs(half) >= far / 2)
  {
    return far;
  }
  return std::abs(x - y);
}

namespace
{
/// Counts, per bit, where two integers differ.
void countDifferingBits(std::int64_t x, std::int64_t y, ArrayDifference& difference)
{
  const std::uint64_t bits = static_cast<std::uint64_t>(x) ^ static_cast<std::uint64_t>(y);
  for (std::size_t bit = 0; bit < 64; ++bit)
  {
    difference.bitCounts[bit] += (bits >> bit) & 1u;
  }
}

/// A value of each file, with their standard errors.
struct ValuePair
{
  double a, b, errorA, errorB;
};

enum class NoiseJudgement
{
  NotJudged, // no finite standard error above 0: judged by the rule alone
  Within,
  Outside, // outside the rule's count of standard errors
};

/// Where the pair's combined standard error is finite and above 0, the difference counted
/// against it (within 1, 2 and 3 of them, and into its component's tally): a value within the
/// rule agrees (the rounding of a float under a tiny standard error is no noise), so it is not
/// outside and its difference counts as 0.
NoiseJudgement judgeByStandardErrors(const ValuePair& pair, double gap, bool passesRule, const ValueRule& rule,
  NoiseTally& tally, ArrayDifference& difference)
{
  const double combined = std::sqrt(pair.errorA * pair.errorA + pair.errorB * pair.errorB);
  if (!(combined > 0 && std::isfinite(combined) && std::isfinite(gap)))
  {
    difference.exactValues += combined == 0 ? 1 : 0;
    return NoiseJudgement::NotJudged;
  }
  ++difference.withStandardError;
  for (int k = 0; k < 3; ++k)
  {
    difference.withinStandardErrors[static_cast<std::size_t>(k)] += gap <= (k + 1) * combined ? 1 : 0;
  }
  const bool outside = !passesRule && gap > *rule.standardErrors * combined;
  tally.add(passesRule ? 0.0 : pair.b - pair.a, combined * combined, outside);
  return outside ? NoiseJudgement::Outside : NoiseJudgement::Within;
}
}

ArrayDifference compareArrays(const ArrayValues& a, const ArrayValues& b, const ValueRule& rule,
  const ArrayValues* errorsA, const ArrayValues* errorsB)
{
  ArrayDifference difference;
  const std::size_t count = std::min(a.size(), b.size());
  const std::size_t components = static_cast<std::size_t>(std::max(a.components, 1));
  difference.values = count;
  difference.tuplePasses.assign(count / components, 1);
  const bool statistical = rule.standardErrors && errorsA && errorsB && errorsA->type != ValueType::Integer &&
    errorsB->type != ValueType::Integer && errorsA->reals.size() == count && errorsB->reals.size() == count;
  std::vector<NoiseTally> tallies(statistical ? components : 0);
  // The largest gap among failing values, and among all; infinite for a NaN against a number.
  double worstFailingGap = -1, worstGap = 0;
  std::optional<std::size_t> worstFailing, worstOverall;
  auto consider = [&](std::size_t i, double gap, bool passes)
  {
    if (!passes && gap > worstFailingGap)
    {
      worstFailingGap = gap;
      worstFailing = i;
    }
    if (gap > worstGap)
    {
      worstGap = gap;
      worstOverall = i;
    }
  };
  for (std::size_t i = 0; i < count; ++i)
  {
    bool passes = false;
    double gap = 0;
    if (a.type == ValueType::Integer)
    {
      const std::int64_t x = a.integers[i], y = b.integers[i];
      passes = x == y;
      gap = std::abs(static_cast<double>(x) - static_cast<double>(y));
      countDifferingBits(x, y, difference);
    }
    else
    {
      const double x = a.reals[i], y = b.reals[i];
      if (std::isnan(x) && std::isnan(y))
      {
        ++difference.nanInBoth;
        continue; // passes
      }
      if (std::isnan(x) || std::isnan(y))
      {
        ++difference.nanInOne;
        ++difference.failing;
        difference.tuplePasses[i / components] = 0;
        consider(i, std::numeric_limits<double>::infinity(), false);
        continue;
      }
      gap = x == y ? 0.0 : std::abs(x - y); // equal infinities differ by 0, not NaN
      // An infinity passes only against itself (rtol times infinity would pass anything).
      passes = x == y ||
        (std::isfinite(gap) &&
          (rule.ulps ? ulpDistance(x, y, a.type) <= *rule.ulps
                     : gap <= std::max(rule.relative * std::max(std::abs(x), std::abs(y)), rule.absolute)));
      const NoiseJudgement judgement = statistical
        ? judgeByStandardErrors(
            { x, y, errorsA->reals[i], errorsB->reals[i] }, gap, passes, rule, tallies[i % components], difference)
        : NoiseJudgement::NotJudged;
      if (judgement != NoiseJudgement::NotJudged)
      {
        passes = true; // judged by the count of values outside, not one by one
        if (judgement == NoiseJudgement::Outside)
        {
          difference.tuplePasses[i / components] = 0;
        }
      }
    }
    difference.largest = std::max(difference.largest, gap);
    difference.sumOfSquares += std::isfinite(gap) ? gap * gap : 0.0;
    if (!passes)
    {
      ++difference.failing;
      difference.tuplePasses[i / components] = 0;
    }
    consider(i, gap, passes);
  }
  difference.worst = worstFailing ? worstFailing : worstOverall;
  const double perCheck = significancePerCheck(rule.significance, static_cast<int>(components));
  for (const NoiseTally& tally : tallies)
  {
    difference.noise.push_back(checkNoise(tally, *rule.standardErrors, perCheck));
  }
  return difference;
}
}
