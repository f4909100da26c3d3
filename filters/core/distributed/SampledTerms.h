#pragma once
// The Monte Carlo loop the area-light and environment-map estimators share: E and S from
// sampled directions, with their standard errors.
#include "DistributedLight.h"
#include "MonteCarloEstimate.h"
#include "SampleSequence.h"
#include "VisibleFraction.h"

#include <optional>

namespace shadelab
{
/// A sampled direction w and L(w) / pdf(w), the sample's radiance over its density.
struct RadianceSample
{
  glm::dvec3 direction{ 0.0 };
  Rgb weighted{ 0.0 };
  /// An estimate of S made from more than this direction (multiple importance sampling), to
  /// use instead of weighted x lobe(w).
  std::optional<Rgb> specular;
};

/// Averages L(w) max(0, n.w) / pdf(w) (when irradiance is wanted) and L(w) lobe(w) / pdf(w)
/// (when the lobe is) over the sequence's points, which sampleAt(u) turns into RadianceSamples.
/// With hidden (shadows), each sample counts only where its ray got through, and the visible
/// fraction of the irradiance is estimated from the same samples.
template <typename SampleAt>
DistributedTerms sampledTerms(const SampleSequence& sequence, bool stratified, bool irradiance, const LobeModel& lobe,
  const glm::dvec3& n, const glm::dvec3& v, const HiddenSamples* hidden, SampleAt&& sampleAt)
{
  MonteCarloEstimate e(stratified), s(stratified);
  VisibleFraction visible(stratified);
  for (int j = 0; j < sequence.count(); ++j)
  {
    const RadianceSample sample = sampleAt(sequence.point(j));
    const bool through = !hidden || !hidden->hidden(j);
    const double seen = through ? 1.0 : 0.0;
    const Rgb unshadowed = sample.weighted * std::max(0.0, glm::dot(n, sample.direction));
    if (irradiance)
    {
      e.add(unshadowed * seen);
    }
    if (lobe.wanted())
    {
      s.add((sample.specular ? *sample.specular : sample.weighted * lobe(n, sample.direction, v)) * seen);
    }
    if (hidden)
    {
      visible.add((unshadowed.x + unshadowed.y + unshadowed.z) / 3, through);
    }
  }
  DistributedTerms terms;
  if (irradiance)
  {
    terms.irradiance = e.mean();
    terms.irradianceStdError = e.standardError();
  }
  if (lobe.wanted())
  {
    terms.specular = s.mean();
    terms.specularStdError = s.standardError();
  }
  if (hidden)
  {
    terms.visibility = visible.value();
    terms.visibilityStdError = visible.standardError();
  }
  return terms;
}
}
