#pragma once
// Estimators of E and S (DistributedLight.h) for an area light: exact, Monte Carlo over the
// emitter, or a point light at its centre.
#include "AreaLight.h"
#include "DistributedLight.h"
#include "SampleWarps.h"
#include "SampledTerms.h"
#include "SequentialSampling.h"

#include <vector>

namespace shadelab
{
class AreaLightEstimator final
  : public DistributedLightEstimator
  , public ShadowedLightEstimator
{
public:
  /// targets: where the light's samples are drawn to a tolerance's share.
  AreaLightEstimator(
    const AreaLight& light, std::uint64_t lightIndex, const LobeModel& lobe, const SampleTargets& targets = {});

  DistributedTerms estimate(const SurfacePoint& point) const override;

  /// The samples' rays to the emitter (the point estimator: one ray, to the centre).
  int shadowRayCount() const override;
  void shadowRays(const SurfacePoint& point, ShadowRay* rays) const override;
  /// Exact: the exact E times the visible fraction of the samples, S from the samples that get
  /// through. Monte Carlo: E and S from the samples that get through. Point: the point light's
  /// E and S, times whether its one ray gets through.
  DistributedTerms estimate(const SurfacePoint& point, const HiddenSamples& hidden) const override;
  DistributedTerms estimate(const SurfacePoint& point, RoundShadows& shadows) const override;
  std::optional<glm::dvec3> emitterCentre() const override { return centre_; }

  /// A direction from point to the emitter, with 1 / pdf in solid angle (weight 0 where the
  /// emitter sends no light back along it). Warps u in [0, 1)^2 onto the emitter: uniformly over a polygon's or
  /// disk's area, uniformly over the cone a sphere subtends (every direction hits it), or
  /// cosine-weighted over the hemisphere from inside a sphere.
  WeightedDirection sample(const glm::dvec2& u, const SurfacePoint& point) const;

  /// E / L by the exact formulas (PolygonIrradiance.h, DiskIrradiance.h, SphereIrradiance.h).
  double exactProjectedSolidAngle(const SurfacePoint& point) const;

  /// The emitter's area-weighted centre, where the point approximation puts the light.
  const glm::dvec3& centre() const { return centre_; }

private:
  void measurePolygon(const PolygonEmitter& polygon);
  /// Polygons and disks, which emit from one side of a plane (or both when two-sided).
  bool isPlanar() const;
  /// A planar emitter's cosine toward a receiver in the given direction from it, 0 behind a
  /// one-sided emitter.
  double emittedCosine(const glm::dvec3& towardEmitter) const;
  bool sendsLightTo(const glm::dvec3& position) const;
  /// Whether any of the emitter is above the plane of the point's normal: where none is, no
  /// sample reaches the point's lit side, and it casts no ray.
  bool risesAbovePlaneOf(const SurfacePoint& point) const;
  /// A sampled direction and the distance along it to the emitter.
  struct EmitterSample
  {
    WeightedDirection toward;
    double distance = 0;
  };
  EmitterSample sampleEmitter(const glm::dvec2& u, const SurfacePoint& point) const;
  glm::dvec3 pointOnPolygon(const PolygonEmitter& polygon, const glm::dvec2& u) const;
  glm::dvec3 pointOnDisk(const DiskEmitter& disk, const glm::dvec2& u) const;
  /// The direction to a point sampled on a planar emitter by area, weighted as solid angle.
  EmitterSample towardPoint(const glm::dvec3& onEmitter, const glm::dvec3& receiver) const;
  EmitterSample towardSphere(const SphereEmitter& sphere, const glm::dvec2& u, const SurfacePoint& point) const;
  /// The rays of the sequence's samples (shadowRays' for the light's whole sequence).
  void shadowRaysOf(const SurfacePoint& point, const SampleSequence& sequence, ShadowRay* rays) const;
  DistributedTerms monteCarlo(
    const SurfacePoint& point, bool irradiance, const SampleTargets& targets, const SampleShadowing& shadowing) const;
  DistributedTerms pointApproximation(const SurfacePoint& point) const;
  DistributedTerms estimateWith(const SurfacePoint& point, const SampleShadowing& shadowing) const;

  AreaLight light_;
  Rgb radiance_;
  std::uint64_t lightIndex_;
  LobeModel lobe_;
  SampleTargets targets_;
  glm::dvec3 centre_{ 0.0 };
  glm::dvec3 normal_{ 0.0 };                     // polygons and disks
  glm::dvec3 tangent_{ 0.0 }, bitangent_{ 0.0 }; // disks: the plane's axes
  double area_ = 0;
  double backFace_ = 0;                 // 1 for a two-sided emitter: its back emits as its front
  std::vector<double> fanAreaFraction_; // polygons: cumulative share of each fan triangle
};
}
