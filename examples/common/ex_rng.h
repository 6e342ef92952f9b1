/* ex_rng.h — deterministic per-sample random numbers for example renderers.
   A pixel sample's stream depends only on (seed, x, y, sample), never on which
   thread draws it, so renders are identical for any thread count. */
#ifndef FILIGREE_EX_RNG_H
#define FILIGREE_EX_RNG_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ex_rng_t { uint64_t state; } ex_rng_t;

static inline uint64_t ex__rng_mix(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
/* The stream of pixel (x, y), sample `sample`, for a render seeded with `seed`. */
static inline ex_rng_t ex_rng_for_sample(uint64_t seed, int x, int y, int sample)
{
    ex_rng_t r;
    uint64_t k = ex__rng_mix(seed ^ 0x6A09E667F3BCC909ull);
    k = ex__rng_mix(k ^ (uint64_t)(uint32_t)x);
    k = ex__rng_mix(k ^ ((uint64_t)(uint32_t)y << 32));
    r.state = ex__rng_mix(k ^ (uint64_t)(uint32_t)sample * 0x9E3779B97F4A7C15ull);
    return r;
}
/* splitmix64 */
static inline uint64_t ex_rng_u64(ex_rng_t *r)
{
    return ex__rng_mix(r->state += 0x9E3779B97F4A7C15ull);
}
/* uniform in [0, 1) */
static inline double ex_rng_unit(ex_rng_t *r) { return (double)(ex_rng_u64(r) >> 11) * (1.0 / 9007199254740992.0); }

#ifdef __cplusplus
}
#endif
#endif /* FILIGREE_EX_RNG_H */
