#include "SpectralColors.h"

#include "ReflectanceUpsampling.h"
#include "SpectrumFields.h"

#include <glm/matrix.hpp>

#include <algorithm>

namespace shadelab
{
namespace
{
/// A spectrum as a function of the wavelength.
using SpectralFunction = std::function<double(double)>;

/// An RGB with channels >= 0 as a smooth spectrum of that RGB: its largest channel times the
/// upsampled reflectance of the RGB over it.
SpectralFunction upsampled(const Rgb& rgb)
{
  const double largest = std::max({ rgb.x, rgb.y, rgb.z });
  if (largest <= 0)
  {
    return [](double) { return 0.0; };
  }
  const SampledSpectrum shape = upsampleReflectance(rgb / largest, standardObserver(), d65Illuminant()).spectrum;
  return [shape, largest](double nm) { return largest * shape.at(nm); };
}

/// The light's emission, its luminance scaled to 1 for a spectrum, D65's luminance to 1 for an RGB.
SpectralFunction emissionOf(const NamedLight& light, double bandNm)
{
  auto luminance = [&](const SpectralFunction& f) { return tristimulus(f, standardObserver(), bandNm).y; };
  if (light.spectrum)
  {
    const SampledSpectrum s = *light.spectrum;
    const double y = luminance([&](double nm) { return s.at(nm); });
    return [s, y](double nm) { return s.at(nm) / y; };
  }
  const SpectralFunction shape = upsampled(std::visit([](const auto& l) { return l.color; }, light.source));
  const SampledSpectrum& d65 = d65Illuminant();
  const double y = luminance([&](double nm) { return d65.at(nm); });
  return [shape, &d65, y](double nm) { return d65.at(nm) * shape(nm) / y; };
}

/// The material's coefficient as a reflectance: its spectrum, or its RGB upsampled.
SpectralFunction reflectanceOf(const Material& m, MaterialCoefficient c, const Rgb& rgb)
{
  if (const std::optional<SampledSpectrum>& spectrum = m.spectra[int(c)])
  {
    const SampledSpectrum s = *spectrum;
    return [s](double nm) { return s.at(nm); };
  }
  return upsampled(rgb);
}

/// The light's colour x intensity (x |direction|) with its colour replaced by `color`.
Rgb emittedWith(const LightSource& source, const Rgb& color)
{
  LightSource recoloured = source;
  std::visit([&](auto& light) { light.color = color; }, recoloured);
  return emittedColor(recoloured);
}
}

LightColors spectralLightColors(const Scene& scene)
{
  const double bandNm = scene.spectral ? scene.spectral->bandNm : SpectralMode{}.bandNm;
  const glm::dmat3 toRgb = xyzToLinearSrgb();
  const Material& m = scene.material;
  const SpectralFunction ka = reflectanceOf(m, MaterialCoefficient::Ambient, m.ka);
  const SpectralFunction kd = reflectanceOf(m, MaterialCoefficient::Diffuse, m.kd);
  const SpectralFunction ks = reflectanceOf(m, MaterialCoefficient::Specular, m.ks);
  // The emission times a reflectance, summed through the observer, as linear sRGB.
  auto reflected = [&](const SpectralFunction& emission, const SpectralFunction& reflectance) {
    return toRgb * tristimulus([&](double nm) { return emission(nm) * reflectance(nm); }, standardObserver(), bandNm);
  };
  LightColors colors;
  for (const NamedLight& light : scene.lights)
  {
    const SpectralFunction emission = emissionOf(light, bandNm);
    const bool ambient = isAmbient(light.source);
    colors.diffuse.push_back(ambient ? Rgb(0.0) : emittedWith(light.source, reflected(emission, kd)));
    colors.specular.push_back(ambient ? Rgb(0.0) : emittedWith(light.source, reflected(emission, ks)));
    colors.ambient += ambient ? emittedWith(light.source, reflected(emission, ka)) : Rgb(0.0);
  }
  return colors;
}

std::optional<SceneProblem> spectralModeProblem(const Scene& scene)
{
  if (!scene.spectral)
  {
    return std::nullopt;
  }
  if (!(scene.spectral->bandNm > 0 && scene.spectral->bandNm <= 50))
  {
    return SceneProblem{ "/spectral/band_nm", "must be a number of nm > 0 and <= 50" };
  }
  if (reproducesVtkRenderer(scene.model))
  {
    return SceneProblem{ "/spectral",
      std::string("the ") + modelName(scene.model) +
        " model is VTK's renderer, whose colours are RGB: use the lecture model" };
  }
  if (scene.material.arrays.any())
  {
    return SceneProblem{ "/material",
      "a material from the mesh's arrays is RGB per vertex; the spectral mode takes spectra or numbers" };
  }
  for (std::size_t l = 0; l < scene.lights.size(); ++l)
  {
    if (isDistributed(scene.lights[l].source))
    {
      return SceneProblem{ "/lights/" + std::to_string(l),
        "the spectral mode shades distant, point, spot, headlights and ambient lights; an area light's or a "
        "map's colour is not yet summed band by band" };
    }
  }
  return std::nullopt;
}
}
