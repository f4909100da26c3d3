#pragma once
// Turning a radiance given by its spherical-harmonic coefficients: a rotation maps each band
// onto itself (the bands are the rotation group's irreducible representations), so the
// coefficients of the turned radiance are, band by band, a (2l + 1) x (2l + 1) matrix times
// the band's coefficients. Relighting a mesh's transfer vectors under a turned map needs only
// this, not the map projected again (docs/formulas.md section 12.8).
#include "SphericalHarmonics.h"

#include <glm/mat3x3.hpp>

#include <vector>

namespace shadelab
{
/// The matrices of bands 0 to order for one rotation.
class ShRotation
{
public:
  /// For the radiance turned by `rotation` (orthogonal): L'(w) = L(r^T w). Throws
  /// std::invalid_argument for an order outside 0 to largestShOrder.
  ShRotation(int order, const glm::dmat3& rotation);

  int order() const { return order_; }
  /// The coefficients of the turned radiance, from shCount(order()) coefficients.
  ShCoefficients operator()(const ShCoefficients& coefficients) const;

private:
  int order_;
  /// Band l's matrix D_l, row-major, after the bands before it: D_l[m][m'] is the integral of
  /// Y_lm(r u) Y_lm'(u) over the sphere.
  std::vector<double> matrices_;
};
}
