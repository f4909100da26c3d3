#include "PointLight.h"

#include "PositionalLight.h"

namespace shadelab
{
const std::vector<SceneFileType>& PointLight::sceneFileTypes()
{
  static const std::vector<SceneFileType> types = { { "point", { "position", "attenuation", "min_distance" } } };
  return types;
}

PointLight PointLight::read(const JsonNode& node, const SceneFileType&, const std::string&)
{
  PointLight light;
  readPositionalLight(node, light);
  return light;
}

std::string PointLight::typeName() const
{
  return "point";
}

Rgb PointLight::emitted() const
{
  return color * intensity;
}

void PointLight::check(LightChecks& checks) const
{
  checkPositionalLight(*this, checks);
}

double PointLight::peakContribution(const Material& m) const
{
  return positionalPeakContribution(*this, m);
}

bool PointLight::hasTerm(LightTerm term) const
{
  return localLightHasTerm(term, positional);
}

void PointLight::placeOn(const MeshPlacement& placement)
{
  placePositionalLight(*this, placement);
}

LightEvaluation PointLight::prepare(const EvaluationContext& context) const
{
  LocalEvaluation evaluation;
  evaluation.color = emitted();
  if (context.distantFrom)
  {
    // The approximation: the direction, distance and attenuation at that point, everywhere.
    const glm::dvec3 offset = position - *context.distantFrom;
    const double distance = vectorLength(offset);
    evaluation.toLight = distance > 0 ? unitVector(offset) : glm::dvec3(0, 0, 1);
    evaluation.distance = distance;
    evaluation.attenuation = attenuationAt(attenuation, distance);
    return evaluation;
  }
  evaluation.geometry = LocalEvaluation::Geometry::Point;
  evaluation.position = position;
  evaluation.falloff = attenuation;
  return evaluation;
}
}
