#pragma once
// The Monte Carlo loop the area-light and environment-map estimators share: E and S from
// sampled directions, with their standard errors.
#include "DistributedLight.h"
#include "MonteCarloEstimate.h"
#include "SampleSequence.h"
#include "SequentialSampling.h"
#include "Vec3.h"
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
/// (when the lobe is) over the vertex's sample points (SampleSequence of this light and vertex),
/// which sampleAt(u) turns into RadianceSamples: sampling's fixed count or, with targets, rounds
/// until each sampled estimate meets its target (SequentialSampling.h; unshadowed only). With
/// hidden (shadows), each sample counts only where its ray got through, and the visible
/// fraction of the irradiance is estimated from the same samples.
template <typename SampleAt>
DistributedTerms sampledTerms(std::uint64_t light, std::uint64_t vertex, const Sampling& sampling,
  const SampleTargets& targets, bool irradiance, const LobeModel& lobe, const glm::dvec3& n, const glm::dvec3& v,
  const HiddenSamples* hidden, SampleAt&& sampleAt)
{
  MonteCarloEstimate e(sampling.stratified), s(sampling.stratified);
  VisibleFraction visible(sampling.stratified);
  auto draw = [&](const SampleSequence& sequence, int first)
  {
    for (int j = 0; j < sequence.count(); ++j)
    {
      const RadianceSample sample = sampleAt(sequence.point(j));
      const bool through = !hidden || !hidden->hidden(first + j);
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
  };
  bool shortOfTarget = false;
  if (!targets.any())
  {
    draw(SampleSequence(light, vertex, sampling), 0);
  }
  else
  {
    // The next round is the larger that either estimate's target asks for.
    auto nextRound = [&](int drawn)
    {
      const int forE = irradiance && targets.irradiance
        ? targets.irradiance->nextRound(drawn, drawn > 0 ? largestComponent(e.standardError()) : 0.0)
        : 0;
      const int forS = lobe.wanted() && targets.specular
        ? targets.specular->nextRound(drawn, drawn > 0 ? largestComponent(s.standardError()) : 0.0)
        : 0;
      return std::max(forE, forS);
    };
    int drawn = 0;
    for (int round = nextRound(0); round > 0; round = nextRound(drawn))
    {
      draw(SampleSequence(light, vertex, { round, sampling.stratified }, static_cast<std::uint64_t>(drawn)), drawn);
      drawn += round;
    }
    shortOfTarget = (irradiance && targets.irradiance && largestComponent(e.standardError()) > targets.irradiance->standardError()) ||
      (lobe.wanted() && targets.specular && largestComponent(s.standardError()) > targets.specular->standardError());
  }
  DistributedTerms terms;
  terms.shortOfTarget = shortOfTarget;
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
