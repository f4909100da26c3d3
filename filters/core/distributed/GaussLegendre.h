#pragma once
// Gauss-Legendre quadrature on [-1, 1]: n nodes integrate every polynomial of degree up to
// 2n - 1 exactly. Used for the rim of a disk light (DiskIrradiance.cpp) and for exact rules on
// the sphere (sphereQuadrature).
#include <vector>

namespace shadelab
{
struct GaussLegendreRule
{
  std::vector<double> nodes;   // from the largest down: the first n / 2 are the positive ones
  std::vector<double> weights; // of the nodes
};

/// The nodes are the roots of the Legendre polynomial P_n, found by Newton's method from
/// Tricomi's estimate cos(pi (i + 3/4) / (n + 1/2)), and the weights 2 / ((1 - x^2) P_n'(x)^2)
/// (Abramowitz and Stegun 25.4.29). n >= 1.
GaussLegendreRule gaussLegendreRule(int n);
}
