// fix table/time's table (law/time_table.h): the value at a time against exact answers, and each
// bad row or table refused with what is wrong.
#include "law/time_table.h"
#include "parse_words.h"

#include <gtest/gtest.h>

using tbags::TimeTable;

static TimeTable table(std::vector<std::vector<std::string>> rows, std::string &what)
{
  TimeTable t;
  for (const auto &r : rows) {
    what = tbags::add_time_row(t, r, tbags::to_number);
    if (!what.empty()) break;
  }
  return t;
}

TEST(TimeTable, LinearBetweenRowsHeldOutside)
{
  std::string what;
  const auto t = table({{"0", "0"}, {"0.5", "2"}, {"1.5", "-1"}}, what);
  ASSERT_EQ(what, "");
  EXPECT_EQ(tbags::check_time_table(t, 0.0), "");
  EXPECT_DOUBLE_EQ(t.at(-1.0), 0.0);        // before time 0: the first value
  EXPECT_DOUBLE_EQ(t.at(0.25), 1.0);
  EXPECT_DOUBLE_EQ(t.at(0.5), 2.0);
  EXPECT_DOUBLE_EQ(t.at(1.0), 0.5);         // 2 + (1.0 - 0.5) / 1.0 * (-3)
  EXPECT_DOUBLE_EQ(t.at(1.5), -1.0);
  EXPECT_DOUBLE_EQ(t.at(7.0), -1.0);        // after the last time: held, not extended
  EXPECT_DOUBLE_EQ(t.duration(), 1.5);
  EXPECT_DOUBLE_EQ(t.largest(), 2.0);
}

TEST(TimeTable, BadRowsAreRefusedSayingWhy)
{
  std::string what;
  table({{"0", "0", "1"}}, what);
  EXPECT_NE(what.find("two columns"), std::string::npos) << what;
  table({{"0", "abc"}}, what);
  EXPECT_NE(what.find("value 'abc' is not a finite number"), std::string::npos) << what;
  table({{"0", "nan"}}, what);
  EXPECT_NE(what.find("not a finite number"), std::string::npos) << what;
  table({{"0.1", "0"}}, what);
  EXPECT_NE(what.find("first time must be 0"), std::string::npos) << what;
  table({{"0", "0"}, {"1", "1"}, {"1", "2"}}, what);
  EXPECT_NE(what.find("does not increase"), std::string::npos) << what;
  table({{"0", "0"}, {"1", "1"}, {"0.5", "2"}}, what);
  EXPECT_NE(what.find("does not increase"), std::string::npos) << what;
}

TEST(TimeTable, ShortOrTooLargeTablesAreRefused)
{
  std::string what;
  auto t = table({{"0", "0"}}, what);
  EXPECT_EQ(tbags::check_time_table(t, 0.0), "needs at least two rows");
  t = table({{"0", "0"}, {"1", "-5.5"}}, what);
  EXPECT_EQ(tbags::check_time_table(t, 5.5), "");
  EXPECT_NE(tbags::check_time_table(t, 5.0).find("beyond the limit"), std::string::npos);
}
