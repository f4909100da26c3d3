#pragma once
// A texture's colour at a vertex, averaged over the texels the vertex stands for
// (docs/formulas.md section 7.2). Sampling a texture at the vertex alone (point sampling) takes
// one texel's colour where a vertex stands for many, and so aliases where the texture is finer
// than the mesh; a box filter over the vertex's share of the texture does not.
#include "PointNormals.h"
#include "Vec3.h"

#include <array>
#include <cstddef>
#include <vector>

namespace shadelab
{
/// An image of linear RGB texels, row by row from the row at texture coordinate v = 0 (VTK's
/// image order), repeated beyond [0, 1) in both directions (a texture's default wrap).
struct RgbImage
{
  int width = 0;
  int height = 0;
  std::vector<Rgb> texels; // width * height

  const Rgb& at(int column, int row) const { return texels[std::size_t(row) * std::size_t(width) + column]; }
};

/// The mean of the image over the square of side `side` texels centred at the texture
/// coordinates (u, v), each texel weighted by the part of it the square covers. A square within
/// one texel is that texel's colour (where the mesh is finer than the texture, each vertex takes
/// the texel it stands in, and only vertices near a texel's edge mix), and a square of one texel
/// is bilinear interpolation between texel centres.
Rgb boxMean(const RgbImage& image, double u, double v, double side);

/// boxMean for many squares of one image: squares over more than 64 x 64 texels (a vertex that
/// stands for a whole repeat of a tiled texture, or more) are summed from a table of the
/// image's sums over [0, x) x [0, y) (built at the first such square, 24 bytes a texel), in a
/// time that does not grow with the square; smaller ones as boxMean sums them, texel by texel.
class BoxFilteredTexture
{
public:
  explicit BoxFilteredTexture(const RgbImage& image)
    : image_(image)
  {
  }
  Rgb mean(double u, double v, double side) const;

private:
  /// The image's sum over [0, x) x [0, y) of the repeated texture, x and y in texels.
  Rgb sumTo(double x, double y) const;
  /// The sum over [0, x) x [0, y) within one repeat, 0 <= x <= width and 0 <= y <= height:
  /// the table's corners interpolated, exact since the sum is bilinear within a texel.
  Rgb sumWithin(double x, double y) const;

  const RgbImage& image_;
  mutable std::vector<Rgb> sums_; // (width + 1) x (height + 1), from the first large square
};

/// The side, in texels of a width x height texture, of the square each point stands for: the
/// square root of a third of the texture area of the triangles around it. Points that are one
/// surface point read as several (the same position and texture coordinates: an OBJ's corners)
/// share their triangles. positions and uv hold each point's; a polygon counts as the triangles
/// of its fan.
std::vector<double> texelFootprints(const std::vector<std::array<double, 3>>& positions,
  const std::vector<std::array<double, 2>>& uv, const PolygonList& polygons, int width, int height);
}
