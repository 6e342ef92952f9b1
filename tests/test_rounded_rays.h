/* tests/test_rounded_rays.h — ray batteries shared by the rounded_edges.h
   tests: random rays at a mesh, host hit by brute force, query, and the
   comparison with an independent oracle. Include after test.h,
   rounded_edges.h and test_rounded_util.h. */
#ifndef TEST_ROUNDED_RAYS_H
#define TEST_ROUNDED_RAYS_H
#include "test_rounded_checks.h"

/* set by a test whose coordinates are large: compare t within the error
   the positions' own rounding allows, rel * scale / |cos(ray, normal)| */
static int g_t_conditioned;

/* the layout build1() asks for: the compact-layout tests rerun batteries
   with RE_LAYOUT_COMPACT (sphere centres solved at query time) */
static re_layout_t g_layout = RE_LAYOUT_FAST;

/* runs a test with build1() asking for RE_LAYOUT_COMPACT */
static void with_compact_layout(void (*test)(void))
{
    g_layout = RE_LAYOUT_COMPACT;
    test();
    g_layout = RE_LAYOUT_FAST;
}

/* One object of m, radius r, in g_layout; its positions as doubles or
   rounded to float (RE_FLOAT32); re_mesh_t.flat_sin = flat_sin. NULL when
   the build fails (dg says why). */
static re_scene_t *build1_as(const tm_mesh_t *m, double r, int as_float, double flat_sin, re_diag_t *dg)
{
    re_mesh_t mesh;
    re_scene_desc_t desc;
    re_scene_t *s = NULL;
    float *pos = NULL;
    unsigned k;
    memset(&mesh, 0, sizeof mesh);
    memset(&desc, 0, sizeof desc);
    if (as_float) {
        pos = (float *)malloc(sizeof(float) * 3 * (m->nv ? m->nv : 1));
        for (k = 0; k < 3 * m->nv; k++) pos[k] = (float)m->v[k];
        mesh.positions = pos;
        mesh.position_type = RE_FLOAT32;
    } else
        mesh.positions = m->v;
    mesh.vertex_count = m->nv;
    mesh.indices = m->idx;
    mesh.index_count = m->ni;
    mesh.radius = r;
    mesh.flat_sin = flat_sin;
    desc.layout = g_layout;
    desc.objects = &mesh;
    desc.object_count = 1;
    if (re_build(&desc, &s, dg) != RE_OK) s = NULL;
    free(pos);
    return s;
}
static re_scene_t *build1(const tm_mesh_t *m, double r, re_diag_t *dg) { return build1_as(m, r, 0, 0, dg); }
static re_scene_t *build1_float(const tm_mesh_t *m, double r, re_diag_t *dg) { return build1_as(m, r, 1, 0, dg); }

/* re_query_uv() gives re_query()'s answer, bit for bit, whether or not its
   per-triangle bands let it skip the kd-tree (query step 0); and the
   answer's point is o + t d (to a few ulps of the coordinates). */
static long g_uv_skipped, g_uv_calls;
static void check_query_uv(const re_scene_t *s, const double o[3], const double d[3], unsigned tri, double t_host,
                           double u, double v, const re_hit_t *want)
{
    re_hit_t h;
    const re__object_t *ob = &s->objects[0];
    double off = 0, mag = 0;
    int a;
    for (a = 0; a < 3; a++) {
        double x = o[a] + want->t * d[a];
        off = fmax(off, fabs(want->point[a] - x)), mag += fabs(o[a]) + fabs(want->t * d[a]);
    }
    if (!(off <= 8 * RE__DBL_EPS * mag)) T_FAIL("the answer's point is %.3g off o + t d (t %.17g)", off, want->t);
    g_uv_calls++;
    if (tri < ob->n_tris && re__pk_get(&ob->tri_plane, tri) != RE__NONE && re__band_flat(ob, tri, u, v)) g_uv_skipped++;
    re_query_uv(s, o, d, 0, tri, t_host, u, v, &h);
    if (h.kind != want->kind || h.t != want->t || h.normal[0] != want->normal[0] || h.normal[1] != want->normal[1] ||
        h.normal[2] != want->normal[2])
        T_FAIL("re_query_uv: kind %d t %.17g, re_query: kind %d t %.17g (tri %u, u %.9g v %.9g)", (int)h.kind, h.t,
               (int)want->kind, want->t, tri, u, v);
    else
        T_CHECK(1);
}

