/**
 * @class vtkLocalReflectanceFilter
 * @brief Per-vertex terms of the local reflectance model (ambient, Lambert, Phong,
 * Blinn-Phong, or VTK's own renderer) as point-data arrays.
 *
 * Reads points and point normals, evaluates a shadelab::Scene at every vertex, and adds the
 * requested arrays (see shadelab::selectArrays; docs/guide/arrays.md has the table). Every input array
 * passes through unchanged. Without point normals, normals are computed by
 * vtkShadingNormalsFilter (smooth, shared by coincident points, point ids and count unchanged)
 * and added as "<ArrayPrefix>Normals". Normals that point into a closed or nearly closed mesh
 * are used flipped unless OrientNormalsOutward is off; GetNormalsReport() says what happened,
 * and so does the output's field data array "shadelab_normals". Where the scene has shadows or
 * ambient occlusion, vtkMeshVisibilityFilter casts the rays first: each shadowed light's
 * visibility multiplies its diffuse and specular terms, and the occlusion the ambient term.
 *
 * The scene (lights, material and viewer) is set as vtkShadeLabSceneFilter says, and read and
 * checked by shadelab::sceneProblems when the filter runs; a scene that cannot be used is an
 * error with the command line's message.
 *
 * A piece of a mesh split over processes (see SetController) is shaded as its points are in
 * the whole mesh, bit for bit: the normals, the outward test, the extent that places the scene
 * and plans the tolerance, and the occluders are the whole mesh's, and each point's samples
 * are seeded by its id in it (ShadeLabWholeMesh.h).
 *
 * Progress moves through the normals, the rays and the shading. SetAbortExecute (ParaView's
 * Cancel) stops the run between blocks of the rays or the shading, leaving an empty output and
 * no error; a piece of a split mesh runs to its end, as its processes must all take part.
 */
#ifndef vtkLocalReflectanceFilter_h
#define vtkLocalReflectanceFilter_h

#include "ShadeLabFiltersModule.h"
#include "vtkCommand.h"                // MethodsChosenEvent
#include "vtkDataArraySelection.h"     // the scene's arrays, a member
#include "vtkMultiProcessController.h" // the controller, a member
#include "vtkNew.h"
#include "vtkShadeLabSceneFilter.h"

#include "MethodChoice.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace shadelab
{
struct HiddenSide;
struct MeshPieces;
}

