#include "ShadeLabPieceNormals.h"

#include "PointNormals.h"
#include "ShadeLabLargeArrays.h"
#include "ShadeLabMeshExtent.h"
#include "ShadeLabMeshPolygons.h"
#include "ShadeLabPieceExchange.h"

#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkDataSetAttributes.h"
#include "vtkMultiProcessController.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cstring>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <utility>

namespace shadelab
{
namespace
{
/// The polygons of a mesh or piece that it sums, in the order of their global cell ids (their
/// order in the whole mesh); a piece's ghost cells are left out, since the piece that owns them
/// sums them.
struct OwnPolygons
{
  /// Whether they are every polygon, in order; otherwise, their indices in the polygon list.
  bool everyPolygon = true;
  std::vector<std::size_t> indices;
  vtkDataArray* cellIds = nullptr; // the global cell ids, if any
  vtkIdType firstPolygon = 0;      // the polygons' first cell id

  /// Own polygon k's global cell id, or its cell id where there are none.
  vtkIdType keyOf(std::size_t k) const { return keyOfPolygon(everyPolygon ? k : indices[k]); }
  /// The same of the polygon at this index in the polygon list.
  vtkIdType keyOfPolygon(std::size_t index) const
  {
    const vtkIdType cell = firstPolygon + static_cast<vtkIdType>(index);
    return cellIds ? static_cast<vtkIdType>(cellIds->GetTuple1(cell)) : cell;
  }
};

OwnPolygons ownPolygons(vtkPolyData* mesh, std::size_t polygonCount)
{
  OwnPolygons own;
  own.firstPolygon = mesh->GetNumberOfVerts() + mesh->GetNumberOfLines();
  own.cellIds = mesh->GetCellData()->GetGlobalIds();
  auto* ghosts =
    vtkUnsignedCharArray::SafeDownCast(mesh->GetCellData()->GetArray(vtkDataSetAttributes::GhostArrayName()));
  auto isGhost = [&](std::size_t k)
  {
    return ghosts &&
      (ghosts->GetValue(own.firstPolygon + static_cast<vtkIdType>(k)) & vtkDataSetAttributes::DUPLICATECELL);
  };
  // Usually every polygon is the piece's own and in order: then nothing is kept.
  vtkIdType previous = 0;
  for (std::size_t k = 0; own.everyPolygon && k < polygonCount; ++k)
  {
    const vtkIdType key = own.keyOfPolygon(k);
    own.everyPolygon = !isGhost(k) && (k == 0 || previous < key);
    previous = key;
  }
  if (own.everyPolygon)
  {
    return own;
  }
  std::vector<std::pair<vtkIdType, std::size_t>> keyed;
  for (std::size_t k = 0; k < polygonCount; ++k)
  {
    if (!isGhost(k))
    {
      keyed.emplace_back(own.keyOfPolygon(k), k);
    }
  }
  std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& entry : keyed)
  {
    own.indices.push_back(entry.second);
  }
  return own;
}

/// The whole mesh's winding from every piece's exact sums (`mine`, this piece's), on every
/// process (a collective call).
NormalOrientation wholeMeshWinding(
  vtkMultiProcessController* controller, const NormalOrientationAccumulator& mine, const MeshExtent& extent)
{
  NormalOrientationAccumulator whole(extent.centre, extent.radius);
  const std::vector<long long> every = allGather(controller, mine.words());
  for (std::size_t p = 0; p + NormalOrientationAccumulator::wordCount <= every.size();
       p += NormalOrientationAccumulator::wordCount)
  {
    whole.addWords(every.data() + p);
  }
  return whole.result();
}

/// Some of a mesh's polygons as a list: the mesh's own list where they are all of them, in
/// order, and a copy otherwise.
class ChosenPolygons
{
public:
  ChosenPolygons(const PolygonList& all, const OwnPolygons& own)
  {
    subset_ = own.everyPolygon ? nullptr : std::make_unique<PolygonSubset>(all, own.indices);
    list_ = subset_ ? subset_->list() : all;
  }
  const PolygonList& list() const { return list_; }

private:
  std::unique_ptr<PolygonSubset> subset_;
  PolygonList list_;
};

/// The edge balance's signature of a piece's point: its global id's, as one process signs it.
struct GlobalIdSignature
{
  const vtkIdType* globalIds;
  std::uint64_t operator()(PointId id) const { return idSignature(globalIds[id]); }
};

constexpr int sharedIdsTag = 7311;
constexpr int cornerRecordsTag = 7313;
constexpr int cornerAreasTag = 7315;
constexpr int sharedValuesTag = 7317;
constexpr int sharedHoldersTag = 7319;

/// One polygon's corner at a point that other pieces hold (or that the piece holds twice): what
/// the polygon adds to the point's sums (CornerSum), and the polygon's place in the whole mesh's
/// order.
struct CornerRecord
{
  vtkIdType point; // its global id
  vtkIdType polygonKey;
  std::uint64_t balance;
  glm::dvec3 area;

