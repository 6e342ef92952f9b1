/* bench_grooves_lines — §5.6 line samples and §6 inter-reflection (issue 8).

   build/bench/bench_grooves_lines out/bench
     → table on stdout, out/bench/grooves_lines.csv

   Scene: a tiled floor (Figure 15's kind), 7 V grooves along u and 7 along
   v crossing in a 0.6 x 0.6 field (no repeat), every footprint within 0.02
   of a crossing (so every one meets an intersection), random size
   (half-axes 0.004-0.03, turned at random), view with E_w >= 0.3, one
   light. Per method: CPU time per footprint (clock(), one thread) and the
   mean error against supersampled geometry (Embree on the explicit mesh
   of tests/grooves_oracle.h, 256 x 256 rays per footprint): the total
   variation ½ Σ_i |r_i - r_i,ref| of the visible ratios, (groove, facet)
   by (groove, facet). Methods: gr_query() with line_samples = 0, which
   sends these footprints to the polygon path (§5.2-5.5), 1/2/4/8/16/32
   line samples, and geometry with 4x4 ... 32x32 rays (shadow rays included); the
   geometry time at each method's error, interpolated log-log between the
   geometry rows. Then §5.6's cache on a scanline, and gr_shade_indirect()
   at depth 0..3 (and 8, the converged answer the others are compared
   with), every facet a 50 % mirror, then clear Fresnel glass. */
#define GR_IMPLEMENTATION
#include "grooves.h"
#include "grooves_oracle.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#define NG 7
#define NFP 300
#define NREF 256
#define SLOTS (2 * NG * GRO_SLOTS + 1)

static const double VSEC[6] = {-0.01, 0, 0, -0.02, 0.01, 0};

static double cpu(void) { return (double)clock() / CLOCKS_PER_SEC; }

/* the rows of the error-against-time table: line samples (0 = polygons
   through gr_query) or supersampled geometry (rays per side) */
typedef struct method_t { const char *name; int lines, rays; } method_t;
static const method_t methods[] = {
    {"polygons (gr_query)", 0, 0}, {"1 line sample", 1, 0},   {"2 line samples", 2, 0}, {"4 line samples", 4, 0},
    {"8 line samples", 8, 0},      {"16 line samples", 16, 0}, {"32 line samples", 32, 0}, {"geometry 4x4", 0, 4},
    {"geometry 8x8", 0, 8},        {"geometry 16x16", 0, 16},  {"geometry 32x32", 0, 32},
};
#define NMETHODS (int)(sizeof methods / sizeof methods[0])
static double us[NMETHODS], mean_err[NMETHODS], vs_poly[NMETHODS];

/* Geometry's time at a given error: log-log interpolation between its
   rows (error falls as rays grow), extrapolated along the end slopes. */
static double geometry_at(double err, int *extrap)
{
    int m, first = -1, last = -1;
    for (m = 0; m < NMETHODS; m++)
        if (methods[m].rays) { if (first < 0) first = m; last = m; }
    *extrap = err < mean_err[last] || err > mean_err[first];
    for (m = first; m < last; m++) {
        double e0 = log(mean_err[m]), e1 = log(mean_err[m + 1]), f;
        if (m + 1 < last && err < mean_err[m + 1]) continue;
        if (m > first && err > mean_err[m]) continue;
        f = (log(err) - e0) / (e1 - e0);
        return exp(log(us[m]) + f * (log(us[m + 1]) - log(us[m])));
    }
    return us[first];
}

static unsigned long long rng_s = 88172645463325252ull;
static double urand(void)
{
    rng_s ^= rng_s << 13; rng_s ^= rng_s >> 7; rng_s ^= rng_s << 17;
    return (double)(rng_s >> 11) * (1.0 / 9007199254740992.0);
}

