/* interval.h — rigorous interval and affine arithmetic (part of filigree)

   Interval enclosures that are guaranteed in the default rounding mode, and
   affine forms for tighter ranges along rays.

   USAGE
     In exactly one C or C++ file:
         #define IV_IMPLEMENTATION
         #include "interval.h"
     Everywhere else just #include "interval.h".
   OPTIONS (define before including)
     IV_IMPLEMENTATION  emit the implementation in this translation unit
     IV_STATIC          make every function static (private to this file)
     IV_DEF             linkage of public functions (default extern)
     IV_ASSERT(c)       internal-invariant check (default assert)
     IV_MALLOC(sz,ctx) / IV_FREE(p,ctx)   allocator hooks (default malloc/free)
     IV_NO_AFFINE        leave out affine arithmetic
     IV_FAST             round-to-nearest endpoints: faster, NOT rigorous
   CONVENTIONS
     See docs/conventions.md: results are iv_result_t codes with IV_OK = 0,
     zero-initialised config structs mean defaults, queries are const,
     allocation-free and thread-safe.

   LICENSE
     MIT, see the end of this file.
*/
#ifndef FILIGREE_IV_H
#define FILIGREE_IV_H

#include <stddef.h>
#include <math.h>
#ifndef IV_DEF
#  ifdef IV_STATIC
#    if defined(__GNUC__) || defined(__clang__)
#      define IV_DEF static __attribute__((unused))
#    else
#      define IV_DEF static
#    endif
#  else
#    define IV_DEF extern
#  endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Result codes. IV_OK is 0; iv_result_string() names each. */
typedef enum iv_result_t {
    IV_OK = 0,
    IV_ERR_INVALID_ARG,   /* a NULL pointer or an out-of-range parameter */
    IV_ERR_OUT_OF_MEMORY, /* the allocator hook returned NULL */
    IV_RESULT_COUNT_
} iv_result_t;

/* A human-readable name for a result code; never NULL. */
IV_DEF const char *iv_result_string(iv_result_t r);

#ifdef __cplusplus
}
#endif

#endif /* FILIGREE_IV_H */

/* ======================================================================== */
/*                              IMPLEMENTATION                              */
/* ======================================================================== */
#ifdef IV_IMPLEMENTATION
#ifndef FILIGREE_IV_IMPLEMENTATION_DONE
#define FILIGREE_IV_IMPLEMENTATION_DONE

#ifndef IV_ASSERT
#  include <assert.h>
#  define IV_ASSERT(c) assert(c)
#endif
#if defined(IV_MALLOC) != defined(IV_FREE)
#  error "define both IV_MALLOC and IV_FREE, or neither"
#endif
#ifndef IV_MALLOC
#  include <stdlib.h>
#  define IV_MALLOC(sz, ctx) ((void)(ctx), malloc(sz))
#  define IV_FREE(p, ctx) ((void)(ctx), free(p))
#endif

#ifdef __cplusplus
extern "C" {
#endif

IV_DEF const char *iv_result_string(iv_result_t r)
{
    switch (r) {
    case IV_OK: return "ok";
    case IV_ERR_INVALID_ARG: return "invalid argument";
    case IV_ERR_OUT_OF_MEMORY: return "out of memory";
    case IV_RESULT_COUNT_: break;
    }
    return "unknown result";
}

#ifdef __cplusplus
}
#endif

#endif /* FILIGREE_IV_IMPLEMENTATION_DONE */
#endif /* IV_IMPLEMENTATION */

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
