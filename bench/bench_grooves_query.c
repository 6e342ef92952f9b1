/* bench_grooves_query — cost of one gr_query() (grooves.h, §4) by scene
   and footprint size, single thread, plus grid and scratch memory.

   build/bench/bench_grooves_query out/bench
     → table on stdout, out/bench/grooves_query.csv

   Scenes: one V-groove; the paper's Figure 14 plane (250 parallel
   V-grooves, no ground between them) with footprints covering ~0.1 to
   ~250 grooves; 64 random curved (cubic Bézier) scratches. Each row is
   the median of 5 runs of N queries at random centres. */
#define GR_IMPLEMENTATION
#include "grooves.h"
#include "ex_timer.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct rng_t { unsigned long long s; } rng_t;
static double unit(rng_t *r)
{
    unsigned long long z = (r->s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return (double)((z ^ (z >> 31)) >> 11) * (1.0 / 9007199254740992.0);
}

static int cmp(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

#define QUERY_RUN_SECONDS 0.4

/* ns per query: median of 5 runs of up to n queries, each run stopped after
   QUERY_RUN_SECONDS (footprints over crossings take the §5 polygon path,
   which costs 100-1000x a §4 query). Also the share of queries that the
   polygon path answered (GR_LIST_POLYGON). */
static double time_queries(const gr_grid_t *grid, double radius, double theta, int lights, int n, double *grooves,
                           double *polygon_share)
{
    size_t need = gr_query_scratch_bytes(grid);
    void *scratch = malloc(need);
    double runs[5], light[6] = {0.5, 0.3, 0.812403840463596, -0.4, 0.2, 0.894427190999916};
    int r, i;
    long long seen = 0, done = 0, poly = 0;
    for (r = 0; r < 5; r++) {
        rng_t rng = {(unsigned long long)r + 1};
        double t0 = ex_now();
        for (i = 0; i < n; i++) {
            if ((i & 63) == 63 && ex_now() - t0 > QUERY_RUN_SECONDS) break;
            gr_query_t q;
            gr_facet_list_t l;
            memset(&q, 0, sizeof q);
            q.footprint.center[0] = unit(&rng);
            q.footprint.center[1] = unit(&rng);
            q.footprint.axis1[0] = radius;
            q.footprint.axis2[1] = radius / cos(theta);
            q.footprint.view[0] = 0;
            q.footprint.view[1] = -sin(theta);
            q.footprint.view[2] = cos(theta);
            /* view across the grooves of Figure 14 (they run along v) */
            q.footprint.view[0] = -sin(theta);
            q.footprint.view[1] = 0;
            q.lights = light;
            q.light_count = lights;
            gr_query(grid, &q, scratch, need, &l);
            seen += l.grooves;
            poly += (l.flags & GR_LIST_POLYGON) != 0;
        }
        runs[r] = (ex_now() - t0) / i * 1e9;
        done += i;
    }
    free(scratch);
    *grooves = (double)seen / (double)done;
    *polygon_share = (double)poly / (double)done;
    qsort(runs, 5, sizeof(double), cmp);
    return runs[2];
}

static gr_grid_t *parallel_scene(int n, double *sec, int *nsec)
{
    gr_groove_desc_t *g = (gr_groove_desc_t *)calloc((size_t)n, sizeof *g);
    double *p = (double *)malloc(sizeof(double) * 4 * (size_t)n), w = 1.0 / n;
    gr_grid_desc_t d;
    gr_grid_t *grid = NULL;
    int i;
    sec[0] = -w / 2; sec[1] = 0; sec[2] = 0; sec[3] = -w / 2; sec[4] = w / 2; sec[5] = 0;
    *nsec = 3;
    for (i = 0; i < n; i++) {
        p[4 * i] = (i + 0.5) * w; p[4 * i + 1] = 0; p[4 * i + 2] = (i + 0.5) * w; p[4 * i + 3] = 1;
        g[i].points = p + 4 * i; g[i].point_count = 2; g[i].section = sec; g[i].section_count = 3;
    }
    memset(&d, 0, sizeof d);
    d.grooves = g;
    d.groove_count = n;
    if (gr_grid_build(&d, &grid, NULL) != GR_OK) { fprintf(stderr, "build failed\n"); exit(1); }
    free(g);
    free(p);
    return grid;
}

static gr_grid_t *curved_scene(int n)
{
    static const double sec[8] = {-0.002, 0, -0.001, -0.0015, 0.001, -0.0015, 0.002, 0};
    gr_groove_desc_t *g = (gr_groove_desc_t *)calloc((size_t)n, sizeof *g);
    double *p = (double *)malloc(sizeof(double) * 8 * (size_t)n);
    gr_grid_desc_t d;
    gr_grid_t *grid = NULL;
    rng_t rng = {99};
    int i, k;
    for (i = 0; i < n; i++) {
        for (k = 0; k < 4; k++) { p[8 * i + 2 * k] = unit(&rng); p[8 * i + 2 * k + 1] = unit(&rng); }
        g[i].kind = GR_PATH_CUBIC; g[i].points = p + 8 * i; g[i].point_count = 4;
        g[i].section = sec; g[i].section_count = 4;
    }
    memset(&d, 0, sizeof d);
    d.grooves = g;
    d.groove_count = n;
    if (gr_grid_build(&d, &grid, NULL) != GR_OK) { fprintf(stderr, "build failed\n"); exit(1); }
    free(g);
    free(p);
    return grid;
}

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "out/bench";
    char path[512];
    FILE *csv;
    double sec[6], grooves, polyshare;
    int nsec, i;
    gr_grid_t *one, *fig14, *curved;
    static const double radii[] = {0.0004, 0.004, 0.04, 0.4};
    snprintf(path, sizeof path, "%s/grooves_query.csv", dir);
    csv = fopen(path, "w");
    if (!csv) { fprintf(stderr, "bench_grooves_query: cannot write %s\n", path); return 1; }
    fprintf(csv, "scene,footprint_radius,view_deg,lights,grooves_per_query,polygon_share,ns_per_query,grid_bytes,scratch_bytes\n");
    printf("%-10s %9s %5s %6s %9s %8s %12s %10s %10s\n", "scene", "radius", "view", "lights", "grooves", "poly %", "ns/query",
           "grid B", "scratch B");
    {
        double p1[4] = {0.5, 0, 0.5, 1}, s1[6] = {-0.01, 0, 0, -0.01, 0.01, 0};
        gr_groove_desc_t g;
        gr_grid_desc_t d;
        memset(&g, 0, sizeof g);
        g.points = p1; g.point_count = 2; g.section = s1; g.section_count = 3;
        memset(&d, 0, sizeof d);
        d.grooves = &g; d.groove_count = 1;
        if (gr_grid_build(&d, &one, NULL) != GR_OK) return 1;
    }
    fig14 = parallel_scene(250, sec, &nsec);
    curved = curved_scene(64);
    {
        struct { const char *name; gr_grid_t *grid; } sc[3];
        int s, l;
        sc[0].name = "one"; sc[0].grid = one;
        sc[1].name = "fig14"; sc[1].grid = fig14;
        sc[2].name = "curved64"; sc[2].grid = curved;
        for (s = 0; s < 3; s++)
            for (i = 0; i < 4; i++)
                for (l = 0; l <= 2; l += 2) {
                    double th = 60 * 3.14159265358979 / 180;
                    int n = radii[i] > 0.1 ? 2000 : 20000;
                    double ns = time_queries(sc[s].grid, radii[i], th, l, n, &grooves, &polyshare);
                    printf("%-10s %9.4f %5d %6d %9.1f %8.1f %12.0f %10zu %10zu\n", sc[s].name, radii[i], 60, l, grooves,
                           100 * polyshare, ns, sc[s].grid->bytes, gr_query_scratch_bytes(sc[s].grid));
                    fprintf(csv, "%s,%g,60,%d,%.2f,%.4f,%.1f,%zu,%zu\n", sc[s].name, radii[i], l, grooves, polyshare, ns,
                            sc[s].grid->bytes, gr_query_scratch_bytes(sc[s].grid));
                }
    }
    fclose(csv);
    gr_grid_free(one);
    gr_grid_free(fig14);
    gr_grid_free(curved);
    return 0;
}
