// The checks of an STL file against what VTK 9.1's vtkSTLReader makes of it: in an ASCII file
// it reads a vertex with strtod, "1 2 3abc" as (1, 2, 3), "nan" as NaN, and ignores what follows
// the first three numbers; a binary file's coordinates it takes as they are, NaN too.
#include "MeshFileChecks.h"
#include "MeshText.h"

#include "IsolatedWork.h"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace shadelab::app
{
namespace
{
/// vtkSTLReader reads a line with fgets into 255 chars: a longer line goes on as the next.
constexpr std::size_t longestStlLine = 254;

/// Whether word is keyword, in any case, as vtkSTLReader compares them.
bool isKeyword(std::string_view word, std::string_view keyword)
{
  if (word.size() != keyword.size())
  {
    return false;
  }
  for (std::size_t i = 0; i < word.size(); ++i)
  {
    if (std::tolower(static_cast<unsigned char>(word[i])) != keyword[i])
    {
      return false;
    }
  }
  return true;
}

/// The words of a line, at most 6 of them (more make the line wrong wherever it is).
struct Words
{
  std::string_view word[6];
  int count = 0;
};

Words wordsOf(std::string_view line)
{
  Words words;
  for (std::string_view word; words.count < 6 && nextWord(line, word, isSpace);)
  {
    words.word[words.count++] = word;
  }
  return words;
}

/// "facet normal nx ny nz" or "vertex x y z" after the keywords: three finite floats.
std::string numbersProblem(const Words& words, int first, const char* form, const char* noun)
{
  if (words.count != first + 3)
  {
    return std::string(form) + ", and this line has " + std::to_string(words.count - first) +
      (words.count - first == 1 ? " value" : " values") + " after '" + std::string(words.word[first - 1]) + "'";
  }
  static const char* const axes[] = { "x", "y", "z" };
  for (int i = 0; i < 3; ++i)
  {
    double value = 0;
    const NumberFault fault = readFloat(words.word[first + i], value);
    if (fault != NumberFault::None)
    {
      return numberMessage(fault, words.word[first + i], std::string(noun) + axes[i], floatRange);
    }
  }
  return "";
}

/// ASCII STL, statement by statement: solid, then facets of "facet normal", "outer loop",
/// three "vertex" lines, "endloop" and "endfacet", then "endsolid"; more solids may follow.
class AsciiStlCheck
{
public:
  MeshFileCheck run(std::string_view text)
  {
    if (const long long line = lineWithZeroByte(text))
    {
      return { atLine(line, "a zero byte: this is not a text file, or a damaged one"), "" };
    }
    TextLines lines(text);
    std::string_view line;
    while (lines.next(line))
    {
      if (line.size() > longestStlLine)
      {
        return { atLine(lines.number(), "longer than 254 characters, which VTK's STL reader reads as two lines"), "" };
      }
      const Words words = wordsOf(line);
      const std::string problem = words.count == 0 ? "" : statementProblem(words, line);
      if (!problem.empty())
      {
        return { atLine(lines.number(), problem), "" };
      }
    }
    if (state_ != Solid || solids_ == 0)
    {
      return { atLine(lines.number() + 1, "the file ends where '" + std::string(expected()) + "' should be"), "" };
    }
    return { "", ignored_.describe() };
  }

private:
  enum State
  {
    Solid,
    Facet,
    Loop,
    Vertex,
    EndLoop,
    EndFacet,
  };

  const char* expected() const
  {
    static const char* const names[] = { "solid", "facet normal' or 'endsolid", "outer loop", "vertex", "endloop",
      "endfacet" };
    return names[state_];
  }

  std::string statementProblem(const Words& words, std::string_view line)
  {
    const std::string_view keyword = words.word[0];
    if (state_ == Solid && isKeyword(keyword, "solid"))
    {
      ++solids_, state_ = Facet;
      return "";
    }
    if (state_ == Facet && isKeyword(keyword, "color"))
    {
      ignored_.add("color", "colours");
      return "";
    }
    if (state_ == Facet && isKeyword(keyword, "endsolid"))
    {
      state_ = Solid;
      return "";
    }
    if (state_ == Facet && isKeyword(keyword, "facet") && words.count > 1 && isKeyword(words.word[1], "normal"))
    {
      state_ = Loop;
      return numbersProblem(words, 2, "a facet starts 'facet normal nx ny nz'", "the facet normal's ");
    }
    if (state_ == Loop && words.count == 2 && isKeyword(keyword, "outer") && isKeyword(words.word[1], "loop"))
    {
      state_ = Vertex, vertices_ = 0;
      return "";
    }
    if (state_ == Vertex && isKeyword(keyword, "vertex"))
    {
      state_ = ++vertices_ == 3 ? EndLoop : Vertex;
      return numbersProblem(words, 1, "a vertex is 'vertex x y z'", "the vertex's ");
    }
    if ((state_ == EndLoop && words.count == 1 && isKeyword(keyword, "endloop")) ||
      (state_ == EndFacet && words.count == 1 && isKeyword(keyword, "endfacet")))
    {
      state_ = state_ == EndLoop ? EndFacet : Facet;
      return "";
    }
    if (state_ == Solid && solids_ == 0)
    {
      return "an ASCII STL file starts with 'solid', not " + quotedWord(trimmedStart(line, isSpace));
    }
    return "'" + std::string(expected()) + "' should be here, not " + quotedWord(trimmedStart(line, isSpace));
  }

  State state_ = Solid;
  int vertices_ = 0;
  long long solids_ = 0;
  IgnoredStatements ignored_;
};

/// Binary STL: an 80-byte header, a 4-byte count (which vtkSTLReader ignores, reading to the
/// end of the file), and 50 bytes a triangle: a normal, three vertices, two bytes more.
std::string binaryStlProblem(std::string_view bytes)
{
  constexpr std::size_t headerBytes = 84, triangleBytes = 50;
  if (bytes.size() < headerBytes)
  {
    return "a binary STL file starts with an 84-byte header, and this one has " + std::to_string(bytes.size()) +
      " bytes: it is cut short, or not an STL file";
  }
  const std::size_t body = bytes.size() - headerBytes;
  if (body % triangleBytes != 0)
  {
    return "a binary STL file has 50 bytes a triangle after its 84-byte header, and this one has " +
      std::to_string(body) + ": it is cut short, or not an STL file";
  }
  const std::size_t triangles = body / triangleBytes;
  for (std::size_t t = 0; t < triangles; ++t)
  {
    for (int i = 0; i < 9; ++i)
    {
      const auto* at =
        reinterpret_cast<const unsigned char*>(bytes.data() + headerBytes + t * triangleBytes + 12 + 4 * i);
      const std::uint32_t bits = at[0] | at[1] << 8 | at[2] << 16 | std::uint32_t(at[3]) << 24; // little-endian
      float coordinate = 0;
      std::memcpy(&coordinate, &bits, 4);
      if (!std::isfinite(coordinate))
      {
        return "triangle " + std::to_string(t + 1) + " of " + std::to_string(triangles) + " has a vertex coordinate " +
          "that is not a finite number (" + (std::isnan(coordinate) ? "NaN" : "infinite") + ")";
      }
    }
  }
  return "";
}
}

MeshFileCheck stlFileCheck(std::string_view text, bool ascii)
{
  return ascii ? AsciiStlCheck().run(text) : MeshFileCheck{ binaryStlProblem(text), "" };
}
}
