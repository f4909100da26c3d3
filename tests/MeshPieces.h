#pragma once
// A mesh cut into pieces for processes, as a reader of a split file gives them: each piece with
// global point and cell ids (the whole mesh's indices), so that the filters can put the mesh
// back together (ShadeLabWholeMesh.h). For the tests of split meshes.
#include "vtkCellData.h"
#include "vtkExtractPolyDataPiece.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <numeric>
#include <string>

namespace shadelab::testing
{
namespace detail
{
/// Makes attributes' global ids (added as each tuple's index where there are none) an ordinary
/// array, which vtkExtractPolyDataPiece passes on (it drops the global ids attribute); returns
/// its name.
inline std::string globalIdsAsArray(vtkDataSetAttributes* attributes, vtkIdType count)
{
  vtkSmartPointer<vtkDataArray> ids = attributes->GetGlobalIds();
  if (!ids)
  {
    auto indices = vtkSmartPointer<vtkIdTypeArray>::New();
    indices->SetNumberOfValues(count);
    std::iota(indices->GetPointer(0), indices->GetPointer(0) + count, vtkIdType(0));
    ids = indices;
  }
  else if (!ids->GetName())
  {
    ids = vtk::TakeSmartPointer(ids->NewInstance()); // the mesh's own, under a name of their own
    ids->DeepCopy(attributes->GetGlobalIds());
  }
  if (!ids->GetName())
  {
    ids->SetName("GlobalIds");
  }
  attributes->SetActiveAttribute(-1, vtkDataSetAttributes::GLOBALIDS);
  attributes->AddArray(ids);
  return ids->GetName();
}
}

/// Piece `piece` of `pieces` of mesh, by vtkExtractPolyDataPiece (runs of cells, with
/// ghostLevels layers of ghost cells around it), every array passed through, and global ids
/// added where the mesh has none: each point's and cell's index in mesh.
inline vtkSmartPointer<vtkPolyData> meshPiece(vtkPolyData* mesh, int piece, int pieces, int ghostLevels)
{
  vtkNew<vtkPolyData> numbered;
  numbered->ShallowCopy(mesh); // attributes of its own: the mesh's stay as they are
  const std::string pointIds = detail::globalIdsAsArray(numbered->GetPointData(), mesh->GetNumberOfPoints());
  const std::string cellIds = detail::globalIdsAsArray(numbered->GetCellData(), mesh->GetNumberOfCells());
  vtkNew<vtkExtractPolyDataPiece> extract;
  extract->SetInputData(numbered);
  extract->SetCreateGhostCells(ghostLevels > 0);
  extract->UpdatePiece(piece, pieces, ghostLevels);
  vtkSmartPointer<vtkPolyData> result = extract->GetOutput();
  result->GetPointData()->SetActiveGlobalIds(pointIds.c_str());
  result->GetCellData()->SetActiveGlobalIds(cellIds.c_str());
  return result;
}
}
