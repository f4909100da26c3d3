#pragma once
// A picture of one array on a mesh, rendered off screen to PNG.
#include "Scene.h"

#include "vtkPolyData.h"

#include <optional>
#include <string>

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
};

/// Renders `array` of mesh to a PNG. A 3-component array is drawn as RGB colours, clamped to
/// [0, 1], with VTK's lighting off: the picture shows ShadeLab's shading, not VTK's. A
/// 1-component array is drawn through a diverging colour map with a labelled scalar bar.
/// Needs an X display (run under xvfb-run on a headless machine). Writes through a temporary
/// file. Throws UserError.
void renderToPng(vtkPolyData* mesh, const std::string& meshName, const RenderOptions& options,
  const std::string& pngFile);
}
