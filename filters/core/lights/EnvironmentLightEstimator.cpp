#include "EnvironmentLightEstimator.h"

#include "LobeSampling.h"
#include "SampledTerms.h"
#include "SampleWarps.h"

#include <algorithm>
#include <cmath>

namespace shadelab
{
namespace
{
/// Rotation by angle about +y, anticlockwise seen from above (+y toward the viewer): maps the
/// map's frame to the world's.
glm::dmat3 rotationAboutY(double degrees)
{
  const double a = degrees * samplePi / 180;
  const double c = std::cos(a), s = std::sin(a);
  // glm is column-major: columns are the images of x, y and z.
  return glm::dmat3(glm::dvec3(c, 0, -s), glm::dvec3(0, 1, 0), glm::dvec3(s, 0, c));
}
}

EnvironmentLightEstimator::EnvironmentLightEstimator(const EnvironmentLight& light, std::uint64_t lightIndex, const LobeModel& lobe)
  : light_(light)
  , scale_(light.color * light.intensity)
  , lightIndex_(lightIndex)
  , lobe_(lobe)
  , worldToMap_(glm::transpose(rotationAboutY(light.rotationDegrees)))
{
  const EnvironmentMap& map = *light.map;
  switch (light.estimator)
  {
    case EnvironmentEstimator::BruteForce:
    {
      const EnvironmentMap level =
        map.width > light.bruteForceWidth ? downsampled(map, light.bruteForceWidth) : map;
      texels_.reserve(std::size_t(level.width) * level.height);
      for (int row = 0; row < level.height; ++row)
      {
        const double solidAngle = texelSolidAngle(row, level.width, level.height);
        for (int column = 0; column < level.width; ++column)
        {
          texels_.push_back({ texelCentreDirection(level, column, row), scale_ * level.texel(column, row) * solidAngle });
        }
      }
      break;
    }
    case EnvironmentEstimator::SphericalHarmonics:
    {
      ShCoefficients9 coefficients = projectRadiance(map);
      for (Rgb& coefficient : coefficients)
      {
        coefficient *= scale_; // the coefficients are linear in the radiance
      }
      irradiance_ = composedWith(irradiancePolynomial(coefficients), worldToMap_);
      if (lobe.wanted())
      {
        sampler_.emplace(map);
      }
      break;
    }
    case EnvironmentEstimator::MonteCarlo:
      if (light.directions == EnvironmentDirections::Luminance)
      {
        sampler_.emplace(map);
      }
      break;
  }
}

Rgb EnvironmentLightEstimator::radianceAt(const glm::dvec3& mapDirection) const
{
  const glm::ivec2 texel = texelToward(*light_.map, mapDirection);
  return light_.map->texel(texel.x, texel.y);
}

DistributedTerms EnvironmentLightEstimator::bruteForce(const glm::dvec3& n, const glm::dvec3& v) const
{
  // Every texel a distant light of intensity L Omega (docs/formulas.md section 12.3).
  DistributedTerms terms;
  for (const Texel& texel : texels_)
  {
    const double cosIncidence = glm::dot(n, texel.direction);
    if (cosIncidence > 0)
    {
      terms.irradiance += texel.radiantIntensity * cosIncidence;
      if (lobe_.wanted())
      {
        terms.specular += texel.radiantIntensity * lobe_(n, texel.direction, v);
      }
    }
  }
  return terms;
}

DistributedTerms EnvironmentLightEstimator::monteCarlo(const glm::dvec3& n, const glm::dvec3& v, std::uint64_t vertex,
  bool irradiance, EnvironmentDirections directions) const
{
  const SampleSequence sequence(lightIndex_, vertex, light_.sampling);
  return sampledTerms(sequence, light_.sampling.stratified, irradiance, lobe_, n, v, nullptr,
    [&](const glm::dvec2& u)
    {
      if (directions == EnvironmentDirections::Luminance)
      {
        const EnvironmentSample sample = sampler_->sample(u.x, u.y);
        const Rgb radiance = scale_ * sample.radiance;
        RadianceSample drawn{ sample.direction, sample.pdf > 0 ? radiance / sample.pdf : Rgb(0.0), std::nullopt };
        if (lobe_.wanted())
        {
          drawn.specular = specularByBothStrategies(n, v, u, sample.direction, radiance, sample.pdf);
        }
        return drawn;
      }
      const WeightedDirection sample = cosineWeightedDirection(n, u);
      return RadianceSample{ sample.direction, scale_ * radianceAt(sample.direction) * sample.weight, std::nullopt };
    });
}

Rgb EnvironmentLightEstimator::specularByBothStrategies(const glm::dvec3& n, const glm::dvec3& v, const glm::dvec2& u,
  const glm::dvec3& byLuminance, const Rgb& radiance, double luminanceDensity) const
{
  // Veach's balance heuristic with one sample of each strategy (E. Veach, "Robust Monte Carlo
  // Methods for Light Transport Simulation", 1997, section 9.2): f(x) / (p_L(x) + p_B(x)) +
  // f(y) / (p_L(y) + p_B(y)), x drawn by luminance and y by the lobe, is unbiased wherever
  // either density covers f. Luminance alone misses a sharp lobe under a dim sky; the lobe alone
  // misses a small sun.
  Rgb estimate(0.0);
  if (luminanceDensity > 0)
  {
    estimate += radiance * lobe_(n, byLuminance, v) / (luminanceDensity + lobeDensity(lobe_, n, v, byLuminance));
  }
  const glm::dvec3 byLobe = lobeDirection(lobe_, n, v, u);
  const double density = lobeDensity(lobe_, n, v, byLobe);
  if (density > 0)
  {
    const EnvironmentSample there = sampler_->at(byLobe);
    estimate += scale_ * there.radiance * lobe_(n, byLobe, v) / (there.pdf + density);
  }
  return estimate;
}

DistributedTerms EnvironmentLightEstimator::estimate(const SurfacePoint& point) const
{
  // The map is fixed and the scene turns: normal and viewer go into the map's frame.
  const glm::dvec3 n = worldToMap_ * point.normal;
  const glm::dvec3 v = worldToMap_ * point.toViewer;
  switch (light_.estimator)
  {
    case EnvironmentEstimator::BruteForce:
      return bruteForce(n, v);
    case EnvironmentEstimator::MonteCarlo:
      return monteCarlo(n, v, point.index, true, light_.directions);
    case EnvironmentEstimator::SphericalHarmonics:
      break;
  }
  // Nine coefficients cannot hold a lobe sharper than the cosine: S is sampled, by luminance and by the lobe.
  DistributedTerms terms =
    lobe_.wanted() ? monteCarlo(n, v, point.index, false, EnvironmentDirections::Luminance) : DistributedTerms{};
  terms.irradiance = (*irradiance_)(point.normal);
  return terms;
}
}
