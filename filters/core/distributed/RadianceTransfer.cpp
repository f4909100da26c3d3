#include "RadianceTransfer.h"

#include "SampleWarps.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace shadelab
{
TransferVector unshadowedTransfer(int order, const glm::dvec3& unitNormal)
{
  requireShOrder(order, "unshadowedTransfer");
  TransferVector transfer = shBasis(order, unitNormal);
  for (int l = 0; l <= order; ++l)
  {
    for (int m = -l; m <= l; ++m)
    {
      transfer[shIndex(l, m)] *= clampedCosineBand(l);
    }
  }
  return transfer;
}

namespace
{
/// sum of L_k T_k, T_k a number or an RGB value.
template<typename Transfer>
Rgb dotProduct(const ShCoefficients& radiance, const Transfer& transfer)
{
  if (radiance.size() > transfer.size())
  {
    throw std::invalid_argument("irradianceFromTransfer: " + std::to_string(radiance.size()) +
      " coefficients, more than a transfer vector's " + std::to_string(transfer.size()));
  }
  Rgb sum(0.0);
  for (std::size_t k = 0; k < radiance.size(); ++k)
  {
    sum += radiance[k] * transfer[k];
  }
  return sum;
}
}

Rgb irradianceFromTransfer(const ShCoefficients& radiance, const TransferVector& transfer)
{
  return dotProduct(radiance, transfer);
}

Rgb irradianceFromTransfer(const ShCoefficients& radiance, const ChannelTransfer& transfer)
{
  return dotProduct(radiance, transfer);
}

Rgb radianceFromCoefficients(const ShCoefficients& radiance, const ShBasis& basis)
{
  return irradianceFromTransfer(radiance, basis); // the same sum, of L_k Y_k(w)
}

Rgb bandLimitError(const EnvironmentMap& map, int order)
{
  const ShCoefficients coefficients = projectRadiance(map, order); // which checks the order
  Rgb error(0.0);
  for (int row = 0; row < map.height; ++row)
  {
    const double solidAngle = texelSolidAngle(row, map.width, map.height);
    for (int column = 0; column < map.width; ++column)
    {
      const Rgb limited =
        radianceFromCoefficients(coefficients, shBasis(order, texelCentreDirection(map, column, row)));
      error += glm::abs(map.texel(column, row) - limited) * solidAngle;
    }
  }
  return error;
}

TransferEstimate::TransferEstimate(int order, bool stratified, ShCoefficients radiance)
  : order_((requireShOrder(order, "TransferEstimate"), order))
  , estimates_((shCount(order) + 2) / 3, MonteCarloEstimate(stratified))
  , radiance_(std::move(radiance))
  , irradiance_(stratified)
{
  if (radiance_.size() > std::size_t(shCount(order)))
  {
    throw std::invalid_argument("TransferEstimate: " + std::to_string(radiance_.size()) +
      " radiance coefficients, more than order " + std::to_string(order) + "'s " + std::to_string(shCount(order)));
  }
}

void TransferEstimate::add(const glm::dvec3& direction, bool visible)
{
  // With pdf cos / pi, a sample of V max(0, n.w) Y_k is pi V Y_k(w); the last group padded.
  std::array<double, 3 * largestGroups> sample{};
  Rgb radiance(0.0);
  if (visible)
  {
    const ShBasis basis = shBasis(order_, direction);
    std::copy(basis.begin(), basis.end(), sample.begin());
    radiance = radianceFromCoefficients(radiance_, basis);
  }
  for (std::size_t g = 0; g < estimates_.size(); ++g)
  {
    estimates_[g].add(samplePi * Rgb(sample[3 * g], sample[3 * g + 1], sample[3 * g + 2]));
  }
  irradiance_.add(samplePi * radiance);
}

namespace
{
/// The coefficients from their groups of three.
template<typename OfGroup>
TransferVector ungrouped(int count, int groups, OfGroup&& ofGroup)
{
  TransferVector values{};
  for (int g = 0; g < groups; ++g)
  {
    const Rgb three = ofGroup(g);
    for (int c = 0; c < 3 && 3 * g + c < count; ++c)
    {
      values[3 * g + c] = three[c];
    }
  }
  return values;
}
}

TransferVector TransferEstimate::value() const
{
  return ungrouped(shCount(order_), int(estimates_.size()), [&](int g) { return estimates_[g].mean(); });
}

TransferVector TransferEstimate::standardError() const
{
  return ungrouped(shCount(order_), int(estimates_.size()), [&](int g) { return estimates_[g].standardError(); });
}
}
