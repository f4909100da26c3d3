#pragma once
// Whether the differences between two Monte Carlo estimates are their noise (docs/formulas.md
// section 21). With n independent values and no true difference, z = (b - a) / sqrt(e_a^2 +
// e_b^2) is standard normal, so the count of values with |z| > k is Binomial(n, p), p =
// 2 P(Z > k); and the mean difference (1/n) sum (b - a) is normal with standard error
// sqrt(sum (e_a^2 + e_b^2)) / n. A component passes when its count is at most the binomial
// quantile and its mean difference within the normal quantile, each check at its share of the
// significance. The bias is judged by the mean difference, not by the mean of the z-scores:
// where a standard error is estimated from the same samples as its value, z leans to the side
// where that error came out small (32 occlusion rays that all miss: a standard error of 0),
// and the mean z of two honest runs drifts by more than its 1 / sqrt(n).
#include <cmath>
#include <cstddef>

namespace shadelab
{
/// P(Z > z) for a standard normal Z, 0.5 erfc(z / sqrt(2)): accurate far into the upper tail.
double normalUpperTail(double z);

/// The z with P(Z > z) = tail, for 1e-300 <= tail <= 0.5: bisection on normalUpperTail, to
/// the last bit.
double normalUpperQuantile(double tail);

/// log P(X = k) for X ~ Binomial(n, p), 0 < p < 1, k <= n, from lgamma.
double binomialLogProbability(std::size_t n, double p, std::size_t k);

/// The smallest count c with P(X > c) <= tail for X ~ Binomial(n, p), 0 <= p <= 1 and
/// 1e-40 <= tail < 1: the most values a test at significance `tail` lets lie outside.
std::size_t binomialUpperQuantile(std::size_t n, double p, double tail);

/// One component's z-scores, gathered value by value.
struct NoiseTally
{
  std::size_t values = 0;  // with a combined standard error > 0
  std::size_t outside = 0; // of them, with |z| > k
  double sumOfDifferences = 0, sumOfVariances = 0;

  /// A value: b - a, e_a^2 + e_b^2, and whether it lies outside k standard errors.
  void add(double difference, double variance, bool isOutside)
  {
    ++values;
    outside += isOutside ? 1 : 0;
    sumOfDifferences += difference;
    sumOfVariances += variance;
  }
};

/// The two checks of one component: the count outside k standard errors and the mean
/// difference.
struct NoiseCheck
{
  std::size_t values = 0, outside = 0;
  double expected = 0;     // n p
  std::size_t allowed = 0; // the binomial quantile
  double meanDifference = 0;
  double meanDifferenceError = 0; // its standard error
  double meanDifferenceLimit = 0; // the largest |mean difference| that passes

  bool countPasses() const { return outside <= allowed; }
  bool biasPasses() const { return std::abs(meanDifference) <= meanDifferenceLimit; }
  bool passes() const { return countPasses() && biasPasses(); }
};

/// The significance of each check when an array's significance is shared equally among its
/// components' two checks (Bonferroni: the chance that any of them fails stays at most the
/// array's significance).
double significancePerCheck(double significance, int components);

/// The checks of one component's tally with k standard errors, each at `perCheck`: the count
/// against Binomial(values, 2 P(Z > k)) at 1 - perCheck, and the mean difference over its
/// standard error against the normal quantile at 1 - perCheck / 2 (two-sided). A tally without
/// values passes.
NoiseCheck checkNoise(const NoiseTally& tally, double k, double perCheck);
}
