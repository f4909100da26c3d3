// A material from the mesh's own arrays (docs/formulas.md section 7.1): each light's diffuse term
// against its closed form with each vertex's decoded colour, per-vertex shininess and ks against
// uniform runs, and the exact message for every array that cannot be used.
#include "FilterRun.h"
#include "TestMeshes.h"

#include "ArrayCatalog.h"
#include "SceneFile.h"
#include "ShadeLabMaterialArrays.h"

#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <random>

namespace
{
using namespace shadelab;
using shadelab::testing::exactSphere;
using shadelab::testing::shadeWithFilter;

/// The scene's JSON with this material, under one distant light of colour (0.9, 0.8, 0.7) x
/// 1.25 from direction (0.3, -0.2, -1), and an ambient light of 0.1.
Scene sceneWithMaterial(const std::string& material, const std::string& model = "lecture")
{
  return parseScene(R"({ "model": ")" + model + R"(", "viewer": { "position": [0, 0, 6] }, "material": )" + material +
      R"(, "lights": [ { "name": "sun", "type": "distant", "direction": [0.3, -0.2, -1], "color": [0.9, 0.8, 0.7],
        "intensity": 1.25 })" +
      (model == "lecture" ? R"(, { "name": "sky", "type": "ambient", "intensity": 0.1 })" : "") + R"( ] })",
    "scene.json");
}

const glm::dvec3 towardSun = -glm::normalize(glm::dvec3(0.3, -0.2, -1));
const glm::dvec3 sunColor = 1.25 * glm::dvec3(0.9, 0.8, 0.7);

/// A sphere with `name` holding random 8-bit colours (components per vertex).
vtkSmartPointer<vtkPolyData> sphereWithColors(const std::string& name, int components, unsigned seed)
{
  vtkSmartPointer<vtkPolyData> sphere = exactSphere(80);
  std::mt19937 random(seed);
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName(name.c_str());
  colors->SetNumberOfComponents(components);
  for (vtkIdType i = 0; i < components * sphere->GetNumberOfPoints(); ++i)
  {
    colors->InsertNextValue(static_cast<unsigned char>(random() % 256));
  }
  sphere->GetPointData()->AddArray(colors);
  return sphere;
}

/// A sphere with a 1-component float64 array `name` of these values, in vertex order, cycled.
vtkSmartPointer<vtkPolyData> sphereWithValues(const std::string& name, const std::vector<double>& values)
{
  vtkSmartPointer<vtkPolyData> sphere = exactSphere(40);
  vtkNew<vtkDoubleArray> array;
  array->SetName(name.c_str());
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    array->InsertNextValue(values[std::size_t(i) % values.size()]);
  }
  sphere->GetPointData()->AddArray(array);
  return sphere;
}

/// Each vertex's expected diffuse term of the sun, and ambient term, from its linear colour.
void expectDiffuseAndAmbient(
  vtkPolyData* output, const std::function<glm::dvec3(vtkIdType)>& linearColor, double tolerance)
{
  vtkDataArray* diffuse = output->GetPointData()->GetArray("sun_diffuse");
  vtkDataArray* ambient = output->GetPointData()->GetArray("ambient");
  ASSERT_TRUE(diffuse && ambient);
  vtkDataArray* normals = output->GetPointData()->GetNormals();
  double worst = 0;
  for (vtkIdType i = 0; i < output->GetNumberOfPoints(); ++i)
  {
    double n[3];
    normals->GetTuple(i, n);
    const double cosine = std::max(0.0, glm::dot(glm::dvec3(n[0], n[1], n[2]), towardSun));
    const glm::dvec3 kd = linearColor(i);
    for (int c = 0; c < 3; ++c)
    {
      const double expectedDiffuse = kd[c] * cosine * sunColor[c];
      const double expectedAmbient = kd[c] * 0.1; // ka follows kd
      worst = std::max(worst, std::abs(diffuse->GetComponent(i, c) - expectedDiffuse));
      ASSERT_NEAR(diffuse->GetComponent(i, c), expectedDiffuse, tolerance) << "vertex " << i << " channel " << c;
      ASSERT_NEAR(ambient->GetComponent(i, c), expectedAmbient, tolerance) << "vertex " << i << " channel " << c;
    }
  }
  std::cout << "largest difference from the closed form: " << worst << "\n";
}

