// Every failure point of docs/formulas.md section 16 at its exact point: a defined, finite
// result and the right flag, in float64 and float32.
#include "KernelHarness.h"
#include "ShadingFlags.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace
{
using namespace shadelab;
using shadelab::testing::KernelHarness;

Scene oneLightScene(LightSource source, SpecularModel specular, double shininess)
{
  Scene scene;
  scene.material.kd = Rgb(0.5);
  scene.material.ka = Rgb(0.2);
  scene.material.ks = Rgb(0.25);
  scene.material.shininess = shininess;
  scene.material.specular = specular;
  scene.viewer.viewDirection = { 0, 0, -1 }; // v = +z
  scene.lights.push_back({ "lamp", std::move(source) });
  scene.lights.push_back({ "room", AmbientLight{ Rgb(1.0), 0.4 } });
  return scene;
}

template<typename T>
void expectAllFinite(const KernelHarness<T>& run)
{
  for (const auto& [name, values] : run.arrays)
  {
    for (T x : values)
    {
      ASSERT_TRUE(std::isfinite(x)) << name;
    }
  }
}

template<typename T>
class FailurePoints : public ::testing::Test
{
};
using Precisions = ::testing::Types<float, double>;
TYPED_TEST_SUITE(FailurePoints, Precisions);

TYPED_TEST(FailurePoints, ShininessZeroGivesConstantSpecularOnLitVertices)
{
  using T = TypeParam;
  // s = normalize(0, 1, 0.2), v = +z. Vertex 0 (n = +y) is lit with r.v < 0, vertex 1
  // (n = +z) is lit with r.v > 0, vertex 2 (n = -y) is unlit.
  const Scene scene = oneLightScene(DistantLight{ { 0, -1, -0.2 }, Rgb(1.0), 2.0, false }, SpecularModel::Phong, 0.0);
  const KernelHarness<T> run(
    scene, { Vec3<T>(0), Vec3<T>(0), Vec3<T>(0) }, { Vec3<T>(0, 1, 0), Vec3<T>(0, 0, 1), Vec3<T>(0, -1, 0) });
  expectAllFinite(run);
  EXPECT_GT(run.value("lamp_cos_incidence", 0), T(0));
  EXPECT_LT(run.value("lamp_r_dot_v", 0), T(0));
  EXPECT_GT(run.value("lamp_r_dot_v", 1), T(0));
  EXPECT_EQ(run.value("lamp_specular", 0), T(0.5)); // ks Ls = 0.25 * 2
  EXPECT_EQ(run.value("lamp_specular", 1), T(0.5));
  EXPECT_EQ(run.value("lamp_specular", 2), T(0));
  EXPECT_TRUE(run.flags[2] & FlagLightBelowHorizon);
}

TYPED_TEST(FailurePoints, ShininessTenThousandUnderflowsWithoutNaN)
{
  using T = TypeParam;
  const Scene scene =
    oneLightScene(DistantLight{ { 0, 0, -1 }, Rgb(1.0), 1.0, false }, SpecularModel::BlinnPhong, 10000.0);
  const double tilt = 0.01; // n.h = cos(0.01 rad)
  const KernelHarness<T> run(
    scene, { Vec3<T>(0), Vec3<T>(0) }, { Vec3<T>(0, 0, 1), Vec3<T>(T(std::sin(tilt)), 0, T(std::cos(tilt))) });
  expectAllFinite(run);
  EXPECT_EQ(run.value("lamp_specular", 0), T(0.25));
  const double expected = 0.25 * std::pow(std::cos(tilt), 10000.0); // about 0.152
  // float32: within ks Ls eta 2^-23 (docs/guide/accuracy.md, "Precision"); measured 1.3e-5.
  EXPECT_NEAR(
    run.value("lamp_specular", 1), expected, (std::is_same_v<T, float> ? 0.25 * 10000 * std::ldexp(1.0, -23) : 1e-12));
}

TYPED_TEST(FailurePoints, GrazingLightExactlyOnTheHorizon)
{
  using T = TypeParam;
  const Scene scene = oneLightScene(DistantLight{ { -1, 0, 0 }, Rgb(1.0), 1.0, false }, SpecularModel::Phong, 10.0);
  const KernelHarness<T> run(scene, { Vec3<T>(0) }, { Vec3<T>(0, 0, 1) });
  expectAllFinite(run);
  EXPECT_EQ(run.value("lamp_cos_incidence", 0), T(0));
  EXPECT_EQ(run.value("lamp_incidence_angle", 0), T(90));
  EXPECT_EQ(run.value("lamp_diffuse", 0), T(0));
  EXPECT_EQ(run.value("lamp_specular", 0), T(0));
  EXPECT_EQ(run.flags[0], FlagLightBelowHorizon);
}

TYPED_TEST(FailurePoints, LightOppositeTheViewerLeavesHalfVectorUndefined)
{
  using T = TypeParam;
  // s = -v: the light shines from behind the surface toward the viewer.
  const Scene scene = oneLightScene(DistantLight{ { 0, 0, 1 }, Rgb(1.0), 1.0, false }, SpecularModel::BlinnPhong, 10.0);
  const KernelHarness<T> run(scene, { Vec3<T>(0) }, { Vec3<T>(0, 0, -1) });
  expectAllFinite(run);
  EXPECT_EQ(run.vec("lamp_half_vector", 0), Vec3<T>(0));
  EXPECT_EQ(run.value("lamp_n_dot_h", 0), T(0));
  EXPECT_EQ(run.value("lamp_specular", 0), T(0));
  EXPECT_EQ(run.value("lamp_diffuse", 0), T(0.5)); // lit head-on: kd Ld n.s
  EXPECT_EQ(run.flags[0], FlagHalfVectorUndefined);
}

TYPED_TEST(FailurePoints, PointLightAtTheVertex)
{
  using T = TypeParam;
  PointLight bulb;
  bulb.position = { 1, 2, 3 };
  bulb.intensity = 1e-4; // so that Ld / minDistance^2 = 1
  const Scene scene = oneLightScene(bulb, SpecularModel::BlinnPhong, 10.0);
  const KernelHarness<T> run(scene, { Vec3<T>(1, 2, 3) }, { Vec3<T>(0, 0, 1) });
  expectAllFinite(run);
  EXPECT_EQ(run.value("lamp_distance", 0), T(0));
  EXPECT_NEAR(run.value("lamp_attenuation", 0), T(1e4), T(1e4) * T(1e-6)); // 1 / 0.01^2
  EXPECT_EQ(run.vec("lamp_to_light", 0), Vec3<T>(0, 0, 1));                // along the normal
  EXPECT_NEAR(run.value("lamp_diffuse", 0), T(0.5), T(1e-6));
  EXPECT_EQ(run.flags[0], FlagLightAtMinimumDistance);
}

TYPED_TEST(FailurePoints, ZeroNormalGetsAmbientOnly)
{
  using T = TypeParam;
  const Scene scene = oneLightScene(DistantLight{ { 0, 0, -1 }, Rgb(1.0), 1.0, false }, SpecularModel::Phong, 0.0);
  const KernelHarness<T> run(scene, { Vec3<T>(0) }, { Vec3<T>(0) });
  expectAllFinite(run);
  // ka La is formed in float64, then rounded once.
  EXPECT_EQ(run.vec("ambient", 0), Vec3<T>(T(0.2 * 0.4)));
  EXPECT_EQ(run.vec("total", 0), run.vec("ambient", 0));
  EXPECT_EQ(run.value("lamp_cos_incidence", 0), T(0));
  EXPECT_EQ(run.value("lamp_incidence_angle", 0), T(90));
  EXPECT_EQ(run.flags[0], FlagDegenerateNormal | FlagLightBelowHorizon);
}

TYPED_TEST(FailurePoints, HugeNormalShadesAsItsDirection)
{
  // A finite normal whose squared length overflows (1e30 in float32, 1e200 in float64) shades
  // exactly as the unit normal along it: under a point light and a sphere light, every term.
  using T = TypeParam;
  Scene scene =
    oneLightScene(PointLight{ { 0.3, 0.2, 2.0 }, Rgb(1.0), 2.0, Attenuation{} }, SpecularModel::BlinnPhong, 20);
  AreaLight bulb;
  bulb.shape = SphereEmitter{ { -0.5, 0.4, 3.0 }, 0.5 };
  scene.lights.push_back({ "bulb", bulb });
  const T huge = std::is_same<T, float>::value ? T(1e30) : T(1e200);
  const Vec3<T> direction = glm::normalize(Vec3<T>(T(0.6), T(0), T(0.8)));
  const KernelHarness<T> unit(scene, { Vec3<T>(0) }, { direction });
  const KernelHarness<T> scaled(scene, { Vec3<T>(0) }, { Vec3<T>(T(0.6) * huge, T(0), T(0.8) * huge) });
  expectAllFinite(scaled);
  for (const auto& [name, values] : unit.arrays)
  {
    for (std::size_t i = 0; i < values.size(); ++i)
    {
      EXPECT_NEAR(
        scaled.arrays.at(name)[i], values[i], 4 * std::numeric_limits<T>::epsilon() * (1 + std::abs(values[i])))
        << name;
    }
  }
  EXPECT_EQ(scaled.flags[0], unit.flags[0]);
}

TYPED_TEST(FailurePoints, NaNCoordinateZeroesEveryOutput)
{
  using T = TypeParam;
  const Scene scene = oneLightScene(PointLight{}, SpecularModel::Phong, 5.0);
  const T nan = std::numeric_limits<T>::quiet_NaN();
  const KernelHarness<T> run(scene, { Vec3<T>(nan, 0, 0), Vec3<T>(0, 0, -1) },
    { Vec3<T>(0, 0, 1), Vec3<T>(0, 0, std::numeric_limits<T>::infinity()) });
  expectAllFinite(run);
  for (const auto& [name, values] : run.arrays)
  {
    for (T x : values)
    {
      EXPECT_EQ(x, T(0)) << name;
    }
  }
  EXPECT_EQ(run.flags[0], FlagNonFiniteInput);
  EXPECT_EQ(run.flags[1], FlagNonFiniteInput);
}

TYPED_TEST(FailurePoints, TwoSidedFlipsNormalsFacingAway)
{
  using T = TypeParam;
  Scene scene = oneLightScene(DistantLight{ { 0, 0, -1 }, Rgb(1.0), 1.0, false }, SpecularModel::Phong, 1.0);
  scene.material.twoSided = true;
  const KernelHarness<T> run(scene, { Vec3<T>(0), Vec3<T>(0) }, { Vec3<T>(0, 0, -2), Vec3<T>(0, 0, 2) });
  EXPECT_EQ(run.value("lamp_cos_incidence", 0), T(1));
  EXPECT_EQ(run.flags[0], FlagNormalFlipped);
  EXPECT_EQ(run.value("lamp_cos_incidence", 1), T(1));
  EXPECT_EQ(run.flags[1], 0);
}

TEST(DistantLight, IntensityFromTheDirectionsLength)
{
  // docs/formulas.md section 8.1: the strength of a distant light may be the length of its direction.
  Scene scene = oneLightScene(DistantLight{ { 0, 0, -3 }, Rgb(1.0), 0.5, true }, SpecularModel::None, 1.0);
  const KernelHarness<double> run(scene, { Vec3<double>(0) }, { Vec3<double>(0, 0, 1) });
  EXPECT_DOUBLE_EQ(run.value("lamp_diffuse", 0), 0.5 * 0.5 * 3.0); // kd x intensity x |direction|
  std::get<DistantLight>(scene.lights[0].source).intensityFromLength = false;
  const KernelHarness<double> plain(scene, { Vec3<double>(0) }, { Vec3<double>(0, 0, 1) });
  EXPECT_DOUBLE_EQ(plain.value("lamp_diffuse", 0), 0.5 * 0.5);
  // A length whose square would overflow still counts in full.
  scene.lights[0].source = DistantLight{ { 0, 0, -3e200 }, Rgb(1.0), 1e-200, true };
  const KernelHarness<double> huge(scene, { Vec3<double>(0) }, { Vec3<double>(0, 0, 1) });
  EXPECT_DOUBLE_EQ(huge.value("lamp_diffuse", 0), 0.5 * 3.0);
}

TEST(Directions, HugeAndTinyVectorsStillNormalise)
{
  // glm::normalize squares the components: 1e200 would overflow, 1e-170 underflow.
  for (double scale : { 1e200, 1e-170 })
  {
    Scene scene = oneLightScene(DistantLight{ { 0, 0, -scale }, Rgb(1.0), 1.0, false }, SpecularModel::None, 1.0);
    EXPECT_TRUE(sceneProblems(scene).empty()) << scale;
    const KernelHarness<double> run(scene, { Vec3<double>(0) }, { Vec3<double>(0, 0, 1) });
    EXPECT_EQ(run.vec("lamp_to_light", 0), Vec3<double>(0, 0, 1)) << scale;
    EXPECT_EQ(run.value("lamp_diffuse", 0), 0.5) << scale;
  }
}

TEST(Flags, DoNotDependOnTheArraysRequested)
{
  // s = -v at the vertex: the half vector is undefined whether or not h was asked for.
  const Scene scene = oneLightScene(DistantLight{ { 0, 0, 1 }, Rgb(1.0), 1.0, false }, SpecularModel::Phong, 10.0);
  const std::vector<Vec3<double>> at{ Vec3<double>(0) }, normal{ Vec3<double>(0, 0, -1) };
  const KernelHarness<double> everything(scene, at, normal, { "all" });
  const KernelHarness<double> flagsOnly(scene, at, normal, { "shading_flags" });
  EXPECT_EQ(everything.flags[0], FlagHalfVectorUndefined);
  EXPECT_EQ(flagsOnly.flags[0], FlagHalfVectorUndefined);
}
}
