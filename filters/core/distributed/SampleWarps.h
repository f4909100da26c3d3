#pragma once
// Warps of the unit square onto the shapes the Monte Carlo estimators sample, each with its
// source. They keep neighbouring strata of the square neighbours on the shape, so that
// stratification survives the warp.
#include "Vec3.h"

#include <glm/vec2.hpp>

#include <cmath>

namespace shadelab
{
constexpr double samplePi = 3.14159265358979323846;

/// (cos a, sin a) for |a| <= pi/4, by the Taylor series to degree 12 and 11, which err by less
/// than 1e-11 there (the first terms left out, (pi/4)^14 / 14! and (pi/4)^13 / 13!), far below
/// a float32 ray direction's resolution. The library's sincos took an eighth of the time of
/// ambient occlusion's rays (docs/dev/benchmarks.md); these are a dozen multiplications.
inline glm::dvec2 cosSinOfSmallAngle(double a)
{
  const double a2 = a * a;
  const double cosine = 1 -
    a2 * (1.0 / 2) *
      (1 -
        a2 * (1.0 / 12) *
          (1 - a2 * (1.0 / 30) * (1 - a2 * (1.0 / 56) * (1 - a2 * (1.0 / 90) * (1 - a2 * (1.0 / 132))))));
  const double sine = a *
    (1 -
      a2 * (1.0 / 6) * (1 - a2 * (1.0 / 20) * (1 - a2 * (1.0 / 42) * (1 - a2 * (1.0 / 72) * (1 - a2 * (1.0 / 110))))));
  return { cosine, sine };
}

/// Shirley and Chiu's concentric map of the square onto the unit disk ("A Low Distortion Map
/// Between Disk and Square", JGT 2(3), 1997): area-preserving.
inline glm::dvec2 concentricDisk(const glm::dvec2& u)
{
  const glm::dvec2 s = 2.0 * u - 1.0;
  // The angle is (pi/4) s.y/s.x where |s.x| is the larger, pi/2 - (pi/4) s.x/s.y where |s.y| is,
  // whose cosine and sine are the sine and cosine of (pi/4) s.x/s.y: one angle within pi/4.
  // Selects rather than branches, so that loops of samples vectorize; the centre, where both
  // are 0, has radius 0 and any angle.
  const bool xMajor = std::abs(s.x) > std::abs(s.y);
  const double r = xMajor ? s.x : s.y;
  const double ratio = r != 0 ? (xMajor ? s.y : s.x) / r : 0.0;
  const glm::dvec2 cs = cosSinOfSmallAngle((samplePi / 4) * ratio);
  return xMajor ? r * cs : r * glm::dvec2(cs.y, cs.x);
}

/// A direction and 1 / its pdf in solid angle: the weight of a Monte Carlo sample.
struct WeightedDirection
{
  glm::dvec3 direction{ 0.0 };
  double weight = 0;
};

/// Cosine-weighted about unit n, pdf cos / pi (Malley's method: the concentric disk lifted to
/// the hemisphere). Estimates E from a constant radiance L exactly: every sample is pi L.
inline WeightedDirection cosineWeightedDirection(const glm::dvec3& n, const glm::dvec2& u)
{
  glm::dvec3 t, b;
  orthonormalBasis(n, t, b);
  const glm::dvec2 disk = concentricDisk(u);
  const double cosTheta = std::sqrt(std::max(0.0, 1 - glm::dot(disk, disk)));
  return { disk.x * t + disk.y * b + cosTheta * n, cosTheta > 0 ? samplePi / cosTheta : 0.0 };
}

/// Uniform over the cone about unit axis whose half-angle has 1 - cos = oneMinusCosMax (pbrt-v4
/// SampleUniformCone), pdf 1 / (2 pi (1 - cos theta_max)). oneMinusCosMax is passed rather than
/// the cosine so that a small cone keeps its digits.
inline WeightedDirection uniformConeDirection(const glm::dvec3& axis, double oneMinusCosMax, const glm::dvec2& u)
{
  glm::dvec3 t, b;
  orthonormalBasis(axis, t, b);
  const double cosTheta = 1 - u.x * oneMinusCosMax;
  const double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
  const double phi = 2 * samplePi * u.y;
  return { sinTheta * std::cos(phi) * t + sinTheta * std::sin(phi) * b + cosTheta * axis,
    2 * samplePi * oneMinusCosMax };
}

/// A uniform point on triangle (a, b, c) (the square-root warp, G. Turk, "Generating Random
/// Points in Triangles", Graphics Gems, 1990).
inline glm::dvec3 pointOnTriangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, const glm::dvec2& u)
{
  const double root = std::sqrt(u.x);
  return (1 - root) * a + root * (1 - u.y) * b + root * u.y * c;
}

/// Points first .. first + count - 1 of a sample sequence (anything with points(first, count,
/// x, y), SampleSequence.h) warped by warp(u) onto a shape or directions, into x[], y[], z[]:
/// arrays of coordinates, so that the loop vectorizes where the warp has no branches.
template<typename Points, typename Warp>
void warpedPoints(const Points& points, int first, int count, Warp warp, double* x, double* y, double* z)
{
  points.points(first, count, x, y);
  for (int j = 0; j < count; ++j)
  {
    const glm::dvec3 p = warp(glm::dvec2(x[j], y[j]));
    x[j] = p.x;
    y[j] = p.y;
    z[j] = p.z;
  }
}
}
