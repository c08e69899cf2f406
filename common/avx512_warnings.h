#pragma once
// GCC 12 warns of an uninitialized variable inside its own AVX-512 headers
// (the masked intrinsics' _mm512_undefined_* sources). The warning is not
// ours, but it fires where our code inlines those intrinsics, so a file
// that uses them silences it around its own code, and only there:
//   RC_AVX512_WARNINGS_OFF  (before <immintrin.h>)
//   ...
//   RC_AVX512_WARNINGS_ON   (after the last function that uses them)
// Clang has neither the warning nor its name, so both are empty there.
#if defined(__GNUC__) && !defined(__clang__)
#define RC_AVX512_WARNINGS_OFF                                                               \
  _Pragma("GCC diagnostic push") _Pragma("GCC diagnostic ignored \"-Wmaybe-uninitialized\"") \
      _Pragma("GCC diagnostic ignored \"-Wuninitialized\"")
#define RC_AVX512_WARNINGS_ON _Pragma("GCC diagnostic pop")
#else
#define RC_AVX512_WARNINGS_OFF
#define RC_AVX512_WARNINGS_ON
#endif
