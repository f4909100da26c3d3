// Exact irradiance from area lights (PolygonIrradiance, SphereIrradiance, DiskIrradiance)
// against truths found independently: closed-form configuration factors and numerical
// integrals over the emitter's surface or its cone of directions.
#include "DiskIrradiance.h"
#include "PolygonIrradiance.h"
#include "SphereIrradiance.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <vector>

namespace
{
using namespace shadelab;
constexpr double pi = M_PI;

// ---- Independent truths ----------------------------------------------------------------

/// pi F for a plane element facing a parallel rectangle a x b at distance c whose corner lies
/// on the element's normal (J. R. Howell, "A Catalog of Radiation Heat Transfer Configuration
/// Factors", section B, differential element to finite area; Siegel and Howell, "Thermal
/// Radiation Heat Transfer"): F = 1/(2 pi) [X/sqrt(1+X^2) atan(Y/sqrt(1+X^2)) + Y/sqrt(1+Y^2)
/// atan(X/sqrt(1+Y^2))], X = a/c, Y = b/c.
double cornerRectangle(double a, double b, double c)
{
  const double x = a / c;
  const double y = b / c;
  const double rootX = std::sqrt(1 + x * x);
  const double rootY = std::sqrt(1 + y * y);
  return 0.5 * (x / rootX * std::atan(y / rootX) + y / rootY * std::atan(x / rootY));
}

/// pi F for a plane element facing a parallel disk of radius r at height h, the element's
/// normal a distance s from the disk's axis (Howell's catalogue, section B; M. F. Modest,
/// "Radiative Heat Transfer", appendix D): with H = h/s, R = r/s, A = 1 + H^2 - R^2 and
/// B = sqrt(A^2 + 4 R^2 H^2), F = 1/2 (1 - A/B). Where A > 0 that difference cancels, and
/// F = 2 R^2 H^2 / (B (A + B)) instead, the same value since B^2 - A^2 = 4 R^2 H^2.
double parallelDiskOffAxis(double r, double h, double s)
{
  const double bigH = h / s;
  const double bigR = r / s;
  const double a = 1 + bigH * bigH - bigR * bigR;
  const double b = std::sqrt(a * a + 4 * bigR * bigR * bigH * bigH);
  return pi * (a > 0 ? 2 * bigR * bigR * bigH * bigH / (b * (a + b)) : 0.5 * (1 - a / b));
}

/// The surface integrand of the projected solid angle: dP = max(0, cos_receiver) cos_emitter
/// dA / d^2, for an emitter element at x with unit normal emitterNormal.
double surfaceIntegrand(
  const glm::dvec3& x, const glm::dvec3& emitterNormal, const glm::dvec3& point, const glm::dvec3& normal)
{
  const glm::dvec3 w = x - point;
  const double d2 = glm::dot(w, w);
  const double cosReceiver = std::max(0.0, glm::dot(normal, w)) / std::sqrt(d2);
  const double cosEmitter = std::abs(glm::dot(emitterNormal, w)) / std::sqrt(d2);
  return cosReceiver * cosEmitter / d2;
}

/// P over the parallelogram corner + s u + t v, (s, t) in [0, 1]^2, by the midpoint rule on
/// cells x cells cells.
double parallelogramByMidpoints(const glm::dvec3& corner, const glm::dvec3& u, const glm::dvec3& v,
  const glm::dvec3& point, const glm::dvec3& normal, int cells)
{
  const glm::dvec3 areaVector = glm::cross(u, v);
  const glm::dvec3 emitterNormal = glm::normalize(areaVector);
  double sum = 0;
  for (int i = 0; i < cells; ++i)
  {
    for (int j = 0; j < cells; ++j)
    {
      const glm::dvec3 x = corner + ((i + 0.5) / cells) * u + ((j + 0.5) / cells) * v;
      sum += surfaceIntegrand(x, emitterNormal, point, normal);
    }
  }
  return sum * glm::length(areaVector) / (double(cells) * cells);
}

/// Composite Simpson's rule on [a, b] with an even number of panels.
double simpson(const std::function<double(double)>& f, double a, double b, int panels)
{
  const double h = (b - a) / panels;
  double sum = f(a) + f(b);
  for (int k = 1; k < panels; ++k)
  {
    sum += (k % 2 ? 4 : 2) * f(a + k * h);
  }
  return sum * h / 3;
}

struct Disk
{
  glm::dvec3 centre;
  glm::dvec3 normal; // unit
  double radius;
};

/// Two unit vectors spanning the plane normal to the unit vector n.
void planeBasis(const glm::dvec3& n, glm::dvec3& e1, glm::dvec3& e2)
{
  const glm::dvec3 helper = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  e1 = glm::normalize(glm::cross(n, helper));
  e2 = glm::cross(n, e1);
}

/// P for a disk by a surface integral in polar coordinates, for a disk wholly above the
/// receiver's horizon: Simpson's rule in the radius, the trapezoid rule (spectrally accurate on
/// a periodic integrand) in the angle.
double diskByPolarQuadrature(const Disk& disk, const glm::dvec3& point, const glm::dvec3& normal, int steps)
{
  glm::dvec3 e1, e2;
  planeBasis(disk.normal, e1, e2);
  const auto ring = [&](double rho)
  {
    double sum = 0;
    for (int k = 0; k < steps; ++k)
    {
      const double t = 2 * pi * k / steps;
      const glm::dvec3 x = disk.centre + rho * (std::cos(t) * e1 + std::sin(t) * e2);
      sum += surfaceIntegrand(x, disk.normal, point, normal);
    }
    return rho * sum * 2 * pi / steps;
  };
  return simpson(ring, 0, disk.radius, steps);
}

/// P for a disk cut by the receiver's tangent plane, by a surface integral over the part above
/// it in coordinates that follow the cut: u along the in-plane direction m of n (the height
/// over the tangent plane grows with u), v along the chord. u = r sin(theta) and
/// v = r cos(theta) sigma, sigma in [-1, 1], leave a smooth integrand with Jacobian
/// r^2 cos^2(theta); Simpson's rule in both.
double diskCutByHorizon(const Disk& disk, const glm::dvec3& point, const glm::dvec3& normal, int steps)
{
  const glm::dvec3 m = glm::normalize(normal - glm::dot(normal, disk.normal) * disk.normal);
  const glm::dvec3 k = glm::cross(disk.normal, m);
  const double cutAt = -glm::dot(disk.centre - point, normal) / glm::dot(m, normal); // u on the chord
  const double r = disk.radius;
  const auto strip = [&](double theta)
  {
    const auto across = [&](double sigma)
    {
      const glm::dvec3 x = disk.centre + r * std::sin(theta) * m + r * std::cos(theta) * sigma * k;
      return surfaceIntegrand(x, disk.normal, point, normal);
    };
    return simpson(across, -1, 1, steps) * r * r * std::cos(theta) * std::cos(theta);
  };
  return simpson(strip, std::asin(cutAt / r), pi / 2, steps);
}

/// P for a sphere by integrating over its cone of directions: theta from the direction to the
/// centre, phi about it. With beta the angle from n to the centre, n.w = cos(theta) cos(beta)
/// + sin(theta) sin(beta) cos(phi) = a + b cos(phi), whose clamped integral over phi is
/// 2 pi a (a >= b), 0 (a <= -b), else 2 (a phi0 + b sin(phi0)), phi0 = acos(-a/b). The
/// theta integral is Simpson's rule, split where the phi integral changes form.
double sphereByConeQuadrature(double distance, double radius, double beta, int panels)
{
  const double alpha = std::asin(radius / distance);
  const auto ring = [&](double theta)
  {
    const double a = std::cos(theta) * std::cos(beta);
    const double b = std::sin(theta) * std::sin(beta);
    double clamped = 0;
    if (a >= b)
    {
      clamped = 2 * pi * a;
    }
    else if (a > -b)
    {
      const double phi0 = std::acos(-a / b);
      clamped = 2 * (a * phi0 + b * std::sin(phi0));
    }
    return clamped * std::sin(theta);
  };
  // The change of form: |a| = b at theta = |pi/2 - beta|.
  const double kink = std::min(alpha, std::abs(pi / 2 - beta));
  return simpson(ring, 0, kink, panels) + simpson(ring, kink, alpha, panels);
}

std::vector<glm::dvec3> regularPolygon(const Disk& disk, int sides)
{
  glm::dvec3 e1, e2;
  planeBasis(disk.normal, e1, e2);
  std::vector<glm::dvec3> vertices;
  for (int k = 0; k < sides; ++k)
  {
    const double t = 2 * pi * k / sides;
    vertices.push_back(disk.centre + disk.radius * (std::cos(t) * e1 + std::sin(t) * e2));
  }
  return vertices;
}

void report(const char* what, double measured, double truth)
{
  std::cout << "  " << what << ": " << measured << " vs " << truth << ", relative error "
            << std::abs(measured - truth) / std::abs(truth) << "\n";
}

const glm::dvec3 up(0, 0, 1);
const glm::dvec3 down(0, 0, -1);
const glm::dvec3 origin(0.0);

// ---- Polygon -------------------------------------------------------------------------------

TEST(PolygonIrradiance, NewellNormalAndArea)
{
  const std::vector<glm::dvec3> square = { { 0, 0, 0 }, { 2, 0, 0 }, { 2, 2, 0 }, { 0, 2, 0 } };
  EXPECT_EQ(polygonNormal(square), up);
  EXPECT_DOUBLE_EQ(polygonArea(square), 4);
  // A non-convex L: the 2 x 2 square less its 1 x 1 top-right quarter, turned clockwise.
  const std::vector<glm::dvec3> ell = { { 0, 0, 0 }, { 0, 2, 0 }, { 1, 2, 0 }, { 1, 1, 0 }, { 2, 1, 0 }, { 2, 0, 0 } };
  EXPECT_EQ(polygonNormal(ell), down);
  EXPECT_DOUBLE_EQ(polygonArea(ell), 3);
  // Far from the origin, where Newell's sum over raw coordinates would cancel.
  std::vector<glm::dvec3> far = square;
  for (glm::dvec3& v : far)
  {
    v += glm::dvec3(1e9, -3e9, 7e8);
  }
  EXPECT_EQ(polygonNormal(far), up);
  EXPECT_DOUBLE_EQ(polygonArea(far), 4);
  const std::vector<glm::dvec3> collinear = { { 0, 0, 0 }, { 0.1, 0.2, 0.3 }, { 0.3, 0.6, 0.9 } };
  EXPECT_EQ(polygonNormal(collinear), glm::dvec3(0.0));
  EXPECT_EQ(polygonProjectedSolidAngle(collinear, { 1, 0, 0 }, up), 0);
}

TEST(PolygonIrradiance, CentredSquareMatchesHowellsRectangle)
{
  // A unit square facing down at height h over a receiver facing up on its axis: four corner
  // rectangles of 1/2 x 1/2.
  const std::vector<glm::dvec3> square = { { -0.5, -0.5, 0 }, { 0.5, -0.5, 0 }, { 0.5, 0.5, 0 }, { -0.5, 0.5, 0 } };
  double worst = 0;
  for (const double h : { 0.01, 0.3, 1.0, 7.0, 1000.0 })
  {
    const glm::dvec3 p(0, 0, -h);
    const double truth = 4 * cornerRectangle(0.5, 0.5, h);
    const double measured = polygonProjectedSolidAngle(square, p, up);
    worst = std::max(worst, std::abs(measured - truth) / truth);
    EXPECT_NEAR(measured, truth, 1e-12 * truth) << "h = " << h;
  }
  std::cout << "  centred square: largest relative error " << worst << "\n";
}

TEST(PolygonIrradiance, OffAxisRectangleMatchesHowellsRectangle)
{
  // [-0.3, 0.7] x [-0.2, 1.1] at height 0.8 over the origin: four unequal corner rectangles.
  const std::vector<glm::dvec3> rectangle = { { -0.3, -0.2, 0.8 }, { 0.7, -0.2, 0.8 }, { 0.7, 1.1, 0.8 },
    { -0.3, 1.1, 0.8 } };
  const double truth = cornerRectangle(0.3, 0.2, 0.8) + cornerRectangle(0.7, 0.2, 0.8) +
    cornerRectangle(0.7, 1.1, 0.8) + cornerRectangle(0.3, 1.1, 0.8);
  const double measured = polygonProjectedSolidAngle(rectangle, origin, up);
  report("off-axis rectangle", measured, truth);
  EXPECT_NEAR(measured, truth, 1e-12 * truth);
}

TEST(PolygonIrradiance, WindingDoesNotMatter)
{
  std::vector<glm::dvec3> quad = { { -1, 0.2, 2 }, { 1.5, -0.4, 2.5 }, { 1.2, 1.4, 2.8 }, { -0.7, 1.1, 2.2 } };
  const glm::dvec3 p(0.1, 0.2, 0.3);
  const glm::dvec3 n = glm::normalize(glm::dvec3(0.3, -0.2, 1));
  const double forward = polygonProjectedSolidAngle(quad, p, n);
  std::reverse(quad.begin(), quad.end());
  EXPECT_GT(forward, 0.1);
  EXPECT_NEAR(polygonProjectedSolidAngle(quad, p, n), forward, 1e-15);
}

TEST(PolygonIrradiance, PointInThePolygonsPlaneSeesItEdgeOn)
{
  const std::vector<glm::dvec3> triangle = { { 0, 0, 1 }, { 1, 0, 2 }, { 0, 1, 3 } }; // z = 1 + x + 2y
  const glm::dvec3 tilted = glm::normalize(glm::dvec3(1, 1, 1));
  EXPECT_EQ(polygonProjectedSolidAngle(triangle, { 3, 3, 10 }, tilted), 0);      // outside the triangle
  EXPECT_EQ(polygonProjectedSolidAngle(triangle, { 0.2, 0.2, 1.6 }, tilted), 0); // inside it
  EXPECT_EQ(polygonProjectedSolidAngle(triangle, { 0.5, 0, 1.5 }, tilted), 0);   // on an edge
}

TEST(PolygonIrradiance, RectangleCutByTheHorizonMatchesSurfaceIntegral)
{
  // A tilted rectangle whose lower part is below the receiver's tangent plane.
  const glm::dvec3 corner(-1, 0.5, -0.6);
  const glm::dvec3 u(2, 0.3, 0.4);
  const glm::dvec3 v(0.2, 0.4, 1.8);
  const glm::dvec3 n = glm::normalize(glm::dvec3(0.1, 0.2, 1));
  const std::vector<glm::dvec3> rectangle = { corner, corner + u, corner + u + v, corner + v };
  const double truth = parallelogramByMidpoints(corner, u, v, origin, n, 2000);
  const double measured = polygonProjectedSolidAngle(rectangle, origin, n);
  report("rectangle cut by the horizon", measured, truth);
  EXPECT_NEAR(measured, truth, 1e-5 * truth);
}

TEST(PolygonIrradiance, NonConvexPolygonCutByTheHorizonMatchesSurfaceIntegral)
{
  // An L in the plane y = 1, cut by the receiver's tangent plane z = 0.4 x, so that its two
  // arms each keep a part above and the clipped polygon has an edge along the plane.
  const glm::dvec3 p(0, 0, 0);
  const glm::dvec3 n = glm::normalize(glm::dvec3(-0.4, 0, 1));
  const std::vector<glm::dvec3> ell = { { -1, 1, -1 }, { 2, 1, -1 }, { 2, 1, 0 }, { 0, 1, 0 }, { 0, 1, 2 },
    { -1, 1, 2 } };
  // The L as two rectangles: [-1, 2] x [-1, 0] and [-1, 0] x [0, 2] in (x, z).
  const double truth = parallelogramByMidpoints({ -1, 1, -1 }, { 3, 0, 0 }, { 0, 0, 1 }, p, n, 2000) +
    parallelogramByMidpoints({ -1, 1, 0 }, { 1, 0, 0 }, { 0, 0, 2 }, p, n, 2000);
  const double measured = polygonProjectedSolidAngle(ell, p, n);
  report("non-convex L cut by the horizon", measured, truth);
  EXPECT_NEAR(measured, truth, 1e-5 * truth);
}

TEST(PolygonIrradiance, VerticesOnTheHorizonAreKeptOnce)
{
  // A diamond in the plane y = 1 with two vertices exactly on the tangent plane z = 0: clipping
  // keeps each of them twice (as a vertex and as a crossing), and the zero-length edges between
  // the copies must add nothing. What remains is the triangle above.
  const std::vector<glm::dvec3> diamond = { { 0, 1, -1 }, { 1, 1, 0 }, { 0, 1, 1 }, { -1, 1, 0 } };
  const std::vector<glm::dvec3> upperHalf = { { 1, 1, 0 }, { 0, 1, 1 }, { -1, 1, 0 } };
  const double truth = parallelogramByMidpoints({ 1, 1, 0 }, { -1, 0, 1 }, { -1, 0, -1 }, origin, up, 2000);
  EXPECT_NEAR(
    polygonProjectedSolidAngle(diamond, origin, up), polygonProjectedSolidAngle(upperHalf, origin, up), 1e-15);
  report("diamond with vertices on the horizon", polygonProjectedSolidAngle(diamond, origin, up), truth);
  EXPECT_NEAR(polygonProjectedSolidAngle(diamond, origin, up), truth, 1e-5 * truth);
}

TEST(PolygonIrradiance, BelowTheHorizonGivesZeroAndAHugePlaneGivesPi)
{
  const std::vector<glm::dvec3> below = { { -1, -1, -0.1 }, { 1, -1, -0.5 }, { 0, 1, -2 } };
  EXPECT_EQ(polygonProjectedSolidAngle(below, origin, up), 0);
  // A square 1e6 wide one unit above: the whole upper hemisphere but for about 1e-12.
  const double half = 5e5;
  const std::vector<glm::dvec3> huge = { { -half, -half, 1 }, { half, -half, 1 }, { half, half, 1 },
    { -half, half, 1 } };
  const double measured = polygonProjectedSolidAngle(huge, origin, up);
  report("huge square", measured, pi);
  EXPECT_NEAR(measured, pi, 1e-5 * pi);
}

// ---- Sphere --------------------------------------------------------------------------------

/// A sphere of radius 1 at distance d in the direction at angle beta from n = z.
double sphereAt(double distance, double beta)
{
  const glm::dvec3 centre = distance * glm::dvec3(std::sin(beta), 0, std::cos(beta));
  return sphereProjectedSolidAngle(centre, 1, origin, up);
}

TEST(SphereIrradiance, AboveTheHorizonIsThePointLightsCosineLaw)
{
  // d = 2, cos(beta) = 0.6: pi 0.6 (1/2)^2.
  const glm::dvec3 centre(1.6, 0, 1.2);
  EXPECT_NEAR(sphereProjectedSolidAngle(centre, 1, origin, up), 0.15 * pi, 1e-15);
  // And the cone quadrature agrees with the cosine law there.
  const double beta = std::acos(0.6);
  const double cone = sphereByConeQuadrature(2, 1, beta, 20000);
  report("sphere above the horizon, cone quadrature", cone, 0.15 * pi);
  EXPECT_NEAR(cone, 0.15 * pi, 1e-10);
}

TEST(SphereIrradiance, PartlyBelowTheHorizonMatchesConeQuadrature)
{
  double worst = 0;
  for (const double distance : { 1.05, 2.0, 10.0 })
  {
    const double alpha = std::asin(1 / distance);
    for (const double fraction : { 0.05, 0.3, 0.5, 0.7, 0.95 })
    {
      // beta across the band from pi/2 - alpha (touching the horizon from above) to pi/2 + alpha.
      const double beta = pi / 2 - alpha + 2 * alpha * fraction;
      const double truth = sphereByConeQuadrature(distance, 1, beta, 200000);
      const double measured = sphereAt(distance, beta);
      worst = std::max(worst, std::abs(measured - truth) / truth);
      EXPECT_NEAR(measured, truth, 1e-6 * truth) << "d = " << distance << ", beta = " << beta;
    }
  }
  std::cout << "  sphere partly below the horizon: largest relative error " << worst << "\n";
}

TEST(SphereIrradiance, ContinuousAcrossTheHorizonBoundaries)
{
  // beta 1e-12 either side of each boundary: the values differ by at most about 1e-12 times
  // their slope if the three forms join.
  double worst = 0;
  for (const double distance : { 1.001, 1.5, 4.0, 100.0 })
  {
    const double alpha = std::asin(1 / distance);
    for (const double boundary : { pi / 2 - alpha, pi / 2 + alpha })
    {
      const double jump = std::abs(sphereAt(distance, boundary + 1e-12) - sphereAt(distance, boundary - 1e-12));
      worst = std::max(worst, jump);
      EXPECT_LT(jump, 1e-9) << "d = " << distance << ", beta = " << boundary;
    }
  }
  std::cout << "  sphere across the horizon boundaries: largest jump " << worst << "\n";
}

TEST(SphereIrradiance, BelowTheHorizonZeroInsidePi)
{
  EXPECT_EQ(sphereAt(3, 2.0), 0);
  EXPECT_EQ(sphereAt(3, pi), 0);
  EXPECT_EQ(sphereProjectedSolidAngle({ 0.2, 0.1, -0.3 }, 1, origin, up), pi);
  EXPECT_EQ(sphereProjectedSolidAngle({ 1, 0, 0 }, 1, origin, up), pi); // on the surface
}

TEST(SphereIrradiance, SameAsTheDiskOfItsSilhouette)
{
  // The sphere fills the cone of half-angle alpha about w, as does the disk facing p at
  // distance d cos^2(alpha) along w with radius d cos(alpha) sin(alpha): the same directions,
  // so the same P. An independent check of Snyder's formula against the rim integral.
  const double distance = 1.7;
  const double alpha = std::asin(1 / distance);
  double worst = 0;
  for (const double beta : { 0.3, pi / 2 - alpha, 1.2, pi / 2, 1.9, pi / 2 + alpha - 1e-3 })
  {
    const glm::dvec3 w(std::sin(beta), 0, std::cos(beta));
    const double cosAlpha = std::cos(alpha);
    const double disk = diskProjectedSolidAngle(
      distance * cosAlpha * cosAlpha * w, -w, distance * cosAlpha * std::sin(alpha), origin, up);
    worst = std::max(worst, std::abs(sphereAt(distance, beta) - disk));
    EXPECT_NEAR(sphereAt(distance, beta), disk, 1e-12) << "beta = " << beta;
  }
  std::cout << "  sphere against the disk of its silhouette: largest difference " << worst << "\n";
}

// ---- Disk ----------------------------------------------------------------------------------

TEST(DiskIrradiance, OnAxisFacingIsTheClosedForm)
{
  double worst = 0;
  for (const double h : { 1e-6, 0.01, 0.5, 1.0, 3.0, 1e4 })
  {
    const double r = 0.7;
    const double truth = pi * r * r / (r * r + h * h);
    const double measured = diskProjectedSolidAngle({ 0, 0, h }, down, r, origin, up);
    worst = std::max(worst, std::abs(measured - truth) / truth);
    EXPECT_NEAR(measured, truth, 1e-12 * truth) << "h = " << h;
  }
  std::cout << "  disk on axis: largest relative error " << worst << "\n";
}

TEST(DiskIrradiance, ParallelOffAxisMatchesHowellsDisk)
{
  // Receiver parallel to the disk, its normal at distance s from the disk's axis, including
  // points within 1e-6 r of the rim, where the rim integrand is sharpest. The rim integral
  // sums terms up to r / delta, delta the distance to the rim, whose rounding is absolute.
  const double r = 1;
  double worstRelative = 0;   // where P > 1e-3
  double worstInRimUnits = 0; // absolute error over 1e-16 max(1, r / delta)
  for (const double h : { 1e-6, 1e-3, 0.2, 2.0 })
  {
    for (const double s : { 0.3, 0.999, 1 - 1e-6, 1 + 1e-6, 1.001, 1.5, 5.0 })
    {
      const double truth = parallelDiskOffAxis(r, h, s);
      const double measured = diskProjectedSolidAngle({ s, 0, h }, up, r, origin, up);
      const double error = std::abs(measured - truth);
      const double rimScale = std::max(1.0, r / std::hypot(s - r, h));
      worstRelative = truth > 1e-3 ? std::max(worstRelative, error / truth) : worstRelative;
      worstInRimUnits = std::max(worstInRimUnits, error / (1e-16 * rimScale));
      EXPECT_NEAR(measured, truth, 1e-12 * truth + 1e-15 * rimScale) << "h = " << h << ", s = " << s;
    }
  }
  std::cout << "  parallel disk off axis: largest relative error where P > 1e-3 " << worstRelative
            << ", largest absolute error " << worstInRimUnits << " x 1e-16 max(1, r / delta)\n";
}

TEST(DiskIrradiance, TiltedAboveTheHorizonMatchesSurfaceIntegral)
{
  const Disk disk{ { 0.4, -0.3, 1.5 }, glm::normalize(glm::dvec3(0.5, 0.2, -1)), 0.8 };
  const glm::dvec3 n = glm::normalize(glm::dvec3(-0.2, 0.1, 1));
  const double truth = diskByPolarQuadrature(disk, origin, n, 2000);
  const double measured = diskProjectedSolidAngle(disk.centre, disk.normal, disk.radius, origin, n);
  report("tilted disk above the horizon", measured, truth);
  EXPECT_NEAR(measured, truth, 1e-8 * truth);
}

TEST(DiskIrradiance, CutByTheHorizonMatchesSurfaceIntegral)
{
  const glm::dvec3 n = glm::normalize(glm::dvec3(0.3, -0.1, 1));
  for (const Disk& disk : { Disk{ { 0.4, -0.3, 0.2 }, glm::normalize(glm::dvec3(0.5, 0.2, -1)), 0.8 },
         Disk{ { 2, 0.5, 0.1 }, glm::normalize(glm::dvec3(-1, 0.1, 0.3)), 1.0 },
         Disk{ { 0.1, 0.2, -0.3 }, glm::normalize(glm::dvec3(0.1, 1, 0.2)), 0.6 } })
  {
    const double truth = diskCutByHorizon(disk, origin, n, 2000);
    const double measured = diskProjectedSolidAngle(disk.centre, disk.normal, disk.radius, origin, n);
    report("disk cut by the horizon", measured, truth);
    EXPECT_NEAR(measured, truth, 1e-6 * truth);
  }
}

TEST(DiskIrradiance, BelowTheHorizonOrEdgeOnGivesZero)
{
  EXPECT_EQ(diskProjectedSolidAngle({ 0, 0, -2 }, up, 1, origin, up), 0);
  EXPECT_EQ(diskProjectedSolidAngle({ 0.5, 0, -0.8 }, glm::normalize(glm::dvec3(1, 0, 1)), 0.3, origin, up), 0);
  // The point in the disk's plane, outside the disk and inside it.
  EXPECT_EQ(diskProjectedSolidAngle({ 3, 0, 0 }, up, 1, origin, glm::normalize(glm::dvec3(1, 0, 1))), 0);
  EXPECT_EQ(diskProjectedSolidAngle({ 0.2, 0, 0 }, up, 1, origin, glm::normalize(glm::dvec3(1, 0, 1))), 0);
}

TEST(DiskIrradiance, InscribedPolygonsConverge)
{
  // The inscribed N-gon misses area of order r^2 / N^2, so its P approaches the disk's as
  // 1/N^2: a quarter of the error each time N doubles. Once tilted above the horizon, once cut.
  const glm::dvec3 n = glm::normalize(glm::dvec3(0.3, -0.1, 1));
  for (const Disk& disk : { Disk{ { 0.4, -0.3, 1.5 }, glm::normalize(glm::dvec3(0.5, 0.2, -1)), 0.8 },
         Disk{ { 0.4, -0.3, 0.2 }, glm::normalize(glm::dvec3(0.5, 0.2, -1)), 0.8 } })
  {
    const double exact = diskProjectedSolidAngle(disk.centre, disk.normal, disk.radius, origin, n);
    double previous = 0;
    for (const int sides : { 64, 128, 256, 512, 1024, 2048, 4096 })
    {
      const double error = std::abs(polygonProjectedSolidAngle(regularPolygon(disk, sides), origin, n) - exact) / exact;
      if (previous > 0)
      {
        EXPECT_NEAR(previous / error, 4, 0.1) << sides << " sides";
      }
      previous = error;
    }
    std::cout << "  4096-gon inscribed in the disk: relative difference " << previous << "\n";
    EXPECT_LT(previous, 1e-5);
  }
}
}
