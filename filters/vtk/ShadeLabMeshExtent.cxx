#include "ShadeLabMeshExtent.h"

#include "Vec3.h"

#include "vtkDataArray.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>

namespace shadelab
{
PointBox finitePointBox(vtkPolyData* mesh)
{
  double range[3][2];
  for (int c = 0; c < 3; ++c)
  {
    mesh->GetPoints()->GetData()->GetFiniteRange(range[c], c);
  }
  return { glm::dvec3(range[0][0], range[1][0], range[2][0]), glm::dvec3(range[0][1], range[1][1], range[2][1]) };
}

MeshExtent extentOfBox(const PointBox& box)
{
  MeshExtent extent;
  extent.centre = 0.5 * (box.low + box.high);
  extent.radius = 0.5 * vectorLength(box.high - box.low);
  extent.reach = std::max(largestComponent(box.low), largestComponent(box.high));
  return extent;
}

MeshExtent meshExtentOf(vtkPolyData* mesh)
{
  return extentOfBox(finitePointBox(mesh));
}
}
