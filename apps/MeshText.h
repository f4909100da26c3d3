#pragma once
// What the strict checks of text mesh files (OBJ, ASCII PLY and STL) share: lines with their
// numbers, words, numbers read over their whole word, and the count of what a reader ignores.
// VTK 9.1's readers read numbers as atof and istream do: "1.0abc" as 1, "abc" as 0 or as the
// previous value, "nan" as NaN, without a word. Read here first, such a file is refused.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace shadelab::app
{
/// A text, line by line: each line without its "\n" (a "\r" before it stays), numbered from
/// the number given for the first.
class TextLines
{
public:
  explicit TextLines(std::string_view text, long long firstNumber = 1)
    : rest_(text)
    , number_(firstNumber - 1)
  {
  }

  /// The next line, or false at the end of the text.
  bool next(std::string_view& line)
  {
    if (rest_.empty())
    {
      return false;
    }
    const std::size_t end = rest_.find('\n');
    ended_ = end != std::string_view::npos;
    line = rest_.substr(0, end);
    rest_.remove_prefix(ended_ ? end + 1 : rest_.size());
    ++number_;
    return true;
  }
  /// The number of the line next() returned last.
  long long number() const { return number_; }
  /// Whether that line ended in "\n" (the last line of a file may not).
  bool ended() const { return ended_; }
  /// The text after that line.
  std::string_view rest() const { return rest_; }

private:
  std::string_view rest_;
  long long number_;
  bool ended_ = false;
};

/// The separators of C's isspace, with which VTK's OBJ and STL readers split words.
inline bool isSpace(char c)
{
  return c == ' ' || (c >= '\t' && c <= '\r');
}

/// The separators of vtkPLY's get_words.
inline bool isPlySpace(char c)
{
  return c == ' ' || c == '\t' || c == '\r';
}

/// Takes the next word off the front of text: the characters before the next separator, after
/// any separators. False when only separators are left.
template<typename IsSeparator>
bool nextWord(std::string_view& text, std::string_view& word, IsSeparator isSeparator)
{
  std::size_t start = 0;
  while (start < text.size() && isSeparator(text[start]))
  {
    ++start;
  }
  if (start == text.size())
  {
    text = {};
    return false;
  }
  std::size_t end = start + 1;
  while (end < text.size() && !isSeparator(text[end]))
  {
    ++end;
  }
  word = text.substr(start, end - start);
  text.remove_prefix(end);
  return true;
}

/// text after its leading separators.
template<typename IsSeparator>
std::string_view trimmedStart(std::string_view text, IsSeparator isSeparator)
{
  std::size_t start = 0;
  while (start < text.size() && isSeparator(text[start]))
  {
    ++start;
  }
  return text.substr(start);
}

/// Why a word is not the number it should be.
enum class NumberFault
{
  None,
  NotANumber, // not a number over its whole length
  NotFinite,  // "nan", "inf", or beyond the range of a double
  NotAnInteger,
  OutOfRange, // a number, beyond the range the caller allows
};

/// word as a real number over its whole length: an optional sign, digits with an optional
/// point and exponent, as strtod reads them, but no hexadecimal, leading space or trailing
/// junk. A value below double's smallest is rounded as strtod rounds it.
NumberFault readReal(std::string_view word, double& value);

/// readReal, and within the range of a float, where VTK's readers store coordinates.
NumberFault readFloat(std::string_view word, double& value);

/// word as a decimal integer over its whole length, with an optional sign; OutOfRange beyond
/// the range of a long long.
NumberFault readInteger(std::string_view word, long long& value);

/// "'word'": quoted for a message, made printable and cut short.
std::string quotedWord(std::string_view word);

/// The range of the floats in which VTK's readers store coordinates, for numberMessage.
extern const char* const floatRange;

/// The message for a word that is not the number it should be: "'abc' is not a number (what)";
/// for OutOfRange, "'1e39' is beyond <range> (what)".
std::string numberMessage(NumberFault fault, std::string_view word, const std::string& what, const std::string& range);

/// "line N: message".
std::string atLine(long long number, const std::string& message);

/// The line of text where a zero byte is, or 0: text has none. A zero byte ends a C string,
/// and with it what fgets-based readers see of the line.
long long lineWithZeroByte(std::string_view text);

/// Statements of a file that its reader skips, counted for the command's summary.
class IgnoredStatements
{
public:
  /// Counts one statement of keyword, which holds what (e.g. "smoothing groups").
  void add(std::string_view keyword, const char* what);
  /// "12 's', 1 'o' statements (smoothing groups and object names are not read)", or "".
  std::string describe() const;

private:
  struct Count
  {
    std::string keyword;
    const char* what;
    long long n;
  };
  std::vector<Count> counts_; // in the order first met
};
}