  bool operator<(const CornerRecord& other) const
  {
    return point != other.point ? point < other.point : polygonKey < other.polygonKey;
  }
};

/// Calls visit(point) for each of the piece's points with this global id.
template<typename Visit>
void forEachPointWith(const SharedPoints& shared, vtkIdType globalId, Visit visit)
{
  for (auto found = shared.firstWith(globalId); found != shared.byGlobalId.end() && found->first == globalId; ++found)
  {
    visit(found->second);
  }
}

/// The piece's normals: the sums of its own polygons, completed at shared points with the other
/// pieces' polygons, then what only the whole mesh could change (welding, reordering) looked for
/// in the points whose edges do not pair up. A worker for visitPackedPoints.
struct PieceNormalsWorker
{
  vtkMultiProcessController* controller;
  vtkPolyData* piece;
  const std::vector<vtkIdType>& globalIds;
  const SharedPoints& shared;
  const MeshExtent& extent;
  bool weld;
  PieceNormals& result;
  CornerSumArray sums;

  template<typename Real>
  void operator()(PackedPoints<Real> pointAt)
  {
    std::unique_ptr<MeshPolygons> polygons;
    std::unique_ptr<ChosenPolygons> ownList;
    OwnPolygons own;
    std::unique_ptr<CornerSums> pieceSums;
    std::vector<CornerRecord> records;
    agreedStep(controller,
      [&]
      {
        polygons = std::make_unique<MeshPolygons>(piece);
        own = ownPolygons(piece, polygons->list().count);
        ownList = std::make_unique<ChosenPolygons>(polygons->list(), own);
        pieceSums = std::make_unique<CornerSums>(globalIds.size(), extent.centre, extent.radius);
        // What each polygon adds at a shared point, for the pieces that share it.
        const std::vector<std::uint8_t> isShared = sharedMarks();
        auto keepShared = [&](std::size_t k, PointId id, std::uint64_t balance, const glm::dvec3& area)
        {
          if (isShared[static_cast<std::size_t>(id)] != 0)
          {
            records.push_back({ globalIds[static_cast<std::size_t>(id)], own.keyOf(k), balance, area });
          }
        };
        sumAtCorners(ownList->list(), 0, ownList->list().count, {}, pointAt, *pieceSums,
          GlobalIdSignature{ globalIds.data() }, keepShared);
        sums = std::move(pieceSums->points);
      });
    // A polygon on two pieces: the whole mesh's gathering says which.
    if (completeSharedPoints(std::move(records)) && noMeshChangeNeeded(ownList->list(), own, pointAt))
    {
      result.computed = true;
      result.orientation = wholeMeshWinding(controller, pieceSums->winding, extent);
    }
  }

  /// For each of the piece's points, whether other pieces hold it or the piece holds it twice.
  std::vector<std::uint8_t> sharedMarks() const
  {
    std::vector<std::uint8_t> isShared(globalIds.size(), 0);
    auto mark = [&](vtkIdType id) { forEachPointWith(shared, id, [&](vtkIdType p) { isShared[std::size_t(p)] = 1; }); };
    for (const std::vector<vtkIdType>& ids : shared.withProcess)
    {
      std::for_each(ids.begin(), ids.end(), mark);
    }
    std::for_each(shared.repeated.begin(), shared.repeated.end(), mark);
    return isShared;
  }

