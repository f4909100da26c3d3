#pragma once
// What the kernel (kernel/ShadingKernel.h) evaluates for one light: each light type turns its
// parameters into one of these forms once per scene (its prepare), and the kernel has a loop
// for each form, not for each light type.
#include "Attenuation.h"
#include "DistributedLight.h"
#include "IrradiancePolynomial.h"
#include "SequentialSampling.h"
#include "SpotCone.h"
#include "Vec3.h"

#include <glm/geometric.hpp>

#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <variant>

namespace shadelab
{
/// Light arriving equally from all directions: ka La at every vertex.
struct AmbientEvaluation
{
  Rgb radiance{ 0.0 }; // La
};

/// Light arriving at each vertex from one direction s (docs/formulas.md section 8).
struct LocalEvaluation
{
  enum class Geometry
  {
    Distant, // s, d and the attenuation are the same at every vertex
    Point,   // s and d from the position, attenuated with distance
    Spot,    // a point light times its cone's factor about the axis
  };
  Geometry geometry = Geometry::Distant;
  glm::dvec3 toLight{ 0.0 };  // Distant: the constant unit s
  double distance = 0;        // Distant: the constant d (0, or the approximated one)
  double attenuation = 1;     // Distant: the constant attenuation
  glm::dvec3 position{ 0.0 }; // Point, Spot
  glm::dvec3 axis{ 0.0 };     // Spot: the unit direction the cone points
  Attenuation falloff;        // Point, Spot
  SpotCone cone;              // Spot
  Rgb color{ 0.0 };           // what the light delivers before attenuation, cone and material
};

/// Light integrated over a solid angle (DistributedLight.h): the estimator of E and S, and for
/// an irradiance that is a polynomial of the normal, the polynomial, which the kernel
/// evaluates in vectorised loops instead of the estimator's E.
struct DistributedEvaluation
{
  std::shared_ptr<const DistributedLightEstimator> estimator; // null when nothing is left to estimate
  std::optional<IrradiancePolynomial> irradiance;
  /// The estimator with the light's shadows, for a light that can cast them (null otherwise).
  std::shared_ptr<const ShadowedLightEstimator> shadowed;
};

using LightEvaluation = std::variant<AmbientEvaluation, LocalEvaluation, DistributedEvaluation>;

/// Where a light is seen from a vertex: its unit direction, and its distance (infinite for a
/// distant light).
struct LightDirection
{
  glm::dvec3 toLight{ 0.0 };
  double distance = std::numeric_limits<double>::infinity();
};

/// Where the local light is seen from p (a point or spot light at p itself: direction 0).
inline LightDirection towardLight(const LocalEvaluation& light, const glm::dvec3& p)
{
  if (light.geometry == LocalEvaluation::Geometry::Distant)
  {
    return { light.toLight, std::numeric_limits<double>::infinity() };
  }
  const glm::dvec3 d = light.position - p;
  const double distance = glm::length(d);
  return { distance > 0 ? d / distance : glm::dvec3(0.0), distance };
}

/// What a light's preparation needs from outside the light.
struct EvaluationContext
{
  std::optional<glm::dvec3> lineOfSight; // the viewer's unit viewing direction (the headlight's)
  /// A tolerance's plan (planning/LightMethod.h): evaluate a point light as a distant one,
  /// with its direction and attenuation at this point.
  std::optional<glm::dvec3> distantFrom;
  std::uint64_t lightIndex = 0; // seeds the light's samples
  LobeModel lobe;               // the specular lobe to integrate; model None: no S is needed
  SampleTargets targets;        // a tolerance's plan: a distributed light's samples drawn to its share
};
}
