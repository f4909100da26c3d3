#include "AccuracyStudies.h"

#include "AccuracyStudyParts.h"
#include "BenchmarkMeshes.h"
#include "Chart.h"
#include "CsvText.h"
#include "DistributedStudies.h"
#include "InterreflectionStudies.h"
#include "MeshFiles.h"
#include "MetallicRoughness.h"
#include "SceneFile.h"
#include "SpectralStudies.h"
#include "TextureStudies.h"

#include "vtkLocalReflectanceFilter.h"

#include "vtkDataArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>
#include <tuple>

namespace shadelab::app
{
MethodRun runMethod(vtkPolyData* mesh, const Scene& scene, const std::vector<std::string>& arrays, Precision precision,
  const std::vector<LightMethod>& methods, int maxRepeats, int minRepeats)
{
  vtkNew<vtkLocalReflectanceFilter> filter;
  filter->SetInputData(mesh);
  // The normals (computed, or tested for pointing inward) are prepared in a run of their own,
  // which the filter keeps while the input is unchanged; one distant light makes that run
  // cheap even when the scene's estimators take seconds.
  Scene lambert;
  lambert.lights = { { "sun", DistantLight{} } };
  filter->SetScene(lambert);
  filter->SetArraySelection({ "shading_flags" });
  filter->Update();
  filter->SetScene(scene);
  filter->SetArraySelection(arrays);
  filter->SetOutputPrecision(
    precision == Precision::Float64 ? vtkAlgorithm::DOUBLE_PRECISION : vtkAlgorithm::SINGLE_PRECISION);
  filter->SetLightMethods(methods);
  MethodRun run;
  run.milliseconds = medianMilliseconds(
    [&]
    {
      filter->Modified();
      filter->Update();
    },
    minRepeats, maxRepeats);
  run.output = vtkSmartPointer<vtkPolyData>::New();
  run.output->ShallowCopy(filter->GetOutput());
  return run;
}

vtkDataArray* arrayOf(const MethodRun& run, const std::string& name)
{
  return run.output->GetPointData()->GetArray(name.c_str());
}

namespace
{
std::string precisionText(Precision precision)
{
  return precision == Precision::Float32 ? "float32" : "float64";
}

/// The bounding box's centre and half diagonal.
MeshExtent boundingSphere(vtkPolyData* mesh)
{
  MeshExtent extent;
  mesh->GetCenter(&extent.centre.x);
  extent.radius = mesh->GetLength() / 2;
  return extent;
}

/// The bunny's scene: a point light above and to the side, Blinn-Phong, a local viewer.
Scene bunnyScene(vtkPolyData* mesh, double shininess)
{
  const MeshExtent extent = boundingSphere(mesh);
  const glm::dvec3 centre = extent.centre;
  const double radius = extent.radius;
  Scene scene;
  scene.viewer.position = centre + glm::dvec3(0, 0, 4 * radius);
  scene.material = { Rgb(0.1), Rgb(0.7, 0.6, 0.5), Rgb(0.4), shininess, SpecularModel::BlinnPhong, false, {} };
  PointLight key;
  key.position = centre + radius * glm::dvec3(2, 2, 2);
  key.intensity = 12 * radius * radius;
  scene.lights = { { "key", key } };
  return scene;
}

/// 1. float32 against float64, and the three pow methods, on the subdivided bunny.
std::vector<AccuracyRow> arithmeticStudy(const Mesh& mesh, int maxRepeats, ChartSpec& chart)
{
  const Scene scene = bunnyScene(mesh.data, 30);
  const MethodRun reference = runMethod(mesh.data, scene, { "total" }, Precision::Float64, {}, maxRepeats);
  std::vector<AccuracyRow> rows;
  std::vector<double> times, errors;
  for (const Precision precision : { Precision::Float64, Precision::Float32 })
  {
    for (const PowMethod pow : { PowMethod::Exact, PowMethod::Series, PowMethod::Schlick })
    {
      const MethodRun run =
        runMethod(mesh.data, scene, { "total" }, precision, { LightMethod{ std::nullopt, pow, {} } }, maxRepeats);
      const Differences stats = compareArrays(arrayOf(reference, "total"), arrayOf(run, "total"));
      // The kernel's exact power in float32 at a whole eta is binary exponentiation.
      const std::string method =
        precision == Precision::Float32 && pow == PowMethod::Exact && isWholeExponent(scene.material.shininess)
        ? "exact pow (binary exponentiation)"
        : powMethodName(pow);
      AccuracyRow row{ "1 arithmetic and pow", precisionText(precision) + ", " + method, "eta", 30,
        mesh.data->GetNumberOfPoints(), run.milliseconds, stats.largest, stats.rms, std::nullopt, "" };
      if (precision == Precision::Float64 && pow == PowMethod::Exact)
      {
        row.note = "the reference";
      }
      rows.push_back(row);
      chart.series.push_back(
        { row.method, { run.milliseconds }, { stats.largest }, false, palette[chart.series.size()] });
      times.push_back(run.milliseconds);
      errors.push_back(stats.largest);
    }
  }
  chart.series.push_back(paretoFront(times, errors)); // the reference's error 0 is off the log axis
  chart.title = "Total, one point light, Blinn-Phong eta = 30, " + mesh.name + " (" +
    std::to_string(mesh.data->GetNumberOfPoints()) + " vertices): error against float64 std::pow";
  chart.xTitle = "time per run (ms, median)";
  chart.yTitle = "largest |error| over the mesh";
  chart.logY = true;
  return rows;
}

/// 2. The pow methods alone, over eta, including eta = 0 and eta = 10000 (failure points).
std::vector<AccuracyRow> powStudy(ChartSpec& chart)
{
  constexpr std::size_t count = 1 << 20;
  std::vector<float> x(count), y(count);
  for (std::size_t i = 0; i < count; ++i)
  {
    x[i] = float(i) / float(count - 1);
  }
  std::vector<AccuracyRow> rows;
  std::vector<double> times, errors;
  int colour = 0;
  // One method's row per eta; eta = 0 and 10000 are failure points, in the CSV only.
  auto measureOverEta = [&](const std::string& label, auto&& run, auto&& largestError)
  {
    ChartSeries series{ label, {}, {}, false, palette[colour++] };
    for (const double eta : { 0.0, 1.0, 10.0, 100.0, 1000.0, 10000.0 })
    {
      const double ms = medianMilliseconds([&] { run(eta); }, 5, 15);
      const double error = largestError(eta);
      const bool failurePoint = eta == 0 || eta == 10000;
      rows.push_back({ "2 pow", label + " (float32)", "eta", eta, count, ms, error, 0, std::nullopt,
        failurePoint ? "failure point" : "" });
      if (!failurePoint)
      {
        series.x.push_back(ms);
        series.y.push_back(error);
        times.push_back(ms);
        errors.push_back(error);
      }
    }
    chart.series.push_back(series);
  };
  for (const PowMethod method : { PowMethod::Exact, PowMethod::Series, PowMethod::Schlick })
  {
    measureOverEta(
      powMethodName(method), [&](double eta) { evaluatePowers(method, x.data(), y.data(), count, float(eta)); },
      [&](double eta) { return largestPowError<float>(method, eta); });
  }
  // What the kernel's exact method does in float32 when eta is a whole number.
  measureOverEta(
    "binary exponentiation, whole eta",
    [&](double eta) { wholePowers(x.data(), y.data(), count, static_cast<unsigned>(eta)); },
    [&](double eta) { return largestWholePowerError(static_cast<unsigned>(eta)); });
  chart.series.push_back(paretoFront(times, errors));
  chart.title = "x^eta in float32 for 2^20 x in [0, 1], eta = 1, 10, 100, 1000: largest error against exact";
  chart.xTitle = "time for 2^20 values (ms, median, one thread)";
  chart.yTitle = "largest |x^eta - exact| over x in [0, 1]";
  chart.logY = true;
  return rows;
}

/// 3. A point light taken as distant, against its distance from the mesh's centre. At 0.5
/// radii the light is inside the mesh's bounding sphere, where the approximation fails.
std::vector<AccuracyRow> distantStudy(const Mesh& mesh, int maxRepeats, ChartSpec& chart)
{
  Scene scene = bunnyScene(mesh.data, 30);
  scene.material.specular = SpecularModel::None;
  const MeshExtent extent = boundingSphere(mesh.data);
  std::vector<AccuracyRow> rows;
  ChartSeries largest{ "largest error", {}, {}, true, palette[0] };
  ChartSeries rms{ "RMS error", {}, {}, true, palette[1] };
  ChartSeries bound{ "predicted bound", {}, {}, true, palette[3] };
  for (const double ratio : { 0.5, 1.5, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 1000.0 })
  {
    PointLight& key = std::get<PointLight>(scene.lights[0].source);
    key.position = extent.centre + ratio * extent.radius * glm::dvec3(1, 1, 1) / std::sqrt(3.0);
    key.intensity = ratio * ratio * extent.radius * extent.radius; // about 1 at the mesh
    const MethodRun exact = runMethod(mesh.data, scene, { "diffuse" }, Precision::Float64, {}, maxRepeats);
    const MethodRun exact32 = runMethod(mesh.data, scene, { "diffuse" }, Precision::Float32, {}, maxRepeats);
    const MethodRun distant = runMethod(mesh.data, scene, { "diffuse" }, Precision::Float32,
      { LightMethod{ extent.centre, PowMethod::Exact, {} } }, maxRepeats);
    const MethodRun distant64 = runMethod(
      mesh.data, scene, { "diffuse" }, Precision::Float64, { LightMethod{ extent.centre, PowMethod::Exact, {} } }, 1);
    const Differences stats = compareArrays(arrayOf(exact, "diffuse"), arrayOf(distant64, "diffuse"));
    const double predicted = distantApproximationError(key, scene.material, false, extent);
    std::ostringstream note;
    note << std::setprecision(3) << "exact point light (float32) " << exact32.milliseconds << " ms";
    if (ratio <= 1)
    {
      note << "; failure point: the light is inside the mesh's bounding sphere";
    }
    rows.push_back({ "3 point light as distant", "distant from the centre (float32 time)", "distance / radius", ratio,
      mesh.data->GetNumberOfPoints(), distant.milliseconds, stats.largest, stats.rms,
      std::isfinite(predicted) ? std::optional<double>(predicted) : std::nullopt, note.str() });
    for (ChartSeries* series : { &largest, &rms, &bound })
    {
      series->x.push_back(ratio);
    }
    largest.y.push_back(stats.largest);
    rms.y.push_back(stats.rms);
    bound.y.push_back(std::isfinite(predicted) ? predicted : 0);
  }
  chart.series = { largest, rms, bound };
  chart.title = "Diffuse, a point light (1/d^2) taken as distant, " + mesh.name + ": error against distance";
  chart.xTitle = "light's distance from the mesh's centre / mesh radius";
  chart.yTitle = "|error| of the diffuse term (light about 1 at the mesh)";
  chart.logX = chart.logY = true;
  return rows;
}

/// 4. Phong at eta against Blinn-Phong at 4 eta (the usual conversion).
std::vector<AccuracyRow> phongStudy(const Mesh& mesh, int maxRepeats, ChartSpec& chart)
{
  std::vector<AccuracyRow> rows;
  ChartSeries largest{ "largest difference", {}, {}, true, palette[0] };
  ChartSeries rms{ "RMS difference", {}, {}, true, palette[1] };
  for (const double eta : { 1.0, 10.0, 100.0, 1000.0 })
  {
    Scene phong = bunnyScene(mesh.data, eta);
    phong.material.specular = SpecularModel::Phong;
    Scene blinn = bunnyScene(mesh.data, 4 * eta);
    const MethodRun a = runMethod(mesh.data, phong, { "specular" }, Precision::Float32, {}, maxRepeats);
    const MethodRun b = runMethod(mesh.data, blinn, { "specular" }, Precision::Float32, {}, maxRepeats);
    const Differences stats = compareArrays(arrayOf(a, "specular"), arrayOf(b, "specular"));
    std::ostringstream note;
    note << std::setprecision(3) << "Phong " << a.milliseconds << " ms, Blinn-Phong " << b.milliseconds << " ms";
    rows.push_back({ "4 Phong vs Blinn-Phong x4", "Phong(eta) - Blinn-Phong(4 eta), specular", "eta", eta,
      mesh.data->GetNumberOfPoints(), b.milliseconds, stats.largest, stats.rms, std::nullopt, note.str() });
    largest.x.push_back(eta);
    rms.x.push_back(eta);
    largest.y.push_back(stats.largest);
    rms.y.push_back(stats.rms);
  }
  chart.series = { largest, rms };
  chart.title = "Specular term, Phong with eta against Blinn-Phong with 4 eta, " + mesh.name;
  chart.xTitle = "Phong exponent eta";
  chart.yTitle = "|difference| of the specular term";
  chart.logX = chart.logY = true;
  return rows;
}

/// The specular term over its largest value on the mesh, against the angle between n and h in
/// degrees, at every stride-th vertex where it is above 1e-6 of that largest (a log axis).
ChartSeries normalisedLobe(const MethodRun& run, const std::string& name, std::array<unsigned char, 3> color)
{
  vtkDataArray* specular = arrayOf(run, "key_specular");
  vtkDataArray* nDotH = arrayOf(run, "key_n_dot_h");
  double largest = 0;
  for (vtkIdType i = 0; i < specular->GetNumberOfTuples(); ++i)
  {
    largest = std::max(largest, specular->GetComponent(i, 1));
  }
  ChartSeries series{ name, {}, {}, false, color };
  const vtkIdType stride = std::max<vtkIdType>(1, specular->GetNumberOfTuples() / 3000);
  for (vtkIdType i = 0; i < specular->GetNumberOfTuples(); i += stride)
  {
    const double value = specular->GetComponent(i, 1) / largest;
    if (value > 1e-6)
    {
      series.x.push_back(std::acos(std::clamp(nDotH->GetComponent(i, 0), -1.0, 1.0)) * 180 / 3.14159265358979323846);
      series.y.push_back(value);
    }
  }
  return series;
}

/// 15. The lecture's Phong and Blinn-Phong lobes against VTK's PBR microfacet model (the
/// vtk_pbr model: GGX, Smith, Schlick) on the same mesh, light and viewer, with lobes of matched
/// width: GGX of roughness r, Blinn-Phong of Walter's eta = 2 / r^4 - 2 (the exponent whose lobe
/// matches it; docs/formulas.md section 7.3) and Phong of eta / 4.
std::vector<AccuracyRow> reflectanceModelsStudy(const Mesh& mesh, int maxRepeats, ChartSpec& chart)
{
  const double roughness = 0.4;
  const double blinnEta = lectureCoefficients(Rgb(1.0), 0.0, roughness).shininess;
  Scene blinn = bunnyScene(mesh.data, blinnEta);
  // VTK's attenuation 1 / d^2, which every model accepts, and a local viewer, which VTK has.
  auto& key = std::get<PointLight>(blinn.lights[0].source);
  key.attenuation.model = AttenuationModel::ConstantLinearQuadratic;
  key.attenuation.constant = 0;
  key.attenuation.quadratic = 1;
  Scene phong = blinn;
  phong.material.specular = SpecularModel::Phong;
  phong.material.shininess = blinnEta / 4;
  Scene microfacet = blinn;
  microfacet.model = ShadingModel::VtkPbr;
  microfacet.material.microfacet.baseColor = blinn.material.kd;
  microfacet.material.microfacet.roughness = roughness;
  const std::vector<std::string> arrays = { "key_specular", "key_n_dot_h" };
  std::vector<AccuracyRow> rows;
  std::ostringstream parameters;
  parameters << std::setprecision(3) << "roughness " << roughness << ", Blinn-Phong eta " << blinnEta << ", Phong eta "
             << blinnEta / 4;
  int colour = 0;
  for (const auto& [name, scene] : { std::pair{ "Phong", &phong }, std::pair{ "Blinn-Phong", &blinn },
         std::pair{ "GGX microfacets (vtk_pbr)", &microfacet } })
  {
    const MethodRun run = runMethod(mesh.data, *scene, arrays, Precision::Float32, {}, maxRepeats);
    chart.series.push_back(normalisedLobe(run, name, palette[colour++]));
    // The share of the specular light beyond 30 degrees from the half vector: the lobe's tail.
    vtkDataArray* specular = arrayOf(run, "key_specular");
    vtkDataArray* nDotH = arrayOf(run, "key_n_dot_h");
    double all = 0, tail = 0;
    for (vtkIdType i = 0; i < specular->GetNumberOfTuples(); ++i)
    {
      all += specular->GetComponent(i, 1);
      tail += nDotH->GetComponent(i, 0) < std::cos(3.14159265358979323846 / 6) ? specular->GetComponent(i, 1) : 0;
    }
    std::ostringstream note;
    note << std::setprecision(3) << parameters.str() << "; " << 100 * tail / all
         << "% of the specular light more than 30 degrees from h";
    rows.push_back({ "15 reflectance models", name, "roughness", roughness, mesh.data->GetNumberOfPoints(),
      run.milliseconds, std::nullopt, std::nullopt, std::nullopt, note.str() });
  }
  chart.title = "15 Specular lobes on " + mesh.name + " under one point light (" + parameters.str() + ")";
  chart.xTitle = "angle between n and h (degrees)";
  chart.yTitle = "specular term / its largest on the mesh";
  chart.logY = true;
  return rows;
}

/// One total of the core kernel, evaluated in arithmetic of type T, at arbitrary points with
/// given normals.
template<typename T>
std::vector<glm::dvec3> totalAt(
  const Scene& scene, TotalTerm term, const std::vector<glm::dvec3>& points, const std::vector<glm::dvec3>& normals)
{
  std::vector<T> total(3 * points.size());
  const ShadingKernel<T> kernel(scene, oneTotal(scene, term, total.data()));
  shadeRange(kernel, 0, points.size(),
    [&](std::size_t i, VertexBlock<T>& block, std::size_t k) { block.set(k, points[i], normals[i]); });
  std::vector<glm::dvec3> result(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    result[i] = { total[3 * i], total[3 * i + 1], total[3 * i + 2] };
  }
  return result;
}

/// 5. Shading at the vertices, interpolated across each triangle (Gouraud), against shading
/// evaluated exactly inside it, on unit spheres whose true normal is the position.
std::vector<AccuracyRow> tessellationStudy(ChartSpec& chart)
{
  Scene scene;
  scene.viewer.viewDirection = { 0, 0, -1 };
  scene.material = { Rgb(0.0), Rgb(0.5), Rgb(0.5), 1, SpecularModel::BlinnPhong, false, {} };
  scene.lights = { { "sun", DistantLight{ { -1, -0.3, -1 }, Rgb(1.0), 1.0, false } } };
  // Barycentric points inside each triangle: the centroid and three points near the corners.
  const glm::dvec3 samples[] = { { 1 / 3., 1 / 3., 1 / 3. }, { 2 / 3., 1 / 6., 1 / 6. }, { 1 / 6., 2 / 3., 1 / 6. },
    { 1 / 6., 1 / 6., 2 / 3. } };
  std::vector<AccuracyRow> rows;
  int colour = 0;
  for (const double eta : { 1.0, 10.0, 100.0, 1000.0 })
  {
    scene.material.shininess = eta;
    ChartSeries series{ "eta " + std::to_string(int(eta)), {}, {}, true, palette[colour++] };
    for (const long long size : { 1000LL, 10000LL, 100000LL, 1000000LL })
    {
      const Mesh sphere = sphereOfAbout(size);
      vtkPolyData* mesh = sphere.data;
      std::vector<glm::dvec3> points(mesh->GetNumberOfPoints());
      for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
      {
        mesh->GetPoint(i, &points[i].x);
      }
      std::vector<glm::dvec3> normals = points; // a unit sphere at the origin
      const auto start = std::chrono::steady_clock::now();
      const std::vector<glm::dvec3> atVertices = totalAt<double>(scene, TotalTerm::Total, points, normals);
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      std::vector<glm::dvec3> inside, interpolated;
      vtkNew<vtkIdList> ids;
      for (vtkIdType cell = 0; cell < mesh->GetNumberOfCells(); ++cell)
      {
        mesh->GetCellPoints(cell, ids);
        for (vtkIdType k = 2; k < ids->GetNumberOfIds(); ++k) // fans of the sphere's polygons
        {
          const vtkIdType a = ids->GetId(0), b = ids->GetId(k - 1), c = ids->GetId(k);
          for (const glm::dvec3& w : samples)
          {
            inside.push_back(w.x * points[a] + w.y * points[b] + w.z * points[c]);
            interpolated.push_back(w.x * atVertices[a] + w.y * atVertices[b] + w.z * atVertices[c]);
          }
        }
      }
      std::vector<glm::dvec3> insideNormals;
      for (const glm::dvec3& p : inside)
      {
        insideNormals.push_back(glm::normalize(p));
      }
      const std::vector<glm::dvec3> exact = totalAt<double>(scene, TotalTerm::Total, inside, insideNormals);
      DifferenceSum sum;
      for (std::size_t i = 0; i < exact.size(); ++i)
      {
        sum.add(largestComponent(exact[i] - interpolated[i]));
      }
      const Differences stats = sum.result();
      rows.push_back({ "5 tessellation", "vertex shading interpolated (eta " + std::to_string(int(eta)) + ")",
        "vertices", double(points.size()), static_cast<long long>(points.size()), ms, stats.largest, stats.rms,
        std::nullopt, "" });
      series.x.push_back(double(points.size()));
      series.y.push_back(stats.largest);
    }
    chart.series.push_back(series);
  }
  chart.title = "Total on a unit sphere: vertex shading interpolated across triangles against exact inside them";
  chart.xTitle = "vertices";
  chart.yTitle = "largest |interpolated - exact| inside the triangles";
  chart.logX = chart.logY = true;
  return rows;
}

/// Failure point of float32: a vertex whose light grazes its horizon, with a viewer placed
/// on the mirror direction so that the Phong lobe is 1 where the light counts as lit. The
/// coordinates are far from the origin, so that float32 rounds the direction to the light.
/// The filter's output for the mesh under the scene: exact methods in float64 (tolerance 0),
/// or the tolerance's plan, whose predicted error goes into `predicted`.
vtkSmartPointer<vtkPolyData> shadedUnder(vtkPolyData* mesh, const Scene& scene, double tolerance,
  const std::vector<std::string>& arrays, std::optional<MethodPlan>* plan = nullptr)
{
  vtkNew<vtkLocalReflectanceFilter> filter;
  filter->SetInputData(mesh);
  filter->SetScene(scene);
  filter->SetArraySelection(arrays);
  filter->SetOutputPrecision(vtkAlgorithm::DOUBLE_PRECISION);
  filter->SetTolerance(tolerance);
  filter->Update();
  if (plan)
  {
    *plan = filter->GetMethodPlan();
  }
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->ShallowCopy(filter->GetOutput());
  return output;
}

/// The samples of an area light or a map, to set.
Sampling& samplingIn(LightSource& source)
{
  if (auto* area = std::get_if<AreaLight>(&source))
  {
    return area->sampling;
  }
  return std::get<EnvironmentLight>(source).sampling;
}

/// The 95th percentile and the largest over the points of the largest |a - b| over the named
/// arrays and their components at each.
std::pair<double, double> percentileAndLargest(vtkPolyData* a, vtkPolyData* b, const std::vector<std::string>& names)
{
  std::vector<double> errors(static_cast<std::size_t>(a->GetNumberOfPoints()), 0.0);
  for (const std::string& name : names)
  {
    vtkDataArray* x = a->GetPointData()->GetArray(name.c_str());
    vtkDataArray* y = b->GetPointData()->GetArray(name.c_str());
    for (vtkIdType i = 0; i < x->GetNumberOfTuples(); ++i)
    {
      for (int c = 0; c < x->GetNumberOfComponents(); ++c)
      {
        errors[i] = std::max(errors[i], std::abs(x->GetComponent(i, c) - y->GetComponent(i, c)));
      }
    }
  }
  std::sort(errors.begin(), errors.end());
  return { errors[errors.size() * 95 / 100], errors.back() };
}

/// 11. What a tolerance predicts against what it gets. Each bundled mesh under each bundled
/// scene of local lights at tolerances 1e-2 and 1e-5: the plan's predicted error against the
/// largest difference from float64's exact methods over the totals at every point; the studio
/// map's SH irradiance likewise against E by 16384 samples. Where the
/// bunny is sampled to a target (ambient occlusion under studio.json, the softbox with its soft
/// shadows, the studio map by mis), the error 95% of the vertices are within, in the totals and
/// the sampled arrays (E, the occlusion), against 16384 samples (whose own standard error is
/// half that of a vertex that drew the maximum, 4096): predicted by the plan (its share at 95%
/// confidence) and after sampling (from the vertices' standard errors).
std::vector<AccuracyRow> predictionStudy(ChartSpec& chart)
{
  const std::string study = "11 predicted against measured";
  std::vector<AccuracyRow> rows;
  ChartSeries plans{ "a plan's predicted error (local lights, SH): largest error", {}, {}, false, palette[0] };
  const std::vector<std::string> totals = { "totals" };
  for (const char* file : { "bunny_zipper.ply", "xyzrgb_dragon_50k.ply", "spot.obj", "teapot.obj", "owl_scan.vtp" })
  {
    const vtkSmartPointer<vtkPolyData> mesh = readMesh(std::string("data/meshes/") + file);
    for (const char* name : { "studio", "studio_mesh", "sun", "spotlight", "three_lights", "vtk_headlight" })
    {
      const Scene scene = readSceneFile(std::string("data/scenes/") + name + ".json");
      const vtkSmartPointer<vtkPolyData> exact = shadedUnder(mesh, scene, 0, totals);
      for (const double tolerance : { 1e-2, 1e-5 })
      {
        std::optional<MethodPlan> plan;
        const vtkSmartPointer<vtkPolyData> chosen = shadedUnder(mesh, scene, tolerance, totals, &plan);
        double largest = 0;
        for (const char* total : { "ambient", "diffuse", "specular", "total" })
        {
          largest = std::max(largest,
            compareArrays(chosen->GetPointData()->GetArray(total), exact->GetPointData()->GetArray(total)).largest);
        }
        rows.push_back(
          { study, std::string(file) + " under " + name + ".json", "tolerance", tolerance, mesh->GetNumberOfPoints(),
            std::nullopt, largest, std::nullopt, plan->predictedError(), plan->describe()[0] });
        plans.x.push_back(plan->predictedError());
        plans.y.push_back(largest);
      }
    }
  }
  // The studio map's SH irradiance, without a specular term (so nothing is sampled): its
  // band-limit bound against the largest difference from E by 16384 samples (mis), over E's
  // array and the totals.
  const vtkSmartPointer<vtkPolyData> bunny = readMesh("data/meshes/bunny_zipper.ply");
  Scene harmonics = readSceneFile("data/scenes/studio_envmap.json");
  harmonics.material.ks = Rgb(0.0);
  Scene sampledMap = harmonics;
  auto& reference = std::get<EnvironmentLight>(sampledMap.lights[0].source);
  reference.estimator = EnvironmentEstimator::MonteCarlo;
  reference.directions = EnvironmentDirections::Mis;
  reference.sampling.samples = 16384;
  const std::vector<std::string> mapArrays = { "total", "studio_irradiance" };
  const vtkSmartPointer<vtkPolyData> sampledE = shadedUnder(bunny, sampledMap, 0, mapArrays);
  {
    const double tolerance = 0.2; // the bound, 0.12, fits
    std::optional<MethodPlan> plan;
    const vtkSmartPointer<vtkPolyData> chosen = shadedUnder(bunny, harmonics, tolerance, mapArrays, &plan);
    const double largest = percentileAndLargest(chosen, sampledE, mapArrays).second;
    rows.push_back({ study, "bunny_zipper.ply under studio_envmap.json (sh, no specular term)", "tolerance", tolerance,
      bunny->GetNumberOfPoints(), std::nullopt, largest, std::nullopt, plan->predictedError(), plan->describe()[1] });
    plans.x.push_back(plan->predictedError());
    plans.y.push_back(largest);
  }
  ChartSeries sampledPlans{ "sampled to a target: the plan's share, 95th percentile", {}, {}, false, palette[1] };
  ChartSeries afterSampling{ "sampled to a target: estimated after sampling, 95th percentile", {}, {}, false,
    palette[2] };
  Scene occluded = readSceneFile("data/scenes/studio.json");
  occluded.ambientOcclusion = AmbientOcclusion{};
  Scene studioMap = readSceneFile("data/scenes/studio_envmap.json");
  auto& map = std::get<EnvironmentLight>(studioMap.lights[0].source);
  map.estimator = EnvironmentEstimator::MonteCarlo;
  map.directions = EnvironmentDirections::Mis;
  struct SampledCase
  {
    std::string label;
    Scene drawn;
    std::vector<std::string> arrays;
    std::vector<double> tolerances;
  };
  const std::vector<SampledCase> cases = {
    { "ambient occlusion to a target, bunny under studio.json", occluded, { "total", "ambient_occlusion" },
      { 0.1, 0.05, 0.02, 0.01 } },
    { "the softbox and its soft shadows to a target, bunny under soft_shadows_to_a_tolerance.json",
      readSceneFile("data/scenes/soft_shadows_to_a_tolerance.json"), { "total", "softbox_irradiance" },
      { 0.05, 0.02, 0.01 } },
    { "the studio map by mis to a target, bunny under studio_envmap.json", studioMap, { "total", "studio_irradiance" },
      { 0.05, 0.02, 0.01 } },
  };
  for (const SampledCase& sampled : cases)
  {
    Scene fixed = sampled.drawn;
    Scene drawn = sampled.drawn;
    Sampling& fixedSampling =
      fixed.ambientOcclusion ? fixed.ambientOcclusion->sampling : samplingIn(fixed.lights[0].source);
    fixedSampling.fromTolerance = false;
    fixedSampling.samples = 16384;
    (drawn.ambientOcclusion ? drawn.ambientOcclusion->sampling : samplingIn(drawn.lights[0].source)).fromTolerance =
      true;
    const vtkSmartPointer<vtkPolyData> reference = shadedUnder(bunny, fixed, 0, sampled.arrays);
    for (const double tolerance : sampled.tolerances)
    {
      std::optional<MethodPlan> plan;
      const vtkSmartPointer<vtkPolyData> run = shadedUnder(bunny, drawn, tolerance, sampled.arrays, &plan);
      const auto [percentile95, largest] = percentileAndLargest(run, reference, sampled.arrays);
      const std::string measured = "95th percentile " + std::to_string(percentile95);
      rows.push_back({ study, sampled.label + ": the plan", "tolerance", tolerance, bunny->GetNumberOfPoints(),
        std::nullopt, largest, std::nullopt, plan->predictedError(), measured });
      rows.push_back({ study, sampled.label + ": estimated after sampling", "tolerance", tolerance,
        bunny->GetNumberOfPoints(), std::nullopt, largest, std::nullopt, plan->estimatedError(), measured });
      sampledPlans.x.push_back(plan->predictedError());
      sampledPlans.y.push_back(percentile95);
      afterSampling.x.push_back(plan->estimatedError());
      afterSampling.y.push_back(percentile95);
    }
  }
  const double low = 1e-9, high = 1.0;
  ChartSeries equal{ "measured = predicted", { low, high }, { low, high }, true, { 0, 0, 0 } };
  equal.dashed = true;
  ChartSeries third{ "measured = predicted / 3", { low, high }, { low / 3, high / 3 }, true, { 150, 150, 150 } };
  third.dashed = true;
  chart = { "Predicted against measured error: tolerances' plans, and samples to a target",
    "predicted error (the plan's; sampled parts at 95%)", "measured error (sampled: 95th percentile)", true, true, true,
    { equal, third, plans, sampledPlans, afterSampling } };
  return rows;
}

std::vector<AccuracyRow> grazingRows()
{
  std::vector<AccuracyRow> rows;
  const glm::dvec3 position(1000.1, 2000.3, 500.7);
  const glm::dvec3 n = glm::normalize(glm::dvec3(1, 2, 3));
  const glm::dvec3 tangent = glm::normalize(glm::cross(n, glm::dvec3(0, 0, 1)));
  for (const double elevation : { 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7 })
  {
    const glm::dvec3 toLight = glm::normalize(tangent + elevation * n);
    Scene scene;
    scene.material = { Rgb(0.0), Rgb(0.0), Rgb(1.0), 30, SpecularModel::Phong, false, {} };
    PointLight light;
    light.position = position + 10.0 * toLight;
    light.intensity = 100; // 1 at the vertex
    scene.lights = { { "grazing", light } };
    const glm::dvec3 mirror = 2 * glm::dot(n, toLight) * n - toLight;
    scene.viewer.viewDirection = -mirror;
    const double exact = totalAt<double>(scene, TotalTerm::Specular, { position }, { n })[0].x;
    const double rounded = totalAt<float>(scene, TotalTerm::Specular, { position }, { n })[0].x;
    rows.push_back({ "failure points", "float32 near grazing incidence (Phong, eta 30)", "light elevation (rad)",
      elevation, 1, std::nullopt, std::abs(rounded - exact), std::abs(rounded - exact), std::nullopt,
      "float64 specular " + std::to_string(exact) });
  }
  return rows;
}

void printRows(const std::vector<AccuracyRow>& rows)
{
  for (const AccuracyRow& r : rows)
  {
    std::cout << "  " << std::left << std::setw(48) << r.method << " " << r.parameter << " " << std::setw(8) << r.value
              << std::right;
    if (r.maxError && r.rmsError)
    {
      std::cout << std::scientific << std::setprecision(2) << " max " << *r.maxError << " rms " << *r.rmsError
                << std::defaultfloat;
    }
    if (r.milliseconds)
    {
      std::cout << std::fixed << std::setprecision(2) << "  " << *r.milliseconds << " ms" << std::defaultfloat;
    }
    std::cout << (r.note.empty() ? "" : "  (" + r.note + ")") << "\n";
  }
}

void writeCsv(const std::vector<AccuracyRow>& rows, const std::string& file)
{
  writeThroughTemporary(file,
    [&](const std::string& temporary) -> std::string
    {
      std::ofstream csv(temporary);
      csv << "study,method,parameter,value,vertices,ms,max error,rms error,predicted bound,note\n";
      csv << std::setprecision(9);
      for (const AccuracyRow& r : rows)
      {
        csv << csvText(r.study) << "," << csvText(r.method) << "," << csvText(r.parameter) << "," << r.value << ","
            << r.vertices;
        for (const std::optional<double>& value : { r.milliseconds, r.maxError, r.rmsError, r.predicted })
        {
          csv << ",";
          if (value)
          {
            csv << *value;
          }
        }
        csv << "," << csvText(r.note) << "\n";
      }
      csv.close();
      return csv ? "" : "the CSV could not be written (disk full?)";
    });
}
}

void runAccuracyStudies(const AccuracyOptions& options)
{
  std::error_code error;
  std::filesystem::create_directories(options.directory, error);
  if (error || !std::filesystem::is_directory(options.directory))
  {
    throw UserError("--charts: cannot create the folder " + options.directory + " (" + error.message() + ")");
  }
  const std::string folder = options.directory + "/";
  const DistributedStudyInputs distributed = readDistributedStudyInputs(options);
  const vtkSmartPointer<vtkPolyData> clean = cleanBunny(options.bunnyFile);
  std::optional<Mesh> bunny = bunnyOfAbout(clean, 140000);
  if (!bunny)
  {
    throw UserError(options.bunnyFile + ": could not be subdivided to about 140,000 vertices");
  }
  // Not subdivided (level 0, with outward normals): area lights and maps cost far more per vertex.
  const Mesh plainBunny = *bunnyOfAbout(clean, clean->GetNumberOfPoints());
  std::vector<AccuracyRow> rows;
  int charts = 0;
  auto study = [&](const std::string& name, const std::function<std::vector<AccuracyRow>(ChartSpec&)>& run)
  {
    const bool chosen = options.studyFilters.empty() ||
      std::any_of(options.studyFilters.begin(), options.studyFilters.end(),
        [&](const std::string& filter) { return name.find(filter) != std::string::npos; });
    if (!chosen)
    {
      return;
    }
    ++charts;
    std::cout << "study: " << name << "..." << std::endl;
    ChartSpec chart;
    const std::vector<AccuracyRow> studyRows = run(chart);
    rows.insert(rows.end(), studyRows.begin(), studyRows.end());
    writeChartPng(chart, folder + name + ".png");
    printRows(studyRows);
  };
  study("1_arithmetic_and_pow", [&](ChartSpec& chart) { return arithmeticStudy(*bunny, options.maxRepeats, chart); });
  study("2_pow", [&](ChartSpec& chart) { return powStudy(chart); });
  study("3_point_as_distant", [&](ChartSpec& chart) { return distantStudy(*bunny, options.maxRepeats, chart); });
  study("4_phong_vs_blinn_phong", [&](ChartSpec& chart) { return phongStudy(*bunny, options.maxRepeats, chart); });
  study("5_tessellation", [&](ChartSpec& chart) { return tessellationStudy(chart); });
  for (const bool shadows : { false, true })
  {
    study(shadows ? "6b_soft_shadows" : "6_area_light",
      [&](ChartSpec& chart)
      { return areaLightStudy(plainBunny, distributed.softbox, shadows, options.maxRepeats, chart); });
  }
  for (const bool shadows : { false, true })
  {
    for (const auto& [map, number, name] :
      { std::tuple{ &distributed.sunset, "7", "sunset" }, std::tuple{ &distributed.studio, "8", "studio" } })
    {
      const std::string id = std::string(number) + (shadows ? "b" : "");
      const std::string title = id + " " + name + " map" + (shadows ? ", shadows" : "");
      const auto measure = shadows ? environmentShadowStudy : environmentMapStudy;
      study(id + "_" + name + "_map" + (shadows ? "_shadows" : ""),
        [&, map = map](ChartSpec& chart)
        { return measure(plainBunny, distributed.softbox, *map, title, options.maxRepeats, chart); });
    }
  }
  study("11_predicted_against_measured", [&](ChartSpec& chart) { return predictionStudy(chart); });
  study("12_spectral_rgb_error", [&](ChartSpec& chart) { return spectralRgbErrorStudy(plainBunny, chart); });
  study("13_spectral_bands", [&](ChartSpec& chart) { return spectralBandStudy(plainBunny, chart); });
  study("14_interreflection_bounces",
    [&](ChartSpec& chart) { return interreflectionBouncesStudy(options.maxRepeats, chart); });
  study(
    "14b_interreflection_rays", [&](ChartSpec& chart) { return interreflectionRaysStudy(options.maxRepeats, chart); });
  study(
    "14c_interreflection_time", [&](ChartSpec& chart) { return interreflectionPlanStudy(options.maxRepeats, chart); });
  study("15_reflectance_models",
    [&](ChartSpec& chart) { return reflectanceModelsStudy(*bunny, options.maxRepeats, chart); });
  study("16_texture_filtering", [&](ChartSpec& chart) { return textureFilteringStudy(chart); });
  const std::vector<AccuracyRow> grazing = grazingRows();
  rows.insert(rows.end(), grazing.begin(), grazing.end());
  for (const AccuracyRow& r : grazing)
  {
    std::cout << "  " << r.method << ", elevation " << r.value << ": |float32 - float64| = " << *r.maxError << "\n";
  }
  std::cout << "speed requirements:" << std::endl;
  const std::vector<AccuracyRow> speed = speedRequirementRows(plainBunny, distributed.softbox, distributed.studio);
  rows.insert(rows.end(), speed.begin(), speed.end());
  printRows(speed);
  writeCsv(rows, folder + "accuracy.csv");
  std::cout << "wrote " << folder << "accuracy.csv and " << charts << " charts\n";
}
}
