// shadelab compare as a user runs it: hand-made pairs of files with known differences, each
// option, each kind of mismatch and its message, the exit codes, and the JSON report.
#include "CliFixture.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkStructuredGrid.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"
#include "vtkUnstructuredGridWriter.h"
#include "vtkXMLDataElement.h"
#include "vtkXMLDataParser.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"
#include "vtkXMLStructuredGridWriter.h"
#include "vtkXMLUnstructuredGridWriter.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace
{
using shadelab::testing::Cli;
using shadelab::testing::Result;

/// A square of 4 points and 2 triangles with the arrays edit adds.
vtkSmartPointer<vtkPolyData> square(const std::function<void(vtkPolyData*)>& edit)
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(1, 0, 0);
  points->InsertNextPoint(1, 1, 0);
  points->InsertNextPoint(0, 1, 0);
  mesh->SetPoints(points);
  vtkNew<vtkCellArray> triangles;
  const vtkIdType first[3] = { 0, 1, 2 }, second[3] = { 0, 2, 3 };
  triangles->InsertNextCell(3, first);
  triangles->InsertNextCell(3, second);
  mesh->SetPolys(triangles);
  edit(mesh);
  return mesh;
}

template<typename Array>
void addArray(vtkPolyData* mesh, const char* name, int components, const std::vector<double>& values)
{
  vtkNew<Array> array;
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(static_cast<vtkIdType>(values.size()) / components);
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    array->SetValue(static_cast<vtkIdType>(i), static_cast<typename Array::ValueType>(values[i]));
  }
  mesh->GetPointData()->AddArray(array);
}

/// The arrays of a shaded square: total (float32 x 3) and shading_flags.
void shaded(vtkPolyData* mesh)
{
  addArray<vtkFloatArray>(mesh, "total", 3, { 0.5, 0.25, 0.125, 0.5, 0.5, 0.5, 1, 0, 0, 0.75, 0.75, 0.75 });
  addArray<vtkUnsignedCharArray>(mesh, "shading_flags", 1, { 0, 64, 4, 0 });
}

std::string digits17(double x)
{
  std::ostringstream text;
  text << std::setprecision(17) << x;
  return text.str();
}

std::string digits3(double x)
{
  std::ostringstream text;
  text << std::setprecision(3) << x;
  return text.str();
}

/// The square's ambient_occlusion, these values, and its standard errors, all this one.
std::function<void(vtkPolyData*)> occlusion(const std::vector<double>& values, double error)
{
  return [=](vtkPolyData* mesh)
  {
    addArray<vtkDoubleArray>(mesh, "ambient_occlusion", 1, values);
    addArray<vtkDoubleArray>(mesh, "ambient_occlusion_std_error", 1, std::vector<double>(values.size(), error));
  };
}

class Compare : public Cli
{
protected:
  /// data written to name in the test's folder by a VTK writer of type Writer; its path.
  template<typename Writer>
  std::string writeWith(const std::string& name, vtkDataObject* data)
  {
    const std::string path = (folder / name).string();
    vtkNew<Writer> writer;
    writer->SetInputData(data);
    writer->SetFileName(path.c_str());
    writer->Write();
    return path;
  }

  std::string write(const std::string& name, vtkPolyData* mesh) { return writeWith<vtkXMLPolyDataWriter>(name, mesh); }

  /// Squares of ambient_occlusion (values, and one standard error for all), compared with these
  /// options and their standard errors left out of the comparison.
  Result compareOcclusion(const std::vector<double>& baseline, double baselineError, const std::vector<double>& result,
    double resultError, const std::string& options)
  {
    const std::string a = write("a.vtp", square(occlusion(baseline, baselineError)));
    const std::string b = write("b.vtp", square(occlusion(result, resultError)));
    return shadelab("compare " + a + " " + b + " " + options + " --exclude '*_std_error'");
  }

  /// The lines of the report that mention the array, after the heading.
  static std::string linesAbout(const std::string& report, const std::string& name)
  {
    std::istringstream lines(report);
    std::string line, found;
    bool inArray = false;
    while (std::getline(lines, line))
    {
      const bool row = line.rfind("  ok ", 0) == 0 || line.rfind("  DIFFER ", 0) == 0;
      if (row)
      {
        std::istringstream words(line);
        std::string verdict, array;
        words >> verdict >> array;
        inArray = array == name;
      }
      else if (line.rfind("         ", 0) != 0)
      {
        inArray = false;
      }
      if (inArray)
      {
        found += line + "\n";
      }
    }
    return found;
  }
};

TEST_F(Compare, IdenticalFilesAgree)
{
  const std::string a = write("a.vtp", square(shaded)), b = write("b.vtp", square(shaded));
  const Result result = shadelab("compare " + a + " " + b);
  EXPECT_EQ(result.exitCode, 0) << result.out << result.err;
  EXPECT_EQ(result.err, "");
  EXPECT_NE(result.out.find("\nPASS: 3 arrays agree\n"), std::string::npos) << result.out;
  EXPECT_EQ(linesAbout(result.out, "total"),
    "  ok     total                          point  float32 x3 0 / 12            0          0          0          "
    "atol 0, rtol 4.77e-07\n");
}

TEST_F(Compare, ADifferenceBeyondTheDefaultToleranceFailsAndTheWorstIsShown)
{
  // 0.5 + 1e-7 is within 4 ULP of float32 (rtol 4.8e-7); 0.75 + 1e-3 is not.
  const std::string a = write("a.vtp", square(shaded));
  const std::string b = write("b.vtp",
    square(
      [](vtkPolyData* mesh)
      {
        addArray<vtkFloatArray>(
          mesh, "total", 3, { 0.5 + 1e-7, 0.25, 0.125, 0.5, 0.5, 0.5, 1, 0, 0, 0.75, 0.751, 0.75 });
        addArray<vtkUnsignedCharArray>(mesh, "shading_flags", 1, { 0, 64, 4, 0 });
      }));
  const Result result = shadelab("compare " + a + " " + b);
  EXPECT_EQ(result.exitCode, 1);
  const float changed = 0.751f;
  EXPECT_EQ(linesAbout(result.out, "total"),
    "  DIFFER total                          point  float32 x3 1 / 12            0.001      0.000289   0.001      "
    "atol 0, rtol 4.77e-07\n"
    "         worst failing at point 3 (0, 1, 0), component 1: 0.75 in the baseline, " +
      digits17(changed) + " in the result\n");
  EXPECT_NE(result.out.find("\nFAIL: 1 of 3 arrays differ\n"), std::string::npos) << result.out;
  // Loosened for that array, by name or by pattern, or relative to its range (1 here).
  EXPECT_EQ(shadelab("compare " + a + " " + b + " --atol total:2e-3").exitCode, 0);
  EXPECT_EQ(shadelab("compare " + a + " " + b + " --rtol 't*:2e-3'").exitCode, 0);
  EXPECT_EQ(shadelab("compare " + a + " " + b + " --atol '2e-3*range'").exitCode, 0);
  EXPECT_EQ(shadelab("compare " + a + " " + b + " --atol '5e-4*range'").exitCode, 1);
  // Options before the files take one value each, not the files.
  EXPECT_EQ(shadelab("compare --atol total:2e-3 --arrays total,shading_flags " + a + " " + b).exitCode, 0);
  // The last rule that matches wins.
  EXPECT_EQ(shadelab("compare " + a + " " + b + " --atol 1 --atol total:0").exitCode, 1);
  // Or left out.
  EXPECT_EQ(shadelab("compare " + a + " " + b + " --exclude total").exitCode, 0);
  EXPECT_EQ(shadelab("compare " + a + " " + b + " --arrays shading_flags").exitCode, 0);
}

