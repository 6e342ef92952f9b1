/* scripts/fingerprint/fp_grooves.c — grooves.h's answers, hashed: on each
   of the example's scenes, with and without wrapping, random footprints
   (sizes 1e-4 to 0.05 of the tile, aspect down to 1/20, skewed, a fifth of
   the views grazing) through gr_query in five settings (default, §4.4's
   normals, ellipse, straight occlusion, no oversampling or lights),
   gr_query_lines, and gr_query_lines_cached on three neighbouring
   footprints (the cache's hits and misses too); the grid itself as
   gr_grid_build_into() writes it at a fixed address (Linux), the same on
   four grooves that cross themselves (cut into pieces by the builder); and
   gr_poly_boolean's trapezoids and areas for the four operations on
   random star polygons (two rings each, some with a shared vertex height
   or a copy of the other's ring). */
#define _GNU_SOURCE
#define GR_IMPLEMENTATION
#include "grooves.h"
#include "../../examples/grooves/gx_scene.h"
#include <sys/mman.h>
#include "test.h"
#include "fp.h"

#define FP_GRID_AT ((void *)0x7e0000000000ull)

#define FP_PI 3.14159265358979323846
#define FP_SETTINGS 6 /* gr_query in five settings, gr_query_lines */

static unsigned long long fp_list(unsigned long long h, gr_result_t r, const gr_facet_list_t *L)
{
    h = fp_hash(h, &r, sizeof r);
    if (r != GR_OK) return h;
    h = fp_hash(h, &L->count, sizeof L->count);
    h = fp_hash(h, &L->flags, sizeof L->flags);
    h = fp_hash(h, &L->grooves, sizeof L->grooves);
    h = fp_hash(h, &L->subfootprints, sizeof L->subfootprints);
    return fp_hash(h, L->facets, sizeof L->facets[0] * (size_t)L->count);
}

static gr_query_t fp_footprint(t_rng_t *rng, const gx_scene_t *s)
{
    gr_query_t Q;
    double size = exp(log(1e-4) + (log(0.05) - log(1e-4)) * t_rng_unit(rng)), a = 2 * FP_PI * t_rng_unit(rng);
    double asp = 0.05 + 0.95 * t_rng_unit(rng), el = t_rng_unit(rng) < 0.2 ? 1e-3 + 0.05 * t_rng_unit(rng) : asin(t_rng_unit(rng));
    double az = 2 * FP_PI * t_rng_unit(rng), skew = 0.3 * (t_rng_unit(rng) - 0.5);
    memset(&Q, 0, sizeof Q);
    Q.footprint.center[0] = t_rng_unit(rng);
    Q.footprint.center[1] = t_rng_unit(rng);
    Q.footprint.axis1[0] = size * cos(a), Q.footprint.axis1[1] = size * sin(a);
    Q.footprint.axis2[0] = -size * asp * sin(a + skew), Q.footprint.axis2[1] = size * asp * cos(a + skew);
    Q.footprint.view[0] = cos(el) * cos(az), Q.footprint.view[1] = cos(el) * sin(az), Q.footprint.view[2] = sin(el);
    Q.lights = &s->light[0][0];
    Q.light_count = s->nlights;
    return Q;
}

/* The grid's bytes as gr_grid_build_into() writes them at FP_GRID_AT, the
   perturbation callbacks and their user pointers (which move from run to
   run with the program's load address) set to their presence. */
static unsigned long long fp_grid_bytes(const gr_grid_desc_t *gd)
{
    size_t bytes = 0;
    void *mem;
    gr_grid_t *grid;
    unsigned long long h = FP_START;
    if (gr_grid_size(gd, &bytes, NULL) != GR_OK) return 0;
    mem = mmap(FP_GRID_AT, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED_NOREPLACE, -1, 0);
    if (mem != FP_GRID_AT) return 0;
    if (gr_grid_build_into(gd, mem, bytes, &grid, NULL) == GR_OK) {
        int g;
        for (g = 0; g < grid->groove_count + grid->split_records_; g++) {
            gr__groove_t *rec = &grid->grooves_[g];
            rec->perturb = rec->perturb ? (gr_perturb_fn)1 : NULL;
            rec->perturb_user = rec->perturb_user ? (void *)1 : NULL;
        }
        h = fp_hash(h, mem, bytes);
    }
    munmap(mem, bytes);
    return h;
}

