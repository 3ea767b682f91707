// Stands in for the fuzz suite when the tree was configured without clang++: the fuzz
// targets need libFuzzer, so they were not built. A missing check fails; it never skips.
#include <gtest/gtest.h>

TEST(Fuzz, ClangWasFound) {
  FAIL() << "clang++ was not found when this tree was configured, so the libFuzzer targets were not built. "
            "Install clang and libclang-rt-14-dev (make deps does) and configure again.";
}
