#include "LightChecks.h"

namespace shadelab
{
std::string outOfRange(Precision precision)
{
  return std::string("must be a finite point with coordinates within +-") + scientific(coordinateLimit(precision)) +
    " for " + precisionName(precision) + " arithmetic";
}

void LightChecks::strength(const Rgb& color, double intensity)
{
  require(isNonNegative(color), "/color", "components must be numbers >= 0");
  require(isNonNegative(intensity), "/intensity", "must be a number >= 0");
}

void LightChecks::point(const glm::dvec3& p, const std::string& field)
{
  require(isWithin(p, coordinateLimit(precision)), field, outOfRange(precision));
}

void LightChecks::direction(const glm::dvec3& v, const std::string& field)
{
  require(isNonZero(v), field, "must be a non-zero vector");
}

void LightChecks::distributed(const Sampling& sampling)
{
  require(!reproducesVtkRenderer(model), "/type",
    model == ShadingModel::VtkPbr
      ? "the vtk_pbr model has VTK's punctual lights only (its image-based lighting is not reproduced): use the "
        "lecture model"
      : "VTK's renderer has no area lights or environment maps: use the lecture model");
  require(sampling.samples >= 2 && sampling.samples <= maxSamplesPerVertex, "/samples",
    "must be a whole number from 2 to " + std::to_string(maxSamplesPerVertex));
}
}
