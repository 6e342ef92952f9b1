/* ex_render.c — see ex_render.h */
#include "ex_render.h"

#include <errno.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "ex_progress.h"

extern char *program_invocation_short_name; /* glibc */

typedef struct ex__render_job_t {
    const ex_render_desc_t *desc;
    ex_pixel_fn fn;
    void *user;
    float *rgb;
    int tiles_x, ntiles, tile, spp;
    int next_tile;      /* atomic: the next tile to hand out */
    int tiles_done;     /* atomic: for the progress bar */
} ex__render_job_t;

int ex_cpu_count(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > 1024 ? 1024 : (int)n;
}

typedef struct ex__call_t {
    void (*fn)(void *ctx, unsigned i);
    void *ctx;
    unsigned i;
} ex__call_t;

static void *ex__call(void *p)
{
    ex__call_t *c = (ex__call_t *)p;
    c->fn(c->ctx, c->i);
    return NULL;
}

void ex_parallel_for(unsigned count, void (*fn)(void *ctx, unsigned i), void *ctx)
{
    pthread_t *th = count > 1 ? (pthread_t *)malloc(sizeof(pthread_t) * count) : NULL;
    ex__call_t *call = count > 1 ? (ex__call_t *)malloc(sizeof(ex__call_t) * count) : NULL;
    unsigned char *started = count > 1 ? (unsigned char *)calloc(count, 1) : NULL;
    unsigned i;
    for (i = 1; i < count; i++) {
        if (th && call && started) {
            call[i].fn = fn, call[i].ctx = ctx, call[i].i = i;
            started[i] = pthread_create(&th[i], NULL, ex__call, &call[i]) == 0;
        }
        if (!started || !started[i]) fn(ctx, i);
    }
    if (count) fn(ctx, 0);
    for (i = 1; i < count; i++)
        if (started && started[i]) pthread_join(th[i], NULL);
    free(th), free(call), free(started);
}

static void ex__render_tile(ex__render_job_t *job, int t)
{
    const ex_render_desc_t *d = job->desc;
    int x0 = (t % job->tiles_x) * job->tile, y0 = (t / job->tiles_x) * job->tile;
    int x1 = x0 + job->tile < d->width ? x0 + job->tile : d->width;
    int y1 = y0 + job->tile < d->height ? y0 + job->tile : d->height;
    int x, y, s;
    for (y = y0; y < y1; y++)
        for (x = x0; x < x1; x++) {
            double sum[3] = {0, 0, 0};
            float *out = job->rgb + 3 * ((size_t)y * (size_t)d->width + (size_t)x);
            for (s = 0; s < job->spp; s++) {
                ex_rng_t rng = ex_rng_for_pixel(d->seed, x, y, s, job->spp);
                float c[3] = {0, 0, 0};
                job->fn(job->user, x, y, s, &rng, c);
                sum[0] += c[0]; sum[1] += c[1]; sum[2] += c[2];
            }
            out[0] = (float)(sum[0] / job->spp);
            out[1] = (float)(sum[1] / job->spp);
            out[2] = (float)(sum[2] / job->spp);
        }
}

static void *ex__render_worker(void *arg)
{
    ex__render_job_t *job = (ex__render_job_t *)arg;
    for (;;) {
        int t = __atomic_fetch_add(&job->next_tile, 1, __ATOMIC_RELAXED);
        if (t >= job->ntiles) break;
        ex__render_tile(job, t);
        __atomic_fetch_add(&job->tiles_done, 1, __ATOMIC_RELEASE);
    }
    return NULL;
}

/* Watches the workers from the calling thread and draws the progress bar. */
static void ex__render_watch(ex__render_job_t *job)
{
    ex_progress_t bar;
    struct timespec nap = {0, 50 * 1000 * 1000};
    const char *label = job->desc->label ? job->desc->label : "render";
    ex_progress_begin(&bar, label, job->ntiles);
    for (;;) {
        int done = __atomic_load_n(&job->tiles_done, __ATOMIC_ACQUIRE);
        if (done >= job->ntiles) break;
        ex_progress_update(&bar, done);
        nanosleep(&nap, NULL);
    }
    ex_progress_end(&bar);
}

int ex_render(const ex_render_desc_t *desc, ex_pixel_fn fn, void *user, float *rgb)
{
    ex__render_job_t job;
    pthread_t *threads;
    int nthreads, i, started = 0, err = 0;
    if (!desc || !fn || !rgb || desc->width <= 0 || desc->height <= 0 || desc->width > 65536 ||
        desc->height > 65536 || desc->spp < 0 || desc->threads < 0 || desc->tile < 0) {
        fprintf(stderr, "%s: bad render description (size %dx%d)\n", program_invocation_short_name,
                desc ? desc->width : 0, desc ? desc->height : 0);
        return -1;
    }
    memset(&job, 0, sizeof job);
    job.desc = desc; job.fn = fn; job.user = user; job.rgb = rgb;
    job.tile = desc->tile ? desc->tile : 16;
    job.spp = desc->spp ? desc->spp : 1;
    job.tiles_x = (desc->width + job.tile - 1) / job.tile;
    job.ntiles = job.tiles_x * ((desc->height + job.tile - 1) / job.tile);
    nthreads = desc->threads ? desc->threads : ex_cpu_count();
    if (nthreads > job.ntiles) nthreads = job.ntiles;
    threads = (pthread_t *)malloc(sizeof(pthread_t) * (size_t)nthreads);
    if (!threads) { fprintf(stderr, "%s: out of memory for threads\n", program_invocation_short_name); return -1; }
    for (i = 0; i < nthreads; i++) {
        err = pthread_create(&threads[i], NULL, ex__render_worker, &job);
        if (err) break;
        started++;
    }
    if (started == 0) {
        free(threads);
        fprintf(stderr, "%s: cannot start a thread: %s\n", program_invocation_short_name, strerror(err));
        return -1;
    }
    /* with fewer threads than asked the started ones still finish every tile */
    if (desc->quiet) {
        for (i = 0; i < started; i++) pthread_join(threads[i], NULL);
    } else {
        ex__render_watch(&job);
        for (i = 0; i < started; i++) pthread_join(threads[i], NULL);
    }
    free(threads);
    return 0;
}
