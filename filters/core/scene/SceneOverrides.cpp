#include "SceneOverrides.h"

#include "JsonNode.h"
#include "LightFields.h"
#include "SceneFile.h"

#include <vector>

namespace shadelab
{
namespace
{
/// A count of samples as an option gives it, "auto" or a whole number, as a scene file writes it.
Json sampleCountJson(const std::string& count)
{
  return count == "auto" ? Json(count) : Json(std::stoi(count));
}

/// The --envmap light as a scene file's light object, for the environment light's own reader.
Json environmentLightJson(const EnvironmentMapOverride& environment)
{
  Json light = { { "type", EnvironmentLight::sceneFileTypes().front().name }, { "file", environment.file },
    { "rotation", environment.rotation }, { "intensity", environment.intensity } };
  if (!environment.estimator.empty())
  {
    light["estimator"] = environment.estimator;
  }
  if (!environment.directions.empty())
  {
    light["directions"] = environment.directions;
  }
  if (environment.order != 0)
  {
    light["order"] = environment.order;
  }
  if (!environment.samples.empty())
  {
    light["samples"] = sampleCountJson(environment.samples);
  }
  return light;
}

/// A problem the scene file's readers found in an override, said of its option. CLI11 has
/// checked each option's value alone, which leaves the map's file and the settings that depend
/// on the estimator: for those two rules the remedy is an option to leave out.
std::string optionProblem(const JsonError& error, const SceneOverrides& overrides)
{
  if (error.path == "/order")
  {
    return "--envmap-order: only --envmap-estimator prt has an order";
  }
  if (error.path == "/directions")
  {
    return "--envmap-directions " + overrides.environment.directions +
      ": prt draws its shadow rays by the cosine, the density its transfer vectors are estimated for: leave "
      "--envmap-directions out";
  }
  if (error.path.rfind("/ambient_occlusion", 0) == 0)
  {
    return "--ambient-occlusion " + overrides.ambientOcclusion + ": " + error.message;
  }
  if (error.path.rfind("/interreflection", 0) == 0)
  {
    return "--bounces " + overrides.bounces + ": " + error.message;
  }
  // The map's file says its own problem; any other field is named by its JSON pointer.
  return "--envmap: " + (error.path == "/file" ? "" : error.path + ": ") + error.message;
}

/// The --envmap light added to the scene, read by the environment light's own reader and then
/// checked with the scene.
void addEnvironmentLight(Scene& scene, const EnvironmentMapOverride& environment, const std::string& sceneName)
{
  for (const NamedLight& light : scene.lights)
  {
    if (light.name == environment.name)
    {
      throw SceneOverrideError("--envmap: " + sceneName + " already has a light named '" + environment.name +
        "', the name --envmap gives its light: rename that light");
    }
  }
  // Read relative to the working folder: no scene file holds it.
  const Json light = environmentLightJson(environment);
  scene.lights.push_back({ environment.name, readLightSource(JsonNode(light, ""), "") });
  const std::vector<SceneProblem> problems = sceneProblems(scene);
  if (!problems.empty())
  {
    throw SceneOverrideError("--envmap: " + problems.front().message);
  }
}

/// --ambient-occlusion's rays in place of the scene's "rays", read as a scene file's are; the
/// scene's other occlusion settings stay.
void overrideOcclusionRays(Scene& scene, const std::string& rays)
{
  AmbientOcclusion occlusion = scene.ambientOcclusion.value_or(AmbientOcclusion{});
  occlusion.sampling.fromTolerance = false; // a number replaces the scene's "auto"
  const Json given = { { "rays", sampleCountJson(rays) } };
  readSampleCount(JsonNode(given, "/ambient_occlusion"), "rays", "max_rays", occlusion.sampling);
  scene.ambientOcclusion = occlusion;
}

/// --bounces in place of the scene's "bounces", read as a scene file's are; the scene's other
/// interreflection settings stay.
void overrideBounces(Scene& scene, const std::string& bounces)
{
  Interreflection interreflection = scene.interreflection.value_or(Interreflection{});
  const Json given = { { "bounces", sampleCountJson(bounces) } };
  readBounces(JsonNode(given, "/interreflection").at("bounces"), interreflection);
  // The command has no option for the gather's rays: "auto" bounces take them from the tolerance too.
  interreflection.sampling.fromTolerance =
    interreflection.sampling.fromTolerance || interreflection.bouncesFromTolerance;
  scene.interreflection = interreflection.bounces > 0 ? std::optional(interreflection) : std::nullopt;
}

/// --shadows, --self-shadowing, --ambient-occlusion and --bounces.
void overrideVisibility(Scene& scene, const SceneOverrides& overrides)
{
  for (NamedLight& light : scene.lights)
  {
    light.shadows = light.shadows || (overrides.shadows && castsShadows(light.source));
  }
  for (const auto& [name, selfShadowing] : selfShadowingNames)
  {
    scene.selfShadowing = overrides.selfShadowing == name ? selfShadowing : scene.selfShadowing;
  }
  if (!overrides.ambientOcclusion.empty())
  {
    overrideOcclusionRays(scene, overrides.ambientOcclusion);
  }
  if (!overrides.bounces.empty())
  {
    overrideBounces(scene, overrides.bounces);
  }
}
}

Scene withOverrides(Scene scene, const SceneOverrides& overrides, const std::string& sceneName)
{
  try
  {
    if (!overrides.environment.file.empty())
    {
      addEnvironmentLight(scene, overrides.environment, sceneName);
    }
    overrideVisibility(scene, overrides);
  }
  catch (const JsonError& error)
  {
    throw SceneOverrideError(optionProblem(error, overrides));
  }
  return scene;
}
}
