#include "vtkShadingNormalsFilter.h"

#include "NormalOrientation.h"
#include "PointNormals.h"
#include "ShadeLabFieldNotes.h"
#include "ShadeLabLargeArrays.h"
#include "ShadeLabMeshChecks.h"
#include "ShadeLabMeshExtent.h"
#include "ShadeLabMeshPolygons.h"
#include "ShadeLabPieceNormals.h"
#include "ShadeLabWholeMesh.h"

#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkCellArrayIterator.h"
#include "vtkDataArrayRange.h"
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

#include <numeric>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <type_traits>

vtkStandardNewMacro(vtkShadingNormalsFilter);
static_assert(std::is_same<vtkIdType, shadelab::PointId>::value, "ShadeLab needs VTK built with 64-bit ids");

namespace
{
/// For the candidate points (ascending), the id of the point that stands for each one's
/// position (an empty map: no two share one): with a tolerance of 0, exactly coincident
/// points (shadelab::coincidentPointMap); otherwise each candidate not yet placed stands for
/// those within the tolerance of it, in id order (vtkStaticPointLocator over the candidates;
/// VTK 9.1's MergePoints with a tolerance is not used: run after run on spot.obj it left 1 to
/// 10 positions split among several ids, differently each time).
template<typename PointAt>
std::vector<shadelab::PointId> positionMergeMap(
  vtkPolyData* mesh, const std::vector<shadelab::PointId>& candidates, double relativeTolerance, PointAt pointAt)
{
  const std::size_t pointCount = static_cast<std::size_t>(mesh->GetNumberOfPoints());
  if (relativeTolerance == 0.0)
  {
    return shadelab::coincidentPointMap(candidates, pointCount, pointAt);
  }
  vtkNew<vtkPoints> positions;
  positions->SetDataTypeToDouble();
  for (shadelab::PointId id : candidates)
  {
    const glm::dvec3 p = pointAt(id);
    positions->InsertNextPoint(p.x, p.y, p.z);
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(positions);
  vtkNew<vtkStaticPointLocator> locator;
  locator->SetDataSet(cloud);
  locator->BuildLocator();
  std::vector<shadelab::PointId> map(pointCount);
  std::iota(map.begin(), map.end(), shadelab::PointId(0));
  std::vector<bool> placed(candidates.size(), false);
  const double radius = relativeTolerance * mesh->GetLength();
  vtkNew<vtkIdList> near;
  for (std::size_t k = 0; k < candidates.size(); ++k)
  {
    if (placed[k])
    {
      continue;
    }
    locator->FindPointsWithinRadius(radius, positions->GetPoint(static_cast<vtkIdType>(k)), near);
    for (vtkIdType n = 0; n < near->GetNumberOfIds(); ++n)
    {
      const std::size_t j = static_cast<std::size_t>(near->GetId(n));
      if (!placed[j])
      {
        map[static_cast<std::size_t>(candidates[j])] = candidates[k];
        placed[j] = true;
      }
    }
  }
  return map;
}

/// flipped[k] for every polygon that vtkPolyDataNormals' consistency pass turns round, on the
/// welded mesh (so that seams join the pieces they separate).
std::vector<bool> polygonsToTurn(
  vtkPolyData* mesh, const shadelab::MeshPolygons& polygons, const std::vector<shadelab::PointId>& mergeMap)
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

/// What find(first, last) returns for each block of count items, joined in block order.
template<typename T, typename Find>
std::vector<T> foundInBlocks(std::size_t count, Find find)
{
  std::vector<std::vector<T>> found(shadelab::blockCount(count));
  shadelab::forEachBlock(
    count, [&](std::size_t b, std::size_t first, std::size_t last) { found[b] = find(first, last); });
  std::vector<T> joined;
  for (const std::vector<T>& block : found)
  {
    joined.insert(joined.end(), block.begin(), block.end());
  }
  return joined;
}

/// Computed point normals: what was found and done, for the report.
struct ComputedNormals
{
  vtkSmartPointer<vtkFloatArray> normals;
  std::size_t inconsistentEdges = 0;
  shadelab::WeldSummary weld;
  shadelab::NormalOrientation orientation; // of the polygons' winding, which the normals follow
  bool turnedOutward = false;              // written flipped, the winding pointing in
};

/// The polygons' sums at their corners (shadelab::sumAtCorners), in polygon order: one
/// thread, because the pass is bound by memory (scattering to points), and two threads
/// scattering into two sets of sums ran no faster here.
template<typename Real>
shadelab::CornerSums sumAtCorners(const shadelab::PolygonList& list, const std::vector<bool>& flipped,
  std::size_t pointCount, const shadelab::MeshExtent& extent, shadelab::PackedPoints<Real> points)
{
  shadelab::CornerSums sums(pointCount, extent.centre, extent.radius);
  shadelab::sumAtCorners(list, 0, list.count, flipped, points, sums);
  return sums;
}

/// The indices of the polygons with an edge between two of the points, in order: a vtkSMPTools
/// loop over fixed blocks of polygons, whose findings are joined in block order.
std::vector<std::size_t> polygonsBetween(
  const shadelab::PolygonList& list, const std::vector<shadelab::PointId>& points, std::size_t pointCount)
{
  if (points.empty())
  {
    return {};
  }
  std::vector<std::uint8_t> listed(pointCount, 0);
  for (shadelab::PointId id : points)
  {
    listed[static_cast<std::size_t>(id)] = 1;
  }
  return foundInBlocks<std::size_t>(list.count,
    [&](std::size_t first, std::size_t last)
    {
      std::vector<std::size_t> found;
      for (std::size_t k = first; k < last; ++k)
      {
        if (shadelab::hasEdgeBetween(list, k, listed))
        {
          found.push_back(k);
        }
      }
      return found;
    });
}

/// Computes area-weighted point normals (PointNormals.h) from the points' raw memory.
struct NormalsWorker
{
  vtkPolyData* mesh;
  const shadelab::MeshPolygons& polygons;
  bool weld;
  double weldTolerance;
  double featureAngle;
  bool orientOutward;
  ComputedNormals computed;

  template<typename Real>
  void operator()(shadelab::PackedPoints<Real> pointAt)
  {
    const shadelab::PolygonList& list = polygons.list();
    const std::size_t pointCount = static_cast<std::size_t>(mesh->GetNumberOfPoints());
    const shadelab::MeshExtent extent = shadelab::meshExtentOf(mesh);
    shadelab::CornerSums sums = sumAtCorners(list, {}, pointCount, extent, pointAt);
    // Only points whose edges do not pair up can be copies on a seam or on an inconsistent
    // edge: the rest of the mesh needs nothing more.
    const std::vector<shadelab::PointId> candidates = foundInBlocks<shadelab::PointId>(pointCount,
      [&](std::size_t first, std::size_t last) { return shadelab::unbalancedPoints(sums.points, first, last); });
    const std::vector<shadelab::PointId> mergeMap =
      weld ? positionMergeMap(mesh, candidates, weldTolerance, pointAt) : std::vector<shadelab::PointId>{};
    const shadelab::PolygonSubset aroundCandidates(list, polygonsBetween(list, candidates, pointCount));
    const shadelab::PolygonEdges edges(aroundCandidates.list(), mergeMap);
    computed.inconsistentEdges = edges.inconsistentCount();
    std::vector<bool> flipped;
    if (computed.inconsistentEdges > 0)
    {
      // The rare, slow case: reorder the windings over the whole mesh, and sum again.
      flipped = polygonsToTurn(mesh, polygons, mergeMap);
      sums = sumAtCorners(list, flipped, pointCount, extent, pointAt);
    }
    if (!mergeMap.empty())
    {
      std::vector<bool> flippedAround;
      for (std::size_t k = 0; !flipped.empty() && k < aroundCandidates.list().count; ++k)
      {
        flippedAround.push_back(flipped[aroundCandidates.original(k)]);
      }
      shadelab::weldCopies(sums.points, edges,
        shadelab::polygonAreaVectors(aroundCandidates.list(), flippedAround, pointAt), mergeMap, featureAngle,
        &computed.weld);
    }
    computed.orientation = sums.winding.result();
    computed.turnedOutward = orientOutward && computed.orientation.pointsInward();
    const double sign = computed.turnedOutward ? -1.0 : 1.0; // so that they need no second pass
    computed.normals = vtkSmartPointer<vtkFloatArray>::New();
    computed.normals->SetNumberOfComponents(3);
    if (!shadelab::allocateTuples<float>(computed.normals, static_cast<vtkIdType>(pointCount)))
    {
      throw std::bad_alloc();
    }
    float* out = computed.normals->GetPointer(0);
    vtkSMPTools::For(0, static_cast<vtkIdType>(pointCount),
      [&](vtkIdType begin, vtkIdType end)
      {
        for (std::size_t i = static_cast<std::size_t>(begin); i < static_cast<std::size_t>(end); ++i)
        {
          const glm::dvec3 n = sign * shadelab::unitNormal(sums.points[i].area);
          out[3 * i] = static_cast<float>(n.x);
          out[3 * i + 1] = static_cast<float>(n.y);
          out[3 * i + 2] = static_cast<float>(n.z);
        }
      });
  }
};

ComputedNormals computeNormals(vtkPolyData* mesh, const shadelab::MeshPolygons& polygons, bool weld,
  double weldTolerance, double featureAngle, bool orientOutward)
{
  NormalsWorker worker{ mesh, polygons, weld, weldTolerance, featureAngle, orientOutward, {} };
  shadelab::visitPackedPoints(mesh->GetPoints()->GetData(), worker);
  return worker.computed;
}

void flipInPlace(vtkDataArray* normals)
{
  for (auto tuple : vtk::DataArrayTupleRange<3>(normals))
  {
    tuple[0] = -tuple[0];
    tuple[1] = -tuple[1];
    tuple[2] = -tuple[2];
  }
}

vtkSmartPointer<vtkDataArray> flippedCopy(vtkDataArray* normals)
{
  vtkSmartPointer<vtkDataArray> copy = vtk::TakeSmartPointer(normals->NewInstance());
  copy->DeepCopy(normals);
  flipInPlace(copy);
  return copy;
}

bool usableNormals(vtkDataArray* normals, vtkIdType pointCount)
{
  return normals && normals->GetNumberOfComponents() == 3 && normals->GetNumberOfTuples() == pointCount;
}

/// Whether some piece with points has normals of its own (a collective call), as the whole mesh
/// put together would.
bool piecesHaveNormals(vtkMultiProcessController* controller, vtkPolyData* piece)
{
  return !shadelab::everyProcessHolds(
    controller, piece->GetNumberOfPoints() == 0 || !piece->GetPointData()->GetNormals());
}

/// The report's sentence on computed normals (named `name`).
std::string computedNormalsSentence(bool hadNormals, const std::string& name, std::size_t inconsistentEdges,
  const shadelab::WeldSummary& weld, double featureAngle)
{
  std::ostringstream sentence;
  sentence << (hadNormals ? "Replaced the mesh's point normals" : "The mesh has no point normals")
           << ": computed area-weighted ones and added them as '" << name << "'";
  if (inconsistentEdges > 0)
  {
    sentence << ", after turning round the polygons wound against their neighbours (" << inconsistentEdges
             << " edges were traversed twice in one direction)";
  }
  if (weld.sharedPositions > 0)
  {
    sentence << "; " << weld.sharedPositions << " positions are shared by several points: averaged "
             << weld.pointsAveraged << " points with their copies";
    if (weld.pointsKeptApart > 0)
    {
      sentence << ", kept " << weld.pointsKeptApart << " apart at edges sharper than " << featureAngle << " degrees";
    }
  }
  sentence << ".";
  return sentence.str();
}

/// The report's sentence on normals that point into the mesh ("" for others), having flipped the
/// output's normals outward where orientOutward asks and they were not computed so
/// (turnedOutward); the input's own (inputNormals) are flipped in a copy.
std::string orientationSentence(const shadelab::NormalOrientation& orientation, bool orientOutward, vtkPolyData* output,
  vtkDataArray* inputNormals, bool turnedOutward)
{
  if (!orientation.pointsInward())
  {
    return "";
  }
  std::ostringstream sentence;
  sentence << " They point into the mesh (closure " << orientation.closure << ", flux " << orientation.flux << ")";
  if (!orientOutward)
  {
    sentence << "; kept as they are, because orienting them outward is off.";
    return sentence.str();
  }
  vtkDataArray* normals = output->GetPointData()->GetNormals();
  if (normals && normals == inputNormals)
  {
    output->GetPointData()->SetNormals(flippedCopy(normals)); // the input's own pass through
  }
  else if (normals && !turnedOutward)
  {
    flipInPlace(normals);
  }
  sentence << "; flipped them outward.";
  return sentence.str();
}

}

vtkShadingNormalsFilter::vtkShadingNormalsFilter()
  : Controller(vtkMultiProcessController::GetGlobalController())
{
}

int vtkShadingNormalsFilter::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0]);
  vtkPolyData* output = vtkPolyData::GetData(outputVector);
  this->Report.clear();
  const bool alone = !this->Controller || this->Controller->GetNumberOfProcesses() == 1;
  // Splitting changes the points, so pieces read in one process are taken as they are then.
  if (!shadelab::isPieceOfSplitMesh(this->Controller, input) || (this->SplitSharpEdges && alone))
  {
    return this->ComputeNormals(input, output);
  }
  if (this->SplitSharpEdges) // the same on every process
  {
    vtkErrorMacro("splitting sharp edges adds points, which the pieces of a mesh split over processes cannot "
                  "share: split them before the mesh is split");
    return 0;
  }
  const int onPieces = this->ComputeOnPieces(input, output);
  if (onPieces != needsWholeMesh)
  {
    return onPieces;
  }
  // Computed once, on the first process, which sends each piece its points' normals. The
  // pieces' own normals come only where they are kept; the report says whether there were any.
  const bool hadNormals = piecesHaveNormals(this->Controller, input);
  const int succeeded = shadelab::computeOnPiece(this->Controller, this, input, output, this->KeepInputNormals,
    shadelab::WholeMeshOn::FirstProcess,
    [this, hadNormals](vtkPolyData* mesh, vtkPolyData* result, const std::vector<vtkIdType>*)
    { return this->ComputeNormals(mesh, result, hadNormals) == 1; });
  auto* note = vtkStringArray::SafeDownCast(output->GetFieldData()->GetAbstractArray(shadelab::normalsNoteName));
  this->Report = succeeded && note && note->GetNumberOfValues() > 0 ? note->GetValue(0) : "";
  return succeeded;
}

