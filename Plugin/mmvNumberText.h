/**
 * Parsing of numbers typed into the Multi-Material Editor's fields, free of
 * Qt so it can be unit-tested (Testing/Cxx/TestNumberText.cxx).
 *
 * Qt's QDoubleSpinBox accepts only fixed notation and drops the characters
 * it does not expect, so "1e9" became 19. This accepts what strtod accepts in
 * the C locale (fixed and exponent notation, surrounding blanks), refuses
 * NaN, infinities and trailing garbage, and tells a value outside the
 * field's range apart, so the editor can refuse it visibly.
 */
#ifndef mmvNumberText_h
#define mmvNumberText_h

#include <cctype>
#include <charconv>
#include <cmath>
#include <string>
#include <system_error>

namespace mmv
{
enum class NumberTextState
{
  Acceptable,   // a finite number within [min, max]
  Intermediate, // could still become a number: "", "-", "1e", "2.5e-"
  OutOfRange,   // a finite number outside [min, max] (Value holds it)
  Invalid       // not a number and cannot become one: "abc", "1e9x", "nan"
};

struct NumberText
{
  NumberTextState State = NumberTextState::Invalid;
  double Value = 0.0;
};

/// Whether `s` (no blanks) is a prefix of a number that a few more
/// characters could complete: sign, digits, one point, one exponent with
/// its own sign.
inline bool IsNumberPrefix(const std::string& s)
{
  size_t i = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-'))
  {
    ++i;
  }
  bool digits = false, point = false;
  for (; i < s.size() && (std::isdigit(static_cast<unsigned char>(s[i])) || s[i] == '.'); ++i)
  {
    if (s[i] == '.')
    {
      if (point)
      {
        return false;
      }
      point = true;
    }
    else
    {
      digits = true;
    }
  }
  if (i == s.size())
  {
    return true;
  }
  if (!digits || (s[i] != 'e' && s[i] != 'E'))
  {
    return false;
  }
  ++i;
  if (i < s.size() && (s[i] == '+' || s[i] == '-'))
  {
    ++i;
  }
  for (; i < s.size(); ++i)
  {
    if (!std::isdigit(static_cast<unsigned char>(s[i])))
    {
      return false;
    }
  }
  return true;
}

/// Parses `text` as a number for a field that accepts [min, max].
inline NumberText ParseNumberText(const std::string& text, double min, double max)
{
  size_t first = 0, last = text.size();
  while (first < last && std::isspace(static_cast<unsigned char>(text[first])))
  {
    ++first;
  }
  while (last > first && std::isspace(static_cast<unsigned char>(text[last - 1])))
  {
    --last;
  }
  const std::string s = text.substr(first, last - first);
  NumberText result;
  // from_chars is locale-independent (ParaView's locale must not turn "0.5"
  // into 5); it takes no leading '+', so that is skipped here ("+-5" stays
  // invalid).
  const size_t start = (!s.empty() && s[0] == '+') ? 1 : 0;
  const bool signAfterPlus = start == 1 && s.size() > 1 && (s[1] == '-' || s[1] == '+');
  const char* end = s.data() + s.size();
  double value = 0.0;
  const auto parsed = std::from_chars(s.data() + start, end, value);
  const bool whole = !signAfterPlus && parsed.ptr == end;
  const bool letters = s.find_first_of("nNiI") != std::string::npos; // nan, inf
  if (whole && !letters && parsed.ec == std::errc::result_out_of_range)
  {
    // "1e999" is a number too large for a double; "1e-999" one too small.
    const size_t e = s.find_first_of("eE");
    const bool tiny = e != std::string::npos && e + 1 < s.size() && s[e + 1] == '-';
    value = tiny ? 0.0 : (s[0] == '-' ? -HUGE_VAL : HUGE_VAL);
  }
  if (whole && !letters &&
    (parsed.ec == std::errc() || parsed.ec == std::errc::result_out_of_range))
  {
    result.Value = value;
    result.State = (std::isfinite(value) && value >= min && value <= max)
      ? NumberTextState::Acceptable
      : NumberTextState::OutOfRange;
    return result;
  }
  result.State = IsNumberPrefix(s) ? NumberTextState::Intermediate : NumberTextState::Invalid;
  return result;
}
}

#endif
