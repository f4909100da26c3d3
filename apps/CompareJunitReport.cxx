#include "CompareReports.h"

#include <algorithm>
#include <sstream>

namespace shadelab::app::compare
{
namespace
{
/// The length of the UTF-8 sequence at text[i] if it is a character XML 1.0 may hold
/// (shortest form, no surrogate, not U+FFFE or U+FFFF), else 0.
std::size_t xmlCharacterLength(const std::string& text, std::size_t i)
{
  const auto byte = [&](std::size_t k) { return k < text.size() ? static_cast<unsigned char>(text[k]) : 0u; };
  const unsigned lead = byte(i);
  const std::size_t length = lead < 0x80 ? 1
    : lead >= 0xC2 && lead <= 0xDF       ? 2
    : lead >= 0xE0 && lead <= 0xEF       ? 3
    : lead >= 0xF0 && lead <= 0xF4       ? 4
                                         : 0;
  if (length == 0)
  {
    return 0;
  }
  unsigned code = length == 1 ? lead : lead & (0x7Fu >> length);
  for (std::size_t k = 1; k < length; ++k)
  {
    if ((byte(i + k) & 0xC0u) != 0x80u)
    {
      return 0;
    }
    code = (code << 6) | (byte(i + k) & 0x3Fu);
  }
  const unsigned smallest[] = { 0, 0, 0x80, 0x800, 0x10000 };
  const bool allowed = (code >= 0x20 || code == '\t' || code == '\n' || code == '\r') && code >= smallest[length] &&
    !(code >= 0xD800 && code <= 0xDFFF) && code != 0xFFFE && code != 0xFFFF && code <= 0x10FFFF;
  return allowed ? length : 0;
}

/// Text in XML: the five characters XML reserves escaped, and each byte that is not part of a
/// character XML may hold (a name that is not UTF-8, a control character) as '?'.
std::string xmlText(const std::string& text)
{
  std::string escaped;
  for (std::size_t i = 0; i < text.size();)
  {
    const std::size_t length = xmlCharacterLength(text, i);
    if (length == 0)
    {
      escaped += '?';
      ++i;
      continue;
    }
    const char c = text[i];
    switch (c)
    {
      case '&': escaped += "&amp;"; break;
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      case '"': escaped += "&quot;"; break;
      case '\'': escaped += "&apos;"; break;
      default: escaped.append(text, i, length);
    }
    i += length;
  }
  return escaped;
}
}

std::string junitReport(
  const std::vector<ArrayReport>& reports, const ComparedFiles& files, const CompareOptions& options)
{
  const std::size_t failures = static_cast<std::size_t>(
    std::count_if(reports.begin(), reports.end(), [](const ArrayReport& r) { return !r.passes(); }));
  std::ostringstream xml;
  xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<testsuites name=\"shadelab compare\" tests=\"" << reports.size() << "\" failures=\"" << failures << "\">\n"
      << "  <testsuite name=\"" << xmlText(options.result + " against " + options.baseline) << "\" tests=\""
      << reports.size() << "\" failures=\"" << failures << "\">\n";
  for (const ArrayReport& report : reports)
  {
    xml << "    <testcase classname=\"shadelab.compare." << associationName(report.association) << "\" name=\""
        << xmlText(report.name) << "\"";
    const bool noise = report.difference && !report.difference->noise.empty();
    if (report.passes() && !noise)
    {
      xml << "/>\n";
      continue;
    }
    // A passing noise check says its counts too, as standard output.
    const char* element = report.passes() ? "system-out" : "failure";
    xml << ">\n      <" << element;
    if (!report.passes())
    {
      xml << " message=\"" << xmlText(verdictOf(report)) << "\"";
    }
    xml << ">";
    for (const std::string& line : detailsOf(report, files.baseline, files.result))
    {
      xml << xmlText(line) << "\n";
    }
    xml << "</" << element << ">\n    </testcase>\n";
  }
  xml << "  </testsuite>\n</testsuites>\n";
  return xml.str();
}
}
