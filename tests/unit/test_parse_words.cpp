// The word parsing of the code compiled into both engines (src-plugin/parse_words.h).
#include "parse_words.h"

#include <gtest/gtest.h>

using tbags::to_number;
using tbags::words;

TEST(ParseWords, WholeFiniteNumbersOnly)
{
  double x = 0.0;
  EXPECT_TRUE(to_number("1e-3", x));
  EXPECT_DOUBLE_EQ(x, 1e-3);
  EXPECT_TRUE(to_number("-42", x));
  EXPECT_DOUBLE_EQ(x, -42.0);
  for (const char *bad : {"", "1e-3x", "x", "nan", "inf", "1e999", "0.5 "}) EXPECT_FALSE(to_number(bad, x)) << bad;
}

TEST(ParseWords, WordsWithoutComment)
{
  EXPECT_EQ(words("  N 3  # rows"), (std::vector<std::string>{"N", "3"}));
  EXPECT_TRUE(words("# only a comment").empty());
  EXPECT_EQ(words("1\t0.5  2e3"), (std::vector<std::string>{"1", "0.5", "2e3"}));
}