int vtkShadingNormalsFilter::ComputeOnPieces(vtkPolyData* piece, vtkPolyData* output)
{
  const shadelab::PieceLayout layout = shadelab::pieceLayout(this->Controller, piece);
  if (!layout.problem.empty() || !layout.putTogether || (this->WeldCoincidentPoints && this->WeldTolerance > 0.0) ||
    !shadelab::everyProcessHolds(this->Controller, piece->GetNumberOfStrips() == 0))
  {
    return needsWholeMesh; // which says what is wrong, or is one process's piece, or welds by distance, or has strips
  }
  const bool empty = piece->GetNumberOfPoints() == 0;
  vtkDataArray* inputNormals = piece->GetPointData()->GetNormals();
  const bool keepNormals = this->KeepInputNormals &&
    shadelab::everyProcessHolds(this->Controller, empty || usableNormals(inputNormals, piece->GetNumberOfPoints()));
  bool succeeded = true;
  std::ostringstream report;
  shadelab::NormalOrientation orientation;
  bool turnedOutward = false;
  output->ShallowCopy(piece);
  try
  {
    const shadelab::SharedPoints shared = shadelab::sharedPointsOf(this->Controller, layout.pieceIds);
    std::string problem = shadelab::differingSharedValues(
      this->Controller, shared, empty ? nullptr : piece->GetPoints()->GetData(), "positions");
    if (problem.empty() && keepNormals)
    {
      problem = shadelab::differingSharedValues(this->Controller, shared, inputNormals, "normals");
    }
    if (!problem.empty()) // the same on every process
    {
      throw std::runtime_error(problem);
    }
    if (keepNormals)
    {
      // The name the single process would see: the first piece's, as the whole mesh's gathering takes it.
      const std::string name =
        shadelab::firstText(this->Controller, inputNormals && inputNormals->GetName() ? inputNormals->GetName() : "");
      report << "Using the mesh's point normals '" << name << "'.";
      orientation = shadelab::storedNormalsOrientation(piece, inputNormals, this->Controller);
    }
    else
    {
      const shadelab::PieceNormals computed = shadelab::computePieceNormals(
        this->Controller, piece, layout, shared, this->WeldCoincidentPoints, this->OrientOutward);
      if (!computed.computed)
      {
        output->Initialize(); // for the whole mesh's computation to fill, or leave empty where it fails
        return needsWholeMesh;
      }
      const bool anyNormals = piecesHaveNormals(this->Controller, piece);
      computed.normals->SetName(this->NormalsName.c_str());
      output->GetPointData()->SetNormals(computed.normals);
      report << computedNormalsSentence(anyNormals, this->NormalsName, 0, {}, this->FeatureAngle);
      orientation = computed.orientation;
      turnedOutward = computed.turnedOutward;
    }
  }
  catch (const std::exception& error) // thrown on every process alike
  {
    vtkErrorMacro(<< error.what());
    succeeded = false;
  }
  if (succeeded)
  {
    report << orientationSentence(orientation, this->OrientOutward, output, inputNormals, turnedOutward);
    this->Report = report.str();
    shadelab::addFieldNote(output, shadelab::normalsNoteName, { this->Report });
  }
  else
  {
    output->Initialize();
  }
  return succeeded ? 1 : 0;
}