TEST_F(Compare, UlpModeCountsTheFloatsBetween)
{
  const std::string a = write("a.vtp", square(shaded));
  // 5 floats above 0.125: beyond the default (4 ULP), within --ulps 5.
  float up = 0.125f;
  for (int k = 0; k < 5; ++k)
  {
    up = std::nextafter(up, 1.0f);
  }
  const std::string b = write("b.vtp",
    square(
      [&](vtkPolyData* mesh)
      {
        addArray<vtkFloatArray>(mesh, "total", 3, { 0.5, 0.25, up, 0.5, 0.5, 0.5, 1, 0, 0, 0.75, 0.75, 0.75 });
        addArray<vtkUnsignedCharArray>(mesh, "shading_flags", 1, { 0, 64, 4, 0 });
      }));
  EXPECT_EQ(shadelab("compare " + a + " " + b).exitCode, 1);
  EXPECT_EQ(shadelab("compare " + a + " " + b + " --ulps 5").exitCode, 0);
  const Result four = shadelab("compare " + a + " " + b + " --ulps total:4");
  EXPECT_EQ(four.exitCode, 1);
  EXPECT_NE(linesAbout(four.out, "total").find("within 4 ULP\n"), std::string::npos) << four.out;
}

TEST_F(Compare, FlagsAreComparedExactlyAndTheirBitsNamed)
{
  const std::string a = write("a.vtp", square(shaded));
  const std::string b = write("b.vtp",
    square(
      [](vtkPolyData* mesh)
      {
        addArray<vtkFloatArray>(mesh, "total", 3, { 0.5, 0.25, 0.125, 0.5, 0.5, 0.5, 1, 0, 0, 0.75, 0.75, 0.75 });
        addArray<vtkUnsignedCharArray>(mesh, "shading_flags", 1, { 64, 64, 0, 0 });
      }));
  const Result result = shadelab("compare " + a + " " + b + " --atol 1");
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_EQ(linesAbout(result.out, "shading_flags"),
    "  DIFFER shading_flags                  point  integer x1 2 / 4             64         32.1       64.1       "
    "equal\n"
    "         worst failing at point 0 (0, 0, 0): 0 in the baseline, 64 in the result\n"
    "         bits that differ: 4 (a light below the horizon) in 1, 64 (a shadowed light's ray meeting its own "
    "triangles first) "
    "in 1\n");
  // Other integer arrays: bits by number.
  const Result plain = shadelab("compare " + a + " " + b + " --flags none");
  EXPECT_NE(plain.out.find("bits that differ: bit 2 in 1, bit 6 in 1\n"), std::string::npos) << plain.out;
}

TEST_F(Compare, EachMismatchIsAClearFailure)
{
  const std::string a = write("a.vtp", square(shaded));
  const std::string missing = write("missing.vtp",
    square(
      [](vtkPolyData* mesh) {
        addArray<vtkUnsignedCharArray>(mesh, "shading_flags", 1, { 0, 64, 4, 0 });
      }));
  const std::string extra = write("extra.vtp",
    square(
      [](vtkPolyData* mesh)
      {
        shaded(mesh);
        addArray<vtkFloatArray>(mesh, "key_diffuse", 1, { 0, 0, 0, 0 });
      }));
  const std::string doubles = write("doubles.vtp",
    square(
      [](vtkPolyData* mesh)
      {
        addArray<vtkDoubleArray>(mesh, "total", 3, { 0.5, 0.25, 0.125, 0.5, 0.5, 0.5, 1, 0, 0, 0.75, 0.75, 0.75 });
        addArray<vtkUnsignedCharArray>(mesh, "shading_flags", 1, { 0, 64, 4, 0 });
      }));
  const std::string flat = write("flat.vtp",
    square(
      [](vtkPolyData* mesh)
      {
        addArray<vtkFloatArray>(
          mesh, "total", 4, { 0.5, 0.25, 0.125, 0, 0.5, 0.5, 0.5, 0, 1, 0, 0, 0, 0.75, 0.75, 0.75, 0 });
        addArray<vtkUnsignedCharArray>(mesh, "shading_flags", 1, { 0, 64, 4, 0 });
      }));
  auto row = [&](const std::string& result, const std::string& name)
  {
    const Result run = shadelab("compare " + a + " " + result);
    EXPECT_EQ(run.exitCode, 1) << run.out;
    return linesAbout(run.out, name);
  };
  EXPECT_EQ(
    row(missing, "total"), "  DIFFER total                          point  float32 x3 missing from " + missing + "\n");
  EXPECT_EQ(row(extra, "key_diffuse"), "  DIFFER key_diffuse                    point             not in " + a + "\n");
  EXPECT_EQ(row(doubles, "total"),
    "  DIFFER total                          point  float32 x3 float32 in " + a + ", float64 in " + doubles + "\n");
  EXPECT_EQ(row(flat, "total"),
    "  DIFFER total                          point  float32 x3 3 components in " + a + ", 4 in " + flat + "\n");
  // Another number of points: every point array says so.
  const std::string five = write("five.vtp",
    square(
      [](vtkPolyData* mesh)
      {
        mesh->GetPoints()->InsertNextPoint(2, 2, 0);
        addArray<vtkFloatArray>(
          mesh, "total", 3, { 0.5, 0.25, 0.125, 0.5, 0.5, 0.5, 1, 0, 0, 0.75, 0.75, 0.75, 0, 0, 0 });
        addArray<vtkUnsignedCharArray>(mesh, "shading_flags", 1, { 0, 64, 4, 0, 0 });
      }));
  EXPECT_EQ(row(five, "points"),
    "  DIFFER points                         points float32 x3 4 tuples in " + a + ", 5 in " + five + "\n");
  EXPECT_EQ(row(five, "shading_flags"),
    "  DIFFER shading_flags                  point  integer x1 4 tuples in " + a + ", 5 in " + five + "\n");
}

TEST_F(Compare, NanEqualsNanOnlyInBothFiles)
{
  const double nan = std::nan("");
  const std::string a = write("a.vtp",
    square(
      [&](vtkPolyData* mesh) {
        addArray<vtkFloatArray>(mesh, "value", 1, { nan, 1, nan, 2 });
      }));
  const std::string b = write("b.vtp",
    square(
      [&](vtkPolyData* mesh) {
        addArray<vtkFloatArray>(mesh, "value", 1, { nan, nan, 3, 2 });
      }));
  const Result result = shadelab("compare " + a + " " + b);
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_NE(linesAbout(result.out, "value")
              .find("         NaN in both files at 1 values (equal), in one only at 2 (they fail)\n"),
    std::string::npos)
    << result.out;
  EXPECT_EQ(shadelab("compare " + a + " " + a).exitCode, 0);
}

