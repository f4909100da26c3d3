// The checks of a PLY file against what VTK 9.1's vtkPLYReader makes of it: a header whose
// counts are more than the file holds crashes it or has it read out of bounds; in an ASCII body
// it reads numbers with atof and atoi ("1.0abc" as 1, "abc" as 0, "nan" as NaN), an integer
// beyond its type wraps, and a line with too few values takes the next line's.
#include "MeshFileChecks.h"
#include "MeshText.h"
#include "PlyHeader.h"

#include <cfloat>
#include <cmath>
#include <cstring>
#include <iomanip>
#include <sstream>

namespace shadelab::app
{
namespace
{
/// What a value of the body must be, whether read from text or from bytes: a real number
/// finite (and a coordinate within a float, where vtkPLYReader stores it, whatever its type),
/// and a face's vertex index one of the vertices.
class PlyValueRules
{
public:
  explicit PlyValueRules(const PlyHeader& header)
    : vertices_(vertexCount(header))
  {
  }

  /// "the 'vertex' property 'x'", "the count of the 'face' list 'vertex_indices'".
  static std::string what(const PlyElement& element, const PlyProperty& property, bool count)
  {
    if (!property.countType)
    {
      return "the '" + element.name + "' property '" + property.name + "'";
    }
    return std::string(count ? "the count of" : "a value of") + " the '" + element.name + "' list '" + property.name +
      "'";
  }

  /// Whether value keeps the rules: the test alone, with no text made, for every value of a
  /// file (a 2.2M-vertex binary PLY has 24M of them).
  bool keeps(const PlyProperty& property, bool count, double value) const
  {
    const PlyType& type = *(count ? property.countType : property.type);
    const bool index = !count && property.vertexIndices;
    return !(type.real && !std::isfinite(value)) &&
      !(type.real && (property.coordinate || type.bytes == 4) && std::fabs(value) > FLT_MAX) &&
      !(count && !(value >= 0 && value <= 4294967295.0 && value == std::floor(value))) && // a count of a real type too
      !(index && value != std::floor(value)) && !(index && !(value >= 0 && value < static_cast<double>(vertices_)));
  }

