/* scripts/fingerprint/fp.h — shared by the fingerprint programs (make
   fingerprint, docs/conventions.md "Refactoring"): FNV-1a over the bytes of
   results, so two versions of a header can be compared bit for bit. */
#ifndef FILIGREE_FP_H
#define FILIGREE_FP_H
#include <stddef.h>

#define FP_START 14695981039346656037ull

static unsigned long long fp_hash(unsigned long long h, const void *p, size_t n)
{
    const unsigned char *c = (const unsigned char *)p;
    size_t i;
    for (i = 0; i < n; i++) h = (h ^ c[i]) * 1099511628211ull;
    return h;
}
#endif