TEST_F(Compare, StatisticalModeCountsTheValuesOutsideKStandardErrors)
{
  // Combined errors sqrt(0.03^2 + 0.04^2) = 0.05: differences 0.02, -0.07, 0.2 and -0.2 are z =
  // 0.4, -1.4, 4 and -4. Two of 4 values outside 3 are too many: Binomial(4, 0.0027) exceeds 1
  // with probability 4.4e-5, within each check's 0.0005, and 0 with 0.011, which is not. The
  // mean difference, -0.0125, has standard error sqrt(4 * 0.05^2) / 4 = 0.025: within 3.48 of
  // them.
  const std::vector<double> baseline{ 0.5, 0.5, 0.5, 0.5 }, result{ 0.52, 0.43, 0.7, 0.3 };
  const Result three = compareOcclusion(baseline, 0.03, result, 0.04, "--standard-errors 3");
  EXPECT_EQ(three.exitCode, 1);
  EXPECT_EQ(linesAbout(three.out, "ambient_occlusion"),
    "  DIFFER ambient_occlusion              point  float64 x1 0 / 4             0.2        0.146      0.292      "
    "atol 0, rtol 8.88e-16; noise: 3 standard errors, significance 0.001\n"
    "         largest difference at point 3 (0, 1, 0): 0.5 in the baseline, 0.29999999999999999 in the result\n"
    "         noise: 2 of 4 values outside 3 standard errors (0.0108 expected, at most 1 allowed: too many); mean "
    "difference -0.0125 (at most 0.087 either way)\n"
    "         each check at significance 0.0005 (0.001 shared equally by the count and the mean difference, "
    "Bonferroni)\n"
    "         within 1, 2, 3 combined standard errors: 25.0%, 50.0%, 50.0% of 4 values (a normal error: 68.3%, "
    "95.4%, 99.7%)\n");
  // Within 4.5 standard errors, none is outside.
  EXPECT_EQ(compareOcclusion(baseline, 0.03, result, 0.04, "--standard-errors 4.5").exitCode, 0);
  // Options out of range, or alone, exit with 2 and say why.
  const std::pair<std::string, std::string> refusals[] = {
    { "--standard-errors 0", "--standard-errors must be a number > 0 (3 is usual)" },
    { "--significance 0.01",
      "--significance is the statistical mode's: give --standard-errors K with it (3 is usual)" },
    { "--standard-errors 3 --significance 0", "--significance must be a number from 1e-12 to 0.5 (0.001 is usual)" },
  };
  for (const auto& [options, message] : refusals)
  {
    const Result refused = compareOcclusion(baseline, 0.03, result, 0.04, options);
    EXPECT_EQ(refused.exitCode, 2) << options;
    EXPECT_EQ(refused.err, "shadelab compare: " + message + "\n");
  }
}

TEST_F(Compare, StatisticalModeFindsABiasByTheMeanDifference)
{
  // Every value 2.4 standard errors up: none outside 3, but a mean difference of 0.12, beyond
  // 3.48 times its standard error 0.025 (0.087); at a significance of 1e-12, 7.23 times (0.181).
  const std::vector<double> baseline{ 0.5, 0.5, 0.5, 0.5 }, result{ 0.62, 0.62, 0.62, 0.62 };
  const Result biased = compareOcclusion(baseline, 0.03, result, 0.04, "--standard-errors 3");
  EXPECT_EQ(biased.exitCode, 1);
  const std::string line = "         noise: 0 of 4 values outside 3 standard errors (0.0108 expected, at most 1 "
                           "allowed); mean difference 0.12 (at most 0.087 either way: a bias)\n";
  EXPECT_NE(linesAbout(biased.out, "ambient_occlusion").find(line), std::string::npos) << biased.out;
  const Result loose = compareOcclusion(baseline, 0.03, result, 0.04, "--standard-errors 3 --significance 1e-12");
  EXPECT_EQ(loose.exitCode, 0) << loose.out;
  EXPECT_NE(loose.out.find("mean difference 0.12 (at most 0.181 either way)\n"), std::string::npos) << loose.out;
  EXPECT_NE(loose.out.find("each check at significance 5e-13 (1e-12 shared equally"), std::string::npos) << loose.out;
}

TEST_F(Compare, StatisticalModeJudgesExactValuesByTheRule)
{
  // Where both standard errors are 0 (every ray of both runs missed), the values must be equal
  // within atol and rtol.
  const std::vector<double> baseline{ 1, 1, 1, 1 }, changed{ 1, 1, 1, 0.999 };
  const Result result = compareOcclusion(baseline, 0, changed, 0, "--standard-errors 3");
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_EQ(linesAbout(result.out, "ambient_occlusion"),
    "  DIFFER ambient_occlusion              point  float64 x1 1 / 4             0.001      0.0005     0.001      "
    "atol 0, rtol 8.88e-16; noise: 3 standard errors, significance 0.001\n"
    "         worst failing at point 3 (0, 1, 0): 1 in the baseline, 0.999 in the result\n"
    "         noise: no value with a standard error > 0\n"
    "         each check at significance 0.0005 (0.001 shared equally by the count and the mean difference, "
    "Bonferroni)\n"
    "         4 values have both standard errors 0: judged by atol 0, rtol 8.88e-16\n");
  EXPECT_EQ(compareOcclusion(baseline, 0, changed, 0, "--standard-errors 3 --atol 2e-3").exitCode, 0);
}

TEST_F(Compare, TheJsonReportHoldsWhatTheTableSays)
{
  const std::string a = write("a.vtp", square(shaded));
  const std::string b = write("b.vtp",
    square(
      [](vtkPolyData* mesh)
      {
        addArray<vtkFloatArray>(mesh, "total", 3, { 0.5, 0.25, 0.125, 0.5, 0.5, 0.5, 1, 0, 0, 0.75, 0.751, 0.75 });
        addArray<vtkUnsignedCharArray>(mesh, "shading_flags", 1, { 64, 64, 4, 0 });
      }));
  const std::string report = (folder / "report.json").string();
  EXPECT_EQ(shadelab("compare " + a + " " + b + " --json " + report).exitCode, 1);
  const nlohmann::json json = nlohmann::json::parse(slurp(report));
  EXPECT_EQ(json["passed"], false);
  ASSERT_EQ(json["arrays"].size(), 3u);
  const nlohmann::json& total = json["arrays"][1];
  EXPECT_EQ(total["name"], "total");
  EXPECT_EQ(total["data"], "point");
  EXPECT_EQ(total["type"], "float32");
  EXPECT_EQ(total["failing"], 1);
  EXPECT_EQ(total["values"], 12);
  EXPECT_EQ(total["worst"]["tuple"], 3);
  EXPECT_EQ(total["worst"]["component"], 1);
  EXPECT_EQ(total["worst"]["baseline"], 0.75);
  EXPECT_EQ(total["worst"]["result"], double(0.751f));
  EXPECT_NEAR(total["max_difference"].get<double>(), 0.001, 1e-7);
  const nlohmann::json& flags = json["arrays"][2];
  const nlohmann::json bits = nlohmann::json::array(
    { { { "bit", 6 }, { "name", "64 (a shadowed light's ray meeting its own triangles first)" }, { "values", 1 } } });
  EXPECT_EQ(flags["bits_that_differ"], bits);
  EXPECT_EQ(json["arrays"][0]["passed"], true);
}

