#pragma once
// Text as a cell of the benchmarks' CSV files.
#include <string>

namespace shadelab::app
{
/// RFC 4180: quoted when it holds a comma, a quote or a line break, its quotes doubled.
inline std::string csvText(const std::string& text)
{
  if (text.find_first_of(",\"\r\n") == std::string::npos)
  {
    return text;
  }
  std::string quoted = "\"";
  for (char character : text)
  {
    quoted += character == '"' ? "\"\"" : std::string(1, character);
  }
  return quoted + "\"";
}
}