typedef struct rbox_t { double c[3], half[3], r; } rbox_t;
static double rbox_sdf(const void *ctx, const double p[3])
{
    const rbox_t *b = (const rbox_t *)ctx;
    return tm_rbox_sdf(b->c, b->half, b->r, p);
}

/* rc_feature_ok, counted as a failed check. */
static int check_feature(const re_scene_t *s, const re_hit_t *h, double tol, double scale)
{
    char why[256];
    if (rc_feature_ok(s, h, tol, scale, why, sizeof why)) return 1;
    T_FAIL("%s", why);
    return 0;
}

/* One ray against the sharp mesh + query, compared with the rounded-box
   oracle. Returns 1 if the query changed the host hit. */
/* The largest normal component error check_box_ray has seen (its own
   check allows 1e3 rel: tiny radii turn a point's 1e-9 of the size into
   far more of r); box_exact_vs_analytic asserts the 1e-9. */
static double g_box_normal_worst;

static int check_box_ray(const re_scene_t *s, const tm_mesh_t *m, const rbox_t *b, const double o[3],
                         const double d[3], double rel, double scale, long *n_round, long *n_pass)
{
    double t_host, t_ref, n_ref[3], u, v;
    unsigned tri;
    re_hit_t h;
    if (!tm_hit_uv(m, o, d, &t_host, &tri, &u, &v)) return 0;
    re_query(s, o, d, 0, tri, t_host, &h);
    check_query_uv(s, o, d, tri, t_host, u, v, &h);
    t_ref = tm_trace(rbox_sdf, b, o, d, 1e3 * scale, scale);
    if (h.kind == RE_UNCHANGED || h.kind == RE_HIT_ROUNDED) {
        double p[3];
        if (!T_LT(t_ref, HUGE_VAL)) return 1;
        double tol_t = rel * scale;
        if (g_t_conditioned) { /* t error of a grazing ray grows as 1/cos: bound the point, not t */
            double pr[3], nr[3], c;
            pr[0] = o[0] + t_ref * d[0], pr[1] = o[1] + t_ref * d[1], pr[2] = o[2] + t_ref * d[2];
            tm_rbox_normal(b->c, b->half, b->r, pr, nr);
            c = fabs(tm_dot(nr, d)) / tm_len(d);
            tol_t /= fmax(c, 1e-6);
        }
        if (!T_NEAR(h.t, t_ref, tol_t)) {
            T_FAIL("kind %d t %.17g ref %.17g host %.17g tri %u I (%.6g %.6g %.6g)", (int)h.kind, h.t, t_ref, t_host, tri,
                   o[0] + t_host * d[0], o[1] + t_host * d[1], o[2] + t_host * d[2]);
            return 1;
        }
        p[0] = o[0] + h.t * d[0], p[1] = o[1] + h.t * d[1], p[2] = o[2] + h.t * d[2];
        T_NEAR(tm_rbox_sdf(b->c, b->half, b->r, p), 0.0, rel * scale);
        if (h.kind == RE_HIT_ROUNDED) {
            tm_rbox_normal(b->c, b->half, b->r, p, n_ref);
            g_box_normal_worst = fmax(g_box_normal_worst, fmax(fabs(h.normal[0] - n_ref[0]),
                                                               fmax(fabs(h.normal[1] - n_ref[1]), fabs(h.normal[2] - n_ref[2]))));
            T_NEAR(h.normal[0], n_ref[0], 1e3 * rel);
            T_NEAR(h.normal[1], n_ref[1], 1e3 * rel);
            T_NEAR(h.normal[2], n_ref[2], 1e3 * rel);
            check_feature(s, &h, rel * scale, scale);
            (*n_round)++;
        }
    } else {
        /* pass-through: the rounded box is missed entirely, and the host
           continues from where the ray leaves the sharp box */
        double side = 0, dn = 0, p[3], mag;
        p[0] = o[0] + h.t * d[0], p[1] = o[1] + h.t * d[1], p[2] = o[2] + h.t * d[2];
        mag = fabs(p[0]) + fabs(p[1]) + fabs(p[2]);
        T_EQ(t_ref, HUGE_VAL);
        T_GE(h.t, t_host);
        if (!tm_box_exit_ok(b->c, b->half, p, h.normal, rel * scale + 8 * RE__DBL_EPS * mag, &side, &dn))
            T_FAIL("pass-through at t %.17g (host %.17g) is %.3g outside the sharp box, normal %.3g off its face's", h.t,
                   t_host, side, dn);
        (*n_pass)++;
    }
    return h.kind != RE_UNCHANGED;
}

