#include "ShRotation.h"

#include <stdexcept>
#include <string>

namespace shadelab
{
// L'_lm = integral of L(r^T w) Y_lm(w) dw = integral of L(u) Y_lm(r u) du, and Y_lm(r u) is a
// band-l function of u, so it is sum over m' of D_l[m][m'] Y_lm'(u) with D_l[m][m'] = integral of
// Y_lm(r u) Y_lm'(u) du. That integrand is a polynomial of degree 2l, which sphereQuadrature
// integrates exactly: the matrices come from the basis alone, without the recurrences of
// J. Ivanic and K. Ruedenberg ("Rotation Matrices for Real Spherical Harmonics. Direct
// Determination by Recursion", J. Phys. Chem. 100(15), 1996), to which they are equal.
ShRotation::ShRotation(int order, const glm::dmat3& rotation)
  : order_(order)
{
  requireShOrder(order, "ShRotation");
  const std::vector<SphereNode> nodes = sphereQuadrature(2 * order);
  std::vector<ShBasis> turned, plain;
  for (const SphereNode& node : nodes)
  {
    turned.push_back(shBasis(order, rotation * node.direction));
    plain.push_back(shBasis(order, node.direction));
  }
  matrices_.push_back(1.0); // band 0 is constant: turned, it is itself (4 pi Y00^2 could round)
  for (int l = 1; l <= order; ++l)
  {
    for (int m = -l; m <= l; ++m)
    {
      for (int n = -l; n <= l; ++n)
      {
        double sum = 0;
        for (std::size_t k = 0; k < nodes.size(); ++k)
        {
          sum += nodes[k].weight * turned[k][shIndex(l, m)] * plain[k][shIndex(l, n)];
        }
        matrices_.push_back(sum);
      }
    }
  }
}

ShCoefficients ShRotation::operator()(const ShCoefficients& coefficients) const
{
  if (coefficients.size() != std::size_t(shCount(order_)))
  {
    throw std::invalid_argument("ShRotation: " + std::to_string(coefficients.size()) + " coefficients for order " +
      std::to_string(order_) + ", which has " + std::to_string(shCount(order_)));
  }
  ShCoefficients result(coefficients.size(), Rgb(0.0));
  const double* matrix = matrices_.data();
  for (int l = 0; l <= order_; ++l)
  {
    const int width = 2 * l + 1;
    for (int row = 0; row < width; ++row)
    {
      for (int column = 0; column < width; ++column)
      {
        result[shIndex(l, -l) + row] += matrix[row * width + column] * coefficients[shIndex(l, -l) + column];
      }
    }
    matrix += width * width;
  }
  return result;
}
}