// The float32 kernel rounds n.s, the colour and their products: a few units in the last place
// of values up to 1.1.
constexpr double float32Rounding = 4e-7;

TEST(MaterialArrays, RandomEightBitColorsAreDecodedFromSrgb)
{
  vtkSmartPointer<vtkPolyData> sphere = sphereWithColors("Colors", 3, 11);
  const Scene scene = sceneWithMaterial(R"({ "kd": { "array": "Colors" }, "specular": "none" })");
  vtkSmartPointer<vtkPolyData> output =
    shadeWithFilter(sphere, scene, { "sun_diffuse", "ambient" }, vtkAlgorithm::SINGLE_PRECISION);
  auto* colors = vtkUnsignedCharArray::SafeDownCast(sphere->GetPointData()->GetArray("Colors"));
  expectDiffuseAndAmbient(
    output,
    [&](vtkIdType i)
    {
      return glm::dvec3(srgbToLinear(colors->GetComponent(i, 0) / 255.0),
        srgbToLinear(colors->GetComponent(i, 1) / 255.0), srgbToLinear(colors->GetComponent(i, 2) / 255.0));
    },
    float32Rounding);
  // The input's array passes through untouched.
  EXPECT_EQ(output->GetPointData()->GetArray("Colors"), colors);
}

TEST(MaterialArrays, LinearFloatColorsAreUsedAsTheyAreAndGreysAndAlphaToo)
{
  vtkSmartPointer<vtkPolyData> sphere = exactSphere(60);
  std::mt19937 random(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  vtkNew<vtkFloatArray> albedo;
  albedo->SetName("Albedo");
  albedo->SetNumberOfComponents(3);
  for (vtkIdType i = 0; i < 3 * sphere->GetNumberOfPoints(); ++i)
  {
    albedo->InsertNextValue(unit(random));
  }
  sphere->GetPointData()->AddArray(albedo);
  vtkSmartPointer<vtkPolyData> output =
    shadeWithFilter(sphere, sceneWithMaterial(R"({ "kd": { "array": "Albedo", "scale": 0.5 }, "specular": "none" })"),
      { "sun_diffuse", "ambient" }, vtkAlgorithm::SINGLE_PRECISION);
  expectDiffuseAndAmbient(
    output,
    [&](vtkIdType i)
    { return 0.5 * glm::dvec3(albedo->GetComponent(i, 0), albedo->GetComponent(i, 1), albedo->GetComponent(i, 2)); },
    float32Rounding);

  // A grey (1 component) in every channel; RGBA's alpha is not a reflectance.
  vtkSmartPointer<vtkPolyData> grey = sphereWithColors("Grey", 1, 3);
  auto* greys = grey->GetPointData()->GetArray("Grey");
  expectDiffuseAndAmbient(
    shadeWithFilter(grey,
      sceneWithMaterial(R"({ "kd": { "array": "Grey", "encoding": "linear" }, "specular": "none" })"),
      { "sun_diffuse", "ambient" }),
    [&](vtkIdType i) { return glm::dvec3(greys->GetComponent(i, 0) / 255.0); }, 1e-15);
  vtkSmartPointer<vtkPolyData> rgba = sphereWithColors("RGBA", 4, 9);
  auto* rgbas = rgba->GetPointData()->GetArray("RGBA");
  expectDiffuseAndAmbient(
    shadeWithFilter(
      rgba, sceneWithMaterial(R"({ "kd": { "array": "RGBA" }, "specular": "none" })"), { "sun_diffuse", "ambient" }),
    [&](vtkIdType i)
    {
      return glm::dvec3(srgbToLinear(rgbas->GetComponent(i, 0) / 255.0),
        srgbToLinear(rgbas->GetComponent(i, 1) / 255.0), srgbToLinear(rgbas->GetComponent(i, 2) / 255.0));
    },
    1e-15);
}

TEST(MaterialArrays, PerVertexShininessAndKsEqualUniformRunsVertexByVertex)
{
  const std::vector<double> etas{ 5.5, 40.25, 12.0 }, gloss{ 0.3, 0.75 };
  vtkSmartPointer<vtkPolyData> sphere = sphereWithValues("eta", etas);
  vtkNew<vtkDoubleArray> glossArray;
  glossArray->SetName("gloss");
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    glossArray->InsertNextValue(gloss[std::size_t(i) % gloss.size()]);
  }
  sphere->GetPointData()->AddArray(glossArray);
  const vtkSmartPointer<vtkPolyData> varying = shadeWithFilter(sphere,
    sceneWithMaterial(R"({ "kd": 0.5, "ks": { "array": "gloss" }, "shininess": { "array": "eta" } })"),
    { "sun_specular" });
  vtkDataArray* specular = varying->GetPointData()->GetArray("sun_specular");
  ASSERT_NE(specular, nullptr);
  for (std::size_t e = 0; e < etas.size(); ++e)
  {
    const vtkSmartPointer<vtkPolyData> uniform = shadeWithFilter(sphere,
      sceneWithMaterial(R"({ "kd": 0.5, "ks": 1, "shininess": )" + std::to_string(etas[e]) + "}"), { "sun_specular" });
    vtkDataArray* expected = uniform->GetPointData()->GetArray("sun_specular");
    int lit = 0;
    for (vtkIdType i = vtkIdType(e); i < sphere->GetNumberOfPoints(); i += vtkIdType(etas.size()))
    {
      const double ks = gloss[std::size_t(i) % gloss.size()];
      for (int c = 0; c < 3; ++c)
      {
        ASSERT_NEAR(specular->GetComponent(i, c), ks * expected->GetComponent(i, c), 1e-15) << "vertex " << i;
      }
      lit += expected->GetComponent(i, 0) > 0.01 ? 1 : 0;
    }
    EXPECT_GT(lit, 10); // the comparison met highlights, not only zeros
  }
}

