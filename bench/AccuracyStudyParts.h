#pragma once
// What the accuracy studies (AccuracyStudies.cxx, DistributedStudies.cxx) share: a row of
// accuracy.csv, the filter run for one method, and the charts' colours.
#include "MethodChoice.h"
#include "Scene.h"
#include "ShadingKernel.h"

#include "vtkDataArray.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace shadelab::app
{
/// One measured method: a row of accuracy.csv. The errors are empty for a timing alone.
struct AccuracyRow
{
  std::string study, method, parameter;
  double value = 0; // the parameter's value (eta, distance / radius, ...)
  long long vertices = 0;
  std::optional<double> milliseconds;
  std::optional<double> maxError, rmsError;
  std::optional<double> predicted;
  std::string note;
};

/// The output of a filter set up for one method, and its time per run (median).
struct MethodRun
{
  vtkSmartPointer<vtkPolyData> output;
  double milliseconds = 0;
};

/// Runs the filter on the mesh computing `arrays`, at least minRepeats times and more up to
/// maxRepeats while the runs fit in about two seconds. Preparing the normals is not timed.
MethodRun runMethod(vtkPolyData* mesh, const Scene& scene, const std::vector<std::string>& arrays, Precision precision,
  const std::vector<LightMethod>& methods, int maxRepeats, int minRepeats = 3);

vtkDataArray* arrayOf(const MethodRun& run, const std::string& name);

inline const std::array<unsigned char, 3> palette[] = { { 31, 119, 180 }, { 255, 127, 14 }, { 44, 160, 44 },
  { 214, 39, 40 }, { 148, 103, 189 }, { 140, 86, 75 }, { 227, 119, 194 }, { 127, 127, 127 } };

/// Kernel outputs that ask for one total of the scene, into `values` (3 per vertex), and nothing else.
template<typename T>
ShadingOutputs<T> oneTotal(const Scene& scene, TotalTerm term, T* values)
{
  ShadingOutputs<T> outputs;
  outputs.lights.resize(scene.lights.size()); // every per-light pointer null
  outputs.totals[int(term)] = values;
  return outputs;
}
}
