// A texture averaged over the texels a vertex stands for (docs/formulas.md section 7.2): exact
// at texel centres, bilinear between them, the texture's mean over a whole repeat, and the
// footprint of a regular grid's vertices one grid step.
#include "TextureFootprint.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
using namespace shadelab;

/// A 4 x 3 image whose texel (i, j) is (i, j, i j).
RgbImage rampImage()
{
  RgbImage image;
  image.width = 4;
  image.height = 3;
  for (int j = 0; j < 3; ++j)
  {
    for (int i = 0; i < 4; ++i)
    {
      image.texels.push_back(Rgb(i, j, i * j));
    }
  }
  return image;
}

double centre(int texel, int count)
{
  return (texel + 0.5) / count;
}

TEST(TextureFootprint, ATexelsCentreGivesTheTexel)
{
  const RgbImage image = rampImage();
  for (int j = 0; j < 3; ++j)
  {
    for (int i = 0; i < 4; ++i)
    {
      for (double side : { 0.0, 0.5, 1.0 }) // within the texel
      {
        EXPECT_EQ(boxMean(image, centre(i, 4), centre(j, 3), side), image.at(i, j)) << i << ", " << j;
      }
    }
  }
}

TEST(TextureFootprint, WithinATexelItIsTheTexel)
{
  const RgbImage image = rampImage();
  // Texel (2, 1) spans u in [0.5, 0.75), v in [1/3, 2/3): a square of 0.2 texels near its corner.
  EXPECT_EQ(boxMean(image, 0.5 + 0.11 / 4, 1.0 / 3 + 0.11 / 3, 0.2), image.at(2, 1));
  // Across its left edge, 0.1 of 0.2 texels on each side: half and half.
  const Rgb mixed = boxMean(image, 0.5, 0.5, 0.2);
  EXPECT_NEAR(mixed.x, 0.5 * (image.at(1, 1).x + image.at(2, 1).x), 1e-12);
}

TEST(TextureFootprint, OneTexelWideItIsBilinear)
{
  const RgbImage image = rampImage();
  // A quarter of the way from texel (1, 1)'s centre to (2, 2)'s: weights 3/4 and 1/4 each way.
  const Rgb mean = boxMean(image, (1.5 + 0.25) / 4, (1.5 + 0.25) / 3, 1);
  const Rgb expected = 0.75 * 0.75 * image.at(1, 1) + 0.25 * 0.75 * image.at(2, 1) + 0.75 * 0.25 * image.at(1, 2) +
    0.25 * 0.25 * image.at(2, 2);
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(mean[c], expected[c], 1e-15);
  }
}

TEST(TextureFootprint, AWholeRepeatIsTheTexturesMean)
{
  RgbImage image = rampImage();
  image.height = 4; // square, so that a square of 4 texels is one whole repeat
  for (int i = 0; i < 4; ++i)
  {
    image.texels.push_back(Rgb(i, 3, 3 * i));
  }
  Rgb mean(0.0);
  for (const Rgb& texel : image.texels)
  {
    mean += texel / double(image.texels.size());
  }
  for (double u : { 0.0, 0.3, -2.7, 15.1 })
  {
    for (double side : { 4.0, 8.0, 4e12 }) // whole repeats, and one clamped to 2^20 of them
    {
      const Rgb box = boxMean(image, u, 0.6, side);
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_NEAR(box[c], mean[c], 1e-9) << "u " << u << ", side " << side;
      }
    }
  }
  EXPECT_TRUE(std::isnan(boxMean(image, NAN, 0.5, 1).x));
}

