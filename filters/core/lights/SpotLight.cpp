#include "SpotLight.h"

#include "LightFields.h"

namespace shadelab
{
const std::vector<SceneFileType>& SpotLight::sceneFileTypes()
{
  static const std::vector<SceneFileType> types = {
    { "spot", { "position", "direction", "attenuation", "min_distance", "cone" } }
  };
  return types;
}

SpotLight SpotLight::read(const JsonNode& node, const SceneFileType&, const std::string&)
{
  SpotLight light;
  readStrength(node, light);
  light.position = node.at("position").vector3();
  light.axis = node.at("direction").vector3();
  light.attenuation = readAttenuation(node);
  light.cone = readCone(node);
  return light;
}

std::string SpotLight::typeName() const
{
  return "spot";
}

Rgb SpotLight::emitted() const
{
  return color * intensity;
}

void SpotLight::check(LightChecks& checks) const
{
  checks.strength(color, intensity);
  checks.point(position, "/position");
  checkAttenuation(attenuation, checks);
  checks.direction(axis, "/direction");
  checkCone(cone, checks);
}

double SpotLight::peakContribution(const Material& m) const
{
  // At full attenuation, on the axis: a vertex at the minimum distance.
  return largestComponent(emitted()) * attenuationAt(attenuation, 0.0) * largestReflectance(m);
}

bool SpotLight::hasTerm(LightTerm term) const
{
  return localLightHasTerm(term, positional);
}

void SpotLight::placeOn(const MeshPlacement& placement)
{
  position = placement.point(position);
  placeFalloff(intensity, attenuation, placement.radius);
}

LightEvaluation SpotLight::prepare(const EvaluationContext&) const
{
  LocalEvaluation evaluation;
  evaluation.geometry = LocalEvaluation::Geometry::Spot;
  evaluation.position = position;
  evaluation.axis = unitVector(axis);
  evaluation.falloff = attenuation;
  evaluation.cone = cone;
  evaluation.color = emitted();
  return evaluation;
}
}
