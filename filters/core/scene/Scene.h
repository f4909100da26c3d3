#pragma once
// Everything the local model needs besides the mesh: lights, material and viewer.
#include "LightChecks.h"
#include "LightSource.h"
#include "Material.h"
#include "Precision.h"
#include "SampleSequence.h"
#include "SelfShadowing.h"
#include "SequentialSampling.h"
#include "Vec3.h"

#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

namespace shadelab
{
/// Where the viewer is: a camera position (local viewer) or, when position is empty, at
/// infinity looking along viewDirection.
struct Viewer
{
  std::optional<glm::dvec3> position;
  /// The point the camera looks at. Needed only for a headlight with a local viewer.
  std::optional<glm::dvec3> focalPoint;
  glm::dvec3 viewDirection{ 0, 0, -1 }; // used when position is empty

  /// The direction the viewer looks (unit), which is where a headlight shines.
  std::optional<glm::dvec3> lineOfSight() const;
  /// The unit direction from p to the viewer: toward its position, or against the view
  /// direction of a distant one; (0, 0, 0) at its position (where the kernel sees along n).
  glm::dvec3 directionFrom(const glm::dvec3& p) const;
};

/// What a scene's positions and lengths are measured in.
enum class SceneFrame
{
  World, // the mesh's own coordinates
  /// Units of the mesh's bounding-sphere radius R about its centre c (world = c + R p), with
  /// intensities defined so that the lighting does not depend on where the mesh is or how
  /// big it is. placedOnMesh (SceneFrame.h) turns such a scene into world coordinates.
  Mesh,
};

/// Ambient occlusion (visibility/Visibility.h): the ambient term becomes ka La times the
/// cosine-weighted fraction of the sky each vertex sees past the mesh.
struct AmbientOcclusion
{
  /// "rays": "auto" (sampling.fromTolerance): each vertex draws as many rays as its share of a
  /// tolerance needs, at most sampling.maximum ("max_rays"); the tolerance's plan
  /// (MethodChoice.h) sets the target. Without a tolerance there is no target, and the filters
  /// refuse the scene.
  Sampling sampling{ 64, true };
  std::optional<SamplingTarget> target;
  /// Occluders farther than this do not count (infinite: all do). In the scene's frame.
  double maxDistance = std::numeric_limits<double>::infinity();
};

/// "interreflection": the light the mesh reflects onto itself (docs/formulas.md section 23),
/// diffusely, over `bounces` reflections, gathered at each vertex along `sampling.samples`
/// cosine-weighted rays; the albedo is the material's kd.
struct Interreflection
{
  /// The most bounces a scene may ask for: past it, even a white closed mesh's next bounce
  /// changes little that more rays would not change more.
  static constexpr int maxBounces = 64;
  /// 1 .. maxBounces (a scene file's "bounces": 0 leaves interreflection out).
  int bounces = 1;
  /// "samples": "auto": the gather's rays per vertex from a tolerance's share; `samples` is then
  /// the first run's count, whose standard errors choose the count (at most `maximum`, 1024 by
  /// default: the later bounces keep a quarter of the rays' hits, 8 bytes each, so 2 KB a vertex).
  Sampling sampling{ 64, true, false, 1024 };
  /// "bounces": "auto": as many as a tolerance's share needs (MethodChoice.h), chosen once the
  /// direct light is known; at most maxBounces.
  bool bouncesFromTolerance = false;
};

/// "spectral": colour evaluated wavelength by wavelength (docs/formulas.md section 22): each
/// light's emission times the material's reflectance, summed over bands of bandNm nanometres
/// through the CIE observer, instead of the product of their RGB values.
struct SpectralMode
{
  double bandNm = 5;
};

/// Which side of a two-sided surface a vertex is shaded on: the one the viewer sees, or the
/// other (whose light interreflection needs too: it reaches the vertices that see that side).
enum class ShadedSide
{
  Seen,
  Hidden
};

struct Scene
{
  ShadingModel model = ShadingModel::Lecture;
  SceneFrame frame = SceneFrame::World;
  std::vector<NamedLight> lights;
  Material material;
  /// Whether the scene gives the material: where it does not, a mesh file's own materials
  /// shade it (an OBJ with its MTL file).
  bool materialGiven = false;
  Viewer viewer;
  /// VtkOpenGL2 and VtkPbr: VTK's "lighting complexity 1", the single-headlight shader (in
  /// VtkPbr the scene file then puts the headlight at the camera, as a point light).
  /// SceneFromVtk sets it by VTK's own rule; the scene file sets it when the only light is a
  /// headlight.
  bool vtkLoneHeadlight = false;
  std::optional<AmbientOcclusion> ambientOcclusion;
  std::optional<Interreflection> interreflection;
  std::optional<SpectralMode> spectral;
  /// Which triangles hide a shadowed light: "self_shadowing" in a scene file.
  SelfShadowing selfShadowing = SelfShadowing::SmoothSurface;
  /// Set by the filter, not by a scene file: the side shaded where both sides are.
  ShadedSide shadedSide = ShadedSide::Seen;

