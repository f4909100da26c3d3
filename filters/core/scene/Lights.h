#pragma once
// Light sources (docs/formulas.md sections 8, 11 and 12), one struct per type, in the manner of
// pbrt-v4's lights.h. These describe a light; ShadingKernel.h evaluates them at vertices.
#include "Attenuation.h"
#include "SpotCone.h"
#include "Vec3.h"

#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace shadelab
{
/// docs/formulas.md section 8.1: at infinite distance, constant direction, no attenuation.
struct DistantLight
{
  glm::dvec3 direction{ 0, 0, -1 }; // the direction the light travels; s = -direction
  Rgb color{ 1, 1, 1 };
  double intensity = 1.0;
  /// docs/formulas.md section 8.1: the light's strength may be carried by the length of its
  /// direction vector. When set, intensity is multiplied by |direction|.
  bool intensityFromLength = false;
};

/// A distant light that travels along the viewer's line of sight (VTK's headlight).
struct Headlight
{
  Rgb color{ 1, 1, 1 };
  double intensity = 1.0;
};

/// docs/formulas.md sections 8.2 and 9: a local light radiating equally in all directions.
struct PointLight
{
  glm::dvec3 position{ 0, 0, 0 };
  Rgb color{ 1, 1, 1 };
  double intensity = 1.0;
  Attenuation attenuation;
};

/// docs/formulas.md sections 8.3 and 10: a point light that emits only inside a cone around
/// its axis.
struct SpotLight
{
  glm::dvec3 position{ 0, 0, 0 };
  glm::dvec3 axis{ 0, 0, -1 }; // the direction the cone points
  Rgb color{ 1, 1, 1 };
  double intensity = 1.0;
  Attenuation attenuation;
  SpotCone cone;
};

/// docs/formulas.md sections 8.4 and 2: light arriving equally from all directions (La).
struct AmbientLight
{
  Rgb color{ 1, 1, 1 };
  double intensity = 1.0;
};

/// docs/formulas.md section 11: distributed sources. An emitter of uniform radiance L = colour x
/// intensity over its surface (a Lambertian emitter), seen from each vertex as a solid angle.
/// A planar convex polygon; it emits on the side its vertices wind anticlockwise around (the
/// right-hand normal), or on both sides when the light is two-sided.
struct PolygonEmitter
{
  std::vector<glm::dvec3> vertices;
};

/// A disk, emitting on the side its normal points to (or both when two-sided).
struct DiskEmitter
{
  glm::dvec3 centre{ 0, 0, 0 };
  glm::dvec3 normal{ 0, 0, -1 };
  double radius = 1.0;
};

/// A sphere, emitting outward everywhere on its surface.
struct SphereEmitter
{
  glm::dvec3 centre{ 0, 0, 0 };
  double radius = 1.0;
};

using EmitterShape = std::variant<PolygonEmitter, DiskEmitter, SphereEmitter>;

/// How the irradiance from an area light is estimated. The specular term is estimated by
/// Monte Carlo for Exact and MonteCarlo, and by the point light for Point.
enum class AreaEstimator
{
  Exact,      // Lambert's polygon formula clipped to the horizon; the sphere's and disk's exact forms
  MonteCarlo, // `samples` points on the emitter, with a standard error per vertex
  Point,      // a point light at the emitter's centre ("five-times rule", docs/formulas.md section 11.5)
};

/// More samples than this per vertex is a mistake (a 100k-vertex mesh would take hours); at
/// least 2 give a standard error.
constexpr int maxSamplesPerVertex = 1 << 20;

/// How Monte Carlo estimators place their samples in the unit square they warp.
struct Sampling
{
  int samples = 64;
  /// One sample in each of `samples` cells of a grid over the square, rather than independent.
  bool stratified = true;
};

struct AreaLight
{
  EmitterShape shape;
  Rgb color{ 1, 1, 1 };
  double intensity = 1.0; // L = color x intensity, radiance
  bool twoSided = false;
  AreaEstimator estimator = AreaEstimator::Exact;
  Sampling sampling;
};

struct EnvironmentMap; // EnvironmentMap.h

/// How the irradiance from an environment map is estimated. The specular term is estimated by
/// the same sum for BruteForce, by sampling for MonteCarlo and SphericalHarmonics (nine
/// coefficients hold too little of a map for a lobe sharper than the cosine).
enum class EnvironmentEstimator
{
  BruteForce,         // every texel of the map downsampled to `bruteForceWidth`, as a distant light
  MonteCarlo,         // `sampling.samples` directions, drawn by `directions`
  SphericalHarmonics, // 9 coefficients (Ramamoorthi and Hanrahan 2001), diffuse only
};

/// Where Monte Carlo directions for an environment map come from.
enum class EnvironmentDirections
{
  Luminance, // importance sampling of the map's luminance, good for small bright sources; for S
             // combined with sampling the lobe (multiple importance sampling)
  Cosine,    // cosine-weighted about the normal: exact irradiance from a constant map
};

/// docs/formulas.md section 12: an environment map, where every texel is a distant light of
/// radiance colour x intensity x texel, over the texel's solid angle.
struct EnvironmentLight
{
  std::shared_ptr<const EnvironmentMap> map;
  std::string file; // where the map came from, for messages and reports
  double rotationDegrees = 0; // about +y, anticlockwise seen from above
  Rgb color{ 1, 1, 1 };
  double intensity = 1.0;
  EnvironmentEstimator estimator = EnvironmentEstimator::SphericalHarmonics;
  EnvironmentDirections directions = EnvironmentDirections::Luminance;
  Sampling sampling;
  int bruteForceWidth = 128;
};

using LightSource =
  std::variant<DistantLight, Headlight, PointLight, SpotLight, AmbientLight, AreaLight, EnvironmentLight>;

struct NamedLight
{
  std::string name;
  LightSource source;
};

/// True for lights that sit at a position, so that distance means something.
inline bool isPositional(const LightSource& source)
{
  return std::holds_alternative<PointLight>(source) || std::holds_alternative<SpotLight>(source);
}

/// The position of a point or spot light, or nullptr for the others.
inline const glm::dvec3* positionOf(const LightSource& source)
{
  if (const auto* point = std::get_if<PointLight>(&source))
  {
    return &point->position;
  }
  if (const auto* spot = std::get_if<SpotLight>(&source))
  {
    return &spot->position;
  }
  return nullptr;
}

/// The distance attenuation of a point or spot light, or nullptr for the others.
inline const Attenuation* attenuationOf(const LightSource& source)
{
  if (const auto* point = std::get_if<PointLight>(&source))
  {
    return &point->attenuation;
  }
  if (const auto* spot = std::get_if<SpotLight>(&source))
  {
    return &spot->attenuation;
  }
  return nullptr;
}

inline bool isAmbient(const LightSource& source)
{
  return std::holds_alternative<AmbientLight>(source);
}

/// Area lights and environment maps: lights integrated over a solid angle per vertex.
inline bool isDistributed(const LightSource& source)
{
  return std::holds_alternative<AreaLight>(source) || std::holds_alternative<EnvironmentLight>(source);
}

/// Colour x intensity (x |direction| for a distant light with intensityFromLength): the RGB
/// the light delivers before attenuation, cone and material.
Rgb emittedColor(const LightSource& source);

/// The name of a light type as the scene file spells it.
std::string lightTypeName(const LightSource& source);
}
