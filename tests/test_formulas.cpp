// The core's formulas at points where their values are known by hand.
#include "Attenuation.h"
#include "Reflectance.h"
#include "SpotCone.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace
{
using namespace shadelab;
constexpr double degree = M_PI / 180.0;

TEST(Attenuation, LectureModelsAtKnownDistances)
{
  EXPECT_DOUBLE_EQ(inverseSquareFalloff(2.0), 0.25);
  EXPECT_DOUBLE_EQ(inverseFalloff(4.0), 0.25);
  EXPECT_DOUBLE_EQ(constantLinearQuadraticFalloff(1.0, 0.5, 0.25, 2.0), 1.0 / 3.0);
  // (1 - (2/4)^4) / 2^2 = (1 - 1/16) / 4
  EXPECT_DOUBLE_EQ(gltfRangeFalloff(4.0, 2.0), 0.234375);
  EXPECT_DOUBLE_EQ(gltfRangeFalloff(4.0, 4.0), 0.0);
  EXPECT_DOUBLE_EQ(gltfRangeFalloff(4.0, 9.0), 0.0);
}

TEST(Attenuation, EveryModelThroughAttenuationAt)
{
  Attenuation a;
  a.minDistance = 0.5;
  a.model = AttenuationModel::None;
  EXPECT_EQ(attenuationAt(a, 3.0), 1.0);
  a.model = AttenuationModel::Inverse;
  EXPECT_DOUBLE_EQ(attenuationAt(a, 3.0), 1.0 / 3.0);
  a.model = AttenuationModel::InverseSquare;
  EXPECT_DOUBLE_EQ(attenuationAt(a, 3.0), 1.0 / 9.0);
  a.model = AttenuationModel::ConstantLinearQuadratic;
  a.constant = 2;
  a.linear = 1;
  a.quadratic = 1;
  EXPECT_DOUBLE_EQ(attenuationAt(a, 3.0), 1.0 / 14.0);
  a.model = AttenuationModel::GltfRange;
  a.range = 6;
  EXPECT_DOUBLE_EQ(attenuationAt(a, 3.0), (1.0 - 1.0 / 16.0) / 9.0);
}

TEST(Attenuation, MinimumDistanceKeepsDistanceZeroFinite)
{
  Attenuation a; // inverse square, 0.01 minimum distance
  EXPECT_DOUBLE_EQ(attenuationAt(a, 0.0), 1e4);
  EXPECT_DOUBLE_EQ(attenuationAt(a, 0.005), 1e4);
  EXPECT_DOUBLE_EQ(attenuationAt(a, 0.02), 2500.0);
  EXPECT_TRUE(std::isfinite(attenuationAt(a, 0.0f)));
  EXPECT_TRUE(divergesAtZero(a));
  a.model = AttenuationModel::ConstantLinearQuadratic; // VTK default (1, 0, 0)
  EXPECT_FALSE(divergesAtZero(a));
  a.constant = 0;
  a.quadratic = 1;
  EXPECT_TRUE(divergesAtZero(a));
}

TEST(SpotCone, VtkConeInsideOnAndOutside)
{
  SpotCone cone; // VTK model
  cone.halfAngleDegrees = 30;
  cone.exponent = 2;
  const PreparedCone<double> prepared(cone);
  EXPECT_DOUBLE_EQ(prepared.factor(std::cos(20 * degree)), std::pow(std::cos(20 * degree), 2));
  // On the cone: VTK tests coneDot >= cos(angle), so the boundary is inside.
  EXPECT_DOUBLE_EQ(prepared.factor(std::cos(30 * degree)), std::pow(std::cos(30 * degree), 2));
  EXPECT_EQ(prepared.factor(std::cos(30.001 * degree)), 0.0);
  EXPECT_EQ(prepared.factor(-1.0), 0.0);
}

TEST(SpotCone, VtkConeOfNinetyDegreesOrMoreIsNoCone)
{
  SpotCone cone;
  cone.halfAngleDegrees = 90;
  cone.exponent = 5;
  const PreparedCone<double> prepared(cone);
  EXPECT_EQ(prepared.factor(std::cos(89 * degree)), 1.0);
  EXPECT_EQ(prepared.factor(-0.5), 1.0);
}

TEST(SpotCone, GltfSmoothFalloff)
{
  SpotCone cone;
  cone.model = ConeModel::Gltf;
  cone.innerAngleDegrees = 10;
  cone.outerAngleDegrees = 30;
  const PreparedCone<double> prepared(cone);
  EXPECT_DOUBLE_EQ(prepared.factor(std::cos(5 * degree)), 1.0);
  EXPECT_DOUBLE_EQ(prepared.factor(std::cos(10 * degree)), 1.0);
  EXPECT_NEAR(prepared.factor(std::cos(30 * degree)), 0.0, 1e-15);
  EXPECT_EQ(prepared.factor(std::cos(40 * degree)), 0.0);
  const double a = (std::cos(20 * degree) - std::cos(30 * degree)) / (std::cos(10 * degree) - std::cos(30 * degree));
  EXPECT_NEAR(prepared.factor(std::cos(20 * degree)), a * a, 1e-15);
}

TEST(Reflectance, AngleOfIncidence)
{
  const glm::dvec3 n(0, 0, 1);
  EXPECT_NEAR(incidenceAngleDegrees(n, glm::dvec3(std::sin(60 * degree), 0, 0.5)), 60.0, 1e-12);
  EXPECT_EQ(incidenceAngleDegrees(n, glm::dvec3(1, 0, 0)), 90.0);
  EXPECT_EQ(incidenceAngleDegrees(n, n), 0.0);
  EXPECT_EQ(incidenceAngleDegrees(n, -n), 180.0);
  EXPECT_EQ(incidenceAngleDegrees(glm::dvec3(0), n), 90.0); // zero normal: n.s = 0
  // Near 0 degrees, where acos(n.s) would lose half its digits: 1e-4 degrees in float32.
  const float small = 1e-4f * float(degree);
  EXPECT_NEAR(incidenceAngleDegrees(glm::vec3(0, 0, 1), glm::vec3(std::sin(small), 0, std::cos(small))), 1e-4f, 1e-9f);
}

TEST(Reflectance, ReflectionAndHalfVector)
{
  const glm::dvec3 n(0, 0, 1);
  const glm::dvec3 s = glm::normalize(glm::dvec3(1, 0, 1));
  const glm::dvec3 r = reflectAboutNormal(s, n, glm::dot(n, s));
  EXPECT_NEAR(r.x, -s.x, 1e-15);
  EXPECT_NEAR(r.z, s.z, 1e-15);

  glm::dvec3 h(7);
  ASSERT_TRUE(halfVector(s, glm::dvec3(-1, 0, 0), h));
  EXPECT_NEAR(h.x, std::sin(-22.5 * degree), 1e-15);
  EXPECT_NEAR(h.z, std::cos(22.5 * degree), 1e-15);

  h = glm::dvec3(7);
  EXPECT_FALSE(halfVector(s, -s, h));
  EXPECT_EQ(h, glm::dvec3(7)); // untouched when undefined
}

TEST(Reflectance, SpecularLobeAtItsFailurePoints)
{
  // eta = 0: the constant 1 on lit vertices, whatever the cosine, even below zero.
  EXPECT_EQ(specularLobe(true, 0.3, 0.0), 1.0);
  EXPECT_EQ(specularLobe(true, -0.3, 0.0), 1.0);
  EXPECT_EQ(specularLobe(false, 0.3, 0.0), 0.0);
  // Negative cosines clamp to 0 before pow.
  EXPECT_EQ(specularLobe(true, -0.3, 8.0), 0.0);
  // eta = 10000: underflows smoothly, exactly 1 at the peak.
  EXPECT_NEAR(specularLobe(true, 0.999, 10000.0), std::exp(10000 * std::log(0.999)), 1e-18);
  EXPECT_EQ(specularLobe(true, 1.0, 10000.0), 1.0);
  EXPECT_EQ(specularLobe(true, 0.5f, 10000.0f), 0.0f);
}
}
