/* The containment properties of test_interval_props.c on the code a
   default x86-64 build compiles (gcc -O2, no -march): without __FMA__ the
   outward step is the bit-pattern one (iv__next_down_bits), the pair path
   and the arrays' fused loops are off. The tests are built with
   -march=native, so this file hides __FMA__ from the header (the compiler
   may still fuse, which the header survives: -ffp-contract=fast). 10^6
   interval and 10^6 affine cases. */
#undef __FMA__
#define IV_PROPS_CASES 1000000
#include "test_interval_props.c"
