/* bench/bench_rounded_render.c — render time and image error of every way to
   round edges, per scene (the paper's Table 1, plus error):

     sharp, rounded (rounded_edges.h), bevel-blog-N, bevel-cycles-N, tess-N

   Every mode renders the same pixels with the same random streams, so
   pixels whose paths never meet a chamfer are identical and the RMSE
   against the reference measures the rounding, not unrelated noise. The
   reference is an independent rounded solid: the tessellated mesh at the
   finest level that fits the time budget and memory (64 for article and
   cornell; blocks at level 64 would need ~1.3 10^9 triangles, at 16 it has
   79 million, takes about 35 s to build and 9 GB, so its reference is
   tess-16).
   RMSE is over tone-mapped RGB in [0, 1).

   Render time is the CPU time of the process (user + system, all render
   threads) during the render, not wall time: the benchmark machine is shared
   and wall times swing by 2x with its load, CPU time much less. sharp,
   rounded, rounded-compact and bevel-cycles-4 (the modes the goals
   compare) are built once, rendered once in full (the image, its error
   and the chamfer rate), then timed in RX_BENCH_ROUNDS rounds: a round
   renders the scene's samples one at a time, each sample by the four
   modes in turn (the order rotating), so a change of the machine's speed
   lasting longer than one sample pass (about 0.02-0.2 s) slows the four
   alike. Each round gives one overhead per layout (its CPU time over
   sharp's in that round) and one speed-up per layout over
   bevel-cycles-4 (the bevel's CPU time over the layout's); the table
   prints their medians and ranges, and each mode's mean time per full
   render. The environment variable RX_BENCH_ROUNDS overrides the default
   of 9 rounds;
   RX_BENCH_ONLY=article (a substring of the scenes' labels) runs only the
   scenes it names.

   Usage: build/bench/bench_rounded_render OUTDIR   (table on stdout, CSV
   OUTDIR/rounded_render.csv, progress on stderr). */
#define RE_IMPLEMENTATION
#define RX_SCENE_IMPLEMENTATION
#define RX_TESS_IMPLEMENTATION
#define RX_RENDER_IMPLEMENTATION
#include "rounded_edges.h"
#include "../examples/rounded_edges/rx_scene.h"
#include "../examples/rounded_edges/rx_tess.h"
#include "../examples/rounded_edges/rx_render.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include "ex_image.h"
#include "ex_timer.h"

#define RX_BENCH_ROUNDS 9
#define RX_BENCH_MAX_ROUNDS 64
#define RX_BENCH_W 320
#define RX_BENCH_H 200

typedef struct row_t {
    char mode[32];
    size_t tris;
    double build, round_build, mem_mb, render, chamfer, rmse;
    unsigned long long round_edges; /* rounded modes: the rounding structure's edges and bytes */
    size_t round_bytes;
} row_t;

typedef struct bench_scene_t {
    const char *name;
    int spp;
    const char *reference; /* NULL: no reference render, no RMSE */
    const char *const *modes;
    double radius_scale;
    const char *label;     /* the scene's name in the table */
} bench_scene_t;

static const char *const modes_all[] = {"sharp", "rounded", "rounded-compact", "bevel-blog-8", "bevel-blog-27", "bevel-cycles-2",
                                          "bevel-cycles-4", "bevel-cycles-8", "tess-1", "tess-3", "tess-5",
                                          "tess-10", NULL};
/* The modes timed in interleaved rounds, in this order (every scene lists
   them; the first three lead its list). They are also all that the blocks
   at 0.44 times their radii render: the paper's Blocks had 2.65% of its
   rays on chamfers (Fig. 9), those blocks have 2.66%, so their overhead is
   compared with the paper's at the same chamfer rate. */
#define RX_BENCH_TIMED 4
static const char *const modes_timed[RX_BENCH_TIMED + 1] = {"sharp", "rounded", "rounded-compact", "bevel-cycles-4", NULL};

static double cpu_seconds(void)
{
    struct rusage u;
    getrusage(RUSAGE_SELF, &u);
    return (double)u.ru_utime.tv_sec + 1e-6 * (double)u.ru_utime.tv_usec + (double)u.ru_stime.tv_sec +
           1e-6 * (double)u.ru_stime.tv_usec;
}

