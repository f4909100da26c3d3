#pragma once
// The kernel's loops over a block's lanes (one array per quantity, VertexBlock::capacity long):
// storing terms, multiplying them channel by channel, and the unit vectors to a point. Each is
// a plain loop that GCC vectorises. Used by ShadingKernel.cpp alone.
#include "ShadingKernel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shadelab::kernel_lanes
{
template<typename T>
using Lane = std::array<T, VertexBlock<T>::capacity>;

/// Multiplies a term by a light's visibility, where it has shadows (visibility not null).
template<typename T>
void applyVisibility(const float* visibility, const VertexBlock<T>& b, Lane<T>& term)
{
  for (std::size_t k = 0; visibility && k < b.count; ++k)
  {
    term[k] *= T(visibility[b.first + k]);
  }
}

template<typename T>
void store(T* out, std::size_t first, std::size_t count, const Lane<T>& values)
{
  if (out)
  {
    std::copy(values.begin(), values.begin() + count, out + first);
  }
}

template<typename T>
void store(T* out, std::size_t first, std::size_t count, const Lane<T>& x, const Lane<T>& y, const Lane<T>& z)
{
  if (out)
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      out[3 * (first + k)] = x[k];
      out[3 * (first + k) + 1] = y[k];
      out[3 * (first + k) + 2] = z[k];
    }
  }
}

/// A light's term per channel, before its colour.
template<typename T>
struct RgbLanes
{
  const Lane<T>& r;
  const Lane<T>& g;
  const Lane<T>& b;
};

/// A term that is the same in every channel (a material whose coefficient is one number).
template<typename T>
RgbLanes<T> sameLanes(const Lane<T>& term)
{
  return { term, term, term };
}

/// Three lanes as a term's channels.
template<typename T>
RgbLanes<T> lanesOf(const std::array<Lane<T>, 3>& channels)
{
  return { channels[0], channels[1], channels[2] };
}

/// A term times the vertices' own coefficient (a material from arrays), channel by channel.
template<typename T>
RgbLanes<T> timesCoefficient(const RgbLanes<T>& term, const std::array<Lane<T>, 3>& coefficient, std::size_t count,
  std::array<Lane<T>, 3>& product)
{
  const Lane<T>* channels[3] = { &term.r, &term.g, &term.b };
  for (int channel = 0; channel < 3; ++channel)
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      product[channel][k] = (*channels[channel])[k] * coefficient[channel][k];
    }
  }
  return lanesOf(product);
}

/// Adds a term, channel by channel times a colour, to the sums over lights.
template<typename T>
void addTimesColor(
  const RgbLanes<T>& term, const Vec3<T>& color, std::size_t count, Lane<T>& sumR, Lane<T>& sumG, Lane<T>& sumB)
{
  for (std::size_t k = 0; k < count; ++k)
  {
    sumR[k] += term.r[k] * color.x;
    sumG[k] += term.g[k] * color.y;
    sumB[k] += term.b[k] * color.z;
  }
}

/// Vertex k's own coefficient (lanes).
template<typename T>
Vec3<T> coefficientAt(const std::array<Lane<T>, 3>& lanes, std::size_t k)
{
  return Vec3<T>(lanes[0][k], lanes[1][k], lanes[2][k]);
}

/// An RGB term that is colour x (r, g, b) at each vertex.
template<typename T>
void store(T* out, std::size_t first, std::size_t count, const Lane<T>& r, const Lane<T>& g, const Lane<T>& b,
  const Vec3<T>& color)
{
  if (out)
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      out[3 * (first + k)] = r[k] * color.x;
      out[3 * (first + k) + 1] = g[k] * color.y;
      out[3 * (first + k) + 2] = b[k] * color.z;
    }
  }
}

/// Whether slot k's position and normal are finite. & rather than &&: no branches, so that a
/// loop of it vectorises.
template<typename T>
bool isFiniteVertex(const VertexBlock<T>& b, std::size_t k)
{
  return std::isfinite(b.px[k]) & std::isfinite(b.py[k]) & std::isfinite(b.pz[k]) & std::isfinite(b.nx[k]) &
    std::isfinite(b.ny[k]) & std::isfinite(b.nz[k]);
}

/// The unit vectors (x, y, z) from each vertex of the block to `target`, and the distances.
/// Returns how many vertices are closer than the smallest normal number, where the direction
/// is undefined: they get (0, 0, 0) here. (A select against a fallback direction inside this
/// loop would stop GCC vectorising it, so the rare fix-up is a separate pass.)
template<typename T>
std::size_t unitVectorsFrom(
  const Vec3<T>& target, const VertexBlock<T>& b, Lane<T>& x, Lane<T>& y, Lane<T>& z, Lane<T>& distance)
{
  constexpr T smallest = std::numeric_limits<T>::min();
  const T tx = target.x, ty = target.y, tz = target.z; // copies: target could alias the lanes
  std::size_t undefined = 0;
  for (std::size_t k = 0; k < b.count; ++k)
  {
    const T ox = tx - b.px[k];
    const T oy = ty - b.py[k];
    const T oz = tz - b.pz[k];
    const T d = std::sqrt(ox * ox + oy * oy + oz * oz);
    const T divisor = std::max(d, smallest);
    x[k] = ox / divisor;
    y[k] = oy / divisor;
    z[k] = oz / divisor;
    distance[k] = d;
    undefined += d < smallest ? 1 : 0;
  }
  return undefined;
}
}
