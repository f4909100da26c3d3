#pragma once
// What vtkLocalReflectanceFilter's checks before shading settle, for the steps that write:
// shared by the filter's source files (the pipeline's, the tolerance's).
#include "vtkLocalReflectanceFilter.h"

#include "ArrayCatalog.h"
#include "MeshExtent.h"
#include "Scene.h"

#include <vector>

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
