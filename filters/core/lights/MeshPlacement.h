#pragma once
// A scene written in the mesh's frame (scene/SceneFrame.h) is placed on the mesh by each light
// type's placeOn: positions p become c + R p, lengths scale by R.
#include "Vec3.h"

namespace shadelab
{
struct MeshPlacement
{
  glm::dvec3 centre{ 0.0 }; // c, the mesh's bounding-box centre
  double radius = 1.0;      // R, its bounding sphere's radius about c

  glm::dvec3 point(const glm::dvec3& p) const { return centre + radius * p; }
};
}
