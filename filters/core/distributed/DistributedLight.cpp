#include "DistributedLight.h"

#include "AreaLightEstimator.h"
#include "EnvironmentLightEstimator.h"

namespace shadelab
{
std::unique_ptr<DistributedLightEstimator> makeEstimator(
  const LightSource& source, std::uint64_t lightIndex, const LobeModel& lobe)
{
  if (const auto* area = std::get_if<AreaLight>(&source))
  {
    return std::make_unique<AreaLightEstimator>(*area, lightIndex, lobe);
  }
  return std::make_unique<EnvironmentLightEstimator>(std::get<EnvironmentLight>(source), lightIndex, lobe);
}

bool estimatesIrradianceError(const LightSource& source)
{
  if (const auto* area = std::get_if<AreaLight>(&source))
  {
    return area->estimator == AreaEstimator::MonteCarlo;
  }
  const auto* environment = std::get_if<EnvironmentLight>(&source);
  return environment && environment->estimator == EnvironmentEstimator::MonteCarlo;
}

bool estimatesSpecularError(const LightSource& source)
{
  // Every estimator but the point approximation and the brute-force sum samples S.
  if (const auto* area = std::get_if<AreaLight>(&source))
  {
    return area->estimator != AreaEstimator::Point;
  }
  const auto* environment = std::get_if<EnvironmentLight>(&source);
  return environment && environment->estimator != EnvironmentEstimator::BruteForce;
}
}