  /// Replaces the sums at points other pieces hold (or the piece holds twice) with those over
  /// every piece's polygons, in the whole mesh's order, from the piece's records and those each
  /// other piece sends; false on every process where a polygon is on two pieces.
  bool completeSharedPoints(std::vector<CornerRecord> records)
  {
    const std::size_t ownCount = records.size();
    forEveryOtherProcess(controller,
      [&](int other)
      {
        const std::vector<vtkIdType>& with = shared.withProcess[static_cast<std::size_t>(other)];
        std::vector<vtkIdType> words;
        std::vector<double> areas;
        for (std::size_t r = 0; r < ownCount; ++r)
        {
          const CornerRecord& record = records[r];
          if (std::binary_search(with.begin(), with.end(), record.point))
          {
            words.insert(words.end(), { record.point, record.polygonKey, static_cast<vtkIdType>(record.balance) });
            areas.insert(areas.end(), { record.area.x, record.area.y, record.area.z });
          }
        }
        const std::vector<vtkIdType> theirWords = swapWith(controller, other, words, cornerRecordsTag);
        const std::vector<double> theirAreas = swapWith(controller, other, areas, cornerAreasTag);
        for (std::size_t r = 0; 3 * r + 2 < theirWords.size() && 3 * r + 2 < theirAreas.size(); ++r)
        {
          records.push_back(
            { theirWords[3 * r], theirWords[3 * r + 1], static_cast<std::uint64_t>(theirWords[3 * r + 2]),
              { theirAreas[3 * r], theirAreas[3 * r + 1], theirAreas[3 * r + 2] } });
        }
      });
    bool eachPolygonOnce = true;
    agreedStep(controller,
      [&]
      {
        std::sort(records.begin(), records.end());
        for (std::size_t r = 0; r < records.size();)
        {
          const vtkIdType point = records[r].point;
          CornerSum sum;
          for (const std::size_t first = r; r < records.size() && records[r].point == point; ++r)
          {
            eachPolygonOnce = eachPolygonOnce && !(r > first && records[r - 1].polygonKey == records[r].polygonKey);
            sum.area += records[r].area; // from zero in the polygons' order, as one process sums
            sum.edgeBalance += records[r].balance;
          }
          forEachPointWith(shared, point, [&](vtkIdType p) { sums[static_cast<std::size_t>(p)] = sum; });
        }
      });
    return everyProcessHolds(controller, eachPolygonOnce);
  }

  /// Whether the whole mesh needs no change that only it can settle: copies at one position
  /// among the points whose edges do not pair up (where welding is on), or an edge between
  /// them that two polygons traverse in one direction. Every process gathers those points and
  /// their polygons, and finds the same.
  template<typename Real>
  bool noMeshChangeNeeded(const PolygonList& list, const OwnPolygons& own, PackedPoints<Real> pointAt)
  {
    std::vector<std::uint8_t> unbalanced;
    std::vector<vtkIdType> candidateIds;
    std::vector<double> candidatePositions;
    agreedStep(controller,
      [&]
      {
        unbalanced.assign(globalIds.size(), 0);
        for (std::size_t i = 0; i < globalIds.size(); ++i)
        {
          if (sums[i].edgeBalance != 0)
          {
            unbalanced[i] = 1;
            candidateIds.push_back(globalIds[i]);
            const glm::dvec3 p = pointAt(static_cast<PointId>(i));
            candidatePositions.insert(candidatePositions.end(), { p.x, p.y, p.z });
          }
        }
      });
    if (weld && sharePositions(allGather(controller, candidateIds), allGather(controller, candidatePositions)))
    {
      return false; // copies to weld
    }
    std::vector<vtkIdType> polygonKeys, sizes, corners;
    agreedStep(controller,
      [&]
      {
        for (std::size_t k = 0; k < list.count; ++k)
        {
          if (hasEdgeBetween(list, k, unbalanced))
          {
            polygonKeys.push_back(own.keyOf(k));
            sizes.push_back(static_cast<vtkIdType>(list.size(k)));
            for (std::size_t i = 0; i < list.size(k); ++i)
            {
              corners.push_back(globalIds[static_cast<std::size_t>(list.ids(k)[i])]);
            }
          }
        }
      });
    return !inconsistentlyWound(
      allGather(controller, polygonKeys), allGather(controller, sizes), allGather(controller, corners));
  }

