/* frep.h's implementation, compiled once per test build (normal, ASan+UBSan,
   clang) into that build's libfiligree.a. A test that does not define
   FR_IMPLEMENTATION links it from there; a test that needs its own copy
   (FR_NO_* switches, allocator hooks, or the fr__ internals) defines it,
   and the linker then takes nothing from this member. */
#define FR_IMPLEMENTATION
#include "frep.h"
