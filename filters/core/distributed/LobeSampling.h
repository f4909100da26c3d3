#pragma once
// Directions drawn in proportion to the specular lobe (docs/formulas.md sections 4, 5 and
// 13.3), for Monte Carlo estimates of S = integral of L lobe dw where L is smooth and the lobe
// sharp. The lobe is a cosine power about an axis, whose normalised density is
// (eta + 1) / (2 pi) cos^eta (Phong's lobe as a distribution: E. Lafortune and Y. Willems,
// "Using the Modified Phong Reflectance Model for Physically Based Rendering", 1994; pbrt-v3
// section 14.1.1 for the half-vector form).
#include "DistributedLight.h"
#include "SampleWarps.h"

#include <cmath>

namespace shadelab
{
namespace detail
{
/// A direction about unit axis with density (eta + 1) / (2 pi) cos^eta: cos = u.x^(1/(eta+1)).
inline glm::dvec3 cosinePowerDirection(const glm::dvec3& axis, double eta, const glm::dvec2& u)
{
  glm::dvec3 t, b;
  orthonormalBasis(axis, t, b);
  const double cosTheta = std::pow(u.x, 1 / (eta + 1));
  const double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
  const double phi = 2 * samplePi * u.y;
  return sinTheta * std::cos(phi) * t + sinTheta * std::sin(phi) * b + cosTheta * axis;
}

/// The density of cosinePowerDirection at a cosine to the axis (above 1 by rounding: 1).
inline double cosinePowerDensity(double cosine, double eta)
{
  return cosine > 0 ? (eta + 1) / (2 * samplePi) * std::pow(std::min(cosine, 1.0), eta) : 0.0;
}

/// Phong's lobe max(0, r.v)^eta, r the mirror of s, is max(0, s.m)^eta about m, the mirror of v.
inline glm::dvec3 mirrorOfViewer(const glm::dvec3& n, const glm::dvec3& v)
{
  return 2 * glm::dot(n, v) * n - v;
}
}

/// The density in solid angle with which lobeDirection draws s.
inline double lobeDensity(const LobeModel& lobe, const glm::dvec3& n, const glm::dvec3& v, const glm::dvec3& s)
{
  if (lobe.model == SpecularModel::Phong)
  {
    return detail::cosinePowerDensity(glm::dot(s, detail::mirrorOfViewer(n, v)), lobe.eta);
  }
  // Blinn-Phong: h is drawn about n, s = reflect(v, h), and dw_s = 4 |v.h| dw_h. The h that
  // gives s is +-(s + v)/|s + v|, the sign that faces n (where v.h < 0 it is the sign that makes
  // the lobe 0 there, but the density must count it).
  glm::dvec3 h;
  if (!halfVector(s, v, h))
  {
    return 0;
  }
  h = glm::dot(n, h) < 0 ? -h : h;
  const double vDotH = std::abs(glm::dot(v, h));
  return vDotH > 0 ? detail::cosinePowerDensity(glm::dot(n, h), lobe.eta) / (4 * vDotH) : 0.0;
}

/// The lobe at s, lobe(n, s, v), and the density lobeDensity(lobe, n, v, s), found together.
struct LobeAtDirection
{
  double value, density;
};

/// lobe(n, s, v) and lobeDensity(lobe, n, v, s), the same bits: Blinn-Phong's two share their
/// half vector and, where n.h > 0, their power (the power is most of either's cost).
inline LobeAtDirection lobeWithDensity(
  const LobeModel& lobe, const glm::dvec3& n, const glm::dvec3& v, const glm::dvec3& s)
{
  glm::dvec3 h;
  if (lobe.model == SpecularModel::Phong || !halfVector(s, v, h))
  {
    return { lobe(n, s, v), lobeDensity(lobe, n, v, s) };
  }
  const double cosine = glm::dot(n, h);
  const bool lit = glm::dot(n, s) > 0;
  if (!(cosine > 0))
  {
    return { specularLobe(lit, cosine, lobe.eta), lobeDensity(lobe, n, v, s) };
  }
  const double power = std::pow(std::min(cosine, 1.0), lobe.eta); // as specularLobe and cosinePowerDensity clamp it
  const double vDotH = std::abs(glm::dot(v, h));
  return { lit ? power : 0.0, vDotH > 0 ? (lobe.eta + 1) / (2 * samplePi) * power / (4 * vDotH) : 0.0 };
}

/// A direction drawn in proportion to the lobe (lobe.wanted()), from u in [0, 1)^2.
inline glm::dvec3 lobeDirection(const LobeModel& lobe, const glm::dvec3& n, const glm::dvec3& v, const glm::dvec2& u)
{
  if (lobe.model == SpecularModel::Phong)
  {
    return detail::cosinePowerDirection(detail::mirrorOfViewer(n, v), lobe.eta, u);
  }
  const glm::dvec3 h = detail::cosinePowerDirection(n, lobe.eta, u);
  return 2 * glm::dot(v, h) * h - v;
}
}