static void fp_grid(const gx_scene_t *s, int wrap, int nq, unsigned long long seed)
{
    static gr_line_cache_t cache;
    gr_grid_desc_t gd;
    gr_grid_t *grid = NULL;
    gr_diag_t diag;
    unsigned long long h[FP_SETTINGS + 1];
    size_t sb;
    void *scratch;
    t_rng_t rng;
    int q, v, j;
    memset(&gd, 0, sizeof gd);
    gd.grooves = s->desc, gd.groove_count = s->ngrooves, gd.no_wrap = !wrap;
    if (gr_grid_build(&gd, &grid, &diag) != GR_OK) { printf("grooves   %-13s grid failed: %s\n", s->name, diag.message); return; }
    sb = gr_query_scratch_bytes(grid);
    scratch = malloc(sb);
    memset(&cache, 0, sizeof cache);
    for (v = 0; v <= FP_SETTINGS; v++) h[v] = FP_START;
    rng.s = seed;
    for (q = 0; q < nq; q++) {
        gr_query_t Q = fp_footprint(&rng, s);
        gr_facet_list_t L;
        for (v = 0; v < FP_SETTINGS; v++) {
            gr_query_t V = Q;
            gr_result_t r;
            if (v == 1) V.perturb_normals = -1;
            if (v == 2) V.ellipse = 1;
            if (v == 3) V.straight_occlusion = 1;
            if (v == 4) V.oversample_tol = -1, V.light_count = 0;
            if (v == 5) V.line_samples = 2;
            memset(&L, 0, sizeof L);
            r = v == 5 ? gr_query_lines(grid, &V, scratch, sb, &L, NULL) : gr_query(grid, &V, scratch, sb, &L);
            h[v] = fp_list(h[v], r, &L);
        }
        for (j = 0; j < 3; j++) { /* neighbours through the cache */
            gr_query_t V = Q;
            V.line_samples = 2 + j;
            V.footprint.center[0] += 0.3 * j * V.footprint.axis1[0];
            V.footprint.center[1] += 0.3 * j * V.footprint.axis1[1];
            memset(&L, 0, sizeof L);
            h[FP_SETTINGS] = fp_list(h[FP_SETTINGS], gr_query_lines_cached(grid, &V, &cache, scratch, sb, &L, NULL), &L);
        }
    }
    h[FP_SETTINGS] = fp_hash(h[FP_SETTINGS], &cache.hits, sizeof cache.hits);
    h[FP_SETTINGS] = fp_hash(h[FP_SETTINGS], &cache.misses, sizeof cache.misses);
    printf("grooves   %-13s wrap %d  grid %016llx ", s->name, wrap, fp_grid_bytes(&gd));
    for (v = 0; v <= FP_SETTINGS; v++) printf(" %016llx", h[v]);
    printf("\n");
    free(scratch);
    gr_grid_free(grid);
}

/* A star polygon of n points around c (radii 0.3..1 times r). */
static void fp_star(t_rng_t *rng, int n, const double c[2], double r, double *xy)
{
    int k;
    for (k = 0; k < n; k++) {
        double a = 2 * FP_PI * (k + 0.8 * t_rng_unit(rng)) / n, rho = r * (0.3 + 0.7 * t_rng_unit(rng));
        xy[2 * k] = c[0] + rho * cos(a);
        xy[2 * k + 1] = c[1] + rho * sin(a);
    }
}

