#pragma once
// Running vtkLocalReflectanceFilter once in a test, for the output alone.
#include "Scene.h"
#include "VtkErrorCapture.h"
#include "vtkLocalReflectanceFilter.h"

#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <string>
#include <vector>

namespace shadelab::testing
{
/// The filter's output for `mesh` under `scene` with these arrays, in this precision, as a copy
/// that outlives the filter.
inline vtkSmartPointer<vtkPolyData> shadeWithFilter(vtkPolyData* mesh, const Scene& scene,
  const std::vector<std::string>& arrays, int precision = vtkAlgorithm::DOUBLE_PRECISION, bool orientOutward = true)
{
  vtkNew<vtkLocalReflectanceFilter> filter;
  filter->SetInputData(mesh);
  filter->SetScene(scene);
  filter->SetArraySelection(arrays);
  filter->SetOutputPrecision(precision);
  filter->SetOrientNormalsOutward(orientOutward);
  filter->Update();
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->ShallowCopy(filter->GetOutput());
  return output;
}

/// The lines of the tolerance's plan that the filter wrote in the output's field data
/// (shadelab_methods); none without a tolerance.
inline std::vector<std::string> methodsNote(vtkPolyData* output)
{
  std::vector<std::string> lines;
  auto* note = vtkStringArray::SafeDownCast(output->GetFieldData()->GetAbstractArray("shadelab_methods"));
  for (vtkIdType i = 0; note && i < note->GetNumberOfValues(); ++i)
  {
    lines.push_back(note->GetValue(i));
  }
  return lines;
}

/// The filter's error for `mesh` under `scene` at this tolerance ("" where it shades).
inline std::string filterError(vtkPolyData* mesh, const Scene& scene, double tolerance = 0)
{
  vtkNew<vtkLocalReflectanceFilter> filter;
  vtkNew<app::VtkErrorCapture> errors;
  errors->watch(filter);
  filter->SetInputData(mesh);
  filter->SetScene(scene);
  filter->SetTolerance(tolerance);
  filter->Update();
  return errors->message();
}

/// A run under a tolerance on this many threads: the output (a copy), the plan and the
/// filter's sampling report.
struct ToleranceRun
{
  vtkSmartPointer<vtkPolyData> output;
  MethodPlan plan;
  std::vector<std::string> samplingReport;
};

inline ToleranceRun shadeToTolerance(vtkPolyData* mesh, const Scene& scene, double tolerance, int threads)
{
  vtkNew<vtkLocalReflectanceFilter> filter;
  filter->SetInputData(mesh);
  filter->SetScene(scene);
  filter->SetArraySelection({ "all" });
  filter->SetTolerance(tolerance);
  vtkSMPTools::LocalScope(vtkSMPTools::Config{ threads }, [&] { filter->Update(); });
  ToleranceRun run{ vtkSmartPointer<vtkPolyData>::New(), *filter->GetMethodPlan(), filter->GetSamplingReport() };
  run.output->ShallowCopy(filter->GetOutput());
  return run;
}
}
