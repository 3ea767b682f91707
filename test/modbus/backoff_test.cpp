// The reconnection back-off shared by the Modbus and FATEK bridges (io/backoff.h).
#include <gtest/gtest.h>

#include <vector>

#include "plc_cell/io/backoff.h"

namespace plc_cell {
namespace {

std::vector<double> failures(Backoff& b, int n) {
  std::vector<double> v;
  for (int i = 0; i < n; ++i) v.push_back(b.failed());
  return v;
}

TEST(Backoff, DoublesFromTheMinimumUpToTheMaximum) {
  Backoff b(0.5, 10.0);
  EXPECT_EQ(failures(b, 8), (std::vector<double>{0.5, 1, 2, 4, 8, 10, 10, 10}));
}

TEST(Backoff, ASuccessStartsAgainFromTheMinimum) {
  Backoff b(0.1, 10.0);
  failures(b, 5);
  b.reset();
  EXPECT_EQ(failures(b, 3), (std::vector<double>{0.1, 0.2, 0.4}));
}

TEST(Backoff, TheFirstDelayIsTheMinimumEvenAboveTheMaximum) {
  // As the bridges always did: ~max_backoff below the first delay caps the later ones only.
  Backoff b(0.1, 0.05);
  EXPECT_EQ(failures(b, 3), (std::vector<double>{0.1, 0.05, 0.05}));
}

}  // namespace
}  // namespace plc_cell
