/* frep.h — FRep solids and ray-surface root finding (part of filigree)

   Function-representation solids f(x) >= 0: primitives, R-functions, blends and
   space maps as an instruction tape, evaluated in points, intervals, affine
   forms and gradients; ray-surface intersection and polynomial solvers.

   USAGE
     In exactly one C or C++ file:
         #define FR_IMPLEMENTATION
         #include "frep.h"
     Everywhere else just #include "frep.h".
     With interval evaluation (the default) define IV_IMPLEMENTATION in one
     file too, or include interval.h there with it.
   OPTIONS (define before including)
     FR_IMPLEMENTATION  emit the implementation in this translation unit
     FR_STATIC          make every function static (private to this file)
     FR_DEF             linkage of public functions (default extern)
     FR_ASSERT(c)       internal-invariant check (default assert)
     FR_MALLOC(sz,ctx) / FR_FREE(p,ctx)   allocator hooks (default malloc/free)
     FR_NO_INTERVAL      leave out interval/affine evaluation (no interval.h)
     FR_NO_PARSER        leave out the HyperFun-subset text front end
   CONVENTIONS
     See docs/conventions.md: results are fr_result_t codes with FR_OK = 0,
     zero-initialised config structs mean defaults, queries are const,
     allocation-free and thread-safe.

   LICENSE
     MIT, see the end of this file.
*/
#ifndef FILIGREE_FR_H
#define FILIGREE_FR_H

#include <stddef.h>
#include <math.h>
#ifndef FR_DEF
#  ifdef FR_STATIC
#    if defined(__GNUC__) || defined(__clang__)
#      define FR_DEF static __attribute__((unused))
#    else
#      define FR_DEF static
#    endif
#  else
#    define FR_DEF extern
#  endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Result codes. FR_OK is 0; fr_result_string() names each. */
typedef enum fr_result_t {
    FR_OK = 0,
    FR_ERR_INVALID_ARG,   /* a NULL pointer or an out-of-range parameter */
    FR_ERR_OUT_OF_MEMORY, /* the allocator hook returned NULL */
    FR_RESULT_COUNT_
} fr_result_t;

/* A human-readable name for a result code; never NULL. */
FR_DEF const char *fr_result_string(fr_result_t r);

/* ==== [section: model] declarations: tape, primitives, operations, evaluation, parser ==== */

/* ==== [end section: model] ==== */

/* ==== [section: solvers] declarations: polynomial solvers ==== */

/* ==== [end section: solvers] ==== */

/* ==== [section: trace] declarations: ray-surface intersection ==== */

/* ==== [end section: trace] ==== */


#ifdef __cplusplus
}
#endif

#endif /* FILIGREE_FR_H */

/* ======================================================================== */
/*                              IMPLEMENTATION                              */
/* ======================================================================== */
#ifdef FR_IMPLEMENTATION
#ifndef FILIGREE_FR_IMPLEMENTATION_DONE
#define FILIGREE_FR_IMPLEMENTATION_DONE

#ifndef FR_ASSERT
#  include <assert.h>
#  define FR_ASSERT(c) assert(c)
#endif
#if defined(FR_MALLOC) != defined(FR_FREE)
#  error "define both FR_MALLOC and FR_FREE, or neither"
#endif
#ifndef FR_MALLOC
#  include <stdlib.h>
#  define FR_MALLOC(sz, ctx) ((void)(ctx), malloc(sz))
#  define FR_FREE(p, ctx) ((void)(ctx), free(p))
#endif

#ifdef __cplusplus
extern "C" {
#endif

FR_DEF const char *fr_result_string(fr_result_t r)
{
    switch (r) {
    case FR_OK: return "ok";
    case FR_ERR_INVALID_ARG: return "invalid argument";
    case FR_ERR_OUT_OF_MEMORY: return "out of memory";
    case FR_RESULT_COUNT_: break;
    }
    return "unknown result";
}

/* ==== [section: model] implementation: tape, primitives, operations, evaluation, parser ==== */

/* ==== [end section: model] ==== */

/* ==== [section: solvers] implementation: polynomial solvers ==== */

/* ==== [end section: solvers] ==== */

/* ==== [section: trace] implementation: ray-surface intersection ==== */

/* ==== [end section: trace] ==== */


#ifdef __cplusplus
}
#endif

#endif /* FILIGREE_FR_IMPLEMENTATION_DONE */
#endif /* FR_IMPLEMENTATION */

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
