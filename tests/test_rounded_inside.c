/* tests/test_rounded_inside.c — rays from inside (refraction):
   re_query_exit() and re_query_exit_uv() for a ray that leaves the sharp
   mesh through a back face. Oracles: the analytic rounded box and the eroded
   hull, exact distances inside and out. For an origin inside the rounded
   solid the oracle marches the inside distance forward to the exit; for an
   origin in the removed volume it traces the entry forward and the exit
   backward from the exit face (the solids are convex). The host's exit face
   is brute force in double: the reversed ray's first front face. */
#define RE_IMPLEMENTATION
#include "rounded_edges.h"
#include "test.h"
#include "test_rounded_util.h"
#include "test_rounded_rays.h"

/* A convex test solid: its sharp mesh, the oracle's distance, and the
   library's scene built from the mesh. */
typedef struct solid_t {
    tm_mesh_t m;
    tm_sdf_fn sdf;
    const void *ctx;
    double lo[3], hi[3], size;
    re_scene_t *s;
} solid_t;

static void solid_bounds(solid_t *S)
{
    unsigned k;
    int a;
    for (a = 0; a < 3; a++) S->lo[a] = HUGE_VAL, S->hi[a] = -HUGE_VAL;
    for (k = 0; k < S->m.nv; k++)
        for (a = 0; a < 3; a++) S->lo[a] = fmin(S->lo[a], S->m.v[3 * k + a]), S->hi[a] = fmax(S->hi[a], S->m.v[3 * k + a]);
    S->size = fmax(S->hi[0] - S->lo[0], fmax(S->hi[1] - S->lo[1], S->hi[2] - S->lo[2]));
}

/* the outward normal of the oracle surface at p, by central differences */
static void solid_normal(const solid_t *S, const double p[3], double n[3])
{
    double q[3], e = 1e-7 * S->size;
    int a;
    for (a = 0; a < 3; a++) {
        double f1, f0;
        memcpy(q, p, sizeof q), q[a] += e, f1 = S->sdf(S->ctx, q);
        memcpy(q, p, sizeof q), q[a] -= e, f0 = S->sdf(S->ctx, q);
        n[a] = f1 - f0;
    }
    tm_norm(n);
}

/* where the ray from o (inside the solid: sdf < 0) leaves it: march the
   inside distance, exact for both oracles */
static double trace_exit(const solid_t *S, const double o[3], const double d[3])
{
    double t = 0, dl = tm_len(d), p[3];
    int it;
    for (it = 0; it < 2000000; it++) {
        double s;
        p[0] = o[0] + t * d[0], p[1] = o[1] + t * d[1], p[2] = o[2] + t * d[2];
        s = -S->sdf(S->ctx, p);
        if (s <= 1e-15 * S->size || t + s / dl == t) return t;
        t += s / dl;
    }
    return HUGE_VAL;
}

/* The host: the face where the ray from inside leaves the sharp mesh (the
   first front face of the ray reversed from far beyond it), t and u, v. */
static int host_exit(const solid_t *S, const double o[3], const double d[3], double *t, unsigned *tri, double *u, double *v)
{
    return tm_exit_uv(&S->m, o, d, 4 * S->size / tm_len(d), t, tri, u, v);
}

/* re_query_exit and re_query_exit_uv agree bit for bit */
static void exit_query(const solid_t *S, const double o[3], const double d[3], unsigned tri, double t, double u, double v,
                       re_hit_t *h)
{
    re_hit_t g;
    re_query_exit(S->s, o, d, 0, tri, t, h);
    re_query_exit_uv(S->s, o, d, 0, tri, t, u, v, &g);
    if (g.kind != h->kind || g.t != h->t || memcmp(g.normal, h->normal, sizeof g.normal) || memcmp(g.point, h->point, sizeof g.point))
        T_FAIL("re_query_exit_uv: kind %d t %.17g, re_query_exit: kind %d t %.17g", (int)g.kind, g.t, (int)h->kind, h->t);
}

typedef struct tally_t { long rays, rounded, flat, pass, bad; } tally_t;

/* A ray from an origin inside the rounded solid: it leaves where the
   oracle says, through the rounding or the face, never "passes". */
