// Every array the filter writes, at every vertex of a finely tessellated unit sphere, against
// closed forms in the vertex's polar angle theta and azimuth phi (light and viewer on the z
// axis). float64 must agree within 1e-12, float32 within 1e-5 (shininess up to 100).
#include "TestMeshes.h"

#include "ArrayCatalog.h"
#include "ShadingFlags.h"
#include "vtkLocalReflectanceFilter.h"

#include "vtkDataArray.h"
#include "vtkNew.h"

#include <gtest/gtest.h>

#include <functional>
#include <map>

namespace
{
using namespace shadelab;

/// A vertex of the unit sphere in spherical coordinates.
struct SpherePoint
{
  double theta; // polar angle from +z
  double phi;   // azimuth from +x
  glm::dvec3 n() const { return { std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta) }; }
};

using Expected = std::function<std::vector<double>(const SpherePoint&)>;

std::vector<double> scalar(double x)
{
  return { x };
}

std::vector<double> vector(const glm::dvec3& v)
{
  return { v.x, v.y, v.z };
}

std::vector<double> grey(double x)
{
  return { x, x, x };
}

double positive(double x)
{
  return std::max(x, 0.0);
}

struct Tolerance
{
  double relative;
  const char* precision;
};

/// Runs the filter with every array on and compares each with its closed form. Every array
/// the scene can produce (but the flags) must have an expectation, so none goes unchecked.
void expectClosedForms(
  const Scene& scene, const std::map<std::string, Expected>& expected, int precision, const Tolerance& tolerance)
{
  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(150);
  vtkNew<vtkLocalReflectanceFilter> filter;
  filter->SetInputData(sphere);
  filter->SetScene(scene);
  filter->SetArraySelection({ "all" });
  filter->SetOutputPrecision(precision);
  filter->Update();
  vtkPolyData* output = filter->GetOutput();

  std::size_t checked = 0;
  for (const ArrayDescription& description : availableArrays(scene))
  {
    if (description.name == flagsArrayName(""))
    {
      continue;
    }
    SCOPED_TRACE(description.name + " in " + tolerance.precision);
    ASSERT_EQ(expected.count(description.name), 1u) << "no closed form for " << description.name;
    vtkDataArray* array = output->GetPointData()->GetArray(description.name.c_str());
    ASSERT_NE(array, nullptr);
    ASSERT_EQ(array->GetNumberOfComponents(), description.components);
    double worst = 0;
    for (vtkIdType i = 0; i < output->GetNumberOfPoints(); ++i)
    {
      double p[3];
      sphere->GetPoint(i, p);
      const SpherePoint point{ std::atan2(std::hypot(p[0], p[1]), p[2]), std::atan2(p[1], p[0]) };
      const std::vector<double> want = expected.at(description.name)(point);
      for (int c = 0; c < description.components; ++c)
      {
        const double got = array->GetComponent(i, c);
        const double error = std::abs(got - want[c]) / std::max(1.0, std::abs(want[c]));
        worst = std::max(worst, error);
        ++checked;
      }
    }
    EXPECT_LE(worst, tolerance.relative) << "largest error relative to max(1, |value|)";
  }
  EXPECT_GT(checked, 100000u);
}

constexpr Tolerance float64Tolerance{ 1e-12, "float64" };
constexpr Tolerance float32Tolerance{ 1e-5, "float32" };

void expectInBothPrecisions(
  const Scene& scene, const std::map<std::string, Expected>& expected, const Tolerance& float32 = float32Tolerance)
{
  expectClosedForms(scene, expected, vtkAlgorithm::DOUBLE_PRECISION, float64Tolerance);
  expectClosedForms(scene, expected, vtkAlgorithm::SINGLE_PRECISION, float32);
}

