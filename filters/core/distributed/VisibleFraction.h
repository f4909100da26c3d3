#pragma once
// The visible fraction of a light at a vertex, V = sum x_j v_j / sum x_j: each sample's
// unshadowed irradiance x_j (L max(0, n.w) / pdf) weighted by whether the mesh lets it
// through (v_j, 0 or 1). A ratio of two sample means, so the exact unshadowed E times V is E
// itself, bit for bit, where every ray gets through (docs/formulas.md section 11.6).
#include <algorithm>
#include <cmath>

namespace shadelab
{
/// Accumulates the samples in order; stratified samples are paired as MonteCarloEstimate pairs
/// them.
///
/// Standard error: V is a ratio estimator (W. G. Cochran, "Sampling Techniques", 3rd ed., 1977,
/// section 6.3), whose variance to first order is that of the mean of d_j = y_j - V x_j
/// (y_j = x_j v_j) over the square of the mean of x. Where every ray agrees (all through, or
/// all blocked) the d_j are all 0, which says nothing about the part of the light the samples
/// missed: one sample's share of the weight, sum x_j^2 / (sum x_j)^2 (1 / N for equal
/// weights), is added in quadrature, as ambient occlusion adds one ray's (Visibility.cpp).
class VisibleFraction
{
public:
  explicit VisibleFraction(bool stratified)
    : stratified_(stratified)
  {
  }

  void add(double x, bool visible)
  {
    const double y = visible ? x : 0.0;
    ++count_;
    sumX_ += x;
    sumY_ += y;
    sumXX_ += x * x;
    if (!stratified_)
    {
      sumYY_ += y * y;
      sumXY_ += x * y;
    }
    else if (count_ % 2 == 0)
    {
      const double dx = x - previousX_, dy = y - previousY_;
      sumXX2_ += dx * dx;
      sumYY_ += dy * dy;
      sumXY_ += dx * dy;
    }
    previousX_ = x;
    previousY_ = y;
  }

  /// 1 where no sample carries light: the light is below the horizon and nothing is hidden.
  double value() const { return sumX_ > 0 ? sumY_ / sumX_ : 1.0; }

  double standardError() const
  {
    if (!(sumX_ > 0) || count_ < 2)
    {
      return 0;
    }
    const double v = value();
    const double n = double(count_);
    const double meanX = sumX_ / n;
    double varianceOfMeanD;
    if (stratified_)
    {
      const double pairs = double(count_ / 2);
      const double squares = std::max(0.0, sumYY_ - 2 * v * sumXY_ + v * v * sumXX2_);
      varianceOfMeanD = squares * (n / (2 * pairs)) / (n * n);
    }
    else
    {
      // The d_j have mean 0 exactly, at V = sum y / sum x.
      const double squares = std::max(0.0, sumYY_ - 2 * v * sumXY_ + v * v * sumXX_);
      varianceOfMeanD = squares / (n * (n - 1));
    }
    const double oneSampleShare = sumXX_ / (sumX_ * sumX_);
    return std::hypot(std::sqrt(varianceOfMeanD) / meanX, oneSampleShare);
  }

private:
  bool stratified_;
  long count_ = 0;
  double sumX_ = 0, sumY_ = 0, sumXX_ = 0;
  double sumYY_ = 0, sumXY_ = 0; // independent: raw sums; stratified: over the pairs' differences
  double sumXX2_ = 0;            // stratified: the pairs' squared differences of x
  double previousX_ = 0, previousY_ = 0;
};
}
