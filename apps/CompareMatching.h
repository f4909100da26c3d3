#pragma once
// shadelab compare --nearest: the result's points matched to the baseline's by nearest point,
// for meshes whose points were re-ordered.
#include "ComparedArrays.h"

#include "vtkDataSet.h"

#include <vector>

namespace shadelab::app::compare
{
/// The result's point and cell arrays put in the baseline's order, matching points (and cells,
/// by their centres) by nearest point within the tolerance.
Matching matchByNearest(vtkDataSet* baseline, vtkDataSet* result, std::vector<FileArray>& arrays, double tolerance);
}