// The complete model (docs/formulas.md section 6) under a distant light along +z with the viewer at infinity
// on +z: n.s = cos(theta), r = (sin 2theta cos phi, sin 2theta sin phi, cos 2theta),
// r.v = cos(2 theta), h = z, n.h = cos(theta).
void distantLightOverhead(SpecularModel model, double eta, const Tolerance& float32 = float32Tolerance)
{
  Scene scene;
  scene.material = { Rgb(0.1), Rgb(0.6), Rgb(0.3), eta, model, false, {} };
  scene.viewer.viewDirection = { 0, 0, -1 };
  scene.lights = { { "sun", DistantLight{ { 0, 0, -2 }, Rgb(1.0), 1.5, false } },
    { "sky", AmbientLight{ Rgb(1.0), 0.5 } } };

  auto lobe = [=](const SpherePoint& x)
  {
    if (std::cos(x.theta) <= 0 || model == SpecularModel::None)
    {
      return 0.0;
    }
    return std::pow(positive(model == SpecularModel::Phong ? std::cos(2 * x.theta) : std::cos(x.theta)), eta);
  };
  auto diffuse = [](const SpherePoint& x) { return 0.6 * 1.5 * positive(std::cos(x.theta)); };
  auto specular = [=](const SpherePoint& x) { return 0.3 * 1.5 * lobe(x); };
  const std::map<std::string, Expected> expected = {
    { "sun_to_light",
      [](const SpherePoint&) {
        return vector({ 0, 0, 1 });
      } },
    { "sun_attenuation", [](const SpherePoint&) { return scalar(1); } },
    { "sun_spot_factor", [](const SpherePoint&) { return scalar(1); } },
    { "sun_cos_incidence", [](const SpherePoint& x) { return scalar(std::cos(x.theta)); } },
    { "sun_incidence_angle", [](const SpherePoint& x) { return scalar(x.theta * 180 / M_PI); } },
    { "sun_reflection",
      [](const SpherePoint& x)
      {
        return vector(
          { std::sin(2 * x.theta) * std::cos(x.phi), std::sin(2 * x.theta) * std::sin(x.phi), std::cos(2 * x.theta) });
      } },
    { "sun_r_dot_v", [](const SpherePoint& x) { return scalar(std::cos(2 * x.theta)); } },
    { "sun_half_vector",
      [](const SpherePoint&) {
        return vector({ 0, 0, 1 });
      } },
    { "sun_n_dot_h", [](const SpherePoint& x) { return scalar(std::cos(x.theta)); } },
    { "sun_diffuse", [=](const SpherePoint& x) { return grey(diffuse(x)); } },
    { "sun_specular", [=](const SpherePoint& x) { return grey(specular(x)); } },
    { "ambient", [](const SpherePoint&) { return grey(0.05); } },
    { "diffuse", [=](const SpherePoint& x) { return grey(diffuse(x)); } },
    { "specular", [=](const SpherePoint& x) { return grey(specular(x)); } },
    { "total", [=](const SpherePoint& x) { return grey(0.05 + diffuse(x) + specular(x)); } },
  };
  expectInBothPrecisions(scene, expected, float32);
}

TEST(SphereAnalytic, DistantLightPhong)
{
  for (double eta : { 1.0, 10.0, 100.0 })
  {
    SCOPED_TRACE("eta " + std::to_string(eta));
    distantLightOverhead(SpecularModel::Phong, eta);
  }
}

TEST(SphereAnalytic, Float32AboveShininess100)
{
  // x^eta turns a rounding error dx of x into eta x^(eta-1) dx <= eta dx, and float32
  // rounds x near 1 by at most 2^-24; with the products around it, the specular term is off
  // by at most ks Ls eta 2^-23 (measured on this sphere: 7e-6 at eta 1000, 2e-8 at 10000).
  for (double eta : { 1000.0, 10000.0 })
  {
    SCOPED_TRACE("eta " + std::to_string(eta));
    const double bound = std::max(float32Tolerance.relative, 0.3 * 1.5 * eta * std::ldexp(1.0, -23));
    distantLightOverhead(SpecularModel::Phong, eta, { bound, "float32" });
  }
}

TEST(SphereAnalytic, DistantLightBlinnPhong)
{
  for (double eta : { 1.0, 10.0, 100.0 })
  {
    SCOPED_TRACE("eta " + std::to_string(eta));
    distantLightOverhead(SpecularModel::BlinnPhong, eta);
  }
}

