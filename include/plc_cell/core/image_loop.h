#pragma once
// A loop over a whole I/O image (256 points, at every scan) compiled twice on x86-64:
// for AVX2, chosen once by the loader where the CPU has it (an ifunc), and for the
// baseline. The AVX2 copy does 32 points an instruction instead of 16.
//
// Not under a sanitizer: the loader runs the ifunc's resolver before the sanitizer's
// runtime is up, and ThreadSanitizer then crashes at start.
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define PLC_CELL_SANITIZED 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define PLC_CELL_SANITIZED 1
#endif

#if defined(__x86_64__) && defined(__GNUC__) && !defined(PLC_CELL_SANITIZED)
#define PLC_CELL_IMAGE_LOOP __attribute__((target_clones("avx2", "default")))
#else
#define PLC_CELL_IMAGE_LOOP
#endif
