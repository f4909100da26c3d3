#include "Benchmark.h"

#include "BenchmarkMeshes.h"
#include "CalculatorBaseline.h"
#include "CsvText.h"
#include "MemoryProbe.h"
#include "MeshFiles.h"

#include "ShadeLabLargeArrays.h"
#include "vtkLocalReflectanceFilter.h"

#include "vtkArrayCalculator.h"
#include "vtkCleanPolyData.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkLoopSubdivisionFilter.h"
#include "vtkPointData.h"
#include "vtkSMPTools.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"

#include <malloc.h> // mallopt, malloc_trim: glibc's allocator, for the memory measurement

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <new>
#include <sstream>

namespace shadelab::app
{
using Clock = std::chrono::steady_clock;

double medianMilliseconds(const std::function<void()>& run, int minRepeats, int maxRepeats)
{
  return interleavedMedianMilliseconds({ run }, minRepeats, maxRepeats).front();
}

std::vector<double> interleavedMedianMilliseconds(
  const std::vector<std::function<void()>>& runs, int minRepeats, int maxRepeats)
{
  std::vector<std::vector<double>> times(runs.size());
  const Clock::time_point start = Clock::now();
  for (int round = 0; round < std::max(1, minRepeats) ||
       (round < maxRepeats && std::chrono::duration<double>(Clock::now() - start).count() < 2.0 * runs.size());
       ++round)
  {
    for (std::size_t r = 0; r < runs.size(); ++r)
    {
      const Clock::time_point begin = Clock::now();
      runs[r]();
      times[r].push_back(std::chrono::duration<double, std::milli>(Clock::now() - begin).count());
    }
  }
  std::vector<double> medians;
  for (std::vector<double>& each : times)
  {
    std::sort(each.begin(), each.end());
    medians.push_back(each[each.size() / 2]);
  }
  return medians;
}

Differences compareArrays(vtkDataArray* a, vtkDataArray* b)
{
  if (!a || !b || a->GetNumberOfComponents() != b->GetNumberOfComponents() ||
    a->GetNumberOfTuples() != b->GetNumberOfTuples())
  {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return { nan, nan };
  }
  DifferenceSum sum;
  for (vtkIdType t = 0; t < a->GetNumberOfTuples(); ++t)
  {
    for (int c = 0; c < a->GetNumberOfComponents(); ++c)
    {
      sum.add(std::abs(a->GetComponent(t, c) - b->GetComponent(t, c)));
    }
  }
  return sum.result();
}

namespace
{
/// How glibc's malloc treats large blocks. For timing, like a long-lived process: every block
/// comes from the heap, which keeps freed memory for reuse, so that a run at any size reuses
/// what the run before it freed (without this, blocks above 32 MB, glibc's largest mmap
/// threshold, would be mapped afresh each run, and 10M vertices would pay for zeroing new
/// pages where 1M does not). For measuring memory: every block of 1 MB and more is mapped
/// on its own and returned when freed, and freed heap memory is given back first, so that the
/// resident size follows what is allocated.
void allocateForTiming()
{
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
}

void allocateForMemoryMeasurement()
{
  mallopt(M_MMAP_MAX, 65536); // glibc's default
  mallopt(M_MMAP_THRESHOLD, 1 << 20);
  mallopt(M_TRIM_THRESHOLD, 128 << 10);
  malloc_trim(0);
}

/// The mesh with the normals ShadeLab itself would compute and orient outward (the bunny's
/// point inward), so that the calculator baseline sees the same normals as the filter.
vtkSmartPointer<vtkPolyData> withOutwardNormals(vtkPolyData* mesh)
{
  Scene scene;
  scene.lights = { { "sun", DistantLight{} } };
  vtkNew<vtkLocalReflectanceFilter> prepare;
  prepare->SetInputData(mesh);
  prepare->SetScene(scene);
  prepare->SetArraySelection({ "shading_flags" });
  prepare->Update();
  if (!prepare->GetOutput()->GetPointData()->GetNormals())
  {
    throw UserError("the benchmark's mesh could not be given normals");
  }
  auto prepared = vtkSmartPointer<vtkPolyData>::New();
  prepared->ShallowCopy(prepare->GetOutput());
  prepared->GetPointData()->RemoveArray("shading_flags");
  prepared->GetFieldData()->Initialize();
  return prepared;
}
}

Mesh sphereOfAbout(long long points)
{
  const int resolution = std::max(3, static_cast<int>(std::lround(std::sqrt(static_cast<double>(points)))));
  vtkNew<vtkSphereSource> sphere;
  sphere->SetThetaResolution(resolution);
  sphere->SetPhiResolution(resolution + 2);
  sphere->Update();
  return { "sphere", sphere->GetOutput() };
}

// vtkLoopSubdivisionFilter gives nothing for a mesh with unused points, and the bunny has 1,113.
vtkSmartPointer<vtkPolyData> cleanBunny(const std::string& file)
{
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputData(readMesh(file));
  clean->Update();
  return clean->GetOutput();
}

/// The bunny Loop-subdivided until it has the number of vertices closest to `points` (about
/// 4x per level), or nothing if no level is within a factor 2.5.
std::optional<Mesh> bunnyOfAbout(vtkPolyData* bunny, long long points)
{
  int levels = 0;
  double estimate = bunny->GetNumberOfPoints();
  while (std::abs(std::log(estimate * 4 / points)) < std::abs(std::log(estimate / points)))
  {
    estimate *= 4;
    ++levels;
  }
  if (std::abs(std::log(estimate / points)) > std::log(2.5))
  {
    return std::nullopt;
  }
  vtkSmartPointer<vtkPolyData> subdivided = bunny;
  if (levels > 0)
  {
    vtkNew<vtkLoopSubdivisionFilter> subdivide;
    subdivide->SetInputData(bunny);
    subdivide->SetNumberOfSubdivisions(levels);
    subdivide->Update();
    subdivided = subdivide->GetOutput();
    if (subdivided->GetNumberOfPoints() == 0)
    {
      throw UserError("vtkLoopSubdivisionFilter could not subdivide the bunny");
    }
  }
  return Mesh{ "bunny x" + std::to_string(1 << (2 * levels)), withOutwardNormals(subdivided) };
}

/// What a scan's material looks like, for the cases that read theirs from arrays: an 8-bit
/// RGB "Colors" array and a float "Gloss" in [0, 0.5], varying from vertex to vertex.
void addMaterialArrays(vtkPolyData* mesh)
{
  const vtkIdType count = mesh->GetNumberOfPoints();
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(3);
  colors->SetNumberOfTuples(count);
  vtkNew<vtkFloatArray> gloss;
  gloss->SetName("Gloss");
  gloss->SetNumberOfTuples(count);
  for (vtkIdType i = 0; i < count; ++i)
  {
    for (int c = 0; c < 3; ++c)
    {
      colors->SetValue(3 * i + c, static_cast<unsigned char>((i * (37 + 11 * c)) % 256));
    }
    gloss->SetValue(i, 0.5f * float(i % 101) / 100.0f);
  }
  mesh->GetPointData()->AddArray(colors);
  mesh->GetPointData()->AddArray(gloss);
}

namespace
{
struct Case
{
  std::string name;
  Scene scene;
  std::vector<std::string> arrays;
  /// What vtkArrayCalculator computes as the same thing: "diffuse", "total" or nothing.
  std::string calculatorArray;
  /// The filter's Tolerance: 0 for the exact methods.
  double tolerance = 0;
};

/// The lighting cases, with lights placed around a mesh of this centre and radius.
std::vector<Case> casesAround(const glm::dvec3& centre, double radius)
{
  auto at = [&](double x, double y, double z) { return centre + radius * glm::dvec3(x, y, z); };
  auto point = [&](const char* name, glm::dvec3 position, double intensity)
  {
    PointLight light;
    light.position = position;
    light.intensity = intensity * radius * radius; // about 1 at the mesh
    return NamedLight{ name, light };
  };
  auto distant = [](const char* name, glm::dvec3 direction, double intensity) {
    return NamedLight{ name, DistantLight{ direction, Rgb(1.0), intensity, false } };
  };

  Scene base;
  base.viewer.position = at(0, 0, 4);
  base.material = { Rgb(0.8, 0.6, 0.4), Rgb(0.8, 0.6, 0.4), Rgb(0.3), 30.0, SpecularModel::BlinnPhong, false, {} };
  const NamedLight room{ "room", AmbientLight{ Rgb(1.0), 0.1 } };

  Scene lambert = base;
  lambert.material.specular = SpecularModel::None;
  lambert.lights = { distant("sun", { -1, -1, -1 }, 1.0) };

  Scene one = base;
  one.lights = { point("key", at(2, 2, 2), 12.0), room };

  Scene three = base;
  three.lights = { point("key", at(2, 2, 2), 12.0), distant("fill", { 1, -0.2, -0.6 }, 0.4),
    point("back", at(-2, 1, -2), 9.0), room };

  Scene eight = base;
  const char* names[] = { "p0", "d0", "p1", "d1", "p2", "d2", "p3", "d3" };
  for (int l = 0; l < 8; ++l)
  {
    const double angle = l * 0.785398;
    eight.lights.push_back(l % 2 == 0 ? point(names[l], at(3 * std::cos(angle), 1.5, 3 * std::sin(angle)), 4.0)
                                      : distant(names[l], { -std::cos(angle), -0.5, -std::sin(angle) }, 0.2));
  }
  eight.lights.push_back(room);

  Scene threeMatte = three;
  threeMatte.material.specular = SpecularModel::None;

  // The scan's colours for ka and kd, its gloss for ks (addMaterialArrays).
  Scene threeScanned = three;
  MaterialArrays& arrays = threeScanned.material.arrays;
  ArrayCoefficient colors, gloss;
  colors.array = "Colors";
  gloss.array = "Gloss";
  arrays[MaterialCoefficient::Diffuse] = colors;
  arrays[MaterialCoefficient::Ambient] = colors;
  arrays[MaterialCoefficient::Specular] = gloss;
  threeScanned.material.ka = threeScanned.material.kd = threeScanned.material.ks = Rgb(1.0);

  return {
    { "lambert", lambert, { "diffuse" }, "diffuse" },
    { "complete, 1 point light", one, { "total" }, "total" },
    // The same with the methods a tolerance picks (here the series pow, whose error is float
    // rounding): the max |diff| column checks the result against vtkArrayCalculator's.
    { "complete, 1 point, tolerance 1e-4", one, { "total" }, "total", 1e-4 },
    { "complete, 3 lights", three, { "total" }, "total" },
    // Against the row above: a material per vertex, from the mesh's arrays.
    { "complete, 3 lights, material arrays", threeScanned, { "total" }, "" },
    { "complete, 8 lights", eight, { "total" }, "total" },
    { "all 40 arrays, 3 lights", three, { "all" }, "" },
    // The pair that shows an unrequested term costs nothing: the shiny material's specular
    // lobes are not computed when only the diffuse total is asked for.
    { "diffuse only, 3 lights, shiny", three, { "diffuse" }, "diffuse" },
    { "diffuse only, 3 lights, matte", threeMatte, { "diffuse" }, "diffuse" },
  };
}

/// The bytes of the arrays the filter added.
std::size_t addedBytes(vtkPolyData* input, vtkPolyData* output)
{
  std::size_t bytes = 0;
  vtkPointData* pointData = output->GetPointData();
  for (int a = 0; a < pointData->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = pointData->GetArray(a);
    if (!input->GetPointData()->HasArray(array->GetName()))
    {
      bytes += array->GetNumberOfValues() * array->GetDataTypeSize();
    }
  }
  return bytes;
}

struct Row
{
  long long vertices;
  std::string mesh, name;
  double firstMilliseconds, milliseconds, floorMilliseconds;
  std::optional<double> calculatorMilliseconds, calculatorDifference;
  std::optional<double> peakMegabytes;
  double arrayMegabytes;
};

/// The floor: reading the input bytes and writing the output bytes once (memcpy and memset,
/// the least that any pass over the same bytes costs), the output into a newly allocated block as the
/// filter's arrays are (ShadeLabLargeArrays.h).
class FloorCopy
{
public:
  FloorCopy(vtkPolyData* mesh, std::size_t outputBytes)
    : points_(mesh->GetPoints()->GetData())
    , normals_(mesh->GetPointData()->GetNormals())
    , pointBytes_(points_->GetNumberOfValues() * points_->GetDataTypeSize())
    , normalBytes_(normals_->GetNumberOfValues() * normals_->GetDataTypeSize())
    , outputBytes_(outputBytes)
    , in_(pointBytes_ + normalBytes_, 1)
  {
  }

