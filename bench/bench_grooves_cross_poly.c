/* bench_grooves_cross_poly — cost and accuracy of the 2D polygon routines
   that the polygon path of §5 (issue 8) is built on, at the sizes §5 uses:
   a footprint quadrilateral against a facet strip (Sutherland-Hodgman,
   §5.2), and a footprint minus k projected cross-sections of V and U
   grooves (the slab-sweep boolean, §5.3), plus gr_detect() per footprint.

   build/bench/bench_grooves_cross_poly out/bench
     → table on stdout, out/bench/grooves_cross_poly.csv

   Error: each operation is run on a square [-1,1]^2 against copies of
   itself turned by 45° (about the centre), whose intersection is the
   regular octagon of area 8(√2 - 1); the difference and union follow.
   Each row is the median of 5 runs of N calls.

   Then error against run time at intersections (issue 8's benchmark):
   footprints on an X crossing, a T junction and an isolated end, random
   views, one light; the scalar each method estimates is the footprint's
   Lambert radiance Σ r_i lit_i max(0, N_i.L). gr_query() (the polygon path)
   against the same grooves as Embree geometry (tests/grooves_oracle.h,
   built once) with n x n stratified primary rays plus one shadow ray each,
   n = 2..32; the reference is that geometry at n = 384. CPU time per
   footprint (process clock, one thread), RMS error over the footprints.
   Line samples (§5.6) at 2, 4 and 8 segments on the same footprints.
     → out/bench/grooves_cross_error_time.csv */
#define GR_IMPLEMENTATION
#include "grooves.h"
#include "ex_timer.h"

#include "grooves_oracle.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double cpu_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

#define XE_FOOTPRINTS 32
typedef struct xe_fp_t { double c[2], r, e[3]; } xe_fp_t;

/* Lambert radiance of a footprint from the geometry: n x n stratified rays. */
static double xe_geometry(const gro_scene_t *sc, const xe_fp_t *f, const double *L, int n, uint64_t *seed)
{
    double sum = 0;
    int i, j, m;
    for (i = 0; i < n; i++)
        for (j = 0; j < n; j++) {
            double x[3], o[3], d[3], a = -1 + 2 * (i + gro__unit(seed)) / n, c = -1 + 2 * (j + gro__unit(seed)) / n;
            gro_hit_t h;
            x[0] = f->c[0] + a * f->r; x[1] = f->c[1] + c * f->r; x[2] = 0;
            for (m = 0; m < 3; m++) { o[m] = x[m] + 0.2 * f->e[m]; d[m] = -f->e[m]; }
            h = gro_scene_intersect(sc, o, d, 0, INFINITY);
            if (h.kind != GRO_HIT_NONE && gro_scene_lit(sc, &h, L))
                sum += fmax(0, h.n[0] * L[0] + h.n[1] * L[1] + h.n[2] * L[2]);
        }
    return sum / ((double)n * n);
}

/* The same from gr_query(). */
/* Radiance of one footprint by gr_query(): the polygon path (lines = 0) or
   `lines` line samples (§5.6). */
static double xe_ours(const gr_grid_t *grid, const xe_fp_t *f, const double *L, int lines, void *scratch, size_t bytes)
{
    gr_query_t q;
    gr_facet_list_t list;
    double sum = 0;
    int i;
    memset(&q, 0, sizeof q);
    q.footprint.center[0] = f->c[0]; q.footprint.center[1] = f->c[1];
    q.footprint.axis1[0] = f->r; q.footprint.axis2[1] = f->r;
    memcpy(q.footprint.view, f->e, sizeof f->e);
    q.lights = L; q.light_count = 1;
    q.line_samples = lines;
    if (gr_query(grid, &q, scratch, bytes, &list) != GR_OK) return NAN;
    for (i = 0; i < list.count; i++) {
        const gr_facet_t *e = &list.facets[i];
        sum += e->ratio * e->lit[0] * fmax(0, e->normal[0] * L[0] + e->normal[1] * L[1] + e->normal[2] * L[2]);
    }
    return sum;
}

