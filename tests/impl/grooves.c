/* grooves.h's implementation, compiled once per test build (normal, ASan+UBSan,
   clang) into that build's libfiligree.a. A test that does not define
   GR_IMPLEMENTATION links it from there; a test that needs its own copy
   (GR_NO_* switches, allocator hooks, or the gr__ internals) defines it,
   and the linker then takes nothing from this member. */
#define GR_IMPLEMENTATION
#include "grooves.h"
