#ifndef ShadeLabMeshExtent_h
#define ShadeLabMeshExtent_h
// The extent of a VTK mesh as the core describes it (MeshExtent.h): what scenes in the mesh
// frame are placed by, and what the tolerance's error bounds are measured against.
#include "ShadeLabFiltersModule.h"

#include "MeshExtent.h"

class vtkPolyData;

namespace shadelab
{
/// The bounding box's centre and half diagonal, and the largest |coordinate|, over the finite
/// points (NaN and Inf points are flagged by shading, not refused). The mesh has points.
SHADELABFILTERS_EXPORT MeshExtent meshExtentOf(vtkPolyData* mesh);
}

#endif
