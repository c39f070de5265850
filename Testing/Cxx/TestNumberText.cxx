// mmv::ParseNumberText, the parser behind the Multi-Material Editor's numeric
// fields (Plugin/mmvNumberText.h): exponent notation parses to the exact
// value ("1e9" typed into Shininess must not become 19), out-of-range
// numbers are told apart so the editor refuses them, and text that cannot
// become a number is invalid.
#include "mmvNumberText.h"

#include <gtest/gtest.h>

namespace mmvtest
{
namespace
{
using mmv::NumberTextState;

NumberTextState StateOf(const char* text, double min = 0.0, double max = 1.0e4)
{
  return mmv::ParseNumberText(text, min, max).State;
}

TEST(NumberText, ExponentNotationParsesExactly)
{
  const struct
  {
    const char* Text;
    double Value;
  } cases[] = { { "2.5e-1", 0.25 }, { "1e3", 1000.0 }, { "1E2", 100.0 }, { "  7.5e+0 ", 7.5 },
    { "+3e1", 30.0 }, { ".5", 0.5 }, { "12", 12.0 }, { "0", 0.0 }, { "1e-999", 0.0 } };
  for (const auto& c : cases)
  {
    const mmv::NumberText parsed = mmv::ParseNumberText(c.Text, 0.0, 1.0e4);
    EXPECT_EQ(parsed.State, NumberTextState::Acceptable) << c.Text;
    EXPECT_DOUBLE_EQ(parsed.Value, c.Value) << c.Text;
  }
}

TEST(NumberText, OutOfRangeIsReportedWithTheValue)
{
  // Shininess accepts [0, 1e4]: "1e9" is a billion, refused, never 19.
  const mmv::NumberText big = mmv::ParseNumberText("1e9", 0.0, 1.0e4);
  EXPECT_EQ(big.State, NumberTextState::OutOfRange);
  EXPECT_DOUBLE_EQ(big.Value, 1.0e9);
  const mmv::NumberText negative = mmv::ParseNumberText("-5", 0.0, 1.0e3);
  EXPECT_EQ(negative.State, NumberTextState::OutOfRange);
  EXPECT_DOUBLE_EQ(negative.Value, -5.0);
  EXPECT_EQ(StateOf("1e999"), NumberTextState::OutOfRange);
  EXPECT_EQ(StateOf("-1e999"), NumberTextState::OutOfRange);
  // The bounds themselves are accepted; anisotropy's range is signed.
  EXPECT_EQ(StateOf("1e4"), NumberTextState::Acceptable);
  EXPECT_EQ(StateOf("-0.99", -0.99, 0.99), NumberTextState::Acceptable);
  EXPECT_EQ(StateOf("-9.9e-1", -0.99, 0.99), NumberTextState::Acceptable);
  EXPECT_EQ(StateOf("-1", -0.99, 0.99), NumberTextState::OutOfRange);
}

TEST(NumberText, UnfinishedTextIsIntermediate)
{
  for (const char* text : { "", " ", "-", "+", ".", "1e", "2.5e-", "1E+", "-." })
  {
    EXPECT_EQ(StateOf(text), NumberTextState::Intermediate) << '"' << text << '"';
  }
}

TEST(NumberText, GarbageNaNAndInfinityAreInvalid)
{
  for (const char* text : { "abc", "1e9x", "nan", "NaN", "inf", "-inf", "1.2.3", "1e2e3", "+-5",
         "1 2", "0x10", "e5", "1,5" })
  {
    EXPECT_EQ(StateOf(text), NumberTextState::Invalid) << '"' << text << '"';
  }
}
}
}