TEST_F(Compare, TheArraysThatAreNotNumbersAreListedForEachFile)
{
  // Text arrays cannot be compared value by value: the console and the JSON report list each
  // file's, and the ones --exclude leaves out are in neither.
  auto withText = [](const std::vector<std::pair<const char*, bool>>& texts)
  {
    return [texts](vtkPolyData* mesh)
    {
      shaded(mesh);
      for (const auto& [name, onPoints] : texts)
      {
        vtkNew<vtkStringArray> text;
        text->SetName(name);
        text->SetNumberOfValues(onPoints ? 4 : 1);
        (onPoints ? static_cast<vtkFieldData*>(mesh->GetPointData()) : mesh->GetFieldData())->AddArray(text);
      }
    };
  };
  const std::string a = write("a.vtp", square(withText({ { "note", false }, { "skipped", false } })));
  const std::string b = write("b.vtp", square(withText({ { "label", true }, { "skipped", false } })));
  const std::string report = (folder / "report.json").string();
  const Result result = shadelab("compare " + a + " " + b + " --exclude skipped --json " + report);
  EXPECT_EQ(result.exitCode, 0) << result.out << result.err;
  EXPECT_NE(result.out.find("  not compared in the baseline (not numbers): note (field data, vtkStringArray)\n"
                            "  not compared in the result (not numbers): label (point data, vtkStringArray)\n"),
    std::string::npos)
    << result.out;
  const nlohmann::json json = nlohmann::json::parse(slurp(report));
  EXPECT_EQ(json["not_compared"], nlohmann::json::array({ "note (field data, vtkStringArray)" }));
  EXPECT_EQ(json["not_compared_in_result"], nlohmann::json::array({ "label (point data, vtkStringArray)" }));
}

TEST_F(Compare, AnyDatasetIsRead)
{
  // An unstructured grid with the square's points and arrays agrees with the polydata.
  vtkSmartPointer<vtkPolyData> mesh = square(shaded);
  vtkNew<vtkUnstructuredGrid> grid;
  grid->SetPoints(mesh->GetPoints());
  grid->GetPointData()->ShallowCopy(mesh->GetPointData());
  const vtkIdType triangle[3] = { 0, 1, 2 };
  grid->InsertNextCell(VTK_TRIANGLE, 3, triangle);
  const std::string vtu = writeWith<vtkXMLUnstructuredGridWriter>("grid.vtu", grid);
  const Result result = shadelab("compare " + vtu + " " + write("a.vtp", mesh));
  EXPECT_EQ(result.exitCode, 0) << result.out << result.err;
  EXPECT_NE(
    result.out.find("(4 points, 2 cells) against the baseline " + vtu + " (4 points, 1 cells)"), std::string::npos)
    << result.out;
  // The same grid as legacy .vtk agrees with its .vtu.
  const std::string legacy = writeWith<vtkUnstructuredGridWriter>("grid.vtk", grid);
  const Result legacyRun = shadelab("compare " + vtu + " " + legacy);
  EXPECT_EQ(legacyRun.exitCode, 0) << legacyRun.out << legacyRun.err;
  // An image (its points implicit) and a structured grid with the same points and values agree.
  vtkNew<vtkImageData> image;
  image->SetDimensions(2, 2, 1);
  vtkNew<vtkFloatArray> value;
  value->SetName("value");
  for (float v : { 1.0f, 2.0f, 3.0f, 4.0f })
  {
    value->InsertNextValue(v);
  }
  image->GetPointData()->AddArray(value);
  const std::string vti = writeWith<vtkXMLImageDataWriter>("image.vti", image);
  vtkNew<vtkStructuredGrid> structured;
  structured->SetDimensions(2, 2, 1);
  vtkNew<vtkPoints> gridPoints;
  gridPoints->SetDataTypeToDouble();
  for (vtkIdType i = 0; i < 4; ++i)
  {
    gridPoints->InsertNextPoint(image->GetPoint(i));
  }
  structured->SetPoints(gridPoints);
  structured->GetPointData()->AddArray(value);
  const std::string vts = writeWith<vtkXMLStructuredGridWriter>("grid.vts", structured);
  const Result grids = shadelab("compare " + vti + " " + vts);
  EXPECT_EQ(grids.exitCode, 0) << grids.out << grids.err;
  EXPECT_NE(grids.out.find("  ok     value "), std::string::npos) << grids.out;
  EXPECT_NE(grids.out.find("  ok     points                         points float64 x3 0 / 12"), std::string::npos)
    << grids.out;
  const Result diff = shadelab("compare " + vtu + " " + vtu + " --diff " + (folder / "diff.vtp").string());
  EXPECT_EQ(diff.exitCode, 2);
  EXPECT_EQ(diff.err,
    "shadelab compare: --diff writes a mesh (.vtp or .vtk), and the result is a vtkUnstructuredGrid: "
    "leave --diff out for it\n");
  EXPECT_FALSE(std::filesystem::exists(folder / "diff.vtp"));
}

TEST_F(Compare, UnreadableFilesAndBadOptionsExitWithTwo)
{
  const std::string a = write("a.vtp", square(shaded));
  const std::string absent = (folder / "absent.vtp").string();
  const Result missing = shadelab("compare " + a + " " + absent);
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_EQ(missing.err, "shadelab compare: " + absent + ": no such file\n");
  const std::string garbage = file("garbage.vtu", "<VTKFile type=\"UnstructuredGrid\"> not really\n");
  const Result broken = shadelab("compare " + garbage + " " + a);
  EXPECT_EQ(broken.exitCode, 2);
  EXPECT_EQ(broken.err.rfind("shadelab compare: " + garbage + ": cannot be read as .vtu: ", 0), 0u) << broken.err;
  const std::string unknown = file("data.xyz", "1 2 3\n");
  EXPECT_EQ(shadelab("compare " + unknown + " " + a).err,
    "shadelab compare: " + unknown +
      ": unknown dataset format '.xyz'; ShadeLab reads .vtp, .pvtp, .vtu, .vti, .vts, .vtr, .vtk (legacy), .ply, "
      ".obj, .stl\n");
  const Result tolerance = shadelab("compare " + a + " " + a + " --atol total:lots");
  EXPECT_EQ(tolerance.exitCode, 2);
  EXPECT_EQ(tolerance.err,
    "shadelab compare: 'lots' is not a tolerance: write a number >= 0 (1e-6), or one times the array's range "
    "(1e-3*range)\n");
  EXPECT_EQ(shadelab("compare " + a).exitCode, 2); // CLI11: the result is required
  const Result typo = shadelab("compare " + a + " " + a + " --arrays totl");
  EXPECT_EQ(typo.exitCode, 2);
  EXPECT_EQ(typo.err, "shadelab compare: --arrays 'totl' matches no array of either file\n");
  const Result nothing = shadelab("compare " + a + " " + a + " --no-points --exclude '*'");
  EXPECT_EQ(nothing.exitCode, 2);
  EXPECT_EQ(nothing.err, "shadelab compare: no array to compare (see --arrays, --exclude and --no-points)\n");
  const Result ranged = shadelab("compare " + a + " " + a + " --rtol 'total:1e-3*range'");
  EXPECT_EQ(ranged.exitCode, 2);
  EXPECT_EQ(ranged.err,
    "shadelab compare: --rtol 'total:1e-3*range': a relative tolerance is a plain number (a fraction "
    "of the values); a tolerance relative to the range is --atol's\n");
}
}

