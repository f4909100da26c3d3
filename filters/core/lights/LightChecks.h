#pragma once
// Checking a scene's values: each problem is a JSON pointer into the scene file's layout and
// what is wrong there. The scene's checks (scene/Scene.h) and each light type's own use these.
#include "Material.h"
#include "Precision.h"
#include "SampleSequence.h"
#include "Vec3.h"

#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace shadelab
{
/// One thing wrong with a scene: where (such as "/lights/2/min_distance") and what.
struct SceneProblem
{
  std::string path;
  std::string message;
};

class ProblemList
{
public:
  void check(bool ok, const std::string& path, const std::string& message)
  {
    if (!ok)
    {
      problems.push_back({ path, message });
    }
  }
  std::vector<SceneProblem> problems;
};

inline bool isNonNegative(const glm::dvec3& v)
{
  return isFinite(v) && v.x >= 0 && v.y >= 0 && v.z >= 0;
}

inline bool isNonNegative(double x)
{
  return std::isfinite(x) && x >= 0;
}

inline bool isNonZero(const glm::dvec3& v)
{
  return isFinite(v) && largestComponent(v) > 0;
}

inline bool isWithin(const glm::dvec3& point, double limit)
{
  return isFinite(point) && largestComponent(point) <= limit;
}

/// What a point out of the precision's range is told.
std::string outOfRange(Precision precision);

/// One light's checks: what they may ask of the scene around the light, and where the
/// problems they find go. A field is a path below the light's, such as "/min_distance".
class LightChecks
{
public:
  LightChecks(
    std::string at, ShadingModel model, std::optional<glm::dvec3> lineOfSight, Precision precision, ProblemList& list)
    : model(model)
    , lineOfSight(lineOfSight)
    , precision(precision)
    , at_(std::move(at))
    , list_(list)
  {
  }

  /// Records message at the light's field when ok is false.
  void require(bool ok, const std::string& field, const std::string& message) { list_.check(ok, at_ + field, message); }

  /// Colour components and intensity >= 0.
  void strength(const Rgb& color, double intensity);
  /// A point within the precision's coordinate range.
  void point(const glm::dvec3& p, const std::string& field);
  /// A direction: non-zero and finite.
  void direction(const glm::dvec3& v, const std::string& field);
  /// Area lights and environment maps: the lecture model, and a sample count in range.
  void distributed(const Sampling& sampling);

  const ShadingModel model;
  const std::optional<glm::dvec3> lineOfSight; // the viewer's
  const Precision precision;

private:
  std::string at_;
  ProblemList& list_;
};
}
