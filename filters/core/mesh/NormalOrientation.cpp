#include "NormalOrientation.h"

#include <glm/geometric.hpp>

namespace shadelab
{
void NormalOrientationAccumulator::addTriangle(const glm::dvec3& p0, const glm::dvec3& p1, const glm::dvec3& p2,
  const glm::dvec3& n0, const glm::dvec3& n1, const glm::dvec3& n2)
{
  const double area = 0.5 * glm::length(glm::cross(p1 - p0, p2 - p0));
  const glm::dvec3 normalSum = n0 + n1 + n2;
  const double normalLength = glm::length(normalSum);
  if (!(area > 0.0) || !(normalLength > 0.0))
  {
    return;
  }
  add(area * (normalSum / normalLength), area, (p0 + p1 + p2) / 3.0);
}

NormalOrientation NormalOrientationAccumulator::result() const
{
  NormalOrientation result;
  if (area_ > 0.0)
  {
    result.closure = glm::length(vectorArea_) / area_;
    result.flux = flux_;
  }
  return result;
}
}