/* Random rays at the rounded box: half aimed at points near edges and
   corners, a quarter grazing the rounded surface, a quarter anywhere. */
static void box_rays(const double lo[3], const double hi[3], double r, long nrays, double rel, unsigned long long seed)
{
    tm_mesh_t m = {0};
    rbox_t b;
    re_scene_t *s;
    re_diag_t dg;
    t_rng_t rng;
    long i, n_round = 0, n_pass = 0, changed = 0;
    double scale = 0;
    int a;
    rng.s = seed;
    tm_box(&m, lo, hi);
    for (a = 0; a < 3; a++) b.c[a] = 0.5 * (lo[a] + hi[a]), b.half[a] = 0.5 * (hi[a] - lo[a]), scale = fmax(scale, hi[a] - lo[a]);
    b.r = r;
    s = build1(&m, r, &dg);
    if (!T_CHECK(s != NULL)) { tm_free(&m); return; }
    for (i = 0; i < nrays; i++) {
        double o[3], d[3], tgt[3], u, v, w;
        int mode = (int)(i % 4);
        if (mode <= 1) { /* near an edge or corner of the sharp box */
            for (a = 0; a < 3; a++) {
                u = t_rng_unit(&rng);
                tgt[a] = u < 0.35 ? lo[a] + 1.5 * r * t_rng_unit(&rng) : u < 0.7 ? hi[a] - 1.5 * r * t_rng_unit(&rng)
                                                                                    : t_rng_range(&rng, lo[a], hi[a]);
            }
            u = t_rng_range(&rng, 0, 2 * M_PI), v = t_rng_range(&rng, -1, 1), w = sqrt(1 - v * v);
            o[0] = tgt[0] + 3 * scale * w * cos(u), o[1] = tgt[1] + 3 * scale * w * sin(u), o[2] = tgt[2] + 3 * scale * v;
            tm_sub(tgt, o, d);
        } else if (mode == 2) { /* grazing: nearly tangent at a point of the rounded surface */
            double p0[3], n0[3], tdir[3], e[3] = {0.3, 0.5, 0.8}, tt;
            for (a = 0; a < 3; a++) p0[a] = t_rng_range(&rng, lo[a] - 0.1 * scale, hi[a] + 0.1 * scale);
            /* project onto the rounded surface along the gradient (exact for this SDF) */
            for (a = 0; a < 50; a++) {
                double sd = tm_rbox_sdf(b.c, b.half, r, p0);
                tm_rbox_normal(b.c, b.half, r, p0, n0);
                p0[0] -= sd * n0[0], p0[1] -= sd * n0[1], p0[2] -= sd * n0[2];
            }
            tm_rbox_normal(b.c, b.half, r, p0, n0);
            e[0] = t_rng_range(&rng, -1, 1), e[1] = t_rng_range(&rng, -1, 1), e[2] = t_rng_range(&rng, -1, 1);
            tm_cross(n0, e, tdir); tm_norm(tdir);
            tt = -pow(10.0, t_rng_range(&rng, -4, -0.5));
            for (a = 0; a < 3; a++) d[a] = tdir[a] + tt * n0[a];
            for (a = 0; a < 3; a++) o[a] = p0[a] - 2 * scale * d[a] + 1e-3 * scale * n0[a];
        } else {
            for (a = 0; a < 3; a++) tgt[a] = t_rng_range(&rng, lo[a], hi[a]);
            u = t_rng_range(&rng, 0, 2 * M_PI), v = t_rng_range(&rng, -1, 1), w = sqrt(1 - v * v);
            o[0] = tgt[0] + 3 * scale * w * cos(u), o[1] = tgt[1] + 3 * scale * w * sin(u), o[2] = tgt[2] + 3 * scale * v;
            tm_sub(tgt, o, d);
        }
        changed += check_box_ray(s, &m, &b, o, d, rel, scale, &n_round, &n_pass);
    }
    fprintf(stderr, "    rays %ld: rounded %ld, pass-through %ld, changed %ld\n", nrays, n_round, n_pass, changed);
    T_GT(n_round, nrays / 10); /* the rays do exercise the rounded surface */
    T_GT(n_pass, 0);
    re_free(s);
    tm_free(&m);
}