  /// Whether two different global ids among `ids` have one finite position (3 per id, in order).
  static bool sharePositions(const std::vector<vtkIdType>& ids, const std::vector<double>& positions)
  {
    std::vector<std::size_t> order(ids.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return ids[a] < ids[b]; });
    std::vector<PointId> distinct; // each global id once: a point several pieces hold is one
    for (std::size_t k = 0; k < order.size(); ++k)
    {
      if (k == 0 || ids[order[k]] != ids[order[k - 1]])
      {
        distinct.push_back(static_cast<PointId>(order[k]));
      }
    }
    std::sort(distinct.begin(), distinct.end());
    auto positionOf = [&](PointId i)
    {
      const double* p = positions.data() + 3 * i;
      return glm::dvec3(p[0], p[1], p[2]);
    };
    return !coincidentPointMap(distinct, ids.size(), positionOf).empty();
  }

  /// Whether two of the polygons (every piece's, keyed by global cell id, their corners by
  /// global point id) traverse an edge in one direction.
  static bool inconsistentlyWound(
    const std::vector<vtkIdType>& keys, const std::vector<vtkIdType>& sizes, const std::vector<vtkIdType>& corners)
  {
    std::vector<vtkIdType> firstCorner(sizes.size() + 1, 0);
    std::partial_sum(sizes.begin(), sizes.end(), firstCorner.begin() + 1);
    std::vector<std::size_t> order(keys.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });
    std::vector<PointId> offsets{ 0 }, connectivity;
    for (std::size_t k : order)
    {
      connectivity.insert(connectivity.end(), corners.begin() + firstCorner[k], corners.begin() + firstCorner[k + 1]);
      offsets.push_back(static_cast<PointId>(connectivity.size()));
    }
    const PolygonList polygons{ offsets.data(), connectivity.data(), order.size() };
    return PolygonEdges(polygons, {}).inconsistentCount() > 0;
  }
};

/// The orientation sums of the stored normals over some polygons.
struct OrientationWorker
{
  const PolygonList& polygons;
  NormalOrientationAccumulator sums;

  template<typename PointArray, typename NormalArray>
  void operator()(PointArray* pointArray, NormalArray* normalArray)
  {
    const auto points = vtk::DataArrayTupleRange<3>(pointArray);
    const auto normals = vtk::DataArrayTupleRange<3>(normalArray);
    auto vec = [](const auto& tuple) { return glm::dvec3(tuple[0], tuple[1], tuple[2]); };
    std::vector<NormalOrientationAccumulator> blockSums(blockCount(polygons.count), sums);
    forEachBlock(polygons.count,
      [&](std::size_t b, std::size_t first, std::size_t last)
      {
        for (std::size_t k = first; k < last; ++k)
        {
          const PointId* ids = polygons.ids(k);
          for (std::size_t i = 2; i < polygons.size(k); ++i)
          {
            blockSums[b].addTriangle(vec(points[ids[0]]), vec(points[ids[i - 1]]), vec(points[ids[i]]),
              vec(normals[ids[0]]), vec(normals[ids[i - 1]]), vec(normals[ids[i]]));
          }
        }
      });
    for (const NormalOrientationAccumulator& block : blockSums)
    {
      sums.add(block);
    }
  }
};
}

