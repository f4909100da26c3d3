#pragma once
// The accuracy study of textures at vertices (docs/formulas.md section 7.2): a texture's colour
// taken at each vertex by point sampling, by bilinear interpolation and by the box filter over
// the texels the vertex stands for (what ShadeLab's importers do), against the texture itself.
#include "AccuracyStudyParts.h"
#include "Chart.h"

namespace shadelab::app
{
/// 16. A square of n x n vertices over a 1024 x 1024 texture (a checker of 2-texel squares, the
/// worst case, and waves with the same power in every octave, as a photograph's detail has), n
/// from 9 to 2049: for each way of taking the colour, the mean of the colours interpolated
/// between each cell's vertices (what a renderer draws over the cell) against the texture's own
/// mean over the cell (exact: BoxFilteredTexture), and the time the colours took.
std::vector<AccuracyRow> textureFilteringStudy(ChartSpec& chart);
}
