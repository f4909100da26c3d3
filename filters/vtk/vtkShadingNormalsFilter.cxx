#include "vtkShadingNormalsFilter.h"

#include "NormalOrientation.h"
#include "PointNormals.h"
#include "ShadeLabMeshChecks.h"

#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDataArrayRange.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataNormals.h"
#include "vtkSMPTools.h"
#include "vtkStaticPointLocator.h"
#include "vtkStringArray.h"

#include <sstream>
#include <type_traits>

vtkStandardNewMacro(vtkShadingNormalsFilter);
static_assert(std::is_same<vtkIdType, shadelab::PointId>::value, "ShadeLab needs VTK built with 64-bit ids");

namespace
{
/// The mesh's polygons, and its strips as triangles, as one shadelab::PolygonList. Uses the
/// mesh's own arrays where they are 64-bit and there are no strips, and a copy otherwise.
class MeshPolygons
{
public:
  explicit MeshPolygons(vtkPolyData* mesh)
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
      offsets_.push_back(static_cast<shadelab::PointId>(connectivity_.size()));
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
        connectivity_.insert(connectivity_.end(), { even ? ids[k - 2] : ids[k - 1], even ? ids[k - 1] : ids[k - 2], ids[k] });
        offsets_.push_back(static_cast<shadelab::PointId>(connectivity_.size()));
      }
    }
    list_.offsets = offsets_.data();
    list_.connectivity = connectivity_.data();
    list_.count = offsets_.size() - 1;
  }

  const shadelab::PolygonList& list() const { return list_; }

  /// The same polygons as a vtkCellArray with their ids replaced by mergeMap's.
  vtkSmartPointer<vtkCellArray> welded(const std::vector<shadelab::PointId>& mergeMap) const
  {
    vtkNew<vtkIdTypeArray> offsets, connectivity;
    offsets->SetNumberOfValues(static_cast<vtkIdType>(list_.count + 1));
    for (std::size_t k = 0; k <= list_.count; ++k)
    {
      offsets->SetValue(static_cast<vtkIdType>(k), list_.offsets[k]);
    }
    const shadelab::PointId idCount = list_.offsets[list_.count];
    connectivity->SetNumberOfValues(idCount);
    for (shadelab::PointId i = 0; i < idCount; ++i)
    {
      const shadelab::PointId id = list_.connectivity[i];
      connectivity->SetValue(i, mergeMap.empty() ? id : mergeMap[static_cast<std::size_t>(id)]);
    }
    auto cells = vtkSmartPointer<vtkCellArray>::New();
    cells->SetData(offsets, connectivity);
    return cells;
  }

private:
  shadelab::PolygonList list_;
  std::vector<shadelab::PointId> offsets_;
  std::vector<shadelab::PointId> connectivity_;
};

glm::dvec3 pointOf(vtkPoints* points, shadelab::PointId id)
{
  double p[3];
  points->GetPoint(id, p);
  return { p[0], p[1], p[2] };
}

/// For each point, the id of the point that stands for its position: with a tolerance of 0,
/// exactly coincident points share one (vtkStaticPointLocator::MergePoints, threaded);
/// otherwise each point not yet placed stands for those within the tolerance of it, in id
/// order. (VTK 9.1's MergePoints with a tolerance is not used: run after run on spot.obj it
/// left 1 to 10 positions split among several ids, differently each time.)
std::vector<shadelab::PointId> positionMergeMap(vtkPolyData* mesh, double relativeTolerance)
{
  vtkNew<vtkStaticPointLocator> locator;
  locator->SetDataSet(mesh);
  locator->BuildLocator();
  std::vector<shadelab::PointId> map(static_cast<std::size_t>(mesh->GetNumberOfPoints()), -1);
  if (relativeTolerance == 0.0)
  {
    locator->MergePoints(0.0, map.data());
    return map;
  }
  const double radius = relativeTolerance * mesh->GetLength();
  vtkNew<vtkIdList> near;
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    if (map[static_cast<std::size_t>(i)] >= 0)
    {
      continue;
    }
    double p[3];
    mesh->GetPoint(i, p);
    locator->FindPointsWithinRadius(radius, p, near);
    for (vtkIdType k = 0; k < near->GetNumberOfIds(); ++k)
    {
      shadelab::PointId& position = map[static_cast<std::size_t>(near->GetId(k))];
      position = position >= 0 ? position : i;
    }
    map[static_cast<std::size_t>(i)] = i;
  }
  return map;
}