// A point light on the z axis at height D and a local viewer at height V. By the law of
// cosines the distance is d = sqrt(1 + D^2 - 2 D cos theta), and with e the viewer's distance:
// n.s = (D cos theta - 1)/d, n.v = (V cos theta - 1)/e, s.v = (D V - (D + V) cos theta + 1)/(d e),
// r.v = 2 (n.s)(n.v) - s.v, n.h = (n.s + n.v)/sqrt(2 + 2 s.v).
struct AxisGeometry
{
  double D, V;
  double d(const SpherePoint& x) const { return std::sqrt(1 + D * D - 2 * D * std::cos(x.theta)); }
  double e(const SpherePoint& x) const { return std::sqrt(1 + V * V - 2 * V * std::cos(x.theta)); }
  double ns(const SpherePoint& x) const { return (D * std::cos(x.theta) - 1) / d(x); }
  double nv(const SpherePoint& x) const { return (V * std::cos(x.theta) - 1) / e(x); }
  double sv(const SpherePoint& x) const { return (D * V - (D + V) * std::cos(x.theta) + 1) / (d(x) * e(x)); }
  glm::dvec3 s(const SpherePoint& x) const { return (glm::dvec3(0, 0, D) - x.n()) / d(x); }
  glm::dvec3 v(const SpherePoint& x) const { return (glm::dvec3(0, 0, V) - x.n()) / e(x); }
  // The cosine between the spot axis (-z) and the direction from the light to the vertex.
  double coneCos(const SpherePoint& x) const { return (D - std::cos(x.theta)) / d(x); }
};

/// The per-light expectations of a positional light named name, whose strength (attenuation
/// times cone factor, times colour and intensity) is given, under Blinn-Phong.
std::map<std::string, Expected> positionalLight(const std::string& name, const AxisGeometry& g,
  std::function<double(double)> attenuation, std::function<double(double)> cone, double eta)
{
  auto lit = [=](const SpherePoint& x) { return g.ns(x) > 0; };
  auto strength = [=](const SpherePoint& x) { return attenuation(g.d(x)) * cone(g.coneCos(x)); };
  auto diffuse = [=](const SpherePoint& x) { return 0.6 * 2.0 * positive(g.ns(x)) * strength(x); };
  auto nh = [=](const SpherePoint& x) { return (g.ns(x) + g.nv(x)) / std::sqrt(2 + 2 * g.sv(x)); };
  auto specular = [=](const SpherePoint& x)
  { return lit(x) ? 0.3 * 2.0 * std::pow(positive(nh(x)), eta) * strength(x) : 0.0; };
  return {
    { name + "_to_light", [=](const SpherePoint& x) { return vector(g.s(x)); } },
    { name + "_distance", [=](const SpherePoint& x) { return scalar(g.d(x)); } },
    { name + "_attenuation", [=](const SpherePoint& x) { return scalar(attenuation(g.d(x))); } },
    { name + "_spot_factor", [=](const SpherePoint& x) { return scalar(cone(g.coneCos(x))); } },
    { name + "_cos_incidence", [=](const SpherePoint& x) { return scalar(g.ns(x)); } },
    { name + "_incidence_angle", [=](const SpherePoint& x) { return scalar(std::acos(g.ns(x)) * 180 / M_PI); } },
    { name + "_reflection", [=](const SpherePoint& x) { return vector(2 * g.ns(x) * x.n() - g.s(x)); } },
    { name + "_r_dot_v", [=](const SpherePoint& x) { return scalar(2 * g.ns(x) * g.nv(x) - g.sv(x)); } },
    { name + "_half_vector",
      [=](const SpherePoint& x) { return vector((g.s(x) + g.v(x)) / std::sqrt(2 + 2 * g.sv(x))); } },
    { name + "_n_dot_h", [=](const SpherePoint& x) { return scalar(nh(x)); } },
    { name + "_diffuse", [=](const SpherePoint& x) { return grey(diffuse(x)); } },
    { name + "_specular", [=](const SpherePoint& x) { return grey(specular(x)); } },
    { "ambient", [](const SpherePoint&) { return grey(0.0); } },
    { "diffuse", [=](const SpherePoint& x) { return grey(diffuse(x)); } },
    { "specular", [=](const SpherePoint& x) { return grey(specular(x)); } },
    { "total", [=](const SpherePoint& x) { return grey(diffuse(x) + specular(x)); } },
  };
}

Scene axisScene(LightSource light, double viewerHeight, double eta)
{
  Scene scene;
  scene.material = { Rgb(0.1), Rgb(0.6), Rgb(0.3), eta, SpecularModel::BlinnPhong, false, {} };
  scene.viewer.position = glm::dvec3(0, 0, viewerHeight);
  scene.lights = { { "bulb", std::move(light) } };
  return scene;
}