static void check_exit_from_inside(const solid_t *S, const double o[3], const double d[3], double tol, tally_t *n)
{
    double t_host, u, v, t_ref, p[3], nr[3];
    unsigned tri;
    re_hit_t h;
    int a, ok;
    if (!host_exit(S, o, d, &t_host, &tri, &u, &v)) return;
    n->rays++;
    exit_query(S, o, d, tri, t_host, u, v, &h);
    t_ref = trace_exit(S, o, d);
    for (a = 0; a < 3; a++) p[a] = o[a] + t_ref * d[a];
    solid_normal(S, p, nr);
    if (h.kind == RE_HIT_ROUNDED) n->rounded++;
    if (h.kind == RE_UNCHANGED) n->flat++;
    if (h.kind == RE_PASS_THROUGH) n->pass++;
    ok = h.kind != RE_PASS_THROUGH && fabs(h.t - t_ref) * tm_len(d) <= (h.kind == RE_HIT_ROUNDED ? tol : 1e-12) * S->size;
    if (ok && h.kind == RE_HIT_ROUNDED) ok = tm_dot(h.normal, nr) >= 1 - 1e-7 && h.t <= t_host;
    if (!ok && n->bad++ < 5)
        T_FAIL("exit: kind %d t %.17g (host %.17g), reference %.17g, 1 - cos %.3g", (int)h.kind, h.t, t_host, t_ref,
               1 - tm_dot(h.normal, nr));
}

/* A ray from a point of the removed volume (inside the sharp mesh, outside
   the rounded solid): RE_PASS_THROUGH at the host's t when it misses the
   rounded solid on its way out; else where it leaves it, through the
   rounding or the face. */
static void check_from_removed_volume(const solid_t *S, const double o[3], const double d[3], double tol, tally_t *n)
{
    double t_host, u, v, t_in, t_out = HUGE_VAL, e[3], back[3];
    unsigned tri;
    re_hit_t h;
    int a, ok;
    if (!host_exit(S, o, d, &t_host, &tri, &u, &v)) return;
    n->rays++;
    exit_query(S, o, d, tri, t_host, u, v, &h);
    t_in = tm_trace(S->sdf, S->ctx, o, d, t_host, S->size);
    if (t_in < HUGE_VAL) { /* the exit: traced back from the exit face */
        for (a = 0; a < 3; a++) e[a] = o[a] + t_host * d[a], back[a] = -d[a];
        t_out = t_host - tm_trace(S->sdf, S->ctx, e, back, t_host, S->size);
    }
    if (h.kind == RE_HIT_ROUNDED) n->rounded++;
    if (h.kind == RE_PASS_THROUGH) n->pass++;
    if (h.kind == RE_UNCHANGED) n->flat++;
    if (t_in == HUGE_VAL) ok = h.kind == RE_PASS_THROUGH && h.t == t_host;
    else ok = h.kind != RE_PASS_THROUGH && fabs(h.t - t_out) * tm_len(d) <= (h.kind == RE_HIT_ROUNDED ? tol : 1e-12) * S->size;
    if (!ok && n->bad++ < 5)
        T_FAIL("from the removed volume: kind %d t %.17g (host %.17g), reference entry %.17g exit %.17g", (int)h.kind, h.t, t_host,
               t_in, t_out);
}

static void random_dir(t_rng_t *rng, double d[3])
{
    double u = t_rng_range(rng, 0, 2 * M_PI), v = t_rng_range(rng, -1, 1), w = sqrt(1 - v * v);
    d[0] = w * cos(u), d[1] = w * sin(u), d[2] = v;
}

/* n origins inside the rounded solid (its distance below -1e-3 of the
   size: the exit is not at the origin), a third of them within 2r of a
   vertex, and rays in random directions */
static void rays_from_inside(const solid_t *S, double r, long n, double tol, unsigned long long seed, tally_t *c)
{
    t_rng_t rng;
    long i;
    rng.s = seed;
    for (i = 0; i < n; i++) {
        double o[3], d[3];
        int a, tries = 0;
        do {
            const double *vx = S->m.v + 3 * (t_rng_u64(&rng) % S->m.nv);
            for (a = 0; a < 3; a++)
                o[a] = i % 3 ? t_rng_range(&rng, S->lo[a], S->hi[a]) : vx[a] + t_rng_range(&rng, -2, 2) * r;
        } while (S->sdf(S->ctx, o) > -1e-3 * S->size && ++tries < 1000);
        random_dir(&rng, d);
        check_exit_from_inside(S, o, d, tol, c);
    }
}

/* n origins in the removed volume (near a vertex, outside the rounded
   solid by 1e-6 of the size, inside every face plane of the sharp one) */
