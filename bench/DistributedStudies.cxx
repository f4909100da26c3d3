#include "DistributedStudies.h"

#include "MeshFiles.h"

#include "EnvironmentMap.h"
#include "RadianceTransfer.h"
#include "SceneFile.h"
#include "SphericalHarmonics.h"

#include "vtkPointData.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <memory>
#include <sstream>

namespace shadelab::app
{
namespace
{
const int sampleCounts[] = { 4, 16, 64, 256, 1024 };
constexpr int areaReferenceSamples = 16384;
constexpr int mapReferenceWidth = 256; // a divisor of the bundled maps' 1024

Scene withLight(const Scene& scene, NamedLight light)
{
  Scene lit = scene;
  lit.lights = { std::move(light) };
  return lit;
}

std::string samplingName(bool stratified)
{
  return stratified ? "stratified" : "independent";
}

/// "P% of the values within E": how many of b's values are within `within` of a's.
std::string withinText(vtkDataArray* a, vtkDataArray* b, double within)
{
  vtkIdType inside = 0;
  for (vtkIdType v = 0; v < a->GetNumberOfValues(); ++v)
  {
    inside += std::abs(a->GetVariantValue(v).ToDouble() - b->GetVariantValue(v).ToDouble()) <= within ? 1 : 0;
  }
  std::ostringstream text;
  text << std::fixed << std::setprecision(1) << 100.0 * double(inside) / double(a->GetNumberOfValues())
       << "% of the values within the predicted error (95% asked)";
  return text.str();
}

/// The measurements of one study: each method's error in each term against the reference, as
/// rows, and the charted term's largest and RMS errors against time, as a line per estimator
/// family (over its sample counts or widths).
class DistributedStudy
{
public:
  /// termRuns: the terms each method computes, one timed run per group.
  DistributedStudy(std::string name, const Mesh& bunny, std::vector<std::vector<std::string>> termRuns,
    std::string chartedTerm, int maxRepeats)
    : name_(std::move(name))
    , bunny_(bunny)
    , termRuns_(std::move(termRuns))
    , chartedTerm_(std::move(chartedTerm))
    // Runs take up to seconds: at most three, and one when the first takes two seconds.
    , maxRepeats_(std::min(maxRepeats, 3))
  {
  }

  /// Runs the reference once, in float64, with every term and the extra arrays.
  const MethodRun& measureReference(const Scene& scene, const std::vector<std::string>& extraArrays)
  {
    std::vector<std::string> arrays = extraArrays;
    for (const auto& run : termRuns_)
    {
      arrays.insert(arrays.end(), run.begin(), run.end());
    }
    reference_ = runMethod(bunny_.data, scene, arrays, Precision::Float64, {}, 1, 1);
    return reference_;
  }

  void addReferenceRow(const std::string& parameter, double value, const std::string& note)
  {
    rows.push_back({ name_, "the reference", parameter, value, bunny_.data->GetNumberOfPoints(),
      reference_.milliseconds, std::nullopt, std::nullopt, std::nullopt, note });
  }

  /// method: the estimator family, such as "monte_carlo, stratified"; parameter and value:
  /// what varies within it (samples 64); methods: the lights' (a target for their samples),
  /// with the error predicted for the charted term.
  void measure(const std::string& method, const std::string& parameter, double value, const Scene& scene,
    const std::vector<LightMethod>& methods = {}, std::optional<double> predicted = std::nullopt)
  {
    for (const std::vector<std::string>& terms : termRuns_)
    {
      const MethodRun run = runMethod(bunny_.data, scene, terms, Precision::Float32, methods, maxRepeats_, 1);
      for (const std::string& term : terms)
      {
        const Differences errors = compareArrays(arrayOf(reference_, term), arrayOf(run, term));
        rows.push_back({ name_, method + ": " + term, parameter, value, bunny_.data->GetNumberOfPoints(),
          run.milliseconds, errors.largest, errors.rms, term == chartedTerm_ ? predicted : std::nullopt,
          predicted && term == chartedTerm_ ? withinText(arrayOf(reference_, term), arrayOf(run, term), *predicted)
                                            : "" });
        if (term == chartedTerm_)
        {
          addPoint(method, run.milliseconds, errors);
        }
      }
    }
  }

