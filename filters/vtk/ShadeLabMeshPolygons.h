#ifndef ShadeLabMeshPolygons_h
#define ShadeLabMeshPolygons_h
// A VTK mesh's polygons as the core reads them (shadelab::PolygonList), and its points as
// packed numbers (shadelab::PackedPoints): what the normals and the ray casting walk.
#include "OccluderMesh.h"
#include "PointNormals.h"

#include "vtkAOSDataArrayTemplate.h"
#include "vtkArrayDispatch.h"
#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkNew.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"

#include <algorithm>
#include <memory>
#include <vector>

class vtkPolyData;

namespace shadelab
{
/// The mesh's polygons, and its strips as triangles, as one shadelab::PolygonList. Uses the
/// mesh's own arrays where they are 64-bit and there are no strips, and a copy otherwise.
class MeshPolygons
{
public:
  explicit MeshPolygons(vtkPolyData* mesh);

  const PolygonList& list() const { return list_; }

  /// The same polygons as a vtkCellArray with their ids replaced by mergeMap's.
  vtkSmartPointer<vtkCellArray> welded(const std::vector<PointId>& mergeMap) const;

private:
  PolygonList list_;
  std::vector<PointId> offsets_;
  std::vector<PointId> connectivity_;
};

/// Hands a float or double array's memory to visit as PackedPoints (for vtkArrayDispatch).
template<typename Visit>
struct PackedPointsWorker
{
  Visit& visit;
  template<typename Real>
  void operator()(vtkAOSDataArrayTemplate<Real>* array)
  {
    visit(PackedPoints<Real>{ array->GetPointer(0) });
  }
};

/// Calls visit(PackedPoints<Real>) with the points' own memory where they are float or double
/// (x, y, z after one another), and with a double copy otherwise (integer points, say).
template<typename Visit>
void visitPackedPoints(vtkDataArray* points, Visit&& visit)
{
  using RealArrays = vtkTypeList::Create<vtkAOSDataArrayTemplate<float>, vtkAOSDataArrayTemplate<double>>;
  PackedPointsWorker<Visit> worker{ visit };
  if (!vtkArrayDispatch::DispatchByArray<RealArrays>::Execute(points, worker))
  {
    vtkNew<vtkDoubleArray> asDoubles;
    asDoubles->DeepCopy(points);
    worker(asDoubles.Get());
  }
}

/// Polygons and points are visited in fixed blocks of this many: the blocks do not depend on
/// the number of threads, so results kept per block and joined in block order are the same on
/// any number.
constexpr std::size_t blockSize = 1 << 16;

inline std::size_t blockCount(std::size_t count)
{
  return (count + blockSize - 1) / blockSize;
}

/// Calls visit(b, first, last) for each block b of count items (items first..last-1), in a
/// vtkSMPTools loop.
template<typename Visit>
void forEachBlock(std::size_t count, Visit visit)
{
  vtkSMPTools::For(0, static_cast<vtkIdType>(blockCount(count)),
    [&](vtkIdType firstBlock, vtkIdType endBlock)
    {
      for (std::size_t b = static_cast<std::size_t>(firstBlock); b < static_cast<std::size_t>(endBlock); ++b)
      {
        visit(b, b * blockSize, std::min(count, (b + 1) * blockSize));
      }
    });
}

/// The mesh's polygons and strips as an Embree BVH over its points (in their own precision).
std::unique_ptr<OccluderMesh> occludersOf(vtkPolyData* mesh);
}

#endif