/* poly_rays' aim points: a vertex or a point on a chord, moved by up to
   this many radii along each axis (a test may narrow it to look closely
   at the vertices) */
static double g_poly_jitter = 3.0;
/* poly_rays hands the host's t early by this fraction (a float tracer's
   rounding); an unchanged answer is then off by that much */
static double g_poly_host_early = 0;

/* Rays at a convex polyhedron (hull mesh + planes), compared with sphere
   tracing of dist(x, eroded polytope) - r. Returns rays that hit a corner
   feature of a vertex with degree >= 4 planes. */
static void poly_rays(const tm_mesh_t *m, tm_poly_t *P, double r_req, long nrays, double tol_rel,
                      unsigned long long seed, const char *what)
{
    re_scene_t *s;
    re_diag_t dg;
    re_stats_t st;
    tm_eroded_t E;
    t_rng_t rng;
    double scale, r;
    long i, n_round = 0, n_pass = 0, bad = 0;
    int a;
    rng.s = seed;
    s = build1(m, r_req, &dg);
    if (!T_CHECK(s != NULL)) { fprintf(stderr, "%s: %s\n", what, dg.message); return; }
    re_get_stats(s, &st);
    r = re_object_radius(s, 0);
    T_GT(r, 0.0);
    T_INT_EQ(st.rounded_edges, st.convex_edges); /* a convex hull rounds every convex edge */
    scale = tm_size(m->v, m->nv);
    E.P = P;
    E.r = r;
    tm_erode(P, r);
    {
        const double zero[3] = {0, 0, 0};
        char why[256];
        if (!T_CHECK(rc_features_ok(s, 0, P, m->v, zero, r, tol_rel * scale, why, sizeof why))) T_FAIL("%s: %s", what, why);
    }
    for (i = 0; i < nrays; i++) {
        double o[3], d[3], tgt[3], u, v, w, t_host, t_ref, bu, bv;
        unsigned tri;
        re_hit_t h;
        const double *vx = m->v + 3 * (t_rng_u64(&rng) % m->nv);
        const double *vy = m->v + 3 * (t_rng_u64(&rng) % m->nv);
        double f = i % 2 ? 0 : t_rng_unit(&rng); /* a vertex, or along a chord toward another */
        for (a = 0; a < 3; a++) tgt[a] = vx[a] + f * (vy[a] - vx[a]) + t_rng_range(&rng, -g_poly_jitter, g_poly_jitter) * r;
        u = t_rng_range(&rng, 0, 2 * M_PI), v = t_rng_range(&rng, -1, 1), w = sqrt(1 - v * v);
        o[0] = tgt[0] + 3 * scale * w * cos(u), o[1] = tgt[1] + 3 * scale * w * sin(u), o[2] = tgt[2] + 3 * scale * v;
        tm_sub(tgt, o, d);
        if (!tm_hit_uv(m, o, d, &t_host, &tri, &bu, &bv)) continue;
        t_host *= 1 - g_poly_host_early;
        re_query(s, o, d, 0, tri, t_host, &h);
        check_query_uv(s, o, d, tri, t_host, bu, bv, &h);
        t_ref = tm_trace(tm_eroded_sdf, &E, o, d, 10.0, scale);
        if (h.kind == RE_PASS_THROUGH) {
            double side = 0, dn = 0, p[3];
            n_pass++;
            if (t_ref != HUGE_VAL) { bad++; if (bad < 5) T_FAIL("%s ray %ld: pass-through but reference hits at %.17g", what, i, t_ref); }
            /* the host continues from where the ray leaves the sharp hull */
            for (a = 0; a < 3; a++) p[a] = o[a] + h.t * d[a];
            if (!(h.t >= t_host && tm_hull_exit_ok(P, p, h.normal, tol_rel * scale, &side, &dn))) {
                bad++;
                if (bad < 5) T_FAIL("%s ray %ld: pass-through at t %.17g (host %.17g) is %.3g outside the sharp hull, normal %.3g "
                                    "off its face's", what, i, h.t, t_host, side, dn);
            }
        } else {
            if (h.kind == RE_HIT_ROUNDED) n_round++;
            if (h.kind == RE_HIT_ROUNDED && !check_feature(s, &h, tol_rel * scale, scale)) bad++;
            if (!(fabs(h.t - t_ref) <= tol_rel * scale + (h.kind == RE_UNCHANGED ? g_poly_host_early * t_host * 1.01 : 0))) {
                bad++;
                if (bad < 5) T_FAIL("%s ray %ld: kind %d feature %d t %.17g, reference %.17g (host %.17g)", what, i, (int)h.kind,
                                    (int)h.feature, h.t, t_ref, t_host);
            }
        }
    }
    T_INT_EQ(bad, 0);
    /* not vacuous: some rays must reach the rounded surface. Random rays hit
       it about 5% of the time on an icosphere with r = 0.06 size, so ask for
       2% (a 1-in-20 guard sat at that rate and failed by seed) */
    T_GT(n_round, nrays / 50);
    re_free(s);
}

