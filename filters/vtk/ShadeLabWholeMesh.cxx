#include "ShadeLabWholeMesh.h"

#include "ShadeLabPieceExchange.h"

#include "ShadeLabFieldNotes.h"
#include "ShadeLabMeshChecks.h"
#include "ShadeLabMeshExtent.h"

#include "vtkAlgorithm.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommunicator.h"
#include "vtkDataArray.h"
#include "vtkDataSetAttributes.h"
#include "vtkFieldData.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkMultiProcessController.h"
#include "vtkMultiProcessStream.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <atomic>
#include <cstring>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace shadelab
{
namespace
{
std::atomic<std::size_t> wholeMeshCount{ 0 };
constexpr int numberingTag = 7341;

/// The raw bytes of an array's tuples (its components interleaved, as VTK stores them).
std::vector<char> bytesOf(vtkDataArray* values)
{
  std::vector<char> bytes;
  if (values && values->GetNumberOfTuples() > 0)
  {
    const char* first = static_cast<const char*>(values->GetVoidPointer(0));
    bytes.assign(first, first + values->GetNumberOfValues() * values->GetDataTypeSize());
  }
  return bytes;
}

std::vector<vtkIdType> idsOf(vtkDataArray* ids)
{
  std::vector<vtkIdType> values(static_cast<std::size_t>(ids ? ids->GetNumberOfTuples() : 0));
  if (vtkIdTypeArray* typed = vtkIdTypeArray::FastDownCast(ids))
  {
    std::copy_n(typed->GetPointer(0), values.size(), values.begin());
  }
  else
  {
    for (std::size_t i = 0; i < values.size(); ++i)
    {
      values[i] = static_cast<vtkIdType>(ids->GetTuple1(static_cast<vtkIdType>(i)));
    }
  }
  return values;
}

/// One kind of cells (polygons or strips) of every piece: each cell's order key (its global
/// cell id), its size and its points' global ids.
struct GatheredCells
{
  std::vector<vtkIdType> keys, sizes, corners;
};

GatheredCells cellsOf(vtkCellArray* cells, vtkIdType firstCellId, vtkDataArray* cellGlobalIds,
  vtkUnsignedCharArray* ghosts, vtkIdType keyBase, const std::vector<vtkIdType>& pointGlobalIds)
{
  GatheredCells mine;
  vtkIdType size = 0;
  const vtkIdType* ids = nullptr;
  vtkIdType cellId = firstCellId;
  for (cells->InitTraversal(); cells->GetNextCell(size, ids); ++cellId)
  {
    if (ghosts && (ghosts->GetValue(cellId) & vtkDataSetAttributes::DUPLICATECELL))
    {
      continue; // another piece owns it
    }
    mine.keys.push_back(cellGlobalIds ? static_cast<vtkIdType>(cellGlobalIds->GetTuple1(cellId)) : keyBase + cellId);
    mine.sizes.push_back(size);
    for (vtkIdType i = 0; i < size; ++i)
    {
      mine.corners.push_back(pointGlobalIds[static_cast<std::size_t>(ids[i])]);
    }
  }
  return mine;
}

/// Every piece's cells of one kind, in the order of their keys, with their points' global ids
/// (their indices in the whole mesh), where they are gathered `where` (nullptr elsewhere); or a
/// problem.
vtkSmartPointer<vtkCellArray> wholeCells(vtkMultiProcessController* controller, const GatheredCells& mine,
  WholeMeshOn where, const char* kind, std::string& problem)
{
  const std::vector<vtkIdType> keys = gathered(controller, mine.keys, where);
  const std::vector<vtkIdType> sizes = gathered(controller, mine.sizes, where);
  const std::vector<vtkIdType> corners = gathered(controller, mine.corners, where);
  if (!receives(controller, where))
  {
    return nullptr;
  }
  try // where the first process alone gathers, it alone could fail: it says so in `problem`
  {
    std::vector<vtkIdType> firstCorner(sizes.size() + 1, 0);
    std::partial_sum(sizes.begin(), sizes.end(), firstCorner.begin() + 1);
    std::vector<std::size_t> order(keys.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });
    vtkNew<vtkIdTypeArray> offsets, connectivity;
    offsets->SetNumberOfValues(static_cast<vtkIdType>(order.size() + 1));
    connectivity->SetNumberOfValues(static_cast<vtkIdType>(corners.size()));
    if (offsets->GetNumberOfValues() != static_cast<vtkIdType>(order.size() + 1) ||
      connectivity->GetNumberOfValues() != static_cast<vtkIdType>(corners.size()))
    {
      throw std::bad_alloc();
    }
    vtkIdType written = 0;
    for (std::size_t k = 0; k < order.size(); ++k)
    {
      const std::size_t c = order[k];
      if (k > 0 && keys[c] == keys[order[k - 1]])
      {
        std::ostringstream text;
        text << "the global cell id " << keys[c] << " is on two pieces' " << kind
             << ": mark the copies as ghost cells (vtkGhostType) or give each cell its own id";
        problem = text.str();
        return nullptr;
      }
      offsets->SetValue(static_cast<vtkIdType>(k), written);
      for (vtkIdType i = firstCorner[c]; i < firstCorner[c + 1]; ++i)
      {
        connectivity->SetValue(written++, corners[static_cast<std::size_t>(i)]);
      }
    }
    offsets->SetValue(static_cast<vtkIdType>(order.size()), written);
    auto cells = vtkSmartPointer<vtkCellArray>::New();
    cells->SetData(offsets, connectivity);
    return cells;
  }
  catch (const std::bad_alloc&)
  {
    problem = std::string("out of memory putting the pieces' ") + kind + " together";
    return nullptr;
  }
}

/// An array rebuilt in whole-mesh order from every piece's tuples (gathered as bytes `where`:
/// nullptr elsewhere), or a problem where two pieces give one point different values.
vtkSmartPointer<vtkDataArray> wholeTuples(vtkMultiProcessController* controller, vtkDataArray* mine, WholeMeshOn where,
  int dataType, const std::vector<vtkIdType>& allGlobalIds, vtkIdType wholeCount, const char* what,
  std::string& problem)
{
  const std::vector<char> bytes = gathered(controller, bytesOf(mine), where);
  if (!receives(controller, where))
  {
    return nullptr;
  }
  // Where the first process alone gathers, it alone could run out of memory: it says so in
  // `problem`, which every process then learns.
  const std::string outOfMemory = std::string("out of memory putting the pieces' ") + what + " together";
  auto whole = vtk::TakeSmartPointer(vtkDataArray::CreateDataArray(dataType));
  whole->SetNumberOfComponents(3);
  whole->SetNumberOfTuples(wholeCount);
  std::vector<bool> filled;
  try
  {
    filled.assign(static_cast<std::size_t>(wholeCount), false);
  }
  catch (const std::bad_alloc&)
  {
    filled.clear();
  }
  if (whole->GetNumberOfTuples() != wholeCount || filled.size() != static_cast<std::size_t>(wholeCount))
  {
    problem = outOfMemory;
    return nullptr;
  }
  const std::size_t tupleBytes = 3 * static_cast<std::size_t>(whole->GetDataTypeSize());
  char* target = static_cast<char*>(whole->GetVoidPointer(0));
  for (std::size_t i = 0; i < allGlobalIds.size(); ++i)
  {
    const std::size_t w = static_cast<std::size_t>(allGlobalIds[i]);
    const char* source = bytes.data() + i * tupleBytes;
    if (filled[w] && std::memcmp(target + w * tupleBytes, source, tupleBytes) != 0)
    {
      std::ostringstream text;
      text << "the point with global id " << allGlobalIds[i] << " has two different " << what
           << " in two pieces: the pieces are not of one mesh, or their global ids are wrong";
      problem = text.str();
      return nullptr;
    }
    std::memcpy(target + w * tupleBytes, source, tupleBytes);
    filled[w] = true;
  }
  return whole;
}

/// What sharedValue is given for an array a piece lacks.
constexpr int absent = 1000; // above every VTK type code

/// The one value (above 0) every non-empty piece has (a type code, say): 0 where every piece is
/// empty, -1 where they differ.
int sharedValue(vtkMultiProcessController* controller, bool empty, int value)
{
  int shared = 0;
  for (int v : allGather(controller, std::vector<int>{ empty ? 0 : value }))
  {
    if (v != 0 && shared != 0 && v != shared)
    {
      return -1;
    }
    shared = v != 0 ? v : shared;
  }
  return shared;
}

/// The point arrays a computation on the whole mesh wrote into `made`: those the gathered mesh
/// (`brought`) has not, and its normals where they are new (computed, or a flipped copy).
std::vector<vtkDataArray*> writtenArrays(vtkPointData* made, vtkPointData* brought)
{
  std::vector<vtkDataArray*> written;
  for (int a = 0; a < made->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = made->GetArray(a);
    if (!brought->HasArray(array->GetName()) || (array == made->GetNormals() && array != brought->GetNormals()))
    {
      written.push_back(array);
    }
  }
  return written;
}

/// The piece with what was computed for its points on the whole mesh: arrays of a value per
/// piece point as they are, normals of the whole mesh (computed, or flipped) at the piece's
/// points, and the field data's notes.
void keepPiece(const WholeMesh& whole, vtkPolyData* computed, vtkPolyData* piece, vtkPolyData* output)
{
  output->ShallowCopy(piece);
  vtkPointData* made = computed->GetPointData();
  for (vtkDataArray* array : writtenArrays(made, whole.mesh->GetPointData()))
  {
    if (array == made->GetNormals())
    {
      output->GetPointData()->SetNormals(tuplesAt(array, whole.pieceIds));
    }
    else
    {
      output->GetPointData()->AddArray(array);
    }
  }
  output->GetFieldData()->PassData(computed->GetFieldData());
}

/// A written array as the first process describes it to the others.
struct SentArray
{
  int type = 0;
  int components = 0;
  std::string name;
  bool isNormals = false;
};

/// The arrays a computation wrote, for the other processes: each one's type, components, name
/// and whether it is the normals (SentArray).
void describeArrays(const std::vector<vtkDataArray*>& written, vtkPointData* made, vtkMultiProcessStream& described)
{
  described << static_cast<int>(written.size());
  for (vtkDataArray* array : written)
  {
    described << array->GetDataType() << array->GetNumberOfComponents()
              << std::string(array->GetName() ? array->GetName() : "") << (array == made->GetNormals());
  }
}

/// A computation's field notes (its string arrays), for the other processes: each one's name
/// and lines.
void describeNotes(vtkFieldData* fields, vtkMultiProcessStream& described)
{
  std::vector<vtkStringArray*> notes;
  for (int a = 0; a < fields->GetNumberOfArrays(); ++a)
  {
    if (auto* note = vtkStringArray::SafeDownCast(fields->GetAbstractArray(a)))
    {
      notes.push_back(note);
    }
  }
  described << static_cast<int>(notes.size());
  for (vtkStringArray* note : notes)
  {
    described << std::string(note->GetName() ? note->GetName() : "")
              << static_cast<vtkTypeInt64>(note->GetNumberOfValues());
    for (vtkIdType i = 0; i < note->GetNumberOfValues(); ++i)
    {
      described << note->GetValue(i);
    }
  }
}

/// The notes describeNotes described, added to output's field data.
void addDescribedNotes(vtkMultiProcessStream& described, vtkPolyData* output)
{
  int noteCount = 0;
  described >> noteCount;
  for (int n = 0; n < noteCount; ++n)
  {
    std::string name;
    vtkTypeInt64 lineCount = 0;
    described >> name >> lineCount;
    std::vector<std::string> lines(static_cast<std::size_t>(lineCount));
    for (std::string& line : lines)
    {
      described >> line;
    }
    addFieldNote(output, name.c_str(), lines);
  }
}

/// The tuples the first process sends of `array` (its own, nullptr elsewhere): every piece's,
/// piece after piece, as each piece's ids list them. Allocates `mine`, the piece's array, where
/// there are several processes. Either may fail on one process: all learn it first, and throw.
vtkSmartPointer<vtkDataArray> tuplesToSend(vtkMultiProcessController* controller, const SentArray& sent,
  vtkDataArray* array, const std::vector<vtkIdType>& everyPieceIds, vtkIdType pointCount, vtkDataArray* mine)
{
  vtkSmartPointer<vtkDataArray> everyPiece;
  bool ready = true;
  try
  {
    everyPiece = isFirstProcess(controller) ? tuplesAt(array, everyPieceIds) : nullptr;
    if (processCount(controller) > 1) // alone, the first process keeps its tuples as they are
    {
      mine->SetName(sent.name.c_str());
      mine->SetNumberOfComponents(sent.components);
      mine->SetNumberOfTuples(pointCount);
      ready = mine->GetNumberOfTuples() == pointCount;
    }
  }
  catch (const std::bad_alloc&)
  {
    ready = false;
  }
  if (!everyProcessHolds(controller, ready))
  {
    throw std::runtime_error("out of memory sending the pieces their '" + sent.name + "'");
  }
  return everyPiece;
}

/// The piece's tuples of an array the first process computed on the whole mesh (`array` there,
/// nullptr elsewhere), a collective call; pieceSizes has every piece's point count.
vtkSmartPointer<vtkDataArray> pieceTuples(vtkMultiProcessController* controller, const SentArray& sent,
  vtkDataArray* array, const std::vector<vtkIdType>& everyPieceIds, const std::vector<vtkIdType>& pieceSizes,
  vtkIdType pointCount)
{
  auto mine = vtk::TakeSmartPointer(vtkDataArray::CreateDataArray(sent.type));
  const vtkIdType tupleBytes = sent.components * mine->GetDataTypeSize();
  const vtkIdType sentTuples = std::accumulate(pieceSizes.begin(), pieceSizes.end(), vtkIdType(0));
  if (sentTuples * tupleBytes > std::numeric_limits<int>::max()) // every process finds the same
  {
    throw std::overflow_error("the mesh is too large to send its pieces their '" + sent.name +
      "': " + std::to_string(sentTuples * tupleBytes) + " bytes in one exchange, more than MPI's 2^31 - 1");
  }
  const vtkSmartPointer<vtkDataArray> everyPiece =
    tuplesToSend(controller, sent, array, everyPieceIds, pointCount, mine);
  if (processCount(controller) == 1)
  {
    return everyPiece;
  }
  std::vector<vtkIdType> lengths(pieceSizes.size()), offsets(pieceSizes.size(), 0);
  std::transform(pieceSizes.begin(), pieceSizes.end(), lengths.begin(), [&](vtkIdType n) { return n * tupleBytes; });
  std::partial_sum(lengths.begin(), lengths.end() - 1, offsets.begin() + 1);
  if (controller->ScatterV(everyPiece ? static_cast<const char*>(everyPiece->GetVoidPointer(0)) : nullptr,
        static_cast<char*>(mine->GetVoidPointer(0)), lengths.data(), offsets.data(), pointCount * tupleBytes, 0) == 0)
  {
    throw std::runtime_error("sending the pieces their '" + sent.name + "' failed (MPI's ScatterV)");
  }
  return mine;
}

/// What the first process computed on the whole mesh, sent to every piece (a collective call):
/// the piece with each point array the computation wrote (not those gathered), its points'
/// tuples only, and the computation's field notes. Throws on every process alike.
void shareFromFirst(vtkMultiProcessController* controller, const WholeMesh& whole, vtkPolyData* computed,
  vtkPolyData* piece, vtkPolyData* output)
{
  const bool first = isFirstProcess(controller);
  // What is sent: the written arrays' descriptions, then the field notes.
  std::vector<vtkDataArray*> written;
  vtkMultiProcessStream described;
  if (first)
  {
    written = writtenArrays(computed->GetPointData(), whole.mesh->GetPointData());
    describeArrays(written, computed->GetPointData(), described);
    describeNotes(computed->GetFieldData(), described);
  }
  if (processCount(controller) > 1 && controller->Broadcast(described, 0) == 0)
  {
    throw std::runtime_error("sending the pieces what was computed failed (MPI's broadcast)");
  }
  const vtkIdType pointCount = piece->GetNumberOfPoints();
  const std::vector<vtkIdType> pieceSizes = allGather(controller, std::vector<vtkIdType>{ pointCount });
  output->ShallowCopy(piece);
  int arrayCount = 0;
  described >> arrayCount;
  for (int a = 0; a < arrayCount; ++a)
  {
    SentArray sent;
    described >> sent.type >> sent.components >> sent.name >> sent.isNormals;
    vtkDataArray* array = first ? written[static_cast<std::size_t>(a)] : nullptr;
    const vtkSmartPointer<vtkDataArray> mine =
      pieceTuples(controller, sent, array, whole.everyPieceIds, pieceSizes, pointCount);
    if (sent.isNormals)
    {
      output->GetPointData()->SetNormals(mine);
    }
    else
    {
      output->GetPointData()->AddArray(mine);
    }
  }
  addDescribedNotes(described, output);
}

/// What `work` returns, or false where it throws (out of memory, say), reported through
/// `filter`: a process that fails alone must still reach the outcome every process agrees on.
template<typename Work>
bool guarded(vtkAlgorithm* filter, const Work& work)
{
  try
  {
    return work();
  }
  catch (const std::exception& error)
  {
    vtkErrorWithObjectMacro(filter, << error.what());
    return false;
  }
}

/// The pieces' layout (PieceLayout, whose pieceIds are the piece's points' global ids), with
/// what the gathering needs of it. Where the pieces are not put together, the mesh is `piece`
/// where wholeIsPiece, and nothing elsewhere.
struct Layout : PieceLayout
{
  bool wholeIsPiece = false;
  std::vector<vtkIdType> allGlobalIds; // every piece's, piece after piece, where the mesh is gathered
  vtkIdType wholeCount = 0;
  int pointType = 0;
  int normalsState = 0; // the normals' shared type, or `absent`
};

/// Why the piece's point data cannot be put together with the others' ("" where it can): the
/// global ids (globalIdsState, as the pieces share it) and the normals' shape.
std::string pointDataProblem(vtkPolyData* piece, bool withNormals, int piecesWithPoints, int globalIdsState)
{
  const vtkIdType pointCount = piece->GetNumberOfPoints();
  vtkDataArray* pointGlobalIds = piece->GetPointData()->GetGlobalIds();
  vtkDataArray* normals = piece->GetPointData()->GetNormals();
  std::ostringstream problem;
  if (globalIdsState != 1)
  {
    problem << "the mesh is in " << piecesWithPoints << " pieces but "
            << (globalIdsState == absent ? "their points have" : "some pieces' points have")
            << " no global ids (vtkGlobalIds), which say which points of different pieces are one: "
               "give them global ids (VTK's vtkGenerateGlobalIds), or read pieces written by shadelab, which have them";
  }
  else if (pointGlobalIds && pointGlobalIds->GetNumberOfTuples() != pointCount)
  {
    problem << "a piece has " << pointGlobalIds->GetNumberOfTuples() << " global point ids for " << pointCount
            << " points";
  }
  else if (withNormals && normals &&
    (normals->GetNumberOfTuples() != pointCount || normals->GetNumberOfComponents() != 3))
  {
    problem << "the point normals '" << (normals->GetName() ? normals->GetName() : "") << "' of a piece have "
            << normals->GetNumberOfTuples() << " tuples of " << normals->GetNumberOfComponents()
            << " components: there must be one 3-component normal per point (" << pointCount << ")";
  }
  return problem.str();
}

/// The type of the points and of the normals that every non-empty piece has, into layout (a
/// collective call); a problem where they differ.
std::string sharedTypesProblem(
  vtkMultiProcessController* controller, vtkPolyData* piece, bool withNormals, Layout& layout)
{
  const bool empty = piece->GetNumberOfPoints() == 0;
  vtkDataArray* points = empty ? nullptr : piece->GetPoints()->GetData();
  vtkDataArray* normals = piece->GetPointData()->GetNormals();
  layout.pointType = sharedValue(controller, empty, points ? points->GetDataType() : 0);
  layout.normalsState =
    withNormals ? sharedValue(controller, empty, normals ? normals->GetDataType() : absent) : absent;
  if (layout.pointType < 0)
  {
    return "the pieces store their points in different types: read them alike";
  }
  if (layout.normalsState < 0)
  {
    return "some pieces have point normals and others do not, or in other types: give every piece the same";
  }
  return "";
}

/// Why the pieces' cells cannot be put in the mesh's order (a collective call), or "".
std::string cellIdsProblem(vtkMultiProcessController* controller, vtkPolyData* piece, int piecesWithPoints)
{
  const bool empty = piece->GetNumberOfPoints() == 0;
  const int cellIdsState = sharedValue(controller, empty, piece->GetCellData()->GetGlobalIds() ? 1 : absent);
  if (cellIdsState == 1 || piecesWithPoints <= 1)
  {
    return "";
  }
  // Sums over a point's polygons are taken in the polygons' order, which only the ids keep.
  return std::string(cellIdsState < 0 ? "some pieces' cells have global ids and others' do not"
                                      : "the pieces' cells have no global ids") +
    " (vtkGlobalIds), which put the polygons in the mesh's order: give every piece's cells global ids";
}

/// Why the piece's own cells cannot be gathered ("" where they can): their arrays' sizes, and
/// point ids out of range, which the gathering would follow.
std::string pieceCellsProblem(vtkPolyData* piece)
{
  vtkCellData* cellData = piece->GetCellData();
  for (vtkDataArray* cellArray :
    { cellData->GetGlobalIds(), cellData->GetArray(vtkDataSetAttributes::GhostArrayName()) })
  {
    if (cellArray && cellArray->GetNumberOfTuples() != piece->GetNumberOfCells())
    {
      std::ostringstream problem;
      problem << "a piece's cell array '" << (cellArray->GetName() ? cellArray->GetName() : "") << "' has "
              << cellArray->GetNumberOfTuples() << " values for " << piece->GetNumberOfCells() << " cells";
      return problem.str();
    }
  }
  return cellProblem(piece);
}

/// Why the piece cannot be put together with the others ("" where it can), the first problem
/// found; the types the pieces share go into layout. Every process makes the same collective
/// calls, whatever it found.
std::string pieceProblem(vtkMultiProcessController* controller, vtkPolyData* piece, bool withNormals,
  int piecesWithPoints, int globalIdsState, Layout& layout)
{
  const std::string pointData = pointDataProblem(piece, withNormals, piecesWithPoints, globalIdsState);
  const std::string types = sharedTypesProblem(controller, piece, withNormals, layout);
  const std::string cellIds = cellIdsProblem(controller, piece, piecesWithPoints);
  for (const std::string& problem : { pointData, types, cellIds })
  {
    if (!problem.empty())
    {
      return problem;
    }
  }
  return pieceCellsProblem(piece);
}

/// Whether every number 0 to largest is among the processes' ids (a collective call): each
/// process marks the numbers it owns (ownerOf) that the others send it, so that none holds more
/// than its own ids and a bit for each number it owns.
bool everyNumberUpTo(vtkMultiProcessController* controller, const std::vector<vtkIdType>& ids, vtkIdType largest)
{
  const int processes = processCount(controller);
  std::vector<std::vector<vtkIdType>> sent(static_cast<std::size_t>(processes));
  agreedStep(controller,
    [&]
    {
      for (vtkIdType id : ids)
      {
        sent[ownerOf(id, processes)].push_back(id);
      }
    });
  const std::size_t me = static_cast<std::size_t>(controller ? controller->GetLocalProcessId() : 0);
  const vtkIdType owned =
    largest >= static_cast<vtkIdType>(me) ? (largest - static_cast<vtkIdType>(me)) / processes + 1 : 0;
  std::vector<bool> present(static_cast<std::size_t>(owned), false);
  for (const std::vector<vtkIdType>& from : swapWithEvery(controller, std::move(sent), numberingTag))
  {
    for (vtkIdType id : from)
    {
      present[static_cast<std::size_t>(id / processes)] = true;
    }
  }
  return everyProcessHolds(controller, std::find(present.begin(), present.end(), false) == present.end());
}

/// Every piece's point ids, into layout (a collective call), and what they say of how the pieces
/// lie: put together where they number the mesh's points 0 to n-1. Where idsOn is given, every
/// piece's ids are also gathered there (for gathering the whole mesh there); otherwise each
/// process holds its own.
void numberPoints(
  vtkMultiProcessController* controller, vtkDataArray* pointGlobalIds, Layout& layout, std::optional<WholeMeshOn> idsOn)
{
  layout.pieceIds = idsOf(pointGlobalIds);
  const std::vector<vtkIdType>& ids = layout.pieceIds;
  // Each process's smallest and largest id and its count, in one exchange.
  const std::vector<vtkIdType> summaries = allGather(controller,
    std::vector<vtkIdType>{
      ids.empty() ? std::numeric_limits<vtkIdType>::max() : *std::min_element(ids.begin(), ids.end()),
      ids.empty() ? std::numeric_limits<vtkIdType>::min() : *std::max_element(ids.begin(), ids.end()),
      static_cast<vtkIdType>(ids.size()) });
  vtkIdType wholeSmallest = std::numeric_limits<vtkIdType>::max(), wholeLargest = std::numeric_limits<vtkIdType>::min();
  vtkIdType total = 0;
  for (std::size_t p = 0; p + 2 < summaries.size(); p += 3)
  {
    wholeSmallest = std::min(wholeSmallest, summaries[p]);
    wholeLargest = std::max(wholeLargest, summaries[p + 1]);
    total += summaries[p + 2];
  }
  // The ids must number the mesh's points 0 to n-1: each point's id is its index in the whole
  // mesh, and seeds its samples as its index does in one process. Fewer ids than numbers cannot
  // hold them all (and a number far past them is not marked).
  layout.wholeCount = wholeLargest + 1;
  const bool numbered = wholeSmallest >= 0 && wholeLargest < total && everyNumberUpTo(controller, ids, wholeLargest);
  if (idsOn)
  {
    layout.allGlobalIds = gathered(controller, ids, *idsOn);
  }
  if (!numbered && processCount(controller) == 1)
  {
    // Ids of some other numbering (one piece's file, read alone): the piece is the mesh.
    layout.wholeIsPiece = true;
  }
  else if (!numbered)
  {
    std::ostringstream text;
    text << "the pieces' global point ids run from " << wholeSmallest << " to " << wholeLargest
         << " but do not number the points 0 to n-1, each at least once: give the points global ids that do";
    layout.problem = text.str(); // every process finds the same
  }
  else
  {
    layout.putTogether = true;
  }
}

Layout layoutOf(
  vtkMultiProcessController* controller, vtkPolyData* piece, bool withNormals, std::optional<WholeMeshOn> idsOn)
{
  Layout layout;
  vtkDataArray* pointGlobalIds = piece->GetPointData()->GetGlobalIds();
  const bool empty = piece->GetNumberOfPoints() == 0;
  const std::vector<int> withPoints = allGather(controller, std::vector<int>{ empty ? 0 : 1 });
  const int piecesWithPoints = std::accumulate(withPoints.begin(), withPoints.end(), 0);
  const int globalIdsState = sharedValue(controller, empty, pointGlobalIds ? 1 : absent);
  if (piecesWithPoints == 0)
  {
    return layout;
  }
  if (piecesWithPoints == 1 && globalIdsState == absent)
  {
    // One process read the mesh (a serial reader in pvbatch): its piece is the whole.
    layout.wholeIsPiece = !empty;
    return layout;
  }
  layout.problem =
    firstText(controller, pieceProblem(controller, piece, withNormals, piecesWithPoints, globalIdsState, layout));
  if (layout.problem.empty())
  {
    numberPoints(controller, pointGlobalIds, layout, idsOn);
  }
  return layout;
}

WholeMesh gatherPieces(vtkMultiProcessController* controller, vtkPolyData* piece, bool withNormals, WholeMeshOn where)
{
  Layout layout = layoutOf(controller, piece, withNormals, where);
  WholeMesh whole;
  whole.problem = layout.problem;
  if (!layout.problem.empty() || !layout.putTogether)
  {
    whole.mesh = layout.wholeIsPiece ? piece : nullptr;
    return whole;
  }
  const bool here = receives(controller, where);
  std::string found;
  vtkNew<vtkPolyData> mesh;
  vtkDataArray* points = piece->GetNumberOfPoints() > 0 ? piece->GetPoints()->GetData() : nullptr;
  vtkSmartPointer<vtkDataArray> coordinates = wholeTuples(
    controller, points, where, layout.pointType, layout.allGlobalIds, layout.wholeCount, "positions", found);
  if (coordinates)
  {
    vtkNew<vtkPoints> wholePoints;
    wholePoints->SetData(coordinates);
    mesh->SetPoints(wholePoints);
  }
  vtkDataArray* normals = piece->GetPointData()->GetNormals();
  if (layout.normalsState != absent)
  {
    vtkSmartPointer<vtkDataArray> wholeNormals = wholeTuples(
      controller, normals, where, layout.normalsState, layout.allGlobalIds, layout.wholeCount, "normals", found);
    // The name the single process would see: the first piece's (every process takes part).
    const std::string name = firstText(controller, normals && normals->GetName() ? normals->GetName() : "");
    if (wholeNormals)
    {
      wholeNormals->SetName(name.c_str());
      mesh->GetPointData()->SetNormals(wholeNormals);
    }
  }
  const vtkIdType keyBase = static_cast<vtkIdType>(controller ? controller->GetLocalProcessId() : 0) << 40;
  const vtkIdType firstPolygon = piece->GetNumberOfVerts() + piece->GetNumberOfLines();
  vtkDataArray* cellGlobalIds = piece->GetCellData()->GetGlobalIds();
  auto* ghosts =
    vtkUnsignedCharArray::SafeDownCast(piece->GetCellData()->GetArray(vtkDataSetAttributes::GhostArrayName()));
  const GatheredCells polygons =
    cellsOf(piece->GetPolys(), firstPolygon, cellGlobalIds, ghosts, keyBase, layout.pieceIds);
  const GatheredCells strips = cellsOf(
    piece->GetStrips(), firstPolygon + piece->GetNumberOfPolys(), cellGlobalIds, ghosts, keyBase, layout.pieceIds);
  // Every process makes both gathers, whatever it found, so that none waits for the others.
  std::string cellsFound;
  vtkSmartPointer<vtkCellArray> wholePolygons = wholeCells(controller, polygons, where, "polygons", cellsFound);
  vtkSmartPointer<vtkCellArray> wholeStrips = wholeCells(controller, strips, where, "strips", cellsFound);
  // Where only the first process gathers, only it can find a problem: it tells the others.
  whole.problem = firstText(controller, !found.empty() ? found : cellsFound);
  if (!whole.problem.empty())
  {
    return whole;
  }
  whole.putTogether = true;
  whole.pieceIds = std::move(layout.pieceIds);
  if (!here)
  {
    return whole;
  }
  mesh->SetPolys(wholePolygons);
  if (wholeStrips->GetNumberOfCells() > 0)
  {
    mesh->SetStrips(wholeStrips);
  }
  whole.mesh = mesh;
  ++wholeMeshCount;
  if (where == WholeMeshOn::FirstProcess)
  {
    whole.everyPieceIds = std::move(layout.allGlobalIds);
  }
  return whole;
}
}

