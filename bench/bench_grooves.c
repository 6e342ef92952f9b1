/* bench_grooves — error against run time: grooves.h at 1 sample per pixel
   against the same grooves as Embree geometry supersampled at 1, 4, 16, 64
   and 256 samples per pixel, for the example's three scenes. The error is
   the RMSE of the displayed image (tonemapped to [0, 1) as the example
   writes it, all channels) against a 4096-sample geometry
   render of the same small image (box pixel filter in both: jittered
   samples for geometry, the pixel's footprint from ray differentials for
   ours), seen from each scene's bench view (only the grooved tile, no plane
   silhouette). Time is wall clock per frame on every core, the best of
   several frames; memory is what each
   method keeps for the grooves (grid, or Embree's BVH and buffers).

   "Equal error": the geometry time at ours' RMSE, interpolated log-log
   between the two spp levels that bracket it (extrapolated as time ∝
   error^-2 beyond 256 spp, and marked so). Ours runs twice: method "paper"
   is §4 as the paper has it (occlusion by the straight groove with the
   profile at P, straight_occlusion = 1; §4.4's facet normals in the frame
   at P, perturb_normals = -1), method "ours" is grooves.h's default (each
   section point where the ray reaching it meets the groove; normals of the
   swept surface there).

   build/bench/bench_grooves out/bench  → table on stdout, progress on stderr,
   out/bench/grooves_error_time.csv and out/bench/grooves_summary.csv */
#define GR_IMPLEMENTATION
#define GR_STATIC
#include "../examples/grooves/gx_scene.h"

#include <errno.h>
#include <sys/stat.h>

#include "ex_image.h"
#include "ex_timer.h"

#define W 80
#define H 50
#define REF_SPP 4096

typedef struct run_t { double seconds, rmse; long long bytes; } run_t;

static float *image(void)
{
    float *p = (float *)malloc(sizeof(float) * 3 * W * H);
    if (!p) { fprintf(stderr, "bench_grooves: out of memory\n"); exit(1); }
    return p;
}

/* RMSE of what is displayed: both images tonemapped as the example does
   (values in [0, 1)), so scenes with hot highlights compare on one scale. */
static double display_rmse(const float *img, const float *ref_tonemapped, double exposure)
{
    static float t[3 * W * H];
    memcpy(t, img, sizeof t);
    ex_image_tonemap(t, W, H, exposure);
    return ex_image_rmse(t, ref_tonemapped, W, H);
}

/* Renders n frames, returns the fastest (the first frames of a fresh
   structure pay thread and cache start-up that a renderer pays once, and
   on a shared machine the fastest frame is the one least disturbed). */
static double best_time(const ex_render_desc_t *rd, ex_pixel_fn fn, void *user, float *out, int n)
{
    double best = INFINITY;
    int k;
    for (k = 0; k < n; k++) {
        double t0 = ex_now();
        if (ex_render(rd, fn, user, out)) exit(1);
        best = fmin(best, ex_now() - t0);
    }
    return best;
}

static run_t run_geometry(gx_geo_t *g, int spp, const float *ref, float *out)
{
    ex_render_desc_t rd;
    run_t r;
    char label[64];
    memset(&rd, 0, sizeof rd);
    rd.width = W; rd.height = H; rd.spp = spp; rd.seed = 0x9e3779b9u + (uint64_t)spp; /* independent of the reference */
    snprintf(label, sizeof label, "%s geometry %d spp", g->s->name, spp);
    rd.label = label;
    rd.quiet = spp < REF_SPP; /* the progress bar's polling would be timed too */
    if (rd.quiet) fprintf(stderr, "bench_grooves: %s\n", label);
    r.seconds = best_time(&rd, gx_geo_pixel, g, out, spp <= 4 ? 25 : spp <= 16 ? 9 : spp <= 64 ? 3 : 1);
    r.bytes = gx_geo_bytes(g);
    r.rmse = ref ? display_rmse(out, ref, g->s->exposure) : 0;
    return r;
}

static run_t run_ours(const gx_scene_t *s, int paper, const float *ref, float *out)
{
    gx_ours_t o;
    ex_render_desc_t rd;
    run_t r;
    memset(&rd, 0, sizeof rd);
    rd.width = W; rd.height = H; rd.spp = 1; rd.quiet = 1;
    if (gx_ours_init(&o, s, W, H)) exit(1);
    o.perturb_normals = paper ? -1 : 0;
    o.straight_occlusion = paper;
    r.seconds = best_time(&rd, gx_ours_pixel, &o, out, 25);
    r.bytes = gx_ours_bytes(&o);
    r.rmse = display_rmse(out, ref, s->exposure);
    gx_ours_free(&o);
    return r;
}

/* Fraction of reference pixels that see the background (should be 0). */
static double background_fraction(const float *rgb, const gx_scene_t *s)
{
    int i, n = 0;
    for (i = 0; i < W * H; i++)
        n += fabs(rgb[3 * i] - s->background.x) < 1e-6 && fabs(rgb[3 * i + 1] - s->background.y) < 1e-6;
    return (double)n / (W * H);
}

