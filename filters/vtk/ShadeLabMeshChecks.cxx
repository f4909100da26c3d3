#include "ShadeLabMeshChecks.h"

#include "vtkCellArray.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"

#include <atomic>
#include <sstream>
#include <tuple>

namespace shadelab
{
namespace
{
/// Whether ok(i) holds for every i in [0, count): a vtkSMPTools loop, since a large mesh has
/// tens of millions of ids; only where it fails is the first failure looked for, in order.
template<typename Check>
bool allHold(vtkIdType count, Check ok)
{
  std::atomic<bool> failed{ false };
  vtkSMPTools::For(0, count,
    [&](vtkIdType begin, vtkIdType end)
    {
      bool holds = true;
      for (vtkIdType i = begin; i < end; ++i)
      {
        holds &= ok(i);
      }
      if (!holds)
      {
        failed = true;
      }
    });
  return !failed;
}

/// The problem with one cell array whose offsets and ids are of type Id, or "".
template<typename Id>
std::string cellArrayProblem(const Id* offsets, vtkIdType cellCount, const Id* ids, vtkIdType idCount,
  vtkIdType pointCount, const char* kind, vtkIdType leastPoints)
{
  std::ostringstream problem;
  if (cellCount > 0 && offsets[0] != 0)
  {
    problem << "the " << kind << " cells' offsets start at " << offsets[0] << ", not 0: the mesh is corrupt";
    return problem.str();
  }
  auto sizeProblem = [&](vtkIdType c)
  { return offsets[c + 1] < offsets[c] || offsets[c + 1] > idCount || offsets[c + 1] - offsets[c] < leastPoints; };
  if (!allHold(cellCount, [&](vtkIdType c) { return !sizeProblem(c); }))
  {
    for (vtkIdType c = 0; c < cellCount; ++c)
    {
      if (offsets[c + 1] < offsets[c] || offsets[c + 1] > idCount)
      {
        problem << kind << " " << c << "'s points run from " << offsets[c] << " to " << offsets[c + 1]
                << " in a list of " << idCount << ": the mesh is corrupt";
        return problem.str();
      }
      if (offsets[c + 1] - offsets[c] < leastPoints)
      {
        problem << kind << " " << c << " has " << offsets[c + 1] - offsets[c] << " points, and a " << kind
                << " needs at least " << leastPoints << ": the mesh is corrupt";
        return problem.str();
      }
    }
  }
  if (cellCount > 0 && offsets[cellCount] != idCount)
  {
    problem << "the " << kind << " cells use " << offsets[cellCount] << " of the " << idCount
            << " point ids they hold: the mesh is corrupt";
    return problem.str();
  }
  if (!allHold(idCount, [&](vtkIdType i) { return ids[i] >= 0 && ids[i] < pointCount; }))
  {
    for (vtkIdType i = 0; i < idCount; ++i)
    {
      if (ids[i] < 0 || ids[i] >= pointCount)
      {
        problem << "the mesh's cells use point id " << ids[i] << ", but it has " << pointCount
                << " points: the mesh is corrupt";
        return problem.str();
      }
    }
  }
  return "";
}

std::string cellArrayProblem(vtkCellArray* cells, vtkIdType pointCount, const char* kind, vtkIdType leastPoints)
{
  const vtkIdType cellCount = cells->GetNumberOfCells();
  const vtkIdType idCount = cells->GetNumberOfConnectivityIds();
  if (cells->IsStorage64Bit())
  {
    return cellArrayProblem(cells->GetOffsetsArray64()->GetPointer(0), cellCount,
      cells->GetConnectivityArray64()->GetPointer(0), idCount, pointCount, kind, leastPoints);
  }
  return cellArrayProblem(cells->GetOffsetsArray32()->GetPointer(0), cellCount,
    cells->GetConnectivityArray32()->GetPointer(0), idCount, pointCount, kind, leastPoints);
}
}

std::string cellProblem(vtkPolyData* mesh)
{
  const vtkIdType points = mesh->GetNumberOfPoints();
  for (const auto& [cells, kind, least] :
    { std::make_tuple(mesh->GetVerts(), "vertex", 1), std::make_tuple(mesh->GetLines(), "line", 2),
      std::make_tuple(mesh->GetPolys(), "polygon", 3), std::make_tuple(mesh->GetStrips(), "strip", 3) })
  {
    const std::string problem = cellArrayProblem(cells, points, kind, least);
    if (!problem.empty())
    {
      return problem;
    }
  }
  return "";
}
}
