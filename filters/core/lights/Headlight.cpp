#include "Headlight.h"

#include "LightFields.h"

namespace shadelab
{
const std::vector<SceneFileType>& Headlight::sceneFileTypes()
{
  static const std::vector<SceneFileType> types = { { "headlight", {} } };
  return types;
}

Headlight Headlight::read(const JsonNode& node, const SceneFileType&, const std::string&)
{
  Headlight light;
  readStrength(node, light);
  return light;
}

std::string Headlight::typeName() const
{
  return "headlight";
}

Rgb Headlight::emitted() const
{
  return color * intensity;
}

void Headlight::check(LightChecks& checks) const
{
  checks.strength(color, intensity);
  checks.require(checks.lineOfSight.has_value(), "",
    "a headlight shines along the viewer's line of sight: give the viewer a focal_point");
}

double Headlight::peakContribution(const Material& m) const
{
  return largestComponent(emitted()) * largestReflectance(m);
}

bool Headlight::hasTerm(LightTerm term) const
{
  return localLightHasTerm(term, positional);
}

void Headlight::placeOn(const MeshPlacement&)
{
  // It follows the viewer, who is placed with the scene.
}

LightEvaluation Headlight::prepare(const EvaluationContext& context) const
{
  LocalEvaluation evaluation;
  evaluation.toLight = -*context.lineOfSight;
  evaluation.color = emitted();
  return evaluation;
}
}
