#pragma once
// vtkLocalReflectanceFilter's state besides its settings, and the types its steps pass each
// other: shared by the filter's source files (the pipeline's, the tolerance's).
#include "vtkLocalReflectanceFilter.h"

#include "ArrayCatalog.h"
#include "MaterialArrays.h"
#include "MeshExtent.h"
#include "Scene.h"
#include "SceneSource.h"

#include "vtkDataArray.h"
#include "vtkInterreflectionFilter.h"
#include "vtkMeshVisibilityFilter.h"
#include "vtkNew.h"
#include "vtkShadingNormalsFilter.h"
#include "vtkSmartPointer.h"

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

namespace shadelab
{
/// Per scene light, the least distance from it to any of the points, for the lights with a
/// position (+infinity for the others, and where `points` is nullptr: a piece without any), for
/// a tolerance's bounds. With processes (a split mesh), the least over every piece: a
/// collective call.
std::vector<double> nearestPointDistances(
  const Scene& scene, vtkDataArray* points, vtkMultiProcessController* processes);
}

/// What the checks before shading settle, for the steps that write.
struct vtkLocalReflectanceFilter::ShadingPlan
{
  shadelab::MeshExtent extent; // the whole mesh's, on a split mesh
  shadelab::Scene scene;       // placed on the mesh
  shadelab::ArrayRequest request;
  std::vector<shadelab::LightMethod> methods;
  shadelab::Precision precision = shadelab::Precision::Float32;
  bool float32Fits = true;             // the mesh's coordinates and the scene's values fit float32
  shadelab::MeshMeasurements measured; // under a tolerance, for its plan's bounds
};

/// What a run's sampling to targets leaves besides its arrays (for its report and plan).
struct vtkLocalReflectanceFilter::SamplingOutcome
{
  /// Per scene light drawn to a target (empty for the others), 1 at each vertex that stopped
  /// at the maximum short of it.
  std::vector<std::vector<std::uint8_t>> shortOfTarget;
  /// Where the plan samples, sized for every point: each one's sampled standard error
  /// (shadelab::ShadingOutputs::sampledStandardError); empty elsewhere.
  std::vector<double> standardError;
  /// Where a forecast was made, sized for every point: each one's count of samples, to set
  /// against the forecast; empty elsewhere.
  std::vector<std::uint32_t> samplesDrawn;
};

/// What the material last read was read from, to know when to read it again.
struct vtkLocalReflectanceFilter::MaterialSource
{
  shadelab::MaterialArrays sources;
  shadelab::ShadingModel model = shadelab::ShadingModel::Lecture;
  shadelab::Precision storage = shadelab::Precision::Float64; // float32: what the float32 kernel alone reads
  vtkIdType points = 0;
  std::vector<std::pair<vtkDataArray*, vtkMTimeType>> arrays; // each array read, and its time then
  bool operator==(const MaterialSource& other) const;
};

/// The points a tolerance's bounds are measured on, with their normals and their ids in the
/// whole mesh.
struct vtkLocalReflectanceFilter::PointSample
{
  vtkSmartPointer<vtkDataArray> points, normals; // nullptr where the piece has none
  std::vector<long long> ids;
};

struct vtkLocalReflectanceFilter::vtkInternals
{
  /// The step that prepares the normals to shade with (the input's own, checked, or computed),
  /// run as a pipeline of its own: it runs again only when the input or its settings have
  /// changed since it last ran (their modification times), since preparing normals costs more
  /// than shading does.
  vtkNew<vtkShadingNormalsFilter> NormalsStep;
  /// The step that casts rays for the scene's shadows and ambient occlusion, on the input with
  /// the normals to shade with.
  vtkNew<vtkMeshVisibilityFilter> VisibilityStep;
  /// The step that gathers the light the mesh reflects onto itself, from the shaded direct
  /// diffuse term, for the scene's interreflection.
  vtkNew<vtkInterreflectionFilter> InterreflectionStep;

  /// AvailableArrays' modification time when RequestInformation last filled it: a later one
  /// is a user's choice.
  vtkMTimeType AvailableArraysFilledAt = 0;
  bool FillingAvailableArrays = false;
  /// Whether ArraySelection holds names ticked in AvailableArrays (rather than set by its setters).
  bool SelectionFromList = false;
  /// The scene as RequestInformation read it, for RequestData: a scene file (and its
  /// environment maps) is read once per update.
  shadelab::SceneReading SceneOfThisUpdate;

  /// The last material read from the mesh's arrays, and what it was read from.
  shadelab::VertexMaterial VertexMaterial;
  std::optional<MaterialSource> VertexMaterialSource;

  /// The current step's share of the run's progress.
  double ProgressStart = 0, ProgressSpan = 0;
  /// Whether an abort stops the run: on a whole mesh only, as a split mesh's processes must all
  /// take part in its exchanges.
  bool Stoppable = true;
};
