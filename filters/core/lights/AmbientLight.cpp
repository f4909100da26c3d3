#include "AmbientLight.h"

#include "LightFields.h"

namespace shadelab
{
const std::vector<SceneFileType>& AmbientLight::sceneFileTypes()
{
  static const std::vector<SceneFileType> types = { { "ambient", {} } };
  return types;
}

AmbientLight AmbientLight::read(const JsonNode& node, const SceneFileType&, const std::string&)
{
  AmbientLight light;
  readStrength(node, light);
  return light;
}

std::string AmbientLight::typeName() const
{
  return "ambient";
}

Rgb AmbientLight::emitted() const
{
  return color * intensity;
}

void AmbientLight::check(LightChecks& checks) const
{
  checks.strength(color, intensity);
  checks.require(!reproducesVtkRenderer(checks.model), "/type",
    checks.model == ShadingModel::VtkPbr
      ? "VTK's renderer has no ambient light, and its PBR shader no ambient term: use the vtk or lecture model"
      : "VTK's renderer has no ambient light: with the vtk model, put the ambient colour in material.ka");
}

double AmbientLight::peakContribution(const Material& m) const
{
  return largestComponent(emitted()) * largestComponent(m.ka);
}

bool AmbientLight::hasTerm(LightTerm) const
{
  return false; // its light is in the ambient total
}

void AmbientLight::placeOn(const MeshPlacement&)
{
  // No geometry.
}

LightEvaluation AmbientLight::prepare(const EvaluationContext&) const
{
  return AmbientEvaluation{ emitted() };
}
}
