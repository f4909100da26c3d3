// Every light type under every estimator, with the shininess and intensity at the ends of what
// a scene file accepts, gives finite arrays or a refusal that names the field (issue: no NaN
// with exit code 0). A shininess of 1e30 once made the sampled specular integral Inf / Inf.
#include "SceneFile.h"
#include "TestMeshes.h"
#include "TestPaths.h"
#include "VtkErrorCapture.h"
#include "vtkLocalReflectanceFilter.h"

#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using namespace shadelab;

/// The largest number a scene file can hold: every field that takes any number >= 0 accepts it.
const std::string largest = "1.7976931348623157e308";

/// One light of each type, with each of its estimators (area lights and maps); "INTENSITY" is
/// replaced by the intensity under test.
const std::vector<std::string> lightsUnderTest = {
  R"({ "type": "point", "position": [0, 0, 3], "intensity": INTENSITY })",
  R"({ "type": "spot", "position": [0, 0, 3], "direction": [0, 0, -1], "intensity": INTENSITY,
       "cone": { "model": "vtk", "angle": 40, "exponent": 128 } })",
  R"({ "type": "spot", "position": [0, 0, 3], "direction": [0, 0, -1], "intensity": INTENSITY,
       "cone": { "model": "gltf", "inner_angle": 0, "outer_angle": 40 } })",
  R"({ "type": "distant", "direction": [0, 0, -1], "intensity": INTENSITY })",
  R"({ "type": "headlight", "intensity": INTENSITY })",
  R"({ "type": "ambient", "intensity": INTENSITY })",
  R"({ "type": "rectangle", "center": [0, 0, 3], "edge_u": [1, 0, 0], "edge_v": [0, -1, 0], "intensity": INTENSITY })",
  R"({ "type": "rectangle", "center": [0, 0, 3], "edge_u": [1, 0, 0], "edge_v": [0, -1, 0], "intensity": INTENSITY,
       "estimator": "monte_carlo" })",
  R"({ "type": "disk", "center": [0, 0, 3], "normal": [0, 0, -1], "radius": 0.5, "intensity": INTENSITY,
       "estimator": "point" })",
  R"({ "type": "sphere", "center": [0, 0, 3], "radius": 0.5, "intensity": INTENSITY })",
  R"({ "type": "environment", "file": "ENVMAP", "intensity": INTENSITY })",
  R"({ "type": "environment", "file": "ENVMAP", "intensity": INTENSITY, "estimator": "monte_carlo" })",
  R"({ "type": "environment", "file": "ENVMAP", "intensity": INTENSITY, "estimator": "monte_carlo",
       "directions": "cosine" })",
  R"({ "type": "environment", "file": "ENVMAP", "intensity": INTENSITY, "estimator": "monte_carlo",
       "directions": "mis" })",
  R"({ "type": "environment", "file": "ENVMAP", "intensity": INTENSITY, "estimator": "prt" })",
  R"({ "type": "environment", "file": "ENVMAP", "intensity": INTENSITY, "estimator": "brute_force" })",
};

std::string replaced(std::string text, const std::string& what, const std::string& with)
{
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + with.size()))
  {
    text.replace(at, what.size(), with);
  }
  return text;
}

/// What the filter made of the scene: its error message, or "" and the output.
struct Outcome
{
  std::string error;
  vtkSmartPointer<vtkPolyData> output;
};

Outcome shade(vtkPolyData* mesh, const std::string& sceneText, int precision)
{
  Outcome outcome;
  try
  {
    vtkNew<vtkLocalReflectanceFilter> filter;
    vtkNew<app::VtkErrorCapture> errors;
    errors->watch(filter);
    filter->SetInputData(mesh);
    filter->SetScene(parseScene(sceneText, shadelab::testing::sourcePath("data/scenes/scene.json")));
    filter->SetArraySelection({ "all" });
    filter->SetOutputPrecision(precision);
    filter->Update();
    outcome.error = errors->message();
    outcome.output = vtkSmartPointer<vtkPolyData>::New();
    outcome.output->ShallowCopy(filter->GetOutput());
  }
  catch (const SceneFileError& e)
  {
    outcome.error = e.what();
  }
  return outcome;
}

