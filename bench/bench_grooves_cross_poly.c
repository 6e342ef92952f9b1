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
   Each row is the median of 5 runs of N calls. */
#define GR_IMPLEMENTATION
#include "grooves.h"
#include "ex_timer.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

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
    return 0;
}
