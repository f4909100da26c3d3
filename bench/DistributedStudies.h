#pragma once
// Studies 6 to 8b of `shadelab-bench --charts`: the estimators of an area light and of two
// environment maps on the bunny, with and without shadows, error against time; and issue 4's
// two speed requirements.
#include "AccuracyStudies.h"
#include "AccuracyStudyParts.h"
#include "BenchmarkMeshes.h"
#include "Chart.h"

namespace shadelab::app
{
/// What the studies read, all read before any study runs so that a missing file stops the
/// run at once.
struct DistributedStudyInputs
{
  /// The area-light scene's material and viewer, with its softbox alone.
  Scene softbox;
  /// The bundled maps as SH lights, each scaled so that the bunny's totals are of order 1.
  EnvironmentLight sunset, studio;
};

/// Throws UserError naming the file or folder that is missing or unreadable.
DistributedStudyInputs readDistributedStudyInputs(const AccuracyOptions& options);

/// 6. The softbox by the exact, Monte Carlo and point estimators, against E exact and S by
/// 16384 stratified samples; charts the error of the total. 6b: the same with its soft shadows,
/// the visible fraction sampled too.
std::vector<AccuracyRow> areaLightStudy(
  const Mesh& bunny, const Scene& softbox, bool shadows, int maxRepeats, ChartSpec& chart);

/// 7 and 8. A map by brute force at several widths, SH and Monte Carlo by luminance and by
/// cosine, against brute force at width 256, under the softbox scene's material and viewer;
/// charts the error of the diffuse term.
std::vector<AccuracyRow> environmentMapStudy(const Mesh& bunny, const Scene& material, const EnvironmentLight& map,
  const std::string& studyName, int maxRepeats, ChartSpec& chart);

/// 7b and 8b. A map with its shadows: Monte Carlo by luminance, by cosine and by both (MIS),
/// stratified and (MIS) independent, and SH times the visible fraction, against Monte Carlo by
/// MIS with 16384 stratified samples; charts the error of the diffuse term.
std::vector<AccuracyRow> environmentShadowStudy(const Mesh& bunny, const Scene& material, const EnvironmentLight& map,
  const std::string& studyName, int maxRepeats, ChartSpec& chart);

/// Issue 4's speed requirements: the SH irradiance's time per vertex against a distant
/// light's Lambert term, and the time to project the map on the 9 coefficients.
std::vector<AccuracyRow> speedRequirementRows(const Mesh& bunny, const Scene& material, const EnvironmentLight& map);
}
