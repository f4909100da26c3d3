#include "MetallicRoughness.h"

#include <algorithm>

namespace shadelab
{
LectureCoefficients lectureCoefficients(const Rgb& baseColor, double metallic, double roughness)
{
  metallic = std::clamp(metallic, 0.0, 1.0);
  const double alpha = std::pow(std::clamp(roughness, 0.03, 1.0), 2);
  LectureCoefficients c;
  c.kd = baseColor * (1 - metallic);
  c.ks = Rgb(0.04) * (1 - metallic) + baseColor * metallic;
  c.shininess = 2 / (alpha * alpha) - 2;
  return c;
}
}
