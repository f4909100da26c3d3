#include "PolygonIrradiance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace shadelab
{
namespace
{
/// Twice the polygon's vector area, by Newell's method (M. E. Newell, in I. E. Sutherland,
/// R. F. Sproull and R. A. Schumacker, "A Characterization of Ten Hidden-Surface Algorithms",
/// Computing Surveys 6(1), 1974; F. Tampieri, "Newell's Method for Computing the Plane
/// Equation of a Polygon", Graphics Gems III, 1992): the sum of v_i x v_{i+1}. Taken relative
/// to v_0, which leaves the sum unchanged, so that a polygon far from the origin loses no
/// digits to cancellation.
glm::dvec3 newellVector(const std::vector<glm::dvec3>& vertices)
{
  glm::dvec3 sum(0.0);
  for (std::size_t i = 1; i + 1 < vertices.size(); ++i)
  {
    sum += glm::cross(vertices[i] - vertices[0], vertices[i + 1] - vertices[0]);
  }
  return sum;
}

/// The largest distance of a vertex from v_0 (0 for no vertices): the polygon's size, for
/// relative tolerances.
double polygonExtent(const std::vector<glm::dvec3>& vertices)
{
  double extent = 0;
  for (const glm::dvec3& v : vertices)
  {
    extent = std::max(extent, vectorLength(v - vertices[0]));
  }
  return extent;
}

/// True when Newell's vector is not above the rounding noise of its cross products, whose
/// terms are up to extent^2: then the vertices are collinear as far as doubles can tell, and
/// the polygon has no area and no normal.
bool hasNoArea(const glm::dvec3& newell, double extent)
{
  constexpr double roundingNoise = 8 * std::numeric_limits<double>::epsilon();
  return !(vectorLength(newell) > roundingNoise * extent * extent);
}

/// A point closer than this fraction of the polygon's size to its plane is taken as in it:
/// there some v_i - p would be nearly 0 and its direction meaningless.
constexpr double inPlaneTolerance = 1e-12;

/// The polygon's vertices relative to p, clipped to the receiver's upper half-space
/// (v - p).n >= 0 by the Sutherland-Hodgman algorithm for one plane (I. E. Sutherland and
/// G. W. Hodgman, "Reentrant Polygon Clipping", CACM 17(1), 1974). A non-convex polygon may
/// come out as several pieces joined by edges along the plane, traversed once each way; their
/// terms in Lambert's sum cancel. A vertex on the plane may come out twice.
std::vector<glm::dvec3> clipAboveTangentPlane(
  const std::vector<glm::dvec3>& vertices, const glm::dvec3& point, const glm::dvec3& unitNormal)
{
  std::vector<glm::dvec3> kept;
  kept.reserve(2 * vertices.size()); // each edge adds at most its start and one crossing
  for (std::size_t i = 0; i < vertices.size(); ++i)
  {
    const glm::dvec3 from = vertices[i] - point;
    const glm::dvec3 to = vertices[(i + 1) % vertices.size()] - point;
    const double fromHeight = glm::dot(from, unitNormal);
    const double toHeight = glm::dot(to, unitNormal);
    if (fromHeight >= 0)
    {
      kept.push_back(from);
    }
    if ((fromHeight >= 0) != (toHeight >= 0))
    {
      kept.push_back(from + (fromHeight / (fromHeight - toHeight)) * (to - from));
    }
  }
  return kept;
}
}

glm::dvec3 polygonNormal(const std::vector<glm::dvec3>& vertices)
{
  const glm::dvec3 newell = newellVector(vertices);
  return hasNoArea(newell, polygonExtent(vertices)) ? glm::dvec3(0.0) : unitVector(newell);
}

double polygonArea(const std::vector<glm::dvec3>& vertices)
{
  return 0.5 * vectorLength(newellVector(vertices));
}

double polygonProjectedSolidAngle(
  const std::vector<glm::dvec3>& vertices, const glm::dvec3& point, const glm::dvec3& unitNormal)
{
  const glm::dvec3 newell = newellVector(vertices);
  const double extent = polygonExtent(vertices);
  if (hasNoArea(newell, extent) ||
    std::abs(glm::dot(unitVector(newell), vertices[0] - point)) <= inPlaneTolerance * extent)
  {
    return 0;
  }
  std::vector<glm::dvec3> directions = clipAboveTangentPlane(vertices, point, unitNormal);
  for (glm::dvec3& u : directions)
  {
    u = unitVector(u);
  }
  // Lambert's formula (J. H. Lambert, Photometria, 1760; D. R. Baum, H. E. Rushmeier and
  // J. M. Winget, SIGGRAPH 1989; J. Arvo, SIGGRAPH 1995): P = 1/2 |sum_i theta_i c_i.n| with
  // theta_i the angle from u_i to u_{i+1} and c_i the unit normal of their great circle,
  // u_i x u_{i+1} / |u_i x u_{i+1}|. The angle is atan2(|u_i x u_{i+1}|, u_i.u_{i+1}), which
  // keeps its digits where acos(u_i.u_{i+1}) loses half of them (near 0 and pi).
  double sum = 0;
  for (std::size_t i = 0; i < directions.size(); ++i)
  {
    const glm::dvec3& from = directions[i];
    const glm::dvec3& to = directions[(i + 1) % directions.size()];
    const glm::dvec3 cross = glm::cross(from, to);
    const double sine = glm::length(cross);
    if (sine > 0) // coincident directions (a vertex kept twice) span no angle
    {
      sum += std::atan2(sine, glm::dot(from, to)) * glm::dot(cross, unitNormal) / sine;
    }
  }
  return 0.5 * std::abs(sum);
}
}
