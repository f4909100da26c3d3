#pragma once
// docs/formulas.md section 8.1: a light at infinite distance, with a constant direction and no
// attenuation (the sun; vtkLight with PositionalOff).
#include "LightType.h"

namespace shadelab
{
struct DistantLight
{
  glm::dvec3 direction{ 0, 0, -1 }; // the direction the light travels; s = -direction
  Rgb color{ 1, 1, 1 };
  double intensity = 1.0;
  /// docs/formulas.md section 8.1: the light's strength may be carried by the length of its
  /// direction vector. When set, intensity is multiplied by |direction|.
  bool intensityFromLength = false;

  SHADELAB_LIGHT_TYPE(DistantLight, Local, false, true);
};
}