namespace
{
TEST_F(Compare, JunitAndTheDifferenceMeshShowWhereTheFilesDiffer)
{
  const std::string a = write("a.vtp", square(shaded));
  const std::string b = write("b.vtp",
    square(
      [](vtkPolyData* mesh)
      {
        addArray<vtkFloatArray>(mesh, "total", 3, { 0.5, 0.25, 0.125, 0.5, 0.5, 0.5, 1, 0, 0, 0.75, 0.751, 0.75 });
        addArray<vtkUnsignedCharArray>(mesh, "shading_flags", 1, { 64, 64, 4, 0 });
      }));
  const std::string junit = (folder / "report.xml").string(), diff = (folder / "diff.vtp").string();
  EXPECT_EQ(shadelab("compare " + a + " " + b + " --junit " + junit + " --diff " + diff).exitCode, 1);

  // JUnit: a test case per array, a failure with the verdict and the details where it differs.
  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName(junit.c_str());
  ASSERT_EQ(parser->Parse(), 1);
  vtkXMLDataElement* suites = parser->GetRootElement();
  EXPECT_STREQ(suites->GetName(), "testsuites");
  EXPECT_STREQ(suites->GetAttribute("tests"), "3");
  EXPECT_STREQ(suites->GetAttribute("failures"), "2");
  vtkXMLDataElement* suite = suites->GetNestedElement(0);
  ASSERT_EQ(suite->GetNumberOfNestedElements(), 3);
  EXPECT_STREQ(suite->GetNestedElement(0)->GetAttribute("name"), "points");
  EXPECT_EQ(suite->GetNestedElement(0)->GetNumberOfNestedElements(), 0);
  vtkXMLDataElement* total = suite->GetNestedElement(1);
  EXPECT_STREQ(total->GetAttribute("classname"), "shadelab.compare.point");
  ASSERT_EQ(total->GetNumberOfNestedElements(), 1);
  EXPECT_STREQ(total->GetNestedElement(0)->GetName(), "failure");
  EXPECT_STREQ(total->GetNestedElement(0)->GetAttribute("message"),
    "1 of 12 values fail (atol 0, rtol 4.77e-07); max |diff| 0.001");

  // The difference mesh: result - baseline for each array, and where it fails.
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(diff.c_str());
  reader->Update();
  vtkPointData* data = reader->GetOutput()->GetPointData();
  auto* totalDifference = vtkDoubleArray::SafeDownCast(data->GetArray("total_difference"));
  ASSERT_NE(totalDifference, nullptr);
  EXPECT_EQ(totalDifference->GetComponent(3, 1), double(0.751f) - double(0.75f));
  EXPECT_EQ(totalDifference->GetComponent(0, 0), 0.0);
  vtkDataArray* flagsDifference = data->GetArray("shading_flags_difference");
  ASSERT_NE(flagsDifference, nullptr);
  EXPECT_EQ(flagsDifference->GetComponent(0, 0), 64.0);
  auto* passed = vtkUnsignedCharArray::SafeDownCast(data->GetArray("compare_passed"));
  ASSERT_NE(passed, nullptr);
  EXPECT_EQ(std::vector<int>({ passed->GetValue(0), passed->GetValue(1), passed->GetValue(2), passed->GetValue(3) }),
    std::vector<int>({ 0, 1, 1, 0 }));
  ASSERT_NE(data->GetArray("total"), nullptr); // the result's own arrays stay beside them
  auto* cellsPassed =
    vtkUnsignedCharArray::SafeDownCast(reader->GetOutput()->GetCellData()->GetArray("compare_passed"));
  ASSERT_NE(cellsPassed, nullptr);
  EXPECT_EQ(cellsPassed->GetNumberOfValues(), 2);
}
}

