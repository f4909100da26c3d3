#include "Spectrum.h"

#include <cmath>

namespace shadelab
{
double SampledSpectrum::at(double nm) const
{
  const double position = (nm - startNm) / stepNm;
  if (values.empty() || !(position >= 0) || position > double(values.size() - 1))
  {
    return 0;
  }
  const auto below = std::size_t(position);
  if (below + 1 >= values.size())
  {
    return values.back();
  }
  const double t = position - double(below);
  return (1 - t) * values[below] + t * values[below + 1];
}

namespace
{
/// Planck's law up to a constant factor: lambda^-5 / (exp(c2 / (lambda T)) - 1), lambda in m.
double planck(double nm, double kelvin)
{
  constexpr double c2 = 1.4388e-2; // m K
  const double metres = nm * 1e-9;
  return std::pow(metres, -5) / std::expm1(c2 / (metres * kelvin));
}
}

SampledSpectrum blackbody(double kelvin, double startNm, double endNm, double stepNm)
{
  SampledSpectrum spectrum;
  spectrum.startNm = startNm;
  spectrum.stepNm = stepNm;
  const double at560 = planck(560, kelvin);
  const auto count = std::size_t(std::lround((endNm - startNm) / stepNm)) + 1;
  for (std::size_t i = 0; i < count; ++i)
  {
    spectrum.values.push_back(planck(startNm + double(i) * stepNm, kelvin) / at560);
  }
  return spectrum;
}
}
