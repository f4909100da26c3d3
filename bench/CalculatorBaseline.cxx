#include "CalculatorBaseline.h"

#include "NumberText.h"

namespace shadelab::app
{
namespace
{
/// All 17 digits, so that the calculator computes with the same doubles.
std::string number(double x)
{
  return withDigits(x, 17);
}

std::string vectorOf(const glm::dvec3& v)
{
  return "(" + number(v.x) + "*iHat+" + number(v.y) + "*jHat+" + number(v.z) + "*kHat)";
}

/// The expression of one light's diffuse and specular terms, or empty if it has none that an
/// expression can state.
std::optional<std::string> lightTerms(
  const NamedLight& named, const Scene& scene, bool diffuseOnly, const std::string& normals)
{
  const Material& m = scene.material;
  std::string toLight, attenuation = "1";
  Rgb strength;
  if (const auto* distant = std::get_if<DistantLight>(&named.source))
  {
    if (distant->intensityFromLength)
    {
      return std::nullopt;
    }
    toLight = vectorOf(-unitVector(distant->direction));
    strength = distant->color * distant->intensity;
  }
  else if (const auto* point = std::get_if<PointLight>(&named.source))
  {
    const AttenuationModel model = point->attenuation.model;
    if (model != AttenuationModel::InverseSquare && model != AttenuationModel::None)
    {
      return std::nullopt;
    }
    const std::string offset = "(" + vectorOf(point->position) + "-coords)";
    toLight = "norm" + offset;
    if (model == AttenuationModel::InverseSquare)
    {
      const double dMin = point->attenuation.minDistance;
      attenuation = "(1/max(mag" + offset + "^2," + number(dMin * dMin) + "))";
    }
    strength = point->color * point->intensity;
  }
  else
  {
    return std::nullopt;
  }
  const std::string cosIncidence = "dot(" + normals + "," + toLight + ")";
  std::string terms = "max(" + cosIncidence + ",0)*" + attenuation + "*" + vectorOf(strength * m.kd);
  if (diffuseOnly || m.specular == SpecularModel::None)
  {
    return terms;
  }
  const std::string toViewer = scene.viewer.position ? "norm(" + vectorOf(*scene.viewer.position) + "-coords)"
                                                     : vectorOf(-unitVector(scene.viewer.viewDirection));
  const std::string cosine = m.specular == SpecularModel::Phong
    ? "dot(2*" + cosIncidence + "*" + normals + "-" + toLight + "," + toViewer + ")"
    : "dot(" + normals + ",norm(" + toLight + "+" + toViewer + "))";
  terms += "+(" + cosIncidence + ">0)*max(" + cosine + ",0)^" + number(m.shininess) + "*" + attenuation + "*" +
    vectorOf(strength * m.ks);
  return terms;
}
}

std::optional<std::string> calculatorExpression(const Scene& scene, bool diffuseOnly, const std::string& normals)
{
  if (scene.model != ShadingModel::Lecture || scene.material.twoSided)
  {
    return std::nullopt;
  }
  Rgb ambient(0.0);
  std::string expression;
  for (const NamedLight& light : scene.lights)
  {
    if (const auto* a = std::get_if<AmbientLight>(&light.source))
    {
      ambient += a->color * a->intensity;
      continue;
    }
    const std::optional<std::string> terms = lightTerms(light, scene, diffuseOnly, normals);
    if (!terms)
    {
      return std::nullopt;
    }
    expression += (expression.empty() ? "" : "+") + *terms;
  }
  if (!diffuseOnly)
  {
    expression = vectorOf(scene.material.ka * ambient) + (expression.empty() ? "" : "+") + expression;
  }
  if (expression.empty())
  {
    return std::nullopt; // no light with a diffuse term: nothing for the calculator to do
  }
  return expression;
}
}
