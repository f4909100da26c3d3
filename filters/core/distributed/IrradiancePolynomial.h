#pragma once
// An irradiance that is a quadratic polynomial of the normal, such as nine spherical-harmonic
// coefficients give (SphericalHarmonics.h). Apart, so that headers that carry one (the
// kernel's LightEvaluation.h) need no more of GLM than its vectors.
#include "Vec3.h"

namespace shadelab
{
/// R&H eq. 13 as the coefficients of a quadratic polynomial in the normal's components, so
/// that a vectorised loop can evaluate it (ShadingKernel):
/// E(n) = xx x^2 + yy y^2 + zz z^2 + xy x y + xz x z + yz y z + x x + y y + z z + constant.
struct IrradiancePolynomial
{
  Rgb xx{ 0.0 }, yy{ 0.0 }, zz{ 0.0 }, xy{ 0.0 }, xz{ 0.0 }, yz{ 0.0 }, x{ 0.0 }, y{ 0.0 }, z{ 0.0 }, constant{ 0.0 };

  Rgb operator()(const glm::dvec3& n) const
  {
    return xx * (n.x * n.x) + yy * (n.y * n.y) + zz * (n.z * n.z) + xy * (n.x * n.y) + xz * (n.x * n.z) +
      yz * (n.y * n.z) + x * n.x + y * n.y + z * n.z + constant;
  }
};
}