TEST(MaterialArrays, AToleranceKeepsTheExactPowForAShininessPerVertex)
{
  vtkSmartPointer<vtkPolyData> sphere = sphereWithValues("eta", { 30, 60 });
  const auto run = shadelab::testing::shadeToTolerance(
    sphere, sceneWithMaterial(R"({ "kd": 0.5, "ks": 0.5, "shininess": { "array": "eta" } })"), 1e-2, 1);
  ASSERT_EQ(run.plan.lights.size(), 2u);
  EXPECT_EQ(run.plan.lights[0].method.pow, PowMethod::Exact);
  EXPECT_NE(run.plan.lights[0].why.find("exact pow: the shininess varies per vertex"), std::string::npos)
    << run.plan.lights[0].why;
}

TEST(MaterialArrays, AConstantFieldTakesTheColorMapsLowEnd)
{
  const vtkSmartPointer<vtkPolyData> output = shadeWithFilter(sphereWithValues("T", { 7.0 }),
    sceneWithMaterial(R"({ "kd": { "array": "T", "colormap": "cool to warm", "encoding": "linear" } })"),
    { "ambient" });
  EXPECT_NEAR(output->GetPointData()->GetArray("ambient")->GetComponent(0, 2), 0.1 * 192 / 255.0, 1e-15);
}

TEST(MaterialArrays, AToleranceBoundsFloat32sRoundingAtTheLargestShininess)
{
  // A shininess of 1 rounds little in float32; 5000, at some vertices, 5000 times as much: the
  // plan takes the array's largest (its scale, 1, would let float32 through).
  vtkSmartPointer<vtkPolyData> sphere = sphereWithValues("eta", { 1, 5000 });
  const std::string material = R"({ "kd": 0.5, "ks": 0.5, "shininess": )";
  const auto uniform = shadelab::testing::shadeToTolerance(sphere, sceneWithMaterial(material + "1 }"), 1e-4, 1);
  EXPECT_EQ(uniform.plan.precision, Precision::Float32);
  const auto varying =
    shadelab::testing::shadeToTolerance(sphere, sceneWithMaterial(material + R"({ "array": "eta" } })"), 1e-4, 1);
  EXPECT_EQ(varying.plan.precision, Precision::Float64);
}

