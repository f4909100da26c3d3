#include "MeshText.h"

#include "IsolatedWork.h"

#include <algorithm>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace shadelab::app
{
NumberFault readReal(std::string_view word, double& value)
{
  // strtod, and so the readers, take a leading '+'; from_chars does not.
  std::string_view digits = word;
  if (!digits.empty() && digits.front() == '+')
  {
    digits.remove_prefix(1);
    if (!digits.empty() && digits.front() == '-')
    {
      return NumberFault::NotANumber;
    }
  }
  if (digits.empty())
  {
    return NumberFault::NotANumber;
  }
  const char* end = digits.data() + digits.size();
  const std::from_chars_result read = std::from_chars(digits.data(), end, value, std::chars_format::general);
  if (read.ptr != end)
  {
    return NumberFault::NotANumber;
  }
  if (read.ec == std::errc::result_out_of_range)
  {
    // Beyond the range either way: strtod says which (an infinity, or a value rounded to 0).
    value = std::strtod(std::string(digits).c_str(), nullptr);
  }
  return std::isfinite(value) ? NumberFault::None : NumberFault::NotFinite; // "nan", "inf" too
}

NumberFault readFloat(std::string_view word, double& value)
{
  const NumberFault fault = readReal(word, value);
  if (fault == NumberFault::None && std::fabs(value) > FLT_MAX)
  {
    return NumberFault::OutOfRange;
  }
  return fault;
}

NumberFault readInteger(std::string_view word, long long& value)
{
  std::string_view digits = word;
  if (!digits.empty() && digits.front() == '+')
  {
    digits.remove_prefix(1); // as strtol and sscanf take it
    if (!digits.empty() && digits.front() == '-')
    {
      return NumberFault::NotAnInteger;
    }
  }
  if (digits.empty())
  {
    return NumberFault::NotAnInteger;
  }
  const char* end = digits.data() + digits.size();
  const std::from_chars_result read = std::from_chars(digits.data(), end, value);
  if (read.ptr != end)
  {
    return NumberFault::NotAnInteger;
  }
  return read.ec == std::errc::result_out_of_range ? NumberFault::OutOfRange : NumberFault::None;
}

std::string quotedWord(std::string_view word)
{
  return "'" + printableText(std::string(word), 40) + "'";
}

const char* const floatRange = "+-3.4e+38, the range of the float in which VTK's reader stores it";

std::string numberMessage(NumberFault fault, std::string_view word, const std::string& what, const std::string& range)
{
  switch (fault)
  {
    case NumberFault::None: break;
    case NumberFault::NotANumber: return quotedWord(word) + " is not a number (" + what + ")";
    case NumberFault::NotFinite: return quotedWord(word) + " is not a finite number (" + what + ")";
    case NumberFault::NotAnInteger: return quotedWord(word) + " is not an integer (" + what + ")";
    case NumberFault::OutOfRange: return quotedWord(word) + " is beyond " + range + " (" + what + ")";
  }
  return "";
}

std::string atLine(long long number, const std::string& message)
{
  return "line " + std::to_string(number) + ": " + message;
}

long long lineWithZeroByte(std::string_view text)
{
  const std::size_t zero = text.find('\0');
  if (zero == std::string_view::npos)
  {
    return 0;
  }
  const std::string_view before = text.substr(0, zero);
  return 1 + static_cast<long long>(std::count(before.begin(), before.end(), '\n'));
}

void IgnoredStatements::add(std::string_view keyword, const char* what)
{
  for (Count& count : counts_)
  {
    if (count.keyword == keyword)
    {
      ++count.n;
      return;
    }
  }
  counts_.push_back({ std::string(keyword), what, 1 });
}

std::string IgnoredStatements::describe() const
{
  if (counts_.empty())
  {
    return "";
  }
  std::string text;
  long long total = 0;
  std::vector<const char*> whats;
  for (const Count& count : counts_)
  {
    text += (text.empty() ? "" : ", ") + std::to_string(count.n) + " '" + count.keyword + "'";
    total += count.n;
    if (std::find_if(whats.begin(), whats.end(), [&](const char* w) { return std::strcmp(w, count.what) == 0; }) ==
      whats.end())
    {
      whats.push_back(count.what);
    }
  }
  text += total == 1 ? " statement (" : " statements (";
  for (std::size_t i = 0; i < whats.size(); ++i)
  {
    text += (i == 0 ? "" : i + 1 == whats.size() ? " and " : ", ") + std::string(whats[i]);
  }
  return text + " are not read)";
}
}
