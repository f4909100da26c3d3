#include "TextureStudies.h"

#include "TextureFootprint.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <random>
#include <tuple>

namespace shadelab::app
{
namespace
{
constexpr int textureSide = 1024;

/// A checker of 2-texel squares, grey 0.1 and 0.9: the finest detail a texture can hold but one.
RgbImage fineChecker()
{
  RgbImage image{ textureSide, textureSide, {} };
  image.texels.resize(std::size_t(textureSide) * textureSide);
  for (int row = 0; row < textureSide; ++row)
  {
    for (int column = 0; column < textureSide; ++column)
    {
      image.texels[std::size_t(row) * textureSide + column] = Rgb(((row / 2 + column / 2) % 2) ? 0.9 : 0.1);
    }
  }
  return image;
}

/// fineChecker's exact mean over the texels [x0, x1] x [y0, y1], worked out rather than summed,
/// so that the study's truth is not the box filter's own code: the checker is 0.5 - 0.4 s(x)
/// s(y), s the square wave +1 on [0, 2) and -1 on [2, 4) texels, whose integral from 0 is the
/// triangle wave below (periodic: s sums to 0 over a period).
Rgb checkerMean(double x0, double x1, double y0, double y1)
{
  auto integral = [](double x)
  {
    const double r = x - 4 * std::floor(x / 4);
    return r < 2 ? r : 4 - r;
  };
  auto mean = [&](double a, double b) { return (integral(b) - integral(a)) / (b - a); };
  return Rgb(0.5 - 0.4 * mean(x0, x1) * mean(y0, y1));
}

/// Waves of about three frequencies an octave from 1 to 231 cycles across the texture, all of
/// one amplitude, each with a random phase and direction (a fixed seed), each channel its own:
/// the same power in every octave, as in a photograph, whose amplitude spectrum falls as 1/f
/// (the octaves' bands widen as f). Scaled into [0, 1]; whole cycles across the texture, so
/// that it repeats without a seam.
RgbImage detailFallingAsOneOverF()
{
  std::mt19937 random(16);
  std::uniform_real_distribution<double> phase(0, 2 * M_PI);
  struct Wave
  {
    int cyclesU, cyclesV;
    double amplitude, phase;
  };
  std::array<std::vector<Wave>, 3> waves;
  for (auto& channel : waves)
  {
    for (int f = 1; f <= 256; f = f * 5 / 4 + 1)
    {
      const double angle = phase(random);
      channel.push_back(
        { int(std::lround(f * std::cos(angle))), int(std::lround(f * std::sin(angle))), 1.0, phase(random) });
    }
  }
  RgbImage image{ textureSide, textureSide, {} };
  image.texels.resize(std::size_t(textureSide) * textureSide);
  std::array<double, 3> low{ 1e30, 1e30, 1e30 }, high{ -1e30, -1e30, -1e30 };
  for (int row = 0; row < textureSide; ++row)
  {
    for (int column = 0; column < textureSide; ++column)
    {
      Rgb& texel = image.texels[std::size_t(row) * textureSide + column];
      for (int c = 0; c < 3; ++c)
      {
        double sum = 0;
        for (const Wave& w : waves[std::size_t(c)])
        {
          sum += w.amplitude *
            std::sin(2 * M_PI * (w.cyclesU * (column + 0.5) + w.cyclesV * (row + 0.5)) / textureSide + w.phase);
        }
        texel[c] = sum;
        low[std::size_t(c)] = std::min(low[std::size_t(c)], sum);
        high[std::size_t(c)] = std::max(high[std::size_t(c)], sum);
      }
    }
  }
  for (Rgb& texel : image.texels)
  {
    for (int c = 0; c < 3; ++c)
    {
      texel[c] = (texel[c] - low[std::size_t(c)]) / (high[std::size_t(c)] - low[std::size_t(c)]);
    }
  }
  return image;
}

/// An n x n grid of points over the texture's square, each cell two triangles split along the
/// diagonal from its (i, j) corner. The grid starts 0.31 texels in and stops 0.31 short of the
/// far edge, so that its points fall on texel corners no more than by chance (a point on a corner
/// point-samples the mean of the texels around it) and its cells do not meet the texture's repeat.
struct TexturedGrid
{
  static constexpr double inset = 0.31; // texels
  int n = 0;
  double step = 0; // in texture coordinates
  std::vector<std::array<double, 3>> positions;
  std::vector<std::array<double, 2>> uv;
  std::vector<PointId> offsets, connectivity;

