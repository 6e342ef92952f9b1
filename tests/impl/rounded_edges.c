/* rounded_edges.h's implementation, compiled once per test build (normal, ASan+UBSan,
   clang) into that build's libfiligree.a. A test that does not define
   RE_IMPLEMENTATION links it from there; a test that needs its own copy
   (RE_NO_* switches, allocator hooks, or the re__ internals) defines it,
   and the linker then takes nothing from this member. */
#define RE_IMPLEMENTATION
#include "rounded_edges.h"
