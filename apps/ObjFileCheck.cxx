// The strict reading of an OBJ file, against what VTK 9.1's vtkOBJReader makes of it: a
// coordinate it cannot read becomes 0 or the previous line's value, a face corner "3x" vertex
// 3, index 0 a point id of -1, and a line it does not know is skipped, all without a word.
#include "MeshFileChecks.h"
#include "MeshText.h"

#include <algorithm>
#include <cstring>

namespace shadelab::app
{
namespace
{
/// The statements of the OBJ format (Wavefront's "Object Files (.obj)", appendix B1 of the
/// Advanced Visualizer manual) that vtkOBJReader skips, with what they hold. It reads v, vt,
/// vn, f, l and p, g (as GroupIds), usemtl (as MaterialIds) and mtllib (the libraries' names).
struct SkippedStatement
{
  const char* keyword;
  const char* what;
};
const SkippedStatement skippedStatements[] = { { "o", "object names" }, { "s", "smoothing groups" },
  { "mg", "merging groups" }, { "vp", "free-form curves and surfaces" }, { "cstype", "free-form curves and surfaces" },
  { "deg", "free-form curves and surfaces" }, { "bmat", "free-form curves and surfaces" },
  { "step", "free-form curves and surfaces" }, { "curv", "free-form curves and surfaces" },
  { "curv2", "free-form curves and surfaces" }, { "surf", "free-form curves and surfaces" },
  { "parm", "free-form curves and surfaces" }, { "trim", "free-form curves and surfaces" },
  { "hole", "free-form curves and surfaces" }, { "scrv", "free-form curves and surfaces" },
  { "sp", "free-form curves and surfaces" }, { "end", "free-form curves and surfaces" },
  { "con", "free-form curves and surfaces" }, { "maplib", "texture maps" }, { "usemap", "texture maps" },
  { "bevel", "render attributes" }, { "c_interp", "render attributes" }, { "d_interp", "render attributes" },
  { "lod", "render attributes" }, { "shadow_obj", "render attributes" }, { "trace_obj", "render attributes" },
  { "ctech", "render attributes" }, { "stech", "render attributes" }, { "call", "included files" },
  { "csh", "shell commands" } };

const char* skippedWhat(std::string_view keyword)
{
  for (const SkippedStatement& statement : skippedStatements)
  {
    if (keyword == statement.keyword)
    {
      return statement.what;
    }
  }
  return nullptr;
}

/// vtkOBJReader reads a line into a buffer of 256 KiB, and refuses a longer one.
constexpr std::size_t longestLine = 1024 * 256 - 2;
/// It reads a material name into 100 chars, with its terminating zero.
constexpr std::size_t longestMaterialName = 99;

enum Slot
{
  VertexSlot,
  TextureSlot,
  NormalSlot,
};
const char* const slotNames[3] = { "vertex", "texture coordinate", "normal" };

/// One corner of a face, line or point as written: "v", "v/vt", "v//vn" or "v/vt/vn".
struct Corner
{
  std::string_view fields[3];
  bool has[3] = { true, false, false };
  long long index[3] = { 0, 0, 0 }; // as written: vtkOBJReader compares them so
};

/// Splits word into a corner's fields at its slashes.
void splitCorner(std::string_view word, Corner& corner)
{
  const std::size_t first = word.find('/');
  corner.fields[VertexSlot] = word.substr(0, first);
  if (first == std::string_view::npos)
  {
    return;
  }
  const std::string_view rest = word.substr(first + 1);
  const std::size_t second = rest.find('/');
  corner.fields[TextureSlot] = rest.substr(0, second);
  corner.has[TextureSlot] = second != 0; // "v//vn" has none
  if (second != std::string_view::npos)
  {
    corner.fields[NormalSlot] = rest.substr(second + 1);
    corner.has[NormalSlot] = true;
  }
}

/// The checker's pass over one file.
class ObjCheck
{
public:
  MeshFileCheck run(std::string_view text);

private:
  std::string statementProblem(std::string_view keyword, std::string_view rest);
  std::string numbersProblem(std::string_view keyword, std::string_view rest);
  std::string elementProblem(std::string_view keyword, std::string_view rest);
  std::string cornerProblem(char kind, std::string_view word, Corner& corner) const;
  std::string indexProblem(char kind, Slot slot, std::string_view field, long long index, NumberFault fault) const;
  std::string wholeFileProblem() const;
  std::string ignoredText() const;

