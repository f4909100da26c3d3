#include "EnvironmentLight.h"

#include "EnvironmentLightEstimator.h"
#include "EnvironmentMap.h"
#include "LightFields.h"
#include "NumberText.h"
#include "RadianceTransfer.h"
#include "SphericalHarmonics.h"

#include <algorithm>
#include <filesystem>

namespace shadelab
{
namespace
{
/// A path in a scene file is relative to the scene file's folder; one read without a scene file
/// (shadelab shade's --envmap light), to the working folder, and kept as given.
std::string resolvePath(const std::string& path, const std::string& sceneFile)
{
  const std::filesystem::path given(path);
  if (given.is_absolute() || sceneFile.empty())
  {
    return path;
  }
  return (std::filesystem::path(sceneFile).parent_path() / given).lexically_normal().string();
}
}

const std::vector<SceneFileType>& EnvironmentLight::sceneFileTypes()
{
  static const std::vector<SceneFileType> types = { { "environment",
    { "file", "rotation", "estimator", "directions", "samples", "max_samples", "stratified", "brute_force_width",
      "order" } } };
  return types;
}

EnvironmentLight EnvironmentLight::read(const JsonNode& node, const SceneFileType&, const std::string& sceneFile)
{
  EnvironmentLight light;
  readStrength(node, light);
  light.file = resolvePath(node.at("file").text(), sceneFile);
  if (node.has("rotation"))
  {
    light.rotationDegrees = node.at("rotation").number();
  }
  if (node.has("estimator"))
  {
    light.estimator = node.at("estimator").choiceAmong(environmentEstimatorNames);
  }
  if (node.has("order"))
  {
    if (light.estimator != EnvironmentEstimator::PrecomputedTransfer)
    {
      node.at("order").fail("only the \"prt\" estimator has an order: remove it, or give \"estimator\": \"prt\"");
    }
    light.shOrder = node.at("order").wholeNumber(2, largestShOrder);
  }
  if (node.has("directions"))
  {
    light.directions = node.at("directions").choiceAmong(environmentDirectionNames);
    if (light.estimator == EnvironmentEstimator::PrecomputedTransfer &&
      light.directions != EnvironmentDirections::Cosine)
    {
      node.at("directions")
        .fail("\"prt\" draws its shadow rays by the cosine, the density its transfer vectors are "
              "estimated for: remove \"directions\"");
    }
  }
  light.sampling = readSampling(node);
  if (node.has("brute_force_width"))
  {
    light.bruteForceWidth = node.at("brute_force_width").wholeNumber(2, 1 << 20);
  }
  try
  {
    light.map = std::make_shared<const EnvironmentMap>(readEnvironmentMap(light.file));
  }
  catch (const std::runtime_error& error)
  {
    node.at("file").fail(error.what());
  }
  return light;
}

std::string EnvironmentLight::typeName() const
{
  return "environment";
}

Rgb EnvironmentLight::emitted() const
{
  return color * intensity;
}

void EnvironmentLight::check(LightChecks& checks) const
{
  checks.strength(color, intensity);
  checks.distributed(sampling);
  checks.require(std::isfinite(rotationDegrees), "/rotation", "must be a finite angle in degrees");
  checks.require(estimator != EnvironmentEstimator::PrecomputedTransfer || (shOrder >= 2 && shOrder <= largestShOrder),
    "/order", "must be a whole number from 2 to " + std::to_string(largestShOrder));
  checks.require(map != nullptr, "/file", "no environment map was loaded for this light");
  if (!map)
  {
    return;
  }
  // readEnvironmentMap ensures these; a map made in C++ may not.
  const bool shaped = map->height > 0 && map->width == 2 * map->height &&
    map->radiance.size() == std::size_t(map->width) * std::size_t(map->height);
  checks.require(shaped, "/file", "the map must be twice as wide as high, with width x height texels");
  const bool radiant =
    std::all_of(map->radiance.begin(), map->radiance.end(), [](const Rgb& t) { return isNonNegative(t); });
  checks.require(radiant, "/file", "every texel must be a finite non-negative radiance");
  const int width = bruteForceWidth;
  checks.require(width >= map->width || (width >= 2 && width % 2 == 0 && map->width % width == 0), "/brute_force_width",
    "must be an even number that divides the map's width (" + std::to_string(map->width) + "), or at least that width");
}

double EnvironmentLight::peakContribution(const Material& m) const
{
  double brightest = 0;
  for (const Rgb& texel : map->radiance)
  {
    brightest = std::max(brightest, largestComponent(texel));
  }
  return largestComponent(emitted()) * brightest * distributedPeakFactor * largestReflectance(m);
}

bool EnvironmentLight::hasTerm(LightTerm term) const
{
  if (term == LightTerm::ShTransfer)
  {
    return estimator == EnvironmentEstimator::PrecomputedTransfer;
  }
  // Every estimator but the brute-force sum samples S.
  return distributedLightHasTerm(
    term, estimator == EnvironmentEstimator::MonteCarlo, estimator != EnvironmentEstimator::BruteForce);
}

void EnvironmentLight::placeOn(const MeshPlacement&)
{
  // Directions only: the map is at infinity in every frame.
}

LightEvaluation EnvironmentLight::prepare(const EvaluationContext& context) const
{
  auto estimator =
    std::make_shared<const EnvironmentLightEstimator>(*this, context.lightIndex, context.lobe, context.targets);
  if (estimator->irradiance())
  {
    // E is the estimator's polynomial of the normal; the estimator is still needed for S,
    // which it samples, and with shadows for E as well (the polynomial times the visible
    // fraction).
    std::optional<IrradiancePolynomial> irradiance = estimator->irradiance();
    return DistributedEvaluation{ context.lobe.wanted() ? estimator : nullptr, irradiance, estimator };
  }
  return DistributedEvaluation{ estimator, std::nullopt, estimator };
}

ToleranceBounds EnvironmentLight::toleranceBounds(const Material& m, bool shadowed) const
{
  ToleranceBounds bounds;
  bounds.sampledIrradiance = estimator == EnvironmentEstimator::MonteCarlo;
  bounds.autoSamples = "\"samples\": \"auto\" (--envmap-samples auto)";
  const bool transfer = estimator == EnvironmentEstimator::PrecomputedTransfer;
  if (estimator == EnvironmentEstimator::BruteForce)
  {
    bounds.unbounded = "the \"brute_force\" sum of a downsampled map has no error bound: use \"sh\" or \"monte_carlo\"";
  }
  else if (transfer && shadowed)
  {
    // Its bands' error under shadows is bounded only by the map less its bands, integrated
    // (docs/formulas.md section 12.10), and its rays are a fixed count.
    const double error =
      largestComponent(color * intensity * bandLimitError(*map, shOrder)) * std::max(1.0, largestComponent(m.kd));
    bounds.unbounded = "its shadowed transfer vectors can err by up to " + scientific(error) +
      " through their bands alone, and are estimated from a fixed \"samples\" count, which no target stops: use "
      "\"estimator\": \"monte_carlo\" (--envmap-estimator monte_carlo) with " +
      bounds.autoSamples;
  }
  else if (transfer || estimator == EnvironmentEstimator::SphericalHarmonics)
  {
    // sh is nine coefficients, bands 0 to 2.
    bounds.irradianceError = largestComponent(color * intensity * shIrradianceErrorBound(*map, transfer ? shOrder : 2));
  }
  return bounds;
}
}