TEST(MaterialArrays, AFieldThroughAColorMapSpansItsOwnRangeByDefault)
{
  const std::vector<double> values{ -2.0, 0.5, 3.0 };
  vtkSmartPointer<vtkPolyData> sphere = sphereWithValues("T", values);
  const vtkSmartPointer<vtkPolyData> output = shadeWithFilter(sphere,
    sceneWithMaterial(
      R"({ "kd": { "array": "T", "colormap": "grayscale", "encoding": "linear" }, "specular": "none" })"),
    { "ambient" });
  // The grey ramp's ends at the field's ends: ambient = kd x 0.1, kd = the table's 8-bit grey.
  const vtkSmartPointer<vtkScalarsToColors> map = namedColorMap("grayscale", { -2.0, 3.0 });
  vtkDataArray* ambient = output->GetPointData()->GetArray("ambient");
  for (vtkIdType i = 0; i < 3; ++i)
  {
    const unsigned char* rgba = map->MapValue(values[std::size_t(i)]);
    EXPECT_NEAR(ambient->GetComponent(i, 0), 0.1 * rgba[0] / 255.0, 1e-15);
  }
  EXPECT_NEAR(ambient->GetComponent(0, 0), 0.0, 1e-15);
  EXPECT_NEAR(ambient->GetComponent(2, 0), 0.1, 1e-15);
}

TEST(MaterialArrays, CoolToWarmIsParaViewsPreset)
{
  // ParaView 5.11's "Cool to Warm": its ends and middle, as 8-bit colours.
  const vtkSmartPointer<vtkScalarsToColors> map = namedColorMap("cool to warm", { 0.0, 1.0 });
  const unsigned char* low = map->MapValue(0.0);
  EXPECT_EQ(std::vector<int>(low, low + 3), (std::vector<int>{ 59, 76, 192 }));
  const unsigned char* high = map->MapValue(1.0);
  EXPECT_EQ(std::vector<int>(high, high + 3), (std::vector<int>{ 180, 4, 38 }));
}

TEST(MaterialArrays, ClampedValuesAreMarkedPerCoefficient)
{
  vtkSmartPointer<vtkPolyData> sphere = sphereWithValues("gloss", { 0.5, 1.5, std::nan("") });
  const vtkSmartPointer<vtkPolyData> output = shadeWithFilter(
    sphere, sceneWithMaterial(R"({ "kd": { "array": "gloss", "clamp": true }, "specular": "none" })"), { "ambient" });
  vtkDataArray* clamped = output->GetPointData()->GetArray("material_clamped");
  vtkDataArray* ambient = output->GetPointData()->GetArray("ambient");
  ASSERT_TRUE(clamped && ambient);
  // ka follows kd: both are clamped (bits 0 and 1).
  EXPECT_EQ(clamped->GetComponent(0, 0), 0);
  EXPECT_EQ(clamped->GetComponent(1, 0), 3);
  EXPECT_EQ(clamped->GetComponent(2, 0), 3);
  EXPECT_NEAR(ambient->GetComponent(0, 0), 0.05, 1e-15);
  EXPECT_NEAR(ambient->GetComponent(1, 0), 0.1, 1e-15);
  EXPECT_NEAR(ambient->GetComponent(2, 0), 0.0, 1e-15);
}

TEST(MaterialArrays, TheArraysAreReadAgainOnlyWhenTheyChange)
{
  vtkSmartPointer<vtkPolyData> sphere = sphereWithValues("gloss", { 0.5 });
  vtkNew<vtkLocalReflectanceFilter> filter;
  filter->SetInputData(sphere);
  filter->SetScene(sceneWithMaterial(R"({ "kd": { "array": "gloss" }, "specular": "none" })"));
  filter->SetArraySelection({ "ambient" });
  filter->SetOutputPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  auto ambientAtVertex0 = [&]
  {
    filter->Update();
    return filter->GetOutput()->GetPointData()->GetArray("ambient")->GetComponent(0, 0);
  };
  EXPECT_DOUBLE_EQ(ambientAtVertex0(), 0.05);
  // New lights on the same arrays: the values read last time.
  filter->SetScene(parseScene(R"({ "material": { "kd": { "array": "gloss" } },
    "lights": [ { "type": "ambient", "intensity": 0.2 } ] })",
    "scene.json"));
  EXPECT_DOUBLE_EQ(ambientAtVertex0(), 0.1);
  // The array's values changed (and it says so): read again.
  vtkDataArray* gloss = sphere->GetPointData()->GetArray("gloss");
  gloss->SetComponent(0, 0, 0.25);
  gloss->Modified();
  filter->Modified();
  EXPECT_DOUBLE_EQ(ambientAtVertex0(), 0.05);
  // Another array of the same name in its place: read again.
  vtkNew<vtkDoubleArray> replacement;
  replacement->DeepCopy(gloss);
  replacement->SetComponent(0, 0, 1.0);
  sphere->GetPointData()->AddArray(replacement);
  filter->Modified();
  EXPECT_DOUBLE_EQ(ambientAtVertex0(), 0.2);
}

