#pragma once
// What a surface reflects (docs/formulas.md sections 2 to 7), and which model evaluates it.
#include "MaterialArrays.h"
#include "Spectrum.h"
#include "Vec3.h"

#include <array>
#include <optional>

namespace shadelab
{
enum class SpecularModel
{
  None,
  Phong,      // Phong 1975, docs/formulas.md section 4: max(0, r.v)^eta
  BlinnPhong, // Blinn 1977, docs/formulas.md section 5: max(0, n.h)^eta
};

/// docs/formulas.md sections 2 to 7: RGB coefficients and shininess. The defaults follow
/// section 7 (ambient RGB = diffuse RGB, specular = white). A coefficient may come from a
/// point-data array instead (arrays); its number here is then its scale: for ka, kd and ks the
/// largest value the array can give, the bound that the scene's checks and a tolerance's plan
/// use; for the shininess, which has no bound, nothing the plan relies on.
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
  MaterialArrays arrays{};
  /// Per MaterialCoefficient (ka, kd, ks), a reflectance spectrum where the scene gives one;
  /// the coefficient's RGB is then the spectrum's under D65 (ReflectanceUpsampling.h).
  std::array<std::optional<SampledSpectrum>, 3> spectra{};
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
}
