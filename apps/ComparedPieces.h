#pragma once
// shadelab compare on a mesh in pieces (a .pvtp, whose pieces are read as one mesh with their
// shared points once per piece): the pieces put back into the mesh they were cut from, so that
// what several processes wrote compares with what one wrote, point by point.
#include "vtkDataSet.h"
#include "vtkSmartPointer.h"

#include <string>

namespace shadelab::app::compare
{
/// A dataset as compare compares it, and how it was put in that order.
struct OrderedDataSet
{
  vtkSmartPointer<vtkDataSet> data;
  /// "" where the dataset is as read; otherwise what was done, for the report's first line.
  std::string description;
};

/// A mesh whose points have global ids numbering them 0 to n-1 (each at least once), put in the
/// order of those ids: each point once (its copies in other pieces must hold the same
/// coordinates and numbers), the cells in the order of their global ids (within verts, lines,
/// polygons and strips, as a mesh keeps them), duplicate (ghost) cells left out. The global ids,
/// then each point's and cell's index, and the ghost flags are dropped. Any other dataset is
/// returned as read. Throws UserError, naming fileName, where copies of a point differ, two cells
/// of a kind share a global id, or an array has not a tuple per point or cell.
OrderedDataSet inGlobalIdOrder(vtkSmartPointer<vtkDataSet> data, const std::string& fileName);
}
