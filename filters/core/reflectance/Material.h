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

/// docs/vtk-renderer.md section 11: what VTK 9.1's PBR shader reads from a vtkProperty with
/// Interpolation PBR. The defaults are vtkProperty's.
struct MicrofacetMaterial
{
  Rgb baseColor{ 1.0, 1.0, 1.0 }; // the albedo: Diffuse x DiffuseColor
  double metallic = 0.0;
  double roughness = 0.5;
  double baseIor = 1.5;          // the index of refraction that gives the dielectric F0, 0.04 at 1.5
  Rgb edgeTint{ 1.0, 1.0, 1.0 }; // a metal's reflectance at grazing angles (F90)
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
  /// The vtk_pbr model's material (ShadingModel::VtkPbr); the coefficients above are unused there.
  MicrofacetMaterial microfacet{};
};

enum class ShadingModel
{
  /// The complete local model of the course (docs/formulas.md section 6), with the options above.
  Lecture,
  /// What VTK 9.1's OpenGL2 renderer computes at a vertex (docs/vtk-renderer.md):
  /// Phong with a local viewer, always two-sided, ambient = ka with no ambient light, and a
  /// lone headlight shaded as df = max(0, n_z), sf = df^p.
  VtkOpenGL2,
  /// What VTK 9.1's OpenGL2 renderer computes at a vertex for a surface with PBR interpolation
  /// and no image-based lighting (docs/vtk-renderer.md section 11): GGX microfacets with
  /// Schlick's Fresnel and a Lambert diffuse part, no ambient term, always two-sided.
  VtkPbr,
};

/// Whether the model reproduces VTK's renderer (its lights, camera and two-sided surfaces).
inline bool reproducesVtkRenderer(ShadingModel model)
{
  return model == ShadingModel::VtkOpenGL2 || model == ShadingModel::VtkPbr;
}

/// A coefficient's key in the model's material in a scene file: the vtk_pbr model's base colour
/// is its kd (an array's colour, VTK's scalar colouring).
inline const char* materialKey(MaterialCoefficient coefficient, ShadingModel model)
{
  return model == ShadingModel::VtkPbr && coefficient == MaterialCoefficient::Diffuse ? "base_color"
                                                                                      : coefficientKey(coefficient);
}

/// The model's name in a scene file ("model").
inline const char* modelName(ShadingModel model)
{
  switch (model)
  {
    case ShadingModel::Lecture: return "lecture";
    case ShadingModel::VtkOpenGL2: return "vtk";
    case ShadingModel::VtkPbr: return "vtk_pbr";
  }
  return "";
}
}