  void operator()()
  {
    std::memcpy(in_.data(), points_->GetVoidPointer(0), pointBytes_);
    std::memcpy(in_.data() + pointBytes_, normals_->GetVoidPointer(0), normalBytes_);
    std::unique_ptr<void, decltype(&std::free)> out(allocateLarge(outputBytes_), &std::free);
    if (!out)
    {
      throw std::bad_alloc();
    }
    std::memset(out.get(), in_[in_.size() / 2], outputBytes_);
  }

private:
  vtkDataArray* points_;
  vtkDataArray* normals_;
  std::size_t pointBytes_, normalBytes_, outputBytes_;
  std::vector<char> in_;
};

Row measure(const Mesh& mesh, const Case& c, int maxRepeats)
{
  Row row{ mesh.data->GetNumberOfPoints(), mesh.name, c.name, 0, 0, 0, {}, {}, {}, 0 };
  vtkNew<vtkLocalReflectanceFilter> filter;
  filter->SetInputData(mesh.data);
  filter->SetScene(c.scene);
  filter->SetArraySelection(c.arrays);
  filter->SetTolerance(c.tolerance);

  // The first run also prepares the normals; its peak memory is measured above what the
  // process held before it.
  allocateForMemoryMeasurement();
  const std::optional<std::size_t> before = statusBytes("VmRSS");
  const bool peakReset = resetPeakMemory();
  const Clock::time_point firstStart = Clock::now();
  filter->Update();
  row.firstMilliseconds = std::chrono::duration<double, std::milli>(Clock::now() - firstStart).count();
  const std::optional<std::size_t> peak = statusBytes("VmHWM");
  if (peakReset && before && peak)
  {
    row.peakMegabytes = (static_cast<double>(*peak) - static_cast<double>(*before)) / 1e6;
  }
  allocateForTiming();
  const std::size_t outputBytes = addedBytes(mesh.data, filter->GetOutput());
  row.arrayMegabytes = outputBytes / 1e6;
  // The filter and the floor in turn, so that their ratio holds under a changing load.
  FloorCopy floor(mesh.data, outputBytes);
  const std::vector<double> medians = interleavedMedianMilliseconds({ [&]
                                                                      {
                                                                        filter->Modified();
                                                                        filter->Update();
                                                                      },
                                                                      std::ref(floor) },
    3, maxRepeats);
  row.milliseconds = medians[0];
  row.floorMilliseconds = medians[1];

  vtkDataArray* normals = mesh.data->GetPointData()->GetNormals();
  const std::optional<std::string> expression = c.calculatorArray.empty()
    ? std::nullopt
    : calculatorExpression(c.scene, c.calculatorArray == "diffuse", normals->GetName());
  if (expression)
  {
    vtkNew<vtkArrayCalculator> calculator;
    calculator->SetInputData(mesh.data);
    calculator->AddVectorArrayName(normals->GetName(), 0, 1, 2);
    calculator->AddCoordinateVectorVariable("coords", 0, 1, 2);
    calculator->SetFunction(expression->c_str());
    calculator->SetResultArrayName("calculator");
    calculator->SetResultArrayType(VTK_FLOAT);
    calculator->Update(); // its first run, like ours, is not timed
    vtkDataArray* theirs = vtkDataSet::SafeDownCast(calculator->GetOutput())->GetPointData()->GetArray("calculator");
    if (theirs)
    {
      row.calculatorDifference =
        compareArrays(filter->GetOutput()->GetPointData()->GetArray(c.calculatorArray.c_str()), theirs).largest;
      row.calculatorMilliseconds = medianMilliseconds(
        [&]
        {
          calculator->Modified();
          calculator->Update();
        },
        1, maxRepeats);
    }
  }
  return row;
}

/// A column of the table: text, or a number shown with `decimals` decimals (0 meaning
/// scientific notation) in the table and in full in the CSV.
struct Column
{
  const char* title;
  int width;
  int decimals;
  std::function<std::string(const Row&)> text;
  std::function<std::optional<double>(const Row&)> number;
};

std::optional<double> ratio(std::optional<double> a, double b)
{
  return a ? std::optional<double>(*a / b) : std::nullopt;
}

const std::vector<Column>& columns()
{
  using Text = std::function<std::string(const Row&)>;
  using Number = std::function<std::optional<double>(const Row&)>;
  static const std::vector<Column> all = {
    { "vertices", 10, 0, [](const Row& r) { return std::to_string(r.vertices); }, Number{} },
    { "mesh", 11, 0, [](const Row& r) { return r.mesh; }, Number{} },
    { "case", 34, 0, [](const Row& r) { return r.name; }, Number{} },
    { "first ms", 9, 2, Text{}, [](const Row& r) { return r.firstMilliseconds; } },
    { "ms", 9, 2, Text{}, [](const Row& r) { return r.milliseconds; } },
    { "Mvertices/s", 12, 1, Text{}, [](const Row& r) { return r.vertices / r.milliseconds / 1e3; } },
    { "x floor", 8, 1, Text{}, [](const Row& r) { return r.milliseconds / r.floorMilliseconds; } },
    { "floor ms", 9, 3, Text{}, [](const Row& r) { return r.floorMilliseconds; } },
    { "calculator ms", 14, 1, Text{}, [](const Row& r) { return r.calculatorMilliseconds; } },
    { "x faster", 9, 1, Text{}, [](const Row& r) { return ratio(r.calculatorMilliseconds, r.milliseconds); } },
    { "max |diff|", 11, 0, Text{}, [](const Row& r) { return r.calculatorDifference; } },
    { "peak MB", 9, 1, Text{}, [](const Row& r) { return r.peakMegabytes; } },
    { "arrays MB", 10, 1, Text{}, [](const Row& r) { return r.arrayMegabytes; } },
  };
  return all;
}

std::string tableCell(const Column& column, const Row& row)
{
  if (column.text)
  {
    return column.text(row);
  }
  const std::optional<double> value = column.number(row);
  if (!value)
  {
    return "-";
  }
  std::ostringstream text;
  if (column.decimals == 0)
  {
    text << std::scientific << std::setprecision(1) << *value;
  }
  else
  {
    text << std::fixed << std::setprecision(column.decimals) << *value;
  }
  return text.str();
}

/// Numbers in full.
std::string csvCell(const Column& column, const Row& row)
{
  if (column.number)
  {
    const std::optional<double> value = column.number(row);
    std::ostringstream text;
    if (value)
    {
      text << std::setprecision(9) << *value;
    }
    return text.str();
  }
  return csvText(column.text(row));
}

void printRow(const Row& row)
{
  for (const Column& column : columns())
  {
    std::cout << std::setw(column.width) << tableCell(column, row) << " ";
  }
  std::cout << std::endl;
}
}

/// Whether the options select this case.
bool selected(const BenchmarkOptions& options, const std::string& caseName)
{
  return options.caseFilters.empty() ||
    std::any_of(options.caseFilters.begin(), options.caseFilters.end(),
      [&](const std::string& filter) { return caseName.find(filter) != std::string::npos; });
}

void runBenchmark(const BenchmarkOptions& options)
{
  const std::vector<Case> allCases = casesAround(glm::dvec3(0), 1);
  for (const std::string& filter : options.caseFilters)
  {
    if (std::none_of(
          allCases.begin(), allCases.end(), [&](const Case& c) { return c.name.find(filter) != std::string::npos; }))
    {
      std::string names;
      for (const Case& c : allCases)
      {
        names += (names.empty() ? "'" : ", '") + c.name + "'";
      }
      throw UserError("--case: no benchmark case contains '" + filter + "'; the cases are " + names);
    }
  }
  if (!options.csvFile.empty())
  {
    checkOutputFile(options.csvFile, { ".csv" });
  }
  vtkSmartPointer<vtkPolyData> bunny = options.bunnyFile.empty() ? nullptr : cleanBunny(options.bunnyFile);
  {
    // Starts the thread pool, so that the first row's first run does not pay for it.
    const Mesh warmUp = sphereOfAbout(1000);
    measure(warmUp, allCases[0], 1);
  }
  std::cout << "shadelab-bench: " << vtkSMPTools::GetEstimatedNumberOfThreads()
            << " threads, float32.\n"
               "first ms: the first run, which also prepares the normals; ms: the median of 3 to "
            << options.maxRepeats
            << " later runs (new lights on the same mesh);\n"
               "x floor: ms / the floor (memcpy of the input and memset of the output bytes, one "
               "thread); x faster: vtkArrayCalculator's median time for the same expression / ms;\n"
               "max |diff|: between the two results; peak MB: resident memory above the start of "
               "the first run; arrays MB: the arrays written.\n";
  for (const Column& column : columns())
  {
    std::cout << std::setw(column.width) << column.title << " ";
  }
  std::cout << "\n";

  std::vector<Row> rows;
  for (const long long size : options.sizes)
  {
    std::vector<Mesh> meshes{ sphereOfAbout(size) };
    if (bunny)
    {
      if (std::optional<Mesh> subdivided = bunnyOfAbout(bunny, size))
      {
        meshes.push_back(*subdivided);
      }
    }
    for (const Mesh& mesh : meshes)
    {
      addMaterialArrays(mesh.data);
      double centre[3];
      mesh.data->GetCenter(centre); // of the bounding box; GetLength is its diagonal
      for (const Case& c : casesAround({ centre[0], centre[1], centre[2] }, 0.5 * mesh.data->GetLength()))
      {
        if (!selected(options, c.name))
        {
          continue;
        }
        rows.push_back(measure(mesh, c, options.maxRepeats));
        printRow(rows.back());
      }
    }
  }

  if (!options.csvFile.empty())
  {
    writeThroughTemporary(options.csvFile,
      [&](const std::string& temporary) -> std::string
      {
        std::ofstream csv(temporary);
        for (std::size_t c = 0; c < columns().size(); ++c)
        {
          csv << (c ? "," : "") << columns()[c].title;
        }
        csv << "\n";
        for (const Row& row : rows)
        {
          for (std::size_t c = 0; c < columns().size(); ++c)
          {
            csv << (c ? "," : "") << csvCell(columns()[c], row);
          }
          csv << "\n";
        }
        csv.close();
        return csv ? "" : "the CSV could not be written (disk full?)";
      });
    std::cout << "wrote " << options.csvFile << "\n";
  }
}
vtkSmartPointer<vtkPolyData> shaded(vtkPolyData* mesh, const Scene& scene)
{
  vtkNew<vtkLocalReflectanceFilter> filter;
  filter->SetInputData(mesh);
  filter->SetScene(scene);
  filter->Update();
  if (filter->GetOutput()->GetNumberOfPoints() != mesh->GetNumberOfPoints())
  {
    throw UserError("the mesh could not be shaded (run shadelab shade on it to see why)");
  }
  auto output = vtkSmartPointer<vtkPolyData>::New();
  output->ShallowCopy(filter->GetOutput());
  return output;
}
}
