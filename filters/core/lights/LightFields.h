#pragma once
// Scene-file fields that several light types share, read through JsonNode.
#include "JsonNode.h"
#include "SampleSequence.h"

#include <string>

namespace shadelab
{
/// "color" and "intensity", where given.
template<typename Light>
void readStrength(const JsonNode& node, Light& light)
{
  light.color = rgbOr(node, "color", light.color);
  light.intensity = numberOr(node, "intensity", light.intensity);
}

/// A count of samples per vertex and its maximum, where given: countKey a whole number, or
/// "auto" (as many as a tolerance needs), and maximumKey, the most "auto" may draw.
inline void readSampleCount(const JsonNode& node, const char* countKey, const char* maximumKey, Sampling& sampling)
{
  if (node.has(countKey) && node.at(countKey).isString())
  {
    if (node.at(countKey).text() != "auto")
    {
      node.at(countKey).fail("must be a whole number per vertex, or \"auto\" (as many as a tolerance needs)");
    }
    sampling.fromTolerance = true;
  }
  else if (node.has(countKey))
  {
    sampling.samples = node.at(countKey).wholeNumber(2, maxSamplesPerVertex);
  }
  if (node.has(maximumKey))
  {
    if (!sampling.fromTolerance)
    {
      node.at(maximumKey)
        .fail(std::string("is the most \"") + countKey + "\": \"auto\" may draw per vertex: give \"" + countKey +
          "\": \"auto\" with it, or leave it out");
    }
    sampling.maximum = node.at(maximumKey).wholeNumber(16, maxSamplesPerVertex);
  }
}

/// "samples" ("auto" with "max_samples") and "stratified", where given.
inline Sampling readSampling(const JsonNode& node)
{
  Sampling sampling;
  readSampleCount(node, "samples", "max_samples", sampling);
  if (node.has("stratified"))
  {
    sampling.stratified = node.at("stratified").boolean();
  }
  return sampling;
}
}
