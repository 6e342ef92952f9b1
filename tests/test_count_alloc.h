/* tests/test_count_alloc.h — an allocator hook for the XX_MALLOC /
   XX_FREE of any header, through the user context it is given: it counts
   the calls, fails the one numbered fail_at (0: none), counts the blocks
   still live, and fills each block with 0xA5 (so unwritten bytes compare
   equal between builds). Thread-safe: hosts call it from their tasks. A
   NULL context is counted in ta_null_context (a test that always passes
   one asserts it stays 0: the header did not lose the user's). */
#ifndef TEST_COUNT_ALLOC_H
#define TEST_COUNT_ALLOC_H
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

typedef struct ta_alloc_t {
    pthread_mutex_t mu;
    long calls, fail_at; /* fail the allocation numbered fail_at (0: never) */
    long live;
} ta_alloc_t;

static long ta_null_context;
static pthread_mutex_t ta_null_mu = PTHREAD_MUTEX_INITIALIZER;

static void *ta_malloc(size_t n, void *ctx)
{
    ta_alloc_t *a = (ta_alloc_t *)ctx;
    void *p;
    if (a) {
        int fail;
        pthread_mutex_lock(&a->mu);
        fail = ++a->calls == a->fail_at;
        if (!fail) a->live++;
        pthread_mutex_unlock(&a->mu);
        if (fail) return NULL;
    } else {
        pthread_mutex_lock(&ta_null_mu);
        ta_null_context++;
        pthread_mutex_unlock(&ta_null_mu);
    }
    p = malloc(n ? n : 1);
    if (p) memset(p, 0xA5, n);
    return p;
}

static void ta_free(void *p, void *ctx)
{
    ta_alloc_t *a = (ta_alloc_t *)ctx;
    if (a && p) {
        pthread_mutex_lock(&a->mu);
        a->live--;
        pthread_mutex_unlock(&a->mu);
    }
    free(p);
}

static ta_alloc_t *ta_alloc_new(long fail_at)
{
    ta_alloc_t *a = (ta_alloc_t *)calloc(1, sizeof *a);
    pthread_mutex_init(&a->mu, NULL);
    a->fail_at = fail_at;
    return a;
}
static void ta_alloc_delete(ta_alloc_t *a)
{
    pthread_mutex_destroy(&a->mu);
    free(a);
}
#endif
