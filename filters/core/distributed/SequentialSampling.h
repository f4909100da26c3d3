#pragma once
// Sampling until an estimate meets the error it is allowed (docs/formulas.md section 13.7):
// rounds of samples, each stratified on its own, until the standard error is at most half the
// allowed error, after a minimum count and never past a maximum. Every round is a function of
// the vertex's own samples only, so where a vertex stops, and its estimate, are the same bits
// on any number of threads and processes.

#include <optional>
#include <vector>

namespace shadelab
{
/// Rounds are whole multiples of this many samples: a packet of rays (OccluderMesh::bundleSize),
/// and an even count, so that every stratum of a round holds its pair (MonteCarloEstimate).
constexpr int samplingRound = 16;

/// The error a sampled estimate is allowed, its share of a tolerance, and the fewest and most
/// samples a vertex draws for it.
struct SamplingTarget
{
  /// The estimate is within this of its mean at 95% confidence: its standard error is at most
  /// half of it (two standard errors, a little more than the normal's 1.96). > 0.
  double error = 0;
  int minimum = samplingRound;
  int maximum = 4096;

  /// The target of a fraction (of open rays, say), whose minimum is the rule of three: an
  /// estimate that has seen n samples agree (every ray open) puts what it has not seen below
  /// 3 / n at 95% confidence, so no vertex stops before 3 / error samples (in whole rounds,
  /// and at most the maximum).
  static SamplingTarget forFraction(double error, int maximum);
  /// A target whose minimum is at least `samples` (in whole rounds, and at most the maximum).
  static SamplingTarget atLeast(double error, int samples, int maximum);

  double standardError() const { return error / 2; }
  /// How many samples the next round draws after `drawn` samples whose standard error is
  /// `standardError`: 0 when the target is met past the minimum, or the maximum is reached.
  /// Otherwise the count that would meet it if the standard error falls as 1 / sqrt(n), in
  /// whole rounds, at most as many as were drawn (the estimate of a few samples is rough).
  int nextRound(int drawn, double standardError) const;

  bool operator==(const SamplingTarget& other) const
  {
    return error == other.error && minimum == other.minimum && maximum == other.maximum;
  }
};

/// A distributed light's targets for its sampled estimates of E and of S, in their own units
/// (absent: the light's fixed count, or not sampled).
struct SampleTargets
{
  std::optional<SamplingTarget> irradiance, specular;
  /// Under shadows, of the visible fraction V where E is an unshadowed E0 computed without
  /// samples times V (an exact or SH E): E's target over E0, set per vertex by the estimator.
  std::optional<SamplingTarget> visibility;

  bool any() const { return irradiance || specular || visibility; }
  bool operator==(const SampleTargets& other) const
  {
    return irradiance == other.irradiance && specular == other.specular && visibility == other.visibility;
  }
};

/// The confidence of a target's error: the share of the vertices within it.
constexpr double targetConfidence = 0.95;

/// The error that a share `fraction` (in (0, 1)) of the vertices are estimated to stay within,
/// from each vertex's standard error (0 where nothing was sampled): the x at which the expected
/// share of vertices beyond it, mean of P(|N(0, s_i^2)| > x), is 1 - fraction (docs/formulas.md
/// section 13.8). All equal, it is 1.96 s at 95%; it is 0 where at least `fraction` of them are 0.
/// A standard error that is not a number counts as infinite.
double estimatedErrorQuantile(std::vector<double> standardErrors, double fraction);
}