/* A round rim finely tessellated: an n-sided prism (circumradius 1, z in
   [-1, 1], caps fanned from their centres; top cap triangle i is 2n + i),
   and the distance in the cap's plane from (x, y) to its rounding's eroded
   n-gon (apothem cos(pi/n) - r), 0 inside it. */
static void rim_prism(tm_mesh_t *m, int n)
{
    int i;
    unsigned top_c, bottom_c;
    for (i = 0; i < n; i++) tm_vert(m, cos(2 * M_PI * i / n), sin(2 * M_PI * i / n), -1);
    for (i = 0; i < n; i++) tm_vert(m, cos(2 * M_PI * i / n), sin(2 * M_PI * i / n), 1);
    bottom_c = tm_vert(m, 0, 0, -1), top_c = tm_vert(m, 0, 0, 1);
    for (i = 0; i < n; i++) tm_quad(m, (unsigned)i, (unsigned)((i + 1) % n), (unsigned)(n + (i + 1) % n), (unsigned)(n + i));
    for (i = 0; i < n; i++) tm_tri(m, top_c, (unsigned)(n + i), (unsigned)(n + (i + 1) % n));
    for (i = 0; i < n; i++) tm_tri(m, bottom_c, (unsigned)((i + 1) % n), (unsigned)i);
}
static double rim_eroded_distance(int n, double x, double y, double r)
{
    double sc = (cos(M_PI / n) - r) / cos(M_PI / n), best = HUGE_VAL;
    int i, inside = 1;
    for (i = 0; i < n; i++) {
        double a0 = 2 * M_PI * i / n, a1 = 2 * M_PI * (i + 1) / n;
        double px = sc * cos(a0), py = sc * sin(a0), ex = sc * cos(a1) - px, ey = sc * sin(a1) - py;
        double t = ((x - px) * ex + (y - py) * ey) / (ex * ex + ey * ey);
        if (ex * (y - py) - ey * (x - px) < 0) inside = 0;
        t = t < 0 ? 0 : t > 1 ? 1 : t;
        best = fmin(best, hypot(x - px - t * ex, y - py - t * ey));
    }
    return inside ? 0 : best;
}