  /// value against the rules, "" where it keeps them; word is how the file writes it ("": as
  /// the value prints).
  std::string problem(
    const PlyElement& element, const PlyProperty& property, bool count, double value, std::string_view word) const
  {
    if (keeps(property, count, value))
    {
      return "";
    }
    const PlyType& type = *(count ? property.countType : property.type);
    auto shown = [&]()
    {
      std::ostringstream text;
      text << std::setprecision(type.bytes == 8 ? 17 : 9) << value;
      return !word.empty() ? std::string(word) : type.real ? text.str() : std::to_string(static_cast<long long>(value));
    };
    if (type.real && !std::isfinite(value))
    {
      return numberMessage(NumberFault::NotFinite, shown(), what(element, property, count), "");
    }
    if (type.real && (property.coordinate || type.bytes == 4) && std::fabs(value) > FLT_MAX)
    {
      return numberMessage(NumberFault::OutOfRange, shown(), what(element, property, count), floatRange);
    }
    if (count)
    {
      return quotedWord(shown()) + " is not a count (" + what(element, property, count) + ")";
    }
    if (value != std::floor(value))
    {
      return numberMessage(NumberFault::NotAnInteger, shown(), "a vertex index", "");
    }
    return "vertex index " + shown() + " refers to no vertex: the header declares " + std::to_string(vertices_) +
      ", numbered from 0";
  }

private:
  long long vertices_;
};

/// vtkPLY reads a line into 4096 chars, with its "\n" and terminating zero.
constexpr std::size_t longestPlyLine = 4094;

/// One value of an ASCII line by its type: an integer within its type's range, or a real.
std::string asciiValueProblem(const PlyValueRules& rules, const PlyElement& element, const PlyProperty& property,
  bool count, std::string_view word, double& value)
{
  const PlyType& type = *(count ? property.countType : property.type);
  NumberFault fault = NumberFault::None;
  if (type.real)
  {
    fault = readReal(word, value);
  }
  else
  {
    long long integer = 0;
    fault = readInteger(word, integer);
    value = static_cast<double>(integer);
    if (fault == NumberFault::None && (value < type.least || value > type.most))
    {
      fault = NumberFault::OutOfRange;
    }
  }
  if (fault != NumberFault::None && fault != NumberFault::NotFinite)
  {
    const std::string range = std::to_string(static_cast<long long>(type.least)) + " to " +
      std::to_string(static_cast<long long>(type.most)) + ", the range of type " + type.name;
    return numberMessage(fault, word, PlyValueRules::what(element, property, count) + ", of type " + type.name, range);
  }
  return rules.problem(element, property, count, fault == NumberFault::NotFinite ? NAN : value, word);
}

/// One line of an ASCII body: one element, its values in the order of its properties.
std::string asciiElementProblem(const PlyValueRules& rules, const PlyElement& element, std::string_view line)
{
  std::string_view word;
  long long values = 0;
  for (const PlyProperty& property : element.properties)
  {
    long long items = 1;
    for (bool count = property.countType != nullptr; items > 0; count = false)
    {
      if (!nextWord(line, word, isPlySpace))
      {
        return "this '" + element.name + "' line ends after " + std::to_string(values) +
          (values == 1 ? " value" : " values") + ", before its '" + property.name + "' is complete";
      }
      ++values;
      double value = 0;
      const std::string problem = asciiValueProblem(rules, element, property, count, word, value);
      if (!problem.empty())
      {
        return problem;
      }
      items = count ? static_cast<long long>(value) : items - 1;
    }
  }
  if (nextWord(line, word, isPlySpace))
  {
    return "this '" + element.name + "' line has more values than the header's properties for it take (" +
      quotedWord(word) + " is one too many)";
  }
  return "";
}

/// "3 'vertex' and 1 'face'".
std::string elementCounts(const PlyHeader& header)
{
  std::string text;
  for (std::size_t i = 0; i < header.elements.size(); ++i)
  {
    text += (i == 0                               ? ""
                : i + 1 == header.elements.size() ? " and "
                                                  : ", ") +
      std::to_string(header.elements[i].count) + " '" + header.elements[i].name + "'";
  }
  return text;
}

/// An ASCII body: a line per element, as vtkPLY's get_words reads them, and nothing after them.
std::string asciiBodyProblem(const PlyHeader& header, std::string_view body)
{
  const PlyValueRules rules(header);
  TextLines lines(body, header.lines + 1);
  std::string_view line;
  for (const PlyElement& element : header.elements)
  {
    for (long long i = 0; i < element.count; ++i)
    {
      if (!lines.next(line))
      {
        return atLine(lines.number() + 1,
          "the file ends after " + std::to_string(i) + " of the " + std::to_string(element.count) + " '" +
            element.name + "' lines the header declares");
      }
      if (!lines.ended())
      {
        return atLine(lines.number(),
          "the file's last line has no line break, and VTK's PLY reader stops before it: end the file with one");
      }
      if (line.size() > longestPlyLine)
      {
        return atLine(lines.number(), "longer than 4,094 characters, the most VTK's PLY reader reads in a line");
      }
      const std::string problem = asciiElementProblem(rules, element, line);
      if (!problem.empty())
      {
        return atLine(lines.number(), problem);
      }
    }
  }
  while (lines.next(line))
  {
    if (!trimmedStart(line, isPlySpace).empty())
    {
      return atLine(lines.number(),
        "the header declares " + elementCounts(header) + " lines, and this one comes after them all: a count is wrong");
    }
  }
  return "";
}

/// The value of type at bytes, stored with the file's byte order.
double binaryValue(const PlyType& type, const char* bytes, bool swap)
{
  char ordered[8];
  for (int i = 0; i < type.bytes; ++i)
  {
    ordered[i] = bytes[swap ? type.bytes - 1 - i : i];
  }
  auto as = [&](auto value)
  {
    std::memcpy(&value, ordered, sizeof value);
    return static_cast<double>(value);
  };
  switch (type.bytes)
  {
    case 1: return type.least < 0 ? as(std::int8_t()) : as(std::uint8_t());
    case 2: return type.least < 0 ? as(std::int16_t()) : as(std::uint16_t());
    case 4: return type.real ? as(float()) : type.least < 0 ? as(std::int32_t()) : as(std::uint32_t());
    default: return as(double());
  }
}

/// A binary body: every element within the file, and every value by the rules. The values
/// are in the machine's byte order or reversed.
std::string binaryBodyProblem(const PlyHeader& header, std::string_view body)
{
  const std::uint16_t one = 1;
  const bool littleEndianMachine = *reinterpret_cast<const char*>(&one) == 1;
  const bool swap = littleEndianMachine != (header.format == PlyFormat::BinaryLittleEndian);
  const PlyValueRules rules(header);
  std::size_t at = 0;
  for (const PlyElement& element : header.elements)
  {
    for (long long i = 0; i < element.count; ++i)
    {
      auto where = [&]()
      {
        return "'" + element.name + "' element " + std::to_string(i) + " of " + std::to_string(element.count) +
          " (counting from 0): ";
      };
      for (const PlyProperty& property : element.properties)
      {
        long long items = 1;
        for (bool count = property.countType != nullptr; items > 0; count = false)
        {
          const PlyType& type = *(count ? property.countType : property.type);
          if (body.size() - at < static_cast<std::size_t>(type.bytes))
          {
            return where() + "the file ends in it: it is cut short or the header's counts are wrong";
          }
          const double value = binaryValue(type, body.data() + at, swap);
          at += static_cast<std::size_t>(type.bytes);
          if (!rules.keeps(property, count, value))
          {
            return where() + rules.problem(element, property, count, value, "");
          }
          items = count ? static_cast<long long>(value) : items - 1;
        }
      }
    }
  }
  return "";
}
}

std::string plyFileProblem(std::string_view text)
{
  PlyHeader header;
  std::string problem = parsePlyHeader(text.substr(0, std::size_t(1) << 20), header);
  if (problem.empty())
  {
    problem = plyCountsProblem(header, text.size());
  }
  if (!problem.empty())
  {
    return problem;
  }
  const std::string_view body = text.substr(header.bodyStart);
  return header.format == PlyFormat::Ascii ? asciiBodyProblem(header, body) : binaryBodyProblem(header, body);
}
}
