#pragma once
// How spherical-harmonic expansions to a band are laid out (SphericalHarmonics.h). Apart from
// it so that the per-vertex terms (DistributedLight.h) can hold a transfer vector without
// including glm's matrices, on which VTK 9.1's wrapping tools do not finish.
#include <array>

namespace shadelab
{
/// The highest band of a general expansion (precomputed radiance transfer's orders 2 to 4).
constexpr int largestShOrder = 4;
/// How many coefficients an expansion to band `order` holds: (order + 1)^2.
constexpr int shCount(int order)
{
  return (order + 1) * (order + 1);
}
/// Where Y_lm stands in an expansion: l (l + 1) + m.
constexpr int shIndex(int l, int m)
{
  return l * (l + 1) + m;
}

/// The order whose expansion has `count` coefficients ((order + 1)^2, order 0 to
/// largestShOrder), or -1 where no order has that many.
constexpr int shOrderOfCount(int count)
{
  for (int order = 0; order <= largestShOrder; ++order)
  {
    if (shCount(order) == count)
    {
      return order;
    }
  }
  return -1;
}

/// Y_lm of bands 0 to largestShOrder at shIndex(l, m).
using ShBasis = std::array<double, shCount(largestShOrder)>;
}