class SHADELABFILTERS_EXPORT vtkLocalReflectanceFilter : public vtkShadeLabSceneFilter
{
public:
  static vtkLocalReflectanceFilter* New();
  vtkTypeMacro(vtkLocalReflectanceFilter, vtkShadeLabSceneFilter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Which arrays to compute, as shadelab::selectArrays reads them. Default: {"default"},
  /// the totals and the flags.
  void SetArraySelection(const std::vector<std::string>& selection);
  const std::vector<std::string>& GetArraySelection() const { return this->ArraySelection; }
  /// The same one entry at a time, for wrappers that cannot carry a vector (ParaView's):
  /// ClearArraySelection() then AddToArraySelection("key_diffuse") and so on.
  void ClearArraySelection();
  void AddToArraySelection(const std::string& entry);
  int GetNumberOfArraySelectionEntries() const { return static_cast<int>(this->ArraySelection.size()); }
  std::string GetArraySelectionEntry(int i) const;

  /// The scene's arrays as a list with a status each, for GUIs (ParaView's panel shows a box
  /// for each): every array the scene can produce, enabled where the selection computes it.
  /// It is filled when the pipeline's information is updated (UpdateInformation, or Update).
  /// Enabling or disabling arrays in it afterwards makes the enabled names the selection, at
  /// the next update; names the scene then lacks (after another scene) are left out of it.
  vtkDataArraySelection* GetAvailableArrays() { return this->AvailableArrays; }

  /// The most threads the filter's vtkSMPTools loops use (0, the default: as vtkSMPTools is
  /// set; at most 1024), through vtkSMPTools::LocalScope, which leaves VTK's own setting as it
  /// was. Embree builds the BVH for shadows and occlusion on threads of its own.
  vtkSetClampMacro(NumberOfThreads, int, 0, 1024);
  vtkGetMacro(NumberOfThreads, int);

  /// With ColorByArray on, the material's colour comes from the input's point array
  /// MaterialColorArray instead of the scene's kd (and ka, which follows it; in the vtk_pbr
  /// model the base colour, scaled by its largest component, which stands for the PBR
  /// property's Diffuse): 3- or 4-component
  /// colours as they are, a 1-component field through MaterialColorMap
  /// (shadelab::colorMaterialBy; docs/guide/scene-files.md). Off (the default): the scene's
  /// material. (Two properties, so that ParaView's panel can switch back to the scene's.)
  vtkSetMacro(ColorByArray, bool);
  vtkGetMacro(ColorByArray, bool);
  vtkBooleanMacro(ColorByArray, bool);
  vtkSetMacro(MaterialColorArray, std::string);
  vtkGetMacro(MaterialColorArray, std::string);
  /// The colour map of a field in MaterialColorArray: "cool to warm" (the default, as ParaView's
  /// default preset), "rainbow" or "grayscale", spanning the field's range.
  vtkSetMacro(MaterialColorMap, std::string);
  vtkGetMacro(MaterialColorMap, std::string);

  /// Prepended to every array name written, to keep clear of names the input already has.
  vtkSetMacro(ArrayPrefix, std::string);
  vtkGetMacro(ArrayPrefix, std::string);

  /// Arithmetic and output arrays in float32 (vtkAlgorithm::SINGLE_PRECISION, the default)
  /// or float64 (vtkAlgorithm::DOUBLE_PRECISION).
  vtkSetClampMacro(OutputPrecision, int, SINGLE_PRECISION, DOUBLE_PRECISION);
  vtkGetMacro(OutputPrecision, int);

  /// The largest absolute error allowed in any shaded value (diffuse, specular, totals).
  /// 0, the default, means exact methods in OutputPrecision. Above 0 the filter chooses, by
  /// shadelab::chooseMethods, the cheapest precision and per-light approximations (a point
  /// light as distant, a cheaper pow) whose predicted errors fit in it; OutputPrecision is then
  /// not used. GetMethodReport() and the field data array shadelab_methods say what it chose.
  vtkSetMacro(Tolerance, double);
  vtkGetMacro(Tolerance, double);

  /// Explicit methods, one per scene light (empty, the default: all exact), used when the
  /// tolerance is 0: for comparing methods side by side, as `shadelab-bench --charts` does.
  void SetLightMethods(const std::vector<shadelab::LightMethod>& methods);
  const std::vector<shadelab::LightMethod>& GetLightMethods() const { return this->LightMethods; }

  /// Fired under a tolerance once the methods are chosen and, where they sample, their cost
  /// forecast, before the rays and the shading: GetMethodPlan() then says what the run will
  /// do and about what it will cost (`shadelab shade` prints it then).
  static constexpr unsigned long MethodsChosenEvent = vtkCommand::UserEvent + 1;

  /// What the last run chose under the tolerance, with its predicted errors; empty when the
  /// tolerance is 0. Its describe() lines are the field data array shadelab_methods.
  const std::optional<shadelab::MethodPlan>& GetMethodPlan() const { return this->MethodPlan; }
  /// After a run under a tolerance: a line per area light or map with vertices whose samples
  /// stopped at their maximum short of their target (also in shadelab_methods, after the plan).
  const std::vector<std::string>& GetSamplingReport() const { return this->SamplingReport; }

  /// Flip normals that point into a closed or nearly closed mesh (default on).
  vtkSetMacro(OrientNormalsOutward, bool);
  vtkGetMacro(OrientNormalsOutward, bool);
  vtkBooleanMacro(OrientNormalsOutward, bool);

  /// Computed normals are shared by points at one position unless their polygons meet at an
  /// edge sharper than FeatureAngle degrees (vtkShadingNormalsFilter; defaults on and 80).
  vtkSetMacro(WeldCoincidentPoints, bool);
  vtkGetMacro(WeldCoincidentPoints, bool);
  vtkBooleanMacro(WeldCoincidentPoints, bool);
  vtkSetClampMacro(FeatureAngle, double, 0.0, 180.0);
  vtkGetMacro(FeatureAngle, double);
  /// How far apart points at "one position" may be, as a fraction of the bounding box's
  /// diagonal (vtkShadingNormalsFilter; default 0, the same coordinates).
  vtkSetClampMacro(WeldTolerance, double, 0.0, 0.1);
  vtkGetMacro(WeldTolerance, double);

  /// What the last run did about normals, in one or two sentences.
  const std::string& GetNormalsReport() const { return this->NormalsReport; }

  /// What the last run's rays did (vtkMeshVisibilityFilter), or "" without shadows and occlusion.
  const std::string& GetVisibilityReport() const { return this->VisibilityReport; }

  /// What the last run's interreflection did (vtkInterreflectionFilter), or "" without it.
  const std::string& GetInterreflectionReport() const { return this->InterreflectionReport; }

  /// The processes over which the mesh may be split (default: the global controller, MPI's
  /// under pvbatch or mpirun; nullptr: this process alone). Where there are several, or the
  /// input's points have global ids, the input is taken as a piece of a mesh whose points are
  /// numbered by their global ids, and its cells by their global cell ids.
  vtkSetSmartPointerMacro(Controller, vtkMultiProcessController);
  vtkGetSmartPointerMacro(Controller, vtkMultiProcessController);

protected:
  vtkLocalReflectanceFilter();
  ~vtkLocalReflectanceFilter() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  /// RequestData within the filter's thread count.
  int Shade(vtkInformationVector** inputVector, vtkInformationVector* outputVector);
  /// Shades input into output: the whole mesh (`pieces` empty), or a piece of a split mesh
  /// shaded as its points are in the whole mesh (a collective call; the steps then run over
  /// the pieces' processes).
  int ShadeMesh(vtkPolyData* input, vtkPolyData* output, const shadelab::MeshPieces& pieces);

private:
  vtkLocalReflectanceFilter(const vtkLocalReflectanceFilter&) = delete;
  void operator=(const vtkLocalReflectanceFilter&) = delete;

  // The settings, and what the last run did.
  std::vector<std::string> ArraySelection{ "default" };
  int NumberOfThreads = 0;
  vtkNew<vtkDataArraySelection> AvailableArrays;
  std::string ArrayPrefix;
  bool ColorByArray = false;
  std::string MaterialColorArray;
  std::string MaterialColorMap = "cool to warm";
  int OutputPrecision = SINGLE_PRECISION;
  bool OrientNormalsOutward = true;
  bool WeldCoincidentPoints = true;
  double FeatureAngle = 80.0;
  double WeldTolerance = 0.0;
  double Tolerance = 0;
  std::vector<shadelab::LightMethod> LightMethods;
  vtkSmartPointer<vtkMultiProcessController> Controller;
  std::string NormalsReport;
  std::string VisibilityReport;
  std::string InterreflectionReport;
  std::optional<shadelab::MethodPlan> MethodPlan;
  std::vector<std::string> SamplingReport;

  /// The rest of the filter's state (its steps, the scene of this update, the material last
  /// read, progress) and the types its steps pass each other: vtkLocalReflectanceFilterInternals.h.
  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
  struct ShadingPlan;
  struct SamplingOutcome;
  struct MaterialSource;
  struct PointSample;

  /// AvailableArrays changed: the filter is modified, unless it is filling the list itself.
  void AvailableArraysChanged();
  /// The selection was set by its own setters: it wins over earlier choices in AvailableArrays.
  void SelectionSetHere();

  /// Progress and abort. The steps' progress is forwarded as this filter's, within the share
  /// of the run the current step has (span 0: not forwarded, as for a forecast's pilot), and an
  /// abort asked of this filter is passed on to them; the shading reports between its blocks.
  /// On a whole mesh (a split mesh's processes must all take part in its exchanges), an abort
  /// throws shadelab::RunAborted, which Shade turns into an empty output.
  void ForwardStepProgress(vtkObject* step, unsigned long, void* done);
  /// This filter's progress, `done` (0 to 1) of the current share, then StopIfAborted.
  void ReportProgress(double done);
  void StopIfAborted();
  /// The next step's share of the progress, after StopIfAborted.
  void StartStep(double start, double span);

  /// ShadeMesh's steps. Those that check say why they fail as the filter's error; on a split
  /// mesh (`pieces`, ShadeLabWholeMesh.h) those that exchange data are collective calls, and
  /// fail on every process alike.
  /// The checks before anything is written (the tolerance, the mesh, the scene, the methods,
  /// the arrays and their names), and what they settle; nothing where one failed.
  std::optional<ShadingPlan> PlanShading(vtkPolyData* input, const shadelab::MeshPieces& pieces);
  bool CheckTolerance();
  /// The mesh's structure, and its coordinates in the plan's precision; sets the plan's extent.
  bool CheckMesh(vtkPolyData* input, const shadelab::MeshPieces& pieces, ShadingPlan& plan);
  /// The scene read for this update, where every process could read it.
  std::optional<shadelab::Scene> SceneReadEverywhere(const shadelab::MeshPieces& pieces);
  /// That scene, placed on the plan's extent and checked where it lands; under a tolerance,
  /// each light's nearest point measured for the plan's bounds.
  bool PlaceScene(vtkPolyData* input, const shadelab::MeshPieces& pieces, ShadingPlan& plan);
  /// The material's arrays read from the input (shadelab::readVertexMaterial), where the scene
  /// has any: read again only when the arrays, their points or what the scene reads from them
  /// have changed since the last run (decoding them costs more than shading does), on every
  /// process alike. With a shininess read from an array, its largest over the whole mesh goes
  /// into plan.measured for the tolerance's bounds.
  bool ReadMaterialArrays(vtkPolyData* input, const shadelab::MeshPieces& pieces, ShadingPlan& plan);
  /// ReadMaterialArrays' decoding, when what it reads has changed.
  bool DecodeMaterialArrays(
    vtkPolyData* input, const shadelab::MeshPieces& pieces, const ShadingPlan& plan, const MaterialSource& source);
  /// Whether the tolerance or the explicit LightMethods fit the scene; forgets the last plan.
  bool CheckLightMethods(const shadelab::Scene& scene);
  /// The arrays the selection asks for, and the methods and precision: the explicit ones, or
  /// those the tolerance chooses (MethodPlan).
  bool ChooseArraysAndMethods(ShadingPlan& plan);
  /// The tolerance's methods and precision (MethodPlan) for the plan's scene and arrays, with
  /// what has been measured on the points (plan.measured): float32's rounding is predicted a
  /// priori until a sample's largest difference is there. roundingMeasuredLater: a prediction
  /// of rounding above the tolerance is not yet an error (the sample may show less).
  bool ChooseMethods(ShadingPlan& plan, bool roundingMeasuredLater);
  /// The points on which the plan's bounds are measured, with their normals and their ids in
  /// the whole mesh: about 16384 evenly spaced by those ids, and every point where a light
  /// grazes the surface. On a split mesh, a collective call whose pieces' samples make up the
  /// whole mesh's, whatever the pieces.
  PointSample SamplePoints(
    vtkPolyData* input, vtkDataArray* shadingNormals, const ShadingPlan& plan, const shadelab::MeshPieces& pieces);
  /// Measures on the sample, into plan.measured: the largest difference between float32 and
  /// float64 shading (exact methods, every light visible, the open sky) where float32 fits, and
  /// each light's largest specular difference under each pow approximation. On a split mesh,
  /// the largest over every piece (a collective call).
  void MeasureOnSample(const PointSample& sample, ShadingPlan& plan, const shadelab::MeshPieces& pieces);
  /// Every point array the filter could write for the scene on this input.
  std::vector<std::string> WritableArrayNames(vtkPolyData* input, const shadelab::Scene& scene) const;
  /// Whether the input lacks all of them.
  bool CheckArrayNamesFree(vtkPolyData* input, const shadelab::Scene& scene, const shadelab::MeshPieces& pieces);

  /// The normals to shade with, prepared by the normals step for this input (a collective call
  /// on a split mesh); fills NormalsReport.
  vtkDataArray* PrepareNormals(vtkPolyData* input, vtkPolyData* output, const shadelab::MeshPieces& pieces);
  /// Under a tolerance, the methods chosen again with what a sample of the points measures.
  bool ChooseMethodsOnSample(
    vtkPolyData* input, vtkDataArray* shadingNormals, ShadingPlan& plan, const shadelab::MeshPieces& pieces);
  /// Under a tolerance, where the plan samples, the cost forecast and room for what sampling
  /// leaves; then MethodsChosenEvent. Throws std::runtime_error where the pilot's rays failed.
  void ForecastAndAnnounce(vtkPolyData* input, vtkDataArray* shadingNormals, const ShadingPlan& plan,
    const shadelab::MeshPieces& pieces, SamplingOutcome& sampling);
  /// Runs the visibility step when the plan's scene needs it (a collective call on a split
  /// mesh), with the plan's targets for the shadowed lights drawn to one, from the points
  /// rayPoints lists (empty: every point; not on a split mesh); returns its output (nullptr:
  /// not needed), or throws std::runtime_error when it failed.
  vtkPolyData* PrepareVisibility(vtkPolyData* input, vtkDataArray* shadingNormals, const ShadingPlan& plan,
    const shadelab::MeshPieces& pieces, const std::vector<vtkIdType>& rayPoints = {});
  /// Where the tolerance's plan samples, on a whole mesh large enough for a pilot to be a small
  /// part of the run: the pilot's vertices (every k-th by id) given their rays and shaded with
  /// the plan, and what they cost scaled to the mesh. nullopt on a split mesh or a small one.
  /// Throws std::runtime_error where the rays failed.
  std::optional<shadelab::CostForecast> ForecastCost(
    vtkPolyData* input, vtkDataArray* shadingNormals, const ShadingPlan& plan, const shadelab::MeshPieces& pieces);
  /// The rays, then the arrays to output: those the kernel computes with the normals and the
  /// rays' arrays, then the occlusion arrays asked for and material_clamped; into `sampling`,
  /// what the sampling to targets left. Throws std::runtime_error where an array cannot be
  /// allocated or the rays failed.
  std::vector<vtkSmartPointer<vtkDataArray>> RaysAndArrays(vtkPolyData* input, vtkDataArray* shadingNormals,
    const ShadingPlan& plan, const shadelab::MeshPieces& pieces, SamplingOutcome& sampling);
  /// For interreflection on a surface shaded on both sides: the side of each vertex the viewer
  /// does not see, with the plan's methods and its rays (a collective call on a split mesh),
  /// its progress over [start, start + span]. Throws std::runtime_error where the rays failed.
  shadelab::HiddenSide ShadeHiddenSide(vtkPolyData* input, vtkDataArray* shadingNormals, const ShadingPlan& plan,
    const shadelab::MeshPieces& pieces, double start, double span);
  /// The arrays the kernel computes with the normals and the rays' arrays in `seen` (nullptr:
  /// no rays), then the occlusion arrays asked for and material_clamped.
  std::vector<vtkSmartPointer<vtkDataArray>> ShadedArrays(vtkPolyData* input, vtkDataArray* shadingNormals,
    vtkPolyData* seen, const ShadingPlan& plan, const shadelab::MeshPieces& pieces, SamplingOutcome& sampling);
  /// What sampling left, over every piece (a collective call, which a failed piece joins with
  /// no values): the report of vertices short of their targets, and the estimated error.
  /// Returns `failure`, or why the estimate failed.
  std::string ReportSampling(
    const ShadingPlan& plan, const shadelab::MeshPieces& pieces, SamplingOutcome& sampling, const std::string& failure);
  /// The error 95% of the whole mesh's vertices are estimated to be within from their sampled
  /// standard errors (shadelab::estimatedErrorQuantile), over every k-th vertex by id on a large
  /// mesh. On a split mesh, a collective call, which a failed piece joins with no values.
  double EstimatedSamplingError(std::vector<double> standardErrors, const shadelab::MeshPieces& pieces) const;
  /// GetSamplingReport's lines: per light drawn to a target, how many vertices of the whole
  /// mesh stopped short of it (on a split mesh, a collective call, each vertex counted once).
  std::vector<std::string> ShortOfTargetReport(const ShadingPlan& plan,
    const std::vector<std::vector<std::uint8_t>>& shortOfTarget, const shadelab::MeshPieces& pieces) const;
  /// The name of the normals the filter computes when the input has none.
  std::string ComputedNormalsName() const { return this->ArrayPrefix + "Normals"; }
  /// What the run did about normals, rays and methods, as the output's field data.
  void AddFieldNotes(vtkPolyData* output) const;
};

#endif
