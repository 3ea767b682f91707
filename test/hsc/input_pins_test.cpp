// The scan's look at X0-X15: which pins with no analytic driver the simulation or a topic
// changed since the last scan (HscUnit::before_inputs), all sixteen compared at once.
#include <gtest/gtest.h>

#include <array>

#include "plc_cell/hsc/input_pins.h"
#include "plc_cell/hsc/pulse_source.h"

namespace plc_cell {
namespace hsc {
namespace {

using Terminals = std::array<uint8_t, 16>;

TEST(InputPins, NoChangeIsNoBit) {
  InputPins pins{HscConfig()};
  Terminals in{};
  EXPECT_EQ(pins.undriven_changes(in.data()), 0u);
}

TEST(InputPins, EachChangedUndrivenPinIsItsBit) {
  InputPins pins{HscConfig()};
  Terminals in{};
  in[0] = in[7] = in[8] = in[15] = 1;
  EXPECT_EQ(pins.undriven_changes(in.data()), (1u << 0) | (1u << 7) | (1u << 8) | (1u << 15));
  pins.set_raw(7, true);
  pins.set_raw(15, true);
  EXPECT_EQ(pins.undriven_changes(in.data()), (1u << 0) | (1u << 8));
  in[0] = in[8] = 0;
  EXPECT_EQ(pins.undriven_changes(in.data()), 0u);
  in[15] = 0;  // back OFF: a change too
  EXPECT_EQ(pins.undriven_changes(in.data()), 1u << 15);
}

TEST(InputPins, ADrivenPinIsNeverAnExternalChangeUntilItsSourceGoes) {
  InputPins pins{HscConfig()};
  PulseSource encoder("encoder", 3, 12);
  pins.bind(&encoder, 3, 12);
  EXPECT_EQ(pins.driven_mask(), (1u << 3) | (1u << 12));
  Terminals in{};
  in[3] = in[12] = 1;  // the source's own levels, set by the unit
  in[5] = 1;
  EXPECT_EQ(pins.undriven_changes(in.data()), 1u << 5);
  in[5] = 0;
  EXPECT_EQ(pins.undriven_changes(in.data()), 0u);
  pins.unbind(&encoder);
  EXPECT_EQ(pins.driven_mask(), 0u);
  EXPECT_EQ(pins.undriven_changes(in.data()), (1u << 3) | (1u << 12));
}

}  // namespace
}  // namespace hsc
}  // namespace plc_cell
