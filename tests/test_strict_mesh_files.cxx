// Text mesh files read strictly (issue 44). A corpus of mutants of small OBJ, ASCII PLY and
// ASCII STL seeds (a number replaced by junk, NaN, infinity, 1e999, a field dropped or added,
// an index 0, out of range or counting back past the first, a junk line, a line cut short):
// each is either refused at the line that was changed, or read by readMesh, the reading path
// of `shadelab shade`, exactly as a strict reference reader written here reads it. The
// reference shares no code with the checks: strtod and strtoll with an end-pointer check,
// istringstream words, and what VTK 9.1's readers make of a valid file (vtkOBJReader copies the
// points of each face when faces number texture coordinates or normals apart from their
// vertices; vtkSTLReader merges equal points and drops the triangles that merging collapses).
#include "MeshFileChecks.h"
#include "MeshFiles.h"
#include "TestPaths.h"

#include "vtkCellArray.h"
#include "vtkIdList.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <tuple>
#include <unistd.h>
#include <vector>

namespace
{
namespace fs = std::filesystem;
using namespace shadelab::app;

/// What a reader makes of a file: the line where it refuses it (-1: the whole file), or, when
/// refusedAt is 0, the mesh.
struct Reading
{
  long long refusedAt = 0;
  std::vector<std::array<double, 3>> points;
  std::vector<std::vector<vtkIdType>> polys, lines, verts;
};

Reading refusedAt(long long line)
{
  Reading reading;
  reading.refusedAt = line;
  return reading;
}

/// The lines of text, without their "\n"; a last line without one counts.
std::vector<std::string> linesOf(const std::string& text)
{
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
  {
    lines.push_back(line);
  }
  return lines;
}

std::vector<std::string> wordsOf(const std::string& line)
{
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string word; in >> word;)
  {
    words.push_back(word);
  }
  return words;
}

/// A number as strtod reads it, over the whole word, finite, not hexadecimal.
bool strictReal(const std::string& word, double& value)
{
  char* end = nullptr;
  value = std::strtod(word.c_str(), &end);
  return !word.empty() && word.find_first_of("xX") == std::string::npos && end == word.c_str() + word.size() &&
    std::isfinite(value);
}

/// strictReal within a float, where VTK's readers store coordinates.
bool strictFloat(const std::string& word, double& value)
{
  return strictReal(word, value) && std::fabs(value) <= FLT_MAX;
}

bool strictInteger(const std::string& word, long long& value)
{
  char* end = nullptr;
  errno = 0;
  value = std::strtoll(word.c_str(), &end, 10);
  return !word.empty() && end == word.c_str() + word.size() && errno == 0;
}

// ---- The reference OBJ reader ------------------------------------------------------------

struct ObjCorner
{
  long long index[3] = { 0, 0, 0 }; // as written
  bool has[3] = { true, false, false };
};

struct ObjFace
{
  long long line = 0;
  std::vector<ObjCorner> corners;
  std::vector<vtkIdType> vertices;
};

/// An OBJ corner word: "v", "v/vt", "v//vn" or "v/vt/vn", each index resolved against the
/// counts listed so far (1 for the first, -1 for the last). False if it is not one.
bool objCorner(const std::string& word, char kind, const long long listed[3], ObjCorner& corner, vtkIdType& vertex)
{
  std::vector<std::string> parts(1);
  for (const char c : word)
  {
    if (c == '/')
    {
      parts.emplace_back();
    }
    else
    {
      parts.back().push_back(c);
    }
  }
  if (parts.size() > 3 || (kind == 'l' && parts.size() == 3) || (kind == 'p' && parts.size() > 1) ||
    (parts.size() == 2 && parts[1].empty()) || (parts.size() == 3 && parts[2].empty()))
  {
    return false;
  }
  for (std::size_t slot = 0; slot < parts.size(); ++slot)
  {
    corner.has[slot] = !parts[slot].empty();
    if (slot == 0 && parts[0].empty())
    {
      return false;
    }
    long long& index = corner.index[slot];
    if (corner.has[slot] &&
      (!strictInteger(parts[slot], index) || index == 0 || index > listed[slot] || -index > listed[slot]))
    {
      return false;
    }
  }
  vertex = corner.index[0] > 0 ? corner.index[0] - 1 : listed[0] + corner.index[0];
  return true;
}

