// The vtk model against what VTK 9.1's OpenGL2 renderer really draws. Each vertex of a sphere
// is rendered as a one-pixel point carrying its normal: the shader then lights it with exactly
// that position and normal, with no interpolation, so the pixel must hold ShadeLab's total,
// clamped to [0, 1] and rounded to 8 bits. Runs under Xvfb (Mesa's software OpenGL).
#include "TestMeshes.h"
#include "VtkLightSets.h"

#include "OffScreenImage.h"

#include "ShadeLabMaterialArrays.h"

#include "vtkActor.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkMatrix4x4.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderer.h"
#include "vtkUnsignedCharArray.h"

#include <cmath>
#include <functional>
#include <map>
#include <random>

namespace
{
using shadelab::testing::litSphereCentre;
using shadelab::testing::litSphereRadius;

constexpr int windowSize = 800;

class RealRender : public shadelab::testing::VtkLightSets
{
protected:
  /// Renders the sphere's vertices as one-pixel points and compares each pixel with the vtk
  /// model's total. With colorBy, the sphere carries the arrays it adds and the scene takes
  /// its material from them; mapWith then sets the mapper's scalar colouring to match.
  void expectPixelsMatch(bool lone, const std::function<void(vtkPolyData*, shadelab::Scene&)>& colorBy = {},
    const std::function<void(vtkPolyDataMapper*)>& mapWith = {})
  {
    const auto [sphere, total] = shadeLitSphere(120, lone, colorBy);
    ASSERT_NE(total, nullptr);

    // The same vertices, normals and arrays as a cloud of vertex cells.
    vtkNew<vtkPolyData> cloud;
    cloud->SetPoints(sphere->GetPoints());
    cloud->GetPointData()->ShallowCopy(sphere->GetPointData());
    vtkNew<vtkCellArray> vertices;
    for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
    {
      vertices->InsertNextCell(1, &i);
    }
    cloud->SetVerts(vertices);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(cloud);
    mapper->SetScalarVisibility(bool(mapWith));
    if (mapWith)
    {
      mapWith(mapper);
    }
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->SetProperty(property);
    vtkNew<vtkRenderer> renderer;
    renderer->AddActor(actor);
    renderer->SetActiveCamera(camera);
    renderer->SetLightCollection(lights);
    renderer->ResetCameraClippingRange();
    vtkSmartPointer<vtkImageData> image = shadelab::app::renderOffScreen(renderer, windowSize, windowSize);
    ASSERT_EQ(image->GetDimensions()[0], windowSize);

    // Where each vertex lands. Only pixels that exactly one vertex lands in, well inside the
    // pixel, on the side facing the camera, are compared: there the pixel is that vertex.
    std::map<std::pair<int, int>, std::vector<vtkIdType>> landings;
    vtkMatrix4x4* projection = camera->GetCompositeProjectionTransformMatrix(1.0, -1, 1);
    std::map<vtkIdType, bool> clearlyInside;
    for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
    {
      double p[3];
      sphere->GetPoint(i, p);
      // Where the vertex lands: the camera's projection (square window, so aspect 1) takes it
      // to normalised device coordinates, whose [-1, 1] spans the window's pixels.
      double h[4] = { p[0], p[1], p[2], 1.0 };
      projection->MultiplyPoint(h, h);
      const double d[2] = { (h[0] / h[3] + 1) * 0.5 * windowSize, (h[1] / h[3] + 1) * 0.5 * windowSize };
      const std::pair<int, int> pixel{ int(std::floor(d[0])), int(std::floor(d[1])) };
      landings[pixel].push_back(i);
      const double fx = d[0] - pixel.first, fy = d[1] - pixel.second;
      double n[3];
      sphere->GetPointData()->GetNormals()->GetTuple(i, n);
      const double* eye = camera->GetPosition();
      const double facing = n[0] * (eye[0] - p[0]) + n[1] * (eye[1] - p[1]) + n[2] * (eye[2] - p[2]);
      clearlyInside[i] = fx > 0.1 && fx < 0.9 && fy > 0.1 && fy < 0.9 && facing > 0.5;
    }
    int compared = 0;
    double worst = 0;
    for (const auto& [pixel, ids] : landings)
    {
      if (ids.size() != 1 || !clearlyInside[ids[0]])
      {
        continue;
      }
      for (int c = 0; c < 3; ++c)
      {
        const double expected = 255.0 * std::clamp(total->GetComponent(ids[0], c), 0.0, 1.0);
        const double drawn = image->GetScalarComponentAsDouble(pixel.first, pixel.second, 0, c);
        worst = std::max(worst, std::abs(drawn - expected));
        // Half a level is the 8-bit rounding itself; 0.001 more covers the shader's float32.
        EXPECT_LE(std::abs(drawn - expected), 0.501)
          << "vertex " << ids[0] << " channel " << c << " at pixel " << pixel.first << ", " << pixel.second;
      }
      ++compared;
    }
    EXPECT_GT(compared, 2000);
    std::cout << "compared " << compared << " vertices with their pixels; largest difference " << worst << "/255\n";
  }
};

TEST_F(RealRender, LoneHeadlight)
{
  addLoneHeadlight();
  expectPixelsMatch(true);
}

TEST_F(RealRender, LightKitOfDirectionalLights)
{
  addLightKit();
  expectPixelsMatch(false);
}

TEST_F(RealRender, SwitchedOffSceneLightStillEndsTheLoneHeadlightShader)
{
  addHeadlightAndSwitchedOffSceneLight();
  expectPixelsMatch(false);
}

TEST_F(RealRender, PositionalSpotAndPointLights)
{
  addPositionalLights();
  expectPixelsMatch(false);
}

/// The material's diffuse and ambient colours from an array, as VTK's mapper colours both with
/// the scalars' colour (times the property's Diffuse and Ambient).
void colorFromArray(shadelab::Scene& scene, const vtkProperty* property, shadelab::ArrayCoefficient source)
{
  using shadelab::MaterialCoefficient;
  source.scale = const_cast<vtkProperty*>(property)->GetDiffuse();
  scene.material.arrays[MaterialCoefficient::Diffuse] = source;
  scene.material.kd = shadelab::Rgb(source.scale);
  source.scale = const_cast<vtkProperty*>(property)->GetAmbient();
  scene.material.arrays[MaterialCoefficient::Ambient] = source;
  scene.material.ka = shadelab::Rgb(source.scale);
}

/// A field over the sphere that sweeps the colour map several times round it.
void addField(vtkPolyData* sphere)
{
  vtkNew<vtkDoubleArray> field;
  field->SetName("field");
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    double p[3];
    sphere->GetPoint(i, p);
    field->InsertNextValue(std::sin(3 * p[0]) + p[1] * p[2]);
  }
  sphere->GetPointData()->AddArray(field);
}

