// asmjit's three DebugUtils functions, defined here so that the linker never takes them
// from Debian's libasmjit.a: that archive is built without -fPIC, and the one object that
// defines them (globals.cpp.o) refers to stderr in a way a shared library cannot hold
// ("relocation R_X86_64_PC32 against stderr"). Every other object of the archive links
// into libplc_cell_core.so as it is. The native engine reports errors by number.
#include <cstdio>
#include <cstdlib>

#include <asmjit/core.h>

ASMJIT_BEGIN_NAMESPACE
namespace DebugUtils {

const char* errorAsString(Error) noexcept { return "asmjit error"; }

void debugOutput(const char* str) noexcept { std::fputs(str, stderr); }

void assertionFailed(const char* file, int line, const char* msg) noexcept {
  std::fprintf(stderr, "asmjit assertion failed at %s:%d: %s\n", file, line, msg);
  std::abort();
}

}  // namespace DebugUtils
ASMJIT_END_NAMESPACE
