#pragma once
// Scene-file fields that several light types share, read through JsonNode.
#include "JsonNode.h"
#include "SampleSequence.h"

namespace shadelab
{
/// "color" and "intensity", where given.
template <typename Light>
void readStrength(const JsonNode& node, Light& light)
{
  light.color = rgbOr(node, "color", light.color);
  light.intensity = numberOr(node, "intensity", light.intensity);
}

/// "samples" and "stratified", where given.
inline Sampling readSampling(const JsonNode& node)
{
  Sampling sampling;
  if (node.has("samples"))
  {
    sampling.samples = node.at("samples").wholeNumber(2, maxSamplesPerVertex);
  }
  if (node.has("stratified"))
  {
    sampling.stratified = node.at("stratified").boolean();
  }
  return sampling;
}
}