TEST(MaterialArrays, AMetallicFactorOrRoughnessThatCannotBeUsedIsRefusedByNameAndVertex)
{
  using shadelab::testing::filterError;
  const std::string both = R"({ "metallic": { "array": "values" }, "roughness": { "array": "values" } })";
  EXPECT_EQ(filterError(sphereWithValues("values", { 0.5, 0.25, 0.0, 0.75 }), sceneWithMaterial(both, "vtk_pbr")),
    "scene /material/roughness: array 'values', vertex 2: it is 0, outside (0, 1] (at 0, VTK's GGX distribution is "
    "0/0 in the mirror direction)");
  EXPECT_EQ(filterError(sphereWithValues("values", { 0.5, 1.25 }), sceneWithMaterial(both, "vtk_pbr")),
    "scene /material/metallic: array 'values', vertex 1: it is 1.25, outside [0, 1]");
  EXPECT_EQ(filterError(sphereWithValues("values", { 0.5, 0.25 }),
              sceneWithMaterial(R"({ "metallic": { "array": "Normals" } })", "vtk_pbr")),
    "scene /material/metallic: array 'Normals' has 3 components; a metallic factor takes 1");
  // In float32 (the filter's default), D's peak needs a roughness of about 0.07 or more: the
  // smallest that the array gives is named, with its vertex.
  vtkSmartPointer<vtkPolyData> smooth = sphereWithValues("values", { 0.5, 0.25, 0.05, 0.06 });
  EXPECT_EQ(filterError(smooth, sceneWithMaterial(both, "vtk_pbr")),
    "scene /material/roughness: array 'values', vertex 2: at roughness 0.05 float32 arithmetic errs by up to 3.8% at "
    "the highlight's peak (D needs 1 - n.h finer than float32 holds): use float64, or a roughness of at least 0.07");
  vtkSmartPointer<vtkPolyData> shaded = shadeWithFilter(smooth, sceneWithMaterial(both, "vtk_pbr"), { "sun_ggx_d" });
  ASSERT_NE(shaded->GetPointData()->GetArray("sun_ggx_d"), nullptr); // float64 shades it
  // Even float64 bounds D's peak: a roughness from an array must be at least 1e-6 there.
  vtkNew<vtkLocalReflectanceFilter> filter;
  vtkNew<app::VtkErrorCapture> errors;
  errors->watch(filter);
  filter->SetInputData(sphereWithValues("values", { 0.5, 1e-7 }));
  filter->SetScene(sceneWithMaterial(both, "vtk_pbr"));
  filter->SetOutputPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  filter->Update();
  EXPECT_EQ(errors->message(),
    "scene /material/roughness: array 'values', vertex 1: at roughness 1e-07 D's peak, 1/(pi r^4), is beyond what the "
    "run's overflow checks bound: a roughness from an array must be at least 1e-06");
  // A byte is over 255: 0 is a roughness of 0.
  vtkSmartPointer<vtkPolyData> bytes = sphereWithValues("values", { 0.5 });
  vtkNew<vtkUnsignedCharArray> roughness;
  roughness->SetName("bytes");
  for (vtkIdType i = 0; i < bytes->GetNumberOfPoints(); ++i)
  {
    roughness->InsertNextValue(i == 3 ? 0 : 200);
  }
  bytes->GetPointData()->AddArray(roughness);
  EXPECT_EQ(filterError(bytes, sceneWithMaterial(R"({ "roughness": { "array": "bytes" } })", "vtk_pbr")),
    "scene /material/roughness: array 'bytes', vertex 3: it is 0, outside (0, 1] (at 0, VTK's GGX distribution is 0/0 "
    "in the mirror direction)");
  // Only the vtk_pbr model has them.
  Scene lecture = sceneWithMaterial(R"({ "kd": 0.5 })");
  lecture.material.arrays[MaterialCoefficient::Metallic] = ArrayCoefficient{ "values" };
  EXPECT_EQ(
    filterError(smooth, lecture), "scene /material: only the vtk_pbr model has a metallic factor and a roughness");
}