static void error_against_time(const char *dir)
{
    static const double a[4] = {0.2, 0.5, 0.8, 0.5}, b[4] = {0.5, 0.2, 0.5, 0.8}, c[4] = {0.65, 0.5, 0.65, 0.7};
    static const double e2[4] = {0.35, 0.3, 0.35, 0.45};
    static const double V[6] = {-0.01, 0, 0, -0.02, 0.01, 0}, U[8] = {-0.01, 0, -0.01, -0.015, 0.01, -0.015, 0.01, 0};
    static const int ns[6] = {2, 4, 8, 16, 32, 384};
    gr_groove_desc_t g[4];
    gro_groove_t geo[4];
    gr_grid_desc_t gd;
    gr_grid_t *grid = NULL;
    gro_device_t dev;
    gro_scene_t sc;
    gro_build_t bo;
    xe_fp_t fps[XE_FOOTPRINTS];
    double ref[XE_FOOTPRINTS], L[3], t0, t_ours, err2;
    void *scratch;
    size_t bytes;
    uint64_t seed = 7;
    char path[512];
    FILE *csv;
    int i, k, m;
    memset(g, 0, sizeof g);
    for (i = 0; i < 4; i++) {
        g[i].points = i == 0 ? a : i == 1 ? b : i == 2 ? c : e2;
        g[i].point_count = 2;
        g[i].section = i % 2 ? U : V;
        g[i].section_count = i % 2 ? 4 : 3;
    }
    memset(&gd, 0, sizeof gd);
    gd.grooves = g; gd.groove_count = 4; gd.no_wrap = 1;
    if (gr_grid_build(&gd, &grid, NULL) != GR_OK || gro_device_init(&dev)) { fprintf(stderr, "setup failed\n"); return; }
    for (i = 0; i < 4; i++) geo[i] = gro_from_gr(&g[i]);
    memset(&bo, 0, sizeof bo);
    if (gro_scene_build(&sc, dev.dev, geo, 4, &bo)) { fprintf(stderr, "geometry failed\n"); return; }
    bytes = gr_query_scratch_bytes(grid);
    scratch = malloc(bytes);
    L[0] = 0.45; L[1] = 0.3; L[2] = sqrt(1 - 0.45 * 0.45 - 0.3 * 0.3);
    /* footprints: the X crossing (0.5, 0.5), the T (0.65, 0.5) and the
       isolated end (0.35, 0.45); half-size 0.005..0.03, views up to 65° */
    for (i = 0; i < XE_FOOTPRINTS; i++) {
        static const double site[3][2] = {{0.5, 0.5}, {0.65, 0.5}, {0.35, 0.45}};
        double th = 65 * M_PI / 180 * sqrt(gro__unit(&seed)), ph = 2 * M_PI * gro__unit(&seed);
        fps[i].c[0] = site[i % 3][0] + 0.01 * (gro__unit(&seed) - 0.5);
        fps[i].c[1] = site[i % 3][1] + 0.01 * (gro__unit(&seed) - 0.5);
        fps[i].r = 0.005 + 0.025 * gro__unit(&seed);
        fps[i].e[0] = sin(th) * cos(ph); fps[i].e[1] = sin(th) * sin(ph); fps[i].e[2] = cos(th);
        ref[i] = xe_geometry(&sc, &fps[i], L, ns[5], &seed);
    }
    snprintf(path, sizeof path, "%s/grooves_cross_error_time.csv", dir);
    csv = fopen(path, "w");
    if (csv) fprintf(csv, "method,samples,us_per_footprint,rms_error\n");
    printf("\nerror against time at intersections (%d footprints, reference: geometry at %d^2 rays)\n",
           XE_FOOTPRINTS, ns[5]);
    printf("%-28s %14s %12s\n", "method", "us/footprint", "rms error");
    /* polygons, then 2, 4 and 8 line samples: repeat for a stable time */
    for (m = 0; m < 4; m++) {
        int lines = m == 0 ? 0 : 1 << m;
        char name[32];
        err2 = 0;
        t0 = cpu_now();
        for (k = 0; k < 20; k++)
            for (i = 0; i < XE_FOOTPRINTS; i++) (void)xe_ours(grid, &fps[i], L, lines, scratch, bytes);
        t_ours = (cpu_now() - t0) / (20.0 * XE_FOOTPRINTS) * 1e6;
        for (i = 0; i < XE_FOOTPRINTS; i++) {
            double v = xe_ours(grid, &fps[i], L, lines, scratch, bytes);
            err2 += (v - ref[i]) * (v - ref[i]);
        }
        if (lines) snprintf(name, sizeof name, "line samples x%d", lines);
        else snprintf(name, sizeof name, "polygons (gr_query)");
        printf("%-28s %14.1f %12.2e\n", name, t_ours, sqrt(err2 / XE_FOOTPRINTS));
        if (csv) fprintf(csv, "%s,%d,%.2f,%.3e\n", lines ? "line_samples" : "polygons", lines, t_ours,
                         sqrt(err2 / XE_FOOTPRINTS));
    }
    for (k = 0; k < 5; k++) {
        double t;
        err2 = 0;
        t0 = cpu_now();
        for (i = 0; i < XE_FOOTPRINTS; i++) {
            double v = xe_geometry(&sc, &fps[i], L, ns[k], &seed);
            err2 += (v - ref[i]) * (v - ref[i]);
        }
        t = (cpu_now() - t0) / XE_FOOTPRINTS * 1e6;
        printf("geometry %3d^2 rays          %14.1f %12.2e\n", ns[k], t, sqrt(err2 / XE_FOOTPRINTS));
        if (csv) fprintf(csv, "geometry,%d,%.2f,%.3e\n", ns[k] * ns[k], t, sqrt(err2 / XE_FOOTPRINTS));
    }
    if (csv) fclose(csv);
    free(scratch);
    gro_scene_free(&sc);
    gro_device_free(&dev);
    gr_grid_free(grid);
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median5(double *r)
{
    qsort(r, 5, sizeof(double), cmp);
    return r[2];
}

/* ring of n points on a circle of radius rad, turned by phase */
static void ngon(double *p, int n, double rad, double phase, double cx, double cy)
{
    int i;
    for (i = 0; i < n; i++) {
        p[2 * i] = cx + rad * cos(phase + 2 * M_PI * i / n);
        p[2 * i + 1] = cy + rad * sin(phase + 2 * M_PI * i / n);
    }
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "out/bench";
    char path[512];
    FILE *csv;
    static unsigned char scratch[1 << 20];
    static double traps[8 * 4096];
    double sq[8], rot[8], out[256], work[256], runs[5], exact = 8 * (sqrt(2.0) - 1);
    volatile double sink = 0;
    int r, i, k, n = 200000;
    snprintf(path, sizeof path, "%s/grooves_cross_poly.csv", dir);
    csv = fopen(path, "w");
    if (!csv) { fprintf(stderr, "bench_grooves_cross_poly: cannot write %s\n", path); return 1; }
    fprintf(csv, "operation,edges,ns_per_call,abs_area_error\n");
    printf("%-44s %6s %12s %12s\n", "operation", "edges", "ns/call", "area error");
    ngon(sq, 4, sqrt(2.0), M_PI / 4, 0, 0);
    ngon(rot, 4, sqrt(2.0), M_PI / 2, 0, 0);
    /* Sutherland-Hodgman, quad against quad (the §5.2 facet-bounds clip) */
    {
        double err, area = 0;
        int m = 0;
        for (r = 0; r < 5; r++) {
            double t0 = ex_now();
            for (i = 0; i < n; i++) {
                gr_poly_clip_convex(sq, 4, rot, 4, out, work, 128, &m);
                sink += out[0];
            }
            runs[r] = (ex_now() - t0) / n * 1e9;
        }
        area = gr_poly_area(out, m);
        err = fabs(area - exact);
        printf("%-44s %6d %12.1f %12.2e\n", "clip_convex: quad ∩ quad", 8, median5(runs), err);
        fprintf(csv, "clip_convex quad-quad,8,%.1f,%.3e\n", median5(runs), err);
    }
    /* slab sweep, quad op quad, area only and with trapezoids */
    for (k = 0; k < 4; k++) {
        gr_polyset_t a, b;
        double area = 0, err, want[4] = {exact, 4 - exact, 8 - exact, 8 - 2 * exact};
        static const char *names[4] = {"boolean: quad ∩ quad", "boolean: quad \\ quad", "boolean: quad ∪ quad",
                                       "boolean: quad xor quad"};
        memset(&a, 0, sizeof a);
        memset(&b, 0, sizeof b);
        a.points = sq; a.point_count = 4;
        b.points = rot; b.point_count = 4;
        for (r = 0; r < 5; r++) {
            double t0 = ex_now();
            for (i = 0; i < n / 4; i++) {
                gr_poly_boolean(&a, &b, (gr_poly_op_t)k, scratch, sizeof scratch, traps, 4096, NULL, &area);
                sink += area;
            }
            runs[r] = (ex_now() - t0) / (n / 4) * 1e9;
        }
        err = fabs(area - want[k]);
        printf("%-44s %6d %12.1f %12.2e\n", names[k], 8, median5(runs), err);
        fprintf(csv, "%s,8,%.1f,%.3e\n", names[k], median5(runs), err);
    }
    /* §5.3 sizes: a footprint quad minus 1..4 projected cross-sections
       (7-point U-groove prisms across it, as polygons of 8 points) */
    for (k = 1; k <= 4; k++) {
        double cut[4 * 16];
        int sizes[4], j;
        gr_polyset_t a, b;
        double area = 0;
        memset(&a, 0, sizeof a);
        memset(&b, 0, sizeof b);
        for (j = 0; j < k; j++) {
            ngon(cut + 16 * j, 8, 0.6, 0.3 * j, -1 + 0.6 * j, 0.2 * j);
            sizes[j] = 8;
        }
        a.points = sq; a.point_count = 4;
        b.points = cut; b.point_count = 8 * k; b.ring_sizes = sizes; b.ring_count = k;
        for (r = 0; r < 5; r++) {
            double t0 = ex_now();
            for (i = 0; i < n / 8; i++) {
                gr_poly_boolean(&a, &b, GR_POLY_DIFFERENCE, scratch, sizeof scratch, traps, 4096, NULL, &area);
                sink += area;
            }
            runs[r] = (ex_now() - t0) / (n / 8) * 1e9;
        }
        printf("boolean: footprint \\ %d cross-section(s)%*s %6d %12.1f %12s\n", k, k > 1 ? 6 : 6, "", 4 + 8 * k,
               median5(runs), "-");
        fprintf(csv, "footprint minus %d sections,%d,%.1f,\n", k, 4 + 8 * k, median5(runs));
    }
    fclose(csv);
    (void)sink;
    error_against_time(dir);
    return 0;
}
