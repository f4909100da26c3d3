#pragma once
// Spectra sampled at evenly spaced wavelengths, and Planck's blackbody (docs/formulas.md section
// 22, the lecture's section 12: light and materials are wavelength dependent).
#include <vector>

namespace shadelab
{
/// A spectrum sampled every stepNm nanometres from startNm: between samples it is linear, and
/// outside them 0.
struct SampledSpectrum
{
  double startNm = 0;
  double stepNm = 1;
  std::vector<double> values;

  double endNm() const { return startNm + stepNm * (values.empty() ? 0.0 : double(values.size() - 1)); }
  /// The value at a wavelength in nm.
  double at(double nm) const;
};

/// Planck's law: a blackbody's spectral exitance at `kelvin`, relative (1 at 560 nm, as CIE
/// illuminant A is given), sampled from startNm to endNm every stepNm. Uses the second radiation
/// constant c2 = 1.4388e-2 m K (CIE 015:2018).
SampledSpectrum blackbody(double kelvin, double startNm, double endNm, double stepNm);
}