/// flipped[k] for every polygon that vtkPolyDataNormals' consistency pass turns round, on the
/// welded mesh (so that seams join the pieces they separate).
std::vector<bool> polygonsToTurn(vtkPolyData* mesh, const MeshPolygons& polygons, const std::vector<shadelab::PointId>& mergeMap)
{
  vtkNew<vtkPolyData> welded;
  welded->SetPoints(mesh->GetPoints());
  vtkSmartPointer<vtkCellArray> cells = polygons.welded(mergeMap);
  welded->SetPolys(cells);
  vtkNew<vtkPolyDataNormals> reorder;
  reorder->SetInputData(welded);
  reorder->SplittingOff();
  reorder->ConsistencyOn();
  reorder->AutoOrientNormalsOff();
  reorder->ComputeCellNormalsOff();
  reorder->Update();
  vtkCellArray* ordered = reorder->GetOutput()->GetPolys();
  std::vector<bool> flipped(polygons.list().count, false);
  vtkNew<vtkIdList> before, after;
  for (vtkIdType k = 0; k < cells->GetNumberOfCells(); ++k)
  {
    cells->GetCellAtId(k, before);
    ordered->GetCellAtId(k, after);
    // vtkPolyDataNormals turns a polygon round by reversing its ids.
    const vtkIdType size = before->GetNumberOfIds();
    bool reversed = size >= 3 && after->GetNumberOfIds() == size;
    for (vtkIdType i = 0; reversed && i < size; ++i)
    {
      reversed = after->GetId(i) == before->GetId(size - 1 - i);
    }
    flipped[static_cast<std::size_t>(k)] = reversed;
  }
  return flipped;
}

/// Feeds every triangle of the mesh's polygons (split into fans) and strips to the
/// orientation test. A worker for vtkArrayDispatch, so that points and normals are read from
/// raw memory. Winding does not matter here: the test uses the stored normals, not the
/// triangles' own orientation.
struct OrientationWorker
{
  vtkPolyData* mesh;
  shadelab::NormalOrientation result;

  template <typename PointArray, typename NormalArray>
  void operator()(PointArray* pointArray, NormalArray* normalArray)
  {
    const auto points = vtk::DataArrayTupleRange<3>(pointArray);
    const auto normals = vtk::DataArrayTupleRange<3>(normalArray);
    auto vec = [](const auto& tuple) { return glm::dvec3(tuple[0], tuple[1], tuple[2]); };
    double centre[3];
    mesh->GetCenter(centre); // of the bounding box
    shadelab::NormalOrientationAccumulator accumulator({ centre[0], centre[1], centre[2] });
    const MeshPolygons polygons(mesh);
    const shadelab::PolygonList& list = polygons.list();
    for (std::size_t k = 0; k < list.count; ++k)
    {
      const shadelab::PointId* ids = list.ids(k);
      for (std::size_t i = 2; i < list.size(k); ++i)
      {
        accumulator.addTriangle(vec(points[ids[0]]), vec(points[ids[i - 1]]), vec(points[ids[i]]),
          vec(normals[ids[0]]), vec(normals[ids[i - 1]]), vec(normals[ids[i]]));
      }
    }
    result = accumulator.result();
  }
};

shadelab::NormalOrientation assessOrientation(vtkPolyData* mesh, vtkDataArray* normals)
{
  OrientationWorker worker{ mesh, {} };
  vtkDataArray* points = mesh->GetPoints()->GetData();
  using Reals = vtkArrayDispatch::Reals;
  if (!vtkArrayDispatch::Dispatch2ByValueType<Reals, Reals>::Execute(points, normals, worker))
  {
    worker(points, normals); // other value types, through the generic vtkDataArray API
  }
  return worker.result;
}

vtkSmartPointer<vtkDataArray> flippedCopy(vtkDataArray* normals)
{
  vtkSmartPointer<vtkDataArray> copy = vtk::TakeSmartPointer(normals->NewInstance());
  copy->DeepCopy(normals);
  for (auto tuple : vtk::DataArrayTupleRange<3>(copy))
  {
    tuple[0] = -tuple[0];
    tuple[1] = -tuple[1];
    tuple[2] = -tuple[2];
  }
  return copy;
}

bool usableNormals(vtkDataArray* normals, vtkIdType pointCount)
{
  return normals && normals->GetNumberOfComponents() == 3 && normals->GetNumberOfTuples() == pointCount;
}
}

int vtkShadingNormalsFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->Report.clear();
  if (input->GetNumberOfPoints() == 0)
  {
    return 1; // an empty mesh has no normals to prepare
  }
  const std::string cells = shadelab::cellProblem(input);
  if (!cells.empty())
  {
    vtkErrorMacro(<< cells);
    return 0;
  }
  std::ostringstream report;
  vtkDataArray* inputNormals = input->GetPointData()->GetNormals();
  vtkSmartPointer<vtkDataArray> normals;
  if (this->KeepInputNormals && usableNormals(inputNormals, input->GetNumberOfPoints()))
  {
    output->ShallowCopy(input);
    normals = inputNormals;
    report << "Using the mesh's point normals '" << (normals->GetName() ? normals->GetName() : "") << "'.";
  }
  else if (this->SplitSharpEdges)
  {
    vtkNew<vtkPolyDataNormals> split;
    split->SetInputData(input);
    split->SplittingOn();
    split->SetFeatureAngle(this->SplitAngle);
    split->ConsistencyOn();
    split->ComputeCellNormalsOff();
    split->Update();
    output->ShallowCopy(split->GetOutput());
    normals = output->GetPointData()->GetNormals();
    normals->SetName(this->NormalsName.c_str());
    report << "Split the mesh at edges sharper than " << this->SplitAngle
           << " degrees (vtkPolyDataNormals): " << input->GetNumberOfPoints() << " points became "
           << output->GetNumberOfPoints() << "; computed normals as '" << this->NormalsName << "'.";
  }
  else
  {
    output->ShallowCopy(input);
    const std::size_t pointCount = static_cast<std::size_t>(input->GetNumberOfPoints());
    const MeshPolygons polygons(input);
    const std::vector<shadelab::PointId> mergeMap = this->WeldCoincidentPoints
      ? positionMergeMap(input, this->WeldTolerance)
      : std::vector<shadelab::PointId>{};
    const shadelab::PolygonEdges edges(polygons.list(), mergeMap, pointCount);
    const std::size_t inconsistent = edges.inconsistentCount();
    const std::vector<bool> flipped =
      inconsistent > 0 ? polygonsToTurn(input, polygons, mergeMap) : std::vector<bool>{};
    vtkPoints* points = input->GetPoints();
    const std::vector<glm::dvec3> areas = shadelab::polygonAreaVectors(
      polygons.list(), flipped, [points](shadelab::PointId id) { return pointOf(points, id); });
    shadelab::WeldSummary weld;
    const std::vector<glm::dvec3> unit = shadelab::unitPointNormals(pointCount, polygons.list(), areas,
      this->WeldCoincidentPoints ? &edges : nullptr, mergeMap, this->FeatureAngle, &weld);
    auto computed = vtkSmartPointer<vtkFloatArray>::New();
    computed->SetName(this->NormalsName.c_str());
    computed->SetNumberOfComponents(3);
    computed->SetNumberOfTuples(static_cast<vtkIdType>(pointCount));
    vtkSMPTools::For(0, static_cast<vtkIdType>(pointCount),
      [&](vtkIdType begin, vtkIdType end)
      {
        for (vtkIdType i = begin; i < end; ++i)
        {
          const glm::dvec3& n = unit[static_cast<std::size_t>(i)];
          const float tuple[3] = { static_cast<float>(n.x), static_cast<float>(n.y), static_cast<float>(n.z) };
          computed->SetTypedTuple(i, tuple);
        }
      });
    normals = computed;
    output->GetPointData()->SetNormals(computed);
    report << (inputNormals ? "Replaced the mesh's point normals" : "The mesh has no point normals")
           << ": computed area-weighted ones and added them as '" << this->NormalsName << "'";
    if (inconsistent > 0)
    {
      report << ", after turning round the polygons wound against their neighbours (" << inconsistent
             << " edges were traversed twice in one direction)";
    }
    if (weld.sharedPositions > 0)
    {
      report << "; " << weld.sharedPositions << " positions are shared by several points: averaged "
             << weld.pointsAveraged << " points with their copies";
      if (weld.pointsKeptApart > 0)
      {
        report << ", kept " << weld.pointsKeptApart << " apart at edges sharper than " << this->FeatureAngle
               << " degrees";
      }
    }
    report << ".";
  }

  const shadelab::NormalOrientation orientation = assessOrientation(output, normals);
  if (orientation.pointsInward())
  {
    report << " They point into the mesh (closure " << orientation.closure << ", flux " << orientation.flux << ")";
    if (this->OrientOutward)
    {
      output->GetPointData()->SetNormals(flippedCopy(normals));
      report << "; flipped them outward.";
    }
    else
    {
      report << "; kept as they are, because orienting them outward is off.";
    }
  }
  this->Report = report.str();
  auto note = vtkSmartPointer<vtkStringArray>::New();
  note->SetName("shadelab_normals");
  note->InsertNextValue(this->Report);
  output->GetFieldData()->AddArray(note);
  return 1;
}

void vtkShadingNormalsFilter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "KeepInputNormals: " << this->KeepInputNormals << "\n";
  os << indent << "WeldCoincidentPoints: " << this->WeldCoincidentPoints << "\n";
  os << indent << "WeldTolerance: " << this->WeldTolerance << "\n";
  os << indent << "FeatureAngle: " << this->FeatureAngle << "\n";
  os << indent << "SplitSharpEdges: " << this->SplitSharpEdges << "\n";
  os << indent << "SplitAngle: " << this->SplitAngle << "\n";
  os << indent << "OrientOutward: " << this->OrientOutward << "\n";
  os << indent << "NormalsName: " << this->NormalsName << "\n";
}
