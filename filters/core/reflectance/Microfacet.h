#pragma once
// The microfacet terms of VTK 9.1's PBR shader (docs/vtk-renderer.md section 11), written as
// VTK's Rendering/OpenGL2/glsl/vtkPBRFunctions.glsl computes them at tag v9.1.0, so that the
// vtk_pbr model gives what VTK draws. The forms are GGX's distribution (Walter, Marschner, Li
// and Torrance, "Microfacet Models for Refraction through Rough Surfaces", EGSR 2007), the
// height-correlated Smith visibility (Heitz, "Understanding the Masking-Shadowing Function in
// Microfacet-Based BRDFs", JCGT 3(2), 2014) and Schlick's Fresnel ("An Inexpensive BRDF Model
// for Physically-based Rendering", Eurographics 1994), as Karis ("Real Shading in Unreal
// Engine 4", SIGGRAPH 2013) and Filament's documentation arrange them.
#include "Material.h"
#include "Precision.h"
#include "Vec3.h"

#include <algorithm>
#include <cmath>

namespace shadelab
{
/// VTK's pi (vtkPBRFunctions.glsl), kept to its digits: the shader's constant, not M_PI.
template<typename T>
constexpr T vtkPi = T(3.14159265359);

/// And its 1/pi, which the Lambert term multiplies by.
constexpr double vtkReciprocalPi = 0.31830988618;

/// The shader clamps every cosine (n.v, n.s, n.h, h.s) to [1e-5, 1]: a light behind the surface
/// still adds its term at a cosine of 1e-5, and a grazing viewer divides by no less than it.
template<typename T>
T vtkClampedCosine(T cosine)
{
  return std::clamp(cosine, T(1e-5), T(1));
}

/// D, GGX's distribution of normals at n.h, with alpha = roughness^2:
/// D = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2). At roughness 1 it is 1/pi everywhere; as
/// the roughness falls to 0 it narrows to a peak of 1 / (pi roughness^4) at n.h = 1. The
/// denominator's base is summed as (1 - n.h)(1 + n.h) + (n.h)^2 alpha^2, where VTK's
/// (n.h alpha^2 - n.h) n.h + 1 cancels digits near n.h = 1 (tests/test_microfacet.cpp): in
/// float32 at roughness 0.013 and below, where alpha^2 - 1 rounds to -1, it gives Inf at n.h = 1.
template<typename T>
T ggxDistribution(T nDotH, T roughness)
{
  const T alpha = roughness * roughness;
  const T alpha2 = alpha * alpha;
  const T d = (T(1) - nDotH) * (T(1) + nDotH) + nDotH * nDotH * alpha2;
  return alpha2 / (vtkPi<T> * d * d);
}

/// V = G / (4 (n.s)(n.v)), the height-correlated Smith masking and shadowing divided by the
/// BRDF's denominator, as VTK 9.1 computes it. VTK passes the roughness where Heitz's form has
/// alpha, so that V uses alpha = roughness while D uses roughness^2 (docs/vtk-renderer.md
/// section 11.3): V = 0.5 / ((n.s) sqrt(r^2 + (n.v)^2 (1 - r^2)) + (n.v) sqrt(r^2 + (n.s)^2 (1 - r^2))).
template<typename T>
T smithCorrelatedVisibility(T nDotV, T nDotL, T roughness)
{
  const T r2 = roughness * roughness;
  const T viewSide = nDotL * std::sqrt(r2 + nDotV * (nDotV - r2 * nDotV));
  const T lightSide = nDotV * std::sqrt(r2 + nDotL * (nDotL - r2 * nDotL));
  return T(0.5) / (viewSide + lightSide);
}

/// Schlick's Fresnel at h.s for one channel: F = F0 + (F90 - F0) (1 - h.s)^5.
template<typename T>
T schlickFresnel(T f0, T f90, T hDotL)
{
  const T m = T(1) - hDotL;
  const T m2 = m * m;
  return f0 + (f90 - f0) * (m2 * m2 * m);
}

/// The base layer's reflectance at normal incidence, ((ior - 1) / (ior + 1))^2 (0.04 at ior 1.5;
/// vtkProperty::ComputeReflectanceOfBaseLayer, with no coat).
inline double dielectricReflectance(double baseIor)
{
  return std::pow((baseIor - 1.0) / (baseIor + 1.0), 2.0);
}

/// F0, the reflectance at normal incidence: the dielectric's (dielectricReflectance) mixed
/// toward the base colour by the metallic factor. This form takes a base colour of its own (a
/// vertex's, VTK's scalar colouring).
inline Rgb reflectanceAtNormalIncidence(double dielectric, double metallic, const Rgb& baseColor)
{
  return (1.0 - metallic) * Rgb(dielectric) + metallic * baseColor;
}

/// F0 of the material's own base colour.
inline Rgb reflectanceAtNormalIncidence(const MicrofacetMaterial& m)
{
  return reflectanceAtNormalIncidence(dielectricReflectance(m.baseIor), m.metallic, m.baseColor);
}

/// F90, the reflectance at grazing incidence: 1 for any F0 whose channels sum to 1/16.5 or more
/// (VTK's "specular occlusion", which darkens only an F0 below about 0.02), mixed toward the edge
/// tint by the metallic factor.
inline Rgb reflectanceAtGrazingIncidence(double metallic, const Rgb& edgeTint, const Rgb& f0)
{
  const double f90 = std::clamp(50.0 * 0.33 * (f0.x + f0.y + f0.z), 0.0, 1.0);
  return (1.0 - metallic) * Rgb(f90) + metallic * edgeTint;
}

/// F90 of the material's own metallic factor.
inline Rgb reflectanceAtGrazingIncidence(const MicrofacetMaterial& m, const Rgb& f0)
{
  return reflectanceAtGrazingIncidence(m.metallic, m.edgeTint, f0);
}

/// D's relative error in float32 at its peak: n.h carries about one rounding, 2^-24, and the
/// peak's denominator 1 - (n.h)^2 (1 - alpha^2) is alpha^2 = r^4 there, so D errs by about
/// 4 x 2^-24 / r^4 (measured on the bunny under a light at the eye: 2.4e-3 at roughness 0.1,
/// 3.8e-2 at 0.05, as predicted).
inline double float32DistributionError(double roughness)
{
  return 4.0 * 0x1p-24 / std::pow(roughness, 4.0);
}

/// The smallest roughness an array may give in each precision, which the scene's overflow
/// checks bound D's peak with: in float32, just below the smallest that float32 shades to 1%
/// (float32DistributionError is 0.01 at 0.06988); in float64, where r^4 would underflow long
/// before, one whose peak 1/(pi r^4), 3e23, leaves the check its range.
inline double smallestArrayRoughness(Precision precision)
{
  return precision == Precision::Float32 ? 0.0698 : 1e-6;
}

/// The largest value the specular factor D V F (n.s) can take for a roughness in (0, 1]: D is
/// at most 1 / (pi r^4), V (n.s) at most 1 / (4 n.v) <= 1 / (4e-5) with the clamps, and F at
/// most 1. The scene's checks bound each light's peak with it.
inline double microfacetSpecularBound(double roughness)
{
  const double r2 = roughness * roughness;
  return 1.0 / (vtkPi<double> * r2 * r2) * (0.25 / 1e-5);
}
}
