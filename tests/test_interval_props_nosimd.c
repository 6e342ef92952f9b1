/* The containment properties of test_interval_props.c on the portable
   scalar path (IV_NO_SIMD), which targets without SSE4.1 + FMA use: the
   same operations, inputs and __float128 references, 2*10^6 interval and
   2*10^6 affine cases (the pair path's own run has 10^7 each, and the two
   paths are compared endpoint for endpoint in test_interval_basic). */
#define IV_NO_SIMD
#define IV_PROPS_CASES 2000000
#include "test_interval_props.c"
