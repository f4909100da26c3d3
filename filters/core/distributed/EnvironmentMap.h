#pragma once
// Equirectangular (latitude-longitude) environment maps: linear RGB radiance arriving from
// every direction, for lighting meshes by HDR images.
//
// Orientation: +y is up. Image coordinates u in [0,1] left to right, v in [0,1] top to
// bottom. Polar angle from +y: theta = pi v. Azimuth phi = 2 pi (u - 0.5).
// Direction = (sin theta sin phi, cos theta, -sin theta cos phi). So the image centre
// (u = 0.5, v = 0.5) is -z (what a default VTK camera looks at), u = 0.75 is +x, u = 0.25 is
// -x, u = 0 and 1 are +z, the top row is +y. This shows the map as seen from inside the
// sphere, not mirrored.
//
// Texel (column, row) covers u in [column, column + 1] / width and v in [row, row + 1] / height.
#include "Vec3.h"

#include <glm/ext/vector_int2.hpp>
#include <glm/vec2.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace shadelab
{
struct EnvironmentMap
{
  int width = 0;
  int height = 0;
  std::vector<Rgb> radiance; // row-major, row 0 at the top

  const Rgb& texel(int column, int row) const { return radiance[static_cast<std::size_t>(row) * width + column]; }
};

/// Throws std::invalid_argument, naming `user`, unless the map has at least one texel and
/// radiance holds exactly width x height of them: texel() does not check its indices.
void requireValidShape(const EnvironmentMap& map, const char* user);

/// The unit direction at image coordinates (u, v), as in the orientation above.
glm::dvec3 directionAt(double u, double v);

/// The inverse of directionAt: u in [0, 1), v in [0, 1]. At the poles, where every u gives
/// the same direction, u is 0.
glm::dvec2 uvOfDirection(const glm::dvec3& unitDirection);

glm::dvec3 texelCentreDirection(const EnvironmentMap& map, int column, int row);

/// The (column, row) of the texel a unit direction falls in.
glm::ivec2 texelToward(const EnvironmentMap& map, const glm::dvec3& unitDirection);

/// The exact solid angle of any texel of the row in a width x height map.
double texelSolidAngle(int row, int width, int height);

/// Luminance of linear RGB with the Rec. 709 (sRGB) primaries.
double luminance(const Rgb& rgb);

/// The largest map readEnvironmentMap takes: 16384 x 8192 texels (1.6 GB as float RGB, and
/// finer than any per-vertex estimate can use).
constexpr std::size_t maxEnvironmentTexels = std::size_t(16384) * 8192;

/// Reads an equirectangular map with OpenImageIO (Radiance .hdr, OpenEXR, anything it reads):
/// the first three channels as RGB, or one channel as grey. Throws std::runtime_error
/// "<path>: <what is wrong>" for a missing or unreadable file, an empty image, 2 channels,
/// a shape other than 2:1, more texels than maxEnvironmentTexels or than the file's size can
/// hold (64 per byte, at least 4096), and a negative or non-finite texel.
EnvironmentMap readEnvironmentMap(const std::string& path);

/// A 2:1 map `width` texels wide, `width` an even divisor of map.width: each texel is the
/// solid-angle-weighted mean radiance of the texels it covers, so the integral of radiance
/// over the sphere is kept. Throws std::invalid_argument for any other width or a map that
/// is not 2:1.
EnvironmentMap downsampled(const EnvironmentMap& map, int width);
}
