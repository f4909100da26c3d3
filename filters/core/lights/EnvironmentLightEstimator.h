#pragma once
// Estimators of E and S (DistributedLight.h) for an environment map: the brute-force sum
// over texels, Monte Carlo, nine spherical-harmonic coefficients, or precomputed radiance
// transfer; with shadows, each of them with the rays of its samples (docs/formulas.md sections
// 12.7 and 12.10).
#include "DistributedLight.h"
#include "EnvironmentLight.h"
#include "EnvironmentMap.h"
#include "EnvironmentSampler.h"
#include "LobeSampling.h"
#include "RadianceTransfer.h"
#include "SampledTerms.h"
#include "SequentialSampling.h"
#include "SphericalHarmonics.h"

#include <glm/mat3x3.hpp>

#include <optional>
#include <vector>

namespace shadelab
{
/// The light's radiance (its map times colour times intensity) as spherical-harmonic
/// coefficients of bands 0 to order (0 to largestShOrder) in world axes, the map turned by its
/// rotation: what precomputed transfer dots each vertex's transfer vector with, when it shades
/// and when it relights (docs/formulas.md section 12.10).
ShCoefficients worldRadianceCoefficients(const EnvironmentLight& light, int order);

class EnvironmentLightEstimator final
  : public DistributedLightEstimator
  , public ShadowedLightEstimator
{
public:
  /// targets: where the light's samples are drawn to a tolerance's share.
  EnvironmentLightEstimator(
    const EnvironmentLight& light, std::uint64_t lightIndex, const LobeModel& lobe, const SampleTargets& targets = {});

  DistributedTerms estimate(const SurfacePoint& point) const override;

  /// The rays of the light's `sampling.samples` directions, drawn by its `directions`, to infinity.
  int shadowRayCount() const override;
  void shadowRays(const SurfacePoint& point, ShadowRay* rays) const override;
  /// Monte Carlo: E and S from the samples that get through. Brute force and spherical
  /// harmonics: their unshadowed E times the samples' visible fraction, S from the samples that
  /// get through (a lobe's own directions would need rays of their own). Precomputed transfer:
  /// the transfer vector from the samples, E its dot product with the map's coefficients.
  DistributedTerms estimate(const SurfacePoint& point, const HiddenSamples& hidden) const override;
  DistributedTerms estimate(const SurfacePoint& point, RoundShadows& shadows) const override;
  std::optional<glm::dvec3> emitterCentre() const override { return std::nullopt; }

  /// For the SH estimator, E as a polynomial of the world normal (eq. 13 turned with the map),
  /// for the kernel's vectorised loops; nothing for the other estimators.
  const std::optional<IrradiancePolynomial>& irradiance() const { return irradiance_; }

private:
  /// A texel of the brute-force level: its centre's direction (map frame) and radiance x
  /// solid angle, scaled by the light's colour and intensity.
  struct Texel
  {
    glm::dvec3 direction;
    Rgb radiantIntensity;
  };

  DistributedTerms bruteForce(const glm::dvec3& n, const glm::dvec3& v, bool specular) const;
  /// n and v in the map's frame; the point's own for its rays.
  DistributedTerms monteCarlo(const glm::dvec3& n, const glm::dvec3& v, std::uint64_t vertex, bool irradiance,
    EnvironmentDirections directions, const SampleTargets& targets, const SampleShadowing& shadowing) const;
  DistributedTerms shadowedEstimate(const SurfacePoint& point, const SampleShadowing& shadowing) const;
  /// Precomputed transfer with shadows: n and v in the map's frame, the point's samples hidden
  /// as `hidden` says (a fixed count).
  DistributedTerms shadowedTransfer(
    const SurfacePoint& point, const glm::dvec3& n, const glm::dvec3& v, const HiddenSamples& hidden) const;
  /// The rays of the sequence's samples, from a point of normal n (the map's frame).
  void shadowRaysOf(const glm::dvec3& n, const SampleSequence& sequence, ShadowRay* rays) const;
  /// The sample's direction with its radiance (times the light's colour) over its pdf.
  RadianceSample weightedByDensity(const EnvironmentSample& sample) const;
  /// The direction (map frame) draw() draws, bit for bit, without its radiance and density.
  glm::dvec3 drawDirection(const glm::dvec3& n, const glm::dvec2& u, EnvironmentDirections directions) const;
  /// The direction of a sample of the mixture of luminance and cosine (Mis).
  glm::dvec3 mixtureDirection(const glm::dvec3& n, const glm::dvec2& u) const;
  /// drawDirection for the sequence's samples first .. first + count - 1 (count at most
  /// directionBlock), into x[], y[], z[]: in loops that vectorize, and with the luminance
  /// samples' tables fetched ahead (EnvironmentSampler::sampleDirections).
  static constexpr int directionBlock = 16;
  void drawDirections(const glm::dvec3& n, const SampleSequence& sequence, int first, int count,
    EnvironmentDirections directions, double* x, double* y, double* z) const;
  /// drawDirections for the mixture (Mis).
  void mixtureDirections(
    const glm::dvec3& n, const SampleSequence& sequence, int first, int count, double* x, double* y, double* z) const;
  /// A direction (map frame) drawn from u as `directions` says, with L(w) / pdf(w).
  RadianceSample draw(const glm::dvec3& n, const glm::dvec2& u, EnvironmentDirections directions) const;
  /// A direction drawn by the lobe: the map there, and the lobe and its density.
  struct ByLobe
  {
    EnvironmentSample map;
    LobeAtDirection lobe;
  };
  /// One estimate of S from a sample drawn by luminance and one drawn by the lobe.
  Rgb specularByBothStrategies(
    const glm::dvec3& n, const glm::dvec3& v, const EnvironmentSample& byLuminance, const ByLobe& byLobe) const;
  Rgb radianceAt(const glm::dvec3& mapDirection) const;

  EnvironmentLight light_;
  Rgb scale_;
  std::uint64_t lightIndex_;
  LobeModel lobe_;
  SampleTargets targets_;
  glm::dmat3 worldToMap_{ 1.0 };
  glm::dmat3 mapToWorld_{ 1.0 };
  std::vector<Texel> texels_;                      // BruteForce
  std::optional<EnvironmentSampler> sampler_;      // sampling by luminance
  std::optional<IrradiancePolynomial> irradiance_; // SphericalHarmonics
  ShCoefficients transferRadiance_;                // PrecomputedTransfer: the map's coefficients in world axes, scaled
};
}
