#include "SpotCone.h"

#include "JsonNode.h"
#include "LightChecks.h"

namespace shadelab
{
SpotCone readCone(const JsonNode& light)
{
  SpotCone cone;
  if (!light.has("cone"))
  {
    return cone;
  }
  const JsonNode node = light.at("cone");
  node.expectObject({ "model", "angle", "exponent", "inner_angle", "outer_angle" });
  cone.model = node.at("model").choice<ConeModel>({ { "vtk", ConeModel::Vtk }, { "gltf", ConeModel::Gltf } });
  if (cone.model == ConeModel::Vtk)
  {
    node.expectObject({ "model", "angle", "exponent" });
    cone.halfAngleDegrees = numberOr(node, "angle", cone.halfAngleDegrees);
    cone.exponent = numberOr(node, "exponent", cone.exponent);
  }
  else
  {
    node.expectObject({ "model", "inner_angle", "outer_angle" });
    cone.innerAngleDegrees = numberOr(node, "inner_angle", cone.innerAngleDegrees);
    cone.outerAngleDegrees = numberOr(node, "outer_angle", cone.outerAngleDegrees);
  }
  return cone;
}

void checkCone(const SpotCone& cone, LightChecks& checks)
{
  if (cone.model == ConeModel::Vtk)
  {
    checks.require(std::isfinite(cone.halfAngleDegrees) && cone.halfAngleDegrees >= 0 && cone.halfAngleDegrees <= 180,
      "/cone/angle", "must be a half-angle in degrees, in [0, 180]");
    checks.require(std::isfinite(cone.exponent) && cone.exponent >= 0 && cone.exponent <= 128, "/cone/exponent",
      "must be in [0, 128], the range vtkLight allows");
    return;
  }
  checks.require(!reproducesVtkRenderer(checks.model), "/cone/model",
    std::string("the ") + modelName(checks.model) + " model has only vtkLight's cone (model \"vtk\")");
  checks.require(std::isfinite(cone.outerAngleDegrees) && cone.outerAngleDegrees > 0 && cone.outerAngleDegrees <= 90,
    "/cone/outer_angle", "must be in (0, 90] degrees");
  checks.require(std::isfinite(cone.innerAngleDegrees) && cone.innerAngleDegrees >= 0 &&
      cone.innerAngleDegrees < cone.outerAngleDegrees,
    "/cone/inner_angle", "must be >= 0 and less than outer_angle");
}
}