static void rays_from_removed_volume(const solid_t *S, const tm_poly_t *P, double r, long n, double tol, unsigned long long seed,
                                     tally_t *c)
{
    t_rng_t rng;
    long i;
    rng.s = seed;
    for (i = 0; i < n; i++) {
        double o[3], d[3], out;
        int a, g, tries = 0;
        do {
            const double *vx = S->m.v + 3 * (t_rng_u64(&rng) % S->m.nv);
            for (a = 0; a < 3; a++) o[a] = vx[a] + t_rng_range(&rng, -r, r);
            for (out = -HUGE_VAL, g = 0; g < P->np; g++) out = fmax(out, tm_dot(P->n[g], o) - P->c[g]);
        } while ((out > -1e-9 * S->size || S->sdf(S->ctx, o) < 1e-6 * S->size) && ++tries < 10000);
        if (tries == 10000) continue;
        random_dir(&rng, d);
        check_from_removed_volume(S, o, d, tol, c);
    }
}

static void box_solid(solid_t *S, rbox_t *b, tm_poly_t *P, const double lo[3], const double hi[3], double r)
{
    re_diag_t dg;
    int a;
    memset(S, 0, sizeof *S);
    tm_box(&S->m, lo, hi);
    for (a = 0; a < 3; a++) b->c[a] = 0.5 * (lo[a] + hi[a]), b->half[a] = 0.5 * (hi[a] - lo[a]);
    b->r = r;
    S->sdf = rbox_sdf, S->ctx = b;
    solid_bounds(S);
    S->s = build1(&S->m, r, &dg);
    T_CHECK(S->s != NULL);
    tm_planes(&S->m, P);
}

/* the box of the box cases, r = BOX_R; 0 if its build failed */
#define BOX_R 0.1
static int the_box(solid_t *S, rbox_t *b, tm_poly_t *P)
{
    static const double lo[3] = {-0.6, -0.4, -0.5}, hi[3] = {0.6, 0.4, 0.5};
    box_solid(S, b, P, lo, hi, BOX_R);
    return S->s != NULL;
}

static void solid_free(solid_t *S)
{
    re_free(S->s);
    tm_free(&S->m);
}

static void exits_from_inside_a_box(void)
{
    static tm_poly_t P;
    solid_t S;
    rbox_t b;
    tally_t c = {0, 0, 0, 0, 0};
    if (!the_box(&S, &b, &P)) return;
    rays_from_inside(&S, BOX_R, t_count(30000), 1e-9, 11, &c);
    fprintf(stderr, "    box, from inside: %ld rays, %ld through the rounding, %ld through a face\n", c.rays, c.rounded, c.flat);
    T_INT_EQ(c.bad, 0);
    T_INT_EQ(c.pass, 0);
    T_GT(c.rounded, c.rays / 10);
    T_GT(c.flat, c.rays / 2);
    solid_free(&S);
}

static void from_the_removed_volume_of_a_box(void)
{
    static tm_poly_t P;
    solid_t S;
    rbox_t b;
    tally_t c = {0, 0, 0, 0, 0};
    if (!the_box(&S, &b, &P)) return;
    rays_from_removed_volume(&S, &P, BOX_R, t_count(20000), 1e-9, 12, &c);
    fprintf(stderr, "    box, from the removed volume: %ld rays, %ld leave the rounded solid through the rounding, %ld through a face, %ld miss it\n",
            c.rays, c.rounded, c.flat, c.pass);
    T_INT_EQ(c.bad, 0);
    T_GT(c.rounded, c.rays / 20);
    T_GT(c.flat, c.rays / 20);
    T_GT(c.pass, c.rays / 10);
    solid_free(&S);
}

