#ifndef ShadeLabMeshExtent_h
#define ShadeLabMeshExtent_h
// The extent of a VTK mesh as the core describes it (MeshExtent.h): what scenes in the mesh
// frame are placed by, and what the tolerance's error bounds are measured against.
#include "ShadeLabFiltersModule.h"

#include "MeshExtent.h"

class vtkPolyData;

namespace shadelab
{
/// A bounding box, corner to corner.
struct PointBox
{
  glm::dvec3 low, high;
};

/// The bounding box of the finite points (NaN and Inf points are flagged by shading, not
/// refused); with none, VTK's empty range in each coordinate. The mesh has points.
SHADELABFILTERS_EXPORT PointBox finitePointBox(vtkPolyData* mesh);

/// The box's centre and half diagonal, and the largest |coordinate| of its corners.
SHADELABFILTERS_EXPORT MeshExtent extentOfBox(const PointBox& box);

/// The extent of the mesh's finite points. The mesh has points.
SHADELABFILTERS_EXPORT MeshExtent meshExtentOf(vtkPolyData* mesh);
}

#endif
