#pragma once
// docs/formulas.md sections 8.2 and 9: a local light radiating equally in all directions,
// fading with distance.
#include "LightType.h"

namespace shadelab
{
struct PointLight
{
  glm::dvec3 position{ 0, 0, 0 };
  Rgb color{ 1, 1, 1 };
  double intensity = 1.0;
  Attenuation attenuation;

  SHADELAB_LIGHT_TYPE(PointLight, Local, true, true);
};
}
