#include "RenderImage.h"

#include "MaterialArrays.h"
#include "MeshFiles.h"
#include "OffScreenImage.h"
#include "VtkErrorCapture.h"

#include "vtkActor.h"
#include "vtkCamera.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPolyDataMapper.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkScalarBarActor.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace shadelab::app
{
namespace
{
std::string arrayNames(vtkPointData* pointData)
{
  std::string names;
  for (int a = 0; a < pointData->GetNumberOfArrays(); ++a)
  {
    names += (a ? ", " : "") + std::string(pointData->GetArrayName(a) ? pointData->GetArrayName(a) : "");
  }
  return names.empty() ? "no point arrays (shade it first: shadelab shade)" : names;
}

/// A view-up vector not parallel to the line of sight.
glm::dvec3 viewUpFor(const glm::dvec3& sight)
{
  return std::abs(sight.y) > 0.99 ? glm::dvec3(0, 0, -1) : glm::dvec3(0, 1, 0);
}

/// RGB in [0, 1] to 8-bit colours, so that the mapper draws them as they are; sRGB-encoded
/// where srgb.
vtkSmartPointer<vtkUnsignedCharArray> directColours(vtkDataArray* rgb, bool srgb)
{
  auto colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colours->SetName("colours");
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(rgb->GetNumberOfTuples());
  for (vtkIdType i = 0; i < rgb->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      const double linear = std::clamp(rgb->GetComponent(i, c), 0.0, 1.0);
      const double value = srgb ? linearToSrgb(linear) : linear;
      colours->SetValue(3 * i + c, static_cast<unsigned char>(std::lround(255.0 * value)));
    }
  }
  return colours;
}

void placeCamera(vtkRenderer* renderer, vtkPolyData* mesh, const std::optional<Viewer>& viewer)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  double centre[3];
  mesh->GetCenter(centre);
  if (viewer && viewer->position)
  {
    const glm::dvec3 eye = *viewer->position;
    const glm::dvec3 target = viewer->focalPoint.value_or(glm::dvec3(centre[0], centre[1], centre[2]));
    camera->SetPosition(eye.x, eye.y, eye.z);
    camera->SetFocalPoint(target.x, target.y, target.z);
    const glm::dvec3 up = viewUpFor(unitVector(target - eye));
    camera->SetViewUp(up.x, up.y, up.z);
    renderer->ResetCameraClippingRange();
    return;
  }
  // A viewer at infinity (or none): a parallel projection along its direction.
  const glm::dvec3 sight = viewer ? unitVector(viewer->viewDirection) : glm::dvec3(0, 0, -1);
  camera->ParallelProjectionOn();
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0] - sight.x, centre[1] - sight.y, centre[2] - sight.z);
  const glm::dvec3 up = viewUpFor(sight);
  camera->SetViewUp(up.x, up.y, up.z);
  renderer->ResetCamera();
}
}

void renderToPng(vtkPolyData* mesh, const std::string& meshName, const RenderOptions& options,
  const std::string& pngFile)
{
  checkOutputFile(pngFile, { ".png" });
  requireDisplay();
  vtkDataArray* array = mesh->GetPointData()->GetArray(options.array.c_str());
  if (!array)
  {
    throw UserError(meshName + ": has no point array '" + options.array + "'; it has: " +
      arrayNames(mesh->GetPointData()));
  }
  const int components = array->GetNumberOfComponents();
  if (components != 1 && components != 3)
  {
    throw UserError(meshName + ": array '" + options.array + "' has " + std::to_string(components) +
      " components; render draws 1 (colour-mapped) or 3 (RGB)");
  }

  auto coloured = vtkSmartPointer<vtkPolyData>::New();
  coloured->CopyStructure(mesh);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(coloured);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(0.16, 0.17, 0.2);
  if (components == 3)
  {
    coloured->GetPointData()->SetScalars(directColours(array, options.srgb));
    mapper->SetColorModeToDirectScalars();
  }
  else
  {
    coloured->GetPointData()->SetScalars(array);
    double range[2];
    array->GetRange(range);
    if (range[0] == range[1])
    {
      // A constant array: a range around it, so the map and its bar stay readable.
      const double half = range[0] == 0 ? 1.0 : 0.5 * std::abs(range[0]);
      range[0] -= half;
      range[1] += half;
    }
    if (range[0] < 0 && range[1] > 0)
    {
      // Signed data (n.s, r.v): centre the diverging map on zero, so white means zero.
      range[1] = std::max(-range[0], range[1]);
      range[0] = -range[1];
    }
    // Moreland's cool-to-warm diverging map (Moreland 2009, "Diverging Color Maps for
    // Scientific Visualization"), the map ParaView uses by default.
    vtkNew<vtkColorTransferFunction> colourMap;
    colourMap->SetColorSpaceToDiverging();
    colourMap->AddRGBPoint(range[0], 0.230, 0.299, 0.754);
    colourMap->AddRGBPoint(range[1], 0.706, 0.016, 0.150);
    mapper->SetLookupTable(colourMap);
    mapper->SetScalarRange(range);
    vtkNew<vtkScalarBarActor> bar;
    bar->SetLookupTable(colourMap);
    bar->SetNumberOfLabels(5);
    bar->SetLabelFormat("%.3g");
    bar->SetWidth(0.1);
    bar->UnconstrainedFontSizeOn();
    bar->GetTitleTextProperty()->SetFontSize(16);
    bar->GetLabelTextProperty()->SetFontSize(14);
    renderer->AddViewProp(bar);
    // The array's name at the top left: a bar's own title, centred on a bar at the right
    // edge, runs off the picture.
    vtkNew<vtkTextActor> title;
    title->SetInput(options.array.c_str());
    title->GetTextProperty()->SetFontSize(16);
    title->GetTextProperty()->BoldOn();
    title->GetTextProperty()->SetVerticalJustificationToTop();
    title->GetPositionCoordinate()->SetCoordinateSystemToNormalizedViewport();
    title->SetPosition(0.02, 0.97);
    renderer->AddViewProp(title);
  }
  mapper->ScalarVisibilityOn();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->LightingOff(); // the colours are the shading
  renderer->AddActor(actor);
  placeCamera(renderer, mesh, options.viewer);

  vtkSmartPointer<vtkImageData> image = renderOffScreen(renderer, options.width, options.height);

  writeThroughTemporary(pngFile,
    [&](const std::string& temporary) -> std::string
    {
      vtkNew<VtkErrorCapture> errors;
      vtkNew<vtkPNGWriter> writer;
      errors->watch(writer);
      writer->SetInputData(image);
      writer->SetFileName(temporary.c_str());
      writer->Write();
      return errors->failed() ? errors->message() : "";
    });
}
}
