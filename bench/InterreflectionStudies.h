#pragma once
// The accuracy study of interreflection (docs/formulas.md section 23): inside a spherical bowl
// under a uniform sky, whose bounces have a closed form, the error against the bounces and
// against the gather's rays.
#include "AccuracyStudyParts.h"
#include "Chart.h"

namespace shadelab::app
{
/// 14. The bowl's indirect diffuse term against its closed form after K = 1 .. 10 bounces (256
/// rays), with what the rest add and the bound that "bounces": "auto" stops on.
std::vector<AccuracyRow> interreflectionBouncesStudy(int maxRepeats, ChartSpec& chart);

/// 14b. The same with the bounces converged, against 16 to 1024 gather rays.
std::vector<AccuracyRow> interreflectionRaysStudy(int maxRepeats, ChartSpec& chart);

/// 14c. Time against the error reached through vtkLocalReflectanceFilter, in the bowl lit by a
/// constant sky without shadows: fixed bounces and rays, and the plan of a tolerance
/// ("bounces" and "samples": "auto").
std::vector<AccuracyRow> interreflectionPlanStudy(int maxRepeats, ChartSpec& chart);
}
