#include "SpotLight.h"

#include "PositionalLight.h"

namespace shadelab
{
const std::vector<SceneFileType>& SpotLight::sceneFileTypes()
{
  static const std::vector<SceneFileType> types = { { "spot",
    { "position", "direction", "attenuation", "min_distance", "cone" } } };
  return types;
}

SpotLight SpotLight::read(const JsonNode& node, const SceneFileType&, const std::string&)
{
  SpotLight light;
  readPositionalLight(node, light);
  light.axis = node.at("direction").vector3();
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
  checkPositionalLight(*this, checks);
  checks.direction(axis, "/direction");
  checkCone(cone, checks);
}

double SpotLight::peakContribution(const Material& m) const
{
  return positionalPeakContribution(*this, m);
}

bool SpotLight::hasTerm(LightTerm term) const
{
  return localLightHasTerm(term, positional);
}

void SpotLight::placeOn(const MeshPlacement& placement)
{
  placePositionalLight(*this, placement);
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
