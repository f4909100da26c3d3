#include "SpectralStudies.h"

#include "SceneFile.h"
#include "SpectrumFields.h"

#include <algorithm>
#include <cmath>

namespace shadelab::app
{
namespace
{
/// The bundled spectral scene, its lights all emitting `emission`.
Scene spectralSceneUnder(const SampledSpectrum& emission)
{
  Scene scene = readSceneFile("data/scenes/spectral_fluorescent.json");
  const Rgb rgb = emitterRgb(emission);
  for (NamedLight& light : scene.lights)
  {
    light.spectrum = emission;
    std::visit([&](auto& source) { source.color = rgb; }, light.source);
  }
  return scene;
}

/// The largest |value| of any component of the output's array.
double largestMagnitude(vtkDataArray* array)
{
  double largest = 0;
  for (int c = 0; c < array->GetNumberOfComponents(); ++c)
  {
    double range[2];
    array->GetRange(range, c);
    largest = std::max({ largest, std::abs(range[0]), std::abs(range[1]) });
  }
  return largest;
}
}

std::vector<AccuracyRow> spectralRgbErrorStudy(const Mesh& mesh, ChartSpec& chart)
{
  std::vector<std::pair<std::string, SampledSpectrum>> emissions;
  for (const std::string& name : cieIlluminantNames())
  {
    emissions.emplace_back(name, cieIlluminant(name));
  }
  for (const double kelvin : { 2700.0, 6500.0 })
  {
    emissions.emplace_back(std::to_string(int(kelvin)) + " K", blackbody(kelvin, 360, 830, 5));
  }
  std::vector<AccuracyRow> rows;
  ChartSeries relative{ "largest |spectral - RGB model| / largest spectral total", {}, {}, false, palette[3] };
  for (std::size_t e = 0; e < emissions.size(); ++e)
  {
    const MethodRun run =
      runMethod(mesh.data, spectralSceneUnder(emissions[e].second), { "total" }, Precision::Float64, {}, 1, 1);
    const double error = largestMagnitude(arrayOf(run, "total_rgb_difference"));
    const double total = largestMagnitude(arrayOf(run, "total"));
    rows.push_back({ "12 spectral against RGB", "RGB model", "illuminant " + emissions[e].first, double(e),
      mesh.data->GetNumberOfPoints(), std::nullopt, error, std::nullopt, std::nullopt,
      "red paint (0.75, 0.12, 0.08); relative to the largest total: " + std::to_string(error / total) });
    relative.x.push_back(double(e));
    relative.y.push_back(error / total);
  }
  chart.series.push_back(relative);
  std::string order;
  for (const auto& [name, spectrum] : emissions)
  {
    order += (order.empty() ? "" : ", ") + name;
  }
  chart.title = "spectral_fluorescent.json on the bunny, every light one illuminant: the RGB model's error";
  chart.xTitle = "illuminant: " + order;
  chart.yTitle = "largest |RGB model - spectral| / largest total";
  chart.logY = true;
  return rows;
}

std::vector<AccuracyRow> spectralBandStudy(const Mesh& mesh, ChartSpec& chart)
{
  Scene scene = spectralSceneUnder(cieIlluminant("F11"));
  auto totalAt = [&](double bandNm)
  {
    scene.spectral = SpectralMode{ bandNm };
    return runMethod(mesh.data, scene, { "total" }, Precision::Float64, {}, 1, 1);
  };
  const MethodRun reference = totalAt(1);
  std::vector<AccuracyRow> rows;
  ChartSeries largest{ "largest error", {}, {}, true, palette[0] };
  ChartSeries rms{ "RMS error", {}, {}, true, palette[1] };
  for (const double band : { 2.0, 5.0, 10.0, 20.0, 30.0, 50.0 })
  {
    const MethodRun run = totalAt(band);
    const Differences d = compareArrays(arrayOf(run, "total"), arrayOf(reference, "total"));
    rows.push_back({ "13 spectral bands", "spectral mode", "band_nm", band, mesh.data->GetNumberOfPoints(),
      run.milliseconds, d.largest, d.rms, std::nullopt, "F11 on red paint, against 1 nm bands" });
    largest.x.push_back(band);
    largest.y.push_back(d.largest);
    rms.x.push_back(band);
    rms.y.push_back(d.rms);
  }
  chart.series = { largest, rms };
  chart.title = "spectral_fluorescent.json under F11 on the bunny: the total against 1 nm bands";
  chart.xTitle = "band width (nm)";
  chart.yTitle = "|total - total at 1 nm|";
  chart.logX = true;
  chart.logY = true;
  return rows;
}
}
