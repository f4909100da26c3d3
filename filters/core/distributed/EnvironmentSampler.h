#pragma once
// Importance sampling of an environment map by luminance, for Monte Carlo estimates of
// integrals over the sphere such as the irradiance sum f / pdf. The density over the image
// (u, v) is piecewise constant, proportional to luminance x sin(theta) of each texel's centre
// (the sin(theta) because a texel's solid angle shrinks towards the poles), and is sampled
// as a 2D piecewise-constant distribution: a row from the marginal distribution of rows,
// then a column from that row's conditional distribution (Pharr, Jakob and Humphreys,
// "Physically Based Rendering", 3rd ed.: piecewise-constant 2D distributions in section 13.6,
// infinite area lights in section 14.2). The density per solid angle is the density over
// (u, v) divided by 2 pi^2 sin(theta), as dw = sin(theta) dtheta dphi = 2 pi^2 sin(theta) du dv.
#include "EnvironmentMap.h"

#include <vector>

namespace shadelab
{
struct SineCosine
{
  double sin, cos;
};

struct EnvironmentSample
{
  glm::dvec3 direction;
  double pdf;   // per unit solid angle
  Rgb radiance; // of the texel hit
};

class EnvironmentSampler
{
public:
  /// Throws std::invalid_argument for a map of the wrong shape or with a negative or
  /// non-finite luminance. A black map is sampled uniformly over the sphere.
  explicit EnvironmentSampler(const EnvironmentMap& map);

  /// u1 chooses the column and u2 the row, both in [0, 1). Exactly at a pole (u2 = 0 with a
  /// lit top row) the density per solid angle is infinite and the pdf returned is 0: a caller
  /// counts the sample as 0, the limit of f / pdf there, as pbrt does.
  EnvironmentSample sample(double u1, double u2) const;

  /// The direction sample(u1, u2) draws, bit for bit, without its density and texel: all a
  /// shadow ray needs.
  glm::dvec3 sampleDirection(double u1, double u2) const;
  /// sampleDirection(u1[k], u2[k]) for k < count, into directions[k], bit for bit: every row
  /// drawn first, and the columns' tables of those rows fetched ahead, so that the cache misses
  /// of the samples overlap (a 1k map's tables and texels are 18 MB, more than a core's cache)
  /// rather than come one after another.
  void sampleDirections(int count, const double* u1, const double* u2, glm::dvec3* directions) const;
  /// sample(u1[k], u2[k]) for k < count, into samples[k], bit for bit: as sampleDirections,
  /// with each drawn texel fetched ahead too.
  void samples(int count, const double* u1, const double* u2, EnvironmentSample* samples) const;

  /// The density per unit solid angle that sample() draws unitDirection with: positive
  /// wherever the radiance is, but 0 exactly at a pole.
  double pdf(const glm::dvec3& unitDirection) const;

  /// The same density and the radiance of the texel unitDirection falls in, found together.
  EnvironmentSample at(const glm::dvec3& unitDirection) const;
  /// at(unitDirections[k]) for k < count, into samples[k], bit for bit: every texel found
  /// first and fetched, then read, so that the cache misses overlap.
  void at(int count, const glm::dvec3* unitDirections, EnvironmentSample* samples) const;

private:
  struct Drawn
  {
    int column, row; // the texel
    glm::dvec3 direction;
  };
  /// A drawn row and where in it, in [0, 1).
  struct DrawnRow
  {
    int row;
    double offset;
  };
  /// For a map with light (uvDensityPerWeight_ > 0): the row from u2, then the texel in it
  /// from u1 and the direction.
  Drawn draw(double u1, double u2) const;
  DrawnRow drawRow(double u2) const;
  Drawn drawInRow(const DrawnRow& row, double u1) const;
  /// directionAt((column + columnOffset) / width, (row + rowOffset) / height), to within a few
  /// roundings, from the texel's edges (where the map has their tables).
  glm::dvec3 directionInTexel(int column, double columnOffset, int row, double rowOffset) const;
  /// onDrawn(k, draw(u1[k], u2[k])) for k < count, the rows drawn and the columns' tables
  /// fetched ahead a batch at a time. A map with light only.
  template<typename OnDrawn>
  void drawBatches(int count, const double* u1, const double* u2, OnDrawn&& onDrawn) const;
  EnvironmentSample sampleOf(const Drawn& drawn) const;
  double pdfAt(int column, int row, const glm::dvec3& direction) const;
  /// at(unitDirection) for the texel it falls in.
  EnvironmentSample atTexel(const glm::dvec3& unitDirection, const glm::ivec2& texel) const;

  EnvironmentMap map_;
  std::vector<double> rowCdf_;     // height + 1 values from 0 to 1
  std::vector<double> columnCdfs_; // height rows of width + 1 values from 0 to 1
  std::vector<int> rowGuide_;      // the rows' cdf's guide table: height bins
  std::vector<int> columnGuides_;  // each row's: height rows of width bins
  std::vector<double> rowCentreSinTheta_;
  /// The angles of directionAt at each row's top edge (theta) and column's left edge (phi), for
  /// maps of at least 128 x 64 texels; empty for smaller ones, whose texels are wider.
  std::vector<SineCosine> rowEdges_, columnEdges_;
  double uvDensityPerWeight_ = 0.0; // width x height / sum of texel weights; 0 for black
};
}