/* supersampled geometry: visible share per slot (groove*GRO_SLOTS + facet, ground last) */
static void geometry(const gro_scene_t *sc, const gr_query_t *q, int n, double *share)
{
    int i, j, k;
    const gr_footprint_t *fp = &q->footprint;
    memset(share, 0, sizeof(double) * SLOTS);
    for (j = 0; j < n; j++)
        for (i = 0; i < n; i++) {
            double a = -1 + (2 * i + urand()) / n, c = -1 + (2 * j + urand()) / n, o[3], d[3];
            gro_hit_t h;
            o[0] = fp->center[0] + a * fp->axis1[0] + c * fp->axis2[0] + 0.1 * fp->view[0] / fp->view[2];
            o[1] = fp->center[1] + a * fp->axis1[1] + c * fp->axis2[1] + 0.1 * fp->view[1] / fp->view[2];
            o[2] = 0.1;
            for (k = 0; k < 3; k++) d[k] = -fp->view[k];
            h = gro_scene_intersect(sc, o, d, 0, INFINITY);
            if (h.kind == GRO_HIT_NONE) continue;
            (void)gro_scene_lit(sc, &h, q->lights); /* the shadow ray's cost */
            share[h.kind == GRO_HIT_GROUND ? SLOTS - 1 : h.groove * GRO_SLOTS + h.facet] += 1.0 / (n * n);
        }
}

static void list_share(const gr_facet_list_t *l, const gr_grid_t *grid, double *share)
{
    int i;
    (void)grid;
    memset(share, 0, sizeof(double) * SLOTS);
    for (i = 0; i < l->count; i++) {
        const gr_facet_t *f = &l->facets[i];
        int slot = f->groove < 0 ? SLOTS - 1 : f->groove * GRO_SLOTS + (f->facet < 2 ? f->facet : f->facet == 2 ? GRO_CAP0 : GRO_CAP1);
        share[slot] += f->ratio;
    }
}

static double tv(const double *a, const double *b)
{
    double s = 0;
    int k;
    for (k = 0; k < SLOTS; k++) s += fabs(a[k] - b[k]);
    return 0.5 * s;
}