/* Answers on rim_prism(n) rounded with r against the exact rounded prism
   (the eroded n-gon times [-1 + r, 1 - r], plus a ball): for each of
   `count` points near the rim, a ray down onto the top cap (re_query) and
   one up from inside it (re_query_exit). Counts the wrong answers, those
   flagged RE_HIT_INCOMPLETE, and the wrong ones not flagged. */
typedef struct rim_tally_t { long queries, wrong, flagged, wrong_unflagged; } rim_tally_t;
static void rim_check(rim_tally_t *t, int layout, const char *how, double x, double y, re_hit_kind_t want, double z,
                      double r, re_hit_kind_t got, const re_hit_t *h)
{
    int wrong = got != want || (got == RE_HIT_ROUNDED && fabs(h->point[2] - z) > 1e-9 * r);
    t->queries++;
    t->flagged += (h->flags & RE_HIT_INCOMPLETE) != 0;
    if (!wrong) return;
    if (t->wrong++ < 3)
        fprintf(stderr, "    layout %d %s at (%.17g, %.17g): kind %d z %.12g flags %u, want %d z %.12g\n", layout, how, x, y,
                got, h->point[2], h->flags, want, z);
    t->wrong_unflagged += !(h->flags & RE_HIT_INCOMPLETE);
}
static void rim_rays(const re_scene_t *s, int n, double r, int count, int layout, rim_tally_t *t)
{
    int k, m = count / 20 > 1 ? count / 20 : 2;
    for (k = 0; k < 20 * m; k++) {
        double phi = 2 * M_PI * (k % m) / m + 0.001, rho = 0.62 + 0.37 * (k / m) / 20.0;
        double x = rho * cos(phi), y = rho * sin(phi), dd = rim_eroded_distance(n, x, y, r);
        double z = (1 - r) + sqrt(r * r - dd * dd), down[3] = {0, 0, -1}, up[3] = {0, 0, 1};
        double o_down[3], o_up[3];
        unsigned tri = 2 * (unsigned)n + (unsigned)(phi / (2 * M_PI / n)) % (unsigned)n;
        re_hit_t h;
        re_hit_kind_t want = dd > 0 ? RE_HIT_ROUNDED : RE_UNCHANGED;
        o_down[0] = o_up[0] = x, o_down[1] = o_up[1] = y, o_down[2] = 3, o_up[2] = 0;
        rim_check(t, layout, "down", x, y, want, z, r, re_query(s, o_down, down, 0, tri, 2.0, &h), &h);
        rim_check(t, layout, "up", x, y, want, z, r, re_query_exit(s, o_up, up, 0, tri, 1.0, &h), &h);
    }
}
/* rim_prism(sides) built with r (not clamped) in `layout`, then rim_rays
   at `count` points into *t; 0 when the build failed (a failed check). */
static int rim_run(int sides, double r, int count, int layout, rim_tally_t *t)
{
    tm_mesh_t m = {0};
    re_diag_t dg;
    re_scene_t *s;
    memset(t, 0, sizeof *t);
    rim_prism(&m, sides);
    g_layout = layout ? RE_LAYOUT_COMPACT : RE_LAYOUT_FAST;
    s = build1(&m, r, &dg);
    g_layout = RE_LAYOUT_FAST;
    if (!T_CHECK(s != NULL)) {
        fprintf(stderr, "    %s\n", dg.message);
        tm_free(&m);
        return 0;
    }
    T_CHECK(re_object_radius(s, 0) == r);
    rim_rays(s, sides, r, count, layout, t);
    fprintf(stderr, "    %d sides, layout %d: %ld queries, %ld wrong, %ld flagged\n", sides, layout, t->queries, t->wrong,
            t->flagged);
    re_free(s);
    tm_free(&m);
    return 1;
}

