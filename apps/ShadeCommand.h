#pragma once
// shadelab shade MESH --scene SCENE.json -o OUT.vtp: the mesh shaded under the scene, its
// per-vertex lighting terms written as point-data arrays (docs/guide/command-line.md).
#include "SceneOverrides.h"

#include <CLI/CLI.hpp>

#include <optional>
#include <string>

namespace shadelab::app
{
struct ShadeOptions
{
  std::string mesh;
  std::string scene;
  std::string output;
  std::string arrays = "default";
  std::string precision = "float32";
  std::string prefix;
  std::string compression = "lz4";
  bool rawAppended = false;
  double tolerance = 0;
  int threads = 0;
  bool keepNormals = false;
  bool noWeld = false;
  double featureAngle = 80;
  double weldTolerance = 0;
  std::optional<double> splitAngle; // split sharp edges at this angle before shading
  SceneOverrides overrides;         // --envmap and its settings, --shadows, --self-shadowing, --ambient-occlusion
  std::string colorBy;              // a point array that colours the material; empty: the scene's
  std::string colorMap = "cool to warm";
};

CLI::App* addShadeCommand(CLI::App& cli, ShadeOptions& options);

/// Exit code 0 done; throws UserError for bad input or a failed run.
int runShade(const ShadeOptions& options);
}