namespace
{
/// The shaded square with its points in reverse order (and its arrays and triangles with them),
/// the point that was 3 moved by `shift` along x.
vtkSmartPointer<vtkPolyData> reversedSquare(double shift)
{
  vtkSmartPointer<vtkPolyData> mesh = square(shaded);
  auto reversed = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  for (vtkIdType i = 3; i >= 0; --i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    p[0] += i == 3 ? shift : 0.0;
    points->InsertNextPoint(p);
  }
  reversed->SetPoints(points);
  vtkNew<vtkCellArray> triangles;
  const vtkIdType second[3] = { 3, 1, 0 }, first[3] = { 3, 2, 1 }; // the cells swapped too
  triangles->InsertNextCell(3, second);
  triangles->InsertNextCell(3, first);
  reversed->SetPolys(triangles);
  for (int a = 0; a < mesh->GetPointData()->GetNumberOfArrays(); ++a)
  {
    vtkDataArray* array = mesh->GetPointData()->GetArray(a);
    vtkSmartPointer<vtkDataArray> copy;
    copy.TakeReference(array->NewInstance());
    copy->SetName(array->GetName());
    copy->SetNumberOfComponents(array->GetNumberOfComponents());
    for (vtkIdType i = 3; i >= 0; --i)
    {
      copy->InsertNextTuple(array->GetTuple(i));
    }
    reversed->GetPointData()->AddArray(copy);
  }
  vtkNew<vtkFloatArray> area;
  area->SetName("cell_value");
  area->InsertNextValue(2.0f); // the baseline's cell 1, now first
  area->InsertNextValue(1.0f);
  reversed->GetCellData()->AddArray(area);
  return reversed;
}

/// A cell of the mesh that CompareInPieces cuts: its kind (1 a vertex, 2 a line, 3 a triangle),
/// its global id, its points' global ids, and whether the piece holds it as a duplicate.
struct PieceCell
{
  int kind;
  vtkIdType id;
  std::vector<vtkIdType> points;
  bool ghost = false;
};

/// A mesh, or a piece of one, of these points and cells (by global id), with the point array
/// value (id + 0.5) and the cell array cell_value (10 id, -1 where a duplicate); with global ids
/// and ghost flags where asked.
vtkSmartPointer<vtkPolyData> meshOfIds(
  const std::vector<vtkIdType>& pointIds, std::vector<PieceCell> cells, bool withIds)
{
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  vtkNew<vtkFloatArray> value;
  vtkNew<vtkIdTypeArray> pointGlobalIds, cellGlobalIds;
  for (vtkIdType id : pointIds)
  {
    points->InsertNextPoint(static_cast<double>(id % 3), static_cast<double>(id / 3), 0.25 * static_cast<double>(id));
    value->InsertNextValue(static_cast<float>(id) + 0.5f);
    pointGlobalIds->InsertNextValue(id);
  }
  mesh->SetPoints(points);
  // A mesh keeps its vertices, then its lines, then its polygons: so do their cell arrays.
  std::stable_sort(cells.begin(), cells.end(), [](const PieceCell& a, const PieceCell& b) { return a.kind < b.kind; });
  vtkNew<vtkCellArray> vertices, lines, triangles;
  vtkNew<vtkFloatArray> cellValue;
  vtkNew<vtkUnsignedCharArray> ghosts;
  for (const PieceCell& cell : cells)
  {
    std::vector<vtkIdType> corners;
    for (vtkIdType id : cell.points)
    {
      corners.push_back(std::find(pointIds.begin(), pointIds.end(), id) - pointIds.begin());
    }
    (cell.kind == 1      ? vertices
        : cell.kind == 2 ? lines
                         : triangles)
      ->InsertNextCell(static_cast<vtkIdType>(corners.size()), corners.data());
    cellValue->InsertNextValue(cell.ghost ? -1.0f : 10.0f * static_cast<float>(cell.id));
    ghosts->InsertNextValue(cell.ghost ? vtkDataSetAttributes::DUPLICATECELL : 0);
    cellGlobalIds->InsertNextValue(cell.id);
  }
  mesh->SetVerts(vertices);
  mesh->SetLines(lines);
  mesh->SetPolys(triangles);
  value->SetName("value");
  mesh->GetPointData()->AddArray(value);
  cellValue->SetName("cell_value");
  mesh->GetCellData()->AddArray(cellValue);
  if (withIds)
  {
    pointGlobalIds->SetName("GlobalIds");
    mesh->GetPointData()->SetGlobalIds(pointGlobalIds);
    cellGlobalIds->SetName("GlobalIds");
    mesh->GetCellData()->SetGlobalIds(cellGlobalIds);
    ghosts->SetName(vtkDataSetAttributes::GhostArrayName());
    mesh->GetCellData()->AddArray(ghosts);
  }
  return mesh;
}

// A .pvtp's pieces are compared as the mesh they were cut from: its points once each in the
// order of their global ids, its vertices, lines and polygons each in the order of theirs, the
// duplicates of cells (ghost cells) left out. Pieces here hold their points and cells in
// another order than the mesh, and each holds a duplicate of a triangle of the other's.
TEST_F(Compare, APvtpIsComparedAsTheMeshItsPiecesWereCutFrom)
{
  const std::vector<PieceCell> cells = { { 1, 0, { 5 } }, { 2, 1, { 4, 5 } }, { 3, 2, { 0, 1, 3 } },
    { 3, 3, { 1, 4, 3 } }, { 3, 4, { 1, 2, 4 } } };
  const std::string whole = write("whole.vtp", meshOfIds({ 0, 1, 2, 3, 4, 5 }, cells, false));
  std::filesystem::create_directories(folder / "pieces");
  auto writePieces = [&](bool secondMarksItsDuplicate)
  {
    write("pieces/pieces_0.vtp",
      meshOfIds({ 4, 3, 1, 0, 5, 2 },
        { { 3, 4, { 1, 2, 4 } }, { 3, 3, { 1, 4, 3 }, true }, { 2, 1, { 4, 5 } }, { 3, 2, { 0, 1, 3 } } }, true));
    write("pieces/pieces_1.vtp",
      meshOfIds({ 3, 5, 1, 4, 2 },
        { { 3, 3, { 1, 4, 3 } }, { 1, 0, { 5 } }, { 3, 4, { 1, 2, 4 }, secondMarksItsDuplicate } }, true));
  };
  writePieces(true);
  const std::string pvtp = file("pieces.pvtp",
    "<?xml version=\"1.0\"?>\n"
    "<VTKFile type=\"PPolyData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
    "  <PPolyData GhostLevel=\"1\">\n"
    "    <PPointData GlobalIds=\"GlobalIds\">\n"
    "      <PDataArray type=\"Float32\" Name=\"value\"/>\n"
    "      <PDataArray type=\"Int64\" Name=\"GlobalIds\"/>\n"
    "    </PPointData>\n"
    "    <PCellData GlobalIds=\"GlobalIds\">\n"
    "      <PDataArray type=\"Float32\" Name=\"cell_value\"/>\n"
    "      <PDataArray type=\"Int64\" Name=\"GlobalIds\"/>\n"
    "      <PDataArray type=\"UInt8\" Name=\"vtkGhostType\"/>\n"
    "    </PCellData>\n"
    "    <PPoints>\n"
    "      <PDataArray type=\"Float32\" Name=\"Points\" NumberOfComponents=\"3\"/>\n"
    "    </PPoints>\n"
    "    <Piece Source=\"pieces/pieces_0.vtp\"/>\n"
    "    <Piece Source=\"pieces/pieces_1.vtp\"/>\n"
    "  </PPolyData>\n"
    "</VTKFile>\n");
  const std::string report = (folder / "report.json").string();
  Result result = shadelab("compare " + whole + " " + pvtp + " --json " + report);
  EXPECT_EQ(result.exitCode, 0) << result.out << result.err;
  const nlohmann::json json = nlohmann::json::parse(slurp(report));
  EXPECT_EQ(json["baseline_order"], "as read");
  EXPECT_EQ(json["result_order"],
    "put in the order of their global ids, which are not themselves compared; 5 copies of points that pieces share "
    "left out; 2 ghost cells left out");
  EXPECT_EQ(result.out.substr(0, result.out.find('\n') + 1),
    "shadelab compare: the result " + pvtp +
      " (6 points, 5 cells, put in the order of their global ids, which are not themselves compared; 5 copies of "
      "points that pieces share left out; 2 ghost cells left out) against the baseline " +
      whole + " (6 points, 5 cells); points and cells matched by id\n");
  EXPECT_NE(result.out.find("\nPASS: 3 arrays agree\n"), std::string::npos) << result.out;
  // A piece alone: its ids do not number its points 0 to n-1.
  result = shadelab("compare " + whole + " " + (folder / "pieces" / "pieces_1.vtp").string());
  EXPECT_EQ(result.exitCode, 1);
  EXPECT_NE(result.out.find(" (5 points, 3 cells, compared as read: its points' global ids do not number them 0 to "
                            "n-1) against"),
    std::string::npos)
    << result.out;
  // A triangle on both pieces that neither marks as a duplicate.
  writePieces(false);
  result = shadelab("compare " + whole + " " + pvtp);
  EXPECT_EQ(result.exitCode, 2);
  EXPECT_EQ(result.err,
    "shadelab compare: " + pvtp +
      ": the global cell id 4 is on two of its pieces' polygons: the pieces are not of one mesh, or their copies of "
      "a cell are not marked as ghost cells (vtkGhostType)\n");
}

TEST_F(Compare, ReorderedMeshesMatchByNearestPoint)
{
  vtkSmartPointer<vtkPolyData> baseline = square(shaded);
  vtkNew<vtkFloatArray> cellValue;
  cellValue->SetName("cell_value");
  cellValue->InsertNextValue(1.0f);
  cellValue->InsertNextValue(2.0f);
  baseline->GetCellData()->AddArray(cellValue);
  const std::string a = write("a.vtp", baseline), b = write("b.vtp", reversedSquare(0.0));
  // By id, everything differs; by nearest point, nothing does.
  EXPECT_EQ(shadelab("compare " + a + " " + b).exitCode, 1);
  const Result nearest = shadelab("compare " + a + " " + b + " --nearest 1e-9");
  EXPECT_EQ(nearest.exitCode, 0) << nearest.out;
  EXPECT_NE(nearest.out.find(
              "; points matched by nearest point, the farthest 0 away; cells by their centres, the farthest 0 away\n"),
    std::string::npos)
    << nearest.out;
  // A point moved by 0.01: within 0.1 it matches and its coordinate differs; within 0.001 it
  // has no match.
  const std::string moved = write("moved.vtp", reversedSquare(0.01));
  const Result within = shadelab("compare " + moved + " " + moved + " --nearest 0.1");
  EXPECT_EQ(within.exitCode, 0);
  // By id, with the points left out: the moved point no longer counts, the reversed arrays do.
  const std::string once = write("once.vtp", reversedSquare(0.0));
  const Result noPoints = shadelab("compare " + once + " " + moved + " --no-points");
  EXPECT_EQ(noPoints.exitCode, 0) << noPoints.out;
  EXPECT_EQ(linesAbout(noPoints.out, "points"), "");
  EXPECT_EQ(shadelab("compare " + once + " " + moved).exitCode, 1);
  const Result loose = shadelab("compare " + a + " " + moved + " --nearest 0.1");
  EXPECT_EQ(loose.exitCode, 1);
  EXPECT_NE(
    linesAbout(loose.out, "points")
      .find("worst failing at point 3 (0, 1, 0), component 0: 0 in the baseline, 0.0099999997764825821 in the result"),
    std::string::npos)
    << loose.out;
  // The difference mesh is the result's: the moved point is its point 0.
  const std::string diff = (folder / "diff.vtp").string();
  EXPECT_EQ(shadelab("compare " + a + " " + moved + " --nearest 0.1 --diff " + diff).exitCode, 1);
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(diff.c_str());
  reader->Update();
  vtkDataArray* pointsDifference = reader->GetOutput()->GetPointData()->GetArray("points_difference");
  ASSERT_NE(pointsDifference, nullptr);
  EXPECT_EQ(pointsDifference->GetComponent(0, 0), double(0.01f));
  EXPECT_EQ(pointsDifference->GetComponent(3, 0), 0.0);
  auto* passed = vtkUnsignedCharArray::SafeDownCast(reader->GetOutput()->GetPointData()->GetArray("compare_passed"));
  ASSERT_NE(passed, nullptr);
  EXPECT_EQ(passed->GetValue(0), 0);
  EXPECT_EQ(passed->GetValue(3), 1);
  // Within 0.001 the moved point has no match: a difference, and the point arrays say why.
  const Result tight = shadelab("compare " + a + " " + moved + " --nearest 0.001");
  EXPECT_EQ(tight.exitCode, 1);
  EXPECT_EQ(linesAbout(tight.out, "total"),
    "  DIFFER total                          point  float32 x3 not compared: the result's point 0 (0.01, 1, 0) has no "
    "match in the baseline within 0.001 (the nearest is 0.01 away)\n");
  // The cells it is a corner of moved their centres by a third of it.
  EXPECT_EQ(linesAbout(tight.out, "cell_value"),
    "  DIFFER cell_value                     cell   float32 x1 not compared: the result's cell centre 0 (0.337, 0.667, "
    "0) has no match in the baseline within 0.001 (the nearest is 0.00333 away)\n");
  // Copies of a point (a seam: spot.obj has a point per corner) match one to one.
  const std::string spot = shadelab::testing::sourcePath("data/meshes/spot.obj");
  EXPECT_EQ(shadelab("compare " + spot + " " + spot + " --nearest 0").exitCode, 0);
}
}