SharedPoints sharedPointsOf(vtkMultiProcessController* controller, const std::vector<vtkIdType>& globalIds)
{
  SharedPoints shared;
  const auto& sorted = shared.byGlobalId;
  // Each id goes, once, to the process that owns it (ownerOf), which tells each process that
  // holds it which others do: a process receives about its share of the ids, and for each point
  // it shares the processes that share it, on any number of processes.
  const int processes = processCount(controller);
  std::vector<std::vector<vtkIdType>> toOwners(static_cast<std::size_t>(processes));
  agreedStep(controller,
    [&]
    {
      for (std::size_t i = 0; i < globalIds.size(); ++i)
      {
        shared.byGlobalId.emplace_back(globalIds[i], static_cast<vtkIdType>(i));
      }
      std::sort(shared.byGlobalId.begin(), shared.byGlobalId.end());
      for (std::size_t k = 0; k < sorted.size(); ++k)
      {
        if (k == 0 || sorted[k].first != sorted[k - 1].first)
        {
          toOwners[ownerOf(sorted[k].first, processes)].push_back(sorted[k].first);
        }
        else if (shared.repeated.empty() || shared.repeated.back() != sorted[k].first)
        {
          shared.repeated.push_back(sorted[k].first);
        }
      }
    });
  std::vector<std::vector<vtkIdType>> received = swapWithEvery(controller, std::move(toOwners), sharedIdsTag);
  std::vector<std::vector<vtkIdType>> holdersTold(received.size()); // (id, another holder) pairs
  agreedStep(controller,
    [&]
    {
      forEachIdReceived(received,
        [&](vtkIdType id, const std::vector<std::pair<std::size_t, std::size_t>>& holders)
        {
          for (const auto& told : holders)
          {
            for (const auto& other : holders)
            {
              if (other.first != told.first)
              {
                holdersTold[told.first].insert(holdersTold[told.first].end(), { id, vtkIdType(other.first) });
              }
            }
          }
        });
      received = {}; // before the answers come in
    });
  const std::vector<std::vector<vtkIdType>> told = swapWithEvery(controller, std::move(holdersTold), sharedHoldersTag);
  agreedStep(controller,
    [&]
    {
      shared.withProcess.resize(static_cast<std::size_t>(processes));
      for (const std::vector<vtkIdType>& pairs : told)
      {
        for (std::size_t k = 0; k + 1 < pairs.size(); k += 2)
        {
          shared.withProcess[static_cast<std::size_t>(pairs[k + 1])].push_back(pairs[k]);
        }
      }
      for (std::vector<vtkIdType>& with : shared.withProcess)
      {
        std::sort(with.begin(), with.end());
      }
    });
  return shared;
}

std::string differingSharedValues(
  vtkMultiProcessController* controller, const SharedPoints& shared, vtkDataArray* values, const std::string& what)
{
  const int components = values ? values->GetNumberOfComponents() : 0;
  // Each global id's first point's tuple, for each of `ids`, as doubles (which hold a float's
  // bits exactly).
  auto tuplesOf = [&](const std::vector<vtkIdType>& ids)
  {
    std::vector<double> tuples;
    for (vtkIdType id : ids)
    {
      const auto at = shared.firstWith(id); // every id given is the piece's
      for (int c = 0; c < components; ++c)
      {
        tuples.push_back(values->GetComponent(at->second, c));
      }
    }
    return tuples;
  };
  auto differ = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) != 0; };
  std::string problem;
  auto say = [&](vtkIdType id)
  {
    if (problem.empty())
    {
      problem = "the point with global id " + std::to_string(id) + " has two different " + what +
        " in two pieces: the pieces are not of one mesh, or their global ids are wrong";
    }
  };
  forEveryOtherProcess(controller,
    [&](int other)
    {
      const std::vector<vtkIdType>& with = shared.withProcess[static_cast<std::size_t>(other)];
      const std::vector<double> mine = tuplesOf(with);
      const std::vector<double> theirs = swapWith(controller, other, mine, sharedValuesTag);
      for (std::size_t k = 0; k < mine.size() && k < theirs.size(); ++k)
      {
        if (differ(mine[k], theirs[k]))
        {
          say(with[k / static_cast<std::size_t>(components)]);
        }
      }
    });
  for (vtkIdType id : shared.repeated) // copies in the piece itself
  {
    const std::vector<double> first = tuplesOf({ id });
    forEachPointWith(shared, id,
      [&](vtkIdType p)
      {
        for (int c = 0; c < components; ++c)
        {
          if (differ(values->GetComponent(p, c), first[static_cast<std::size_t>(c)]))
          {
            say(id);
          }
        }
      });
  }
  return firstText(controller, problem);
}

