#include "ReflectanceUpsampling.h"

#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>

namespace shadelab
{
namespace
{
/// Jakob and Hanika's sigmoid: (0, 1) for any x.
double sigmoid(double x)
{
  return 0.5 + x / (2 * std::sqrt(1 + x * x));
}

/// The spectrum of coefficients c on the observer's wavelengths.
SampledSpectrum sigmoidSpectrum(const glm::dvec3& c, const SampledSpectrum& grid)
{
  SampledSpectrum spectrum{ grid.startNm, grid.stepNm, std::vector<double>(grid.values.size()) };
  const double span = grid.endNm() - grid.startNm;
  for (std::size_t i = 0; i < spectrum.values.size(); ++i)
  {
    const double t = double(i) * grid.stepNm / span;
    spectrum.values[i] = sigmoid(c.x + c.y * t + c.z * t * t);
  }
  return spectrum;
}
}

glm::dvec3 reflectanceRgb(
  const SampledSpectrum& reflectance, const ColorMatchingFunctions& observer, const SampledSpectrum& d65)
{
  const double band = observer.y.stepNm;
  const glm::dvec3 white = tristimulus([&](double nm) { return d65.at(nm); }, observer, band);
  const glm::dvec3 xyz = tristimulus([&](double nm) { return d65.at(nm) * reflectance.at(nm); }, observer, band);
  const glm::dmat3 toRgb = xyzToLinearSrgb();
  // Divided by white's own RGB, so that the flat reflector is exactly (1, 1, 1) at this band width.
  return (toRgb * xyz) / (toRgb * white);
}

UpsampledReflectance upsampleReflectance(
  const glm::dvec3& rgb, const ColorMatchingFunctions& observer, const SampledSpectrum& d65)
{
  UpsampledReflectance result;
  if (rgb.x == rgb.y && rgb.y == rgb.z)
  {
    result.spectrum =
      SampledSpectrum{ observer.y.startNm, observer.y.stepNm, std::vector<double>(observer.y.values.size(), rgb.x) };
    return result;
  }
  auto residual = [&](const glm::dvec3& c)
  { return reflectanceRgb(sigmoidSpectrum(c, observer.y), observer, d65) - rgb; };
  glm::dvec3 c(0.0);
  glm::dvec3 r = residual(c);
  double damping = 1e-3;
  for (int iteration = 0; iteration < 200 && glm::length(r) > 1e-12; ++iteration)
  {
    // The Jacobian by central differences, one column per coefficient.
    glm::dmat3 jacobian;
    for (int k = 0; k < 3; ++k)
    {
      glm::dvec3 step(0.0);
      step[k] = 1e-6;
      jacobian[k] = (residual(c + step) - residual(c - step)) / 2e-6;
    }
    // Levenberg-Marquardt: (J^T J + damping diag) delta = -J^T r, the damping grown until a
    // step lowers the residual and shrunk after it does.
    const glm::dmat3 normal = glm::transpose(jacobian) * jacobian;
    bool improved = false;
    for (int attempt = 0; attempt < 30 && !improved; ++attempt)
    {
      glm::dmat3 damped = normal;
      for (int k = 0; k < 3; ++k)
      {
        damped[k][k] *= 1 + damping;
      }
      const glm::dvec3 next = c - glm::inverse(damped) * (glm::transpose(jacobian) * r);
      const glm::dvec3 nextResidual = residual(next);
      improved = glm::length(nextResidual) < glm::length(r);
      if (improved)
      {
        c = next;
        r = nextResidual;
        damping = std::max(damping / 10, 1e-12);
      }
      else
      {
        damping *= 10;
      }
    }
    if (!improved)
    {
      break; // no step lowers it: the colour is at the edge of what the spectra reach
    }
  }
  result.spectrum = sigmoidSpectrum(c, observer.y);
  result.rgbResidual = std::max({ std::abs(r.x), std::abs(r.y), std::abs(r.z) });
  return result;
}
}