/* Rays along a face (test_rounded_stiff). */
/* An answer h to the ray o + t d (host hit at t_host) against the sharp
   hull P and the rounded solid E, to tol: a pass-through leaves the hull
   at or past t_host through a face with its normal, any other answer lies
   on the rounded surface. 0 and the reason in why when not. */
static int along_answer_on_surface(const tm_poly_t *P, const tm_eroded_t *E, const double o[3], const double d[3],
                                   double t_host, const re_hit_t *h, double tol, char *why, size_t n)
{
    double p[3], side = 0, dn = 0;
    int a;
    for (a = 0; a < 3; a++) p[a] = o[a] + h->t * d[a];
    if (h->kind == RE_PASS_THROUGH) {
        if (h->t >= t_host && tm_hull_exit_ok(P, p, h->normal, tol, &side, &dn)) return 1;
        snprintf(why, n, "pass-through at t %.17g (host %.17g), %.3g outside the hull", h->t, t_host, side);
        return 0;
    }
    if (fabs(tm_eroded_sdf(E, p)) <= tol) return 1;
    snprintf(why, n, "kind %d at t %.17g is %.3g off the rounded surface", (int)h->kind, h->t, tm_eroded_sdf(E, p));
    return 0;
}
/* The ray nowhere tol deep in the rounded solid from 1e-3 of the size
   before t_host to the answer, at steps + 1 points. */
static int along_answer_not_deep(const tm_eroded_t *E, const double o[3], const double d[3], double t_host,
                                 const re_hit_t *h, double scale, double tol, int steps, char *why, size_t n)
{
    int k, a;
    for (k = 0; k <= steps; k++) {
        double q[3], tt = t_host - 1e-3 * scale + (h->t - t_host + 1e-3 * scale) * k / (double)steps;
        for (a = 0; a < 3; a++) q[a] = o[a] + tt * d[a];
        if (!(tm_eroded_sdf(E, q) > -tol)) {
            snprintf(why, n, "kind %d at t %.17g, but %.3g deep in the rounded solid at t %.17g", (int)h->kind, h->t,
                     -tm_eroded_sdf(E, q), tt);
            return 0;
        }
    }
    return 1;
}

/* A rounded hit h of the ray along d: its reflected ray's origin
   (re_secondary_origin) lies on the sharp hull P, pushed out by the
   documented offset, on that ray. off: the scene's coordinates minus P's
   (NULL: none). 0 and the reason in why when not. */
static int along_reflection_starts_on_hull(const re_scene_t *s, const tm_poly_t *P, const double off[3], const double d[3],
                                           const re_hit_t *h, double scale, char *why, size_t n)
{
    double d2[3], org[3], orgl[3], pl[3], out = 0, off_line = 0, dn = tm_dot(d, h->normal), lo = RE_ORIGIN_OFFSET_REL * scale,
           hi = RE_ORIGIN_OFFSET_REL * sqrt(3.0) * scale;
    int a;
    for (a = 0; a < 3; a++) d2[a] = dn < 0 ? d[a] - 2 * dn * h->normal[a] : d[a];
    re_secondary_origin(s, h, d2, org);
    for (a = 0; a < 3; a++) orgl[a] = org[a] - (off ? off[a] : 0), pl[a] = h->point[a] - (off ? off[a] : 0);
    if (tm_origin_ok(P, orgl, pl, d2, lo, hi, 8 * RE__DBL_EPS * (scale + fabs(org[0]) + fabs(org[1]) + fabs(org[2])), &out,
                     &off_line))
        return 1;
    snprintf(why, n, "rounded hit (feature %d %u) at t %.17g: its reflection starts %.3g outside the sharp hull, %.3g off its ray",
             (int)h->feature, h->feature_index, h->t, out, off_line);
    return 0;
}