/* Renders the built world w once; fills *r (the mode's figures and this
   render's CPU time) and returns the tone-mapped image (caller frees). */
static float *render_world(rx_world_t *w, const char *mode, int spp, row_t *r)
{
    float *rgb = (float *)malloc(sizeof(float) * 3 * RX_BENCH_W * RX_BENCH_H);
    double secs;
    if (!rgb) return NULL;
    secs = cpu_seconds();
    if (rx_world_render(w, spp, 0, 1, 1, rgb) < 0) { free(rgb); return NULL; }
    secs = cpu_seconds() - secs;
    snprintf(r->mode, sizeof r->mode, "%s", mode);
    r->tris = w->triangles;
    r->build = w->build_seconds;
    r->round_build = w->round_seconds;
    r->mem_mb = (double)(w->embree_bytes + (long long)w->round_bytes) / 1048576.0;
    r->round_edges = w->round ? (unsigned long long)w->round_stats.rounded_edges : 0;
    r->round_bytes = w->round ? w->round_bytes : 0;
    r->render = secs;
    r->chamfer = w->rays ? 100.0 * (double)w->chamfer_rays / (double)w->rays : 0;
    ex_image_tonemap(rgb, RX_BENCH_W, RX_BENCH_H, 0);
    return rgb;
}

/* Renders scene s in `mode` (built for this one render); fills *r and
   returns the tone-mapped image (caller frees). */
