// The spectral mode (docs/formulas.md section 22): colour summed band by band through the CIE
// observer, written as linear sRGB, as XYZ, and as its difference from the RGB model.
#include "FilterRun.h"
#include "TestMeshes.h"

#include "Colorimetry.h"
#include "SceneFile.h"
#include "SpectralColors.h"

#include "vtkDataArray.h"
#include "vtkPointData.h"

#include <gtest/gtest.h>

namespace
{
using namespace shadelab;
using shadelab::testing::exactSphere;
using shadelab::testing::shadeWithFilter;

/// A flat spectrum of this value over the observer's range, as a scene file writes it.
std::string flat(double value)
{
  std::string values;
  for (int i = 0; i < 48; ++i)
  {
    values += (i ? ", " : "") + std::to_string(value);
  }
  return R"({ "start_nm": 360, "step_nm": 10, "values": [)" + values + "] }";
}

/// A spectral scene: a light with this spectrum from +z (and, where ambient, an ambient light of
/// it too) on this material, seen from +z.
Scene spectralScene(const std::string& lightSpectrum, const std::string& material, double bandNm = 5)
{
  return parseScene(R"({ "viewer": { "position": [0, 0, 6] }, "spectral": { "band_nm": )" + std::to_string(bandNm) +
      R"( }, "material": )" + material + R"(, "lights": [
      { "name": "lamp", "type": "distant", "direction": [0, 0, -1], "spectrum": )" +
      lightSpectrum + R"( },
      { "name": "room", "type": "ambient", "intensity": 0.1, "spectrum": )" +
      lightSpectrum + " } ] }",
    "scene.json");
}

/// The output's array at the sphere's pole facing the light (+z): vertex 0 of vtkSphereSource.
glm::dvec3 atPole(vtkPolyData* output, const char* name)
{
  vtkDataArray* array = output->GetPointData()->GetArray(name);
  EXPECT_NE(array, nullptr) << name;
  double value[3] = { 0, 0, 0 };
  if (array)
  {
    array->GetTuple(0, value);
  }
  return { value[0], value[1], value[2] };
}

TEST(SpectralMode, ConstantSpectraAreTheRgbModel)
{
  // Flat emission and flat reflectances: the product of spectra is the product of their RGB.
  const Scene scene = spectralScene(flat(1.0),
    R"({ "kd": { "spectrum": )" + flat(0.6) + R"( }, "ks": { "spectrum": )" + flat(0.3) + " }, \"shininess\": 20 }");
  vtkSmartPointer<vtkPolyData> output =
    shadeWithFilter(exactSphere(40), scene, { "default" }, vtkAlgorithm::SINGLE_PRECISION);
  vtkDataArray* difference = output->GetPointData()->GetArray("total_rgb_difference");
  ASSERT_NE(difference, nullptr);
  double largest = 0;
  for (vtkIdType i = 0; i < difference->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      largest = std::max(largest, std::abs(difference->GetComponent(i, c)));
    }
  }
  EXPECT_LT(largest, 1e-6) << "float32 rounding of values up to 1";
  EXPECT_GT(atPole(output, "total").x, 0.5); // and the total is lit, not 0
}

TEST(SpectralMode, AWhiteReflectorUnderEAndD65)
{
  const std::string white = R"({ "kd": { "spectrum": )" + flat(1.0) + R"( }, "specular": "none" })";
  vtkSmartPointer<vtkPolyData> underE = shadeWithFilter(
    exactSphere(20), spectralScene(R"({ "illuminant": "E" })", white), { "total" }, vtkAlgorithm::DOUBLE_PRECISION);
  const glm::dvec3 e = atPole(underE, "total_xyz");
  EXPECT_NEAR(e.x / e.y, 1.0, 4e-4); // the 5 nm table's own sums (test_colorimetry.cpp)
  EXPECT_NEAR(e.z / e.y, 1.0, 4e-4);
  // Lit at n.s = 1 by the lamp (luminance 1) and the room (0.1): Y = 1.1.
  EXPECT_NEAR(e.y, 1.1, 1e-12);
  vtkSmartPointer<vtkPolyData> underD65 = shadeWithFilter(
    exactSphere(20), spectralScene(R"({ "illuminant": "D65" })", white), { "total" }, vtkAlgorithm::DOUBLE_PRECISION);
  const glm::dvec2 xy = chromaticity(atPole(underD65, "total_xyz"));
  EXPECT_NEAR(xy.x, 0.3127, 1e-4);
  EXPECT_NEAR(xy.y, 0.3290, 1e-4);
}

TEST(SpectralMode, AFluorescentLampOnRedPaintIsWhereRgbErrs)
{
  // The total at the pole is the light's spectral colours (n.s = 1, the room's ambient added),
  // and the RGB model's differs from it.
  const Scene scene = spectralScene(R"({ "illuminant": "F11" })", R"({ "kd": [0.8, 0.1, 0.1], "specular": "none" })");
  vtkSmartPointer<vtkPolyData> output =
    shadeWithFilter(exactSphere(20), scene, { "total" }, vtkAlgorithm::DOUBLE_PRECISION);
  const LightColors spectral = spectralLightColors(scene);
  const glm::dvec3 total = atPole(output, "total");
  const glm::dvec3 expected = spectral.diffuse[0] + spectral.ambient;
  // The RGB model: F11's RGB times the paint's, from the lamp (n.s = 1) and the room (0.1).
  const Rgb lampRgb = std::get<DistantLight>(scene.lights[0].source).color;
  const glm::dvec3 rgbModel = 1.1 * lampRgb * Rgb(0.8, 0.1, 0.1);
  for (int c = 0; c < 3; ++c)
  {
    EXPECT_NEAR(total[c], expected[c], 1e-12);
    EXPECT_NEAR(atPole(output, "total_rgb_difference")[c], expected[c] - rgbModel[c], 1e-12);
  }
  // F11's three narrow bands miss much of the paint's red: the RGB model overstates it.
  EXPECT_LT(atPole(output, "total_rgb_difference").x, -0.05);
}

TEST(SpectralMode, WhatItCannotShadeYet)
{
  EXPECT_THROW(parseScene(R"({ "spectral": { "band_nm": 0 }, "lights": [] })", "scene.json"), SceneFileError);
  auto errorOf = [](const std::string& text)
  {
    try
    {
      parseScene(text, "scene.json");
    }
    catch (const SceneFileError& error)
    {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(errorOf(R"({ "spectral": { "band_nm": 60 }, "lights": [] })"),
    "scene.json: /spectral/band_nm: must be a number of nm > 0 and <= 50");
  EXPECT_EQ(errorOf(R"({ "model": "vtk", "viewer": { "position": [0, 0, 1] }, "spectral": {}, "lights": [] })"),
    "scene.json: /spectral: the vtk model is VTK's renderer, whose colours are RGB: use the lecture model");
  EXPECT_EQ(errorOf(R"({ "spectral": {}, "lights": [ { "type": "disk", "center": [0, 0, 2], "normal": [0, 0, -1],
      "radius": 0.5 } ] })"),
    "scene.json: /lights/0: the spectral mode shades distant, point, spot, headlights and ambient lights; an area "
    "light's or a map's colour is not yet summed band by band");
}
}