TEST(SphereAnalytic, PointLightUnderEveryAttenuation)
{
  const AxisGeometry g{ 3.0, 5.0 };
  const double eta = 20;
  struct Case
  {
    Attenuation attenuation;
    std::function<double(double)> closedForm;
  };
  Attenuation none, inverse, inverseSquare, vtk, gltf;
  none.model = AttenuationModel::None;
  inverse.model = AttenuationModel::Inverse;
  vtk.model = AttenuationModel::ConstantLinearQuadratic;
  vtk.constant = 1;
  vtk.linear = 0.5;
  vtk.quadratic = 0.25;
  gltf.model = AttenuationModel::GltfRange;
  gltf.range = 3.5; // d runs from 2 to 4: the window closes inside the sphere
  const std::vector<Case> cases = {
    { none, [](double) { return 1.0; } },
    { inverse, [](double d) { return 1 / d; } },
    { inverseSquare, [](double d) { return 1 / (d * d); } },
    { vtk, [](double d) { return 1 / (1 + 0.5 * d + 0.25 * d * d); } },
    { gltf, [](double d) { return std::clamp(1 - std::pow(d / 3.5, 4), 0.0, 1.0) / (d * d); } },
  };
  for (const Case& c : cases)
  {
    SCOPED_TRACE("attenuation model " + std::to_string(int(c.attenuation.model)));
    PointLight bulb{ { 0, 0, g.D }, Rgb(1.0), 2.0, c.attenuation };
    expectInBothPrecisions(axisScene(bulb, g.V, eta),
      positionalLight(
        "bulb", g, c.closedForm, [](double) { return 1.0; }, eta));
  }
}

TEST(SphereAnalytic, SpotlightConesInsideAndOutside)
{
  const AxisGeometry g{ 3.0, 5.0 };
  const double eta = 20;
  // The sphere spans 19.47 degrees seen from the light: a 10 degree cone lights part of it.
  SpotCone vtkCone;
  vtkCone.halfAngleDegrees = 10;
  vtkCone.exponent = 2;
  const double cos10 = std::cos(10 * M_PI / 180);
  SpotCone gltfCone;
  gltfCone.model = ConeModel::Gltf;
  gltfCone.innerAngleDegrees = 5;
  gltfCone.outerAngleDegrees = 12;
  const double cos5 = std::cos(5 * M_PI / 180), cos12 = std::cos(12 * M_PI / 180);
  const std::vector<std::pair<SpotCone, std::function<double(double)>>> cones = {
    { vtkCone, [=](double c) { return c >= cos10 ? c * c : 0.0; } },
    { gltfCone,
      [=](double c)
      {
        const double a = std::clamp((c - cos12) / (cos5 - cos12), 0.0, 1.0);
        return a * a;
      } },
  };
  Attenuation inverseSquare;
  for (const auto& [cone, closedForm] : cones)
  {
    SCOPED_TRACE(cone.model == ConeModel::Vtk ? "vtk cone" : "gltf cone");
    SpotLight spot{ { 0, 0, g.D }, { 0, 0, -1 }, Rgb(1.0), 2.0, inverseSquare, cone };
    expectInBothPrecisions(axisScene(spot, g.V, eta),
      positionalLight(
        "bulb", g, [](double d) { return 1 / (d * d); }, closedForm, eta));
  }
}

TEST(SphereAnalytic, FlagsMarkTheLightsHorizon)
{
  const AxisGeometry g{ 3.0, 5.0 };
  vtkSmartPointer<vtkPolyData> sphere = shadelab::testing::exactSphere(150);
  vtkNew<vtkLocalReflectanceFilter> filter;
  filter->SetInputData(sphere);
  filter->SetScene(axisScene(PointLight{ { 0, 0, g.D }, Rgb(1.0), 1.0, Attenuation{} }, g.V, 10));
  filter->Update();
  vtkDataArray* flags = filter->GetOutput()->GetPointData()->GetArray("shading_flags");
  ASSERT_NE(flags, nullptr);
  vtkIdType below = 0;
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    double p[3];
    sphere->GetPoint(i, p);
    // Lit where D cos(theta) > 1, the tangent cone from the light.
    const bool belowHorizon = g.D * p[2] <= 1;
    EXPECT_EQ(static_cast<int>(flags->GetComponent(i, 0)), belowHorizon ? FlagLightBelowHorizon : 0) << i;
    below += belowHorizon;
  }
  EXPECT_GT(below, 0);
  EXPECT_LT(below, sphere->GetNumberOfPoints());
}
}