TEST(MaterialArrays, ArraysThatCannotBeUsedAreRefusedByNameAndVertex)
{
  using shadelab::testing::filterError;
  vtkSmartPointer<vtkPolyData> sphere = sphereWithValues("gloss", { 0.5, 0.25, 1.5, std::nan("") });
  EXPECT_EQ(filterError(sphere, sceneWithMaterial(R"({ "kd": { "array": "Colors" } })")),
    "scene /material/kd: the mesh has no numeric point-data array 'Colors' (its point arrays: 'Normals', 'gloss')");
  EXPECT_EQ(filterError(sphere, sceneWithMaterial(R"({ "kd": { "array": "gloss" } })")),
    "scene /material/kd: array 'gloss', vertex 2: it is 1.5, outside [0, 1]");
  EXPECT_EQ(filterError(sphere, sceneWithMaterial(R"({ "kd": { "array": "gloss", "colormap": "rainbow" } })")),
    "scene /material/kd: array 'gloss', vertex 3: it is NaN, which has no colour in the colour map (\"clamp\": true "
    "gives it the colour of the range's low end)");
  EXPECT_EQ(filterError(sphere, sceneWithMaterial(R"({ "kd": { "array": "Normals", "colormap": "rainbow" } })")),
    "scene /material/kd: array 'Normals' has 3 components; a colour map takes a field of 1");
  EXPECT_EQ(filterError(sphere, sceneWithMaterial(R"({ "kd": 0.5, "shininess": { "array": "Normals" } })")),
    "scene /material/shininess: array 'Normals' has 3 components; a shininess takes 1");
  vtkSmartPointer<vtkPolyData> pairs = sphereWithColors("UV", 2, 1);
  EXPECT_EQ(filterError(pairs, sceneWithMaterial(R"({ "kd": { "array": "UV" } })")),
    "scene /material/kd: array 'UV' has 2 components; a colour takes 3 (RGB), 4 (RGBA, alpha unused) or 1 (a grey, "
    "or a field through a colour map)");
  // Another length than the mesh's points, another integer type, and from the filter's colour array.
  vtkNew<vtkDoubleArray> few;
  few->SetName("few");
  few->SetNumberOfTuples(7);
  few->FillValue(0.5);
  sphere->GetPointData()->AddArray(few);
  EXPECT_EQ(filterError(sphere, sceneWithMaterial(R"({ "kd": { "array": "few" } })")),
    "scene /material/kd: array 'few' has 7 values for the mesh's 1522 points");
  vtkNew<vtkIntArray> counts;
  counts->SetName("counts");
  counts->SetNumberOfTuples(sphere->GetNumberOfPoints());
  counts->FillValue(1);
  sphere->GetPointData()->AddArray(counts);
  EXPECT_EQ(filterError(sphere, sceneWithMaterial(R"({ "kd": 0.5, "shininess": { "array": "counts" } })")),
    "scene /material/shininess: array 'counts' holds int values; a material reads 8-bit (unsigned char) or "
    "floating-point ones: convert it (16-bit colours divided by 65535 into a float array, say)");
  {
    vtkNew<vtkLocalReflectanceFilter> filter;
    vtkNew<app::VtkErrorCapture> errors;
    errors->watch(filter);
    filter->SetInputData(sphere);
    filter->SetColorByArray(true);
    filter->SetMaterialColorArray("Colors");
    filter->Update();
    EXPECT_EQ(errors->message(),
      "the material's colour array (MaterialColorArray, --color-by): the mesh has no numeric "
      "point-data array 'Colors' (its point arrays: 'Normals', 'gloss', 'few', 'counts')");
  }
  vtkSmartPointer<vtkPolyData> flat = sphereWithValues("nothing", { std::nan("") });
  EXPECT_EQ(filterError(flat, sceneWithMaterial(R"({ "kd": { "array": "nothing", "colormap": "rainbow" } })")),
    "scene /material/kd: array 'nothing' has no finite value to span the colour map: give its \"range\"");
}
}
