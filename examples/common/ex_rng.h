/* ex_rng.h — deterministic per-sample random numbers for example renderers.
   A pixel sample's stream depends only on (seed, x, y, sample), never on which
   thread draws it, so renders are identical for any thread count.

   ex_rng_unit() is plain random (splitmix64). ex_rng_2d() gives stratified
   2D points: the k-th call of every sample of a pixel draws from one R2
   low-discrepancy set of `count` points (Roberts 2018), randomly shifted
   (Cranley-Patterson) per pixel and call and visited in a per-call random
   order, so each point is uniform on [0,1)² yet a pixel's samples cover the
   square evenly. ex_render() sets `count` to spp; with count <= 1 (streams
   made by ex_rng_for_sample) ex_rng_2d() is plain random. */
#ifndef FILIGREE_EX_RNG_H
#define FILIGREE_EX_RNG_H

#include <math.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ex_rng_t {
    uint64_t state;     /* splitmix64 state */
    uint64_t key;       /* the pixel's key, for ex_rng_2d */
    uint32_t sample, count, dim;   /* sample index, samples per pixel, 2D draws so far */
} ex_rng_t;

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
    r.key = k;
    r.sample = (uint32_t)sample;
    r.count = 0;
    r.dim = 0;
    return r;
}
/* The same stream, for sample `sample` of `count` (enables stratified ex_rng_2d). */
static inline ex_rng_t ex_rng_for_pixel(uint64_t seed, int x, int y, int sample, int count)
{
    ex_rng_t r = ex_rng_for_sample(seed, x, y, sample);
    r.count = count > 0 ? (uint32_t)count : 0;
    return r;
}
/* splitmix64 */
static inline uint64_t ex_rng_u64(ex_rng_t *r)
{
    return ex__rng_mix(r->state += 0x9E3779B97F4A7C15ull);
}
/* uniform in [0, 1) */
static inline double ex_rng_unit(ex_rng_t *r) { return (double)(ex_rng_u64(r) >> 11) * (1.0 / 9007199254740992.0); }

static inline uint32_t ex__rng_gcd(uint32_t a, uint32_t b)
{
    while (b) { uint32_t t = a % b; a = b; b = t; }
    return a;
}
/* A stratified point in [0,1)² (see the top comment). */
static inline void ex_rng_2d(ex_rng_t *r, double *u, double *v)
{
    const double a1 = 0.7548776662466927, a2 = 0.5698402909980532; /* 1/g, 1/g² for the plastic number g */
    uint64_t h;
    uint32_t n = r->count, mul, i;
    double x, y;
    if (n <= 1) { *u = ex_rng_unit(r); *v = ex_rng_unit(r); return; }
    h = ex__rng_mix(r->key ^ (0xD1B54A32D192ED03ull * (uint64_t)(r->dim++ + 1)));
    /* a random permutation i = (mul·sample + add) mod n decorrelates the calls */
    mul = (uint32_t)(h % n) | 1u;
    while (ex__rng_gcd(mul, n) != 1) mul += 2;
    i = (uint32_t)(((uint64_t)mul * r->sample + (h >> 32)) % n);
    x = (double)(h >> 11 & 0xFFFFF) / 1048576.0 + a1 * i;   /* 20 bits of shift each */
    y = (double)(h >> 31 & 0xFFFFF) / 1048576.0 + a2 * i;
    *u = x - floor(x);
    *v = y - floor(y);
}

#ifdef __cplusplus
}
#endif
#endif /* FILIGREE_EX_RNG_H */
