#pragma once
// Points in the unit square for the Monte Carlo estimators, which warp them onto an emitter or
// onto directions. Each point is a hash of (light, vertex, sample), not a draw from a
// generator's running state: a vertex's estimate is the same bits whatever thread computes it,
// in whatever order, and with any number of threads.
#include <glm/vec2.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace shadelab
{
/// SplitMix64's finaliser (G. Steele, D. Lea, C. Flood, "Fast Splittable Pseudorandom Number
/// Generators", OOPSLA 2014): a bijection of 64-bit words whose every output bit depends on
/// every input bit. Chained over the three indices it serves as a counter-based generator.
/// Eight lines of code, where <random>'s engines keep a running state that cannot be indexed.
inline std::uint64_t mix64(std::uint64_t z)
{
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

/// A double in [0, 1) from the top 53 bits of a word.
inline double unitInterval(std::uint64_t bits)
{
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

/// More samples than this per vertex is a mistake (a 100k-vertex mesh would take hours); at
/// least 2 give a standard error.
constexpr int maxSamplesPerVertex = 1 << 20;

/// How Monte Carlo estimators place their samples in the unit square they warp.
struct Sampling
{
  int samples = 64;
  /// One sample in each of `samples` cells of a grid over the square, rather than independent.
  bool stratified = true;
  /// "auto" in a scene: as many per vertex as a tolerance's share needs (SequentialSampling.h),
  /// at most `maximum`; the tolerance's plan sets the target.
  bool fromTolerance = false;
  int maximum = 4096;
};

/// The sample points of one light at one vertex. Stratified: the square is cut into a grid of
/// rows x columns = samples cells (columns the largest divisor of samples not above its square
/// root, so every count has an exact grid) and sample j falls at a random place in cell j,
/// cells taken row by row. Independent: every point is uniform over the whole square.
/// firstSample: where a later round of the same vertex's samples starts (its points are hashed
/// from their indices from there on, laid over the square's cells again; SequentialSampling.h).
class SampleSequence
{
public:
  SampleSequence(std::uint64_t light, std::uint64_t vertex, const Sampling& sampling, std::uint64_t firstSample = 0)
    : key_(mix64(mix64(light + 0x9e3779b97f4a7c15ull) ^ vertex))
    , firstHash_(firstSample + 1)
    , sampling_(sampling)
  {
    columns_ = gridColumns(sampling.samples);
    // Reciprocals, so that a point costs multiplications rather than divisions.
    columnWidth_ = 1.0 / columns_;
    rowHeight_ = 1.0 / (sampling.samples / columns_);
  }

  int count() const { return sampling_.samples; }

  /// The columns of the stratified grid of `samples` cells: the largest divisor of samples not
  /// above its square root (cells are taken row by row).
  static int gridColumns(int samples)
  {
    int columns = static_cast<int>(std::sqrt(static_cast<double>(samples)));
    while (columns > 1 && samples % columns != 0)
    {
      --columns;
    }
    return std::max(columns, 1);
  }

  glm::dvec2 point(int j) const
  {
    const std::uint64_t bits = mix64(key_ ^ mix64(static_cast<std::uint64_t>(j) + firstHash_));
    const glm::dvec2 uniform(unitInterval(bits), unitInterval(mix64(bits)));
    if (!sampling_.stratified)
    {
      return uniform;
    }
    const int row = j / columns_;
    const int column = j - row * columns_;
    // min: (cell + u) / cells can round up to exactly 1 for u just below 1.
    return { std::min((column + uniform.x) * columnWidth_, 1 - 0x1.0p-53),
      std::min((row + uniform.y) * rowHeight_, 1 - 0x1.0p-53) };
  }

  /// Points first .. first + count - 1, as point(j) gives them, into x[] and y[]: arrays of
  /// coordinates, which the loops that warp them vectorize over. (This loop stays scalar: the
  /// hashes' 64-bit products have no vector instruction below AVX-512, and GCC's emulation of
  /// them took half as long again.)
  void points(int first, int count, double* x, double* y) const
  {
    for (int k = 0; k < count; ++k)
    {
      const glm::dvec2 p = point(first + k);
      x[k] = p.x;
      y[k] = p.y;
    }
  }

private:
  std::uint64_t key_;
  std::uint64_t firstHash_; // sample j is hashed from j + firstHash_
  Sampling sampling_;
  int columns_ = 1;
  double columnWidth_ = 1, rowHeight_ = 1;
};
}
