#pragma once
// Precomputed radiance transfer (P.-P. Sloan, J. Kautz and J. Snyder, "Precomputed Radiance
// Transfer for Real-Time Rendering in Dynamic, Low-Frequency Lighting Environments", SIGGRAPH
// 2002): what a vertex does with the light from each direction, as spherical-harmonic
// coefficients. For diffuse transfer, coefficient k is the integral over the sphere of
// V(w) max(0, n.w) Y_k(w); the irradiance under any radiance of coefficients L_k is then the
// dot product sum of L_k T_k (docs/formulas.md section 12.9).
#include "MonteCarloEstimate.h"
#include "SphericalHarmonics.h"

#include <array>
#include <vector>

namespace shadelab
{
/// T_k at shIndex(l, m), bands 0 to an order (at most largestShOrder), 0 past them.
using TransferVector = ShBasis;

/// Without shadows (V = 1): A_l Y_lm(n), the clamped cosine turned to n (Funk-Hecke), whose dot
/// product with a map's nine coefficients is R&H's irradiance. Orders 0 to largestShOrder (the
/// others throw std::invalid_argument, as TransferEstimate's constructor does).
TransferVector unshadowedTransfer(int order, const glm::dvec3& unitNormal);

/// A transfer vector per channel, T_k as an RGB value: what interreflection makes of a transfer
/// vector, since each channel's bounces reflect by that channel's albedo.
using ChannelTransfer = std::array<Rgb, shCount(largestShOrder)>;

/// The irradiance sum of L_k T_k over the coefficients given (at most a transfer vector's),
/// channel by channel for a ChannelTransfer.
Rgb irradianceFromTransfer(const ShCoefficients& radiance, const TransferVector& transfer);
Rgb irradianceFromTransfer(const ShCoefficients& radiance, const ChannelTransfer& transfer);

/// The band-limited radiance sum of L_k Y_k(w), from the basis at w (shBasis).
Rgb radianceFromCoefficients(const ShCoefficients& radiance, const ShBasis& basis);

/// The integral over the sphere of |L(w) - sum of L_k Y_k(w)|, the map's radiance less its
/// projection to bands 0 to order, per channel (texel by texel): a bound on how far the
/// irradiance from any transfer vector of that order, shadowed or not, is from the map's, since
/// the transfer's V(w) max(0, n.w) lies in [0, 1] (docs/formulas.md section 12.10). Throws
/// std::invalid_argument for an order outside 0 to largestShOrder.
Rgb bandLimitError(const EnvironmentMap& map, int order);

/// The shadowed transfer estimated from cosine-weighted directions about the normal (pdf
/// cos / pi): each sample is pi V(w_j) Y_k(w_j), added in order, stratified or not as
/// MonteCarloEstimate takes them (whose standard errors it uses). Given a radiance's
/// coefficients, also the irradiance under it from the same samples, pi V(w_j) L(w_j) with L
/// limited to their bands: the dot product of the coefficients with value(), with its own
/// standard error (the coefficients' errors are correlated, so theirs would not give it).
class TransferEstimate
{
public:
  TransferEstimate(int order, bool stratified, ShCoefficients radiance = {});

  /// One cosine-weighted direction, and whether the mesh lets its light through.
  void add(const glm::dvec3& direction, bool visible);

  TransferVector value() const;
  /// Each coefficient's; needs at least 2 samples.
  TransferVector standardError() const;
  /// The irradiance under the radiance given, and its standard error (2 samples or more).
  Rgb irradiance() const { return irradiance_.mean(); }
  Rgb irradianceStandardError() const { return irradiance_.standardError(); }

private:
  /// The coefficients three at a time, as the RGB channels of one estimate each, so that one
  /// implementation of the standard errors serves them all.
  static constexpr int largestGroups = (shCount(largestShOrder) + 2) / 3;
  int order_;
  std::vector<MonteCarloEstimate> estimates_; // (shCount(order_) + 2) / 3 of them
  ShCoefficients radiance_;
  MonteCarloEstimate irradiance_;
};
}
