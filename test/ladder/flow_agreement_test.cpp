// Power flow against the scan (on the default engine): random networks of X/M contacts in
// series, parallel and nested LD blocks (every contact form), feeding OUT / OUT NOT coils
// on Y, some on branches; after every scan the powered state of each coil must be the Y
// value the scan wrote.
#include <random>
#include <sstream>
#include <string>

#include "ladder_fixture.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/ladder/flow.h"

namespace plc_cell {
namespace ladder {
namespace test {

namespace {

class Generator {
 public:
  explicit Generator(unsigned seed) : rng_(seed) {}

  std::string program() {
    std::ostringstream il;
    const int nets = pick(1, 3);
    for (int k = 0; k < nets; ++k) network(il);
    il << "END\n";
    return il.str();
  }

 private:
  int pick(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(rng_); }

  std::string contact() {
    static const char* const forms[] = {"", "NOT ", "TU ", "TD "};
    const std::string area = pick(0, 1) ? "X" : "M";
    return std::string(forms[pick(0, 3)]) + area + std::to_string(pick(0, 5));
  }

  // A block that starts with `first` (ORG or LD) and leaves its value as the result.
  void block(std::ostream& il, const std::string& first, int depth) {
    il << first << ' ' << contact() << '\n';
    const int more = depth > 0 ? pick(0, 3) : pick(0, 1);
    for (int k = 0; k < more; ++k) {
      const bool and_ = pick(0, 1);
      if (depth > 0 && pick(0, 2) == 0) {
        block(il, "LD", depth - 1);
        il << (and_ ? "ANDLD" : "ORLD") << '\n';
      } else {
        il << (and_ ? "AND " : "OR ") << contact() << '\n';
      }
    }
  }

  void coil(std::ostream& il) { il << (pick(0, 3) ? "OUT Y" : "OUT NOT Y") << next_y_++ << '\n'; }

  void network(std::ostream& il) {
    block(il, "ORG", pick(0, 3));
    coil(il);
    const int branches = pick(0, 2);
    for (int b = 0; b < branches; ++b) {
      if (pick(0, 1)) {
        il << "AND " << contact() << '\n';
      } else {
        block(il, "LD", pick(0, 2));
        il << "ANDLD\n";
      }
      for (int c = pick(1, 2); c > 0; --c) coil(il);
    }
  }

  std::mt19937 rng_;
  int next_y_ = 0;
};

// The values of every address the layout reads, as the monitor reads them between scans.
Values read_frame(const Plc& plc, const Layout& l) {
  Values v;
  for (const Network& n : l.networks)
    for (const Address& a : addresses(n)) v.set(a, plc.read(a, 1).at(0));
  return v;
}

}  // namespace

TEST(LadderPowerFlowAgreement, CoilsArePoweredExactlyWhenTheScanDrivesThem) {
  int coils_checked = 0, powered = 0;
  for (unsigned seed = 1; seed <= 300; ++seed) {
    Generator gen(seed);
    const std::string il = gen.program();
    SCOPED_TRACE("seed " + std::to_string(seed) + ":\n" + il);
    const Layout l = lay(il);
    for (const Network& n : l.networks) expect_a_sound_grid(n);
    Plc plc;
    plc.load_program_text(il, "random.il");
    ASSERT_TRUE(plc.set_mode(RunMode::Run));
    std::mt19937 inputs(seed * 7919u);
    Values prev = read_frame(plc, l);  // before the first scan: the edge memories' start
    for (int scan = 0; scan < 24; ++scan) {
      for (uint32_t k = 0; k < 6; ++k) {
        plc.set_input(k, (inputs() & 1u) != 0);
        plc.write(Address{Area::M, Width::Bit, k}, {static_cast<uint32_t>(inputs() & 1u)});
      }
      plc.scan(1000u * scan);
      const Values now = read_frame(plc, l);
      for (const Network& n : l.networks) {
        ASSERT_TRUE(n.drawable) << n.reason;
        const Flow f = flow(n, now.lookup(), prev.lookup());
        for (const Element& e : n.elements) {
          if (e.type != "coil") continue;
          const bool on = std::find(f.on.begin(), f.on.end(), e.id) != f.on.end();
          const bool y = now.get(parse_address(e.address)) != 0;
          ASSERT_EQ(e.form == "out" ? on : !on, y) << "scan " << scan << ", " << e.address;
          ++coils_checked;
          powered += on;
        }
      }
      prev = now;
    }
  }
  // Both answers occur often enough for the comparison to mean something.
  EXPECT_GT(powered, coils_checked / 10);
  EXPECT_LT(powered, coils_checked - coils_checked / 10);
}

}  // namespace test
}  // namespace ladder
}  // namespace plc_cell