  /// Largest error solid, RMS dashed, a colour per family; under them, the Pareto front of
  /// each as a pale band.
  std::vector<ChartSeries> chartSeries() const
  {
    std::vector<ChartSeries> lines;
    std::vector<double> times, largest, rms;
    for (std::size_t i = 0; i < families_.size(); ++i)
    {
      const Family& family = families_[i];
      ChartSeries line{ family.name + ": largest", family.milliseconds, family.largest, true, palette[i] };
      line.markers = true;
      lines.push_back(line);
      line.name = family.name + ": RMS";
      line.y = family.rms;
      line.dashed = true;
      lines.push_back(line);
      times.insert(times.end(), family.milliseconds.begin(), family.milliseconds.end());
      largest.insert(largest.end(), family.largest.begin(), family.largest.end());
      rms.insert(rms.end(), family.rms.begin(), family.rms.end());
    }
    std::vector<ChartSeries> series;
    for (const auto& [errors, name] :
      { std::pair{ &largest, "Pareto front, largest" }, std::pair{ &rms, "Pareto front, RMS" } })
    {
      series.push_back(paretoFront(times, *errors));
      series.back().name = name;
      series.back().color = { 210, 210, 210 };
      series.back().wide = true;
    }
    series.insert(series.end(), lines.begin(), lines.end());
    return series;
  }

  std::vector<AccuracyRow> rows;

private:
  struct Family
  {
    std::string name;
    std::vector<double> milliseconds, largest, rms;
  };

  void addPoint(const std::string& family, double milliseconds, const Differences& errors)
  {
    auto found = std::find_if(families_.begin(), families_.end(), [&](const Family& f) { return f.name == family; });
    if (found == families_.end())
    {
      found = families_.insert(families_.end(), Family{ family, {}, {}, {} });
    }
    found->milliseconds.push_back(milliseconds);
    found->largest.push_back(errors.largest);
    found->rms.push_back(errors.rms);
  }

