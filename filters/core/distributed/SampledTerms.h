#pragma once
// The Monte Carlo loop the area-light and environment-map estimators share: E and S from
// sampled directions, with their standard errors.
#include "DistributedLight.h"
#include "MonteCarloEstimate.h"
#include "SampleSequence.h"
#include "SequentialSampling.h"
#include "Vec3.h"
#include "VisibleFraction.h"

#include <algorithm>
#include <array>
#include <optional>
#include <vector>

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

/// How the mesh hides a vertex's samples: not at all (no shadows), as the visibility step's bits
/// for the light's fixed count, or round by round as they are drawn (to a target).
struct SampleShadowing
{
  const HiddenSamples* fixed = nullptr;
  RoundShadows* rounds = nullptr;

  bool on() const { return fixed || rounds; }

  /// The hidden samples of a round: the fixed bits (a fixed count is one round), or the round's
  /// rays, which raysOf(round, rays) names, traced.
  template<typename RaysOf>
  HiddenSamples of(const SampleSequence& round, RaysOf&& raysOf) const
  {
    if (fixed)
    {
      return *fixed;
    }
    std::vector<ShadowRay> rays(static_cast<std::size_t>(round.count()));
    raysOf(round, rays.data());
    return rounds->trace(rays.data(), round.count());
  }
};

/// The targets of an estimate whose E is an unshadowed E0 computed without samples times the
/// samples' visible fraction V (an exact or SH E under shadows): E's standard error is E0's
/// largest component times V's, so V's target is E's over that (none where E0 is 0: no E to
/// err).
inline SampleTargets withVisibilityTarget(SampleTargets targets, const Rgb& unshadowed)
{
  const double largest = largestComponent(unshadowed);
  if (targets.irradiance && largest > 0)
  {
    targets.visibility =
      SamplingTarget{ targets.irradiance->error / largest, targets.irradiance->minimum, targets.irradiance->maximum };
  }
  return targets;
}

/// The most samples that sampledTerms asks its samplesAt for at once.
constexpr int sampleBlock = 16;

/// A samplesAt for sampledTerms from sampleAt(u), which turns one point into its RadianceSample.
template<typename SampleAt>
auto pointByPoint(SampleAt&& sampleAt)
{
  return [&sampleAt](const SampleSequence& sequence, int first, int count, RadianceSample* samples)
  {
    for (int k = 0; k < count; ++k)
    {
      samples[k] = sampleAt(sequence.point(first + k));
    }
  };
}

/// Averages L(w) max(0, n.w) / pdf(w) (when irradiance is wanted) and L(w) lobe(w) / pdf(w)
/// (when the lobe is) over the vertex's sample points (SampleSequence of this light and vertex),
/// which samplesAt(sequence, first, count, samples) turns into RadianceSamples, at most
/// sampleBlock at a time (so that it can fetch their data ahead): sampling's fixed count or, with targets, rounds
/// until each sampled estimate meets its target (SequentialSampling.h). With shadows, each
/// sample counts only where its ray got through, as hiddenOf(round) says of the round's samples
/// (the bits of the visibility step for the one round of a fixed count, or a round's rays traced
/// as it is drawn), and the visible fraction of the irradiance is estimated from the same samples.
template<typename HiddenOfRound, typename SamplesAt>
DistributedTerms sampledTerms(std::uint64_t light, std::uint64_t vertex, const Sampling& sampling,
  const SampleTargets& targets, bool irradiance, const LobeModel& lobe, const glm::dvec3& n, const glm::dvec3& v,
  bool shadowed, HiddenOfRound&& hiddenOf, SamplesAt&& samplesAt)
{
  MonteCarloEstimate e(sampling.stratified), s(sampling.stratified);
  VisibleFraction visible(sampling.stratified);
  auto draw = [&](const SampleSequence& sequence)
  {
    const HiddenSamples hidden = shadowed ? hiddenOf(sequence) : HiddenSamples{};
    RadianceSample block[sampleBlock];
    for (int j = 0; j < sequence.count(); ++j)
    {
      if (j % sampleBlock == 0)
      {
        samplesAt(sequence, j, std::min(sampleBlock, sequence.count() - j), block);
      }
      const RadianceSample& sample = block[j % sampleBlock];
      const bool through = !shadowed || !hidden.hidden(j);
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
      if (shadowed)
      {
        visible.add((unshadowed.x + unshadowed.y + unshadowed.z) / 3, through);
      }
    }
  };
  bool shortOfTarget = false;
  int drawn = 0;
  if (!targets.any())
  {
    const SampleSequence sequence(light, vertex, sampling);
    draw(sequence);
    drawn = sequence.count();
  }
  else
  {
    // Each target's estimate's standard error now, where that estimate is made.
    auto standardErrors = [&]
    {
      return std::array<std::optional<double>, 3>{
        irradiance && targets.irradiance ? std::optional<double>(largestComponent(e.standardError())) : std::nullopt,
        lobe.wanted() && targets.specular ? std::optional<double>(largestComponent(s.standardError())) : std::nullopt,
        shadowed && targets.visibility ? std::optional<double>(visible.standardError()) : std::nullopt
      };
    };
    const std::optional<SamplingTarget>* each[] = { &targets.irradiance, &targets.specular, &targets.visibility };
    // The next round is the largest that any estimate's target asks for.
    auto nextRound = [&](int drawn)
    {
      const auto errorsNow = standardErrors();
      int round = 0;
      for (int t = 0; t < 3; ++t)
      {
        if (errorsNow[t])
        {
          round = std::max(round, (*each[t])->nextRound(drawn, drawn > 0 ? *errorsNow[t] : 0.0));
        }
      }
      return round;
    };
    for (int round = nextRound(0); round > 0; round = nextRound(drawn))
    {
      draw(SampleSequence(light, vertex, { round, sampling.stratified }, static_cast<std::uint64_t>(drawn)));
      drawn += round;
    }
    const auto errorsAtEnd = standardErrors();
    for (int t = 0; t < 3; ++t)
    {
      shortOfTarget = shortOfTarget || (errorsAtEnd[t] && *errorsAtEnd[t] > (*each[t])->standardError());
    }
  }
  DistributedTerms terms;
  terms.shortOfTarget = shortOfTarget;
  terms.samples = drawn;
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
  if (shadowed)
  {
    terms.visibility = visible.value();
    terms.visibilityStdError = visible.standardError();
  }
  return terms;
}
}