Reading referenceObj(const std::string& text)
{
  const std::vector<std::string> lines = linesOf(text);
  Reading reading;
  long long listed[3] = { 0, 0, 0 };
  std::vector<ObjFace> faces;
  long long firstPointOrLine = 0;
  for (std::size_t n = 0; n < lines.size(); ++n)
  {
    const long long number = static_cast<long long>(n) + 1;
    std::vector<std::string> words = wordsOf(lines[n]);
    if (words.empty() || words[0][0] == '#')
    {
      continue;
    }
    const std::string keyword = words[0];
    words.erase(words.begin());
    if (keyword == "v" || keyword == "vt" || keyword == "vn")
    {
      const std::size_t count = words.size();
      std::vector<double> values(count);
      for (std::size_t i = 0; i < count; ++i)
      {
        if (!strictFloat(words[i], values[i]))
        {
          return refusedAt(number);
        }
      }
      const int slot = keyword == "v" ? 0 : keyword == "vt" ? 1 : 2;
      const bool allowed = slot == 0 ? count == 3 || count == 4 || count == 6
        : slot == 1                  ? count == 2 || count == 3
                                     : count == 3;
      if (!allowed)
      {
        return refusedAt(number);
      }
      ++listed[slot];
      if (slot == 0)
      {
        reading.points.push_back({ values[0], values[1], values[2] });
      }
    }
    else if (keyword == "f" || keyword == "l" || keyword == "p")
    {
      ObjFace face;
      face.line = number;
      long long at = number;
      for (std::size_t w = 0; w < words.size(); ++w)
      {
        if (words[w] == "\\")
        {
          // A line that ends in "\" goes on with the next.
          if (w + 1 != words.size() || lines[n].back() != '\\' || n + 1 == lines.size())
          {
            return refusedAt(at);
          }
          ++n, ++at;
          const std::vector<std::string> more = wordsOf(lines[n]);
          words.insert(words.end(), more.begin(), more.end());
          continue;
        }
        ObjCorner corner;
        vtkIdType vertex = 0;
        if (!objCorner(words[w], keyword[0], listed, corner, vertex) ||
          (keyword == "f" && !face.corners.empty() &&
            (corner.has[1] != face.corners[0].has[1] || corner.has[2] != face.corners[0].has[2])))
        {
          return refusedAt(at);
        }
        face.corners.push_back(corner);
        face.vertices.push_back(vertex);
      }
      if (face.corners.size() < (keyword == "f" ? 3u : keyword == "l" ? 2u : 1u))
      {
        return refusedAt(at);
      }
      if (keyword == "f")
      {
        faces.push_back(face);
      }
      else
      {
        (keyword == "l" ? reading.lines : reading.verts).push_back(face.vertices);
        firstPointOrLine = firstPointOrLine ? firstPointOrLine : number;
      }
    }
    else if (keyword == "usemtl" && words.empty())
    {
      return refusedAt(number);
    }
    else if (keyword != "g" && keyword != "usemtl" && keyword != "mtllib" && keyword != "o" && keyword != "s")
    {
      return refusedAt(number);
    }
  }
  bool textured = false, normals = false, copies = false;
  for (const ObjFace& face : faces)
  {
    for (const ObjCorner& corner : face.corners)
    {
      textured = textured || corner.has[1];
      normals = normals || corner.has[2];
      copies = copies || (corner.has[1] && corner.index[1] != corner.index[0]) ||
        (corner.has[2] && corner.index[2] != corner.index[0]);
    }
  }
  if (!faces.empty() && firstPointOrLine)
  {
    return refusedAt(firstPointOrLine); // VTK 9.1 gives group ids to the faces alone: cells and ids disagree
  }
  if (!copies)
  {
    if ((textured && listed[1] != listed[0]) || (normals && listed[2] != listed[0]))
    {
      return refusedAt(-1);
    }
    for (const ObjFace& face : faces)
    {
      reading.polys.push_back(face.vertices);
    }
    return reading;
  }
  // Each face gets its own copies of its points; a face without normals is dropped.
  for (const ObjFace& face : faces)
  {
    if (normals && !face.corners[0].has[2])
    {
      return refusedAt(face.line);
    }
  }
  std::vector<std::array<double, 3>> copied;
  for (const ObjFace& face : faces)
  {
    reading.polys.emplace_back();
    for (const vtkIdType vertex : face.vertices)
    {
      reading.polys.back().push_back(static_cast<vtkIdType>(copied.size()));
      copied.push_back(reading.points[static_cast<std::size_t>(vertex)]);
    }
  }
  reading.points = copied;
  return reading;
}

// ---- The reference ASCII PLY reader ------------------------------------------------------

struct PlyScalar
{
  bool real;
  double least, most;
  bool isFloat;
};

PlyScalar plyScalar(const std::string& type)
{
  if (type == "float" || type == "float32" || type == "double" || type == "float64")
  {
    return { true, 0, 0, type == "float" || type == "float32" };
  }
  const int bits = type == "char" || type == "uchar" || type == "int8" || type == "uint8" ? 8
    : type == "short" || type == "ushort" || type == "int16" || type == "uint16"          ? 16
                                                                                          : 32;
  const bool isSigned = type[0] != 'u';
  return { false, isSigned ? -std::ldexp(1.0, bits - 1) : 0.0,
    isSigned ? std::ldexp(1.0, bits - 1) - 1 : std::ldexp(1.0, bits) - 1, false };
}

/// One value of type, as the word writes it.
bool plyValue(const std::string& word, const PlyScalar& type, bool coordinate, double& value)
{
  if (type.real)
  {
    return strictReal(word, value) && (!(type.isFloat || coordinate) || std::fabs(value) <= FLT_MAX);
  }
  long long integer = 0;
  if (!strictInteger(word, integer))
  {
    return false;
  }
  value = static_cast<double>(integer);
  return value >= type.least && value <= type.most;
}

struct PlyRefProperty
{
  std::string name;
  PlyScalar type;
  bool list = false;
  PlyScalar countType{};
};

