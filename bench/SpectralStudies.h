#pragma once
// The accuracy studies of the spectral mode (docs/formulas.md section 22): what the RGB model
// errs by under each illuminant, and what the width of the bands errs by.
#include "AccuracyStudyParts.h"
#include "BenchmarkMeshes.h"
#include "Chart.h"

namespace shadelab::app
{
/// 12. data/scenes/spectral_fluorescent.json with each CIE illuminant (and blackbodies) for its
/// lights: the largest |total_rgb_difference| over the mesh, the RGB model's error.
std::vector<AccuracyRow> spectralRgbErrorStudy(const Mesh& mesh, ChartSpec& chart);

/// 13. The same scene (F11) in bands of 2 to 50 nm against 1 nm: the largest difference of the
/// spectral total, falling as the bands get finer.
std::vector<AccuracyRow> spectralBandStudy(const Mesh& mesh, ChartSpec& chart);
}