/* Geometry time at error e from the spp ladder (log-log interpolation). */
static double time_at_error(const run_t *geo, int n, double e, int *extrapolated)
{
    int i;
    *extrapolated = 0;
    if (e >= geo[0].rmse) return geo[0].seconds * (geo[0].rmse / e) * (geo[0].rmse / e);
    for (i = 0; i + 1 < n; i++)
        if (e <= geo[i].rmse && e >= geo[i + 1].rmse) {
            double f = log(geo[i].rmse / e) / log(geo[i].rmse / geo[i + 1].rmse);
            return exp(log(geo[i].seconds) + f * log(geo[i + 1].seconds / geo[i].seconds));
        }
    *extrapolated = 1;
    return geo[n - 1].seconds * (geo[n - 1].rmse / e) * (geo[n - 1].rmse / e);
}

int main(int argc, char **argv)
{
    static const int spps[5] = {1, 4, 16, 64, 256};
    const char *dir = argc > 1 ? argv[1] : "out/bench";
    char path[4096];
    FILE *csv, *sum;
    int si, i;
    float *ref = image(), *img = image();
    if (mkdir(dir, 0777) && errno != EEXIST) { fprintf(stderr, "bench_grooves: cannot create %s\n", dir); return 1; }
    snprintf(path, sizeof path, "%s/grooves_error_time.csv", dir);
    csv = fopen(path, "w");
    snprintf(path, sizeof path, "%s/grooves_summary.csv", dir);
    sum = fopen(path, "w");
    if (!csv || !sum) { fprintf(stderr, "bench_grooves: cannot write into %s\n", dir); return 1; }
    fprintf(csv, "scene,method,spp,seconds,rmse,bytes\n");
    fprintf(sum, "scene,method,ours_rmse,ours_seconds,ours_bytes,geometry_seconds_equal_error,speedup,geometry_bytes,memory_ratio,extrapolated\n");
    printf("grooves.h vs Embree geometry, %dx%d pixels, RMSE against geometry at %d spp, %d threads\n", W, H, REF_SPP,
           ex_cpu_count());
    printf("%-10s %-9s %5s %10s %10s %11s\n", "scene", "method", "spp", "s/frame", "RMSE", "memory KiB");
    for (si = 0; gx_scene_names[si]; si++) {
        gx_scene_t s;
        gx_geo_t g;
        run_t geo[5], ours, refrun;
        double teq, speed;
        int extra, paper;
        if (gx_scene_make(&s, gx_scene_names[si])) { fprintf(stderr, "bench_grooves: out of memory\n"); return 1; }
        gx_scene_bench_view(&s);
        if (gx_geo_init(&g, &s, W, H)) return 1;
        refrun = run_geometry(&g, REF_SPP, NULL, ref);
        if (background_fraction(ref, &s) > 0)
            fprintf(stderr, "bench_grooves: %s: %.1f%% of the view misses the tile\n", s.name, 100 * background_fraction(ref, &s));
        ex_image_tonemap(ref, W, H, s.exposure);
        fprintf(csv, "%s,reference,%d,%.6f,0,%lld\n", s.name, REF_SPP, refrun.seconds, refrun.bytes);
        for (i = 0; i < 5; i++) {
            geo[i] = run_geometry(&g, spps[i], ref, img);
            printf("%-10s %-9s %5d %10.4f %10.5f %11.1f\n", s.name, "geometry", spps[i], geo[i].seconds, geo[i].rmse,
                   geo[i].bytes / 1024.0);
            fprintf(csv, "%s,geometry,%d,%.6f,%.6g,%lld\n", s.name, spps[i], geo[i].seconds, geo[i].rmse, geo[i].bytes);
        }
        for (paper = 1; paper >= 0; paper--) {
            const char *m = paper ? "paper" : "ours";
            ours = run_ours(&s, paper, ref, img);
            printf("%-10s %-9s %5d %10.4f %10.5f %11.1f\n", s.name, m, 1, ours.seconds, ours.rmse, ours.bytes / 1024.0);
            fprintf(csv, "%s,%s,1,%.6f,%.6g,%lld\n", s.name, m, ours.seconds, ours.rmse, ours.bytes);
            teq = time_at_error(geo, 5, ours.rmse, &extra);
            speed = teq / ours.seconds;
            if (ours.rmse > geo[0].rmse) {
                printf("%-10s %-9s error is above geometry's at 1 spp (a model bias, see docs/grooves.md); %.0fx less memory\n",
                       s.name, m, (double)geo[0].bytes / (double)ours.bytes);
                teq = speed = NAN;
            } else
                printf("%-10s %-9s at its error geometry needs %.4f s%s: %.1fx the time; %.0fx the memory\n", s.name, m,
                       teq, extra ? " (extrapolated past 256 spp)" : "", speed, (double)geo[0].bytes / (double)ours.bytes);
            fprintf(sum, "%s,%s,%.6g,%.6f,%lld,%.6f,%.3f,%lld,%.2f,%d\n", s.name, m, ours.rmse, ours.seconds, ours.bytes,
                    teq, speed, geo[0].bytes, (double)geo[0].bytes / (double)ours.bytes, extra);
        }
        fflush(stdout);
        gx_geo_free(&g);
        gx_scene_free(&s);
    }
    fclose(csv);
    fclose(sum);
    free(ref);
    free(img);
    return 0;
}
