/* grooves.h — grooved and scratched surfaces (part of filigree)

   Grooves as UV paths with polyline cross-sections, shaded exactly per pixel
   footprint with clipping, masking and shadowing (Bosch et al. 2006).

   USAGE
     In exactly one C or C++ file:
         #define GR_IMPLEMENTATION
         #include "grooves.h"
     Everywhere else just #include "grooves.h".
   OPTIONS (define before including)
     GR_IMPLEMENTATION  emit the implementation in this translation unit
     GR_STATIC          make every function static (private to this file)
     GR_DEF             linkage of public functions (default extern)
     GR_ASSERT(c)       internal-invariant check (default assert)
     GR_MALLOC(sz,ctx) / GR_FREE(p,ctx)   allocator hooks (default malloc/free)
   CONVENTIONS
     See docs/conventions.md: results are gr_result_t codes with GR_OK = 0,
     zero-initialised config structs mean defaults, queries are const,
     allocation-free and thread-safe.

   LICENSE
     MIT, see the end of this file.
*/
#ifndef FILIGREE_GR_H
#define FILIGREE_GR_H

#include <stddef.h>
#include <math.h>
#ifndef GR_DEF
#  ifdef GR_STATIC
#    if defined(__GNUC__) || defined(__clang__)
#      define GR_DEF static __attribute__((unused))
#    else
#      define GR_DEF static
#    endif
#  else
#    define GR_DEF extern
#  endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Result codes. GR_OK is 0; gr_result_string() names each. */
typedef enum gr_result_t {
    GR_OK = 0,
    GR_ERR_INVALID_ARG,   /* a NULL pointer or an out-of-range parameter */
    GR_ERR_OUT_OF_MEMORY, /* the allocator hook returned NULL */
    GR_RESULT_COUNT_
} gr_result_t;

/* A human-readable name for a result code; never NULL. */
GR_DEF const char *gr_result_string(gr_result_t r);

#ifdef __cplusplus
}
#endif

#endif /* FILIGREE_GR_H */

/* ======================================================================== */
/*                              IMPLEMENTATION                              */
/* ======================================================================== */
#ifdef GR_IMPLEMENTATION
#ifndef FILIGREE_GR_IMPLEMENTATION_DONE
#define FILIGREE_GR_IMPLEMENTATION_DONE

#ifndef GR_ASSERT
#  include <assert.h>
#  define GR_ASSERT(c) assert(c)
#endif
#if defined(GR_MALLOC) != defined(GR_FREE)
#  error "define both GR_MALLOC and GR_FREE, or neither"
#endif
#ifndef GR_MALLOC
#  include <stdlib.h>
#  define GR_MALLOC(sz, ctx) ((void)(ctx), malloc(sz))
#  define GR_FREE(p, ctx) ((void)(ctx), free(p))
#endif

#ifdef __cplusplus
extern "C" {
#endif

GR_DEF const char *gr_result_string(gr_result_t r)
{
    switch (r) {
    case GR_OK: return "ok";
    case GR_ERR_INVALID_ARG: return "invalid argument";
    case GR_ERR_OUT_OF_MEMORY: return "out of memory";
    case GR_RESULT_COUNT_: break;
    }
    return "unknown result";
}

#ifdef __cplusplus
}
#endif

#endif /* FILIGREE_GR_IMPLEMENTATION_DONE */
#endif /* GR_IMPLEMENTATION */

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
