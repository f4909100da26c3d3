#pragma once
// The arrays ShadeLab can write for a scene: their names, sizes and meanings, and the choice
// of which to compute. One table, so the filter, the command line and the guide (docs/guide/arrays.md) agree.
#include "LightTerms.h"
#include "Scene.h"

#include <array>
#include <string>
#include <vector>

namespace shadelab
{
/// Quantities summed over all lights.
enum class TotalTerm
{
  Ambient,
  Diffuse,
  Specular,
  Total,
};
constexpr int TotalTermCount = 4;
static_assert(static_cast<int>(TotalTerm::Total) + 1 == TotalTermCount, "TotalTermCount is stale");

/// Scene-wide quantities of ambient occlusion (Scene::ambientOcclusion).
enum class OcclusionTerm
{
  AmbientOcclusion,
  AmbientOcclusionStdError,
  BentNormal,
  SkyViewFactor,
  Rays,          // "rays": "auto" only: how many each vertex drew
  ShortOfTarget, // "rays": "auto" only: 1 where the vertex stopped at the maximum above its target
};
constexpr int OcclusionTermCount = 6;
static_assert(static_cast<int>(OcclusionTerm::ShortOfTarget) + 1 == OcclusionTermCount, "OcclusionTermCount is stale");

/// Quantities of diffuse interreflection (Scene::interreflection), besides each bounce's own
/// irradiance (indirectBounceArrayName).
enum class InterreflectionTerm
{
  IndirectIrradiance,
  IndirectIrradianceStdError,
  Indirect,             // kd times the indirect irradiance: in the diffuse and total arrays too
  AmbientMinusIndirect, // the ambient term less what it stands in for
};
constexpr int InterreflectionTermCount = 4;
static_assert(static_cast<int>(InterreflectionTerm::AmbientMinusIndirect) + 1 == InterreflectionTermCount,
  "InterreflectionTermCount is stale");

struct TermInfo
{
  const char* name;
  int components; // 0: as many as the light has (lightTermComponents)
  const char* description;
};

const TermInfo& termInfo(LightTerm term);
const TermInfo& termInfo(TotalTerm term);
const TermInfo& termInfo(OcclusionTerm term);
const TermInfo& termInfo(InterreflectionTerm term);
/// Whether the scene's light `light` has the term: lightHasTerm, and the microfacet terms only in
/// the vtk_pbr model.
bool sceneLightHasTerm(const Scene& scene, std::size_t light, LightTerm term);
/// How many components the light's array of the term has: the term's own count, or for a
/// transfer vector its light's coefficients.
int lightTermComponents(const NamedLight& light, LightTerm term);
/// Whether the scene has the occlusion quantity: all but Rays with ambient occlusion, Rays
/// where its count comes from a tolerance.
bool sceneHasTerm(const Scene& scene, OcclusionTerm term);
extern const TermInfo flagsInfo;

/// Which arrays to compute. lights[i] follows scene.lights[i].
struct ArrayRequest
{
  std::vector<std::array<bool, LightTermCount>> lights;
  std::array<bool, TotalTermCount> totals{};
  bool flags = false;
  std::array<bool, OcclusionTermCount> occlusion{};
  std::array<bool, InterreflectionTermCount> interreflection{};
  /// bounces[n - 1]: the irradiance bounce n adds (indirectBounceArrayName), one per bounce.
  std::vector<bool> bounces;
  /// Follows scene.lights: a "prt" map's transfer carried through the bounces
  /// (indirectTransferArrayName).
  std::vector<bool> indirectTransfer;