namespace
{
TEST_F(Compare, NamesThatAreNotUtf8GiveValidReports)
{
  // A legacy file may name an array with any bytes: here Latin-1's "café".
  const std::string legacy = file("latin1.vtk",
    "# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n0 0 0 1 0 0 0 1 0\n"
    "POLYGONS 1 4\n3 0 1 2\nPOINT_DATA 3\nSCALARS caf\xe9 float 1\nLOOKUP_TABLE default\n1 2 3\n");
  const std::string json = (folder / "r.json").string(), junit = (folder / "r.xml").string();
  const Result result = shadelab("compare " + legacy + " " + legacy + " --json " + json + " --junit " + junit);
  EXPECT_EQ(result.exitCode, 0) << result.out << result.err;
  const nlohmann::json report = nlohmann::json::parse(slurp(json));
  EXPECT_EQ(report["arrays"][1]["name"], "caf\xef\xbf\xbd"); // U+FFFD for the byte that is not UTF-8
  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName(junit.c_str());
  ASSERT_EQ(parser->Parse(), 1);
  EXPECT_STREQ(parser->GetRootElement()->GetNestedElement(0)->GetNestedElement(1)->GetAttribute("name"), "caf?");
}
}

namespace
{
vtkSmartPointer<vtkPolyData> readPolyData(const std::string& path)
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader->GetOutput();
}

/// The noise checks of the array of this name in a JSON report.
nlohmann::json noiseIn(const nlohmann::json& report, const std::string& name)
{
  for (const nlohmann::json& array : report["arrays"])
  {
    if (array["name"] == name)
    {
      return array["noise"]["components"][0];
    }
  }
  return {};
}

/// The console's line for a component's noise checks, from the JSON report's figures.
std::string noiseLine(const nlohmann::json& check)
{
  const bool countPasses = check["count_passed"], biasPasses = check["bias_passed"];
  return "noise: " + std::to_string(check["outside"].get<int>()) + " of " + std::to_string(check["values"].get<int>()) +
    " values outside 3 standard errors (" + digits3(check["expected"]) + " expected, at most " +
    std::to_string(check["allowed"].get<int>()) + " allowed" + (countPasses ? "" : ": too many") +
    "); mean difference " + digits3(check["mean_difference"]) + " (at most " + digits3(check["mean_difference_limit"]) +
    " either way" + (biasPasses ? "" : ": a bias") + ")";
}

/// Runs of a sampled scene: the teapot's ambient occlusion under
/// data/scenes/shadows_occlusion.json, a second or so each.
class CompareSampled : public Compare
{
protected:
  const std::string mesh = shadelab::testing::sourcePath("data/meshes/teapot.obj");
  const std::string scene = shadelab::testing::sourcePath("data/scenes/shadows_occlusion.json");
  static constexpr const char* arrays = "ambient_occlusion,ambient_occlusion_std_error";