PieceNormals computePieceNormals(vtkMultiProcessController* controller, vtkPolyData* piece, const PieceLayout& layout,
  const SharedPoints& shared, bool weld, bool orientOutward)
{
  PieceNormals result;
  const MeshExtent extent = wholeMeshExtent(controller, piece);
  PieceNormalsWorker worker{ controller, piece, layout.pieceIds, shared, extent, weld, result, {} };
  if (piece->GetNumberOfPoints() == 0)
  {
    worker(PackedPoints<double>{ nullptr }); // an empty piece takes part in every exchange
  }
  else
  {
    visitPackedPoints(piece->GetPoints()->GetData(), worker);
  }
  if (!result.computed)
  {
    return result;
  }
  result.turnedOutward = orientOutward && result.orientation.pointsInward();
  agreedStep(controller,
    [&]
    {
      const double sign = result.turnedOutward ? -1.0 : 1.0;
      const std::size_t pointCount = worker.sums.size();
      result.normals = vtkSmartPointer<vtkFloatArray>::New();
      result.normals->SetNumberOfComponents(3);
      if (!allocateTuples<float>(result.normals, static_cast<vtkIdType>(pointCount)))
      {
        throw std::bad_alloc();
      }
      float* out = result.normals->GetPointer(0);
      for (std::size_t i = 0; i < pointCount; ++i)
      {
        const glm::dvec3 n = sign * unitNormal(worker.sums[i].area);
        out[3 * i] = static_cast<float>(n.x);
        out[3 * i + 1] = static_cast<float>(n.y);
        out[3 * i + 2] = static_cast<float>(n.z);
      }
    });
  return result;
}

/// The orientation sums of the stored normals over the mesh's polygons (its own, leaving out
/// ghost cells, where leaveOutGhosts), added to `sums`.
NormalOrientationAccumulator ownPolygonsOrientation(
  vtkPolyData* mesh, vtkDataArray* normals, bool leaveOutGhosts, NormalOrientationAccumulator sums);

NormalOrientation storedNormalsOrientation(
  vtkPolyData* mesh, vtkDataArray* normals, vtkMultiProcessController* piecesOver)
{
  const MeshExtent extent = piecesOver ? wholeMeshExtent(piecesOver, mesh) : meshExtentOf(mesh);
  NormalOrientationAccumulator sums(extent.centre, extent.radius);
  agreedStep(piecesOver, [&] { sums = ownPolygonsOrientation(mesh, normals, piecesOver != nullptr, sums); });
  return piecesOver ? wholeMeshWinding(piecesOver, sums, extent) : sums.result();
}

NormalOrientationAccumulator ownPolygonsOrientation(
  vtkPolyData* mesh, vtkDataArray* normals, bool leaveOutGhosts, NormalOrientationAccumulator sums)
{
  if (mesh->GetNumberOfPoints() > 0)
  {
    const MeshPolygons polygons(mesh);
    // A whole mesh sums every polygon, in any order: the sums are exact.
    const std::unique_ptr<ChosenPolygons> own = leaveOutGhosts
      ? std::make_unique<ChosenPolygons>(polygons.list(), ownPolygons(mesh, polygons.list().count))
      : nullptr;
    OrientationWorker worker{ own ? own->list() : polygons.list(), sums };
    vtkDataArray* points = mesh->GetPoints()->GetData();
    using Reals = vtkArrayDispatch::Reals;
    if (!vtkArrayDispatch::Dispatch2ByValueType<Reals, Reals>::Execute(points, normals, worker))
    {
      worker(points, normals); // other value types, through the generic vtkDataArray API
    }
    sums = worker.sums;
  }
  return sums;
}
}
