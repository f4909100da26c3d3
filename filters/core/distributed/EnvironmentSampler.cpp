#include "EnvironmentSampler.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace shadelab
{
namespace
{
constexpr double pi = glm::pi<double>();
constexpr double largestBelowOne = 0x1.fffffffffffffp-1;
/// How many samples EnvironmentSampler draws together, their cache misses overlapping.
constexpr int batch = 16;

/// Writes the cumulative distribution of weights[0, count) to cdf[0, count]: from 0 to
/// exactly 1 (sum / sum), or evenly spaced if every weight is 0. Returns the weights' sum.
double buildCdf(const double* weights, int count, double* cdf)
{
  cdf[0] = 0.0;
  for (int i = 0; i < count; ++i)
  {
    cdf[i + 1] = cdf[i] + weights[i];
  }
  const double sum = cdf[count];
  for (int i = 1; i <= count; ++i)
  {
    cdf[i] = sum > 0.0 ? cdf[i] / sum : static_cast<double>(i) / count;
  }
  return sum;
}

struct BinSample
{
  int bin;
  double offset; // where in the bin, in [0, 1)
};

/// The bin of a cdf of `count` bins that holds u: the one with cdf[bin] <= u < cdf[bin + 1],
/// never one of zero width, since cdf[0] = 0 <= u < 1 = cdf[count]. From a starting bin it
/// walks to that bin, so that it gives the same bin as std::upper_bound from any start.
int binHolding(const double* cdf, int start, double u)
{
  int bin = start;
  while (cdf[bin] > u)
  {
    --bin;
  }
  while (cdf[bin + 1] <= u)
  {
    ++bin;
  }
  return bin;
}

/// The guide table of a cdf of `count` bins (C. Chen and Y. Asau, "On generating random
/// variates from an empirical distribution", AIIE Transactions 6, 1974): guide[k] is the bin
/// that holds k / count. The bin of u is found from guide[floor(u count)] in a step or two on
/// average. A binary search took twenty steps for a map's sample, about every other one a
/// mispredicted branch: the largest cost of a map's shadow rays.
void buildGuide(const double* cdf, int count, int* guide)
{
  int bin = 0;
  for (int k = 0; k < count; ++k)
  {
    bin = binHolding(cdf, bin, static_cast<double>(k) / count);
    guide[k] = bin;
  }
}

/// u brought into [0, 1) (0 for NaN): outside it no bin would hold u.
double withinUnit(double u)
{
  return u > 0.0 ? std::min(u, largestBelowOne) : 0.0;
}

/// The guide table's cell of u in [0, 1) for `count` bins: floor(u count), the last at most.
int guideCell(double u, int count)
{
  return std::min(static_cast<int>(u * count), count - 1);
}

/// Inverts a cdf of `count` bins with its guide table at u: the bin that holds u and where in it.
BinSample sampleCdf(const double* cdf, const int* guide, int count, double u)
{
  u = withinUnit(u);
  const int bin = binHolding(cdf, guide[guideCell(u, count)], u);
  const double offset = (u - cdf[bin]) / (cdf[bin + 1] - cdf[bin]);
  return { bin, std::min(offset, largestBelowOne) };
}

/// The sine and cosine of an angle of at most pi / 64 in magnitude, from their Taylor series
/// (to within 5e-18 there): a sample's direction took two calls of sincos, a tenth of its time.
SineCosine smallAngleSineCosine(double angle)
{
  const double a2 = angle * angle;
  return { angle * (1 - a2 / 6 * (1 - a2 / 20 * (1 - a2 / 42))),
    1 - a2 / 2 * (1 - a2 / 12 * (1 - a2 / 30 * (1 - a2 / 56))) };
}

/// The sine and cosine of the sum of two angles from theirs.
SineCosine sumOf(const SineCosine& a, const SineCosine& b)
{
  return { a.sin * b.cos + a.cos * b.sin, a.cos * b.cos - a.sin * b.sin };
}

bool isRadiance(const Rgb& rgb)
{
  return isFinite(rgb) && rgb.r >= 0.0 && rgb.g >= 0.0 && rgb.b >= 0.0;
}
}

EnvironmentSampler::EnvironmentSampler(const EnvironmentMap& map)
  : map_(map)
{
  requireValidShape(map, "EnvironmentSampler");
  const int width = map.width;
  const int height = map.height;
  rowCentreSinTheta_.resize(height);
  if (height >= 64 && width >= 128)
  {
    // An offset into a texel is then at most pi / 64 in theta and in phi (directionAt's angles).
    for (int row = 0; row < height; ++row)
    {
      const double theta = pi * row / height;
      rowEdges_.push_back({ std::sin(theta), std::cos(theta) });
    }
    for (int column = 0; column < width; ++column)
    {
      const double phi = 2.0 * pi * (static_cast<double>(column) / width - 0.5);
      columnEdges_.push_back({ std::sin(phi), std::cos(phi) });
    }
  }
  columnCdfs_.resize(static_cast<std::size_t>(height) * (width + 1));
  columnGuides_.resize(static_cast<std::size_t>(height) * width);
  rowCdf_.resize(height + 1);
  rowGuide_.resize(height);
  std::vector<double> rowWeights(height);
  std::vector<double> texelWeights(width);
  for (int row = 0; row < height; ++row)
  {
    rowCentreSinTheta_[row] = std::sin(pi * (row + 0.5) / height);
    for (int column = 0; column < width; ++column)
    {
      // Non-negative channels make the luminance 0 only where the radiance is 0, so every
      // texel with radiance can be sampled and the estimates are unbiased.
      if (!isRadiance(map.texel(column, row)))
      {
        throw std::invalid_argument("EnvironmentSampler: texel (column " + std::to_string(column) + ", row " +
          std::to_string(row) + ") is not a finite non-negative radiance");
      }
      texelWeights[column] = luminance(map.texel(column, row)) * rowCentreSinTheta_[row];
    }
    double* columnCdf = &columnCdfs_[static_cast<std::size_t>(row) * (width + 1)];
    rowWeights[row] = buildCdf(texelWeights.data(), width, columnCdf);
    buildGuide(columnCdf, width, &columnGuides_[static_cast<std::size_t>(row) * width]);
  }
  const double weightSum = buildCdf(rowWeights.data(), height, rowCdf_.data());
  buildGuide(rowCdf_.data(), height, rowGuide_.data());
  // The density over (u, v) of a texel is its weight / weightSum divided by its area in
  // (u, v), 1 / (width height).
  uvDensityPerWeight_ = weightSum > 0.0 ? width * static_cast<double>(height) / weightSum : 0.0;
}

EnvironmentSampler::Drawn EnvironmentSampler::draw(double u1, double u2) const
{
  return drawInRow(drawRow(u2), u1);
}

EnvironmentSampler::DrawnRow EnvironmentSampler::drawRow(double u2) const
{
  const BinSample row = sampleCdf(rowCdf_.data(), rowGuide_.data(), map_.height, u2);
  return { row.bin, row.offset };
}

EnvironmentSampler::Drawn EnvironmentSampler::drawInRow(const DrawnRow& row, double u1) const
{
  const std::size_t rowIndex = static_cast<std::size_t>(row.row);
  const BinSample column =
    sampleCdf(&columnCdfs_[rowIndex * (map_.width + 1)], &columnGuides_[rowIndex * map_.width], map_.width, u1);
  return { column.bin, row.row, directionInTexel(column.bin, column.offset, row.row, row.offset) };
}

glm::dvec3 EnvironmentSampler::directionInTexel(int column, double columnOffset, int row, double rowOffset) const
{
  if (rowEdges_.empty())
  {
    return directionAt((column + columnOffset) / map_.width, (row + rowOffset) / map_.height);
  }
  // directionAt's angles as the texel's edge plus the offset, whose sine and cosine are series.
  const SineCosine theta = sumOf(rowEdges_[std::size_t(row)], smallAngleSineCosine(pi * rowOffset / map_.height));
  const SineCosine phi =
    sumOf(columnEdges_[std::size_t(column)], smallAngleSineCosine(2.0 * pi * columnOffset / map_.width));
  return { theta.sin * phi.sin, theta.cos, -theta.sin * phi.cos };
}

template<typename OnDrawn>
void EnvironmentSampler::drawBatches(int count, const double* u1, const double* u2, OnDrawn&& onDrawn) const
{
  // Three passes over a batch, each fetching what the next reads: the rows (whose tables are
  // small) and their columns' guide cells; the guides' bins of the columns' cdfs; the draws. A
  // sample's misses come one after another, but a batch's overlap.
  const std::size_t width = static_cast<std::size_t>(map_.width);
  for (int first = 0; first < count; first += batch)
  {
    const int size = std::min(batch, count - first);
    DrawnRow rows[batch];
    const int* guides[batch];
    for (int k = 0; k < size; ++k)
    {
      rows[k] = drawRow(u2[first + k]);
      const std::size_t row = static_cast<std::size_t>(rows[k].row);
      guides[k] = &columnGuides_[row * width + std::size_t(guideCell(withinUnit(u1[first + k]), map_.width))];
      __builtin_prefetch(guides[k]);
    }
    for (int k = 0; k < size; ++k)
    {
      const std::size_t row = static_cast<std::size_t>(rows[k].row);
      const std::size_t start = static_cast<std::size_t>(*guides[k]);
      __builtin_prefetch(&columnCdfs_[row * (width + 1) + start]);
    }
    for (int k = 0; k < size; ++k)
    {
      onDrawn(first + k, drawInRow(rows[k], u1[first + k]));
    }
  }
}

void EnvironmentSampler::sampleDirections(int count, const double* u1, const double* u2, glm::dvec3* directions) const
{
  if (uvDensityPerWeight_ == 0.0)
  {
    for (int k = 0; k < count; ++k)
    {
      directions[k] = sampleDirection(u1[k], u2[k]); // a black map has no tables
    }
    return;
  }
  drawBatches(count, u1, u2, [&](int k, const Drawn& drawn) { directions[k] = drawn.direction; });
}

void EnvironmentSampler::samples(int count, const double* u1, const double* u2, EnvironmentSample* samples) const
{
  if (uvDensityPerWeight_ == 0.0)
  {
    for (int k = 0; k < count; ++k)
    {
      samples[k] = sample(u1[k], u2[k]);
    }
    return;
  }
  // The texels, fetched once a batch's are known, are read a pass later.
  for (int first = 0; first < count; first += batch)
  {
    const int size = std::min(batch, count - first);
    Drawn drawn[batch];
    drawBatches(size, u1 + first, u2 + first,
      [&](int k, const Drawn& texel)
      {
        drawn[k] = texel;
        __builtin_prefetch(&map_.texel(texel.column, texel.row));
      });
    for (int k = 0; k < size; ++k)
    {
      samples[first + k] = sampleOf(drawn[k]);
    }
  }
}

EnvironmentSample EnvironmentSampler::sample(double u1, double u2) const
{
  if (uvDensityPerWeight_ == 0.0)
  {
    return { sampleDirection(u1, u2), 1.0 / (4.0 * pi), Rgb(0.0) };
  }
  return sampleOf(draw(u1, u2));
}

EnvironmentSample EnvironmentSampler::sampleOf(const Drawn& drawn) const
{
  return { drawn.direction, pdfAt(drawn.column, drawn.row, drawn.direction), map_.texel(drawn.column, drawn.row) };
}

glm::dvec3 EnvironmentSampler::sampleDirection(double u1, double u2) const
{
  if (uvDensityPerWeight_ == 0.0)
  {
    // Black map: cos(theta) = 1 - 2 u2 uniform in [-1, 1] is uniform over the sphere
    // (Archimedes' hat-box theorem), and every texel is 0.
    return directionAt(u1, std::acos(1.0 - 2.0 * u2) / pi);
  }
  return draw(u1, u2).direction;
}

double EnvironmentSampler::pdf(const glm::dvec3& unitDirection) const
{
  return at(unitDirection).pdf;
}

EnvironmentSample EnvironmentSampler::at(const glm::dvec3& unitDirection) const
{
  return atTexel(unitDirection, texelToward(map_, unitDirection));
}

void EnvironmentSampler::at(int count, const glm::dvec3* unitDirections, EnvironmentSample* samples) const
{
  for (int first = 0; first < count; first += batch)
  {
    const int size = std::min(batch, count - first);
    glm::ivec2 texels[batch];
    for (int k = 0; k < size; ++k)
    {
      texels[k] = texelToward(map_, unitDirections[first + k]);
      __builtin_prefetch(&map_.texel(texels[k].x, texels[k].y));
    }
    for (int k = 0; k < size; ++k)
    {
      samples[first + k] = atTexel(unitDirections[first + k], texels[k]);
    }
  }
}

EnvironmentSample EnvironmentSampler::atTexel(const glm::dvec3& unitDirection, const glm::ivec2& texel) const
{
  const double density = uvDensityPerWeight_ == 0.0 ? 1.0 / (4.0 * pi) : pdfAt(texel.x, texel.y, unitDirection);
  return { unitDirection, density, map_.texel(texel.x, texel.y) };
}

double EnvironmentSampler::pdfAt(int column, int row, const glm::dvec3& direction) const
{
  const double sinTheta = std::sqrt(direction.x * direction.x + direction.z * direction.z);
  if (sinTheta == 0.0)
  {
    return 0.0;
  }
  const double uvDensity = luminance(map_.texel(column, row)) * rowCentreSinTheta_[row] * uvDensityPerWeight_;
  return uvDensity / (2.0 * pi * pi * sinTheta);
}
}
