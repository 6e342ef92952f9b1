/* tests/fuzz_check.h — a failed check in a libFuzzer target: print the
   case and where, then abort (which libFuzzer reports as a crash and saves
   the input for). */
#ifndef FILIGREE_FUZZ_CHECK_H
#define FILIGREE_FUZZ_CHECK_H
#include <stdio.h>
#include <stdlib.h>

#define FUZZ_CHECK(c, ...)                                                          \
    do {                                                                            \
        if (!(c)) {                                                                 \
            fprintf(stderr, "%s: ", __FILE__);                                      \
            fprintf(stderr, __VA_ARGS__);                                           \
            fprintf(stderr, "\n  failed: %s (line %d)\n", #c, __LINE__);            \
            abort();                                                                \
        }                                                                           \
    } while (0)

#endif