  bool any(LightTerm term) const;
};

struct ArrayDescription
{
  std::string name;
  int components;
  std::string description;
};

/// Every array the scene can produce, in output order, with names prefixed by prefix.
std::vector<ArrayDescription> availableArrays(const Scene& scene, const std::string& prefix = "");

/// The array name of a light's term: <prefix><light>_<term>. Distinct lights cannot share an
/// array name because no term name ends in "_" followed by another term name (a test keeps
/// it so).
std::string lightArrayName(const std::string& prefix, const std::string& light, LightTerm term);
/// The array name of a total or the flags: <prefix><name>.
std::string totalArrayName(const std::string& prefix, TotalTerm term);
/// A total's XYZ twin in the spectral mode ("total_xyz"), and the spectral total's difference
/// from the RGB model's ("total_rgb_difference").
std::string totalXyzArrayName(const std::string& prefix, TotalTerm term);
std::string rgbDifferenceArrayName(const std::string& prefix);
/// Every array the spectral mode may add to the kernel's (none without it).
std::vector<std::string> spectralArrayNames(const Scene& scene, const std::string& prefix);
std::string flagsArrayName(const std::string& prefix);
/// The name of vtkMeshVisibilityFilter's flags (FlagHiddenByOwnTriangle), which the kernel
/// folds into shading_flags: <prefix>visibility_flags.
std::string visibilityFlagsArrayName(const std::string& prefix);
/// The visibility step's bits of an area light's or a map's samples that the mesh hides
/// (HiddenSamples), which the shading reads and does not write.
std::string hiddenSamplesArrayName(const std::string& prefix, const std::string& light);
/// The visibility step's estimates of a shadowed area light or map drawn to a target, which
/// traces its rays round by round as it draws them (packTerms' rows): read by the shading instead
/// of the hidden samples.
std::string shadowedTermsArrayName(const std::string& prefix, const std::string& light);
/// Whether the scene light's specular term is computed for the request: it can be other than 0
/// (hasSpecularTerm) and its own array or a total holds it (as the kernel decides which lobes
/// to evaluate).
bool specularComputed(const Scene& scene, const ArrayRequest& request, std::size_t light);
/// The array name of an occlusion quantity: <prefix><name>.
std::string occlusionArrayName(const std::string& prefix, OcclusionTerm term);
/// The array name of an interreflection quantity: <prefix><name>.
std::string interreflectionArrayName(const std::string& prefix, InterreflectionTerm term);
/// The array of what bounce n (from 1) adds to the indirect irradiance: <prefix>indirect_bounce_<n>.
std::string indirectBounceArrayName(const std::string& prefix, int bounce);
/// The array of what the bounces add to a "prt" map's transfer vector, per channel:
/// <prefix><light>_sh_transfer_indirect.
std::string indirectTransferArrayName(const std::string& prefix, const std::string& light);
/// Whether the scene carries the light's transfer vector through its bounces: a "prt" map in a
/// scene with interreflection.
bool hasIndirectTransfer(const Scene& scene, std::size_t light);
/// Whether the request asks for anything that interreflection computes: its own arrays, or the
/// diffuse and total arrays that include it.
bool needsInterreflection(const Scene& scene, const ArrayRequest& request);

/// The selection the command line documents:
///   "default"  the totals and shading_flags, and where the scene has them, ambient_occlusion
///              with its standard error, each shadowed light's visibility, each "prt" map's
///              transfer vectors, and indirect_irradiance with its standard error, indirect and
///              the "prt" maps' indirect transfer
///   "totals"   ambient, diffuse, specular, total
///   "all"      every array the scene has
///   "*_TERM"   TERM for every light that has it, e.g. "*_cos_incidence"
///   NAME       one array by its full name (without the prefix), e.g. "key_diffuse"
/// Throws std::invalid_argument naming the first unknown entry and listing what exists, or
/// saying that the selection is empty.
ArrayRequest selectArrays(const Scene& scene, const std::vector<std::string>& selection);

/// The names (without a prefix) of the arrays a selection computes, in output order: what a
/// list of the scene's arrays with a box for each shows ticked. Throws as selectArrays does.
std::vector<std::string> selectedArrayNames(const Scene& scene, const std::vector<std::string>& selection);
}
