#include "CompareMatching.h"

#include "vtkCellCenters.h"
#include "vtkIdList.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkStaticPointLocator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

namespace shadelab::app::compare
{
namespace
{
/// For each point of `from`, the nearest point of `to` not yet matched (points with the same
/// coordinates, copies at a seam, match one to one in the order of their ids), within
/// tolerance: a greedy search among each point's 16 nearest. Empty, with the reason in
/// problem, where a point finds none; what says what the points are.
std::vector<vtkIdType> nearestMatches(
  vtkDataSet* from, vtkDataSet* to, double tolerance, const std::string& what, double& farthest, std::string& problem)
{
  vtkNew<vtkStaticPointLocator> locator;
  locator->SetDataSet(to);
  locator->BuildLocator();
  std::vector<vtkIdType> matches(static_cast<std::size_t>(from->GetNumberOfPoints()));
  std::vector<bool> taken(static_cast<std::size_t>(to->GetNumberOfPoints()), false);
  farthest = 0;
  for (vtkIdType i = 0; i < from->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    from->GetPoint(i, p);
    // The nearest few, nearest first and equal distances by id: the first not yet matched.
    constexpr int candidates = 16;
    vtkNew<vtkIdList> near;
    locator->FindClosestNPoints(candidates, p, near);
    std::vector<std::pair<double, vtkIdType>> byDistance;
    for (vtkIdType k = 0; k < near->GetNumberOfIds(); ++k)
    {
      to->GetPoint(near->GetId(k), q);
      byDistance.emplace_back(std::sqrt(vtkMath::Distance2BetweenPoints(p, q)), near->GetId(k));
    }
    std::sort(byDistance.begin(), byDistance.end());
    vtkIdType chosen = -1;
    double distance = byDistance.empty() ? std::numeric_limits<double>::infinity() : byDistance.front().first;
    for (const auto& [d, id] : byDistance)
    {
      if (!taken[static_cast<std::size_t>(id)] && d <= tolerance)
      {
        chosen = id;
        distance = d;
        break;
      }
    }
    if (chosen < 0)
    {
      const bool allTaken = distance <= tolerance;
      problem = "the result's " + what + " " + std::to_string(i) + " (" + brief(p[0]) + ", " + brief(p[1]) + ", " +
        brief(p[2]) + ") has no match in the baseline within " + brief(tolerance) +
        (allTaken ? ": its " + std::to_string(candidates) + " nearest are matched to others"
                  : " (the nearest is " + brief(distance) + " away)");
      return {};
    }
    taken[static_cast<std::size_t>(chosen)] = true;
    matches[static_cast<std::size_t>(i)] = chosen;
    farthest = std::max(farthest, distance);
  }
  return matches;
}

/// The values moved so that tuple i of the result lands where its match, matches[i], is.
void moveTuples(ArrayValues& values, const std::vector<vtkIdType>& matches)
{
  const std::size_t components = static_cast<std::size_t>(values.components);
  auto move = [&](auto& v)
  {
    auto moved = v;
    for (std::size_t i = 0; i < matches.size() && (i + 1) * components <= v.size(); ++i)
    {
      std::copy_n(&v[i * components], components, &moved[static_cast<std::size_t>(matches[i]) * components]);
    }
    v = std::move(moved);
  };
  values.type == ValueType::Integer ? move(values.integers) : move(values.reals);
}

/// The cells' centres, as points (none for a cell without points).
vtkSmartPointer<vtkDataSet> cellCentres(vtkDataSet* data)
{
  vtkNew<vtkCellCenters> centres;
  centres->SetInputData(data);
  centres->VertexCellsOff();
  centres->Update();
  return centres->GetOutput();
}

}

Matching matchByNearest(vtkDataSet* baseline, vtkDataSet* result, std::vector<FileArray>& arrays, double tolerance)
{
  Matching matching;
  std::ostringstream done;
  for (const bool cells : { false, true })
  {
    vtkSmartPointer<vtkDataSet> from = cells ? cellCentres(result) : vtkSmartPointer<vtkDataSet>(result);
    vtkSmartPointer<vtkDataSet> to = cells ? cellCentres(baseline) : vtkSmartPointer<vtkDataSet>(baseline);
    std::string& problem = cells ? matching.cellProblem : matching.pointProblem;
    if (cells &&
      (from->GetNumberOfPoints() != result->GetNumberOfCells() ||
        to->GetNumberOfPoints() != baseline->GetNumberOfCells()))
    {
      problem = "cells without points have no centre, so the cells cannot be matched by their centres";
      continue;
    }
    if (from->GetNumberOfPoints() != to->GetNumberOfPoints() || from->GetNumberOfPoints() == 0)
    {
      continue; // the arrays' counts differ, which their rows will say
    }
    double farthest = 0;
    std::vector<vtkIdType> matches =
      nearestMatches(from, to, tolerance, cells ? "cell centre" : "point", farthest, problem);
    if (!problem.empty())
    {
      continue;
    }
    for (FileArray& array : arrays)
    {
      const bool onCells = array.association == Association::CellData;
      if (array.association != Association::FieldData && onCells == cells)
      {
        moveTuples(array.values, matches);
      }
    }
    done << (cells ? "; cells by their centres, " : "points matched by nearest point, ") << "the farthest "
         << brief(farthest) << " away";
    (cells ? matching.cells : matching.points) = std::move(matches);
  }
  matching.description = done.str().empty() ? "no points or cells matched by nearest point" : done.str();
  return matching;
}
}
