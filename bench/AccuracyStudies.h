#pragma once
// `shadelab-bench --charts DIR`: each method's error against its time, as PNG charts and one
// CSV, including every method at the point where it fails.
#include <string>
#include <vector>

namespace shadelab::app
{
struct AccuracyOptions
{
  std::string directory;
  std::string bunnyFile;
  int maxRepeats = 9;
  /// Where the area-light study finds its softbox and material, and where the map studies
  /// find venice_sunset_1k.hdr and studio_small_03_1k.hdr.
  std::string areaLightScene = "data/scenes/area_lights.json";
  std::string envmapFolder = "data/envmaps";
  /// Only the studies whose names contain one of these (all when empty).
  std::vector<std::string> studyFilters;
};

/// Runs the studies (arithmetic and pow, pow over eta, a point light as distant, Phong against
/// Blinn-Phong, tessellation, an area light's estimators with and without its shadows, two
/// environment maps' estimators and one's with its shadows, a tolerance's predicted errors
/// against measured ones, a texture at vertices), the failure points and the speed requirements of the SH estimator;
/// writes accuracy.csv and one PNG per study into the directory. Needs an X display for the charts. Throws UserError.
void runAccuracyStudies(const AccuracyOptions& options);
}