TEST(TextureFootprint, LargeSquaresFromTheTableOfSumsAgreeWithTexelByTexel)
{
  // A 96 x 80 image of varied texels; squares from 65 texels (the table's) to several repeats.
  RgbImage image;
  image.width = 96;
  image.height = 80;
  for (int j = 0; j < image.height; ++j)
  {
    for (int i = 0; i < image.width; ++i)
    {
      image.texels.push_back(Rgb(std::sin(i * 0.37 + j), (i * j) % 7, std::cos(0.1 * i * j)));
    }
  }
  const BoxFilteredTexture texture(image);
  for (double side : { 65.5, 80.0, 150.25, 400.0 })
  {
    for (double u : { 0.013, 0.5, 0.97, 3.4, -1.2 })
    {
      const Rgb fromTable = texture.mean(u, 0.31, side), byTexels = boxMean(image, u, 0.31, side);
      for (int c = 0; c < 3; ++c)
      {
        EXPECT_NEAR(fromTable[c], byTexels[c], 1e-9) << "side " << side << ", u " << u;
      }
    }
  }
  EXPECT_EQ(texture.mean(0.3, 0.4, 10), boxMean(image, 0.3, 0.4, 10)); // small: texel by texel
}

TEST(TextureFootprint, AGridVertexStandsForOneGridStep)
{
  // A 5 x 5 grid of vertices over a 64 x 32 texture, one step 0.25 in u and v: 16 x 8 texels,
  // so an inner vertex's square has the area of one step, sqrt(16 x 8) texels a side. Each
  // triangle's corners are points of their own (as an OBJ importer keeps them).
  std::vector<std::array<double, 3>> positions;
  std::vector<std::array<double, 2>> uv;
  std::vector<PointId> offsets = { 0 }, connectivity;
  auto corner = [&](int i, int j)
  {
    positions.push_back({ double(i), double(j), 0 });
    uv.push_back({ i * 0.25, j * 0.25 });
    connectivity.push_back(PointId(positions.size() - 1));
  };
  for (int j = 0; j < 4; ++j)
  {
    for (int i = 0; i < 4; ++i)
    {
      corner(i, j);
      corner(i + 1, j);
      corner(i + 1, j + 1);
      offsets.push_back(PointId(connectivity.size()));
      corner(i, j);
      corner(i + 1, j + 1);
      corner(i, j + 1);
      offsets.push_back(PointId(connectivity.size()));
    }
  }
  const PolygonList triangles{ offsets.data(), connectivity.data(), offsets.size() - 1 };
  const std::vector<double> sides = texelFootprints(positions, uv, triangles, 64, 32);
  for (std::size_t p = 0; p < positions.size(); ++p)
  {
    const bool inner = positions[p][0] > 0 && positions[p][0] < 4 && positions[p][1] > 0 && positions[p][1] < 4;
    if (inner)
    {
      EXPECT_NEAR(sides[p], std::sqrt(16.0 * 8.0), 1e-12) << "point " << p;
    }
  }
  // The corner (0, 0) has two triangles (its cell's diagonal starts there), a third of a step;
  // the corner (4, 0), the last cell's first triangle's second point, one: a sixth.
  EXPECT_NEAR(sides[0], std::sqrt(16.0 * 8.0 / 3), 1e-12);
  EXPECT_NEAR(sides[3 * 6 + 1], std::sqrt(16.0 * 8.0 / 6), 1e-12);
}

TEST(TextureFootprint, APolygonGivesEachTriangleOfItsFanToItsCorners)
{
  // One quad over the whole of a 4 x 4 texture, 16 texels: its fan's two triangles, of 8 texels
  // each, give a third to their corners, so corners 0 and 2 (in both) stand for 16/3 texels.
  const std::vector<std::array<double, 3>> positions = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 } };
  const std::vector<std::array<double, 2>> uv = { { 0, 0 }, { 1, 0 }, { 1, 1 }, { 0, 1 } };
  const PointId offsets[2] = { 0, 4 }, connectivity[4] = { 0, 1, 2, 3 };
  const std::vector<double> sides = texelFootprints(positions, uv, PolygonList{ offsets, connectivity, 1 }, 4, 4);
  EXPECT_NEAR(sides[0], std::sqrt(16.0 / 3), 1e-12);
  EXPECT_NEAR(sides[1], std::sqrt(8.0 / 3), 1e-12);
  EXPECT_NEAR(sides[2], std::sqrt(16.0 / 3), 1e-12);
  EXPECT_NEAR(sides[3], std::sqrt(8.0 / 3), 1e-12);
}
}
