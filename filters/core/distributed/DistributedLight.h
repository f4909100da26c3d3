#pragma once
// Lights integrated over a solid angle at every vertex: area lights and environment maps
// (docs/formulas.md sections 11 and 12). Each light type has several estimators; all of them
// return the same two integrals, so that the kernel and the arrays do not depend on which one
// ran:
//
//   irradiance E = integral of L(w) max(0, n.w) dw
//   specular   S = integral over lit directions (n.w > 0) of L(w) lobe(w) dw
//
// Both reduce to the point light (docs/formulas.md sections 8.2 and 11.1) in the limit of a
// small source: a source of intensity I at distance d gives E = I max(0, n.s) / d^2 and
// S = I lobe(s) / d^2. So the diffuse term is kd E and the specular term ks S, as
// kd Ld max(0, n.s) att and ks Ls lobe att are for a point light.
#include "Material.h"
#include "Reflectance.h"
#include "ShBands.h"

#include <cstdint>
#include <memory>
#include <optional>

namespace shadelab
{
/// A vertex as the estimators see it: unit normal (already flipped where two-sided shading
/// asks), unit direction to the viewer, and the vertex's index, which seeds its samples.
struct SurfacePoint
{
  glm::dvec3 position{ 0.0 };
  glm::dvec3 normal{ 0.0 };
  glm::dvec3 toViewer{ 0.0 };
  std::uint64_t index = 0;
};

/// E and S (before kd and ks), and the standard errors of their Monte Carlo estimates (0 where
/// the estimator has none). With shadows, both are the integrals over the part of the light the
/// vertex sees past the mesh, and visibility is the visible irradiance over the unshadowed one
/// (1 where the light is below the horizon).
struct DistributedTerms
{
  Rgb irradiance{ 0.0 };
  Rgb specular{ 0.0 };
  Rgb irradianceStdError{ 0.0 };
  Rgb specularStdError{ 0.0 };
  double visibility = 1;
  double visibilityStdError = 0;
  /// Drawn to a target (SequentialSampling.h): stopped at the maximum with a standard error
  /// still above it.
  bool shortOfTarget = false;
  /// How many samples the estimate drew (0: computed without samples).
  int samples = 0;
  /// Precomputed radiance transfer only (RadianceTransfer.h): the vertex's transfer vector in
  /// world axes and its coefficients' standard errors (0 without shadows), 0 past its order's.
  ShBasis transfer{};
  ShBasis transferStdError{};
};

/// The specular lobe for light arriving from the unit direction s (docs/formulas.md sections 4
/// and 5; Reflectance.h): max(0, r.v)^eta or max(0, n.h)^eta, on lit directions only.
struct LobeModel
{
  SpecularModel model = SpecularModel::None; // None: no specular integral is estimated
  double eta = 0;

  bool wanted() const { return model != SpecularModel::None; }

  double operator()(const glm::dvec3& n, const glm::dvec3& s, const glm::dvec3& v) const
  {
    const double cosIncidence = glm::dot(n, s);
    if (model == SpecularModel::Phong)
    {
      return specularLobe(cosIncidence > 0, glm::dot(reflectAboutNormal(s, n, cosIncidence), v), eta);
    }
    glm::dvec3 h;
    return halfVector(s, v, h) ? specularLobe(cosIncidence > 0, glm::dot(n, h), eta) : 0.0;
  }
};

class DistributedLightEstimator
{
public:
  virtual ~DistributedLightEstimator() = default;
  /// Safe to call concurrently.
  virtual DistributedTerms estimate(const SurfacePoint& point) const = 0;
};

/// The shadow ray of one sample: from the surface point along a unit direction, up to the
/// light (infinite for a map). Not cast where the sample adds nothing (it counts as visible).
struct ShadowRay
{
  glm::dvec3 direction{ 0.0 };
  double distance = 0;
  bool cast = false;
};

/// Which of a vertex's samples the mesh hides, as the visibility step found them: bit j % 64 of
/// word j / 64 for sample j.
struct HiddenSamples
{
  const std::uint64_t* words = nullptr;

