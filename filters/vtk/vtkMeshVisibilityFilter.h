/**
 * @class vtkMeshVisibilityFilter
 * @brief What a mesh hides from itself: each shadowed light's visibility, and ambient
 * occlusion, by casting rays against its own triangles (Embree 3).
 *
 * Reads points, polygons (and triangle strips) and point normals. For every light of the scene
 * with shadows (shadelab::NamedLight::shadows) adds "<ArrayPrefix><light>_visibility": 1 where
 * the mesh does not block the segment to the light (a distant light's ray goes to infinity),
 * 0 where it does or where the light is behind the surface. For an area light or an
 * environment map it casts a ray per sample of the light's estimator instead and keeps which
 * ones the mesh hides, a bit per sample, in "<ArrayPrefix><light>_hidden_samples" (uint64),
 * from which vtkLocalReflectanceFilter estimates the visible integrals and the visibility
 * (docs/formulas.md section 11.6); that array is internal and never in the shading's output.
 * A light drawn to a target (SetDrawnLights) is estimated here instead, round by round. With the scene's ambient
 * occlusion, adds "ambient_occlusion", its "ambient_occlusion_std_error" and, if asked for,
 * "bent_normal" and "sky_view_factor" (docs/formulas.md section 20). The arrays are float32
 * (but the internal hidden samples' words and estimates of lights drawn to a target).
 * "visibility_flags" has FlagHiddenByOwnTriangle (64) where a shadowed light that the normal
 * faces is hidden by a triangle around the vertex. Every input array passes through. The
 * BVH is built once and kept while the input's points and polygons are the same objects,
 * unmodified (a new scene or material reuses it); GetReport() and the field data array
 * "shadelab_visibility" say how many rays were cast and how long the BVH and the rays took.
 *
 * The scene, set as vtkShadeLabSceneFilter says, gives the lights (those with shadows count)
 * and the ambient occlusion settings; a scene in the mesh's frame is placed on the input.
 *
 * SetAbortExecute (ParaView's Cancel) stops the rays between blocks of a hundredth of the points,
 * leaving an empty output and no error; a piece of a split mesh runs to its end, as its
 * processes must all take part in its exchanges.
 *
 * Results are the same bits on any number of threads: each vertex's samples are a hash of its
 * id, and a ray's answer does not depend on the order the BVH is traversed in. A piece of a
 * mesh split over processes (see SetController) casts its points' rays against the whole
 * mesh's triangles, with the samples of their ids in the whole mesh (ShadeLabWholeMesh.h).
 */
#ifndef vtkMeshVisibilityFilter_h
#define vtkMeshVisibilityFilter_h

#include "ShadeLabFiltersModule.h"
#include "vtkMultiProcessController.h" // the controller, a member
#include "vtkShadeLabSceneFilter.h"

#include "DistributedLight.h"   // LobeModel, a member's
#include "SequentialSampling.h" // SampleTargets, a member's
#include "vtkSmartPointer.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

class vtkCellArray;
class vtkPoints;
namespace shadelab
{
class OccluderMesh;
}

class SHADELABFILTERS_EXPORT vtkMeshVisibilityFilter : public vtkShadeLabSceneFilter
{
public:
  static vtkMeshVisibilityFilter* New();
  vtkTypeMacro(vtkMeshVisibilityFilter, vtkShadeLabSceneFilter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The most threads the rays use (0, the default: as vtkSMPTools is set; at most 1024), as
  /// vtkLocalReflectanceFilter's. Embree builds the BVH on threads of its own.
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);

  /// Prepended to the visibility arrays' names (default "").
  vtkSetMacro(ArrayPrefix, std::string);
  vtkGetMacro(ArrayPrefix, std::string);

  /// Also the bent normal, and the sky view factor (which casts as many rays again) with the
  /// ambient occlusion (defaults on).
  vtkSetMacro(ComputeBentNormal, bool);
  vtkGetMacro(ComputeBentNormal, bool);
  vtkBooleanMacro(ComputeBentNormal, bool);
  vtkSetMacro(ComputeSkyViewFactor, bool);
  vtkGetMacro(ComputeSkyViewFactor, bool);
  vtkBooleanMacro(ComputeSkyViewFactor, bool);

