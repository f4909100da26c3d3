#pragma once
// docs/formulas.md section 12: an environment map, where every texel is a distant light of
// radiance colour x intensity x texel over the texel's solid angle; its estimators are in
// EnvironmentLightEstimator.
#include "LightType.h"
#include "SampleSequence.h"

#include <array>
#include <memory>
#include <string>
#include <utility>

namespace shadelab
{
struct EnvironmentMap; // EnvironmentMap.h

/// How the irradiance from an environment map is estimated. The specular term is estimated by
/// the same sum for BruteForce, by sampling for the others (a few bands of coefficients hold
/// too little of a map for a lobe sharper than the cosine). With shadows, BruteForce and
/// SphericalHarmonics give their unshadowed E times the visible fraction of `sampling.samples`
/// directions drawn by `directions`, and S from those samples (docs/formulas.md section 12.7).
/// PrecomputedTransfer's shadows are in its transfer vectors instead (section 12.10).
enum class EnvironmentEstimator
{
  BruteForce,         // every texel of the map downsampled to `bruteForceWidth`, as a distant light
  MonteCarlo,         // `sampling.samples` directions, drawn by `directions`
  SphericalHarmonics, // 9 coefficients (Ramamoorthi and Hanrahan 2001), diffuse only
  /// The map's coefficients to band `shOrder` dotted with each vertex's transfer vector (Sloan,
  /// Kautz and Snyder 2002), which is written out so that other maps can relight the mesh; with
  /// shadows, estimated from `sampling.samples` cosine-weighted rays (a fixed count).
  PrecomputedTransfer,
};

/// The estimators' names in a scene file's "estimator" (and shadelab shade's --envmap-estimator),
/// in the order messages list them.
inline constexpr std::array<std::pair<const char*, EnvironmentEstimator>, 4> environmentEstimatorNames{ {
  { "sh", EnvironmentEstimator::SphericalHarmonics },
  { "monte_carlo", EnvironmentEstimator::MonteCarlo },
  { "brute_force", EnvironmentEstimator::BruteForce },
  { "prt", EnvironmentEstimator::PrecomputedTransfer },
} };

/// Where Monte Carlo directions for an environment map come from.
enum class EnvironmentDirections
{
  Luminance, // importance sampling of the map's luminance, good for small bright sources; for S
             // combined with sampling the lobe (multiple importance sampling)
  Cosine,    // cosine-weighted about the normal: exact irradiance from a constant map
  Mis,       // each sample by luminance or by the cosine, half and half, weighted by the two
             // densities' mean (Veach's balance heuristic, one-sample model): robust where a
             // shadow hides the bright part of the map or a dim sky is what gets through
};

/// The directions' names in a scene file's "directions" (and --envmap-directions), in the order
/// messages list them.
inline constexpr std::array<std::pair<const char*, EnvironmentDirections>, 3> environmentDirectionNames{ {
  { "luminance", EnvironmentDirections::Luminance },
  { "cosine", EnvironmentDirections::Cosine },
  { "mis", EnvironmentDirections::Mis },
} };

struct EnvironmentLight
{
  std::shared_ptr<const EnvironmentMap> map;
  std::string file;           // where the map came from, for messages and reports
  double rotationDegrees = 0; // about +y, anticlockwise seen from above
  Rgb color{ 1, 1, 1 };
  double intensity = 1.0;
  EnvironmentEstimator estimator = EnvironmentEstimator::SphericalHarmonics;
  EnvironmentDirections directions = EnvironmentDirections::Luminance;
  Sampling sampling;
  int bruteForceWidth = 128;
  int shOrder = 2; // PrecomputedTransfer's highest band, 2 to largestShOrder

  /// The directions of its samples: PrecomputedTransfer's are always cosine-weighted, the
  /// density its transfer estimate is written for.
  EnvironmentDirections sampledDirections() const
  {
    return estimator == EnvironmentEstimator::PrecomputedTransfer ? EnvironmentDirections::Cosine : directions;
  }

  SHADELAB_LIGHT_TYPE(EnvironmentLight, Distributed, false, true);
  ToleranceBounds toleranceBounds(const Material& m, bool shadowed) const;
};
}
