#pragma once
// The scene as shadelab shade's options change it: the --envmap light added, --shadows,
// --self-shadowing, --ambient-occlusion and --bounces, in one step. Each setting is read by the scene
// file's own code (the --envmap light as a scene file's light object), so that the names and
// rules exist once; a problem is said in the options' words.
#include "Scene.h"

#include <stdexcept>
#include <string>

namespace shadelab
{
/// `--envmap FILE` and its settings: an environment light added to the scene. The texts are
/// those of an environment light's fields in a scene file; "" (or order 0): the light's default.
struct EnvironmentMapOverride
{
  std::string file; // "": no --envmap
  std::string name = "envmap";
  std::string estimator;  // a name of environmentEstimatorNames
  std::string directions; // a name of environmentDirectionNames (prt takes only cosine)
  int order = 0;          // prt's highest band
  double rotation = 0;
  double intensity = 1;
  std::string samples; // per vertex: a whole number, or "auto" (as many as a tolerance needs)
};

/// What the command line changes in the scene it shades.
struct SceneOverrides
{
  EnvironmentMapOverride environment;
  bool shadows = false;         // every light that can cast shadows casts them
  std::string selfShadowing;    // a name of selfShadowingNames; "": as the scene says
  std::string ambientOcclusion; // rays per vertex, or "auto"; "": as the scene says
  std::string bounces;          // interreflection's bounces; "": as the scene says
};

/// A setting that cannot be applied; what() is one line that starts with the option's name
/// ("--envmap-order: ...").
class SceneOverrideError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// The scene with the overrides applied: the --envmap light added (read and checked as a scene
/// file's, its name free in the scene, which sceneName names in messages), then the shadows,
/// self-shadowing, ambient occlusion's rays and interreflection's bounces (the scene's other
/// interreflection settings, or their defaults). Throws SceneOverrideError.
Scene withOverrides(Scene scene, const SceneOverrides& overrides, const std::string& sceneName);
}
