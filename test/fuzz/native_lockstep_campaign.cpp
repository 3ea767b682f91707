// A lockstep campaign without libFuzzer (docs/testing.md, "Native engine against the
// interpreter"): feeds native_lockstep_fuzz.cpp's target with pseudo-random inputs from a
// seed, so that a long campaign runs at the optimised build's speed and splits over
// processes by seed. A difference aborts there with the program (as in the fuzz target).
//
//   native_lockstep_campaign <seed> <programs>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s <seed> <programs>\n", argv[0]);
    return 2;
  }
  uint64_t s = std::strtoull(argv[1], nullptr, 0);
  const uint64_t programs = std::strtoull(argv[2], nullptr, 0);
  auto next = [&s] {  // splitmix64
    uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  };
  std::vector<uint8_t> input;
  const auto t0 = std::chrono::steady_clock::now();
  for (uint64_t n = 1; n <= programs; ++n) {
    input.resize(64 + next() % 4033);  // 64 to 4096 bytes, as the fuzz target's -max_len
    for (uint8_t& b : input) b = static_cast<uint8_t>(next());
    LLVMFuzzerTestOneInput(input.data(), input.size());
    if (n % 10000 == 0 || n == programs) {
      const double s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::printf("%llu programs, no difference, %.0f s, %.0f programs/s\n", static_cast<unsigned long long>(n), s_,
                  n / s_);
      std::fflush(stdout);
    }
  }
  return 0;
}