int vtkShadingNormalsFilter::ComputeNormals(vtkPolyData* input, vtkPolyData* output, std::optional<bool> hadNormals)
{
  if (input->GetNumberOfPoints() == 0)
  {
    return 1; // an empty mesh has no normals to prepare
  }
  const std::string cells = this->CheckCells ? shadelab::cellProblem(input) : "";
  if (!cells.empty())
  {
    vtkErrorMacro(<< cells);
    return 0;
  }
  std::ostringstream report;
  std::optional<shadelab::NormalOrientation> orientation; // of computed normals, found with them
  bool turnedOutward = false;                             // computed normals, written so
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
    const ComputedNormals computed = computeNormals(input, shadelab::MeshPolygons(input), this->WeldCoincidentPoints,
      this->WeldTolerance, this->FeatureAngle, this->OrientOutward);
    computed.normals->SetName(this->NormalsName.c_str());
    orientation = computed.orientation;
    turnedOutward = computed.turnedOutward;
    normals = computed.normals;
    output->GetPointData()->SetNormals(computed.normals);
    report << computedNormalsSentence(hadNormals.value_or(inputNormals != nullptr), this->NormalsName,
      computed.inconsistentEdges, computed.weld, this->FeatureAngle);
  }
  if (!orientation)
  {
    orientation = shadelab::storedNormalsOrientation(output, normals);
  }
  report << orientationSentence(*orientation, this->OrientOutward, output, inputNormals, turnedOutward);
  this->Report = report.str();
  shadelab::addFieldNote(output, shadelab::normalsNoteName, { this->Report });
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
  os << indent << "CheckCells: " << this->CheckCells << "\n";
  os << indent << "NormalsName: " << this->NormalsName << "\n";
}