/* the host: a sky brightest at the zenith, a uniform 0.5 in the bulk */
static void sky(void *user, const double origin[3], const double dir[3], int depth, int inside, double weight, double rgb[3])
{
    (void)user; (void)origin; (void)depth; (void)weight;
    rgb[0] = rgb[1] = rgb[2] = inside ? 0.5 : dir[2] > 0 ? dir[2] : 0;
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "out/bench";
    char path[512];
    FILE *csv;
    gr_groove_desc_t g[2 * NG];
    gro_groove_t og[2 * NG];
    double pts[2 * NG][4], light[3] = {0.4, 0.3, 0.866};
    gr_grid_desc_t d;
    gr_grid_t *grid;
    gro_device_t dev;
    gro_scene_t sc;
    gr_query_t *qs;
    double (*ref)[SLOTS], (*poly)[SLOTS], share[SLOTS];
    size_t need;
    void *scratch;
    int i, m;
    memset(g, 0, sizeof g);
    for (i = 0; i < 2 * NG; i++) {
        double c = 0.2 + 0.6 * (i % NG) / (NG - 1);
        pts[i][0] = i < NG ? 0.1 : c; pts[i][1] = i < NG ? c : 0.1;
        pts[i][2] = i < NG ? 0.9 : c; pts[i][3] = i < NG ? c : 0.9;
        g[i].points = pts[i]; g[i].point_count = 2; g[i].section = VSEC; g[i].section_count = 3; g[i].reflectance = 1;
        og[i] = gro_from_gr(&g[i]);
    }
    memset(&d, 0, sizeof d);
    d.grooves = g; d.groove_count = 2 * NG; d.no_wrap = 1;
    if (gr_grid_build(&d, &grid, NULL) != GR_OK) return 1;
    if (gro_device_init(&dev) || gro_scene_build(&sc, dev.dev, og, 2 * NG, NULL)) return 1;
    need = gr_query_scratch_bytes(grid);
    scratch = malloc(need);
    qs = (gr_query_t *)calloc(NFP, sizeof *qs);
    ref = (double (*)[SLOTS])calloc(NFP, sizeof *ref);
    poly = (double (*)[SLOTS])calloc(NFP, sizeof *poly);
    if (!scratch || !qs || !ref || !poly) return 1;
    for (i = 0; i < NFP; i++) {
        double r1 = 0.004 + 0.026 * urand(), r2 = 0.004 + 0.026 * urand(), rot = 3.14159 * urand();
        double ew = 0.3 + 0.7 * urand(), ph = 6.2832 * urand(), s = sqrt(1 - ew * ew);
        gr_query_t *q = &qs[i];
        q->footprint.center[0] = 0.2 + 0.1 * (int)(urand() * NG) + 0.04 * urand() - 0.02;
        q->footprint.center[1] = 0.2 + 0.1 * (int)(urand() * NG) + 0.04 * urand() - 0.02;
        q->footprint.axis1[0] = r1 * cos(rot); q->footprint.axis1[1] = r1 * sin(rot);
        q->footprint.axis2[0] = -r2 * sin(rot); q->footprint.axis2[1] = r2 * cos(rot);
        q->footprint.view[0] = s * cos(ph); q->footprint.view[1] = s * sin(ph); q->footprint.view[2] = ew;
        q->lights = light; q->light_count = 1;
        geometry(&sc, q, NREF, ref[i]);
        if (i % 50 == 49) fprintf(stderr, "bench_grooves_lines: reference %d/%d\r", i + 1, NFP);
    }
    fprintf(stderr, "\n");
    snprintf(path, sizeof path, "%s/grooves_lines.csv", dir);
    csv = fopen(path, "w");
    if (!csv) { fprintf(stderr, "bench_grooves_lines: cannot write %s\n", path); return 1; }
    fprintf(csv, "method,us_per_footprint,mean_tv_error,geometry_us_at_equal_error,mean_tv_vs_polygons\n");
    for (m = 0; m < NMETHODS; m++) {
        double t0, err = 0, err_poly = 0;
        int rep, reps = methods[m].rays ? 1 : 3;
        t0 = cpu();
        for (rep = 0; rep < reps; rep++)
            for (i = 0; i < NFP; i++) {
                gr_facet_list_t l;
                gr_query_t q = qs[i];
                if (methods[m].rays) {
                    geometry(&sc, &q, methods[m].rays, share);
                    if (rep == 0) {
                        err += tv(share, ref[i]) / NFP;
                        err_poly += tv(share, poly[i]) / NFP;
                    }
                    continue;
                }
                if (methods[m].lines == 0) gr_query(grid, &q, scratch, need, &l);
                else {
                    q.line_samples = methods[m].lines;
                    gr_query_lines(grid, &q, scratch, need, &l, NULL);
                }
                if (rep == 0) {
                    list_share(&l, grid, share);
                    err += tv(share, ref[i]) / NFP;
                    if (m == 0) memcpy(poly[i], share, sizeof share);
                    else err_poly += tv(share, poly[i]) / NFP;
                }
            }
        us[m] = (cpu() - t0) / (reps * NFP) * 1e6;
        mean_err[m] = err;
        vs_poly[m] = err_poly;
    }
    printf("%-20s %12s %11s %18s %12s %12s\n", "method", "us/footprint", "mean error", "geometry us at", "vs polygons",
           "difference");
    printf("%-20s %12s %11s %18s %12s %12s\n", "", "", "", "equal error (ratio)", "(speed-up)", "to polygons");
    for (m = 0; m < NMETHODS; m++) {
        int extrap = 0;
        double g = methods[m].rays ? us[m] : geometry_at(mean_err[m], &extrap);
        printf("%-20s %12.1f %11.4f %11.1f%s (%4.1fx) %9.2fx %12.4f\n", methods[m].name, us[m], mean_err[m], g,
               extrap ? "*" : " ", g / us[m], us[0] / us[m], vs_poly[m]);
        fprintf(csv, "%s,%.2f,%.5f,%.2f,%.5f\n", methods[m].name, us[m], mean_err[m], g, vs_poly[m]);
    }
    printf("(* extrapolated beyond the finest geometry row along its last slope; reference %dx%d rays; the last\n"
           " column is the mean total variation against the polygon path's answer, exact for straight grooves)\n",
           NREF, NREF);
    { /* §5.6's cache on a scanline of neighbouring footprints (pixel steps
         of 0.001 across the floor at v = 0.4 + a little, one light): seen
         by an orthographic camera (E fixed: qs[0]'s), then by a
         perspective one (E toward a camera at (0.5, 0.1, 1), turning per
         pixel) */
        int persp;
        for (persp = 0; persp < 2; persp++) {
            gr_line_cache_t cache;
            double tt[2];
            int pass;
            memset(&cache, 0, sizeof cache);
            for (pass = 0; pass < 2; pass++) {
                double t0 = cpu();
                int rep;
                for (rep = 0; rep < 3; rep++)
                    for (i = 0; i < 600; i++) {
                        gr_facet_list_t l;
                        gr_query_t q = qs[0];
                        q.footprint.center[0] = 0.2 + 0.001 * i;
                        q.footprint.center[1] = 0.395 + 0.00002 * i;
                        q.footprint.axis1[0] = 0.003; q.footprint.axis1[1] = 0;
                        q.footprint.axis2[0] = 0; q.footprint.axis2[1] = 0.005;
                        if (persp) {
                            double e[3], n;
                            int k;
                            e[0] = 0.5 - q.footprint.center[0]; e[1] = 0.1 - q.footprint.center[1]; e[2] = 1;
                            n = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
                            for (k = 0; k < 3; k++) q.footprint.view[k] = e[k] / n;
                        }
                        q.line_samples = 2;
                        gr_query_lines_cached(grid, &q, pass ? &cache : NULL, scratch, need, &l, NULL);
                    }
                tt[pass] = (cpu() - t0) / 1800 * 1e6;
            }
            printf("%-20s %14.1f   (%s view, directional light)\n%-20s %14.1f   (%lld served, %lld refills)\n",
                   "2 lines, scanline", tt[0], persp ? "perspective" : "orthographic", "2 lines, cached", tt[1],
                   cache.hits, cache.misses);
            fprintf(csv, "2 line samples scanline%s,%.2f,\n2 line samples scanline%s cached,%.2f,\n",
                    persp ? " perspective" : "", tt[0], persp ? " perspective" : "", tt[1]);
        }
    }
    /* §6: cost of the recursion at depths 0..3, and what the truncation
       leaves out: the mean |rgb_k - rgb_8| against depth 8 (GR_MAX_DEPTH);
       the floor as 50 % mirrors, then as clear glass (Fresnel, ior 1.5:
       every hit splits into a reflected and a refracted segment) */
    printf("\n%-24s %12s %12s %16s\n", "inter-reflection", "us/footprint", "segments", "|rgb - depth 8|");
    for (m = 0; m < 2; m++) {
        static const int depths[5] = {8, 0, 1, 2, 3};
        static double conv[NFP];
        gr_specular_t spec[2];
        gr_indirect_t ind;
        int di, c;
        memset(spec, 0, sizeof spec);
        for (c = 0; c < 3; c++) {
            spec[0].kr[c] = spec[1].kr[c] = m ? 1 : 0.5;
            spec[0].kt[c] = spec[1].kt[c] = m ? 1 : 0;
        }
        spec[0].fresnel = spec[1].fresnel = m;
        memset(&ind, 0, sizeof ind);
        ind.specular = spec; ind.specular_count = 2; ind.trace = sky;
        for (di = 0; di < 5; di++) {
            double t0, t, err = 0, rgb[3];
            long long segs = 0;
            ind.depth = depths[di];
            t0 = cpu();
            for (i = 0; i < NFP; i++) {
                gr_query_t q = qs[i];
                gr_line_stats_t st;
                q.line_samples = 2;
                gr_shade_indirect(grid, &q, &ind, scratch, need, rgb, &st);
                segs += st.segments;
                if (di == 0) conv[i] = rgb[0];
                else err += fabs(rgb[0] - conv[i]) / NFP;
            }
            t = (cpu() - t0) / NFP * 1e6;
            printf("%-6s depth %-11d %12.1f %12.1f %16.4f\n", m ? "glass" : "mirror", depths[di], t, (double)segs / NFP,
                   err);
            fprintf(csv, "indirect %s depth %d (2 line samples),%.2f,%.5f\n", m ? "glass" : "mirror 50%", depths[di], t,
                    err);
        }
    }
    fclose(csv);
    printf("wrote %s\n", path);
    gro_scene_free(&sc);
    gro_device_free(&dev);
    gr_grid_free(grid);
    free(scratch); free(qs); free(ref); free(poly);
    return 0;
}
