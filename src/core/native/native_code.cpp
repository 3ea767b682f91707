#include "plc_cell/core/native/native_code.h"

#include <sys/mman.h>

#include <asmjit/x86.h>

#include "run_emitter.h"

namespace plc_cell::native {

using namespace asmjit;

NativeCode::NativeCode() = default;
NativeCode::~NativeCode() { release(); }

void NativeCode::release() {
  if (pages_) munmap(pages_, size_);
  pages_ = nullptr;
  size_ = 0;
  runs_.clear();
  native_instructions_ = 0;
}

bool NativeCode::host_supported(std::string* why) {
  if (Environment::host().arch() == Arch::kX64) return true;
  *why = "the native engine generates x86-64 code only; this CPU is not x86-64";
  return false;
}

bool NativeCode::compile(const std::vector<Step>& steps, std::string* why) {
  release();
  if (!host_supported(why)) return false;

  std::vector<int> depth(steps.size() + 1, kUnknownDepth);
  std::vector<Run> runs;
  for (uint32_t i = 0; i < steps.size();) {
    const int d = depth[i];
    if (!is_template(steps[i], d)) {
      depth[i + 1] = depth_after(steps[i], d);
      ++i;
      continue;
    }
    uint32_t j = i;
    while (j < steps.size() && is_template(steps[j], depth[j])) {
      depth[j + 1] = depth_after(steps[j], depth[j]);
      ++j;
    }
    if (j - i >= kMinRun) runs.push_back(Run{i, j - i, depth[j], nullptr});
    i = j;
  }

  CodeHolder code;
  code.init(Environment::host());
  x86::Assembler a(&code);
  std::vector<Label> labels;
  labels.reserve(runs.size());
  for (const Run& r : runs) {
    labels.push_back(a.newLabel());
    a.align(AlignMode::kCode, 16);
    a.bind(labels.back());
    emit_run(a, steps, depth, r.first, r.first + r.length);
  }
  asmjit::Error err = code.flatten();
  if (!err) err = code.resolveUnresolvedLinks();
  if (err) {
    *why = std::string("code generation failed: ") + "asmjit error " + std::to_string(err);
    return false;
  }
  const size_t size = std::max<size_t>(code.codeSize(), 1);
  // Written while read+write, then read+execute: the pages are never both at once.
  void* pages = mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (pages == MAP_FAILED) {
    *why = "no memory for the native code";
    return false;
  }
  err = code.relocateToBase(reinterpret_cast<uint64_t>(pages));
  if (!err) err = code.copyFlattenedData(pages, size, CopySectionFlags::kPadSectionBuffer);
  if (err || mprotect(pages, size, PROT_READ | PROT_EXEC) != 0) {
    munmap(pages, size);
    *why = err ? std::string("code relocation failed: ") + "asmjit error " + std::to_string(err)
               : std::string("the native code could not be made executable");
    return false;
  }
  pages_ = pages;
  size_ = size;
  for (size_t k = 0; k < runs.size(); ++k) {
    runs[k].fn = reinterpret_cast<RunFn>(static_cast<char*>(pages) + code.labelOffsetFromBase(labels[k]));
    native_instructions_ += runs[k].length;
  }
  runs_ = std::move(runs);
  return true;
}

}  // namespace plc_cell::native
