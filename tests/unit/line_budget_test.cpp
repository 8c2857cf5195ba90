// A log's budget of lines a minute (core/access/line_budget.hpp), the
// arithmetic of the log gates and of the command log: within a minute at
// most the budget, the rest counted and told once when the minute ends.
#include "access/line_budget.hpp"

#include <gtest/gtest.h>

namespace rotord::access {
namespace {

TEST(LineBudget, AMinuteWritesItsBudgetAndTellsTheRestOnceWhenItEnds) {
  LineBudget budget(3);
  int written = 0;
  for (int n = 0; n < 10; ++n) written += budget.admit(1000 + n) ? 1 : 0;
  EXPECT_EQ(written, 3);
  EXPECT_EQ(budget.take_over(60999), 0u);  // the minute (from the first line) is not over
  EXPECT_EQ(budget.take_over(61000), 7u);
  EXPECT_EQ(budget.take_over(61000), 0u);  // told once
  EXPECT_TRUE(budget.admit(61000));        // a new minute, a new budget
}

TEST(LineBudget, CountedLinesJoinTheRestAndAnEarlyRollStartsTheMinute) {
  LineBudget budget(1);
  budget.roll(0);  // the minute begins at 0, not at the first line
  EXPECT_TRUE(budget.admit(59000));
  EXPECT_FALSE(budget.admit(59001));
  budget.count_over(5);  // a summary's lines, over the budget
  EXPECT_EQ(budget.take_over(60000), 6u);
  EXPECT_TRUE(budget.admit(60000));
}

}  // namespace
}  // namespace rotord::access
