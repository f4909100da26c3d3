#pragma once
// The mean of a Monte Carlo estimator's samples and its standard error, per RGB channel or of
// single values.
#include "Vec3.h"

#include <cmath>

namespace shadelab
{
/// Accumulates samples f_1 .. f_N (each an unbiased estimate of the integral) in order: RGB
/// values, or single ones (Value double, such as a ray's 0 or 1), the same bits as one channel
/// of RGB at a third of the work.
///
/// Independent samples: the standard error of the mean is s / sqrt(N), s^2 the sample variance.
/// Stratified samples (one per cell, SampleSequence): s / sqrt(N) would ignore what the strata
/// remove, so consecutive cells are paired and each pair's variance estimated from its two
/// samples, the "collapsed strata" estimator (W. G. Cochran, "Sampling Techniques", 3rd ed.,
/// 1977, section 5A.12): Var(mean) = sum over pairs (f_a - f_b)^2 / N^2. It errs on the high
/// side by the spread of the paired cells' means, which is small for neighbouring cells. An
/// odd last sample has no partner; the pairs' sum is scaled by N / (2 floor(N/2)) for it.
template<typename Value>
class MonteCarloMean
{
public:
  explicit MonteCarloMean(bool stratified)
    : stratified_(stratified)
  {
  }

  void add(const Value& f)
  {
    ++count_;
    sum_ += f;
    if (stratified_)
    {
      if (count_ % 2 == 0)
      {
        const Value difference = f - previous_;
        squares_ += difference * difference;
      }
      previous_ = f;
    }
    else
    {
      // Welford's update: no cancellation between sum f^2 and (sum f)^2 / N.
      const Value delta = f - mean_;
      mean_ += delta / double(count_);
      squares_ += delta * (f - mean_);
    }
  }

  Value mean() const { return count_ > 0 ? sum_ / double(count_) : Value(0.0); }

  /// Needs at least 2 samples.
  Value standardError() const
  {
    using glm::sqrt;
    using std::sqrt;
    const double n = double(count_);
    if (stratified_)
    {
      const double pairs = double(count_ / 2);
      return sqrt(squares_ * (n / (2 * pairs))) / n;
    }
    return sqrt(squares_ / (n - 1) / n);
  }

private:
  bool stratified_;
  long count_ = 0;
  Value sum_{ 0.0 };
  Value mean_{ 0.0 };     // independent: Welford's running mean
  Value previous_{ 0.0 }; // stratified: the first sample of the open pair
  Value squares_{ 0.0 };
};

using MonteCarloEstimate = MonteCarloMean<Rgb>;
}