/// The first array value that is NaN or Inf, as "array[tuple]", or "".
std::string firstNonFinite(vtkPolyData* output)
{
  vtkPointData* data = output->GetPointData();
  for (int a = 0; a < data->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = data->GetArray(a);
    for (vtkIdType i = 0; array && i < array->GetNumberOfValues(); ++i)
    {
      if (!std::isfinite(
            array->GetComponent(i / array->GetNumberOfComponents(), int(i % array->GetNumberOfComponents()))))
      {
        return std::string(array->GetName()) + "[" + std::to_string(i / array->GetNumberOfComponents()) + "]";
      }
    }
  }
  return "";
}

TEST(AcceptedRanges, EveryLightAndEstimatorIsFiniteOrRefusedByField)
{
  const auto sphere = shadelab::testing::exactSphere(12);
  const std::string envmap = shadelab::testing::sourcePath("data/envmaps/venice_sunset_1k.hdr");
  int shaded = 0, refused = 0;
  for (const std::string& light : lightsUnderTest)
  {
    for (const std::string& shininess : { std::string("1"), std::string("1e6"), std::string("1e30"), largest })
    {
      for (const std::string& intensity : { std::string("1"), std::string("1e6"), largest })
      {
        for (const int precision : { vtkAlgorithm::SINGLE_PRECISION, vtkAlgorithm::DOUBLE_PRECISION })
        {
          const std::string scene = R"({ "viewer": { "position": [0, 0, 6], "focal_point": [0, 0, 0] },
            "material": { "kd": 0.7, "ks": 0.3, "shininess": )" +
            shininess + R"( },
            "lights": [ )" +
            replaced(replaced(light, "INTENSITY", intensity), "ENVMAP", envmap) + " ] }";
          SCOPED_TRACE(scene + (precision == vtkAlgorithm::SINGLE_PRECISION ? " in float32" : " in float64"));
          const Outcome outcome = shade(sphere, scene, precision);
          if (!outcome.error.empty())
          {
            // A refusal names the field the user wrote: the light's or the material's.
            EXPECT_NE(outcome.error.find(": /lights/0/intensity: this light alone can reach "), std::string::npos)
              << outcome.error;
            ++refused;
            continue;
          }
          EXPECT_EQ(firstNonFinite(outcome.output), "");
          ++shaded;
        }
      }
    }
  }
  // Shininess 1 to the largest number is shaded everywhere at intensity 1; only intensities
  // whose terms overflow a precision may be refused.
  EXPECT_GE(shaded, int(lightsUnderTest.size()) * 4 * 2);
  std::cout << shaded << " scenes shaded with finite arrays, " << refused << " refused by field\n";
}

TEST(AcceptedRanges, BlackbodiesFromTheLowestToTheHighestTemperatureAreShaded)
{
  // Below about 1900 K a blackbody lies outside sRGB's gamut (negative linear blue): the RGB
  // model takes its nearest colour, luminance 1, instead of refusing a colour nobody wrote.
  const auto sphere = shadelab::testing::exactSphere(12);
  for (const std::string& kelvin : { "500", "1500", "1e6" })
  {
    const std::string scene = R"({ "viewer": { "position": [0, 0, 6] }, "lights": [
      { "type": "point", "position": [0, 0, 3], "spectrum": { "blackbody": )" +
      kelvin + " } } ] }";
    SCOPED_TRACE(kelvin + " K");
    const Outcome outcome = shade(sphere, scene, vtkAlgorithm::DOUBLE_PRECISION);
    ASSERT_EQ(outcome.error, "");
    EXPECT_EQ(firstNonFinite(outcome.output), "");
    double pole[3];
    outcome.output->GetPointData()->GetArray("diffuse")->GetTuple(0, pole);
    EXPECT_GE(std::min({ pole[0], pole[1], pole[2] }), 0.0);
    EXPECT_GT(pole[0], 0.0);
  }
}
}
