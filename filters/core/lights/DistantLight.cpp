#include "DistantLight.h"

#include "LightFields.h"

namespace shadelab
{
const std::vector<SceneFileType>& DistantLight::sceneFileTypes()
{
  static const std::vector<SceneFileType> types = { { "distant", { "direction", "intensity_from_length" } } };
  return types;
}

DistantLight DistantLight::read(const JsonNode& node, const SceneFileType&, const std::string&)
{
  DistantLight light;
  readStrength(node, light);
  light.direction = node.at("direction").vector3();
  if (node.has("intensity_from_length"))
  {
    light.intensityFromLength = node.at("intensity_from_length").boolean();
  }
  return light;
}

std::string DistantLight::typeName() const
{
  return "distant";
}

Rgb DistantLight::emitted() const
{
  Rgb rgb = color * intensity;
  rgb *= intensityFromLength ? vectorLength(direction) : 1.0;
  return rgb;
}

void DistantLight::check(LightChecks& checks) const
{
  checks.strength(color, intensity);
  checks.direction(direction, "/direction");
}

double DistantLight::peakContribution(const Material& m) const
{
  return largestComponent(emitted()) * largestReflectance(m);
}

bool DistantLight::hasTerm(LightTerm term) const
{
  return localLightHasTerm(term, positional);
}

void DistantLight::placeOn(const MeshPlacement&)
{
  // A direction: the same in every frame.
}

LightEvaluation DistantLight::prepare(const EvaluationContext&) const
{
  LocalEvaluation evaluation;
  evaluation.toLight = -unitVector(direction);
  evaluation.color = emitted();
  return evaluation;
}
}
