#pragma once
// The size and place of a mesh, as its bounding sphere: what the method choice's error bounds
// and the mesh frame of scene files (SceneFrame.h) need to know about it.
#include "Vec3.h"

namespace shadelab
{
struct MeshExtent
{
  glm::dvec3 centre{ 0 }; // of the bounding box
  double radius = 0;      // half the bounding box's diagonal: no vertex is farther from centre
  double reach = 0;       // the largest |coordinate|
};
}
