/* tests/test_fill_alloc.h — RE_MALLOC / RE_FREE for tests that compare
   scene blocks byte for byte: every block starts filled with
   test_fill_byte, so a byte the build leaves unwritten shows as a
   difference when the fill changes between two builds. Include before
   rounded_edges.h. */
#ifndef TEST_FILL_ALLOC_H
#define TEST_FILL_ALLOC_H
#include <stdlib.h>
#include <string.h>

static int test_fill_byte = 0xA5;

static void *test_fill_malloc(size_t n)
{
    void *p = malloc(n ? n : 1);
    if (p) memset(p, test_fill_byte, n);
    return p;
}

#define RE_MALLOC(sz, ctx) ((void)(ctx), test_fill_malloc(sz))
#define RE_FREE(p, ctx) ((void)(ctx), free(p))
#endif
