/* ex_render.h — a multithreaded tile renderer.

   Calls `fn` for every pixel and sample on all cores (pthreads, tiles handed
   out by an atomic counter) and stores the average of the samples per pixel.
   Each call gets its own deterministic random stream, ex_rng_for_pixel(seed,
   x, y, sample, spp) (use ex_rng_2d for stratified 2D draws), and a pixel's samples are summed in order by one thread, so
   the image is bit-identical for any thread count. Shows a progress bar on
   stderr when the render takes longer than a second. */
#ifndef FILIGREE_EX_RENDER_H
#define FILIGREE_EX_RENDER_H

#include <stdint.h>

#include "ex_rng.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Writes one sample's linear RGB radiance of pixel (x, y) into rgb[0..2].
   Called concurrently from several threads: `user` must be read-only or
   synchronised. */
typedef void (*ex_pixel_fn)(void *user, int x, int y, int sample, ex_rng_t *rng, float rgb[3]);

typedef struct ex_render_desc_t {
    int width, height;       /* pixels, required (> 0) */
    int spp;                 /* samples per pixel; 0 → 1 */
    int threads;             /* 0 → every core (ex_cpu_count()) */
    int tile;                /* tile edge in pixels; 0 → 16 */
    uint64_t seed;           /* random stream seed; 0 is a fine seed */
    const char *label;       /* progress bar label; NULL → "render" */
    int quiet;               /* 1 → never draw the progress bar */
} ex_render_desc_t;

/* Renders into rgb (width*height*3 floats). Returns 0, or -1 after printing
   one line (bad size, thread creation failed). */
int ex_render(const ex_render_desc_t *desc, ex_pixel_fn fn, void *user, float *rgb);

/* Number of online cores (at least 1). */
int ex_cpu_count(void);

/* Calls fn(ctx, i) once for each i in [0, count): i = 0 on this thread,
   the others on threads of their own (on this thread when one cannot be
   started); returns when every call has returned. A parallel-for for
   libraries that take one (rounded_edges.h's re_scene_desc_t.parallel). */
void ex_parallel_for(unsigned count, void (*fn)(void *ctx, unsigned i), void *ctx);

#ifdef __cplusplus
}
#endif
#endif /* FILIGREE_EX_RENDER_H */
