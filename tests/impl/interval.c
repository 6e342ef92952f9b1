/* interval.h's implementation, compiled once per test build (normal, ASan+UBSan,
   clang) into that build's libfiligree.a. A test that does not define
   IV_IMPLEMENTATION links it from there; a test that needs its own copy
   (IV_NO_* switches, allocator hooks, or the iv__ internals) defines it,
   and the linker then takes nothing from this member. */
#define IV_IMPLEMENTATION
#include "interval.h"