bool isPieceOfSplitMesh(vtkMultiProcessController* controller, vtkPolyData* piece)
{
  // Several processes call alike; one process decides for itself.
  return processCount(controller) > 1 || piece->GetPointData()->GetGlobalIds() != nullptr;
}

WholeMesh gatherWholeMesh(
  vtkMultiProcessController* controller, vtkPolyData* piece, bool withNormals, WholeMeshOn where)
{
  try
  {
    return gatherPieces(controller, piece, withNormals, where);
  }
  catch (const std::exception& error) // too large for MPI, or no memory for the gathered mesh: alike everywhere
  {
    WholeMesh failed;
    failed.problem = error.what();
    return failed;
  }
}

PieceLayout pieceLayout(vtkMultiProcessController* controller, vtkPolyData* piece)
{
  try
  {
    return layoutOf(controller, piece, true, std::nullopt); // its PieceLayout part
  }
  catch (const std::exception& error) // the pieces' point ids too many for MPI, or no memory for them: alike everywhere
  {
    PieceLayout failed;
    failed.problem = error.what();
    return failed;
  }
}

int computeOnPiece(vtkMultiProcessController* controller, vtkAlgorithm* filter, vtkPolyData* piece, vtkPolyData* output,
  bool withNormals, WholeMeshOn where, const PieceComputation& compute)
{
  const WholeMesh whole = gatherWholeMesh(controller, piece, withNormals, where);
  if (!whole.problem.empty())
  {
    vtkErrorWithObjectMacro(filter, << whole.problem);
    return 0;
  }
  if (where == WholeMeshOn::FirstProcess && whole.putTogether)
  {
    vtkNew<vtkPolyData> computed;
    const bool succeeded = !whole.mesh || guarded(filter, [&] { return compute(whole.mesh, computed, nullptr); });
    if (agreedOutcome(controller, filter, output, succeeded) == 0)
    {
      return 0;
    }
    try
    {
      shareFromFirst(controller, whole, computed, piece, output);
    }
    catch (const std::exception& error) // too large for MPI, or no memory for the arrays sent: alike everywhere
    {
      output->Initialize();
      vtkErrorWithObjectMacro(filter, << error.what());
      return 0;
    }
    return 1;
  }
  const bool succeeded = guarded(filter,
    [&]
    {
      if (!whole.mesh || !whole.putTogether) // the whole mesh, or an empty piece beside it
      {
        return compute(piece, output, nullptr);
      }
      vtkNew<vtkPolyData> computed;
      if (!compute(whole.mesh, computed, &whole.pieceIds))
      {
        return false;
      }
      keepPiece(whole, computed, piece, output);
      return true;
    });
  return agreedOutcome(controller, filter, output, succeeded);
}

std::size_t wholeMeshesPutTogetherHere()
{
  return wholeMeshCount;
}

vtkSmartPointer<vtkDataArray> tuplesAt(vtkDataArray* values, const std::vector<vtkIdType>& ids)
{
  vtkNew<vtkIdList> list;
  list->SetNumberOfIds(static_cast<vtkIdType>(ids.size()));
  std::copy(ids.begin(), ids.end(), list->GetPointer(0));
  auto taken = vtk::TakeSmartPointer(values->NewInstance());
  taken->SetName(values->GetName());
  taken->SetNumberOfComponents(values->GetNumberOfComponents());
  taken->SetNumberOfTuples(list->GetNumberOfIds());
  values->GetTuples(list, taken);
  return taken;
}
}
