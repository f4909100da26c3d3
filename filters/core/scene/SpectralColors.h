#pragma once
// The colours the kernel multiplies each light's terms by, per model: the RGB model's products
// of RGB values, or the spectral mode's products of spectra summed through the CIE observer
// (docs/formulas.md section 22). The geometric terms (n.s, attenuation, visibility) do not
// depend on wavelength, so a spectral total is these colours times the same terms.
#include "Scene.h"

#include <optional>
#include <vector>

namespace shadelab
{
/// Per scene light, Ld kd and Ls ks (0 for ambient lights), and La ka summed over the ambient
/// lights, as linear sRGB with D65 white. (The RGB model's are the kernel's own products of the
/// scene's RGB values.)
struct LightColors
{
  std::vector<Rgb> diffuse, specular;
  Rgb ambient{ 0.0 };
};

/// The spectral mode's: each light's emission times the material's reflectance, band by band
/// (scene.spectral's width), through the CIE 1931 observer, as linear sRGB. A light given as a
/// spectrum emits it with its luminance scaled to 1; a light given as RGB emits D65 times its
/// colour upsampled, and a material given as RGB reflects its colour upsampled
/// (ReflectanceUpsampling.h). Throws std::runtime_error where colord's tables are missing.
LightColors spectralLightColors(const Scene& scene);

/// Why the scene cannot be shaded in the spectral mode (sceneProblems reports it), or nothing.
std::optional<SceneProblem> spectralModeProblem(const Scene& scene);
}