static void exits_from_inside_random_hulls(void)
{
    t_rng_t rng = {31};
    tally_t c = {0, 0, 0, 0, 0}, cv = {0, 0, 0, 0, 0};
    int k;
    for (k = 0; k < 10; k++) {
        static tm_poly_t P;
        solid_t S;
        tm_eroded_t E;
        re_diag_t dg;
        double r;
        memset(&S, 0, sizeof S);
        tm_random_hull(&rng, 12 + 4 * k, 0.4, 0.6, &S.m, &P);
        solid_bounds(&S);
        S.s = build1(&S.m, 0.06, &dg);
        if (!T_CHECK(S.s != NULL)) { tm_free(&S.m); continue; }
        r = re_object_radius(S.s, 0);
        tm_erode(&P, r);
        E.P = &P, E.r = r;
        S.sdf = tm_eroded_sdf, S.ctx = &E;
        rays_from_inside(&S, r, t_count(3000), 1e-7, 100 + (unsigned long long)k, &c);
        rays_from_removed_volume(&S, &P, r, t_count(1000), 1e-7, 200 + (unsigned long long)k, &cv);
        solid_free(&S);
    }
    fprintf(stderr, "    hulls, from inside: %ld rays, %ld through the rounding; from the removed volume: %ld rays, %ld leave it through the rounding, %ld through a face, %ld miss it\n",
            c.rays, c.rounded, cv.rays, cv.rounded, cv.flat, cv.pass);
    T_INT_EQ(c.bad, 0);
    T_INT_EQ(c.pass, 0);
    T_GT(c.rounded, c.rays / 20);
    T_INT_EQ(cv.bad, 0);
    T_GT(cv.rounded, cv.rays / 20);
    T_GT(cv.flat, cv.rays / 20);
    T_GT(cv.pass, cv.rays / 10);
}

/* Stiff: rays from inside running almost along an edge (direction 1e-3 to
   1e-7 off it, outward), leaving through its rounding far from the origin */
static void grazing_exits_along_an_edge(void)
{
    static tm_poly_t P;
    solid_t S;
    rbox_t b;
    tally_t c = {0, 0, 0, 0, 0};
    t_rng_t rng = {13};
    long i;
    if (!the_box(&S, &b, &P)) return;
    for (i = 0; i < t_count(4000); i++) {
        double o[3], d[3], eps = pow(10.0, -t_rng_range(&rng, 3, 7));
        /* the edge along x at y = 0.4, z = 0.5: the origin inside its rounding's reach */
        o[0] = t_rng_range(&rng, -0.5, 0.0), o[1] = 0.4 - t_rng_range(&rng, 0.02, 0.15), o[2] = 0.5 - t_rng_range(&rng, 0.02, 0.15);
        d[0] = 1, d[1] = eps * t_rng_range(&rng, 0.1, 1), d[2] = eps * t_rng_range(&rng, 0.1, 1);
        if (rbox_sdf(&b, o) > -1e-3) continue;
        check_exit_from_inside(&S, o, d, 1e-9, &c);
    }
    fprintf(stderr, "    grazing: %ld rays, %ld through the rounding, %ld through a face\n", c.rays, c.rounded, c.flat);
    T_INT_EQ(c.bad, 0);
    T_INT_EQ(c.pass, 0);
    T_GT(c.rounded, c.rays / 10);
    solid_free(&S);
}

static void compact_layout_exits_from_inside_a_box(void) { with_compact_layout(exits_from_inside_a_box); }
static void compact_layout_from_the_removed_volume(void) { with_compact_layout(from_the_removed_volume_of_a_box); }

/* bad ids and arguments answer RE_UNCHANGED, as re_query does */
static void exit_query_bad_input(void)
{
    static const double o[3] = {0, 0, 0}, d[3] = {1, 0, 0};
    static tm_poly_t P;
    const double nan_d[3] = {NAN, 0, 0};
    solid_t S;
    rbox_t b;
    re_hit_t h;
    if (!the_box(&S, &b, &P)) return;
    T_INT_EQ(re_query_exit(S.s, o, d, 0, 0, 0.6, NULL), RE_UNCHANGED);
    T_INT_EQ(re_query_exit(NULL, o, d, 0, 0, 0.6, &h), RE_UNCHANGED);
    T_INT_EQ(re_query_exit(S.s, o, d, 1, 0, 0.6, &h), RE_UNCHANGED);
    T_INT_EQ(re_query_exit(S.s, o, d, 0, 12, 0.6, &h), RE_UNCHANGED);
    T_INT_EQ(h.object, 0);
    T_INT_EQ(re_query_exit_uv(S.s, o, nan_d, 0, 0, 0.6, 0.2, 0.2, &h), RE_UNCHANGED);
    T_INT_EQ(re_query_exit(S.s, o, d, 0, 0, HUGE_VAL, &h), RE_UNCHANGED);
    solid_free(&S);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {T_CASE(exits_from_inside_a_box), T_CASE(from_the_removed_volume_of_a_box),
                                     T_CASE(exits_from_inside_random_hulls), T_CASE(grazing_exits_along_an_edge),
                                     T_CASE(compact_layout_exits_from_inside_a_box), T_CASE(compact_layout_from_the_removed_volume),
                                     T_CASE(exit_query_bad_input)};
    return T_RUN(argc, argv, cases);
}
