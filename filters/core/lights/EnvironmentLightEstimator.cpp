#include "EnvironmentLightEstimator.h"

#include "SampleWarps.h"
#include "ShRotation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

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

ShCoefficients worldRadianceCoefficients(const EnvironmentLight& light, int order)
{
  ShCoefficients coefficients = projectRadiance(*light.map, order);
  for (Rgb& coefficient : coefficients)
  {
    coefficient *= light.color * light.intensity; // the coefficients are linear in the radiance
  }
  // In world axes, so that relighting turns the map's 9 to 25 coefficients rather than every
  // vertex's transfer vector.
  return ShRotation(order, rotationAboutY(light.rotationDegrees))(coefficients);
}

EnvironmentLightEstimator::EnvironmentLightEstimator(
  const EnvironmentLight& light, std::uint64_t lightIndex, const LobeModel& lobe, const SampleTargets& targets)
  : light_(light)
  , scale_(light.color * light.intensity)
  , lightIndex_(lightIndex)
  , lobe_(lobe)
  , targets_(targets)
  , worldToMap_(glm::transpose(rotationAboutY(light.rotationDegrees)))
  , mapToWorld_(rotationAboutY(light.rotationDegrees))
{
  light_.directions = light.sampledDirections();
  const EnvironmentMap& map = *light.map;
  switch (light.estimator)
  {
    case EnvironmentEstimator::BruteForce:
    {
      const EnvironmentMap level = map.width > light.bruteForceWidth ? downsampled(map, light.bruteForceWidth) : map;
      texels_.reserve(std::size_t(level.width) * level.height);
      for (int row = 0; row < level.height; ++row)
      {
        const double solidAngle = texelSolidAngle(row, level.width, level.height);
        for (int column = 0; column < level.width; ++column)
        {
          texels_.push_back(
            { texelCentreDirection(level, column, row), scale_ * level.texel(column, row) * solidAngle });
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
      break;
    }
    case EnvironmentEstimator::PrecomputedTransfer:
      transferRadiance_ = worldRadianceCoefficients(light, light.shOrder);
      break;
    case EnvironmentEstimator::MonteCarlo: break;
  }
  // Sampling by luminance draws the light's directions (every estimator's with shadows), and
  // the SH and transfer estimators' S.
  const bool coefficientsEstimateE = light.estimator == EnvironmentEstimator::SphericalHarmonics ||
    light.estimator == EnvironmentEstimator::PrecomputedTransfer;
  if (light_.directions != EnvironmentDirections::Cosine || (coefficientsEstimateE && lobe.wanted()))
  {
    sampler_.emplace(map);
  }
}

Rgb EnvironmentLightEstimator::radianceAt(const glm::dvec3& mapDirection) const
{
  const glm::ivec2 texel = texelToward(*light_.map, mapDirection);
  return light_.map->texel(texel.x, texel.y);
}

DistributedTerms EnvironmentLightEstimator::bruteForce(const glm::dvec3& n, const glm::dvec3& v, bool specular) const
{
  // Every texel a distant light of intensity L Omega (docs/formulas.md section 12.3).
  DistributedTerms terms;
  for (const Texel& texel : texels_)
  {
    const double cosIncidence = glm::dot(n, texel.direction);
    if (cosIncidence > 0)
    {
      terms.irradiance += texel.radiantIntensity * cosIncidence;
      if (specular)
      {
        terms.specular += texel.radiantIntensity * lobe_(n, texel.direction, v);
      }
    }
  }
  return terms;
}

RadianceSample EnvironmentLightEstimator::weightedByDensity(const EnvironmentSample& sample) const
{
  return { sample.direction, sample.pdf > 0 ? scale_ * sample.radiance / sample.pdf : Rgb(0.0), std::nullopt };
}

namespace
{
/// The mixture (Mis) draws by luminance where u.x < 1/2, by the cosine elsewhere, each from u.x
/// stretched back to [0, 1).
bool mixtureDrawsByLuminance(const glm::dvec2& u)
{
  return u.x < 0.5;
}

glm::dvec2 mixtureStretched(const glm::dvec2& u)
{
  return { mixtureDrawsByLuminance(u) ? 2 * u.x : 2 * u.x - 1, u.y };
}
}

glm::dvec3 EnvironmentLightEstimator::mixtureDirection(const glm::dvec3& n, const glm::dvec2& u) const
{
  const glm::dvec2 stretched = mixtureStretched(u);
  return mixtureDrawsByLuminance(u) ? sampler_->sampleDirection(stretched.x, stretched.y)
                                    : cosineWeightedDirection(n, stretched).direction;
}

void EnvironmentLightEstimator::mixtureDirections(
  const glm::dvec3& n, const SampleSequence& sequence, int first, int count, double* x, double* y, double* z) const
{
  // Every sample's cosine direction, a loop that vectorizes, then the luminance directions
  // over them where the sample draws by luminance: no branch on which way a sample draws,
  // which went either way at random.
  double u[directionBlock], v[directionBlock];
  int byLuminance[directionBlock];
  int luminanceCount = 0;
  sequence.points(first, count, u, v);
  for (int j = 0; j < count; ++j)
  {
    byLuminance[luminanceCount] = j;
    luminanceCount += mixtureDrawsByLuminance({ u[j], v[j] }) ? 1 : 0;
    u[j] = mixtureStretched({ u[j], v[j] }).x;
  }
  for (int j = 0; j < count; ++j)
  {
    const glm::dvec3 direction = cosineWeightedDirection(n, { u[j], v[j] }).direction;
    x[j] = direction.x;
    y[j] = direction.y;
    z[j] = direction.z;
  }
  double luminanceU[directionBlock] = {}, luminanceV[directionBlock] = {};
  for (int k = 0; k < luminanceCount; ++k)
  {
    luminanceU[k] = u[byLuminance[k]];
    luminanceV[k] = v[byLuminance[k]];
  }
  glm::dvec3 byLuminanceDirections[directionBlock];
  sampler_->sampleDirections(luminanceCount, luminanceU, luminanceV, byLuminanceDirections);
  for (int k = 0; k < luminanceCount; ++k)
  {
    x[byLuminance[k]] = byLuminanceDirections[k].x;
    y[byLuminance[k]] = byLuminanceDirections[k].y;
    z[byLuminance[k]] = byLuminanceDirections[k].z;
  }
}

glm::dvec3 EnvironmentLightEstimator::drawDirection(
  const glm::dvec3& n, const glm::dvec2& u, EnvironmentDirections directions) const
{
  switch (directions)
  {
    case EnvironmentDirections::Luminance: return sampler_->sampleDirection(u.x, u.y);
    case EnvironmentDirections::Cosine: return cosineWeightedDirection(n, u).direction;
    case EnvironmentDirections::Mis: break;
  }
  return mixtureDirection(n, u);
}

void EnvironmentLightEstimator::drawDirections(const glm::dvec3& n, const SampleSequence& sequence, int first,
  int count, EnvironmentDirections directions, double* x, double* y, double* z) const
{
  switch (directions)
  {
    case EnvironmentDirections::Luminance:
    {
      double u[directionBlock] = {}, v[directionBlock] = {};
      glm::dvec3 drawn[directionBlock];
      sequence.points(first, count, u, v);
      sampler_->sampleDirections(count, u, v, drawn);
      for (int j = 0; j < count; ++j)
      {
        x[j] = drawn[j].x;
        y[j] = drawn[j].y;
        z[j] = drawn[j].z;
      }
      return;
    }
    case EnvironmentDirections::Cosine:
      warpedPoints(
        sequence, first, count, [&](const glm::dvec2& u) { return cosineWeightedDirection(n, u).direction; }, x, y, z);
      return;
    case EnvironmentDirections::Mis: break;
  }
  mixtureDirections(n, sequence, first, count, x, y, z);
}

RadianceSample EnvironmentLightEstimator::draw(
  const glm::dvec3& n, const glm::dvec2& u, EnvironmentDirections directions) const
{
  switch (directions)
  {
    case EnvironmentDirections::Luminance: return weightedByDensity(sampler_->sample(u.x, u.y));
    case EnvironmentDirections::Cosine:
    {
      const WeightedDirection sample = cosineWeightedDirection(n, u);
      return { sample.direction, scale_ * radianceAt(sample.direction) * sample.weight, std::nullopt };
    }
    case EnvironmentDirections::Mis: break;
  }
  // The sample's density is the mixture's, the mean of the two (Veach 1997, section 9.2.4: the
  // balance heuristic in the one-sample model).
  const glm::dvec3 direction = mixtureDirection(n, u);
  EnvironmentSample there = sampler_->at(direction);
  there.pdf = 0.5 * (there.pdf + std::max(0.0, glm::dot(n, direction)) / samplePi);
  return weightedByDensity(there);
}

DistributedTerms EnvironmentLightEstimator::monteCarlo(const glm::dvec3& n, const glm::dvec3& v, std::uint64_t vertex,
  bool irradiance, EnvironmentDirections directions, const SampleTargets& targets,
  const SampleShadowing& shadowing) const
{
  return sampledTerms(
    lightIndex_, vertex, light_.sampling, targets, irradiance, lobe_, n, v, shadowing.on(),
    [&](const SampleSequence& round)
    { return shadowing.of(round, [&](const SampleSequence& s, ShadowRay* rays) { shadowRaysOf(n, s, rays); }); },
    [&](const SampleSequence& sequence, int first, int count, RadianceSample* samples)
    {
      if (directions != EnvironmentDirections::Luminance)
      {
        pointByPoint([&](const glm::dvec2& u) { return draw(n, u, directions); })(sequence, first, count, samples);
        return;
      }
      // The lobe's own direction would need a ray of its own: with shadows, S is taken from
      // the light's samples alone.
      const bool bothStrategies = lobe_.wanted() && !shadowing.on();
      double u[sampleBlock], w[sampleBlock];
      EnvironmentSample drawn[sampleBlock], byLobe[sampleBlock];
      sequence.points(first, count, u, w);
      sampler_->samples(count, u, w, drawn);
      LobeSample lobeDrawn[sampleBlock];
      if (bothStrategies)
      {
        // The lobe's directions and their texels, found together (EnvironmentSampler::at).
        const LobeDirections lobeDirections(lobe_, n, v);
        glm::dvec3 directions[sampleBlock];
        for (int k = 0; k < count; ++k)
        {
          lobeDrawn[k] = lobeDirections({ u[k], w[k] });
          directions[k] = lobeDrawn[k].direction;
        }
        sampler_->at(count, directions, byLobe);
      }
      for (int k = 0; k < count; ++k)
      {
        samples[k] = weightedByDensity(drawn[k]);
        if (bothStrategies)
        {
          samples[k].specular = specularByBothStrategies(n, v, drawn[k], { byLobe[k], lobeDrawn[k].lobe });
        }
      }
    });
}

Rgb EnvironmentLightEstimator::specularByBothStrategies(
  const glm::dvec3& n, const glm::dvec3& v, const EnvironmentSample& byLuminance, const ByLobe& byLobe) const
{
  // Veach's balance heuristic with one sample of each strategy (E. Veach, "Robust Monte Carlo
  // Methods for Light Transport Simulation", 1997, section 9.2): f(x) / (p_L(x) + p_B(x)) +
  // f(y) / (p_L(y) + p_B(y)), x drawn by luminance and y by the lobe, is unbiased wherever
  // either density covers f. Luminance alone misses a sharp lobe under a dim sky; the lobe alone
  // misses a small sun.
  Rgb estimate(0.0);
  if (byLuminance.pdf > 0)
  {
    const LobeAtDirection lobe = lobeWithDensity(lobe_, n, v, byLuminance.direction);
    estimate += scale_ * byLuminance.radiance * lobe.value / (byLuminance.pdf + lobe.density);
  }
  if (byLobe.lobe.density > 0)
  {
    estimate += scale_ * byLobe.map.radiance * byLobe.lobe.value / (byLobe.map.pdf + byLobe.lobe.density);
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
    case EnvironmentEstimator::BruteForce: return bruteForce(n, v, lobe_.wanted());
    case EnvironmentEstimator::MonteCarlo: return monteCarlo(n, v, point.index, true, light_.directions, targets_, {});
    case EnvironmentEstimator::SphericalHarmonics:
    case EnvironmentEstimator::PrecomputedTransfer: break;
  }
  // A few bands cannot hold a lobe sharper than the cosine: S is sampled, by luminance and by the lobe.
  DistributedTerms terms = lobe_.wanted()
    ? monteCarlo(n, v, point.index, false, EnvironmentDirections::Luminance, targets_, {})
    : DistributedTerms{};
  if (light_.estimator == EnvironmentEstimator::PrecomputedTransfer)
  {
    terms.transfer = unshadowedTransfer(light_.shOrder, point.normal);
    terms.irradiance = irradianceFromTransfer(transferRadiance_, terms.transfer);
  }
  else
  {
    terms.irradiance = (*irradiance_)(point.normal);
  }
  return terms;
}

int EnvironmentLightEstimator::shadowRayCount() const
{
  return light_.sampling.samples;
}

void EnvironmentLightEstimator::shadowRays(const SurfacePoint& point, ShadowRay* rays) const
{
  shadowRaysOf(worldToMap_ * point.normal, SampleSequence(lightIndex_, point.index, light_.sampling), rays);
}

void EnvironmentLightEstimator::shadowRaysOf(const glm::dvec3& n, const SampleSequence& sequence, ShadowRay* rays) const
{
  // A ray is cast where its direction is above the point's horizon: below, the sample adds
  // nothing. Nor does a sample of a black texel above it, whose ray is cast all the same (the
  // texel's radiance is not looked up for the ray: the estimate is the same bits whatever
  // that ray finds, and the lookup costs more than the ray).
  for (int first = 0; first < sequence.count(); first += directionBlock)
  {
    const int count = std::min(directionBlock, sequence.count() - first);
    double x[directionBlock], y[directionBlock], z[directionBlock];
    drawDirections(n, sequence, first, count, light_.directions, x, y, z);
    for (int j = 0; j < count; ++j)
    {
      const glm::dvec3 direction(x[j], y[j], z[j]);
      rays[first + j] = { mapToWorld_ * direction, std::numeric_limits<double>::infinity(),
        glm::dot(n, direction) > 0 };
    }
  }
}

DistributedTerms EnvironmentLightEstimator::estimate(const SurfacePoint& point, const HiddenSamples& hidden) const
{
  return shadowedEstimate(point, { &hidden, nullptr });
}

DistributedTerms EnvironmentLightEstimator::estimate(const SurfacePoint& point, RoundShadows& shadows) const
{
  return shadowedEstimate(point, { nullptr, &shadows });
}

DistributedTerms EnvironmentLightEstimator::shadowedEstimate(
  const SurfacePoint& point, const SampleShadowing& shadowing) const
{
  const glm::dvec3 n = worldToMap_ * point.normal;
  const glm::dvec3 v = worldToMap_ * point.toViewer;
  Rgb unshadowed(0.0);
  switch (light_.estimator)
  {
    case EnvironmentEstimator::MonteCarlo:
      return monteCarlo(n, v, point.index, true, light_.directions, targets_, shadowing);
    case EnvironmentEstimator::BruteForce: unshadowed = bruteForce(n, v, false).irradiance; break;
    case EnvironmentEstimator::SphericalHarmonics: unshadowed = (*irradiance_)(point.normal); break;
    case EnvironmentEstimator::PrecomputedTransfer:
      if (!shadowing.fixed)
      {
        throw std::logic_error("precomputed transfer is drawn to a fixed count, not in rounds to a target");
      }
      return shadowedTransfer(point, n, v, *shadowing.fixed);
  }
  // As the exact estimator of an area light: where every ray gets through, E is the unshadowed
  // E bit for bit; drawn to E's target over the unshadowed E where there is one.
  DistributedTerms terms =
    monteCarlo(n, v, point.index, false, light_.directions, withVisibilityTarget(targets_, unshadowed), shadowing);
  terms.irradiance = unshadowed * terms.visibility;
  // A magnitude, where nine coefficients ring below 0 as where they do not.
  terms.irradianceStdError = glm::abs(unshadowed) * terms.visibilityStdError;
  return terms;
}

DistributedTerms EnvironmentLightEstimator::shadowedTransfer(
  const SurfacePoint& point, const glm::dvec3& n, const glm::dvec3& v, const HiddenSamples& hidden) const
{
  // S and the visible fraction from the same cosine-weighted samples as the rays (S from the
  // light's samples alone, as the other estimators' with shadows).
  DistributedTerms terms = monteCarlo(n, v, point.index, false, light_.directions, {}, { &hidden, nullptr });
  const SampleSequence sequence(lightIndex_, point.index, light_.sampling);
  TransferEstimate transfer(light_.shOrder, light_.sampling.stratified, transferRadiance_);
  for (int j = 0; j < sequence.count(); ++j)
  {
    // The direction of ray j (shadowRaysOf), in world axes.
    transfer.add(mapToWorld_ * drawDirection(n, sequence.point(j), light_.directions), !hidden.hidden(j));
  }
  terms.transfer = transfer.value();
  terms.transferStdError = transfer.standardError();
  terms.irradiance = transfer.irradiance();
  terms.irradianceStdError = transfer.irradianceStandardError();
  return terms;
}
}
