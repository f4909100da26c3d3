#include "NormalOrientation.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cstdint>

namespace shadelab
{
namespace
{
/// 2^exponent, the exponent kept where a double holds it.
double powerOfTwo(int exponent)
{
  return std::ldexp(1.0, std::clamp(exponent, -1000, 1000));
}
}

NormalOrientationAccumulator::NormalOrientationAccumulator(const glm::dvec3& centre, double radius)
  : centre_(centre)
{
  // radius < 2^k. A polygon within the radius that does not overlap itself has a vector area
  // below pi r^2 < 2^(2k + 2) and a flux term below pi r^3 < 2^(3k + 2): both scaled below 2^59.
  // Larger terms (a polygon wound round several times) make the sums unrepresentable: no
  // orientation, as for a coordinate that is not finite. The exponents are kept within a
  // double's: a mesh smaller than 1e-99 or larger than 1e+99 loses its sums' low bits.
  int k = 0;
  std::frexp(std::isfinite(radius) ? radius : 0.0, &k);
  areaScale_ = powerOfTwo(57 - 2 * k);
  fluxScale_ = powerOfTwo(57 - 3 * k);
}

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

void NormalOrientationAccumulator::add(const NormalOrientationAccumulator& other)
{
  addWords(other.words().data());
}

std::vector<long long> NormalOrientationAccumulator::words() const
{
  std::vector<long long> words;
  for (const FixedSum& sum : { vectorArea_[0], vectorArea_[1], vectorArea_[2], area_, flux_ })
  {
    words.push_back(static_cast<long long>(sum >> 64));
    words.push_back(static_cast<long long>(static_cast<std::uint64_t>(sum)));
  }
  words.push_back(representable_ ? 1 : 0);
  return words;
}

void NormalOrientationAccumulator::addWords(const long long* words)
{
  FixedSum* sums[] = { &vectorArea_[0], &vectorArea_[1], &vectorArea_[2], &area_, &flux_ };
  for (std::size_t s = 0; s < 5; ++s)
  {
    const FixedSum high = static_cast<FixedSum>(words[2 * s]) * (static_cast<FixedSum>(1) << 64);
    *sums[s] += high + static_cast<FixedSum>(static_cast<std::uint64_t>(words[2 * s + 1]));
  }
  representable_ = representable_ && words[10] != 0;
}

NormalOrientation NormalOrientationAccumulator::result() const
{
  NormalOrientation result;
  const double area = static_cast<double>(area_) / areaScale_;
  if (representable_ && area > 0.0)
  {
    const glm::dvec3 vectorArea(
      static_cast<double>(vectorArea_[0]), static_cast<double>(vectorArea_[1]), static_cast<double>(vectorArea_[2]));
    result.closure = glm::length(vectorArea / areaScale_) / area;
    result.flux = static_cast<double>(flux_) / fluxScale_;
  }
  return result;
}
}
