#include "RenderImage.h"

#include "ArrayCatalog.h"
#include "MaterialArrays.h"
#include "MeshFiles.h"
#include "OffScreenImage.h"
#include "ShadingFlags.h"
#include "VtkErrorCapture.h"

#include "vtkActor.h"
#include "vtkActor2D.h"
#include "vtkCamera.h"
#include "vtkCellArray.h"
#include "vtkColorTransferFunction.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkLookupTable.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyDataMapper.h"
#include "vtkPolyDataMapper2D.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkTextActor.h"
#include "vtkTextProperty.h"
#include "vtkTextRenderer.h"
#include "vtkUnsignedCharArray.h"
#include "vtkVariant.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <sstream>

namespace shadelab::app
{
namespace
{
using Rgb = std::array<unsigned char, 3>;

/// Okabe and Ito's palette for colour-blind readers ("Color Universal Design", 2008), without
/// its black, which the dark background would hide: the categories' colours, in order.
constexpr std::array<Rgb, 7> categoryColours{ { { 86, 180, 233 }, { 230, 159, 0 }, { 0, 158, 115 }, { 240, 228, 66 },
  { 0, 114, 178 }, { 213, 94, 0 }, { 204, 121, 167 } } };
/// The colour of the values that the palette has no colour left for.
constexpr Rgb otherValuesColour{ 150, 150, 150 };
constexpr double background[3] = { 0.16, 0.17, 0.2 };
/// The smallest font, in pixels, that the legend shrinks to on a small picture.
constexpr int smallestFont = 8;
/// The share of the picture's width that a legend takes at most if its font can shrink to fit,
/// and at the smallest font.
constexpr double legendShare = 0.5, largestLegendShare = 0.75;

std::string arrayNames(vtkPointData* pointData)
{
  std::string names;
  for (int a = 0; a < pointData->GetNumberOfArrays(); ++a)
  {
    names += (a ? ", " : "") + std::string(pointData->GetArrayName(a) ? pointData->GetArrayName(a) : "");
  }
  return names.empty() ? "no point arrays (shade it first: shadelab shade)" : names;
}

/// A view-up vector not parallel to the line of sight.
glm::dvec3 viewUpFor(const glm::dvec3& sight)
{
  return std::abs(sight.y) > 0.99 ? glm::dvec3(0, 0, -1) : glm::dvec3(0, 1, 0);
}

/// How a 3-component array's values fit the picture's [0, 1].
struct ColourRange
{
  vtkIdType aboveOne = 0;  ///< vertices with a component above 1 once multiplied by the exposure
  vtkIdType nonFinite = 0; ///< vertices with a NaN or infinite component
  double largest = 0;      ///< the largest finite component, before the exposure
};

/// The array's colours as 8-bit RGB, for the mapper to draw as they are: each component (an
/// 8-bit one as a fraction of 255) times the exposure, clipped to [0, 1], sRGB-encoded under
/// --srgb; a non-finite one 0. range receives what does not fit.
vtkSmartPointer<vtkUnsignedCharArray> directColours(vtkDataArray* rgb, const RenderOptions& options, ColourRange& range)
{
  const double scale = rgb->GetDataType() == VTK_UNSIGNED_CHAR ? 1.0 / 255.0 : 1.0;
  auto colours = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colours->SetName("colours");
  colours->SetNumberOfComponents(3);
  colours->SetNumberOfTuples(rgb->GetNumberOfTuples());
  for (vtkIdType i = 0; i < rgb->GetNumberOfTuples(); ++i)
  {
    bool above = false, nonFinite = false;
    for (int c = 0; c < 3; ++c)
    {
      const double value = scale * rgb->GetComponent(i, c);
      nonFinite = nonFinite || !std::isfinite(value);
      range.largest = std::isfinite(value) ? std::max(range.largest, value) : range.largest;
      const double exposed = std::isfinite(value) ? options.exposure * value : 0.0;
      above = above || exposed > 1;
      const double linear = std::clamp(exposed, 0.0, 1.0);
      const double shown = options.srgb ? linearToSrgb(linear) : linear;
      colours->SetValue(3 * i + c, static_cast<unsigned char>(std::lround(255.0 * shown)));
    }
    range.aboveOne += above;
    range.nonFinite += nonFinite;
  }
  return colours;
}

/// "n of N vertices have" (or "has", for one).
std::string verticesHave(vtkIdType count, vtkIdType total)
{
  return std::to_string(count) + " of " + std::to_string(total) + (count == 1 ? " vertices has" : " vertices have");
}

/// The largest exposure with one significant digit that draws `largest` within [0, 1]: a
/// number a user can type.
double exposureWithinRange(double largest)
{
  const double exact = 1.0 / largest;
  const double digit = std::pow(10.0, std::floor(std::log10(exact)));
  return std::floor(exact / digit) * digit;
}

/// What the user should know of colours drawn other than as they are.
std::vector<std::string> clippingNotes(
  const std::string& arrayName, vtkIdType vertices, const ColourRange& range, bool srgb)
{
  std::vector<std::string> notes;
  if (range.aboveOne > 0)
  {
    std::ostringstream note;
    note << arrayName << ": " << verticesHave(range.aboveOne, vertices) << " a value above 1, drawn clipped; "
         << "--exposure " << exposureWithinRange(range.largest) << " scales them into range"
         << (srgb ? "" : " (and --srgb encodes linear values for the screen, as a renderer does)");
    notes.push_back(note.str());
  }
  if (range.nonFinite > 0)
  {
    notes.push_back(arrayName + ": " + verticesHave(range.nonFinite, vertices) + " a non-finite value, drawn black");
  }
  return notes;
}

/// Whether the array holds ShadeLab's flags: 8-bit, named (after any prefix) as the shading's
/// or the visibility step's flags.
bool isFlagsArray(vtkDataArray* array, const std::string& name)
{
  auto endsWith = [&name](const std::string& suffix)
  { return name.size() >= suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0; };
  return array->GetDataType() == VTK_UNSIGNED_CHAR &&
    (endsWith(flagsArrayName("")) || endsWith(visibilityFlagsArrayName("")));
}

/// The number of vertices with each value of an integer array, or nothing once it has more than
/// `most` values.
std::optional<std::map<double, vtkIdType>> valueCounts(vtkDataArray* array, std::size_t most)
{
  std::map<double, vtkIdType> counts;
  for (vtkIdType i = 0; i < array->GetNumberOfTuples(); ++i)
  {
    ++counts[array->GetComponent(i, 0)];
    if (counts.size() > most)
    {
      return std::nullopt;
    }
  }
  return counts;
}

/// A value of the array drawn in a colour of its own, and what the legend says of it.
struct Category
{
  double value;        ///< NaN for the values beyond the palette
  std::string label;   ///< the value, as the legend writes it
  std::string meaning; ///< the flags' meanings, one a line, or nothing
  Rgb colour;
};

/// The bits of a flags value by their meanings (ShadingFlags.h), one a line.
std::string flagMeaningsOf(double value)
{
  std::string lines;
  for (const FlagMeaning& flag : flagMeanings)
  {
    if (static_cast<unsigned>(value) & flag.flag)
    {
      lines += (lines.empty() ? "" : "\n") + std::string(flag.meaning);
    }
  }
  return lines.empty() ? "no flag" : lines;
}

/// The values of counts as categories, in increasing order: every one when the palette has a
/// colour for each, otherwise the most frequent, and the rest together as "other values".
std::vector<Category> categoriesOf(const std::map<double, vtkIdType>& counts, bool flags)
{
  std::vector<std::pair<double, vtkIdType>> byCount(counts.begin(), counts.end());
  std::stable_sort(byCount.begin(), byCount.end(), [](const auto& a, const auto& b) { return a.second > b.second; });
  const std::size_t coloured = std::min(byCount.size(), categoryColours.size());
  std::vector<double> values;
  for (std::size_t c = 0; c < coloured; ++c)
  {
    values.push_back(byCount[c].first);
  }
  std::sort(values.begin(), values.end());
  std::vector<Category> categories;
  for (std::size_t c = 0; c < values.size(); ++c)
  {
    const std::string label = std::to_string(static_cast<long long>(values[c])); // an integer array's
    categories.push_back({ values[c], label, flags ? flagMeaningsOf(values[c]) : "", categoryColours[c] });
  }
  if (byCount.size() > coloured)
  {
    const std::size_t others = byCount.size() - coloured;
    categories.push_back({ std::numeric_limits<double>::quiet_NaN(), "",
      std::to_string(others) + (others == 1 ? " other value" : " other values"), otherValuesColour });
  }
  return categories;
}

/// An indexed lookup table: each category's value in its colour, any other value (NaN
/// included) in the colour of the values beyond the palette.
vtkSmartPointer<vtkLookupTable> categoryTable(const std::vector<Category>& categories)
{
  auto table = vtkSmartPointer<vtkLookupTable>::New();
  table->IndexedLookupOn();
  table->SetNanColor(otherValuesColour[0] / 255.0, otherValuesColour[1] / 255.0, otherValuesColour[2] / 255.0, 1);
  table->SetNumberOfTableValues(
    std::count_if(categories.begin(), categories.end(), [](const Category& c) { return !std::isnan(c.value); }));
  vtkIdType index = 0;
  for (const Category& category : categories)
  {
    if (!std::isnan(category.value))
    {
      const Rgb& rgb = category.colour;
      table->SetTableValue(index++, rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0, 1);
      table->SetAnnotation(vtkVariant(category.value), category.label);
    }
  }
  return table;
}

/// Moreland's cool-to-warm diverging map (Moreland 2009, "Diverging Color Maps for Scientific
/// Visualization"), the map ParaView uses by default, over the array's range: centred on zero
/// for signed data (n.s, r.v), so that white means zero.
vtkSmartPointer<vtkColorTransferFunction> divergingMap(vtkDataArray* array, double range[2])
{
  array->GetRange(range);
  if (range[0] == range[1])
  {
    // A constant array: a range around it, so the map and its bar stay readable.
    const double half = range[0] == 0 ? 1.0 : 0.5 * std::abs(range[0]);
    range[0] -= half;
    range[1] += half;
  }
  if (range[0] < 0 && range[1] > 0)
  {
    range[1] = std::max(-range[0], range[1]);
    range[0] = -range[1];
  }
  auto map = vtkSmartPointer<vtkColorTransferFunction>::New();
  map->SetColorSpaceToDiverging();
  map->AddRGBPoint(range[0], 0.230, 0.299, 0.754);
  map->AddRGBPoint(range[1], 0.706, 0.016, 0.150);
  return map;
}

/// The font size, in pixels, of a picture's text: the same share of the picture at every size,
/// and no smaller than a screen's smallest readable text.
int fontSizeFor(int width, int height)
{
  return std::clamp(static_cast<int>(std::lround(std::min(0.75 * width, 1.0 * height) / 36.0)), 10, 40);
}

vtkSmartPointer<vtkTextActor> textActor(const std::string& text, int fontSize)
{
  auto actor = vtkSmartPointer<vtkTextActor>::New();
  actor->SetInput(text.c_str());
  actor->GetTextProperty()->SetFontSize(fontSize);
  return actor;
}

/// The width and height, in pixels, that text takes on the picture.
std::array<int, 2> textSize(vtkTextActor* text)
{
  int box[4] = { 0, 0, 0, 0 };
  vtkTextRenderer::GetInstance()->GetBoundingBox(text->GetTextProperty(), text->GetInput(), box, 72);
  return { box[1] - box[0] + 1, box[3] - box[2] + 1 };
}

/// A rectangle from (x0, y0) to (x1, y1) in its renderer's pixels, coloured through map from
/// the value `bottom` at its foot to `top` at its head in `rows` steps (one value: a swatch).
vtkSmartPointer<vtkActor2D> colouredRectangle(
  double x0, double y0, double x1, double y1, vtkScalarsToColors* map, double bottom, double top, int rows)
{
  vtkNew<vtkPoints> points;
  vtkNew<vtkDoubleArray> values;
  vtkNew<vtkCellArray> quads;
  for (int r = 0; r <= rows; ++r)
  {
    const double t = static_cast<double>(r) / rows;
    points->InsertNextPoint(x0, y0 + t * (y1 - y0), 0);
    points->InsertNextPoint(x1, y0 + t * (y1 - y0), 0);
    values->InsertNextValue(bottom + t * (top - bottom));
    values->InsertNextValue(bottom + t * (top - bottom));
    if (r > 0)
    {
      const vtkIdType quad[4] = { 2 * r - 2, 2 * r - 1, 2 * r + 1, 2 * r };
      quads->InsertNextCell(4, quad);
    }
  }
  vtkNew<vtkPolyData> rectangle;
  rectangle->SetPoints(points);
  rectangle->SetPolys(quads);
  rectangle->GetPointData()->SetScalars(values);
  vtkNew<vtkPolyDataMapper2D> mapper;
  mapper->SetInputData(rectangle);
  mapper->SetLookupTable(map);
  mapper->UseLookupTableScalarRangeOn();
  mapper->SetColorModeToMapScalars();
  auto actor = vtkSmartPointer<vtkActor2D>::New();
  actor->SetMapper(mapper);
  return actor;
}

/// What the colours mean, drawn beside the mesh in a renderer of its own (so that the mesh is
/// framed beside it, never under it): its props, in that renderer's pixels, and its size.
struct Legend
{
  std::vector<vtkSmartPointer<vtkProp>> props;
  int width = 0;
  int height = 0; ///< of a category legend, which may be taller than the picture
};

/// Labels for values: three significant digits, or as many more (up to 6) as it takes for them
/// to differ; exponents without their "+" and leading zeros ("4.66e5").
std::vector<std::string> numberLabels(const std::vector<double>& values)
{
  std::vector<std::string> labels;
  for (int digits = 3; digits <= 6; ++digits)
  {
    labels.clear();
    for (double value : values)
    {
      char text[32];
      std::snprintf(text, sizeof text, "%.*g", digits, value == 0 ? 0.0 : value); // no "-0"
      std::string label = text;
      for (const char* verbose : { "e+0", "e+", "e-0" })
      {
        if (const std::size_t at = label.find(verbose); at != std::string::npos)
        {
          label.replace(at, std::string(verbose).size(), verbose[1] == '-' ? "e-" : "e");
        }
      }
      labels.push_back(label);
    }
    if (std::adjacent_find(labels.begin(), labels.end()) == labels.end())
    {
      break;
    }
  }
  return labels;
}

/// A colour bar over range with five labels, as tall as the picture less a margin for the end
/// labels.
Legend colourBarLegend(vtkColorTransferFunction* map, const double range[2], int font, int height)
{
  Legend legend;
  const double barLeft = font, barRight = 2.0 * font;
  const double foot = std::max(0.08 * height, 1.2 * font), head = height - foot;
  legend.props.push_back(colouredRectangle(barLeft, foot, barRight, head, map, range[0], range[1], 128));
  constexpr int labelCount = 5;
  std::vector<double> values;
  for (int l = 0; l < labelCount; ++l)
  {
    values.push_back(range[0] + (range[1] - range[0]) * l / (labelCount - 1));
  }
  int widest = 0;
  const std::vector<std::string> labels = numberLabels(values);
  for (int l = 0; l < labelCount; ++l)
  {
    vtkSmartPointer<vtkTextActor> label = textActor(labels[static_cast<std::size_t>(l)], font);
    label->GetTextProperty()->SetVerticalJustificationToCentered();
    label->SetPosition(barRight + 0.5 * font, foot + (head - foot) * l / (labelCount - 1));
    widest = std::max(widest, textSize(label)[0]);
    legend.props.push_back(label);
  }
  legend.width = static_cast<int>(std::ceil(barRight + 0.5 * font + widest + font));
  return legend;
}

/// A swatch of each category's colour, its value and meaning beside it, from the top of a
/// picture `height` pixels high down.
Legend categoryLegend(const std::vector<Category>& categories, vtkLookupTable* table, int font, int height)
{
  Legend legend;
  std::vector<vtkSmartPointer<vtkTextActor>> labels, meanings;
  int labelWidth = 0, meaningWidth = 0;
  for (const Category& category : categories)
  {
    labels.push_back(textActor(category.label, font));
    meanings.push_back(textActor(category.meaning, font));
    labelWidth = std::max(labelWidth, category.label.empty() ? 0 : textSize(labels.back())[0]);
    meaningWidth = std::max(meaningWidth, category.meaning.empty() ? 0 : textSize(meanings.back())[0]);
  }
  // Columns: swatch, value (aligned right), meaning.
  const double swatchRight = 2.0 * font, labelRight = swatchRight + 0.5 * font + labelWidth;
  const double meaningLeft = labelRight + (labelWidth > 0 ? 0.6 * font : 0.0);
  double top = height - font;
  for (std::size_t c = 0; c < categories.size(); ++c)
  {
    const double value = categories[c].value;
    legend.props.push_back(colouredRectangle(font, top - font, swatchRight, top, table, value, value, 1));
    labels[c]->GetTextProperty()->SetJustificationToRight();
    labels[c]->SetPosition(labelRight, top);
    meanings[c]->SetPosition(meaningLeft, top);
    int rowHeight = font;
    for (vtkTextActor* text : { labels[c].Get(), meanings[c].Get() })
    {
      if (*text->GetInput())
      {
        text->GetTextProperty()->SetVerticalJustificationToTop();
        legend.props.push_back(text);
        rowHeight = std::max(rowHeight, textSize(text)[1]);
      }
    }
    top -= rowHeight + 0.6 * font;
  }
  legend.width = static_cast<int>(std::ceil(meaningLeft + meaningWidth + font));
  legend.height = static_cast<int>(std::ceil(height - top + 0.4 * font)); // the margins above and below
  return legend;
}

/// The category legend at the largest font, from `font` down, that fits a picture of this
/// size in at most legendShare of its width; at the smallest font if none does.
Legend fittedCategoryLegend(
  const std::vector<Category>& categories, vtkLookupTable* table, int font, int width, int height)
{
  Legend legend = categoryLegend(categories, table, font, height);
  while (font > smallestFont && (legend.width > legendShare * width || legend.height > height))
  {
    legend = categoryLegend(categories, table, --font, height);
  }
  return legend;
}

/// The array's name at the top left of the mesh's renderer, a picture `height` pixels high.
vtkSmartPointer<vtkTextActor> titleFor(const std::string& name, int font, int height)
{
  vtkSmartPointer<vtkTextActor> title = textActor(name, font);
  title->GetTextProperty()->BoldOn();
  title->GetTextProperty()->SetVerticalJustificationToTop();
  title->SetPosition(0.6 * font, height - 0.6 * font);
  return title;
}

/// Maps the 1-component array through a colour table on mapper (categories for flags and for
/// integers of a few values, the diverging map otherwise), and returns its legend.
Legend mapScalars(
  vtkDataArray* array, const std::string& name, vtkPolyDataMapper* mapper, int font, int width, int height)
{
  mapper->SetColorModeToMapScalars(); // 8-bit values too, which VTK would draw as grey levels
  const bool flags = isFlagsArray(array, name);
  const bool integers = array->GetDataType() != VTK_FLOAT && array->GetDataType() != VTK_DOUBLE;
  if (const auto counts = integers ? valueCounts(array, flags ? 256 : categoryColours.size()) : std::nullopt)
  {
    const std::vector<Category> categories = categoriesOf(*counts, flags);
    vtkSmartPointer<vtkLookupTable> table = categoryTable(categories);
    mapper->SetLookupTable(table);
    return fittedCategoryLegend(categories, table, font, width, height);
  }
  double range[2];
  vtkSmartPointer<vtkColorTransferFunction> map = divergingMap(array, range);
  mapper->SetLookupTable(map);
  mapper->SetScalarRange(range);
  return colourBarLegend(map, range, font, height);
}

/// The camera of the viewer, or framing the mesh; aspect is the renderer's width over its height.
void placeCamera(vtkRenderer* renderer, vtkPolyData* mesh, const std::optional<Viewer>& viewer, double aspect)
{
  vtkCamera* camera = renderer->GetActiveCamera();
  double centre[3];
  mesh->GetCenter(centre);
  if (viewer && viewer->position)
  {
    const glm::dvec3 eye = *viewer->position;
    const glm::dvec3 target = viewer->focalPoint.value_or(glm::dvec3(centre[0], centre[1], centre[2]));
    camera->SetPosition(eye.x, eye.y, eye.z);
    camera->SetFocalPoint(target.x, target.y, target.z);
    const glm::dvec3 up = viewUpFor(unitVector(target - eye));
    camera->SetViewUp(up.x, up.y, up.z);
    // The view angle frames the mesh's height; in a renderer narrower than high (beside a
    // legend), its width.
    camera->SetUseHorizontalViewAngle(aspect < 1);
    renderer->ResetCameraClippingRange();
    return;
  }
  // A viewer at infinity (or none): a parallel projection along its direction.
  const glm::dvec3 sight = viewer ? unitVector(viewer->viewDirection) : glm::dvec3(0, 0, -1);
  camera->ParallelProjectionOn();
  camera->SetFocalPoint(centre);
  camera->SetPosition(centre[0] - sight.x, centre[1] - sight.y, centre[2] - sight.z);
  const glm::dvec3 up = viewUpFor(sight);
  camera->SetViewUp(up.x, up.y, up.z);
  renderer->ResetCamera();
  // ResetCamera fits the mesh's height; a renderer narrower than high needs its width fitted
  // (VTK would know the aspect only once the renderer is in a window).
  if (aspect < 1)
  {
    camera->SetParallelScale(camera->GetParallelScale() / aspect);
  }
}
}

std::vector<std::string> renderToPng(
  vtkPolyData* mesh, const std::string& meshName, const RenderOptions& options, const std::string& pngFile)
{
  checkOutputFile(pngFile, { ".png" });
  requireDisplay();
  vtkDataArray* array = mesh->GetPointData()->GetArray(options.array.c_str());
  if (!array)
  {
    throw UserError(
      meshName + ": has no point array '" + options.array + "'; it has: " + arrayNames(mesh->GetPointData()));
  }
  const int components = array->GetNumberOfComponents();
  if (components != 1 && components != 3)
  {
    throw UserError(meshName + ": array '" + options.array + "' has " + std::to_string(components) +
      " components; render draws 1 (colour-mapped) or 3 (RGB)");
  }
  if (components == 1 && options.exposure != 1)
  {
    throw UserError("--exposure scales an array drawn as RGB colours; '" + options.array +
      "' has 1 component, drawn through a colour map that spans its values");
  }

  auto coloured = vtkSmartPointer<vtkPolyData>::New();
  coloured->CopyStructure(mesh);
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(coloured);
  vtkNew<vtkRenderer> renderer, legendRenderer;
  renderer->SetBackground(background[0], background[1], background[2]);
  legendRenderer->SetBackground(background[0], background[1], background[2]);
  std::vector<std::string> notes;
  double split = 1; // the share of the picture's width that shows the mesh, left of any legend
  if (components == 3)
  {
    ColourRange range;
    coloured->GetPointData()->SetScalars(directColours(array, options, range));
    mapper->SetColorModeToDirectScalars();
    notes = clippingNotes(options.array, array->GetNumberOfTuples(), range, options.srgb);
  }
  else
  {
    coloured->GetPointData()->SetScalars(array);
    const int font = fontSizeFor(options.width, options.height);
    const Legend legend = mapScalars(array, options.array, mapper, font, options.width, options.height);
    for (const vtkSmartPointer<vtkProp>& prop : legend.props)
    {
      legendRenderer->AddViewProp(prop);
    }
    split = 1.0 - std::min(largestLegendShare, static_cast<double>(legend.width) / options.width);
    renderer->SetViewport(0, 0, split, 1);
    legendRenderer->SetViewport(split, 0, 1, 1);
    renderer->AddViewProp(titleFor(options.array, font, options.height));
  }
  mapper->ScalarVisibilityOn();
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->GetProperty()->LightingOff(); // the colours are the shading
  renderer->AddActor(actor);
  placeCamera(renderer, mesh, options.viewer, split * options.width / options.height);

  vtkSmartPointer<vtkImageData> image = components == 3
    ? renderOffScreen(renderer, options.width, options.height)
    : renderOffScreen({ renderer, legendRenderer }, options.width, options.height);

  writeThroughTemporary(pngFile,
    [&](const std::string& temporary) -> std::string
    {
      vtkNew<VtkErrorCapture> errors;
      vtkNew<vtkPNGWriter> writer;
      errors->watch(writer);
      writer->SetInputData(image);
      writer->SetFileName(temporary.c_str());
      writer->Write();
      return errors->failed() ? errors->message() : "";
    });
  return notes;
}
}