static void fp_booleans(int cases)
{
    static double traps[8 * 4096], pa[64], pb[64];
    unsigned long long h = FP_START;
    size_t sb = gr_poly_boolean_scratch_bytes(64);
    void *scratch = malloc(sb);
    t_rng_t rng;
    int q, op;
    rng.s = 42;
    for (q = 0; q < cases; q++) {
        static const double c0[2] = {0, 0};
        double c1[2], cb[2];
        int na = 4 + (int)(t_rng_u64(&rng) % 13), nb = 3 + (int)(t_rng_u64(&rng) % 14), sizes_a[2], sizes_b[2];
        gr_polyset_t A, B;
        c1[0] = 0.9 * (t_rng_unit(&rng) - 0.5), c1[1] = 0.9 * (t_rng_unit(&rng) - 0.5);
        cb[0] = 0.5 * (t_rng_unit(&rng) - 0.5), cb[1] = 0.5 * (t_rng_unit(&rng) - 0.5);
        fp_star(&rng, na, c0, 1.0, pa);
        fp_star(&rng, na, c1, 0.6, pa + 2 * na); /* a second ring (a hole or an island by parity) */
        fp_star(&rng, nb, cb, 0.9, pb);
        if (q % 5 == 0) memcpy(pb, pa, sizeof(double) * 2 * (size_t)(na < nb ? na : nb)); /* shared points */
        if (q % 7 == 0) pb[1] = pa[1];                                                   /* a shared height */
        fp_star(&rng, nb, c1, 0.4, pb + 2 * nb);
        sizes_a[0] = sizes_a[1] = na, sizes_b[0] = sizes_b[1] = nb;
        A.points = pa, A.point_count = 2 * na, A.ring_sizes = sizes_a, A.ring_count = 2;
        B.points = pb, B.point_count = 2 * nb, B.ring_sizes = sizes_b, B.ring_count = 2;
        for (op = 0; op < 4; op++) {
            int n = 0;
            double area = 0;
            gr_result_t r = gr_poly_boolean(&A, &B, (gr_poly_op_t)op, scratch, sb, traps, 4096, &n, &area);
            h = fp_hash(h, &r, sizeof r);
            h = fp_hash(h, &n, sizeof n);
            h = fp_hash(h, &area, sizeof area);
            if (r == GR_OK) h = fp_hash(h, traps, sizeof(double) * 8 * (size_t)n);
        }
    }
    printf("grooves   gr_poly_boolean %016llx  (%d polygon pairs, 4 operations)\n", h, cases);
    free(scratch);
}

/* Grooves that cross themselves (§5: the builder cuts them into pieces):
   an "alpha" polyline, a polyline with two loops in turn (two cuts), a Z
   of three straight cubic pieces (cut at a joint), a looping cubic (cut
   inside its piece), with one light: the scene the example's have none of. */
static void fp_self_crossing(int nq)
{
    static const double alpha[10] = {0.2, 0.3, 0.6, 0.7, 0.8, 0.5, 0.6, 0.3, 0.2, 0.7};
    static const double loops[24] = {0.1, 0.3, 0.3, 0.7, 0.4, 0.5, 0.3, 0.3, 0.1, 0.7, 0.1, 0.9,
                                     0.5, 0.9, 0.55, 0.3, 0.75, 0.7, 0.85, 0.5, 0.75, 0.3, 0.55, 0.7};
    static const double zc[20] = {0.2, 0.2, 0.4, 0.4, 0.6, 0.6, 0.8, 0.8, 0.8, 0.6,
                                  0.8, 0.4, 0.8, 0.2, 0.6, 0.4, 0.4, 0.6, 0.2, 0.8};
    static const double loop[8] = {0.2, 0.3, 1.2, 0.9, 1.2, 0.1, 0.2, 0.7};
    static const double vsec[6] = {-0.01, 0, 0, -0.008, 0.01, 0};
    static const double *pts[4] = {alpha, loops, zc, loop};
    static const int np[4] = {5, 12, 10, 4};
    static gr_groove_desc_t desc[4];
    gx_scene_t s;
    int g, wrap;
    memset(&s, 0, sizeof s);
    memset(desc, 0, sizeof desc);
    for (g = 0; g < 4; g++) {
        desc[g].kind = g < 2 ? GR_PATH_POLYLINE : GR_PATH_CUBIC;
        desc[g].points = pts[g];
        desc[g].point_count = np[g];
        desc[g].section = vsec;
        desc[g].section_count = 3;
    }
    s.name = "selfcross";
    s.desc = desc;
    s.ngrooves = 4;
    s.nlights = 1;
    s.light[0][0] = 0.3, s.light[0][1] = -0.2, s.light[0][2] = sqrt(1 - 0.13);
    for (wrap = 0; wrap < 2; wrap++) fp_grid(&s, wrap, nq, 999);
}

int main(int argc, char **argv)
{
    int i, wrap, nq = argc > 1 ? atoi(argv[1]) : 3000;
    for (i = 0; gx_scene_names[i]; i++) {
        gx_scene_t s;
        memset(&s, 0, sizeof s);
        if (gx_scene_make(&s, gx_scene_names[i])) { printf("grooves   %s: scene failed\n", gx_scene_names[i]); continue; }
        for (wrap = 0; wrap < 2; wrap++) fp_grid(&s, wrap, nq, 1234 + (unsigned long long)i);
        gx_scene_free(&s);
    }
    fp_self_crossing(nq);
    fp_booleans(20000);
    return 0;
}
