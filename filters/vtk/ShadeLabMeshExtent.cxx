#include "ShadeLabMeshExtent.h"

#include "Vec3.h"

#include "vtkDataArray.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <algorithm>

namespace shadelab
{
MeshExtent meshExtentOf(vtkPolyData* mesh)
{
  double range[3][2];
  for (int c = 0; c < 3; ++c)
  {
    mesh->GetPoints()->GetData()->GetFiniteRange(range[c], c);
  }
  MeshExtent extent;
  const glm::dvec3 low(range[0][0], range[1][0], range[2][0]);
  const glm::dvec3 high(range[0][1], range[1][1], range[2][1]);
  extent.centre = 0.5 * (low + high);
  extent.radius = 0.5 * vectorLength(high - low);
  extent.reach = std::max(largestComponent(low), largestComponent(high));
  return extent;
}
}
