#include "TextureFootprint.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace shadelab
{
namespace
{
/// The texel index of a repeated texture: index modulo count, into [0, count).
int wrapped(long long index, int count)
{
  const long long r = index % count;
  return int(r < 0 ? r + count : r);
}

/// How much of texel i, the interval [i, i + 1), the interval [low, high) covers.
double covered(long long i, double low, double high)
{
  return std::max(0.0, std::min(high, double(i + 1)) - std::max(low, double(i)));
}

/// The texels of a repeated row (or column) of `count` that [low, high) covers, each with how
/// much of it is covered, summed over the repeats: a square wider than the texture costs no more
/// than the texture.
std::vector<std::pair<int, double>> coverage(double low, double high, int count)
{
  // Whole repeats of the texture cover each texel once; the rest is narrower than the texture,
  // so it meets each texel at most once.
  const double periods = std::floor((high - low) / count);
  low += periods * count;
  std::vector<std::pair<int, double>> covering;
  if (periods > 0)
  {
    for (int i = 0; i < count; ++i)
    {
      covering.emplace_back(i, periods);
    }
  }
  for (auto i = (long long)std::floor(low); i < high; ++i)
  {
    const double part = covered(i, low, high);
    if (periods > 0)
    {
      covering[std::size_t(wrapped(i, count))].second += part;
    }
    else
    {
      covering.emplace_back(wrapped(i, count), part);
    }
  }
  return covering;
}

/// A point's position and texture coordinates, bit for bit: the key of the points that are one.
struct SurfacePoint
{
  std::array<double, 5> values;
  bool operator==(const SurfacePoint& other) const
  {
    return std::memcmp(values.data(), other.values.data(), sizeof(values)) == 0;
  }
  /// Each value's bits through splitmix64's finalizer, which spreads every bit over the low
  /// ones the table's slots use (coordinates like 3.0 or 0.5 differ only in their high bits).
  std::size_t hash() const
  {
    std::uint64_t hash = 0;
    for (double value : values)
    {
      std::uint64_t bits;
      std::memcpy(&bits, &value, sizeof(bits));
      bits += hash + 0x9e3779b97f4a7c15ull;
      bits = (bits ^ (bits >> 30)) * 0xbf58476d1ce4e5b9ull;
      bits = (bits ^ (bits >> 27)) * 0x94d049bb133111ebull;
      hash = bits ^ (bits >> 31);
    }
    return std::size_t(hash);
  }
};

/// The surface point each point is, numbered in the order first met, and how many there are:
/// points with the same position and texture coordinates (an OBJ importer's corners) are one.
/// An open-addressing table of each surface point's first point, its slots a power of two at
/// least twice the points:
/// std::unordered_map, a node allocated per point, took seconds on 4M points.
std::vector<std::size_t> surfacePointsOf(
  const std::vector<std::array<double, 3>>& positions, const std::vector<std::array<double, 2>>& uv, std::size_t& count)
{
  auto keyOf = [&](std::size_t p) {
    return SurfacePoint{ { positions[p][0], positions[p][1], positions[p][2], uv[p][0], uv[p][1] } };
  };
  constexpr std::size_t empty = std::size_t(-1);
  std::size_t slots = 1;
  while (slots < 2 * positions.size())
  {
    slots *= 2;
  }
  std::vector<std::size_t> firstPoints(slots, empty);
  std::vector<std::size_t> numbers(positions.size());
  count = 0;
  for (std::size_t p = 0; p < positions.size(); ++p)
  {
    const SurfacePoint key = keyOf(p);
    for (std::size_t slot = key.hash() & (slots - 1);; slot = (slot + 1) & (slots - 1))
    {
      if (firstPoints[slot] == empty)
      {
        firstPoints[slot] = p;
        numbers[p] = count++;
        break;
      }
      if (keyOf(firstPoints[slot]) == key)
      {
        numbers[p] = numbers[firstPoints[slot]];
        break;
      }
    }
  }
  return numbers;
}
}

Rgb boxMean(const RgbImage& image, double u, double v, double side)
{
  if (!std::isfinite(u) || !std::isfinite(v) || !std::isfinite(side))
  {
    return Rgb(std::nan("")); // refused with the vertex by the material's checks
  }
  // The texture repeats, so only u and v's fractions matter. A square over 2^20 textures wide
  // has the texture's mean within 2^-20, and wider ones are clamped to it: their coordinates
  // would lose the texel's precision.
  u -= std::floor(u);
  v -= std::floor(v);
  // A point with no area of its own (a corner of degenerate triangles) takes the texel it is in.
  side = std::clamp(side, 1e-6, 1048576.0 * std::max(image.width, image.height));
  // In texel units texel (i, j) spans [i, i + 1) x [j, j + 1), its centre at i + 1/2.
  const double x0 = u * image.width - side / 2, y0 = v * image.height - side / 2;
  const std::vector<std::pair<int, double>> columns = coverage(x0, x0 + side, image.width);
  const std::vector<std::pair<int, double>> rows = coverage(y0, y0 + side, image.height);
  // Each weight over the weights' own sum (side, up to rounding): within one texel they are
  // exactly 1, and the mean is the texel's colour to the bit.
  auto total = [](const std::vector<std::pair<int, double>>& weights)
  {
    double sum = 0;
    for (const auto& weight : weights)
    {
      sum += weight.second;
    }
    return sum;
  };
  const double columnsTotal = total(columns), rowsTotal = total(rows);
  Rgb mean(0.0);
  for (const auto& [row, wy] : rows)
  {
    Rgb rowMean(0.0);
    for (const auto& [column, wx] : columns)
    {
      rowMean += (wx / columnsTotal) * image.at(column, row);
    }
    mean += (wy / rowsTotal) * rowMean;
  }
  return mean;
}

Rgb BoxFilteredTexture::mean(double u, double v, double side) const
{
  const double texels = std::min(side, double(image_.width)) * std::min(side, double(image_.height));
  if (!(texels > 64 * 64) || !std::isfinite(u) || !std::isfinite(v) || !std::isfinite(side))
  {
    return boxMean(image_, u, v, side);
  }
  if (sums_.empty())
  {
    const std::size_t columns = std::size_t(image_.width) + 1;
    sums_.assign(columns * (std::size_t(image_.height) + 1), Rgb(0.0));
    for (int j = 0; j < image_.height; ++j)
    {
      for (int i = 0; i < image_.width; ++i)
      {
        sums_[(j + 1) * columns + i + 1] =
          image_.at(i, j) + sums_[j * columns + i + 1] + sums_[(j + 1) * columns + i] - sums_[j * columns + i];
      }
    }
  }
  side = std::min(side, 1048576.0 * std::max(image_.width, image_.height)); // as boxMean clamps it
  const double x0 = (u - std::floor(u)) * image_.width - side / 2, y0 = (v - std::floor(v)) * image_.height - side / 2;
  const double x1 = x0 + side, y1 = y0 + side;
  return (sumTo(x1, y1) - sumTo(x0, y1) - sumTo(x1, y0) + sumTo(x0, y0)) / (side * side);
}

Rgb BoxFilteredTexture::sumTo(double x, double y) const
{
  // x = a width + r, y = b height + t, r and t within a repeat: a b whole repeats, a strips of
  // [0, width) x [0, t), b strips of [0, r) x [0, height), and [0, r) x [0, t).
  const double a = std::floor(x / image_.width), b = std::floor(y / image_.height);
  const double r = x - a * image_.width, t = y - b * image_.height;
  const double w = image_.width, h = image_.height;
  return a * b * sumWithin(w, h) + a * sumWithin(w, t) + b * sumWithin(r, h) + sumWithin(r, t);
}

Rgb BoxFilteredTexture::sumWithin(double x, double y) const
{
  const std::size_t columns = std::size_t(image_.width) + 1;
  const int i = std::clamp(int(std::floor(x)), 0, image_.width - 1),
            j = std::clamp(int(std::floor(y)), 0, image_.height - 1);
  const double fx = std::clamp(x - i, 0.0, 1.0), fy = std::clamp(y - j, 0.0, 1.0);
  auto at = [&](int column, int row) { return sums_[std::size_t(row) * columns + std::size_t(column)]; };
  return (1 - fy) * ((1 - fx) * at(i, j) + fx * at(i + 1, j)) + fy * ((1 - fx) * at(i, j + 1) + fx * at(i + 1, j + 1));
}

std::vector<double> texelFootprints(const std::vector<std::array<double, 3>>& positions,
  const std::vector<std::array<double, 2>>& uv, const PolygonList& polygons, int width, int height)
{
  std::size_t surfacePoints = 0;
  const std::vector<std::size_t> surfacePoint = surfacePointsOf(positions, uv, surfacePoints);
  auto inTexels = [&](PointId p) { return glm::dvec3(uv[p][0] * width, uv[p][1] * height, 0); };
  std::vector<double> area(surfacePoints, 0.0);
  for (std::size_t k = 0; k < polygons.count; ++k)
  {
    const PointId* ids = polygons.ids(k);
    for (std::size_t i = 2; i < polygons.size(k); ++i)
    {
      // Each triangle of the polygon's fan gives a third of its texture area to its corners.
      const PointId triangle[3] = { ids[0], ids[i - 1], ids[i] };
      const double third = std::abs(polygonAreaVector(triangle, 3, inTexels).z) / 3;
      for (PointId corner : triangle)
      {
        area[surfacePoint[std::size_t(corner)]] += third;
      }
    }
  }
  std::vector<double> side(positions.size());
  for (std::size_t p = 0; p < positions.size(); ++p)
  {
    side[p] = std::sqrt(area[surfacePoint[p]]);
  }
  return side;
}
}