static float *run(const rx_scene_t *s, const char *mode, int spp, row_t *r)
{
    rx_world_t w;
    rx_mode_t m;
    float *rgb;
    if (rx_mode_parse(mode, &m) || rx_world_build(&w, s, m, RX_BENCH_W, RX_BENCH_H, 0)) return NULL;
    rgb = render_world(&w, mode, spp, r);
    rx_world_free(&w);
    return rgb;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* The overheads of one layout over the rounds: median, smallest, largest. */
typedef struct spread_t {
    double median, lo, hi;
} spread_t;

static spread_t spread_of(const double *v, int n)
{
    double w[RX_BENCH_MAX_ROUNDS];
    spread_t sp;
    memcpy(w, v, sizeof(double) * (size_t)n);
    qsort(w, (size_t)n, sizeof w[0], cmp_double);
    sp.median = n % 2 ? w[n / 2] : 0.5 * (w[n / 2 - 1] + w[n / 2]);
    sp.lo = w[0];
    sp.hi = w[n - 1];
    return sp;
}

static int bench_rounds(void)
{
    const char *e = getenv("RX_BENCH_ROUNDS");
    int n = e ? atoi(e) : RX_BENCH_ROUNDS;
    return n < 1 ? 1 : n > RX_BENCH_MAX_ROUNDS ? RX_BENCH_MAX_ROUNDS : n;
}

int main(int argc, char **argv)
{
    static const bench_scene_t scenes[4] = {{"article", 16, "tess-64", modes_all, 1.0, "article"},
                                            {"blocks", 8, "tess-16", modes_all, 1.0, "blocks"},
                                            {"cornell", 16, "tess-64", modes_all, 1.0, "cornell"},
                                            {"blocks", 8, NULL, modes_timed, 0.44, "blocks-r0.44"}};
    char path[4096];
    FILE *csv;
    int si, rounds = bench_rounds();
    if (argc != 2) { fprintf(stderr, "usage: %s OUTDIR\n", argv[0]); return 2; }
    if (mkdir(argv[1], 0777) && errno != EEXIST) { fprintf(stderr, "%s: cannot create %s: %s\n", argv[0], argv[1], strerror(errno)); return 1; }
    snprintf(path, sizeof path, "%s/rounded_render.csv", argv[1]);
    if (!(csv = fopen(path, "w"))) { fprintf(stderr, "%s: cannot write %s: %s\n", argv[0], path, strerror(errno)); return 1; }
    fprintf(csv, "scene,mode,triangles,build_s,rounding_or_tess_build_s,memory_mb,render_cpu_s,overhead_vs_sharp,chamfer_ray_pct,rmse_vs_reference,reference,spp,width,height,overhead_median,overhead_min,overhead_max,rounds,vs_cycles4_median,vs_cycles4_min,vs_cycles4_max\n");
    printf("Rendering %dx%d, path tracing (3 bounces), same random streams in every mode; RMSE of tone-mapped RGB\n",
           RX_BENCH_W, RX_BENCH_H);
    for (si = 0; si < 4; si++) {
        const bench_scene_t *b = &scenes[si];
        const char *only = getenv("RX_BENCH_ONLY");
        rx_scene_t s;
        row_t ref, rows[16], timed[RX_BENCH_TIMED];
        float *ref_img, *img;
        double over[2][RX_BENCH_MAX_ROUNDS], vs_c4[2][RX_BENCH_MAX_ROUNDS];
        spread_t sp[2], sp_c4[2];
        int n = 0, i, k, q;
        if (only && !strstr(b->label, only)) continue;
        if (rx_scene_make(&s, b->name, b->radius_scale)) return 1;
        memset(&ref, 0, sizeof ref);
        ref_img = NULL;
        if (b->reference) {
            fprintf(stderr, "%s: reference %s\n", b->label, b->reference);
            if (!(ref_img = run(&s, b->reference, b->spp, &ref))) return 1;
        }
        /* the timed modes: built once and rendered in full once (image,
           error, chamfer rate); then the rounds, each sample pass by the
           four in turn (the order rotating) */
        {
            rx_world_t wd[RX_BENCH_TIMED];
            double t[RX_BENCH_TIMED], total[RX_BENCH_TIMED] = {0};
            float *pass = (float *)malloc(sizeof(float) * 3 * RX_BENCH_W * RX_BENCH_H);
            int p;
            if (!pass) return 1;
            for (i = 0; i < RX_BENCH_TIMED; i++) {
                rx_mode_t m;
                fprintf(stderr, "%s: %s\n", b->label, modes_timed[i]);
                if (rx_mode_parse(modes_timed[i], &m) || rx_world_build(&wd[i], &s, m, RX_BENCH_W, RX_BENCH_H, 0)) return 1;
                if (!(img = render_world(&wd[i], modes_timed[i], b->spp, &timed[i]))) return 1;
                timed[i].rmse = ref_img ? ex_image_rmse(img, ref_img, RX_BENCH_W, RX_BENCH_H) : 0;
                free(img);
            }
            fprintf(stderr, "%s: %d rounds of %d sample passes x %d modes\n", b->label, rounds, b->spp, RX_BENCH_TIMED);
            for (k = 0; k < rounds; k++) {
                for (i = 0; i < RX_BENCH_TIMED; i++) t[i] = 0;
                for (p = 0; p < b->spp; p++)
                    for (q = 0; q < RX_BENCH_TIMED; q++) {
                        double c;
                        i = (q + p + k) % RX_BENCH_TIMED;
                        c = cpu_seconds();
                        if (rx_world_render(&wd[i], 1, 0, (unsigned long long)(2 + p + k * b->spp), 1, pass) < 0) return 1;
                        t[i] += cpu_seconds() - c;
                    }
                for (i = 0; i < 2; i++) {
                    over[i][k] = t[1 + i] / t[0] - 1;
                    vs_c4[i][k] = t[3] / t[1 + i];
                }
                for (i = 0; i < RX_BENCH_TIMED; i++) total[i] += t[i];
            }
            free(pass);
            for (i = 0; i < RX_BENCH_TIMED; i++) timed[i].render = total[i] / rounds, rx_world_free(&wd[i]);
            for (i = 0; i < 2; i++) sp[i] = spread_of(over[i], rounds), sp_c4[i] = spread_of(vs_c4[i], rounds);
        }
        for (i = 0; b->modes[i]; i++) { /* the table in the scene's order: timed rows as timed, the rest rendered once */
            for (q = 0; q < RX_BENCH_TIMED && strcmp(b->modes[i], modes_timed[q]); q++) {}
            if (q < RX_BENCH_TIMED) {
                rows[n++] = timed[q];
                continue;
            }
            fprintf(stderr, "%s: %s\n", b->label, b->modes[i]);
            if (!(img = run(&s, b->modes[i], b->spp, &rows[n]))) return 1;
            rows[n].rmse = ref_img ? ex_image_rmse(img, ref_img, RX_BENCH_W, RX_BENCH_H) : 0;
            free(img);
            n++;
        }
        if (b->reference)
            printf("\n%s: %zu triangles, %d objects, %d spp; reference %s (%zu triangles)\n", b->label, rx_scene_triangles(&s),
                   s.nobj, b->spp, b->reference, ref.tris);
        else
            printf("\n%s: %zu triangles, %d objects, %d spp, radii x %g; no reference (RMSE 0)\n", b->label,
                   rx_scene_triangles(&s), s.nobj, b->spp, b->radius_scale);
        printf("  %-16s %10s %9s %10s %9s %9s %9s %9s %9s\n", "mode", "triangles", "build s", "memory MB", "CPU s",
               "vs sharp", "chamfer%", "RMSE", "RMSE/ours");
        for (i = 0; i < n; i++) {
            printf("  %-16s %10zu %9.3f %10.2f %9.3f %8.3fx %8.2f%% %9.5f %8.2fx\n", rows[i].mode, rows[i].tris,
                   rows[i].build, rows[i].mem_mb, rows[i].render, rows[i].render / rows[0].render, rows[i].chamfer,
                   rows[i].rmse, rows[1].rmse > 0 ? rows[i].rmse / rows[1].rmse : 0.0);
            fprintf(csv, "%s,%s,%zu,%.6f,%.6f,%.4f,%.6f,%.5f,%.4f,%.6f,%s,%d,%d,%d", b->label, rows[i].mode, rows[i].tris,
                    rows[i].build, rows[i].round_build, rows[i].mem_mb, rows[i].render, rows[i].render / rows[0].render,
                    rows[i].chamfer, rows[i].rmse, b->reference ? b->reference : "none", b->spp, RX_BENCH_W, RX_BENCH_H);
            if (i == 1 || i == 2)
                fprintf(csv, ",%.5f,%.5f,%.5f,%d,%.4f,%.4f,%.4f\n", sp[i - 1].median, sp[i - 1].lo, sp[i - 1].hi, rounds,
                        sp_c4[i - 1].median, sp_c4[i - 1].lo, sp_c4[i - 1].hi);
            else
                fprintf(csv, ",,,,,,,\n");
        }
        for (k = 1; k <= 2; k++) /* per scene, as the paper's Table 1: the rounding structure alone */
            if (rows[k].round_edges)
                printf("  %s: %llu rounded edges, rounding structure and kd-tree built in %.1f ms (both threads), "
                       "%.1f bytes per rounded edge\n",
                       rows[k].mode, rows[k].round_edges, 1e3 * rows[k].round_build,
                       (double)rows[k].round_bytes / (double)rows[k].round_edges);
        {
            const row_t *c4 = &timed[3]; /* bevel-cycles-4 */
            for (k = 1; k <= 2; k++) {
                printf("  %s vs sharp: %+.1f%% time (median of %d rounds; range %+.1f%% .. %+.1f%%; all rounds %+.1f%%) at "
                       "%.2f%% chamfer rays\n",
                       rows[k].mode, 100 * sp[k - 1].median, rounds, 100 * sp[k - 1].lo, 100 * sp[k - 1].hi,
                       100 * (rows[k].render / rows[0].render - 1), rows[k].chamfer);
                printf("  %s vs bevel-cycles-4: %.2fx faster (median of %d rounds; range %.2fx .. %.2fx)", rows[k].mode,
                       sp_c4[k - 1].median, rounds, sp_c4[k - 1].lo, sp_c4[k - 1].hi);
                if (b->reference) printf(", RMSE %.2fx lower", rows[k].rmse > 0 ? c4->rmse / rows[k].rmse : 0);
                printf("\n");
            }
        }
        if (!b->reference)
            printf("  paper's Blocks: +3.4%% time at 2.65%% chamfer rays (its text; Table 1's times give +4.0%%)\n");
        fflush(stdout);
        free(ref_img);
        rx_scene_free(&s);
    }
    fclose(csv);
    return 0;
}