  TextLines lines_{ {} };
  long long listed_[3] = { 0, 0, 0 }; // vertices, texture coordinates, normals so far
  IgnoredStatements ignored_;
  long long coloured_ = 0; // vertices with r g b, which vtkOBJReader 9.1 does not read
  // What wholeFileProblem needs to know of the faces, points and lines.
  long long faces_ = 0;
  bool textured_ = false, texturesMatch_ = true, normals_ = false, normalsMatch_ = true;
  long long firstPointOrLine_ = 0, firstFaceWithoutNormals_ = 0;
  char firstPointOrLineKeyword_ = 0;
};

MeshFileCheck ObjCheck::run(std::string_view text)
{
  if (const long long line = lineWithZeroByte(text))
  {
    return { atLine(line, "a zero byte: this is not a text file, or a damaged one"), "" };
  }
  lines_ = TextLines(text);
  std::string_view line;
  while (lines_.next(line))
  {
    std::string_view rest = line, keyword;
    if (line.size() > longestLine)
    {
      return { atLine(lines_.number(), "longer than 262,142 characters, the most VTK's reader reads in a line"), "" };
    }
    if (!nextWord(rest, keyword, isSpace) || keyword.front() == '#')
    {
      continue;
    }
    if (lines_.number() == 1 && keyword.substr(0, 3) == "\xEF\xBB\xBF")
    {
      // vtkOBJReader takes the mark as part of the keyword, and skips the statement.
      if (keyword.substr(3, 1) == "#")
      {
        continue;
      }
      return {
        atLine(1, "the file starts with a byte order mark, which VTK's reader does not skip: save it without one"), ""
      };
    }
    const std::string problem = statementProblem(keyword, rest);
    if (!problem.empty())
    {
      return { atLine(lines_.number(), problem), "" };
    }
  }
  return { wholeFileProblem(), ignoredText() };
}

std::string ObjCheck::statementProblem(std::string_view keyword, std::string_view rest)
{
  if (keyword == "v" || keyword == "vt" || keyword == "vn")
  {
    return numbersProblem(keyword, rest);
  }
  if (keyword == "f" || keyword == "l" || keyword == "p")
  {
    return elementProblem(keyword, rest);
  }
  if (keyword == "usemtl")
  {
    std::string_view name;
    if (!nextWord(rest, name, isSpace))
    {
      return "'usemtl' needs a material name";
    }
    if (name.size() > longestMaterialName)
    {
      return "the material name is longer than 99 characters, which VTK's reader cannot hold";
    }
    return "";
  }
  if (keyword == "g" || keyword == "mtllib")
  {
    return "";
  }
  if (const char* what = skippedWhat(keyword))
  {
    ignored_.add(keyword, what);
    return "";
  }
  return quotedWord(keyword) + " is not an OBJ statement: delete the line, or make it a comment with '#'";
}

/// "v x y z [w | r g b]", "vt u v [w]" or "vn x y z": every number finite and within a
/// float, where vtkOBJReader stores them.
std::string ObjCheck::numbersProblem(std::string_view keyword, std::string_view rest)
{
  std::string_view words[8];
  int count = 0;
  for (std::string_view word; count < 8 && nextWord(rest, word, isSpace);)
  {
    words[count++] = word;
  }
  static const char* const vertexNames[] = { "x coordinate", "y coordinate", "z coordinate", "w", "r", "g", "b" };
  static const char* const textureNames[] = { "u", "v", "w" };
  static const char* const normalNames[] = { "x", "y", "z" };
  const char* const* names = vertexNames;
  const char* noun = "vertex";
  bool allowed = count == 3 || count == 4 || count == 6;
  const char* form = "a vertex is 'v x y z', optionally followed by w or by r g b";
  Slot slot = VertexSlot;
  if (keyword == "vt")
  {
    names = textureNames, noun = "texture coordinate", slot = TextureSlot;
    allowed = count == 2 || count == 3;
    form = "a texture coordinate is 'vt u v', optionally followed by w";
  }
  else if (keyword == "vn")
  {
    names = normalNames, noun = "normal", slot = NormalSlot;
    allowed = count == 3;
    form = "a normal is 'vn x y z'";
  }
  if (!allowed)
  {
    return std::string(form) + ", and this line has " + (count == 8 ? "more than 7" : std::to_string(count)) +
      (count == 1 ? " value" : " values");
  }
  for (int i = 0; i < count; ++i)
  {
    double value = 0;
    const NumberFault fault = readFloat(words[i], value);
    if (fault != NumberFault::None)
    {
      const char* name = names[i + (slot == VertexSlot && count == 6 && i >= 3)]; // r g b, not w
      return numberMessage(fault, words[i], std::string("the ") + noun + "'s " + name, floatRange);
    }
  }
  ++listed_[slot];
  coloured_ += slot == VertexSlot && count == 6;
  return "";
}

/// "f", "l" or "p" and its corners, each referring to data listed before it. A line ending in
/// "\" continues on the next, as vtkOBJReader reads it.
std::string ObjCheck::elementProblem(std::string_view keyword, std::string_view rest)
{
  const char kind = keyword.front();
  const long long statementLine = lines_.number();
  int corners = 0;
  Corner first;
  std::string_view firstWord;
  for (std::string_view word;;)
  {
    if (!nextWord(rest, word, isSpace))
    {
      break;
    }
    if (word == "\\")
    {
      // vtkOBJReader continues only where "\" is the last character before the line's "\n".
      if (!rest.empty() || !lines_.ended())
      {
        return "'\\' continues a statement on the next line only as the line's last character";
      }
      if (!lines_.next(rest))
      {
        return "the statement continues ('\\') past the end of the file";
      }
      if (rest.size() > longestLine)
      {
        return "longer than 262,142 characters, the most VTK's reader reads in a line";
      }
      continue;
    }
    Corner corner;
    const std::string problem = cornerProblem(kind, word, corner);
    if (!problem.empty())
    {
      return problem;
    }
    if (corners++ == 0)
    {
      first = corner, firstWord = word;
    }
    else if (kind == 'f' &&
      (corner.has[TextureSlot] != first.has[TextureSlot] || corner.has[NormalSlot] != first.has[NormalSlot]))
    {
      return "the corners " + quotedWord(firstWord) + " and " + quotedWord(word) +
        " differ in form: VTK's reader needs every corner of a face to give a texture coordinate, or none; likewise "
        "a normal";
    }
    if (kind == 'f')
    {
      textured_ = textured_ || corner.has[TextureSlot];
      texturesMatch_ =
        texturesMatch_ && (!corner.has[TextureSlot] || corner.index[TextureSlot] == corner.index[VertexSlot]);
      normals_ = normals_ || corner.has[NormalSlot];
      normalsMatch_ =
        normalsMatch_ && (!corner.has[NormalSlot] || corner.index[NormalSlot] == corner.index[VertexSlot]);
    }
  }
  const int least = kind == 'f' ? 3 : kind == 'l' ? 2 : 1;
  if (corners < least)
  {
    static const char* const nouns[] = { "a face needs at least 3 corners", "a line needs at least 2 points",
      "a 'p' statement needs at least 1 point" };
    return std::string(nouns[kind == 'f' ? 0 : kind == 'l' ? 1 : 2]) + ", and this one has " + std::to_string(corners);
  }
  faces_ += kind == 'f';
  if (kind == 'f' && !first.has[NormalSlot] && firstFaceWithoutNormals_ == 0)
  {
    firstFaceWithoutNormals_ = statementLine;
  }
  if (kind != 'f' && firstPointOrLine_ == 0)
  {
    firstPointOrLine_ = statementLine, firstPointOrLineKeyword_ = kind;
  }
  return "";
}

/// One corner: its form (faces v, v/vt, v//vn or v/vt/vn; lines v or v/vt; points v) and
/// each index.
std::string ObjCheck::cornerProblem(char kind, std::string_view word, Corner& corner) const
{
  splitCorner(word, corner);
  NumberFault faults[3] = { NumberFault::None, NumberFault::None, NumberFault::None };
  bool integers =
    kind == 'f' || (kind == 'l' && !corner.has[NormalSlot]) || (!corner.has[TextureSlot] && !corner.has[NormalSlot]);
  for (int slot = 0; integers && slot < 3; ++slot)
  {
    faults[slot] = corner.has[slot] ? readInteger(corner.fields[slot], corner.index[slot]) : NumberFault::None;
    integers = faults[slot] != NumberFault::NotAnInteger;
  }
  if (!integers)
  {
    return quotedWord(word) +
      (kind == 'f'      ? " is not an OBJ face corner"
          : kind == 'l' ? " is not an OBJ line corner (v or v/vt)"
                        : " is not an OBJ point (v)");
  }
  for (int slot = 0; slot < 3; ++slot)
  {
    const std::string problem =
      corner.has[slot] ? indexProblem(kind, Slot(slot), corner.fields[slot], corner.index[slot], faults[slot]) : "";
    if (!problem.empty())
    {
      return problem;
    }
  }
  return "";
}

/// An index counts from 1, or back from the last listed with -1; it must refer to data listed
/// before its line.
std::string ObjCheck::indexProblem(
  char kind, Slot slot, std::string_view field, long long index, NumberFault fault) const
{
  const long long listed = listed_[slot];
  if (fault != NumberFault::OutOfRange && index != 0 && listed + std::min(index, 0LL) >= 0 && index <= listed)
  {
    return "";
  }
  const std::string noun = kind == 'f' ? "face index " : kind == 'l' ? "line index " : "point index ";
  const std::string before = "the file lists " + std::to_string(listed) + " before that line";
  if (fault == NumberFault::OutOfRange)
  {
    return noun + quotedWord(field) + " refers to no " + slotNames[slot] + ": " + before;
  }
  if (index == 0)
  {
    return noun + "0 refers to no " + slotNames[slot] +
      ": OBJ indices start at 1 (and negative ones count back from the last listed, -1 for the last)";
  }
  if (index < 0 && listed + index < 0)
  {
    return noun + std::to_string(index) + " counts back past the first " + slotNames[slot] + ": " + before;
  }
  if (index > listed)
  {
    return noun + std::to_string(index) + " refers to " + slotNames[slot] + " " + std::to_string(index) + ", but " +
      before;
  }
  return "";
}

/// What the whole file makes vtkOBJReader do wrong. It gives the faces alone a group number
/// (GroupIds), so that with points or lines its mesh does not hold together. When the faces
/// number texture coordinates and normals as their vertices, it gives the points these lists
/// as they are, whose lengths must then be the vertices'; otherwise it copies the points of
/// every face, and leaves out the faces without normals if any face has them.
std::string ObjCheck::wholeFileProblem() const
{
  if (faces_ > 0 && firstPointOrLine_ > 0)
  {
    return atLine(firstPointOrLine_,
      std::string("VTK 9.1's reader cannot read this '") + firstPointOrLineKeyword_ +
        "' statement in a file with faces (it numbers the faces' groups alone, and the mesh it makes does not hold "
        "together): keep points and lines in a file of their own");
  }
  const bool copiesPoints = (textured_ && !texturesMatch_) || (normals_ && !normalsMatch_);
  for (const Slot slot : { TextureSlot, NormalSlot })
  {
    const bool used = slot == TextureSlot ? textured_ : normals_;
    if (!copiesPoints && used && listed_[slot] != listed_[VertexSlot])
    {
      const std::string noun = slotNames[slot] + std::string(listed_[slot] == 1 ? "" : "s");
      return "the faces give each corner the " + std::string(slotNames[slot]) +
        " of its vertex's number, but the file "
        "lists " +
        std::to_string(listed_[slot]) + " " + noun + " for " + std::to_string(listed_[VertexSlot]) +
        " vertices, which VTK's reader cannot match: list one for every vertex";
    }
  }
  if (copiesPoints && normals_ && firstFaceWithoutNormals_ > 0)
  {
    return atLine(firstFaceWithoutNormals_,
      "this face gives no normals while others do, and VTK's reader drops such a face where faces number texture "
      "coordinates or normals apart from their vertices: give every face normals, or none");
  }
  return "";
}

std::string ObjCheck::ignoredText() const
{
  std::string text = ignored_.describe();
  if (coloured_ > 0)
  {
    text += (text.empty() ? "" : "; ") + std::string("the r g b colours of ") + std::to_string(coloured_) +
      (coloured_ == 1 ? " vertex (VTK 9.1 reads no vertex colours)" : " vertices (VTK 9.1 reads no vertex colours)");
  }
  return text;
}
}

MeshFileCheck objFileCheck(std::string_view text)
{
  return ObjCheck().run(text);
}
}
