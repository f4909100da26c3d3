#include "ComparedPieces.h"

#include "MeshFiles.h"
#include "ShadeLabWholeMesh.h"

#include "vtkAbstractArray.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstring>
#include <numeric>
#include <utility>
#include <vector>

namespace shadelab::app::compare
{
namespace
{
/// A global ids array's values, -1 for one that is not a whole number.
std::vector<vtkIdType> idsOf(vtkDataArray* ids)
{
  std::vector<vtkIdType> values(static_cast<std::size_t>(ids->GetNumberOfTuples()));
  for (std::size_t k = 0; k < values.size(); ++k)
  {
    const double value = ids->GetTuple1(static_cast<vtkIdType>(k));
    const auto id = static_cast<vtkIdType>(value);
    values[k] = static_cast<double>(id) == value ? id : -1;
  }
  return values;
}

/// For each global id 0 to n-1, the first point that has it (ids: each point's); empty where
/// the ids do not number the points so (each number at least once).
std::vector<vtkIdType> firstCopies(const std::vector<vtkIdType>& ids)
{
  const auto pointCount = static_cast<vtkIdType>(ids.size());
  vtkIdType largest = -1;
  for (vtkIdType id : ids)
  {
    if (id < 0 || id >= pointCount)
    {
      return {};
    }
    largest = std::max(largest, id);
  }
  std::vector<vtkIdType> first(static_cast<std::size_t>(largest + 1), -1);
  for (vtkIdType k = pointCount - 1; k >= 0; --k)
  {
    first[static_cast<std::size_t>(ids[static_cast<std::size_t>(k)])] = k;
  }
  const bool everyNumber = std::find(first.begin(), first.end(), -1) == first.end();
  return everyNumber ? first : std::vector<vtkIdType>{};
}

/// Whether tuples a and b of values hold the same numbers, bit for bit.
bool sameTuple(vtkDataArray* values, vtkIdType a, vtkIdType b)
{
  const int components = values->GetNumberOfComponents();
  if (values->HasStandardMemoryLayout() && values->GetDataTypeSize() > 0)
  {
    const std::size_t size = static_cast<std::size_t>(values->GetDataTypeSize() * components);
    const char* first = static_cast<const char*>(values->GetVoidPointer(0));
    return std::memcmp(first + a * size, first + b * size, size) == 0;
  }
  for (int c = 0; c < components; ++c) // bits, or values stored otherwise
  {
    const double x = values->GetComponent(a, c), y = values->GetComponent(b, c);
    if (std::memcmp(&x, &y, sizeof x) != 0)
    {
      return false;
    }
  }
  return true;
}

/// Why the arrays of attributes cannot follow their points or cells into another order ("" where
/// they can): each needs a tuple per point or cell, the global ids one number, the ghost flags
/// one unsigned byte (as VTK's are).
std::string arraysProblem(vtkDataSetAttributes* attributes, vtkIdType count, const std::string& kind)
{
  for (int a = 0; a < attributes->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* array = attributes->GetAbstractArray(a);
    if (array->GetNumberOfTuples() != count)
    {
      return "its " + kind + " array '" + (array->GetName() ? array->GetName() : "") + "' has " +
        std::to_string(array->GetNumberOfTuples()) + " tuples for " + std::to_string(count) + " " + kind + "s";
    }
  }
  vtkDataArray* ids = attributes->GetGlobalIds();
  if (ids && ids->GetNumberOfComponents() != 1)
  {
    return "its " + kind + "s' global ids have " + std::to_string(ids->GetNumberOfComponents()) +
      " components, where each " + kind + " has one id";
  }
  vtkAbstractArray* ghosts = attributes->GetAbstractArray(vtkDataSetAttributes::GhostArrayName());
  if (ghosts && (!vtkUnsignedCharArray::SafeDownCast(ghosts) || ghosts->GetNumberOfComponents() != 1))
  {
    return "its " + kind + " array '" + std::string(vtkDataSetAttributes::GhostArrayName()) +
      "' is not one unsigned byte a " + kind + ", as VTK's ghost flags are";
  }
  return "";
}

/// Throws where a point's copies (in other pieces) differ from its first in their coordinates
/// or in a point array (the ghost flags aside, which differ by piece).
void checkCopies(vtkPolyData* mesh, const std::vector<vtkIdType>& ids, const std::vector<vtkIdType>& first,
  const std::string& fileName)
{
  std::vector<std::pair<std::string, vtkDataArray*>> compared{ { "coordinates", mesh->GetPoints()->GetData() } };
  vtkPointData* pointData = mesh->GetPointData();
  for (int a = 0; a < pointData->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* values = pointData->GetArray(a);
    const std::string name = values && values->GetName() ? values->GetName() : "";
    if (values && values != pointData->GetGlobalIds() && name != vtkDataSetAttributes::GhostArrayName())
    {
      compared.emplace_back("values of '" + name + "'", values);
    }
  }
  for (vtkIdType k = 0; k < mesh->GetNumberOfPoints(); ++k)
  {
    const vtkIdType id = ids[static_cast<std::size_t>(k)];
    const vtkIdType original = first[static_cast<std::size_t>(id)];
    if (original == k)
    {
      continue; // the first copy itself
    }
    for (const auto& [what, values] : compared)
    {
      if (!sameTuple(values, original, k))
      {
        throw UserError(fileName + ": the point with global id " + std::to_string(id) + " has different " + what +
          " in two of its pieces (points " + std::to_string(original) + " and " + std::to_string(k) +
          " as read): the pieces are not of one mesh, or each computed the point alone; compare its pieces' files one "
          "at a time");
      }
    }
  }
}

/// What orders a mesh's cells: their global ids (empty: their order as read), and the ghost
/// flags that mark the duplicates (nullptr: none), both by the mesh's numbering of cells.
struct CellKeys
{
  std::vector<vtkIdType> ids;
  vtkUnsignedCharArray* ghosts = nullptr;
};

CellKeys cellKeysOf(vtkPolyData* mesh)
{
  vtkCellData* cellData = mesh->GetCellData();
  return { cellData->GetGlobalIds() ? idsOf(cellData->GetGlobalIds()) : std::vector<vtkIdType>{},
    vtkUnsignedCharArray::SafeDownCast(cellData->GetArray(vtkDataSetAttributes::GhostArrayName())) };
}

/// The cells of one kind (those from firstCell on, in the mesh's numbering of cells) in the
/// order of their keys, ghost cells left out, their points numbered by global id (pointIds).
/// Each kept cell's index in the mesh is appended to kept.
vtkSmartPointer<vtkCellArray> cellsInIdOrder(vtkCellArray* cells, vtkIdType firstCell, const CellKeys& keys,
  const std::vector<vtkIdType>& pointIds, const char* kind, const std::string& fileName, vtkIdList* kept)
{
  std::vector<std::pair<vtkIdType, vtkIdType>> order; // (global id, index in mesh)
  for (vtkIdType cell = firstCell; cell < firstCell + cells->GetNumberOfCells(); ++cell)
  {
    if (!keys.ghosts || !(keys.ghosts->GetValue(cell) & vtkDataSetAttributes::DUPLICATECELL))
    {
      const vtkIdType key = keys.ids.empty() ? cell : keys.ids[static_cast<std::size_t>(cell)];
      if (key < 0)
      {
        throw UserError(fileName + ": the global id of its cell " + std::to_string(cell) +
          " is not a whole number >= 0, so that the cells cannot be put in the order of their ids");
      }
      order.emplace_back(key, cell);
    }
  }
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  vtkNew<vtkIdTypeArray> offsets, connectivity;
  offsets->SetNumberOfValues(static_cast<vtkIdType>(order.size() + 1));
  offsets->SetValue(0, 0);
  for (std::size_t k = 0; k < order.size(); ++k)
  {
    if (k > 0 && order[k].first == order[k - 1].first)
    {
      throw UserError(fileName + ": the global cell id " + std::to_string(order[k].first) +
        " is on two of its pieces' " + kind +
        ": the pieces are not of one mesh, or their copies of a cell are not marked as ghost cells (vtkGhostType)");
    }
    vtkIdType size = 0;
    const vtkIdType* corners = nullptr;
    cells->GetCellAtId(order[k].second - firstCell, size, corners);
    for (vtkIdType i = 0; i < size; ++i)
    {
      connectivity->InsertNextValue(pointIds[static_cast<std::size_t>(corners[i])]);
    }
    offsets->SetValue(static_cast<vtkIdType>(k + 1), connectivity->GetNumberOfValues());
    kept->InsertNextId(order[k].second);
  }
  auto result = vtkSmartPointer<vtkCellArray>::New();
  result->SetData(offsets, connectivity);
  return result;
}

/// Copies the tuples `from` of source's arrays into target, in that order, leaving out the
/// global ids and the ghost flags.
void copyTuples(vtkDataSetAttributes* source, vtkIdList* from, vtkDataSetAttributes* target)
{
  vtkNew<vtkIdList> to;
  to->SetNumberOfIds(from->GetNumberOfIds());
  std::iota(to->GetPointer(0), to->GetPointer(0) + to->GetNumberOfIds(), vtkIdType(0));
  target->CopyGlobalIdsOff();
  target->CopyFieldOff(vtkDataSetAttributes::GhostArrayName());
  target->CopyAllocate(source, from->GetNumberOfIds());
  target->CopyData(source, from, to);
}

/// vtkIdList of ids.
vtkSmartPointer<vtkIdList> idList(const std::vector<vtkIdType>& ids)
{
  auto list = vtkSmartPointer<vtkIdList>::New();
  list->SetNumberOfIds(static_cast<vtkIdType>(ids.size()));
  std::copy(ids.begin(), ids.end(), list->GetPointer(0));
  return list;
}
}

OrderedDataSet inGlobalIdOrder(vtkSmartPointer<vtkDataSet> data, const std::string& fileName)
{
  auto* mesh = vtkPolyData::SafeDownCast(data);
  vtkDataArray* globalIds = mesh ? mesh->GetPointData()->GetGlobalIds() : nullptr;
  const bool numbersPoints =
    globalIds && globalIds->GetNumberOfComponents() == 1 && globalIds->GetNumberOfTuples() == mesh->GetNumberOfPoints();
  const std::vector<vtkIdType> pointIds = numbersPoints ? idsOf(globalIds) : std::vector<vtkIdType>{};
  const std::vector<vtkIdType> first = firstCopies(pointIds);
  if (first.empty())
  {
    return { data, globalIds ? "compared as read: its points' global ids do not number them 0 to n-1" : "" };
  }
  for (const std::string& problem : { arraysProblem(mesh->GetPointData(), mesh->GetNumberOfPoints(), "point"),
         arraysProblem(mesh->GetCellData(), mesh->GetNumberOfCells(), "cell") })
  {
    if (!problem.empty())
    {
      throw UserError(fileName + ": " + problem + ": they cannot be put in the order of their global ids");
    }
  }
  checkCopies(mesh, pointIds, first, fileName);
  vtkNew<vtkPolyData> whole;
  vtkNew<vtkPoints> points;
  points->SetData(tuplesAt(mesh->GetPoints()->GetData(), first));
  whole->SetPoints(points);
  copyTuples(mesh->GetPointData(), idList(first), whole->GetPointData());
  vtkNew<vtkIdList> kept;
  const vtkIdType lines = mesh->GetNumberOfVerts();
  const vtkIdType polygons = lines + mesh->GetNumberOfLines();
  const vtkIdType strips = polygons + mesh->GetNumberOfPolys();
  const CellKeys keys = cellKeysOf(mesh);
  whole->SetVerts(cellsInIdOrder(mesh->GetVerts(), 0, keys, pointIds, "vertices", fileName, kept));
  whole->SetLines(cellsInIdOrder(mesh->GetLines(), lines, keys, pointIds, "lines", fileName, kept));
  whole->SetPolys(cellsInIdOrder(mesh->GetPolys(), polygons, keys, pointIds, "polygons", fileName, kept));
  whole->SetStrips(cellsInIdOrder(mesh->GetStrips(), strips, keys, pointIds, "strips", fileName, kept));
  copyTuples(mesh->GetCellData(), kept, whole->GetCellData());
  whole->GetFieldData()->PassData(mesh->GetFieldData());
  // Read after "N points, M cells" in the report's first line.
  std::string description = "put in the order of their global ids, which are not themselves compared";
  const vtkIdType copies = mesh->GetNumberOfPoints() - whole->GetNumberOfPoints();
  const vtkIdType ghostCells = mesh->GetNumberOfCells() - whole->GetNumberOfCells();
  if (copies > 0)
  {
    description +=
      "; " + std::to_string(copies) + (copies == 1 ? " copy" : " copies") + " of points that pieces share left out";
  }
  if (ghostCells > 0)
  {
    description += "; " + std::to_string(ghostCells) + (ghostCells == 1 ? " ghost cell" : " ghost cells") + " left out";
  }
  return { whole, description };
}
}
