#include "SphereIrradiance.h"

#include <algorithm>
#include <cmath>

namespace shadelab
{
double sphereProjectedSolidAngle(
  const glm::dvec3& centre, double radius, const glm::dvec3& point, const glm::dvec3& unitNormal)
{
  constexpr double pi = 3.14159265358979323846;
  const glm::dvec3 toCentre = centre - point;
  const double distance = vectorLength(toCentre);
  if (distance <= radius)
  {
    return pi;
  }
  // The sphere fills the cone of half-angle alpha, sin(alpha) = r/d, about the direction w to
  // its centre; beta is the angle between n and w.
  const glm::dvec3 w = unitVector(toCentre);
  const double sinAlpha = radius / distance;
  const double cosBeta = glm::dot(unitNormal, w);
  if (cosBeta >= sinAlpha) // wholly above the horizon: the point light's cosine law
  {
    return pi * cosBeta * sinAlpha * sinAlpha;
  }
  if (cosBeta <= -sinAlpha) // wholly below
  {
    return 0;
  }
  // Partly below: J. Snyder, "Area Light Sources for Real-Time Graphics", Microsoft Research
  // MSR-TR-96-11, 1996; S. Lagarde and C. de Rousiers, "Moving Frostbite to Physically Based
  // Rendering", SIGGRAPH 2014 course, section 4.7.2.2. With h = d/r, x = sqrt(h^2 - 1) and
  // y = -x cot(beta), the form factor F = P / pi is
  //   (cos(beta) acos(y) - x sin(beta) sqrt(1 - y^2)) / (pi h^2) + atan(sin(beta) sqrt(1 - y^2) / x) / pi.
  // y runs from -1 on the upper boundary (where this is pi cos(beta) / h^2) to 1 on the lower
  // (where it is 0), so the three cases join continuously. x is formed from (d - r)(d + r),
  // which keeps its digits for a point near the surface; y is clamped against rounding.
  const double h = distance / radius;
  const double x = std::sqrt((distance - radius) * (distance + radius)) / radius;
  const double sinBeta = vectorLength(glm::cross(unitNormal, w));
  const double y = std::clamp(-x * cosBeta / sinBeta, -1.0, 1.0);
  const double sinGamma = std::sqrt((1 - y) * (1 + y)); // sqrt(1 - y^2)
  return (cosBeta * std::acos(y) - x * sinBeta * sinGamma) / (h * h) + std::atan(sinBeta * sinGamma / x);
}
}
