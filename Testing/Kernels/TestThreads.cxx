// Thread-count policy of the kernels (ShockTypes.h): small inputs get fewer threads,
// large ones all that were asked for, and never fewer than one.
#include "ShockTypes.h"

#include <gtest/gtest.h>

namespace
{
TEST(ThreadsForWork, SmallWorkGetsOneThread)
{
  EXPECT_EQ(shock::ThreadsForWork(8, 0), 1);
  EXPECT_EQ(shock::ThreadsForWork(8, 64 * 48), 1);
  EXPECT_EQ(shock::ThreadsForWork(8, shock::MinimumWorkPerThread - 1), 1);
}

TEST(ThreadsForWork, GrowsWithWorkUpToTheRequest)
{
  const std::int64_t unit = shock::MinimumWorkPerThread;
  EXPECT_EQ(shock::ThreadsForWork(8, 2 * unit), 2);
  EXPECT_EQ(shock::ThreadsForWork(8, 5 * unit + unit / 2), 5);
  EXPECT_EQ(shock::ThreadsForWork(8, 1000 * unit), 8);
  EXPECT_EQ(shock::ThreadsForWork(3, 1000 * unit), 3);
}

TEST(ThreadsForWork, ZeroMeansTheMachineCapped)
{
  const int all = shock::ResolveThreadCount(0);
  EXPECT_GE(all, 1);
  EXPECT_EQ(shock::ThreadsForWork(0, std::int64_t(1) << 40), all);
  EXPECT_EQ(shock::ThreadsForWork(0, 1), 1);
}
}
