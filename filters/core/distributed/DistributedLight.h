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

#include <cstdint>
#include <memory>

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
/// the estimator has none).
struct DistributedTerms
{
  Rgb irradiance{ 0.0 };
  Rgb specular{ 0.0 };
  Rgb irradianceStdError{ 0.0 };
  Rgb specularStdError{ 0.0 };
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
}
