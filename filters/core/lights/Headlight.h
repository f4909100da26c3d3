#pragma once
// A distant light that travels along the viewer's line of sight (VTK's headlight,
// docs/vtk-renderer.md).
#include "LightType.h"

namespace shadelab
{
struct Headlight
{
  Rgb color{ 1, 1, 1 };
  double intensity = 1.0;

  SHADELAB_LIGHT_TYPE(Headlight, Local, false, true);
};
}