  /// Whether anything needs rays cast against the mesh: a light's shadows or occlusion.
  bool needsVisibility() const;
};

/// The specular model actually evaluated: the material's, or VTK's (docs/vtk-renderer.md section 5:
/// Phong with sign(df); its lone-headlight shader takes max(0, n_z)^p, which is Blinn-Phong
/// with the viewer along the light, where h = s).
SpecularModel evaluatedSpecularModel(const Scene& scene);
/// Whether the scene's specular terms can be other than 0: a specular model is evaluated and ks
/// is not black. Where they cannot, no lobe is evaluated or sampled.
bool hasSpecularTerm(const Scene& scene);
}

namespace shadelab
{
/// The longest light name a scene may have: names become parts of array names.
constexpr std::size_t maxLightNameLength = 64;

/// Why a mesh whose coordinates reach |x| = reach cannot be shaded in this precision, or ""
/// when it can.
std::string meshCoordinateProblem(double reach, Precision precision);

/// Why the vtk_pbr model cannot shade this roughness in this precision (float32 cannot resolve
/// D's peak below about 0.07), or "" when it can.
std::string roughnessPrecisionProblem(double roughness, Precision precision);

/// Everything that would make the scene unusable in this precision, in file order; empty
/// when it is valid. Besides values out of their domain, this refuses scenes whose terms
/// could overflow the precision (a light's colour x intensity x k x attenuation at its
/// minimum distance), so that finite input never gives Inf. The scene file parser and the
/// VTK filter both report these, so the rules live here once.
std::vector<SceneProblem> sceneProblems(const Scene& scene, Precision precision = Precision::Float64);

/// Whether any of the scene's lights has a position (a point or spot light).
bool hasPositionalLight(const Scene& scene);

/// docs/vtk-renderer.md section 11.4: where VTK's PBR shader takes every light's direction from
/// its position (lightsFromPositions: the lone headlight, or any light beside a positional one),
/// each headlight becomes what the shader makes of it, an unattenuated point light at the
/// viewer's position. Needs that position.
void placeHeadlightsAtTheCamera(Scene& scene, bool lightsFromPositions);

/// Whether the surface is shaded on both sides (a two-sided material, or VTK's renderer, which
/// always flips back faces): the normal turned toward the viewer where it faces away.
bool shadesBothSides(const Scene& scene);

/// Whether a vertex of a surface shaded on both sides is shaded with its normal turned round,
/// given n . v (v toward the viewer): where the normal faces away from the viewer, or for the
/// hidden side, where it does not. One rule for the kernel and the rays, so that they agree.
template<typename T>
bool turnsNormalRound(T normalDotToViewer, ShadedSide side)
{
  const bool facesAway = normalDotToViewer < T(0);
  return side == ShadedSide::Seen ? facesAway : !facesAway;
}

/// Why the scene's samples cannot be drawn as it stands, at the field that says so (none
/// where they can): ambient occlusion with "rays": "auto" that no tolerance has given a target
/// (MethodChoice.h), and unless lightsPlanned (a tolerance's plan gives each light its
/// targets, and interreflection its share), any light with "samples": "auto" and
/// interreflection with "bounces" or "samples" "auto".
std::vector<SceneProblem> untargetedSamplingProblems(const Scene& scene, bool lightsPlanned);
}
