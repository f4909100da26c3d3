#pragma once
// Light sources of the lecture (sections 4 to 7), one struct per type, in the manner of
// pbrt-v4's lights.h. These describe a light; ShadingKernel.h evaluates them at vertices.
#include "Attenuation.h"
#include "SpotCone.h"
#include "Vec3.h"

#include <string>
#include <variant>

namespace shadelab
{
/// Lecture section 4.1: at infinite distance, constant direction, no attenuation.
struct DistantLight
{
  glm::dvec3 direction{ 0, 0, -1 }; // the direction the light travels; s = -direction
  Rgb color{ 1, 1, 1 };
  double intensity = 1.0;
  /// Lecture section 6: "the intensity of a distant light source is encoded in the length
  /// of the direction vector". When set, intensity is multiplied by |direction|.
  bool intensityFromLength = false;
};

/// A distant light that travels along the viewer's line of sight (VTK's headlight).
struct Headlight
{
  Rgb color{ 1, 1, 1 };
  double intensity = 1.0;
};

/// Lecture sections 4.2, 5 and 6: a local light radiating equally in all directions.
struct PointLight
{
  glm::dvec3 position{ 0, 0, 0 };
  Rgb color{ 1, 1, 1 };
  double intensity = 1.0;
  Attenuation attenuation;
};

/// Lecture section 6: a point light that emits only inside a cone around its axis.
struct SpotLight
{
  glm::dvec3 position{ 0, 0, 0 };
  glm::dvec3 axis{ 0, 0, -1 }; // the direction the cone points
  Rgb color{ 1, 1, 1 };
  double intensity = 1.0;
  Attenuation attenuation;
  SpotCone cone;
};

/// Lecture section 7 and 11.1: light arriving equally from all directions (La).
struct AmbientLight
{
  Rgb color{ 1, 1, 1 };
  double intensity = 1.0;
};

using LightSource = std::variant<DistantLight, Headlight, PointLight, SpotLight, AmbientLight>;

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

/// Colour x intensity (x |direction| for a distant light with intensityFromLength): the RGB
/// the light delivers before attenuation, cone and material.
Rgb emittedColor(const LightSource& source);

/// The name of a light type as the scene file spells it.
std::string lightTypeName(const LightSource& source);
}
