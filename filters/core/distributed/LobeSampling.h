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
/// The density of a direction drawn about an axis in proportion to cos^eta, at a cosine to the
/// axis (above 1 by rounding: 1).
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

/// A direction drawn in proportion to the lobe, with the lobe and its density there.
struct LobeSample
{
  glm::dvec3 direction;
  LobeAtDirection lobe;
};

/// Draws directions in proportion to a vertex's lobe (lobe.wanted()) from points u of [0, 1)^2:
/// about the lobe's axis (Phong: the mirror of the viewer; Blinn-Phong: the normal, for h) with
/// cos = u.x^(1/(eta+1)) and the azimuth 2 pi u.y. The axis's frame is made once per vertex, and
/// a draw knows its lobe and density without a second power: u.x = cos^(eta+1), so cos^eta is
/// u.x / cos (as lobeWithDensity, to rounding).
class LobeDirections
{
public:
  LobeDirections(const LobeModel& lobe, const glm::dvec3& n, const glm::dvec3& v)
    : lobe_(lobe)
    , n_(n)
    , v_(v)
    , axis_(lobe.model == SpecularModel::Phong ? detail::mirrorOfViewer(n, v) : n)
    , cosineExponent_(1 / (lobe.eta + 1))
  {
    orthonormalBasis(axis_, t_, b_);
  }

  LobeSample operator()(const glm::dvec2& u) const
  {
    const double cosTheta = std::pow(u.x, cosineExponent_);
    const double sinTheta = std::sqrt(std::max(0.0, 1 - cosTheta * cosTheta));
    const double phi = 2 * samplePi * u.y;
    const glm::dvec3 aboutAxis = sinTheta * std::cos(phi) * t_ + sinTheta * std::sin(phi) * b_ + cosTheta * axis_;
    const double power = cosTheta > 0 ? std::min(u.x / cosTheta, 1.0) : specularLobe(true, 0.0, lobe_.eta);
    const double density = (lobe_.eta + 1) / (2 * samplePi) * power;
    if (lobe_.model == SpecularModel::Phong)
    {
      return { aboutAxis, { glm::dot(n_, aboutAxis) > 0 ? power : 0.0, cosTheta > 0 ? density : 0.0 } };
    }
    // Blinn-Phong: s is v reflected about h. Where v.h < 0 the half vector of s and v is -h,
    // below the surface: the lobe is its power of 0 there, but the density counts h.
    const double vDotH = glm::dot(v_, aboutAxis);
    const glm::dvec3 s = 2 * vDotH * aboutAxis - v_;
    const bool lit = vDotH != 0 && glm::dot(n_, s) > 0;
    const double lobe = vDotH > 0 ? power : specularLobe(true, 0.0, lobe_.eta);
    return { s, { lit ? lobe : 0.0, cosTheta > 0 && vDotH != 0 ? density / (4 * std::abs(vDotH)) : 0.0 } };
  }

private:
  const LobeModel& lobe_;
  glm::dvec3 n_, v_, axis_, t_, b_;
  double cosineExponent_;
};
}
