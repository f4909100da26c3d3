// The warps of the unit square the Monte Carlo estimators sample through (SampleWarps.h),
// against the library's trigonometry and the properties each must have.
#include "SampleWarps.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace
{
using namespace shadelab;

TEST(SampleWarps, TheSmallAngleSineAndCosineAreTheLibrarysWithin1e11)
{
  double worst = 0;
  for (int i = -100000; i <= 100000; ++i)
  {
    const double a = (samplePi / 4) * i / 100000.0;
    const glm::dvec2 cs = cosSinOfSmallAngle(a);
    worst = std::max({ worst, std::abs(cs.x - std::cos(a)), std::abs(cs.y - std::sin(a)) });
  }
  EXPECT_LT(worst, 1e-11);
}

TEST(SampleWarps, TheConcentricMapIsShirleyAndChiusPolarForm)
{
  // r and theta as the paper writes them, with the library's cosine and sine.
  for (int i = 0; i <= 400; ++i)
  {
    for (int k = 0; k <= 400; ++k)
    {
      const glm::dvec2 u(i / 400.0, k / 400.0);
      const glm::dvec2 s = 2.0 * u - 1.0;
      glm::dvec2 expected(0.0);
      if (s.x != 0 || s.y != 0)
      {
        const bool xMajor = std::abs(s.x) > std::abs(s.y);
        const double r = xMajor ? s.x : s.y;
        const double theta = xMajor ? (samplePi / 4) * (s.y / s.x) : samplePi / 2 - (samplePi / 4) * (s.x / s.y);
        expected = { r * std::cos(theta), r * std::sin(theta) };
      }
      const glm::dvec2 p = concentricDisk(u);
      ASSERT_NEAR(p.x, expected.x, 1e-11) << u.x << " " << u.y;
      ASSERT_NEAR(p.y, expected.y, 1e-11) << u.x << " " << u.y;
    }
  }
}

TEST(SampleWarps, TheConcentricMapKeepsArea)
{
  // Cell centres of a 1000 x 1000 grid: the share that lands within radius rho is rho^2, up to
  // the cells the circle cuts (about 2 pi rho 1000 / 1000^2 of them).
  for (double rho : { 0.25, 0.5, 0.9 })
  {
    int inside = 0;
    for (int i = 0; i < 1000; ++i)
    {
      for (int k = 0; k < 1000; ++k)
      {
        const glm::dvec2 p = concentricDisk({ (i + 0.5) / 1000, (k + 0.5) / 1000 });
        inside += glm::dot(p, p) < rho * rho ? 1 : 0;
      }
    }
    EXPECT_NEAR(inside / 1e6, rho * rho, 2 * samplePi * rho / 1000) << rho;
  }
}

TEST(SampleWarps, CosineWeightedDirectionsAreUnitAboveTheSurfaceWithWeightPiOverCosine)
{
  const glm::dvec3 n = glm::normalize(glm::dvec3(0.3, -0.5, 0.8));
  for (int i = 0; i < 64; ++i)
  {
    for (int k = 0; k < 64; ++k)
    {
      const WeightedDirection d = cosineWeightedDirection(n, { (i + 0.5) / 64, (k + 0.5) / 64 });
      EXPECT_NEAR(glm::length(d.direction), 1.0, 1e-12);
      const double cosine = glm::dot(n, d.direction);
      EXPECT_GT(cosine, 0.0);
      EXPECT_NEAR(d.weight * cosine, samplePi, 1e-9);
    }
  }
}
}
