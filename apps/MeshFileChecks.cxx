#include "MeshFileChecks.h"

#include "IsolatedWork.h"

#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <vector>

namespace shadelab::app
{
namespace
{
/// Bytes of each PLY scalar type (Turk's format and its sized aliases).
const std::map<std::string, int> plyTypeSizes = { { "char", 1 }, { "uchar", 1 }, { "int8", 1 }, { "uint8", 1 },
  { "short", 2 }, { "ushort", 2 }, { "int16", 2 }, { "uint16", 2 }, { "int", 4 }, { "uint", 4 }, { "int32", 4 },
  { "uint32", 4 }, { "float", 4 }, { "float32", 4 }, { "double", 8 }, { "float64", 8 } };

struct PlyElement
{
  std::string name;
  long long count = 0;
  long long leastBytesEach = 0; // a value per scalar property and a count per list, no list items
  std::vector<std::string> properties;
  bool hasList = false;
};

/// The count in "element NAME COUNT": digits only, and small enough for VTK's int.
bool parseCount(const std::string& text, long long& count)
{
  if (text.empty() || text.size() > 10 || text.find_first_not_of("0123456789") != std::string::npos)
  {
    return false;
  }
  count = std::stoll(text);
  return count <= 2147483647LL;
}

std::vector<std::string> wordsOf(const std::string& line)
{
  std::istringstream in(line);
  return { std::istream_iterator<std::string>(in), std::istream_iterator<std::string>() };
}

bool has(const std::vector<std::string>& names, const std::string& name)
{
  for (const std::string& n : names)
  {
    if (n == name)
    {
      return true;
    }
  }
  return false;
}

std::string readStart(const std::string& fileName, std::size_t bytes)
{
  std::ifstream file(fileName, std::ios::binary);
  std::string text(bytes, '\0');
  file.read(&text[0], static_cast<std::streamsize>(bytes));
  text.resize(static_cast<std::size_t>(file.gcount()));
  return text;
}

std::string readWhole(const std::string& fileName)
{
  std::ifstream file(fileName, std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}
}

std::string plyHeaderProblem(const std::string& text, std::uintmax_t fileSize)
{
  std::vector<PlyElement> elements;
  bool ascii = false;
  std::size_t lineStart = 0;
  for (int lineNumber = 1;; ++lineNumber)
  {
    const std::size_t lineEnd = text.find('\n', lineStart);
    if (lineEnd == std::string::npos)
    {
      return "the PLY header has no end_header line (a damaged file, or the header is longer than 1 MB)";
    }
    std::string line = text.substr(lineStart, lineEnd - lineStart);
    lineStart = lineEnd + 1;
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    for (const char c : line)
    {
      if (c < 0x20 || c >= 0x7f)
      {
        return "line " + std::to_string(lineNumber) + " of the PLY header is not text: the file is damaged";
      }
    }
    const std::vector<std::string> words = wordsOf(line);
    const std::string keyword = words.empty() ? "" : words[0];
    const std::string where = "line " + std::to_string(lineNumber) + " of the PLY header ('" + printableText(line, 60) + "')";
    if (lineNumber == 1)
    {
      if (line != "ply")
      {
        return "not a PLY file (it does not start with a PLY header)";
      }
      continue;
    }
    if (keyword == "comment" || keyword == "obj_info")
    {
      continue;
    }
    if (keyword == "format")
    {
      if (words.size() != 3 || (words[1] != "ascii" && words[1] != "binary_little_endian" && words[1] != "binary_big_endian"))
      {
        return where + " is not 'format ascii|binary_little_endian|binary_big_endian 1.0'";
      }
      ascii = words[1] == "ascii";
    }
    else if (keyword == "element")
    {
      PlyElement element;
      if (words.size() != 3 || !parseCount(words[2], element.count))
      {
        return where + " is not 'element NAME COUNT' with a COUNT from 0 to 2147483647";
      }
      element.name = words[1];
      elements.push_back(element);
    }
    else if (keyword == "property")
    {
      if (elements.empty())
      {
        return where + " comes before any element";
      }
      PlyElement& element = elements.back();
      const bool list = words.size() == 5 && words[1] == "list";
      if (list ? !(plyTypeSizes.count(words[2]) && plyTypeSizes.count(words[3]))
               : !(words.size() == 3 && plyTypeSizes.count(words[1])))
      {
        return where + " is not 'property TYPE NAME' or 'property list TYPE TYPE NAME' with PLY's types";
      }
      const std::string& name = words.back();
      if (has(element.properties, name))
      {
        return where + " repeats the property '" + name + "' of element '" + element.name + "'";
      }
      element.properties.push_back(name);
      element.hasList = element.hasList || list;
      // ASCII: at least one digit and a separator per value; binary: the value's bytes.
      element.leastBytesEach += ascii ? 2 : plyTypeSizes.at(list ? words[2] : words[1]);
    }
    else if (keyword == "end_header")
    {
      break;
    }
    else
    {
      return where + " is not a PLY header line";
    }
  }

  const std::uintmax_t body = fileSize > lineStart ? fileSize - lineStart : 0;
  long long vertices = -1, faces = 0;
  double leastBody = 0;
  for (const PlyElement& element : elements)
  {
    leastBody += static_cast<double>(element.count) * static_cast<double>(element.leastBytesEach);
    if (element.name == "vertex")
    {
      if (!(has(element.properties, "x") && has(element.properties, "y") && has(element.properties, "z")))
      {
        return "the PLY header's vertex element has no x, y and z properties";
      }
      vertices = element.count;
    }
    if (element.name == "face")
    {
      faces = element.count;
    }
  }
  if (vertices < 0)
  {
    return "the PLY header declares no vertex element";
  }
  if (vertices == 0 && faces > 0)
  {
    return "the PLY header declares " + std::to_string(faces) + " faces but no vertices for them to join";
  }
  if (leastBody > static_cast<double>(body) + 1) // + 1: the last value needs no separator
  {
    std::ostringstream message;
    message << "the PLY header declares " << vertices << " vertices and " << faces << " faces, which need at least "
            << static_cast<long long>(leastBody) << " bytes, but the file has " << body
            << " after its header: it is cut short or its counts are wrong";
    return message.str();
  }
  return "";
}

std::string objIndexProblem(const std::string& text)
{
  long long listed[3] = { 0, 0, 0 }; // vertices, texture coordinates, normals so far
  static const char* const names[3] = { "vertex", "texture coordinate", "normal" };
  std::istringstream lines(text);
  std::string line;
  for (long long lineNumber = 1; std::getline(lines, line); ++lineNumber)
  {
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "v" || keyword == "vt" || keyword == "vn")
    {
      ++listed[keyword == "v" ? 0 : keyword == "vt" ? 1 : 2];
      continue;
    }
    if (keyword != "f" && keyword != "l" && keyword != "p")
    {
      continue;
    }
    std::string corner;
    while (words >> corner)
    {
      // v, v/vt, v//vn or v/vt/vn; indices count from 1, negative ones back from the last.
      std::istringstream fields(corner);
      std::string field;
      for (int slot = 0; slot < 3 && std::getline(fields, field, '/'); ++slot)
      {
        if (field.empty() && slot > 0)
        {
          continue;
        }
        long long index = 0;
        std::size_t used = 0;
        try
        {
          index = std::stoll(field, &used);
        }
        catch (const std::exception&)
        {
          used = 0;
        }
        if (used != field.size())
        {
          return "line " + std::to_string(lineNumber) + ": '" + printableText(corner, 40) + "' is not an OBJ face corner";
        }
        const long long resolved = index < 0 ? listed[slot] + index + 1 : index;
        if (resolved < 1 || resolved > listed[slot])
        {
          return "line " + std::to_string(lineNumber) + ": face index " + std::to_string(index) + " refers to " +
            names[slot] + " " + std::to_string(resolved) + ", but the file lists " + std::to_string(listed[slot]) +
            " before that line";
        }
      }
    }
  }
  return "";
}

std::string fileProblem(const std::string& fileName, const std::string& extension, std::uintmax_t fileSize)
{
  if (extension == ".ply")
  {
    return plyHeaderProblem(readStart(fileName, 1 << 20), fileSize);
  }
  if (extension == ".obj")
  {
    return objIndexProblem(readWhole(fileName));
  }
  return "";
}
}
