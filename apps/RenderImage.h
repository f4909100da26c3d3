#pragma once
// A picture of one array on a mesh, rendered off screen to PNG.
#include "Scene.h"

#include "vtkPolyData.h"

#include <optional>
#include <string>
#include <vector>

namespace shadelab::app
{
struct RenderOptions
{
  std::string array = "total";
  int width = 800;
  int height = 600;
  /// Where the camera is; without one the mesh is framed looking down -z.
  std::optional<Viewer> viewer;
  /// Encode a 3-component array's linear values for display by the sRGB transfer function, as
  /// a renderer's output is: a shaded scan then shows its own colours.
  bool srgb = false;
  /// Multiplies a 3-component array's values before they are drawn (and clipped to [0, 1]).
  double exposure = 1;
};

/// Renders `array` of mesh to a PNG. A 3-component array is drawn as RGB colours (8-bit ones
/// as fractions of 255) times the exposure, clipped to [0, 1], with VTK's lighting off: the
/// picture shows ShadeLab's shading, not VTK's. A 1-component array is drawn through a colour
/// table with a legend beside the mesh: a flags array (shading_flags, visibility_flags) and an
/// integer array of a few values as categories, each in a colour of its own and named; any
/// other through a diverging colour map with a labelled bar. Needs an X display (run under
/// xvfb-run on a headless machine). Writes through a temporary file. Returns notes for the
/// user on what the picture does not show as it is (values drawn clipped), one line each.
/// Throws UserError.
std::vector<std::string> renderToPng(
  vtkPolyData* mesh, const std::string& meshName, const RenderOptions& options, const std::string& pngFile);
}
