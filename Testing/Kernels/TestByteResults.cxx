// Results written into 8-bit arrays (ShockTypes.h RoundAndClampBytes): clamped
// to [0, 255], rounded half away from zero as std::round, NaN as 0, whatever
// the position of a value in the array (eight at a time, then one by one).
#include "ShockTypes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace
{
/// The rule, from its statement: NaN is 0; otherwise clamp, then std::round.
unsigned char Expected(double v)
{
  if (std::isnan(v))
  {
    return 0;
  }
  const double clamped = v < 0.0 ? 0.0 : (v > 255.0 ? 255.0 : v);
  return static_cast<unsigned char>(std::round(clamped));
}

TEST(ByteResults, AreClampedAndRoundedHalfAwayFromZeroAtEveryPosition)
{
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double below = std::nextafter(0.5, 0.0); // 0.49999999999999994
  std::vector<double> special = { nan, -nan, inf, -inf, -1e300, 1e300, -0.0, 0.0,
    std::numeric_limits<double>::denorm_min(), -0.5, -0.49, below, 0.5, 1.5, 2.5,
    std::nextafter(2.5, 0.0), 127.5, 254.5, std::nextafter(254.5, 0.0), 254.9999, 255.0,
    255.4, 255.5, 256.0, 1e10, -1e10, 3.0, 17.25, 99.75 };
  std::mt19937 random(11);
  std::uniform_real_distribution<double> any(-20.0, 280.0);
  std::uniform_int_distribution<int> integer(-3, 260);
  for (int k = 0; k < 200; ++k)
  {
    special.push_back(any(random));
    special.push_back(integer(random) + 0.5); // exact halves
  }
  // Every value at every position modulo 8, and every tail length.
  for (size_t shift = 0; shift < 8; ++shift)
  {
    std::vector<double> in(shift, 1.0);
    in.insert(in.end(), special.begin(), special.end());
    for (size_t length = in.size() - 9; length <= in.size(); ++length)
    {
      std::vector<unsigned char> out(length + 1, 77); // one guard byte
      shock::RoundAndClampBytes(in.data(), static_cast<std::int64_t>(length), out.data());
      for (size_t i = 0; i < length; ++i)
      {
        ASSERT_EQ(out[i], Expected(in[i])) << "value " << in[i] << " at " << i << " of " << length;
      }
      EXPECT_EQ(out[length], 77) << "wrote past the end, length " << length;
    }
  }
  // Something is rounded, not truncated.
  unsigned char one = 0;
  shock::RoundAndClampBytes(&special[12], 1, &one); // 0.5
  EXPECT_EQ(one, 1);
}
}