  explicit TexturedGrid(int side)
    : n(side)
    , step((1.0 - 2 * inset / textureSide) / (n - 1))
  {
    positions.reserve(std::size_t(n) * n);
    uv.reserve(std::size_t(n) * n);
    for (int j = 0; j < n; ++j)
    {
      for (int i = 0; i < n; ++i)
      {
        positions.push_back({ double(i), double(j), 0.0 });
        uv.push_back({ coordinate(i), coordinate(j) });
      }
    }
    offsets.push_back(0);
    for (int j = 0; j + 1 < n; ++j)
    {
      for (int i = 0; i + 1 < n; ++i)
      {
        for (const PointId corner :
          { at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1) })
        {
          connectivity.push_back(corner);
          if (connectivity.size() % 3 == 0)
          {
            offsets.push_back(PointId(connectivity.size()));
          }
        }
      }
    }
  }
  /// The texture coordinate of the i-th row or column of points (i + 1/2: a cell's centre).
  double coordinate(double i) const { return inset / textureSide + i * step; }
  double cellTexels() const { return step * textureSide; }
  PointId at(int i, int j) const { return PointId(j) * n + i; }
  PolygonList triangles() const { return { offsets.data(), connectivity.data(), offsets.size() - 1 }; }
};

/// The colour each point takes, and the milliseconds that took.
struct PointColours
{
  std::vector<Rgb> colours;
  double milliseconds = 0;
};

/// How a point's colour is taken from the texture; "box" with the footprint's side.
PointColours coloursOf(const TexturedGrid& grid, const RgbImage& image, const std::string& method)
{
  const auto start = std::chrono::steady_clock::now();
  PointColours result;
  result.colours.resize(grid.uv.size());
  if (method == "box")
  {
    const std::vector<double> sides =
      texelFootprints(grid.positions, grid.uv, grid.triangles(), image.width, image.height);
    const BoxFilteredTexture filtered(image);
    for (std::size_t p = 0; p < grid.uv.size(); ++p)
    {
      result.colours[p] = filtered.mean(grid.uv[p][0], grid.uv[p][1], sides[p]);
    }
  }
  else
  {
    // A square within one texel is the texel (point sampling); one texel wide, it is bilinear.
    const double side = method == "point" ? 1e-9 : 1.0;
    for (std::size_t p = 0; p < grid.uv.size(); ++p)
    {
      result.colours[p] = boxMean(image, grid.uv[p][0], grid.uv[p][1], side);
    }
  }
  result.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return result;
}

/// The texture's mean over the texels [x0, x1] x [y0, y1].
using CellMean = std::function<Rgb(double x0, double x1, double y0, double y1)>;

/// Per cell, the largest channel's |the mean of the colours interpolated over the cell's two
/// triangles - the texture's mean over the cell|: the largest and the RMS over the cells.
std::pair<double, double> cellErrors(
  const TexturedGrid& grid, const CellMean& cellMean, const std::vector<Rgb>& colours)
{
  double largest = 0, squares = 0;
  for (int j = 0; j + 1 < grid.n; ++j)
  {
    for (int i = 0; i + 1 < grid.n; ++i)
    {
      // Each triangle's mean is its corners' mean; the cell's, the two triangles' mean.
      const Rgb drawn = (2.0 * colours[grid.at(i, j)] + colours[grid.at(i + 1, j)] +
                          2.0 * colours[grid.at(i + 1, j + 1)] + colours[grid.at(i, j + 1)]) /
        6.0;
      const Rgb truth = cellMean(grid.coordinate(i) * textureSide, grid.coordinate(i + 1) * textureSide,
        grid.coordinate(j) * textureSide, grid.coordinate(j + 1) * textureSide);
      const double error = largestComponent(glm::abs(drawn - truth));
      largest = std::max(largest, error);
      squares += error * error;
    }
  }
  return { largest, std::sqrt(squares / (double(grid.n - 1) * (grid.n - 1))) };
}
}

std::vector<AccuracyRow> textureFilteringStudy(ChartSpec& chart)
{
  const std::string study = "16 texture filtering";
  std::vector<AccuracyRow> rows;
  chart.title = "16 a texture at vertices: error of the colours drawn over each cell";
  chart.xTitle = "texels per vertex (a side of its square)";
  chart.yTitle = "RMS |drawn mean - texture's mean| over the cells";
  chart.logX = chart.logY = true;
  chart.legendOutside = true;
  // The waves' truth is the table of sums (BoxFilteredTexture), which the unit tests check
  // against texel-by-texel sums; the checker's is worked out.
  const RgbImage checker = fineChecker(), waves = detailFallingAsOneOverF();
  const BoxFilteredTexture summed(waves);
  const CellMean wavesMean = [&](double x0, double x1, double y0, double y1)
  { return summed.mean((x0 + x1) / (2 * textureSide), (y0 + y1) / (2 * textureSide), x1 - x0); };
  const std::vector<std::tuple<std::string, const RgbImage*, CellMean>> textures = {
    { "checker", &checker, checkerMean }, { "1/f detail", &waves, wavesMean }
  };
  const std::vector<std::pair<std::string, std::string>> methods = { { "point", "point sampling" },
    { "bilinear", "bilinear" }, { "box", "box over the footprint (ShadeLab)" } };
  for (std::size_t t = 0; t < textures.size(); ++t)
  {
    for (std::size_t m = 0; m < methods.size(); ++m)
    {
      const auto& [name, image, cellMean] = textures[t];
      ChartSeries series{ name + ", " + methods[m].second, {}, {}, true, palette[m], true, t == 1 };
      for (const int n : { 9, 17, 33, 65, 129, 257, 513, 1025, 2049 })
      {
        const TexturedGrid grid(n);
        const PointColours colours = coloursOf(grid, *image, methods[m].first);
        const auto [largest, rms] = cellErrors(grid, cellMean, colours.colours);
        const double texelsPerVertex = grid.cellTexels();
        rows.push_back({ study, name + ": " + methods[m].second, "texels per vertex", texelsPerVertex,
          static_cast<long long>(n) * n, colours.milliseconds, largest, rms, std::nullopt, "" });
        series.x.push_back(texelsPerVertex);
        series.y.push_back(rms);
      }
      chart.series.push_back(series);
    }
  }
  return rows;
}
}
