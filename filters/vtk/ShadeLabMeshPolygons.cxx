#include "ShadeLabMeshPolygons.h"

#include "vtkCellArrayIterator.h"
#include "vtkIdTypeArray.h"
#include "vtkPolyData.h"

namespace shadelab
{
MeshPolygons::MeshPolygons(vtkPolyData* mesh)
{
  vtkCellArray* polys = mesh->GetPolys();
  if (polys->IsStorage64Bit() && mesh->GetNumberOfStrips() == 0)
  {
    list_.offsets = polys->GetOffsetsArray64()->GetPointer(0);
    list_.connectivity = polys->GetConnectivityArray64()->GetPointer(0);
    list_.count = static_cast<std::size_t>(polys->GetNumberOfCells());
    return;
  }
  offsets_.push_back(0);
  auto cell = vtk::TakeSmartPointer(polys->NewIterator());
  for (cell->GoToFirstCell(); !cell->IsDoneWithTraversal(); cell->GoToNextCell())
  {
    vtkIdType size;
    const vtkIdType* ids;
    cell->GetCurrentCell(size, ids);
    connectivity_.insert(connectivity_.end(), ids, ids + size);
    offsets_.push_back(static_cast<PointId>(connectivity_.size()));
  }
  auto strip = vtk::TakeSmartPointer(mesh->GetStrips()->NewIterator());
  for (strip->GoToFirstCell(); !strip->IsDoneWithTraversal(); strip->GoToNextCell())
  {
    vtkIdType size;
    const vtkIdType* ids;
    strip->GetCurrentCell(size, ids);
    for (vtkIdType k = 2; k < size; ++k)
    {
      // A strip's triangles alternate in winding: every second one is turned back.
      const bool even = k % 2 == 0;
      connectivity_.insert(
        connectivity_.end(), { even ? ids[k - 2] : ids[k - 1], even ? ids[k - 1] : ids[k - 2], ids[k] });
      offsets_.push_back(static_cast<PointId>(connectivity_.size()));
    }
  }
  list_.offsets = offsets_.data();
  list_.connectivity = connectivity_.data();
  list_.count = offsets_.size() - 1;
}

vtkSmartPointer<vtkCellArray> MeshPolygons::welded(const std::vector<PointId>& mergeMap) const
{
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(static_cast<vtkIdType>(list_.count + 1));
  for (std::size_t k = 0; k <= list_.count; ++k)
  {
    offsets->SetValue(static_cast<vtkIdType>(k), list_.offsets[k]);
  }
  const PointId idCount = list_.offsets[list_.count];
  connectivity->SetNumberOfValues(idCount);
  for (PointId i = 0; i < idCount; ++i)
  {
    const PointId id = list_.connectivity[i];
    connectivity->SetValue(i, mergeMap.empty() ? id : mergeMap[static_cast<std::size_t>(id)]);
  }
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(offsets, connectivity);
  return cells;
}

std::unique_ptr<OccluderMesh> occludersOf(vtkPolyData* mesh)
{
  const MeshPolygons polygons(mesh);
  std::unique_ptr<OccluderMesh> occluders;
  visitPackedPoints(mesh->GetPoints()->GetData(),
    [&](auto points)
    {
      occluders =
        std::make_unique<OccluderMesh>(points, static_cast<std::size_t>(mesh->GetNumberOfPoints()), polygons.list());
    });
  return occluders;
}
}
