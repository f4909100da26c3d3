#pragma once
// The per-light quantities ShadeLab can write as arrays (their names and meanings are in
// planning/ArrayCatalog), and which of them each kind of light has.
namespace shadelab
{
/// Quantities computed for each (non-ambient) light.
enum class LightTerm
{
  ToLight,        // s
  Distance,       // d, positional lights only
  Attenuation,    // distance attenuation
  SpotFactor,     // cone factor (1 outside spotlights)
  CosIncidence,   // n.s
  IncidenceAngle, // acos(n.s) in degrees
  Reflection,     // r
  RDotV,          // r.v
  HalfVector,     // h
  NDotH,          // n.h
  // The vtk_pbr model's microfacet factors (Microfacet.h):
  GgxDistribution, // D
  SmithVisibility, // V = G / (4 (n.s)(n.v))
  SchlickFresnel,  // F, RGB
  Diffuse,         // RGB
  Specular,        // RGB
  // Area lights and environment maps (DistributedLight.h):
  Irradiance,         // E, RGB
  IrradianceStdError, // Monte Carlo standard error of E, RGB
  SpecularStdError,   // Monte Carlo standard error of the specular term, RGB
  // Lights that cast shadows (NamedLight::shadows):
  Visibility, // 1 where the mesh does not hide the light, 0 where it does; the visible fraction of E for area lights
  VisibilityStdError, // area lights: the standard error of the sampled visible fraction
  // Area lights and maps drawn to a target ("samples": "auto" under a tolerance):
  ShortOfTarget, // 1 where the vertex stopped at the maximum with a standard error above its target
  // Maps by precomputed radiance transfer (EnvironmentEstimator::PrecomputedTransfer), as many
  // components as the light's order has coefficients:
  ShTransfer,         // the vertex's transfer vector
  ShTransferStdError, // with shadows: the standard errors of its coefficients
};
constexpr int LightTermCount = 23;
static_assert(static_cast<int>(LightTerm::ShTransferStdError) + 1 == LightTermCount, "LightTermCount is stale");

/// The terms only the vtk_pbr model computes.
inline bool isMicrofacetTerm(LightTerm term)
{
  return term == LightTerm::GgxDistribution || term == LightTerm::SmithVisibility || term == LightTerm::SchlickFresnel;
}

/// A light seen from each vertex as one direction: every term up to the specular one, and the
/// distance only when the light has a position. (The microfacet terms only in the vtk_pbr model:
/// ArrayCatalog's sceneLightHasTerm.)
inline bool localLightHasTerm(LightTerm term, bool positional)
{
  return term < LightTerm::Irradiance && (term != LightTerm::Distance || positional);
}

/// A light integrated over a solid angle: E, the diffuse and specular terms, and the standard
/// errors its estimator gives.
inline bool distributedLightHasTerm(LightTerm term, bool irradianceError, bool specularError)
{
  switch (term)
  {
    case LightTerm::Irradiance:
    case LightTerm::Diffuse:
    case LightTerm::Specular: return true;
    case LightTerm::IrradianceStdError: return irradianceError;
    case LightTerm::SpecularStdError: return specularError;
    default: return false;
  }
}
}
