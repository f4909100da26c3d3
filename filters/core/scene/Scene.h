#pragma once
// Everything the local model needs besides the mesh: lights, material and viewer.
#include "Lights.h"
#include "Vec3.h"

#include <cstddef>
#include <optional>
#include <vector>

namespace shadelab
{
enum class SpecularModel
{
  None,
  Phong,      // Phong 1975, docs/formulas.md section 4: max(0, r.v)^eta
  BlinnPhong, // Blinn 1977, docs/formulas.md section 5: max(0, n.h)^eta
};

/// docs/formulas.md sections 2 to 7: RGB coefficients and shininess. The defaults follow
/// section 7 (ambient RGB = diffuse RGB, specular = white).
struct Material
{
  Rgb ka{ 0.8, 0.8, 0.8 };
  Rgb kd{ 0.8, 0.8, 0.8 };
  Rgb ks{ 1.0, 1.0, 1.0 };
  double shininess = 32.0; // eta
  SpecularModel specular = SpecularModel::BlinnPhong;
  /// Two-sided: a normal facing away from the viewer is flipped before shading, as VTK's
  /// renderer does for back faces. One-sided: it is used as it is.
  bool twoSided = false;
};

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
};

enum class ShadingModel
{
  /// The complete local model of the course (docs/formulas.md section 6), with the options above.
  Lecture,
  /// What VTK 9.1's OpenGL2 renderer computes at a vertex (docs/vtk-renderer.md):
  /// Phong with a local viewer, always two-sided, ambient = ka with no ambient light, and a
  /// lone headlight shaded as df = max(0, n_z), sf = df^p.
  VtkOpenGL2,
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

struct Scene
{
  ShadingModel model = ShadingModel::Lecture;
  SceneFrame frame = SceneFrame::World;
  std::vector<NamedLight> lights;
  Material material;
  Viewer viewer;
  /// VtkOpenGL2 only: VTK's "lighting complexity 1", the single-headlight shader.
  /// SceneFromVtk sets it by VTK's own rule; the scene file sets it when the only light is a
  /// headlight.
  bool vtkLoneHeadlight = false;
};

/// The specular model actually evaluated: the material's, or VTK's (docs/vtk-renderer.md section 5:
/// Phong with sign(df); its lone-headlight shader takes max(0, n_z)^p, which is Blinn-Phong
/// with the viewer along the light, where h = s).
SpecularModel evaluatedSpecularModel(const Scene& scene);
}

namespace shadelab
{
/// One thing wrong with a scene: where (a JSON pointer into the scene file's layout, such as
/// "/lights/2/min_distance") and what.
struct SceneProblem
{
  std::string path;
  std::string message;
};

/// The longest light name a scene may have: names become parts of array names.
constexpr std::size_t maxLightNameLength = 64;

/// The arithmetic a scene is evaluated in.
enum class Precision
{
  Float32,
  Float64,
};

/// The largest |coordinate| (mesh points, light and viewer positions) that the precision
/// handles: squared distances between such points cannot overflow.
double coordinateLimit(Precision precision);

/// Why a mesh whose coordinates reach |x| = reach cannot be shaded in this precision, or ""
/// when it can.
std::string meshCoordinateProblem(double reach, Precision precision);

/// Everything that would make the scene unusable in this precision, in file order; empty
/// when it is valid. Besides values out of their domain, this refuses scenes whose terms
/// could overflow the precision (a light's colour x intensity x k x attenuation at its
/// minimum distance), so that finite input never gives Inf. The scene file parser and the
/// VTK filter both report these, so the rules live here once.
std::vector<SceneProblem> sceneProblems(const Scene& scene, Precision precision = Precision::Float64);
}
