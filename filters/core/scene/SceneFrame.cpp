#include "SceneFrame.h"

namespace shadelab
{
Scene placedOnMesh(const Scene& scene, const MeshExtent& extent)
{
  Scene placed = scene;
  if (scene.frame == SceneFrame::World)
  {
    return placed;
  }
  const MeshPlacement placement{ extent.centre, extent.radius > 0 ? extent.radius : 1.0 };
  Viewer& viewer = placed.viewer;
  if (viewer.position)
  {
    viewer.position = placement.point(*viewer.position);
  }
  if (viewer.focalPoint)
  {
    viewer.focalPoint = placement.point(*viewer.focalPoint);
  }
  for (NamedLight& light : placed.lights)
  {
    placeOnMesh(light.source, placement);
  }
  if (placed.ambientOcclusion)
  {
    placed.ambientOcclusion->maxDistance *= placement.radius; // infinity stays infinite
  }
  placed.frame = SceneFrame::World;
  return placed;
}
}
