/* test_interval_basic.c on the code a default x86-64 build compiles (gcc
   -O2, no -march; see test_interval_props_nofma.c): bad input, division
   cases, the tightness of + - * / sqrt sqr against __float128 with the
   bit-pattern outward step, and the step's edge cases
   (pair_path_matches_scalar says SKIPPED here). */
#undef __FMA__
#include "test_interval_basic.c"