constexpr std::array<double, 2> fieldRange{ -0.8, 1.1 }; // inside the field's: both ends clamp

TEST_F(RealRender, FieldThroughTheMappersDefaultLookupTable)
{
  addLightKit();
  expectPixelsMatch(
    false,
    [&](vtkPolyData* sphere, shadelab::Scene& scene)
    {
      addField(sphere);
      colorFromArray(scene, property, { "field", {}, 1.0, "rainbow", fieldRange });
    },
    [](vtkPolyDataMapper* mapper)
    {
      // The mapper's own lookup table (a default vtkLookupTable), only its range set.
      mapper->SetScalarModeToUsePointFieldData();
      mapper->SelectColorArray("field");
      mapper->SetScalarRange(fieldRange[0], fieldRange[1]);
    });
}

TEST_F(RealRender, FieldThroughAColorTransferFunction)
{
  addPositionalLights();
  expectPixelsMatch(
    false,
    [&](vtkPolyData* sphere, shadelab::Scene& scene)
    {
      addField(sphere);
      colorFromArray(scene, property, { "field", {}, 1.0, "cool to warm", fieldRange });
    },
    [](vtkPolyDataMapper* mapper)
    {
      mapper->SetScalarModeToUsePointFieldData();
      mapper->SelectColorArray("field");
      mapper->SetLookupTable(shadelab::namedColorMap("cool to warm", fieldRange));
      mapper->UseLookupTableScalarRangeOn();
    });
}

TEST_F(RealRender, DirectEightBitColors)
{
  addLoneHeadlight();
  expectPixelsMatch(
    true,
    [&](vtkPolyData* sphere, shadelab::Scene& scene)
    {
      std::mt19937 random(7);
      vtkNew<vtkUnsignedCharArray> colors;
      colors->SetName("Colors");
      colors->SetNumberOfComponents(3);
      for (vtkIdType i = 0; i < 3 * sphere->GetNumberOfPoints(); ++i)
      {
        colors->InsertNextValue(static_cast<unsigned char>(random() % 256));
      }
      sphere->GetPointData()->AddArray(colors);
      colorFromArray(scene, property, { "Colors" });
    },
    [](vtkPolyDataMapper* mapper)
    {
      mapper->SetScalarModeToUsePointFieldData();
      mapper->SelectColorArray("Colors");
      mapper->SetColorModeToDirectScalars();
    });
}
}
