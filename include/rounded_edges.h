/* rounded_edges.h — rounded corners and edges for triangle meshes (part of filigree)

   Rounding cylinders and spheres inside the convex edges and corners of a
   triangle mesh, found from a hit on the sharp mesh (Courtin et al. 2019).

   USAGE
     In exactly one C or C++ file:
         #define RE_IMPLEMENTATION
         #include "rounded_edges.h"
     Everywhere else just #include "rounded_edges.h".
   OPTIONS (define before including)
     RE_IMPLEMENTATION  emit the implementation in this translation unit
     RE_STATIC          make every function static (private to this file)
     RE_DEF             linkage of public functions (default extern)
     RE_ASSERT(c)       internal-invariant check (default assert)
     RE_MALLOC(sz,ctx) / RE_FREE(p,ctx)   allocator hooks (default malloc/free)
   CONVENTIONS
     See docs/conventions.md: results are re_result_t codes with RE_OK = 0,
     zero-initialised config structs mean defaults, queries are const,
     allocation-free and thread-safe.

   LICENSE
     MIT, see the end of this file.
*/
#ifndef FILIGREE_RE_H
#define FILIGREE_RE_H

#include <stddef.h>
#include <math.h>
#ifndef RE_DEF
#  ifdef RE_STATIC
#    if defined(__GNUC__) || defined(__clang__)
#      define RE_DEF static __attribute__((unused))
#    else
#      define RE_DEF static
#    endif
#  else
#    define RE_DEF extern
#  endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Result codes. RE_OK is 0; re_result_string() names each. */
typedef enum re_result_t {
    RE_OK = 0,
    RE_ERR_INVALID_ARG,   /* a NULL pointer or an out-of-range parameter */
    RE_ERR_OUT_OF_MEMORY, /* the allocator hook returned NULL */
    RE_RESULT_COUNT_
} re_result_t;

/* A human-readable name for a result code; never NULL. */
RE_DEF const char *re_result_string(re_result_t r);

/* ==== [section: baselines] (owned by the baselines/example helper) ==== */
/* ==== [end section: baselines] ==== */

#ifdef __cplusplus
}
#endif

#endif /* FILIGREE_RE_H */

/* ======================================================================== */
/*                              IMPLEMENTATION                              */
/* ======================================================================== */
#ifdef RE_IMPLEMENTATION
#ifndef FILIGREE_RE_IMPLEMENTATION_DONE
#define FILIGREE_RE_IMPLEMENTATION_DONE

#ifndef RE_ASSERT
#  include <assert.h>
#  define RE_ASSERT(c) assert(c)
#endif
#if defined(RE_MALLOC) != defined(RE_FREE)
#  error "define both RE_MALLOC and RE_FREE, or neither"
#endif
#ifndef RE_MALLOC
#  include <stdlib.h>
#  define RE_MALLOC(sz, ctx) ((void)(ctx), malloc(sz))
#  define RE_FREE(p, ctx) ((void)(ctx), free(p))
#endif

#ifdef __cplusplus
extern "C" {
#endif

RE_DEF const char *re_result_string(re_result_t r)
{
    switch (r) {
    case RE_OK: return "ok";
    case RE_ERR_INVALID_ARG: return "invalid argument";
    case RE_ERR_OUT_OF_MEMORY: return "out of memory";
    case RE_RESULT_COUNT_: break;
    }
    return "unknown result";
}

/* ==== [section: baselines] (owned by the baselines/example helper) ==== */
/* ==== [end section: baselines] ==== */

#ifdef __cplusplus
}
#endif

#endif /* FILIGREE_RE_IMPLEMENTATION_DONE */
#endif /* RE_IMPLEMENTATION */

/*
MIT License

Copyright (c) 2026 the filigree authors

Permission is hereby granted, free of charge, to any person obtaining a copy of
this software and associated documentation files (the "Software"), to deal in
the Software without restriction, including without limitation the rights to
use, copy, modify, merge, publish, distribute, sublicense, and/or sell copies
of the Software, and to permit persons to whom the Software is furnished to do
so, subject to the following conditions:

The above copyright notice and this permission notice shall be included in all
copies or substantial portions of the Software.

THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE
AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER
LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM,
OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE
SOFTWARE.
*/
