#include "Attenuation.h"

#include "JsonNode.h"
#include "LightChecks.h"

namespace shadelab
{
Attenuation readAttenuation(const JsonNode& light)
{
  Attenuation a;
  a.minDistance = numberOr(light, "min_distance", a.minDistance);
  if (!light.has("attenuation"))
  {
    return a;
  }
  const JsonNode node = light.at("attenuation");
  const auto modelOf = [](const JsonNode& name)
  {
    return name.choice<AttenuationModel>({ { "none", AttenuationModel::None }, { "inverse", AttenuationModel::Inverse },
      { "inverse_square", AttenuationModel::InverseSquare }, { "vtk", AttenuationModel::ConstantLinearQuadratic },
      { "gltf_range", AttenuationModel::GltfRange } });
  };
  if (node.isString())
  {
    a.model = modelOf(node);
    if (a.model == AttenuationModel::ConstantLinearQuadratic || a.model == AttenuationModel::GltfRange)
    {
      node.fail("this model has parameters: write it as an object, e.g. {\"model\": \"" + node.text() + "\", ...}");
    }
    return a;
  }
  node.expectObject({ "model", "constant", "linear", "quadratic", "range" });
  a.model = modelOf(node.at("model"));
  // Now that the model is known, its parameters are the only fields allowed.
  switch (a.model)
  {
    case AttenuationModel::ConstantLinearQuadratic:
      node.expectObject({ "model", "constant", "linear", "quadratic" });
      a.constant = numberOr(node, "constant", 1.0);
      a.linear = numberOr(node, "linear", 0.0);
      a.quadratic = numberOr(node, "quadratic", 0.0);
      break;
    case AttenuationModel::GltfRange:
      node.expectObject({ "model", "range" });
      a.range = node.at("range").number();
      break;
    default: node.expectObject({ "model" });
  }
  return a;
}

void checkAttenuation(const Attenuation& a, LightChecks& checks)
{
  const bool vtkCanExpress = a.model == AttenuationModel::None || a.model == AttenuationModel::ConstantLinearQuadratic;
  checks.require(!reproducesVtkRenderer(checks.model) || vtkCanExpress, "/attenuation",
    std::string("the ") + modelName(checks.model) +
      " model has only vtkLight's constant-linear-quadratic attenuation (or none)");
  checks.require(isNonNegative(a.minDistance), "/min_distance", "must be a number >= 0");
  checks.require(!divergesAtZero(a) || a.minDistance > 0, "/min_distance",
    "must be > 0: this attenuation is infinite at distance 0");
  if (a.model == AttenuationModel::ConstantLinearQuadratic)
  {
    const bool allNonNegative = isNonNegative(a.constant) && isNonNegative(a.linear) && isNonNegative(a.quadratic);
    checks.require(allNonNegative, "/attenuation", "constant, linear and quadratic must be >= 0");
    checks.require(
      a.constant + a.linear + a.quadratic > 0, "/attenuation", "constant, linear and quadratic must not all be 0");
  }
  if (a.model == AttenuationModel::GltfRange)
  {
    checks.require(std::isfinite(a.range) && a.range > 0, "/attenuation/range", "must be > 0");
  }
}

void placeFalloff(double& intensity, Attenuation& a, double R)
{
  a.minDistance *= R;
  switch (a.model)
  {
    case AttenuationModel::None: break;
    case AttenuationModel::Inverse: intensity *= R; break;
    case AttenuationModel::InverseSquare: intensity *= R * R; break;
    case AttenuationModel::ConstantLinearQuadratic:
      // 1/(k0 + k1 d + k2 d^2) is dimensionless: k1 and k2 carry 1/length and 1/length^2.
      a.linear /= R;
      a.quadratic /= R * R;
      break;
    case AttenuationModel::GltfRange:
      a.range *= R;
      intensity *= R * R;
      break;
  }
}
}
