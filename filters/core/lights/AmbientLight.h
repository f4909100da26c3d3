#pragma once
// docs/formulas.md sections 8.4 and 2: light arriving equally from all directions (La), which
// gives every vertex ka La.
#include "LightType.h"

namespace shadelab
{
struct AmbientLight
{
  Rgb color{ 1, 1, 1 };
  double intensity = 1.0;

  SHADELAB_LIGHT_TYPE(AmbientLight, Ambient, false, false);
};
}