  bool hidden(int j) const { return (words[j / 64] >> (j % 64)) & 1u; }
};

/// The 64-bit words a vertex needs for the bits of this many samples.
constexpr int hiddenSampleWords(int samples)
{
  return (samples + 63) / 64;
}

/// Traces a vertex's shadow rays one round at a time, as its samples are drawn to a target
/// (soft shadows under a tolerance: how many rounds a vertex draws depends on what the earlier
/// rays found, so its rays cannot be cast before its estimate). Bound to one vertex.
class RoundShadows
{
public:
  virtual ~RoundShadows() = default;
  /// Which of rays[0..count-1] the mesh hides (bit j for ray j; those not cast are not), valid
  /// until the next call.
  virtual HiddenSamples trace(const ShadowRay* rays, int count) = 0;
};

/// DistributedTerms as a row of numbers, for the visibility step to hand its estimates to the
/// shading (soft shadows drawn to a target): E, S, their standard errors (RGB each), the
/// visibility and its standard error, whether the vertex stopped short of its target, and how
/// many samples it drew. Not
/// a transfer vector: precomputed transfer is drawn to a fixed count only (a tolerance refuses
/// it with shadows), so it never comes this way.
constexpr int packedTermsSize = 16;

inline void packTerms(const DistributedTerms& terms, double* row)
{
  const Rgb* colours[] = { &terms.irradiance, &terms.specular, &terms.irradianceStdError, &terms.specularStdError };
  for (int c = 0; c < 4; ++c)
  {
    row[3 * c] = colours[c]->x;
    row[3 * c + 1] = colours[c]->y;
    row[3 * c + 2] = colours[c]->z;
  }
  row[12] = terms.visibility;
  row[13] = terms.visibilityStdError;
  row[14] = terms.shortOfTarget ? 1.0 : 0.0;
  row[15] = terms.samples;
}

inline DistributedTerms unpackTerms(const double* row)
{
  DistributedTerms terms;
  Rgb* colours[] = { &terms.irradiance, &terms.specular, &terms.irradianceStdError, &terms.specularStdError };
  for (int c = 0; c < 4; ++c)
  {
    *colours[c] = Rgb(row[3 * c], row[3 * c + 1], row[3 * c + 2]);
  }
  terms.visibility = row[12];
  terms.visibilityStdError = row[13];
  terms.shortOfTarget = row[14] != 0;
  terms.samples = static_cast<int>(row[15]);
  return terms;
}

/// A distributed light's estimator with its shadows (docs/formulas.md section 11.6): it names
/// the rays of its samples, the visibility step (visibility/) casts them against the mesh, and
/// it estimates E and S from the same samples weighted by what the rays found. The rays and
/// the estimate are separate steps so that the rays can be cast where the whole mesh is (the
/// first process of a split mesh) and the estimate made wherever the vertex is.
class ShadowedLightEstimator
{
public:
  virtual ~ShadowedLightEstimator() = default;
  /// How many shadow rays each vertex has: the length of shadowRays' list.
  virtual int shadowRayCount() const = 0;
  /// The point's shadow rays, one per sample in sample order, into rays[0..shadowRayCount()-1].
  virtual void shadowRays(const SurfacePoint& point, ShadowRay* rays) const = 0;
  /// E, S and the visibility, with the samples hidden as `hidden` says. Safe to call concurrently.
  virtual DistributedTerms estimate(const SurfacePoint& point, const HiddenSamples& hidden) const = 0;
  /// The same, for an estimator drawn to targets: its samples drawn in rounds until they meet
  /// them, each round's rays (as shadowRays names them, for that round's samples) traced by
  /// `shadows` before they are weighted.
  virtual DistributedTerms estimate(const SurfacePoint& point, RoundShadows& shadows) const = 0;
  /// A point inside the emitter (its centre), from which the visibility step finds whether
  /// the mesh encloses the light; nothing for a map, which is at infinity.
  virtual std::optional<glm::dvec3> emitterCentre() const = 0;
};
}
