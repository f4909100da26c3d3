// The command line's changes to a scene (SceneOverrides): read by the scene file's own code,
// their problems said in the options' words.
#include "EnvironmentMap.h"
#include "SceneFile.h"
#include "SceneOverrides.h"
#include "TestPaths.h"

#include <gtest/gtest.h>

#include <string>

namespace
{
using namespace shadelab;

const std::string sunset = shadelab::testing::sourcePath("data/envmaps/venice_sunset_1k.hdr");

/// The message withOverrides throws, or "" where it does not.
std::string problemOf(const Scene& scene, const SceneOverrides& overrides)
{
  try
  {
    withOverrides(scene, overrides, "scene.json");
  }
  catch (const SceneOverrideError& error)
  {
    return error.what();
  }
  return "";
}

TEST(SceneOverrides, TheMapIsAddedAsTheSceneFileWouldReadIt)
{
  SceneOverrides overrides;
  overrides.environment.file = sunset;
  overrides.environment.estimator = "monte_carlo";
  overrides.environment.directions = "mis";
  overrides.environment.rotation = 30;
  overrides.environment.intensity = 2;
  overrides.environment.samples = "auto";
  const Scene scene = withOverrides(Scene{}, overrides, "");
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].name, "envmap");
  const auto& map = std::get<EnvironmentLight>(scene.lights[0].source);
  EXPECT_EQ(map.estimator, EnvironmentEstimator::MonteCarlo);
  EXPECT_EQ(map.directions, EnvironmentDirections::Mis);
  EXPECT_EQ(map.rotationDegrees, 30);
  EXPECT_EQ(map.intensity, 2);
  EXPECT_TRUE(map.sampling.fromTolerance);
  ASSERT_NE(map.map, nullptr);
  EXPECT_EQ(map.map->width, 1024);
}

TEST(SceneOverrides, VisibilityOptionsReplaceTheScenes)
{
  const Scene scene = parseScene(R"({
    "lights": [ { "name": "key", "type": "point", "position": [0, 2, 0] }, { "type": "ambient" } ],
    "ambient_occlusion": { "rays": "auto", "max_rays": 512 },
    "self_shadowing": "facets"
  })",
    "");
  SceneOverrides overrides;
  overrides.shadows = true;
  overrides.selfShadowing = "smooth";
  overrides.ambientOcclusion = "64";
  const Scene changed = withOverrides(scene, overrides, "");
  EXPECT_TRUE(changed.lights[0].shadows);
  EXPECT_FALSE(changed.lights[1].shadows); // an ambient light casts none
  EXPECT_EQ(changed.selfShadowing, SelfShadowing::SmoothSurface);
  ASSERT_TRUE(changed.ambientOcclusion);
  EXPECT_FALSE(changed.ambientOcclusion->sampling.fromTolerance);
  EXPECT_EQ(changed.ambientOcclusion->sampling.samples, 64);
  EXPECT_EQ(changed.ambientOcclusion->sampling.maximum, 512); // the scene's other settings stay
  // Nothing given: the scene as it was.
  const Scene same = withOverrides(scene, SceneOverrides{}, "");
  EXPECT_FALSE(same.lights[0].shadows);
  EXPECT_EQ(same.selfShadowing, SelfShadowing::Facets);
  EXPECT_TRUE(same.ambientOcclusion->sampling.fromTolerance);
}

// --bounces auto: the bounces and, as the command has no option for them, the gather's rays
// from the tolerance; the scene's other interreflection settings stay. A number replaces "auto".
TEST(SceneOverrides, AutoBouncesTakeTheGathersRaysFromTheToleranceToo)
{
  const Scene scene =
    parseScene(R"({ "lights": [], "interreflection": { "bounces": 2, "samples": 32, "stratified": false } })", "");
  SceneOverrides overrides;
  overrides.bounces = "auto";
  const Scene automatic = withOverrides(scene, overrides, "");
  EXPECT_TRUE(automatic.interreflection->bouncesFromTolerance);
  EXPECT_TRUE(automatic.interreflection->sampling.fromTolerance);
  EXPECT_EQ(automatic.interreflection->sampling.samples, 32); // the first run's
  EXPECT_FALSE(automatic.interreflection->sampling.stratified);
  overrides.bounces = "3";
  const Scene fixed = withOverrides(automatic, overrides, "");
  EXPECT_FALSE(fixed.interreflection->bouncesFromTolerance);
  EXPECT_EQ(fixed.interreflection->bounces, 3);
}

TEST(SceneOverrides, ProblemsAreSaidInTheOptionsWords)
{
  SceneOverrides order;
  order.environment.file = sunset;
  order.environment.order = 3;
  EXPECT_EQ(problemOf(Scene{}, order), "--envmap-order: only --envmap-estimator prt has an order");

  SceneOverrides directions;
  directions.environment.file = sunset;
  directions.environment.estimator = "prt";
  directions.environment.directions = "mis";
  EXPECT_EQ(problemOf(Scene{}, directions),
    "--envmap-directions mis: prt draws its shadow rays by the cosine, the density its transfer vectors are "
    "estimated for: leave --envmap-directions out");

  Scene named;
  named.lights.push_back({ "envmap", AmbientLight{} });
  SceneOverrides clash;
  clash.environment.file = sunset;
  EXPECT_EQ(problemOf(named, clash),
    "--envmap: scene.json already has a light named 'envmap', the name --envmap gives its light: rename that light");

  SceneOverrides missing;
  missing.environment.file = "no_such_map.hdr";
  EXPECT_EQ(problemOf(Scene{}, missing).rfind("--envmap: ", 0), 0u) << problemOf(Scene{}, missing);
  EXPECT_NE(problemOf(Scene{}, missing).find("no_such_map.hdr"), std::string::npos) << problemOf(Scene{}, missing);
}
}
