#pragma once
// docs/formulas.md sections 8.3 and 10: a point light that emits only inside a cone around its
// axis.
#include "LightType.h"

namespace shadelab
{
struct SpotLight
{
  glm::dvec3 position{ 0, 0, 0 };
  glm::dvec3 axis{ 0, 0, -1 }; // the direction the cone points
  Rgb color{ 1, 1, 1 };
  double intensity = 1.0;
  Attenuation attenuation;
  SpotCone cone;

  SHADELAB_LIGHT_TYPE(SpotLight, Local, true, true);
};
}
