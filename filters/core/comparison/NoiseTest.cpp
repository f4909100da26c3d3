#include "NoiseTest.h"

#include <algorithm>

namespace shadelab
{
double normalUpperTail(double z)
{
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}

double normalUpperQuantile(double tail)
{
  // P(Z > 0) = 0.5 and P(Z > 40) is below the smallest double: the answer lies between.
  double low = 0, high = 40;
  for (;;)
  {
    const double middle = 0.5 * (low + high);
    if (middle <= low || middle >= high)
    {
      return high;
    }
    (normalUpperTail(middle) > tail ? low : high) = middle;
  }
}

double binomialLogProbability(std::size_t n, double p, std::size_t k)
{
  const double count = static_cast<double>(n), hits = static_cast<double>(k);
  return std::lgamma(count + 1) - std::lgamma(hits + 1) - std::lgamma(count - hits + 1) + hits * std::log(p) +
    (count - hits) * std::log1p(-p);
}

std::size_t binomialUpperQuantile(std::size_t n, double p, double tail)
{
  if (p <= 0)
  {
    return 0;
  }
  if (p >= 1)
  {
    return n;
  }
  // Beyond 40 standard deviations and 100 counts of the mean, the mass left out is below
  // 2 e^-150 (1.4e-65) by Bernstein's inequality, far below any tail asked for (>= 1e-40).
  const double mean = static_cast<double>(n) * p, margin = 40 * std::sqrt(mean * (1 - p)) + 100;
  const std::size_t low = mean > margin ? static_cast<std::size_t>(std::floor(mean - margin)) : 0;
  const std::size_t high = static_cast<std::size_t>(std::min(static_cast<double>(n), std::ceil(mean + margin)));
  // P(X > c - 1) summed from the top, the smallest terms first.
  double above = 0;
  for (std::size_t c = high; c > low; --c)
  {
    above += std::exp(binomialLogProbability(n, p, c));
    if (above > tail)
    {
      return c; // c - 1 allows too much; c, summed one step before, does not
    }
  }
  return low;
}

double significancePerCheck(double significance, int components)
{
  return significance / (2.0 * std::max(components, 1));
}

NoiseCheck checkNoise(const NoiseTally& tally, double k, double perCheck)
{
  NoiseCheck check;
  check.values = tally.values;
  check.outside = tally.outside;
  if (tally.values == 0)
  {
    return check;
  }
  const double n = static_cast<double>(tally.values), p = 2 * normalUpperTail(k);
  check.expected = n * p;
  check.allowed = binomialUpperQuantile(tally.values, p, perCheck);
  check.meanDifference = tally.sumOfDifferences / n;
  check.meanDifferenceError = std::sqrt(tally.sumOfVariances) / n;
  check.meanDifferenceLimit = normalUpperQuantile(perCheck / 2) * check.meanDifferenceError;
  return check;
}
}
