// vtkTransferRelightFilter on hand-made transfer arrays: the irradiance is the dot product of
// the map's world-axis coefficients with each vector, in the precision of the transfer, and
// every input array passes through untouched.
#include "EnvironmentLightEstimator.h"
#include "EnvironmentMap.h"
#include "RadianceTransfer.h"
#include "TestPaths.h"
#include "VtkErrorCapture.h"
#include "vtkTransferRelightFilter.h"

#include "vtkDoubleArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <gtest/gtest.h>

#include <limits>
#include <memory>

namespace
{
using namespace shadelab;
const std::string sunset = shadelab::testing::sourcePath("data/envmaps/venice_sunset_1k.hdr");

/// Three points whose transfer is the unshadowed one of three normals, at order 3.
vtkSmartPointer<vtkPolyData> meshWithTransfer(vtkDataArray* transfer, const std::vector<glm::dvec3>& normals)
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  transfer->SetName("sky_sh_transfer");
  transfer->SetNumberOfComponents(shCount(3));
  for (const glm::dvec3& n : normals)
  {
    points->InsertNextPoint(n.x, n.y, n.z);
    const TransferVector t = unshadowedTransfer(3, n);
    transfer->InsertNextTuple(t.data());
  }
  mesh->SetPoints(points);
  mesh->GetPointData()->AddArray(transfer);
  return mesh;
}

TEST(TransferRelight, TheDotProductOfTheTurnedMapWithEachVectorInTheTransfersPrecision)
{
  const std::vector<glm::dvec3> normals = { { 0, 1, 0 }, { 0.6, 0, 0.8 }, { 0, -1, 0 } };
  vtkNew<vtkDoubleArray> transfer;
  const vtkSmartPointer<vtkPolyData> mesh = meshWithTransfer(transfer, normals);
  vtkNew<vtkTransferRelightFilter> relight;
  relight->SetInputData(mesh);
  relight->SetEnvironmentMapFileName(sunset);
  relight->SetRotation(120);
  relight->SetIntensity(0.5);
  relight->SetColor(1, 0.5, 0.25);
  relight->Update();
  vtkDataArray* irradiance = relight->GetOutput()->GetPointData()->GetArray("relit_irradiance");
  ASSERT_NE(irradiance, nullptr);
  EXPECT_EQ(irradiance->GetDataType(), VTK_DOUBLE);
  EXPECT_EQ(relight->GetOutput()->GetPointData()->GetArray("sky_sh_transfer"), transfer.GetPointer());
  EnvironmentLight light;
  light.map = std::make_shared<const EnvironmentMap>(readEnvironmentMap(sunset));
  light.rotationDegrees = 120;
  light.intensity = 0.5;
  light.color = Rgb(1, 0.5, 0.25);
  const ShCoefficients radiance = worldRadianceCoefficients(light, 3);
  for (std::size_t i = 0; i < normals.size(); ++i)
  {
    const Rgb expected = irradianceFromTransfer(radiance, unshadowedTransfer(3, normals[i]));
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_EQ(irradiance->GetComponent(vtkIdType(i), c), expected[c]) << i << " " << c;
    }
  }
  EXPECT_EQ(
    relight->GetReport(), "'relit_irradiance' from 'sky_sh_transfer' (order 3, 16 coefficients) under " + sunset);
}

TEST(TransferRelight, AnIntegerTransferGivesARealIrradianceAndBadPropertiesAreRefused)
{
  vtkNew<vtkIntArray> transfer;
  const vtkSmartPointer<vtkPolyData> mesh = meshWithTransfer(transfer, { { 0, 1, 0 } });
  vtkNew<vtkTransferRelightFilter> relight;
  relight->SetInputData(mesh);
  relight->SetEnvironmentMapFileName(sunset);
  relight->Update();
  EXPECT_EQ(relight->GetOutput()->GetPointData()->GetArray("relit_irradiance")->GetDataType(), VTK_FLOAT);

  vtkNew<shadelab::app::VtkErrorCapture> errors;
  errors->watch(relight);
  relight->SetColor(1, -1, 1);
  relight->Update();
  EXPECT_EQ(errors->message(), "Color's components must be finite numbers >= 0");
  vtkNew<shadelab::app::VtkErrorCapture> rotation;
  rotation->watch(relight);
  relight->SetColor(1, 1, 1);
  relight->SetRotation(std::numeric_limits<double>::infinity());
  relight->Update();
  EXPECT_EQ(rotation->message(), "Rotation must be a finite angle in degrees");
}
}
