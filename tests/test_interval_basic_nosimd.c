/* test_interval_basic.c on the portable scalar path (IV_NO_SIMD): bad
   input, division cases, the tightness of + - * / sqrt sqr against
   __float128 and the step's edge cases, for the code that targets without
   SSE4.1 + FMA run (pair_path_matches_scalar says SKIPPED here). */
#define IV_NO_SIMD
#include "test_interval_basic.c"