struct PlyRefElement
{
  std::string name;
  long long count;
  std::vector<PlyRefProperty> properties;
};

Reading referencePly(const std::string& text)
{
  const std::vector<std::string> lines = linesOf(text);
  std::vector<PlyRefElement> elements;
  std::size_t n = 0;
  for (; n < lines.size() && wordsOf(lines[n]) != std::vector<std::string>{ "end_header" }; ++n)
  {
    const std::vector<std::string> words = wordsOf(lines[n]);
    if (words[0] == "element")
    {
      elements.push_back({ words[1], std::stoll(words[2]), {} });
    }
    else if (words[0] == "property")
    {
      const bool list = words[1] == "list";
      PlyRefProperty property{ words.back(), plyScalar(words[list ? 3 : 1]), list, {} };
      if (list)
      {
        property.countType = plyScalar(words[2]);
      }
      elements.back().properties.push_back(property);
    }
  }
  long long vertices = 0;
  for (const PlyRefElement& element : elements)
  {
    vertices = element.name == "vertex" ? element.count : vertices;
  }
  Reading reading;
  for (const PlyRefElement& element : elements)
  {
    for (long long i = 0; i < element.count; ++i)
    {
      ++n;
      const long long number = static_cast<long long>(n) + 1;
      if (n >= lines.size() || (n + 1 == lines.size() && text.back() != '\n'))
      {
        return refusedAt(number);
      }
      const std::vector<std::string> words = wordsOf(lines[n]);
      std::size_t w = 0;
      std::array<double, 3> point{};
      for (const PlyRefProperty& property : element.properties)
      {
        double value = 0;
        const bool coordinate =
          element.name == "vertex" && property.name.size() == 1 && std::strchr("xyz", property.name[0]);
        if (w >= words.size() ||
          !plyValue(words[w++], property.list ? property.countType : property.type, coordinate, value))
        {
          return refusedAt(number);
        }
        if (!property.list)
        {
          if (coordinate)
          {
            point[static_cast<std::size_t>(property.name[0] - 'x')] = value;
          }
          continue;
        }
        std::vector<vtkIdType> ids;
        for (long long k = 0, items = static_cast<long long>(value); k < items; ++k)
        {
          const bool indices = element.name == "face" && property.name == "vertex_indices";
          if (w >= words.size() || !plyValue(words[w++], property.type, false, value) ||
            (indices && !(value == std::floor(value) && value >= 0 && value < static_cast<double>(vertices))))
          {
            return refusedAt(number);
          }
          ids.push_back(static_cast<vtkIdType>(value));
        }
        if (element.name == "face" && property.name == "vertex_indices")
        {
          reading.polys.push_back(ids);
        }
      }
      if (w != words.size())
      {
        return refusedAt(number);
      }
      if (element.name == "vertex")
      {
        reading.points.push_back(point);
      }
    }
  }
  for (++n; n < lines.size(); ++n)
  {
    if (!wordsOf(lines[n]).empty())
    {
      return refusedAt(static_cast<long long>(n) + 1);
    }
  }
  return reading;
}

// ---- The reference ASCII STL reader ------------------------------------------------------