/* Rays through every vertex of the hull (v, t) at r_rel of its size (or,
   frac > 0, through the point frac of the way along each triangle's edge
   from that vertex to the next), each in the plane of one of the
   triangles there, in nr directions, tilted by
   up to 1e-10 (the host in __float128): each answer lies on the rounded
   surface, or a pass-through on the sharp hull with a face's normal
   through it, and the ray is nowhere 1e-9 of the size deep in the rounded
   solid before it; a rounded hit's reflected ray starts on the sharp
   hull (along_reflection_starts_on_hull). Adds to *hits the rays that hit
   and returns the failures. */
static long rays_along_faces_of(const double (*v)[3], unsigned nv, const unsigned (*t)[3], unsigned nt, double r_rel, double frac,
                                long nr, long *hits)
{
    static const double tilt[7] = {0, 1e-16, -1e-16, 1e-13, -1e-13, 1e-10, -1e-10};
    static tm_poly_t P;
    tm_mesh_t m = {0}, hm = {0};
    tm_eroded_t E;
    re_scene_t *s;
    re_diag_t dg;
    double scale = tm_size(v[0], nv), tol = 1e-9 * scale, n[3], e1[3], e2[3];
    unsigned k;
    long i, f, bad = 0;
    int a;
    for (k = 0; k < nv; k++) tm_vert(&m, v[k][0], v[k][1], v[k][2]);
    for (k = 0; k < nt; k++) tm_tri(&m, t[k][0], t[k][1], t[k][2]);
    memset(&P, 0, sizeof P);
    tm_hull(v, (int)nv, &hm, &P);
    s = build1(&m, r_rel * scale, &dg);
    if (!T_CHECK(s != NULL)) { tm_free(&m); tm_free(&hm); return 1; }
    E.P = &P, E.r = re_object_radius(s, 0);
    tm_erode(&P, E.r);
    for (f = 0; f < 3 * (long)nt; f++) { /* triangle f / 3, from its vertex f % 3 */
        const double *va = v[t[f / 3][f % 3]], *vb = v[t[f / 3][(f + 1) % 3]], *vc = v[t[f / 3][(f + 2) % 3]];
        tm_sub(vb, va, e1);
        tm_sub(vc, va, e2);
        tm_cross(e1, e2, n);
        tm_norm(n);
        tm_norm(e1);
        tm_cross(n, e1, e2);
        for (i = 0; i < nr; i++) {
            double th = 2 * M_PI * (double)i / (double)nr, d[3], o[3], t_host, bu, bv;
            char why[160];
            unsigned tri;
            re_hit_t h;
            for (a = 0; a < 3; a++)
                d[a] = cos(th) * e1[a] + sin(th) * e2[a] + tilt[i % 7] * n[a], o[a] = va[a] + frac * (vb[a] - va[a]) - 3 * scale * d[a];
            if (!tm_hit_exact_uv(&m, o, d, &t_host, &tri, &bu, &bv)) continue;
            ++*hits;
            re_query(s, o, d, 0, tri, t_host, &h);
            if (!along_answer_on_surface(&P, &E, o, d, t_host, &h, tol, why, sizeof why) && ++bad < 5)
                T_FAIL("triangle %ld vertex %ld ray %ld: %s", f / 3, f % 3, i, why);
            if (!along_answer_not_deep(&E, o, d, t_host, &h, scale, tol, 16, why, sizeof why) && ++bad < 5)
                T_FAIL("triangle %ld vertex %ld ray %ld: %s", f / 3, f % 3, i, why);
            if (h.kind == RE_HIT_ROUNDED && !along_reflection_starts_on_hull(s, &P, NULL, d, &h, scale, why, sizeof why) && ++bad < 5)
                T_FAIL("triangle %ld vertex %ld ray %ld: %s", f / 3, f % 3, i, why);
        }
    }
    re_free(s);
    tm_free(&m);
    tm_free(&hm);
    return bad;
}

#endif
