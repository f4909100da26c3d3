// Spectral colour (docs/formulas.md section 22): colord's CIE tables, blackbodies and linear
// sRGB against the CIE's own white points and the Planckian locus.
#include "Colorimetry.h"
#include "ReflectanceUpsampling.h"

#include <glm/matrix.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>

namespace
{
using namespace shadelab;

/// The XYZ of a flat (1.0) reflector under an illuminant, at the tables' 5 nm bands.
glm::dvec3 whiteUnder(const SampledSpectrum& illuminant, const ColorMatchingFunctions& observer)
{
  return tristimulus([&](double nm) { return illuminant.at(nm); }, observer, 5.0);
}

TEST(Colorimetry, ColordShipsTheCieTables)
{
  const ColorMatchingFunctions observer = cie1931Observer();
  EXPECT_EQ(observer.y.startNm, 360.0);
  EXPECT_EQ(observer.y.endNm(), 830.0);
  EXPECT_EQ(observer.y.values.size(), 95u);
  EXPECT_EQ(observer.y.at(555), 1.0);                              // the photopic peak
  EXPECT_DOUBLE_EQ(observer.x.at(602.5), 0.5 * (1.0622 + 1.0456)); // between two samples
  EXPECT_EQ(observer.z.at(900), 0.0);                              // outside the table
  for (const std::string& name : cieIlluminantNames())
  {
    EXPECT_GT(cieIlluminant(name).values.size(), 80u) << name;
  }
}

TEST(Colorimetry, AWhiteReflectorUnderEIsEqualEnergy)
{
  const glm::dvec3 xyz = whiteUnder(cieIlluminant("E"), cie1931Observer());
  // The 5 nm table's own sums of x, y and z bar differ by 3.4e-4 at most.
  EXPECT_NEAR(xyz.x / xyz.y, 1.0, 4e-4);
  EXPECT_NEAR(xyz.z / xyz.y, 1.0, 4e-4);
}

TEST(Colorimetry, WhitePointsOfD65AndA)
{
  const ColorMatchingFunctions observer = cie1931Observer();
  const glm::dvec2 d65 = chromaticity(whiteUnder(cieIlluminant("D65"), observer));
  EXPECT_NEAR(d65.x, 0.3127, 1e-4);
  EXPECT_NEAR(d65.y, 0.3290, 1e-4);
  const glm::dvec2 a = chromaticity(whiteUnder(cieIlluminant("A"), observer));
  EXPECT_NEAR(a.x, 0.44757, 1e-4);
  EXPECT_NEAR(a.y, 0.40745, 1e-4);
}

TEST(Colorimetry, BlackbodiesLieOnThePlanckianLocus)
{
  const ColorMatchingFunctions observer = cie1931Observer();
  // Illuminant A is a blackbody at 2856 K; 6500 K as tabulated (docs/formulas.md section 22).
  const glm::dvec2 a = chromaticity(whiteUnder(blackbody(2856, 360, 830, 5), observer));
  EXPECT_NEAR(a.x, 0.44757, 1e-4);
  EXPECT_NEAR(a.y, 0.40745, 1e-4);
  const glm::dvec2 hot = chromaticity(whiteUnder(blackbody(6500, 360, 830, 5), observer));
  EXPECT_NEAR(hot.x, 0.3135, 1e-4);
  EXPECT_NEAR(hot.y, 0.3236, 1e-4);
  EXPECT_DOUBLE_EQ(blackbody(4000, 360, 830, 5).at(560), 1.0); // relative to 560 nm
}

TEST(Colorimetry, LinearSrgbOfD65WhiteIsOne)
{
  const glm::dvec3 white = whiteUnder(cieIlluminant("D65"), cie1931Observer());
  const glm::dvec3 rgb = xyzToLinearSrgb() * (white / white.y);
  EXPECT_NEAR(rgb.r, 1.0, 1e-4);
  EXPECT_NEAR(rgb.g, 1.0, 1e-4);
  EXPECT_NEAR(rgb.b, 1.0, 1e-4);
  // IEC 61966-2-1's printed matrix from linear sRGB to XYZ, to its four digits (its printed
  // inverse was rounded from that, and differs from the exact inverse by up to 4e-4).
  const glm::dmat3 toXyz = glm::inverse(xyzToLinearSrgb());
  const double printed[3][3] = { { 0.4124, 0.3576, 0.1805 }, { 0.2126, 0.7152, 0.0722 }, { 0.0193, 0.1192, 0.9505 } };
  for (int row = 0; row < 3; ++row)
  {
    for (int column = 0; column < 3; ++column)
    {
      EXPECT_NEAR(toXyz[column][row], printed[row][column], 5e-5) << row << ", " << column;
    }
  }
}

TEST(ReflectanceUpsampling, SpectraGiveTheirRgbBack)
{
  const ColorMatchingFunctions observer = cie1931Observer();
  const SampledSpectrum d65 = cieIlluminant("D65");
  // Inner colours, and the sRGB cube's saturated corners, which sigmoid spectra reach too.
  for (const glm::dvec3 rgb : { glm::dvec3(0.8, 0.2, 0.1), glm::dvec3(0.1, 0.5, 0.9), glm::dvec3(0.05, 0.6, 0.3),
         glm::dvec3(0.9, 0.85, 0.1), glm::dvec3(0.3, 0.3, 0.31), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0),
         glm::dvec3(0, 0, 1), glm::dvec3(1, 1, 0), glm::dvec3(0, 1, 1), glm::dvec3(1, 0, 1) })
  {
    const UpsampledReflectance fit = upsampleReflectance(rgb, observer, d65);
    const glm::dvec3 back = reflectanceRgb(fit.spectrum, observer, d65);
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(back[c], rgb[c], 1e-9) << rgb.x << " " << rgb.y << " " << rgb.z;
    }
    EXPECT_LT(fit.rgbResidual, 1e-9);
    const auto [low, high] = std::minmax_element(fit.spectrum.values.begin(), fit.spectrum.values.end());
    EXPECT_GT(*low, 0.0);
    EXPECT_LT(*high, 1.0); // a reflectance: the sigmoid keeps it inside (0, 1)
  }
  // A grey is its constant spectrum, white and black included.
  for (const double grey : { 0.0, 0.4, 1.0 })
  {
    const UpsampledReflectance fit = upsampleReflectance(glm::dvec3(grey), observer, d65);
    EXPECT_EQ(fit.spectrum.values.front(), grey);
    EXPECT_EQ(fit.spectrum.values.back(), grey);
    EXPECT_EQ(fit.rgbResidual, 0.0);
  }
}

TEST(Colorimetry, FilesThatCannotBeReadSayWhy)
{
  auto messageOf = [](const std::string& path)
  {
    try
    {
      readColordSpectrum(path);
    }
    catch (const std::runtime_error& error)
    {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(messageOf("/nonexistent/CIE-D65.sp"),
    "/nonexistent/CIE-D65.sp: cannot be read (colord-data ships it: apt-get install colord-data)");
  const std::string broken = testing::TempDir() + "broken.sp";
  std::ofstream(broken) << "SPECT\nSPECTRAL_START_NM\t380.0\nSPECTRAL_END_NM\t390.0\nSPECTRAL_BANDS\t3\n"
                           "BEGIN_DATA\n 1 2\nEND_DATA\n";
  EXPECT_EQ(messageOf(broken), broken + ": set 0 has 2 values for 3 bands");
  EXPECT_THROW(cieIlluminant("D66"), std::runtime_error);
  std::remove(broken.c_str());
}
}