std::string lowered(std::string word)
{
  for (char& c : word)
  {
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return word;
}

/// The three numbers after the keyword words[0..first), exactly.
bool stlNumbers(const std::vector<std::string>& words, std::size_t first, std::array<double, 3>& numbers)
{
  if (words.size() != first + 3)
  {
    return false;
  }
  for (std::size_t i = 0; i < 3; ++i)
  {
    if (!strictFloat(words[first + i], numbers[i]))
    {
      return false;
    }
  }
  return true;
}

Reading referenceStl(const std::string& text)
{
  const std::vector<std::string> lines = linesOf(text);
  // The statements in their order; "facet" stands for "facet normal".
  const std::vector<std::string> facet = { "facet", "outer", "vertex", "vertex", "vertex", "endloop", "endfacet" };
  std::vector<std::array<double, 3>> corners;
  std::size_t inFacet = 0; // the next statement of a facet
  int solids = 0;
  bool inSolid = false;
  for (std::size_t n = 0; n < lines.size(); ++n)
  {
    const long long number = static_cast<long long>(n) + 1;
    const std::vector<std::string> words = wordsOf(lines[n]);
    if (words.empty())
    {
      continue;
    }
    const std::string keyword = lowered(words[0]);
    std::array<double, 3> numbers{};
    if (!inSolid)
    {
      if (keyword != "solid")
      {
        return refusedAt(number);
      }
      inSolid = true, ++solids;
    }
    else if (inFacet == 0 && keyword == "color")
    {
    }
    else if (inFacet == 0 && keyword == "endsolid")
    {
      inSolid = false;
    }
    else if (keyword != facet[inFacet] ||
      (keyword == "facet" && (words.size() < 2 || lowered(words[1]) != "normal" || !stlNumbers(words, 2, numbers))) ||
      (keyword == "outer" && (words.size() != 2 || lowered(words[1]) != "loop")) ||
      (keyword == "vertex" && !stlNumbers(words, 1, numbers)) ||
      ((keyword == "endloop" || keyword == "endfacet") && words.size() != 1))
    {
      return refusedAt(number);
    }
    else
    {
      if (keyword == "vertex")
      {
        corners.push_back(
          { static_cast<float>(numbers[0]), static_cast<float>(numbers[1]), static_cast<float>(numbers[2]) });
      }
      inFacet = (inFacet + 1) % facet.size();
    }
  }
  if (inSolid || solids == 0)
  {
    return refusedAt(static_cast<long long>(lines.size()) + 1);
  }
  // Equal points merge, in the order first met; a triangle with two of its corners merged goes.
  Reading reading;
  for (std::size_t t = 0; t < corners.size(); t += 3)
  {
    std::vector<vtkIdType> ids;
    for (std::size_t c = t; c < t + 3; ++c)
    {
      auto same = std::find(reading.points.begin(), reading.points.end(), corners[c]);
      ids.push_back(static_cast<vtkIdType>(same - reading.points.begin()));
      if (same == reading.points.end())
      {
        reading.points.push_back(corners[c]);
      }
    }
    if (ids[0] != ids[1] && ids[1] != ids[2] && ids[0] != ids[2])
    {
      reading.polys.push_back(ids);
    }
  }
  return reading;
}

// ---- The production path -----------------------------------------------------------------

std::vector<std::vector<vtkIdType>> cellsOf(vtkCellArray* cells)
{
  std::vector<std::vector<vtkIdType>> list;
  vtkNew<vtkIdList> ids;
  for (cells->InitTraversal(); cells->GetNextCell(ids);)
  {
    list.emplace_back(ids->begin(), ids->end());
  }
  return list;
}

/// readMesh's reading of text, written to a file of the extension: the mesh, or the line of
/// its refusal with the message.
Reading productionReading(const std::string& text, const std::string& extension, std::string& message)
{
  const fs::path file = fs::temp_directory_path() / ("shadelab-strict-" + std::to_string(::getpid()) + extension);
  std::ofstream(file, std::ios::binary) << text;
  Reading reading;
  message.clear();
  try
  {
    vtkSmartPointer<vtkPolyData> mesh = readMesh(file.string());
    for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
    {
      double p[3];
      mesh->GetPoint(i, p);
      reading.points.push_back({ p[0], p[1], p[2] });
    }
    reading.polys = cellsOf(mesh->GetPolys());
    reading.lines = cellsOf(mesh->GetLines());
    reading.verts = cellsOf(mesh->GetVerts());
  }
  catch (const UserError& error)
  {
    message = error.what();
    const std::string prefix = file.string() + ": line ";
    reading.refusedAt = message.rfind(prefix, 0) == 0 ? std::atoll(message.c_str() + prefix.size()) : -1;
  }
  fs::remove(file);
  return reading;
}

/// Whether VTK's coordinate is the reference's value as a float. The readers round a decimal
/// to float in two ways: vtkPLYReader and vtkSTLReader through double (atof, strtod, then a
/// cast), vtkOBJReader directly (istream's float extraction, which calls strtof). The two
/// differ only where the double lands exactly halfway between two floats, and then by one
/// unit in the last place: the tolerance is that one float ulp, nothing more.
bool sameCoordinate(double vtk, double reference)
{
  const float expected = static_cast<float>(reference);
  return vtk == expected || vtk == std::nextafter(expected, FLT_MAX) || vtk == std::nextafter(expected, -FLT_MAX);
}

/// The production reading against the reference's: both refuse at the same line, or both read
/// the same points (within sameCoordinate) and the same cells.
void expectSameReading(const Reading& production, const Reading& reference, const std::string& message)
{
  ASSERT_EQ(production.refusedAt, reference.refusedAt) << message;
  if (production.refusedAt != 0)
  {
    return;
  }
  ASSERT_EQ(production.points.size(), reference.points.size());
  for (std::size_t i = 0; i < production.points.size(); ++i)
  {
    for (std::size_t k = 0; k < 3; ++k)
    {
      EXPECT_TRUE(sameCoordinate(production.points[i][k], reference.points[i][k]))
        << "point " << i << "[" << k << "]: " << production.points[i][k] << " read, " << reference.points[i][k]
        << " in the file";
    }
  }
  EXPECT_EQ(production.polys, reference.polys);
  EXPECT_EQ(production.lines, reference.lines);
  EXPECT_EQ(production.verts, reference.verts);
}

// ---- The mutants -------------------------------------------------------------------------

struct Mutant
{
  std::string text;
  long long line; // the line changed
  std::string change;
};

/// What replaces a word: junk, non-finite numbers, numbers beyond a float, numbers with junk
/// after them, and numbers and indices a reader may or may not take.
const char* const replacements[] = { "abc", "nan", "NaN", "inf", "-inf", "1e999", "1e39", "1.0abc", "0x10", "1,5", "0",
  "-0", "-1", "99", "-99", "2.5", "+7", "1e-40", "3.", "" };

std::string joined(const std::vector<std::string>& lines, bool endsInNewline)
{
  std::string text;
  for (std::size_t i = 0; i < lines.size(); ++i)
  {
    text += lines[i] + (i + 1 < lines.size() || endsInNewline ? "\n" : "");
  }
  return text;
}

/// Every mutant of the seed's lines from firstLine on (1 for the first): a word dropped, a
/// word added, the line cut in half, a junk line put before it; and on a line of data (one
/// whose first word is one of dataKeywords, or any line if there are none), every other
/// replacement in one word (not the first, or from firstWord on). Each mutant read costs a
/// reading process, so the replacements alternate between lines, and lines of names and
/// comments get none.
std::vector<Mutant> mutantsOf(
  const std::string& seed, std::size_t firstLine, std::size_t firstWord, const std::vector<std::string>& dataKeywords)
{
  const std::vector<std::string> lines = linesOf(seed);
  std::vector<Mutant> mutants;
  bool continued = false; // the line goes on from the one before
  for (std::size_t n = firstLine - 1; n < lines.size(); ++n)
  {
    const long long number = static_cast<long long>(n) + 1;
    const std::vector<std::string> words = wordsOf(lines[n]);
    // A line that continues on the next ("") changes that line too: only its words change.
    const bool continues = !words.empty() && words.back() == "\\";
    const bool data = dataKeywords.empty() || continued ||
      (!words.empty() && std::find(dataKeywords.begin(), dataKeywords.end(), words[0]) != dataKeywords.end());
    continued = continues;
    auto with = [&](const std::string& line, const std::string& change)
    {
      std::vector<std::string> changed = lines;
      changed[n] = line;
      mutants.push_back({ joined(changed, true), number, change + " in line " + std::to_string(number) });
    };
    auto wordsWith = [&](std::size_t at, const std::string& word)
    {
      std::string line;
      for (std::size_t w = 0; w < words.size(); ++w)
      {
        line += (w ? " " : "") + (w == at ? word : words[w]);
      }
      return line;
    };
    for (std::size_t r = n % 2; data && r < std::size(replacements) && words.size() > firstWord; r += 2)
    {
      const std::size_t at = firstWord + (r / 2 + n) % (words.size() - firstWord);
      if (words[at] != "\\" && words[at] != replacements[r])
      {
        with(wordsWith(at, replacements[r]), "'" + words[at] + "' -> '" + replacements[r] + "'");
      }
    }
    if (!continues && words.size() >= 2)
    {
      with(lines[n].substr(0, lines[n].rfind(words.back())), "the last word dropped");
    }
    with(lines[n] + " 7", "a word added");
    if (!continues && lines[n].size() >= 2)
    {
      with(lines[n].substr(0, lines[n].size() / 2), "cut in half");
    }
    std::vector<std::string> inserted = lines;
    inserted.insert(inserted.begin() + static_cast<std::ptrdiff_t>(n), "hello world");
    mutants.push_back({ joined(inserted, true), number, "a junk line before line " + std::to_string(number) });
  }
  return mutants;
}

/// Checks every mutant of the seed: refused at the changed line, or read as the reference
/// reads it. Returns how many were read, so that the corpus is seen to test both outcomes.
int checkMutants(const std::string& seed, const std::string& extension, Reading (*reference)(const std::string&),
  std::size_t firstLine, std::size_t firstWord, const std::vector<std::string>& dataKeywords)
{
  int read = 0;
  for (const Mutant& mutant : mutantsOf(seed, firstLine, firstWord, dataKeywords))
  {
    SCOPED_TRACE(mutant.change + ":\n" + mutant.text);
    std::string message;
    const Reading production = productionReading(mutant.text, extension, message);
    const Reading expected = reference(mutant.text);
    EXPECT_TRUE(production.refusedAt == 0 || production.refusedAt == mutant.line) << message;
    expectSameReading(production, expected, message);
    read += production.refusedAt == 0;
  }
  return read;
}

// ---- The seeds ---------------------------------------------------------------------------

/// Faces that number texture coordinates and normals as their vertices (vtkOBJReader reads the
/// lists as they are), negative indices, groups, materials and statements it skips.
const std::string objMatchingSeed = "# two triangles and a quad\n"
                                    "mtllib seed.mtl\n"
                                    "o seed\n"
                                    "v 0.5 -1.25 2\n"
                                    "v 1.5e0 0.25 -2.5\n"
                                    "v -0.75 1.0 0.125\n"
                                    "v 2 2 2\n"
                                    "vt 0.1 0.2\n"
                                    "vt 0.3 0.4 0\n"
                                    "vt 0.5 0.6\n"
                                    "vt 0.7 0.8\n"
                                    "vn 0 0 1\n"
                                    "vn 0 1 0\n"
                                    "vn 1 0 0\n"
                                    "vn 0.6 0.8 0\n"
                                    "g front\n"
                                    "usemtl red\n"
                                    "s 1\n"
                                    "f 1/1/1 2/2/2 3/3/3\n"
                                    "f -4/-4/-4 -3/-3/-3 -1/-1/-1\n"
                                    "g back\n"
                                    "f 1//1 3//3 4//4 2//2\n";

/// Plain faces, a w and vertex colours, a face continued on the next line.
const std::string objPlainSeed = "v 1 2 3 1\n"
                                 "v 4 5 6 0.5 0.25 1\n"
                                 "v 7 8 10\n"
                                 "v -1 -2 -3\n"
                                 "\n"
                                 "f 1 2 3\n"
                                 "f 1 3 \\\n"
                                 "4 2\n";

/// Lines and points, without faces (with faces, vtkOBJReader 9.1 makes a mesh that does not
/// hold together).
const std::string objLinesSeed = "v 0 0 0\n"
                                 "v 1 0 0 1\n"
                                 "v 0 1 0\n"
                                 "vt 0.5 0.5\n"
                                 "l 1 2 3\n"
                                 "l 1/1 -1/1\n"
                                 "p 3 \\\n"
                                 "2\n"
                                 "p -2\n";

/// Faces that number texture coordinates apart from their vertices (vtkOBJReader copies the
/// points of each face), and one face without them.
const std::string objCopiedSeed = "v 0 0 0\n"
                                  "v 1 0 0\n"
                                  "v 0 1 0\n"
                                  "v 0 0 1\n"
                                  "vt 0 0\n"
                                  "vt 1 0\n"
                                  "vt 0 1\n"
                                  "f 1/2 2/3 3/1\n"
                                  "f 1/1 3/2 4/3\n"
                                  "f 2 3 4\n";

const std::string plySeed = "ply\n"
                            "format ascii 1.0\n"
                            "comment a seed\n"
                            "element vertex 5\n"
                            "property float x\n"
                            "property float y\n"
                            "property float z\n"
                            "property uchar red\n"
                            "element face 3\n"
                            "property list uchar int vertex_indices\n"
                            "end_header\n"
                            "0.5 -1.25 2 255\n"
                            "1.5e0 0.25 -2.5 0\n"
                            "-0.75 1.0 0.125 17\n"
                            "2 2 2 1\n"
                            "0 0 -3 2\n"
                            "3 0 1 2\n"
                            "4 0 2 3 4\n"
                            "3 4 3 1\n";

/// Double coordinates, a short count, an element vtkPLYReader does not read.
const std::string plyDoubleSeed = "ply\n"
                                  "format ascii 1.0\n"
                                  "element vertex 4\n"
                                  "property double x\n"
                                  "property double y\n"
                                  "property double z\n"
                                  "element face 2\n"
                                  "property list short uint vertex_indices\n"
                                  "element edge 1\n"
                                  "property int vertex1\n"
                                  "property int vertex2\n"
                                  "end_header\n"
                                  "0.1 0.2 0.3\n"
                                  "1 0 0\n"
                                  "0 1 0\n"
                                  "0 0 1\n"
                                  "3 0 1 2\n"
                                  "3 0 2 3\n"
                                  "0 1\n";

/// Two solids, keywords in any case, a colour line, and a shared corner.
const std::string stlSeed = "solid seed\n"
                            "color 1 0 0 1\n"
                            "facet normal 0 0 1\n"
                            "  outer loop\n"
                            "    vertex 0 0 0\n"
                            "    vertex 1 0 0\n"
                            "    vertex 0 1 0\n"
                            "  endloop\n"
                            "endfacet\n"
                            "FACET NORMAL 0 0 -1\n"
                            "  OUTER LOOP\n"
                            "    VERTEX 0 0 0\n"
                            "    VERTEX 0 1 0\n"
                            "    VERTEX 0.5 0.25 -1.5e0\n"
                            "  ENDLOOP\n"
                            "ENDFACET\n"
                            "endsolid seed\n"
                            "solid second\n"
                            "facet normal 1 0 0\n"
                            "outer loop\n"
                            "vertex 1 0 0\n"
                            "vertex 0 1 0\n"
                            "vertex 0 0 1\n"
                            "endloop\n"
                            "endfacet\n"
                            "endsolid\n";

TEST(StrictMeshFiles, TheSeedsReadAsTheReferenceReadsThem)
{
  for (const auto& [seed, extension, reference] : { std::make_tuple(objMatchingSeed, ".obj", &referenceObj),
         std::make_tuple(objPlainSeed, ".obj", &referenceObj), std::make_tuple(objCopiedSeed, ".obj", &referenceObj),
         std::make_tuple(objLinesSeed, ".obj", &referenceObj), std::make_tuple(plySeed, ".ply", &referencePly),
         std::make_tuple(plyDoubleSeed, ".ply", &referencePly), std::make_tuple(stlSeed, ".stl", &referenceStl) })
  {
    SCOPED_TRACE(seed);
    std::string message;
    const Reading production = productionReading(seed, extension, message);
    const Reading expected = reference(seed);
    ASSERT_EQ(expected.refusedAt, 0);
    EXPECT_FALSE(expected.polys.empty() && expected.lines.empty());
    expectSameReading(production, expected, message);
  }
  // The conventions the reference follows, seen in VTK's own reading.
  EXPECT_EQ(referenceObj(objCopiedSeed).points.size(), 9u);  // a copy per corner
  EXPECT_EQ(referenceStl(stlSeed).points.size(), 5u);        // 9 corners, 4 of them repeated
  EXPECT_EQ(referenceObj(objPlainSeed).polys[1].size(), 4u); // continued on the next line
}

TEST(StrictMeshFiles, ObjMutantsAreRefusedAtTheirLineOrReadExactly)
{
  int read = 0;
  for (const std::string* seed : { &objMatchingSeed, &objPlainSeed, &objCopiedSeed, &objLinesSeed })
  {
    read += checkMutants(*seed, ".obj", &referenceObj, 1, 1, { "v", "vt", "vn", "f", "l", "p" });
  }
  EXPECT_GT(read, 30); // both outcomes are tested
}

TEST(StrictMeshFiles, PlyMutantsAreRefusedAtTheirLineOrReadExactly)
{
  int read = 0;
  read += checkMutants(plySeed, ".ply", &referencePly, 12, 0, {});
  read += checkMutants(plyDoubleSeed, ".ply", &referencePly, 13, 0, {});
  EXPECT_GT(read, 10);
}

TEST(StrictMeshFiles, StlMutantsAreRefusedAtTheirLineOrReadExactly)
{
  EXPECT_GT(checkMutants(stlSeed, ".stl", &referenceStl, 1, 1, { "facet", "FACET", "vertex", "VERTEX" }), 10);
}

/// readMesh's message for text in a file of the extension, after the file's name.
std::string refusal(const std::string& text, const std::string& extension)
{
  std::string message;
  productionReading(text, extension, message);
  const std::string name =
    (fs::temp_directory_path() / ("shadelab-strict-" + std::to_string(::getpid()) + extension)).string();
  EXPECT_EQ(message.rfind(name + ": ", 0), 0u) << message;
  return message.substr(std::min(message.size(), name.size() + 2));
}

TEST(StrictMeshFiles, MessagesSayWhereAndWhat)
{
  const std::string triangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  const std::string ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                          "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                          "0 0 0\n";
  const std::string facet = "solid s\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n";
  struct Case
  {
    std::string text;
    const char* extension;
    std::string message; // after "FILE: "
  };
  const Case cases[] = {
    { triangle + "f 0 1 2\n", ".obj",
      "line 4: face index 0 refers to no vertex: OBJ indices start at 1 (and negative ones count back from the last "
      "listed, -1 for the last)" },
    { "v 0 0 0\nv 1.0 abc 2.0\n", ".obj", "line 2: 'abc' is not a number (the vertex's y coordinate)" },
    { "v nan 1 2\n", ".obj", "line 1: 'nan' is not a finite number (the vertex's x coordinate)" },
    { "v 1 2\n", ".obj",
      "line 1: a vertex is 'v x y z', optionally followed by w or by r g b, and this line has 2 values" },
    { "v 1 2 1e39\n", ".obj",
      "line 1: '1e39' is beyond +-3.4e+38, the range of the float in which VTK's reader stores it (the vertex's z "
      "coordinate)" },
    { triangle + "this is junk\n", ".obj",
      "line 4: 'this' is not an OBJ statement: delete the line, or make it a comment with '#'" },
    { triangle + "f 1 2 -4\n", ".obj",
      "line 4: face index -4 counts back past the first vertex: the file lists 3 before that line" },
    { triangle + "f 1 2 3x\n", ".obj", "line 4: '3x' is not an OBJ face corner" },
    { triangle + "vt 0 0\nf 1/1 2 3\n", ".obj",
      "line 5: the corners '1/1' and '2' differ in form: VTK's reader needs every corner of a face to give a texture "
      "coordinate, or none; likewise a normal" },
    { triangle + "f 1 2 3\nl 1 2\n", ".obj",
      "line 5: VTK 9.1's reader cannot read this 'l' statement in a file with faces (it numbers the faces' groups "
      "alone, and the mesh it makes does not hold together): keep points and lines in a file of their own" },
    { ply + "1 0 NaN\n0 1 0\n3 0 1 2\n", ".ply", "line 11: 'NaN' is not a finite number (the 'vertex' property 'z')" },
    { ply + "1 0 0\n0 1 0\n3 0 1 2.7\n", ".ply",
      "line 13: '2.7' is not an integer (a value of the 'face' list 'vertex_indices', of type int)" },
    { ply + "1 0 0\n0 1 0\n300 0 1 2\n", ".ply",
      "line 13: '300' is beyond 0 to 255, the range of type uchar (the count of the 'face' list 'vertex_indices', of "
      "type uchar)" },
    { ply + "1 0\n0 1 0\n3 0 1 2\n", ".ply",
      "line 11: this 'vertex' line ends after 2 values, before its 'z' is complete" },
    { ply + "1 0 0\n0 1 0\n3 0 1 3\n", ".ply",
      "line 13: vertex index 3 refers to no vertex: the header declares 3, numbered from 0" },
    { ply + "1 0 0\n0 1 0\n3 0 1 2", ".ply",
      "line 13: the file's last line has no line break, and VTK's PLY reader stops before it: end the file with one" },
    { ply + "1 0 0\n0 1 0\n3 0 1 2\n7 7 7\n", ".ply",
      "line 14: the header declares 3 'vertex' and 1 'face' lines, and this one comes after them all: a count is "
      "wrong" },
    { facet + "vertex 1 nan 0\n", ".stl", "line 5: 'nan' is not a finite number (the vertex's y)" },
    { facet + "vertex 1 0 0 junk\n", ".stl",
      "line 5: a vertex is 'vertex x y z', and this line has 4 values after 'vertex'" },
    { facet + "vertex 1 0 0\nvertex 0 1 0\nendfacet\nendsolid s\n", ".stl",
      "line 7: 'endloop' should be here, not 'endfacet'" },
    { facet + "vertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n", ".stl",
      "line 9: the file ends where 'facet normal' or 'endsolid' should be" },
  };
  for (const Case& c : cases)
  {
    EXPECT_EQ(refusal(c.text, c.extension), c.message) << c.text;
  }
}

TEST(StrictMeshFiles, WhatTheReaderSkipsIsCounted)
{
  EXPECT_EQ(
    objFileCheck(objMatchingSeed).ignored, "1 'o', 1 's' statements (object names and smoothing groups are not read)");
  EXPECT_EQ(objFileCheck(objPlainSeed).ignored, "the r g b colours of 1 vertex (VTK 9.1 reads no vertex colours)");
  EXPECT_EQ(objFileCheck("v 0 0 0\nvp 0.5\ncstype bspline\ncurv 0 1 1\ns off\nsurf 0 1 0 1 1\ns 2\n").ignored,
    "1 'vp', 1 'cstype', 1 'curv', 2 's', 1 'surf' statements (free-form curves and surfaces and smoothing groups "
    "are not read)");
  EXPECT_EQ(objFileCheck(objCopiedSeed).ignored, "");
  EXPECT_EQ(stlFileCheck(stlSeed, true).ignored, "1 'color' statement (colours are not read)");

  // The same through readMesh, whose report `shadelab shade` prints as "ignored:".
  const fs::path file = fs::temp_directory_path() / ("shadelab-strict-ignored-" + std::to_string(::getpid()) + ".obj");
  std::ofstream(file) << objMatchingSeed;
  std::string ignored;
  EXPECT_EQ(readMesh(file.string(), &ignored)->GetNumberOfPolys(), 3);
  EXPECT_EQ(ignored, "1 'o', 1 's' statements (object names and smoothing groups are not read)");
  fs::remove(file);
}

/// A binary PLY of a triangle, little-endian, with the given second vertex and last index.
std::string binaryPly(float y, int lastIndex)
{
  std::string text = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                     "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const float coordinates[9] = { 0, 0, 0, 1, y, 0, 0, 1, 0 };
  text.append(reinterpret_cast<const char*>(coordinates), sizeof coordinates);
  const int indices[3] = { 0, 1, lastIndex };
  text.push_back(3);
  text.append(reinterpret_cast<const char*>(indices), sizeof indices);
  return text;
}

/// A binary STL of one triangle with the given coordinate.
std::string binaryStl(float coordinate)
{
  std::string text(80, ' ');
  const std::uint32_t count = 1;
  text.append(reinterpret_cast<const char*>(&count), 4);
  const float values[12] = { 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, coordinate, 0 };
  text.append(reinterpret_cast<const char*>(values), sizeof values);
  return text + std::string(2, '\0');
}

TEST(StrictMeshFiles, BinaryFilesGetTheirCheapExactChecks)
{
  EXPECT_EQ(plyFileProblem(binaryPly(0, 2)), "");
  EXPECT_EQ(plyFileProblem(binaryPly(NAN, 2)),
    "'vertex' element 1 of 3 (counting from 0): 'nan' is not a finite number (the 'vertex' property 'y')");
  EXPECT_EQ(plyFileProblem(binaryPly(0, 3)),
    "'face' element 0 of 1 (counting from 0): vertex index 3 refers to no vertex: the header declares 3, numbered "
    "from 0");
  const std::string whole = binaryPly(0, 2);
  EXPECT_EQ(plyFileProblem(whole.substr(0, whole.size() - 2)),
    "'face' element 0 of 1 (counting from 0): the file ends in it: it is cut short or the header's counts are wrong");

  EXPECT_EQ(stlFileCheck(binaryStl(1), false).problem, "");
  EXPECT_EQ(stlFileCheck(binaryStl(INFINITY), false).problem,
    "triangle 1 of 1 has a vertex coordinate that is not a finite number (infinite)");
  EXPECT_EQ(stlFileCheck(binaryStl(1) + "x", false).problem,
    "a binary STL file has 50 bytes a triangle after its 84-byte header, and this one has 51: it is cut short, or "
    "not an STL file");
  // readMesh takes the file as vtkSTLReader does: binary bytes after a header that starts
  // with "solid" are still binary.
  std::string solidHeader = binaryStl(NAN);
  solidHeader.replace(0, 6, "solid ");
  EXPECT_EQ(refusal(solidHeader, ".stl"), "triangle 1 of 1 has a vertex coordinate that is not a finite number (NaN)");
}

TEST(StrictMeshFiles, EveryBundledMeshPasses)
{
  for (const char* name : { "bunny_zipper.ply", "head_scan.ply", "xyzrgb_dragon_50k.ply", "spot.obj", "teapot.obj" })
  {
    const std::string file = shadelab::testing::sourcePath("data/meshes/") + name;
    const MeshFileCheck check = checkMeshFile(file, fs::path(file).extension().string(), fs::file_size(file));
    EXPECT_EQ(check.problem, "") << name;
    EXPECT_EQ(check.ignored, "") << name;
  }
}
}
