#ifndef ShadeLabMeshChecks_h
#define ShadeLabMeshChecks_h
// What makes a mesh's cells unusable, checked before any filter walks them: a vtkPolyData can
// come from a damaged file or from code that built it wrongly, and cells whose offsets or ids
// point outside their arrays would be read out of bounds.
#include "ShadeLabFiltersModule.h"

#include <string>

class vtkPolyData;

namespace shadelab
{
/// "" when every cell array's offsets start at 0, never decrease and end at its connectivity's
/// size, every id names one of the mesh's points, and every cell has the points its kind needs
/// (a vertex 1, a line 2, a polygon or strip 3); otherwise the first problem, in words.
SHADELABFILTERS_EXPORT std::string cellProblem(vtkPolyData* mesh);
}

#endif
