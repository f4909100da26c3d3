#include "PlyHeader.h"

#include "IsolatedWork.h"
#include "MeshFileChecks.h"
#include "MeshText.h"

#include <iterator>
#include <sstream>

namespace shadelab::app
{
namespace
{
/// Turk's PLY types and their sized aliases.
const PlyType plyTypes[] = { { "char", 1, false, -128, 127 }, { "int8", 1, false, -128, 127 },
  { "uchar", 1, false, 0, 255 }, { "uint8", 1, false, 0, 255 }, { "short", 2, false, -32768, 32767 },
  { "int16", 2, false, -32768, 32767 }, { "ushort", 2, false, 0, 65535 }, { "uint16", 2, false, 0, 65535 },
  { "int", 4, false, -2147483648.0, 2147483647.0 }, { "int32", 4, false, -2147483648.0, 2147483647.0 },
  { "uint", 4, false, 0, 4294967295.0 }, { "uint32", 4, false, 0, 4294967295.0 }, { "float", 4, true, 0, 0 },
  { "float32", 4, true, 0, 0 }, { "double", 8, true, 0, 0 }, { "float64", 8, true, 0, 0 } };

const PlyType* plyTypeNamed(const std::string& name)
{
  for (const PlyType& type : plyTypes)
  {
    if (name == type.name)
    {
      return &type;
    }
  }
  return nullptr;
}

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

bool hasProperty(const PlyElement& element, const std::string& name)
{
  for (const PlyProperty& property : element.properties)
  {
    if (property.name == name)
    {
      return true;
    }
  }
  return false;
}
}

std::string parsePlyHeader(std::string_view text, PlyHeader& header)
{
  TextLines lines(text);
  std::string_view view;
  while (lines.next(view))
  {
    const long long lineNumber = lines.number();
    if (!lines.ended())
    {
      break;
    }
    std::string line(view);
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
    const std::string where =
      "line " + std::to_string(lineNumber) + " of the PLY header ('" + printableText(line, 60) + "')";
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
      if (words.size() != 3 ||
        (words[1] != "ascii" && words[1] != "binary_little_endian" && words[1] != "binary_big_endian"))
      {
        return where + " is not 'format ascii|binary_little_endian|binary_big_endian 1.0'";
      }
      header.format = words[1] == "ascii" ? PlyFormat::Ascii
        : words[1] == "binary_big_endian" ? PlyFormat::BinaryBigEndian
                                          : PlyFormat::BinaryLittleEndian;
    }
    else if (keyword == "element")
    {
      PlyElement element;
      if (words.size() != 3 || !parseCount(words[2], element.count))
      {
        return where + " is not 'element NAME COUNT' with a COUNT from 0 to 2147483647";
      }
      element.name = words[1];
      header.elements.push_back(element);
    }
    else if (keyword == "property")
    {
      if (header.elements.empty())
      {
        return where + " comes before any element";
      }
      PlyElement& element = header.elements.back();
      PlyProperty property;
      const bool list = words.size() == 5 && words[1] == "list";
      property.countType = list ? plyTypeNamed(words[2]) : nullptr;
      property.type = list ? plyTypeNamed(words[3]) : words.size() == 3 ? plyTypeNamed(words[1]) : nullptr;
      if (!property.type || (list && !property.countType))
      {
        return where + " is not 'property TYPE NAME' or 'property list TYPE TYPE NAME' with PLY's types";
      }
      // vtkPLY reads "vertex_index" as "vertex_indices", wherever it is.
      property.name = words.back() == "vertex_index" ? "vertex_indices" : words.back();
      property.coordinate =
        element.name == "vertex" && (property.name == "x" || property.name == "y" || property.name == "z");
      property.vertexIndices = element.name == "face" && property.name == "vertex_indices";
      if (hasProperty(element, property.name))
      {
        return where + " repeats the property '" + property.name + "' of element '" + element.name + "'";
      }
      element.properties.push_back(property);
    }
    else if (keyword == "end_header")
    {
      header.bodyStart = text.size() - lines.rest().size();
      header.lines = lineNumber;
      return "";
    }
    else
    {
      return where + " is not a PLY header line";
    }
  }
  return "the PLY header has no end_header line (a damaged file, or the header is longer than 1 MB)";
}

std::string plyCountsProblem(const PlyHeader& header, std::uintmax_t fileSize)
{
  const std::uintmax_t body = fileSize > header.bodyStart ? fileSize - header.bodyStart : 0;
  long long vertices = -1, faces = 0;
  double leastBody = 0;
  for (const PlyElement& element : header.elements)
  {
    // ASCII: at least one digit and a separator per value; binary: the value's bytes (a list's count, no items).
    double leastBytesEach = 0;
    for (const PlyProperty& property : element.properties)
    {
      leastBytesEach +=
        header.format == PlyFormat::Ascii ? 2 : (property.countType ? property.countType : property.type)->bytes;
    }
    leastBody += static_cast<double>(element.count) * leastBytesEach;
    if (element.name == "vertex")
    {
      if (!(hasProperty(element, "x") && hasProperty(element, "y") && hasProperty(element, "z")))
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

long long vertexCount(const PlyHeader& header)
{
  for (const PlyElement& element : header.elements)
  {
    if (element.name == "vertex")
    {
      return element.count;
    }
  }
  return 0;
}

std::string plyHeaderProblem(std::string_view text, std::uintmax_t fileSize)
{
  PlyHeader header;
  const std::string problem = parsePlyHeader(text, header);
  return problem.empty() ? plyCountsProblem(header, fileSize) : problem;
}
}
