#pragma once
// What point and spot lights share: a position and a distance falloff (docs/formulas.md
// section 9), read, checked, bounded and placed on the mesh alike.
#include "Attenuation.h"
#include "LightFields.h"
#include "LightType.h"

namespace shadelab
{
/// "color", "intensity", "position", "attenuation" and "min_distance".
template<typename Light>
void readPositionalLight(const JsonNode& node, Light& light)
{
  readStrength(node, light);
  light.position = node.at("position").vector3();
  light.attenuation = readAttenuation(node);
}

template<typename Light>
void checkPositionalLight(const Light& light, LightChecks& checks)
{
  checks.strength(light.color, light.intensity);
  checks.point(light.position, "/position");
  checkAttenuation(light.attenuation, checks);
}

/// At full attenuation: a vertex at the minimum distance (for a spot, on its axis).
template<typename Light>
double positionalPeakContribution(const Light& light, const Material& m)
{
  return largestComponent(light.emitted()) * attenuationAt(light.attenuation, 0.0) * largestReflectance(m);
}

/// The position moves with the mesh; the falloff scales so that the light a vertex gets stays.
template<typename Light>
void placePositionalLight(Light& light, const MeshPlacement& placement)
{
  light.position = placement.point(light.position);
  placeFalloff(light.intensity, light.attenuation, placement.radius);
}
}
