#include "EnvironmentMap.h"
#include "ImageFile.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace shadelab
{
namespace
{
constexpr double pi = glm::pi<double>();

bool isRadiance(double value)
{
  return std::isfinite(value) && value >= 0.0;
}

std::string shapeText(int width, int height)
{
  return std::to_string(width) + "x" + std::to_string(height);
}

/// atan(k / 8) for k = 0 .. 8, the points about which quickAtan2 expands.
const std::array<double, 9>& atanOfEighths()
{
  static const std::array<double, 9> table = []
  {
    std::array<double, 9> atans{};
    for (int k = 0; k <= 8; ++k)
    {
      atans[std::size_t(k)] = std::atan(k / 8.0);
    }
    return atans;
  }();
  return table;
}

/// atan2(y, x) within 1e-11 for finite (y, x) not both 0 (otherwise NaN): the library's atan2 took
/// a tenth of a map's samples drawn by the lobe. The smaller magnitude over the larger, a in
/// [0, 1], has atan(a) = atan(c) + atan(t) with t = (a - c) / (1 + a c) for the c = k / 8 nearest
/// a, so |t| <= 1/16, and atan(t) is its series to t^7 (what is left is below t^9 / 9 < 5e-12).
double quickAtan2(double y, double x)
{
  if (!std::isfinite(x) || !std::isfinite(y) || (x == 0 && y == 0))
  {
    return std::numeric_limits<double>::quiet_NaN(); // the library's atan2 answers
  }
  const double ay = std::abs(y), ax = std::abs(x);
  const double larger = std::max(ay, ax), smaller = std::min(ay, ax);
  const double a = smaller / larger;
  const int k = static_cast<int>(8 * a + 0.5);
  const double c = k / 8.0;
  const double t = (a - c) / (1 + a * c);
  const double t2 = t * t;
  const double reduced = atanOfEighths()[std::size_t(k)] + t * (1 - t2 * (1.0 / 3 - t2 * (1.0 / 5 - t2 / 7)));
  const double firstOctant = ay > ax ? pi / 2 - reduced : reduced;
  const double halfPlane = x < 0 ? pi - firstOctant : firstOctant;
  return y < 0 ? -halfPlane : halfPlane;
}

/// Whether a position along a map's columns or rows lies farther than quickAtan2's error from a
/// texel's edge (false for NaN), so that its texel is the one the library's atan2 gives.
bool clearOfTexelEdges(double position)
{
  const double intoTexel = position - std::floor(position);
  return intoTexel > 1e-6 && intoTexel < 1 - 1e-6;
}
}

void requireValidShape(const EnvironmentMap& map, const char* user)
{
  if (map.width <= 0 || map.height <= 0 || map.radiance.size() != static_cast<std::size_t>(map.width) * map.height)
  {
    throw std::invalid_argument(std::string(user) + ": the map is " + shapeText(map.width, map.height) + " but holds " +
      std::to_string(map.radiance.size()) + " texels; it needs at least one texel and width x height of them");
  }
}

glm::dvec3 directionAt(double u, double v)
{
  const double theta = pi * v;
  const double phi = 2.0 * pi * (u - 0.5);
  const double sinTheta = std::sin(theta);
  return { sinTheta * std::sin(phi), std::cos(theta), -sinTheta * std::cos(phi) };
}

glm::dvec2 uvOfDirection(const glm::dvec3& unitDirection)
{
  const glm::dvec3& d = unitDirection;
  // atan2 of the pair keeps full precision near the poles, where acos(y) loses half the
  // digits (Kahan, as in Reflectance.h).
  const double theta = std::atan2(std::sqrt(d.x * d.x + d.z * d.z), d.y);
  const double phi = std::atan2(d.x, -d.z);
  const double u = phi / (2.0 * pi) + 0.5;
  // phi = pi (and phi just below it, by rounding) is u = 1, the same direction as u = 0.
  return { u < 1.0 ? u : 0.0, theta / pi };
}

glm::dvec3 texelCentreDirection(const EnvironmentMap& map, int column, int row)
{
  return directionAt((column + 0.5) / map.width, (row + 0.5) / map.height);
}

glm::ivec2 texelToward(const EnvironmentMap& map, const glm::dvec3& unitDirection)
{
  // uvOfDirection's angles from quickAtan2, and from the library's atan2 where a texel's edge lies
  // within quickAtan2's error: the same texels.
  const glm::dvec3& d = unitDirection;
  const double column = (quickAtan2(d.x, -d.z) / (2.0 * pi) + 0.5) * map.width;
  const double row = quickAtan2(std::sqrt(d.x * d.x + d.z * d.z), d.y) / pi * map.height;
  if (clearOfTexelEdges(column) && clearOfTexelEdges(row))
  {
    return { static_cast<int>(column), static_cast<int>(row) };
  }
  const glm::dvec2 uv = uvOfDirection(unitDirection);
  // min: v = 1 exactly (the bottom pole) belongs to the last row.
  return { std::min(static_cast<int>(uv.x * map.width), map.width - 1),
    std::min(static_cast<int>(uv.y * map.height), map.height - 1) };
}

// Solid angle is the integral of sin(theta) dtheta dphi. Over a texel, phi spans 2 pi / W and
// theta spans [a, b] = pi [row, row + 1] / H, so it is (2 pi / W)(cos a - cos b), written as
// (2 pi / W) 2 sin((a + b) / 2) sin((b - a) / 2) to avoid the cancellation of cos a - cos b
// near the poles. For small texels this is (2 pi / W)(pi / H) sin(theta) (docs/formulas.md
// section 12.2).
double texelSolidAngle(int row, int width, int height)
{
  const double centreTheta = pi * (row + 0.5) / height;
  const double halfSpan = 0.5 * pi / height;
  return (2.0 * pi / width) * 2.0 * std::sin(centreTheta) * std::sin(halfSpan);
}

// ITU-R BT.709-6's luminance equation Y = 0.2126 R + 0.7152 G + 0.0722 B. On linear RGB it is
// the Y row of the RGB-to-XYZ matrix of its primaries and D65 white (shared by sRGB).
double luminance(const Rgb& rgb)
{
  return 0.2126 * rgb.r + 0.7152 * rgb.g + 0.0722 * rgb.b;
}

EnvironmentMap readEnvironmentMap(const std::string& path)
{
  const std::unique_ptr<ImageFile> input = ImageFile::open(path);
  const int width = input->width(), height = input->height(), fileChannels = input->channels();
  if (width <= 0 || height <= 0)
  {
    throw std::runtime_error(path + ": the image is empty (" + shapeText(width, height) + ")");
  }
  if (fileChannels != 1 && fileChannels < 3)
  {
    throw std::runtime_error(
      path + ": has " + std::to_string(fileChannels) + " channels; expected 1 (grey) or 3 or more (RGB)");
  }
  if (static_cast<long long>(width) != 2LL * height)
  {
    throw std::runtime_error(
      path + ": an equirectangular map must be twice as wide as it is high; this one is " + shapeText(width, height));
  }

  const int channels = fileChannels == 1 ? 1 : 3;
  const std::size_t texels = static_cast<std::size_t>(width) * height;
  std::error_code ignored;
  const std::uintmax_t fileBytes = std::filesystem::file_size(path, ignored);
  if (texels > mostTexelsIn(fileBytes) || texels > maxEnvironmentTexels)
  {
    std::ostringstream message;
    message << path << ": the header declares " << shapeText(width, height) << " texels ("
            << static_cast<double>(texels) * channels * sizeof(float) / 1e9 << " GB as floats), more than "
            << (texels > maxEnvironmentTexels ? "ShadeLab takes (" + std::to_string(maxEnvironmentTexels) + " texels)"
                                              : "a file of " + std::to_string(fileBytes) + " bytes can hold")
            << ": it is damaged, or too large a map";
    throw std::runtime_error(message.str());
  }
  std::vector<float> pixels(texels * channels);
  input->read(channels, pixels.data());

  EnvironmentMap map;
  map.width = width;
  map.height = height;
  map.radiance.resize(texels);
  for (std::size_t i = 0; i < texels; ++i)
  {
    const float* p = &pixels[i * channels];
    const Rgb value = channels == 1 ? Rgb(p[0]) : Rgb(p[0], p[1], p[2]);
    if (!isRadiance(value.r) || !isRadiance(value.g) || !isRadiance(value.b))
    {
      std::ostringstream message;
      message << path << ": texel (column " << i % map.width << ", row " << i / map.width
              << ") is not a finite non-negative radiance (" << value.r << ", " << value.g << ", " << value.b << ")";
      throw std::runtime_error(message.str());
    }
    map.radiance[i] = value;
  }
  return map;
}

EnvironmentMap downsampled(const EnvironmentMap& map, int width)
{
  requireValidShape(map, "downsampled");
  if (map.width != 2 * map.height)
  {
    throw std::invalid_argument(
      "downsampled: the map is " + shapeText(map.width, map.height) + "; only a 2:1 map can be downsampled");
  }
  if (width < 2 || width % 2 != 0 || map.width % width != 0)
  {
    throw std::invalid_argument("downsampled: width " + std::to_string(width) +
      " must be an even divisor of the map's width " + std::to_string(map.width) + " and at least 2");
  }
  // Each coarse texel covers factor x factor fine ones, as both maps are 2:1.
  const int factor = map.width / width;
  EnvironmentMap coarse;
  coarse.width = width;
  coarse.height = width / 2;
  coarse.radiance.assign(static_cast<std::size_t>(coarse.width) * coarse.height, Rgb(0.0));
  for (int coarseRow = 0; coarseRow < coarse.height; ++coarseRow)
  {
    Rgb* sums = &coarse.radiance[static_cast<std::size_t>(coarseRow) * coarse.width];
    double solidAngleSum = 0.0; // of the fine texels under one coarse texel
    for (int row = coarseRow * factor; row < (coarseRow + 1) * factor; ++row)
    {
      const double solidAngle = texelSolidAngle(row, map.width, map.height);
      solidAngleSum += factor * solidAngle;
      for (int column = 0; column < map.width; ++column)
      {
        sums[column / factor] += map.texel(column, row) * solidAngle;
      }
    }
    // Dividing by the weights' own sum, equal to the coarse texel's solid angle to rounding,
    // makes each texel a true weighted mean: a constant map stays constant.
    for (int column = 0; column < coarse.width; ++column)
    {
      sums[column] /= solidAngleSum;
    }
  }
  return coarse;
}
}