  std::string name_;
  const Mesh& bunny_;
  std::vector<std::vector<std::string>> termRuns_;
  std::string chartedTerm_;
  int maxRepeats_;
  MethodRun reference_;
  std::vector<Family> families_;
};

/// The largest and RMS of an array's values.
Differences magnitudes(vtkDataArray* values)
{
  DifferenceSum sum;
  for (vtkIdType t = 0; t < values->GetNumberOfTuples(); ++t)
  {
    for (int c = 0; c < values->GetNumberOfComponents(); ++c)
    {
      sum.add(std::abs(values->GetComponent(t, c)));
    }
  }
  return sum.result();
}

std::string verticesText(const Mesh& mesh)
{
  return std::to_string(mesh.data->GetNumberOfPoints()) + " vertices";
}

/// "Diffuse under FILE x INTENSITY<condition>, bunny (N vertices)": a map study's chart title.
std::string diffuseUnderMapTitle(const EnvironmentLight& map, const Mesh& bunny, const std::string& condition)
{
  std::ostringstream title;
  title << "Diffuse under " << std::filesystem::path(map.file).filename().string() << " x " << map.intensity
        << condition << ", bunny (" << verticesText(bunny) << ")";
  return title.str();
}
}

DistributedStudyInputs readDistributedStudyInputs(const AccuracyOptions& options)
{
  DistributedStudyInputs inputs;
  try
  {
    inputs.softbox = readSceneFile(options.areaLightScene);
  }
  catch (const SceneFileError& error)
  {
    throw UserError(
      std::string(error.what()) + "; the area-light study reads it: run from the repository's top folder");
  }
  const auto softbox = std::find_if(inputs.softbox.lights.begin(), inputs.softbox.lights.end(),
    [](const NamedLight& light) { return light.name == "softbox" && std::holds_alternative<AreaLight>(light.source); });
  if (softbox == inputs.softbox.lights.end())
  {
    throw UserError(
      options.areaLightScene + ": has no area light named 'softbox', which the area-light study measures");
  }
  inputs.softbox = withLight(inputs.softbox, *softbox);

  if (!std::filesystem::is_directory(options.envmapFolder))
  {
    throw UserError(options.envmapFolder +
      ": no such folder (the environment-map studies read the maps bundled "
      "in data/envmaps: run from the repository's top folder)");
  }
  auto mapLight = [&](const std::string& file, double intensity)
  {
    EnvironmentLight light;
    light.file = options.envmapFolder + "/" + file;
    try
    {
      light.map = std::make_shared<const EnvironmentMap>(readEnvironmentMap(light.file));
    }
    catch (const std::runtime_error& error)
    {
      throw UserError(std::string(error.what()) + "; the environment-map studies read it");
    }
    light.intensity = intensity;
    return light;
  };
  inputs.sunset = mapLight("venice_sunset_1k.hdr", 0.3);
  inputs.studio = mapLight("studio_small_03_1k.hdr", 0.04);
  return inputs;
}

std::vector<AccuracyRow> areaLightStudy(
  const Mesh& bunny, const Scene& softbox, bool shadows, int maxRepeats, ChartSpec& chart)
{
  const std::string name = softbox.lights.front().name;
  AreaLight light = std::get<AreaLight>(softbox.lights.front().source);
  auto lit = [&] { return withLight(softbox, { name, light, shadows }); };
  // The total shows both estimates at once: the exact estimator's error is its sampled S (and,
  // with shadows, its sampled visible fraction).
  DistributedStudy study(shadows ? "6 area light, soft shadows" : "6 area light", bunny,
    { { "diffuse", "specular", "total" } }, "total", maxRepeats);
  const std::string stdErrorArray = name + "_specular_std_error";
  light.estimator = AreaEstimator::Exact;
  light.sampling = { areaReferenceSamples, true };
  const MethodRun& reference = study.measureReference(lit(), { stdErrorArray });
  const Differences referenceError = magnitudes(arrayOf(reference, stdErrorArray));
  std::ostringstream note;
  note << std::setprecision(2) << "E exact (Lambert's polygon formula), S "
       << (shadows ? "and the visible fraction " : "") << "by Monte Carlo with " << areaReferenceSamples
       << " stratified samples, float64; the standard error of its specular term is at most " << referenceError.largest
       << " (RMS " << referenceError.rms << ")";
  study.addReferenceRow("samples", areaReferenceSamples, note.str());
  for (const bool stratified : { true, false })
  {
    light.sampling.stratified = stratified;
    for (const auto& [estimator, family] : { std::pair{ AreaEstimator::Exact, "exact E, S sampled, " },
           std::pair{ AreaEstimator::MonteCarlo, "monte_carlo, " } })
    {
      light.estimator = estimator;
      for (const int samples : sampleCounts)
      {
        light.sampling.samples = samples;
        study.measure(family + samplingName(stratified), "samples", samples, lit());
      }
    }
  }
  // Samples to a target ("samples": "auto" under a tolerance, at least the default 64 and at
  // most 4096), exact E: S to the target and, with shadows, E through its visible fraction. The
  // total errs by at most kd times E's error and ks times S's, at 95% each.
  light.estimator = AreaEstimator::Exact;
  light.sampling = Sampling{};
  for (const double error : { 0.1, 0.03, 0.01, 0.003 })
  {
    std::vector<LightMethod> methods(1);
    const SamplingTarget target = SamplingTarget::atLeast(error, light.sampling.samples, light.sampling.maximum);
    methods[0].targets.specular = target;
    if (shadows)
    {
      methods[0].targets.irradiance = target;
    }
    study.measure("exact E, S sampled, to a target", "E and S within (95%)", error, lit(), methods,
      error * (largestComponent(softbox.material.ks) + (shadows ? largestComponent(softbox.material.kd) : 0.0)));
  }
  light.estimator = AreaEstimator::Point;
  study.measure("point", "(no samples)", 0, lit());
  chart.series = study.chartSeries();
  chart.title = std::string("Total under the softbox") + (shadows ? " with its soft shadows" : "") +
    ", Blinn-Phong eta " + std::to_string(int(softbox.material.shininess)) + ", bunny (" + verticesText(bunny) + ")";
  chart.xTitle = "time per run (ms, median; 4 to 1024 samples along each line, targets 0.1 to 0.003)";
  chart.yTitle = "|error| of the total against the reference: largest (solid), RMS (dashed)";
  chart.logX = chart.logY = true;
  chart.legendOutside = true;
  return study.rows;
}

std::vector<AccuracyRow> environmentMapStudy(const Mesh& bunny, const Scene& material, const EnvironmentLight& map,
  const std::string& studyName, int maxRepeats, ChartSpec& chart)
{
  EnvironmentLight light = map;
  auto lit = [&] { return withLight(material, { "envmap", light }); };
  // Diffuse and specular in runs of their own: SH is about the diffuse term, which it gives
  // without sampling, and its time would otherwise be that of the sampled specular term.
  DistributedStudy study(studyName, bunny, { { "diffuse" }, { "specular" } }, "diffuse", maxRepeats);
  light.estimator = EnvironmentEstimator::BruteForce;
  light.bruteForceWidth = mapReferenceWidth;
  study.measureReference(lit(), {});
  study.addReferenceRow("width", mapReferenceWidth,
    "brute_force at width " + std::to_string(mapReferenceWidth) + " (the " + std::to_string(map.map->width) + "x" +
      std::to_string(map.map->height) + " map averaged by solid angle), float64");
  for (const int width : { 32, 64, 128 })
  {
    light.bruteForceWidth = width;
    study.measure("brute_force", "width", width, lit());
  }
  light.estimator = EnvironmentEstimator::SphericalHarmonics;
  study.measure("sh", "S samples (luminance and lobe)", light.sampling.samples, lit());
  light.estimator = EnvironmentEstimator::MonteCarlo;
  for (const auto& [directions, family] : { std::pair{ EnvironmentDirections::Luminance, "monte_carlo by luminance" },
         std::pair{ EnvironmentDirections::Cosine, "monte_carlo by cosine" } })
  {
    light.directions = directions;
    for (const int samples : sampleCounts)
    {
      light.sampling.samples = samples;
      study.measure(family, "samples", samples, lit());
    }
  }
  // Samples to a target ("samples": "auto" under a tolerance, at least the default 64 and at
  // most 4096): E's error at 95%, which is the diffuse term's times kd.
  light.directions = EnvironmentDirections::Luminance;
  light.sampling = Sampling{};
  for (const double error : { 0.1, 0.03, 0.01, 0.003 })
  {
    std::vector<LightMethod> methods(1);
    methods[0].targets.irradiance = SamplingTarget::atLeast(error, light.sampling.samples, light.sampling.maximum);
    study.measure("monte_carlo by luminance, to a target", "E within (95%)", error, lit(), methods,
      error * largestComponent(material.material.kd));
  }
  chart.series = study.chartSeries();
  chart.title = diffuseUnderMapTitle(map, bunny, "");
  chart.xTitle =
    "time per run, diffuse term only (ms, median; widths 32 to 128, samples 4 to 1024, targets 0.1 to 0.003)";
  chart.yTitle = "|error| of the diffuse term against brute force " + std::to_string(mapReferenceWidth) +
    ": largest (solid), RMS (dashed)";
  chart.logX = chart.logY = true;
  chart.legendOutside = true;
  return study.rows;
}

std::vector<AccuracyRow> environmentShadowStudy(const Mesh& bunny, const Scene& material, const EnvironmentLight& map,
  const std::string& studyName, int maxRepeats, ChartSpec& chart)
{
  EnvironmentLight light = map;
  auto lit = [&] { return withLight(material, { "envmap", light, true }); };
  DistributedStudy study(studyName, bunny, { { "diffuse" } }, "diffuse", maxRepeats);
  light.estimator = EnvironmentEstimator::MonteCarlo;
  light.directions = EnvironmentDirections::Mis;
  light.sampling = { areaReferenceSamples, true };
  const std::string stdErrorArray = "envmap_irradiance_std_error";
  const MethodRun& reference = study.measureReference(lit(), { stdErrorArray });
  const Differences referenceError = magnitudes(arrayOf(reference, stdErrorArray));
  std::ostringstream note;
  note << std::setprecision(2) << "monte_carlo by mis with " << areaReferenceSamples
       << " stratified samples and their shadow rays, float64; the standard error of its irradiance is at most "
       << referenceError.largest << " (RMS " << referenceError.rms << "), to be multiplied by kd";
  study.addReferenceRow("samples", areaReferenceSamples, note.str());
  // The light as it is set, at each sample count, with the charted term's predicted bound.
  auto overSampleCounts = [&](
                            const std::string& family, bool stratified, std::optional<double> predicted = std::nullopt)
  {
    for (const int samples : sampleCounts)
    {
      light.sampling = { samples, stratified };
      study.measure(family + ", " + samplingName(stratified), "samples", samples, lit(), {}, predicted);
    }
  };
  const std::pair<EnvironmentDirections, const char*> kinds[] = { { EnvironmentDirections::Luminance, "luminance" },
    { EnvironmentDirections::Cosine, "cosine" }, { EnvironmentDirections::Mis, "mis" } };
  for (const auto& [directions, name] : kinds)
  {
    light.directions = directions;
    overSampleCounts(std::string("monte_carlo by ") + name, true);
  }
  light.directions = EnvironmentDirections::Mis;
  overSampleCounts("monte_carlo by mis", false);
  light.estimator = EnvironmentEstimator::SphericalHarmonics;
  overSampleCounts("sh x visible fraction by mis", true);
  // Precomputed transfer: the map's bands dotted with transfer vectors from cosine-weighted
  // rays, so its error levels off at the band limit's as the rays grow. Predicted: that limit's
  // bound in the diffuse term (docs/formulas.md section 12.10), without the rays' own error.
  light.estimator = EnvironmentEstimator::PrecomputedTransfer;
  for (int order = 2; order <= largestShOrder; ++order)
  {
    light.shOrder = order;
    const Rgb bandLimit = bandLimitError(*light.map, order);
    overSampleCounts("prt of order " + std::to_string(order), true,
      largestComponent(material.material.kd * light.color * light.intensity * bandLimit));
  }
  chart.series = study.chartSeries();
  chart.title = diffuseUnderMapTitle(map, bunny, " with its shadows");
  chart.xTitle = "time per run, rays included (ms, median; 4 to 1024 samples along each line)";
  chart.yTitle = "|error| of the diffuse term against monte_carlo by mis, 16384 samples: largest (solid), RMS (dashed)";
  chart.logX = chart.logY = true;
  chart.legendOutside = true;
  return study.rows;
}

std::vector<AccuracyRow> speedRequirementRows(const Mesh& bunny, const Scene& material, const EnvironmentLight& map)
{
  const vtkIdType count = bunny.data->GetNumberOfPoints();
  std::vector<glm::dvec3> points(count), normals(count);
  vtkDataArray* meshNormals = bunny.data->GetPointData()->GetNormals();
  for (vtkIdType i = 0; i < count; ++i)
  {
    bunny.data->GetPoint(i, &points[i].x);
    meshNormals->GetTuple(i, &normals[i].x);
  }
  // The kernel on one thread, made before the timing: the coefficients exist by then.
  auto nanosecondsPerVertex = [&](const Scene& scene)
  {
    std::vector<float> diffuse(3 * count);
    const ShadingKernel<float> kernel(scene, oneTotal(scene, TotalTerm::Diffuse, diffuse.data()));
    const double ms = medianMilliseconds(
      [&]
      {
        shadeRange(kernel, 0, count,
          [&](std::size_t i, VertexBlock<float>& block, std::size_t k) { block.set(k, points[i], normals[i]); });
      },
      9, 99);
    return 1e6 * ms / count;
  };
  const double lambert = nanosecondsPerVertex(withLight(material, { "sun", DistantLight{ { -1, -1, -1 } } }));
  EnvironmentLight sh = map;
  sh.estimator = EnvironmentEstimator::SphericalHarmonics;
  const double shPerVertex = nanosecondsPerVertex(withLight(material, { "envmap", sh }));
  std::ostringstream note;
  note << std::setprecision(3) << "diffuse only, float32, one thread, the kernel made beforehand: sh " << shPerVertex
       << " ns per vertex, a distant light's Lambert term " << lambert << " ns";

  const double projection = medianMilliseconds([&] { projectRadiance(*map.map); }, 5, 15);
  const std::string mapSize = std::to_string(map.map->width) + "x" + std::to_string(map.map->height);
  return { { "speed requirements", "sh irradiance time per vertex / Lambert's", "ratio", shPerVertex / lambert, count,
             std::nullopt, std::nullopt, std::nullopt, std::nullopt, note.str() },
    { "speed requirements", "projectRadiance of a " + mapSize + " map", "texels",
      double(map.map->width) * map.map->height, 0, projection, std::nullopt, std::nullopt, std::nullopt,
      "one thread, median; " + std::filesystem::path(map.file).filename().string() } };
}
}