  /// The occlusion from this many rays per vertex, in the test's folder.
  std::string shadeOcclusion(int rays)
  {
    const std::string path = (folder / ("teapot_" + std::to_string(rays) + ".vtp")).string();
    const Result run = shadelab("shade " + mesh + " --scene " + scene + " --ambient-occlusion " + std::to_string(rays) +
      " -a " + arrays + " -o " + path);
    EXPECT_EQ(run.exitCode, 0) << run.err;
    return path;
  }
};

TEST_F(CompareSampled, TwoRunsAgreeAsNoiseAndAShiftedCopyDoesNot)
{
  // 256 rays and 32: two honest runs.
  const std::string many = shadeOcclusion(256), few = shadeOcclusion(32);
  const std::string json = (folder / "r.json").string(), junit = (folder / "r.xml").string();
  const std::string options = " --standard-errors 3 --arrays ambient_occlusion --json " + json + " --junit " + junit;
  const Result agree = shadelab("compare " + many + " " + few + options);
  EXPECT_EQ(agree.exitCode, 0) << agree.out;
  const nlohmann::json check = noiseIn(nlohmann::json::parse(slurp(json)), "ambient_occlusion");
  ASSERT_FALSE(check.is_null()) << slurp(json);
  // n P(|Z| > 3) expected; each check at 0.0005, the mean difference two-sided: z = 3.4808.
  const double values = check["values"];
  EXPECT_GT(values, 3000);
  EXPECT_NEAR(check["expected"].get<double>(), values * std::erfc(3 / std::sqrt(2.0)), 1e-9);
  EXPECT_GT(check["allowed"].get<double>(), check["expected"].get<double>());
  EXPECT_LE(check["outside"].get<double>(), check["allowed"].get<double>());
  EXPECT_NEAR(check["mean_difference_limit"].get<double>(),
    3.4807564043462128 * check["mean_difference_standard_error"].get<double>(), 1e-12);
  EXPECT_LE(std::abs(check["mean_difference"].get<double>()), check["mean_difference_limit"].get<double>());
  EXPECT_NE(agree.out.find("         " + noiseLine(check) + "\n"), std::string::npos) << agree.out;
  // The JUnit report says it too, as the passing test case's output.
  vtkNew<vtkXMLDataParser> parser;
  parser->SetFileName(junit.c_str());
  ASSERT_EQ(parser->Parse(), 1);
  vtkXMLDataElement* occlusion = parser->GetRootElement()->GetNestedElement(0)->FindNestedElementWithNameAndAttribute(
    "testcase", "name", "ambient_occlusion");
  ASSERT_NE(occlusion, nullptr);
  vtkXMLDataElement* output = occlusion->FindNestedElementWithName("system-out");
  ASSERT_NE(output, nullptr);
  EXPECT_NE(std::string(output->GetCharacterData()).find(noiseLine(check)), std::string::npos);
  std::cout << "teapot, 256 against 32 rays: " << noiseLine(check) << "\n";

  // Every 20th point of the 32-ray run moved by 4 combined standard errors, up and down in turn.
  vtkSmartPointer<vtkPolyData> shifted = readPolyData(few), baseline = readPolyData(many);
  vtkDataArray* occlusionValues = shifted->GetPointData()->GetArray("ambient_occlusion");
  vtkDataArray* errors = shifted->GetPointData()->GetArray("ambient_occlusion_std_error");
  vtkDataArray* baselineErrors = baseline->GetPointData()->GetArray("ambient_occlusion_std_error");
  ASSERT_TRUE(occlusionValues && errors && baselineErrors);
  for (vtkIdType i = 0; i < occlusionValues->GetNumberOfTuples(); i += 20)
  {
    const double combined = std::hypot(errors->GetComponent(i, 0), baselineErrors->GetComponent(i, 0));
    occlusionValues->SetComponent(i, 0, occlusionValues->GetComponent(i, 0) + (i % 40 == 0 ? 4 : -4) * combined);
  }
  const Result differ = shadelab("compare " + many + " " + write("shifted.vtp", shifted) + options);
  EXPECT_EQ(differ.exitCode, 1) << differ.out;
  const nlohmann::json moved = noiseIn(nlohmann::json::parse(slurp(json)), "ambient_occlusion");
  EXPECT_EQ(moved["count_passed"], false);
  EXPECT_GT(moved["outside"].get<double>(), moved["allowed"].get<double>());
  EXPECT_NE(differ.out.find("  DIFFER ambient_occlusion "), std::string::npos) << differ.out;
  EXPECT_NE(differ.out.find("         " + noiseLine(moved) + "\n"), std::string::npos) << differ.out;
  std::cout << "5% of it shifted by 4 standard errors: " << noiseLine(moved) << "\n";
}
}

namespace
{
TEST_F(CompareSampled, TheCTestHelperPassesTheStatisticalModeThrough)
{
  // A project of its own with one test: the 32-ray run against the 256-ray baseline, the
  // standard errors left out of the comparison and the significance 0.01.
  const std::string baseline = shadeOcclusion(256);
  const std::filesystem::path project = folder / "project", build = folder / "build";
  std::filesystem::create_directories(project);
  file("project/CMakeLists.txt",
    "cmake_minimum_required(VERSION 3.20)\nproject(SampledRegression NONE)\nenable_testing()\n"
    "include(\"" +
      shadelab::testing::sourcePath("cmake/ShadeLabRegression.cmake") +
      "\")\n"
      "shadelab_add_regression_test(NAME teapot_occlusion MESH \"" +
      mesh + "\" SCENE \"" + scene + "\" BASELINE \"" + baseline + "\" ARRAYS \"" + arrays +
      "\" EXCLUDE \"*_std_error\" STANDARD_ERRORS 3 "
      "SIGNIFICANCE 0.01 SHADE_ARGS --ambient-occlusion 32)\n");
  const Result configured = run("cmake",
    "-S " + project.string() + " -B " + build.string() +
      " -DSHADELAB_EXECUTABLE=" + shadelab::testing::shadelabExecutable());
  ASSERT_EQ(configured.exitCode, 0) << configured.out << configured.err;
  const Result tested = run("ctest", "--test-dir " + build.string() + " -V");
  EXPECT_EQ(tested.exitCode, 0) << tested.out << tested.err;
  EXPECT_NE(tested.out.find("  ok     ambient_occlusion "), std::string::npos) << tested.out;
  EXPECT_NE(tested.out.find("; noise: 3 standard errors, significance 0.01\n"), std::string::npos) << tested.out;
  EXPECT_NE(tested.out.find("values outside 3 standard errors ("), std::string::npos) << tested.out;
  EXPECT_NE(tested.out.find("each check at significance 0.005 (0.01 shared equally"), std::string::npos) << tested.out;
  EXPECT_EQ(tested.out.find("ok     ambient_occlusion_std_error"), std::string::npos) << tested.out;
  EXPECT_NE(slurp(build / "teapot_occlusion.xml").find("<system-out>"), std::string::npos);
}
}
