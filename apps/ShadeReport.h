#pragma once
// What `shadelab shade` prints after a run: what was shaded and how, the arrays and their
// ranges, the flags, the time. On a mesh split over the run's processes (RunProcesses.h) the
// numbers are the whole mesh's, each point counted once.
#include "PlanBeforeRun.h"
#include "ProgressLine.h"
#include "ShadeCommand.h"
#include "VtkErrorCapture.h"

#include "Scene.h"
#include "vtkLocalReflectanceFilter.h"
#include "vtkShadingNormalsFilter.h"

#include "vtkNew.h"

#include <string>
#include <vector>

namespace shadelab::app
{
/// The filters of one run, kept for its report.
struct ShadingPipeline
{
  vtkNew<vtkShadingNormalsFilter> splitter; // --split-sharp-edges: a step of its own, before shading
  vtkNew<vtkLocalReflectanceFilter> filter;
  vtkNew<VtkErrorCapture> errors;
  vtkNew<ProgressLine> progress;
  vtkNew<PlanBeforeRun> planBeforeRun;
};

/// How long the run's stages took, in seconds.
struct StageSeconds
{
  double read = 0, shade = 0, write = 0;
};

/// What the report says of the run beside its filters: what the mesh file held that the reader
/// skipped ("" when nothing), where the scene came from, and the stages' times.
struct RunFacts
{
  std::string ignored;
  std::string sceneOrigin;
  StageSeconds seconds;
};

/// The names of every array the scene can add to the mesh.
std::vector<std::string> arrayNamesOf(const Scene& scene, const std::string& prefix);

/// Prints the run's report. Every process of the run calls it alike (a collective call: the
/// whole mesh's counts and ranges are reduced over them); the first prints it.
void printReport(
  const ShadingPipeline& pipeline, const Scene& scene, const RunFacts& facts, const ShadeOptions& options);
}