  /// Check the cells' offsets and point ids before using them (default on). Off only where
  /// the caller has checked the same cells already, as vtkLocalReflectanceFilter does before
  /// it runs this filter (12 ms on a mesh of 2.2M points).
  vtkSetMacro(CheckCells, bool);
  vtkGetMacro(CheckCells, bool);
  vtkBooleanMacro(CheckCells, bool);

  /// What the last run did, in one sentence.
  const std::string& GetReport() const { return this->Report; }

  /// How the shading draws an area light's or a map's samples where a tolerance's plan gives
  /// them targets (vtkLocalReflectanceFilter sets it): the targets, and the lobe whose integral
  /// the shading needs.
  struct DrawnLight
  {
    shadelab::SampleTargets targets;
    shadelab::LobeModel lobe;
  };
  /// Per scene light (empty, the default: none). A shadowed light with targets is estimated
  /// here, where its rays are: each vertex draws its samples in rounds, tracing each round's
  /// rays, until E and S meet their targets, and its E, S and visibility with their standard
  /// errors go into "<ArrayPrefix><light>_shadowed_terms" (float64, packTerms' rows, internal)
  /// instead of the hidden samples' bits.
  void SetDrawnLights(const std::vector<DrawnLight>& lights);
  const std::vector<DrawnLight>& GetDrawnLights() const { return this->DrawnLights; }

  /// Cast rays from these points only, by id (empty, the default: from every point); the
  /// output's arrays then hold a value for each listed point, in the list's order, with the
  /// samples of those ids (a tolerance's cost forecast, vtkLocalReflectanceFilter). Not on a
  /// split mesh, whose pieces list their own.
  void SetRayPointIds(const std::vector<vtkIdType>& ids);
  /// How long the last run's rays took, in seconds (the BVH's build not included).
  double GetRaySeconds() const { return this->RaySeconds; }

  /// The processes over which the mesh may be split, as vtkShadingNormalsFilter's (default:
  /// the global controller; nullptr: this process alone).
  vtkSetSmartPointerMacro(Controller, vtkMultiProcessController);
  vtkGetSmartPointerMacro(Controller, vtkMultiProcessController);

protected:
  vtkMeshVisibilityFilter();
  ~vtkMeshVisibilityFilter() override;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// RequestData within the filter's thread count.
  int CastRays(vtkInformationVector** inputVector, vtkInformationVector* outputVector);
  /// The rays from the points rayPoints lists (nullptr: every point) against input's triangles;
  /// output's arrays have a value for each of those points.
  int CastRaysFrom(vtkPolyData* input, vtkPolyData* output, const std::vector<vtkIdType>* rayPoints);

private:
  vtkMeshVisibilityFilter(const vtkMeshVisibilityFilter&) = delete;
  void operator=(const vtkMeshVisibilityFilter&) = delete;

  int NumberOfThreads = 0;
  std::string ArrayPrefix;
  bool ComputeBentNormal = true;
  bool ComputeSkyViewFactor = true;
  bool CheckCells = true;
  std::string Report;
  vtkSmartPointer<vtkMultiProcessController> Controller;
  std::vector<DrawnLight> DrawnLights;
  std::vector<vtkIdType> RayPointIds;
  double RaySeconds = 0;
  bool Stoppable = true; // by an abort (not a piece of a split mesh)

  /// The BVH of the mesh it was built for: the same point and cell objects, none modified since.
  struct BuiltOccluders
  {
    std::unique_ptr<shadelab::OccluderMesh> occluders;
    vtkSmartPointer<vtkPoints> points;
    vtkSmartPointer<vtkCellArray> polys, strips;
    vtkMTimeType builtAfter = 0; // the newest of their modification times when it was built
  };
  BuiltOccluders Built;
  /// Built's BVH when it is for this mesh, or a new one; says which in reused.
  const shadelab::OccluderMesh& OccludersFor(vtkPolyData* mesh, bool& reused);
  /// Why the rays cannot be cast from the input's points (its cells, its normals), or "".
  std::string InputProblem(vtkPolyData* input) const;
  /// The scene, placed on the input where it is in the mesh's frame and checked; nothing once
  /// why it cannot be used is reported as the filter's error.
  std::optional<shadelab::Scene> PlacedScene(vtkPolyData* input);
};

#endif
