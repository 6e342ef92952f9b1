/* test_interval_basic.c with the pair path's AVX2 forms (targets with FMA
   but without AVX-512, e.g. -march=haswell or Zen 3): the AVX-512 macros are
   taken back before the header is included, so it picks blendv, abs of the
   max and movmsk instead of the asm blend, vrangepd and mask compares. The
   pair path against the scalar path, the tightness and the step's edge
   cases then run on those forms. <immintrin.h> comes first: its target
   pragmas would define the macros again. */
#include <immintrin.h>
#undef __AVX512F__
#undef __AVX512VL__
#undef __AVX512DQ__
#undef __AVX512BW__
#undef __AVX512CD__
#include "test_interval_basic.c"
