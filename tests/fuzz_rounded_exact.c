/* libFuzzer target for the exactness of rounded_edges.h on convex
   polyhedra (make fuzz; a short run in make test). fuzz_rounded_build
   checks that any mesh builds or fails cleanly and that answers are valid;
   this one checks that they are right: the input is a convex hull and rays
   at it, and every answer is compared with the independent reference of
   the exactness tests (test_rounded_util.h: sphere tracing of the distance
   to the eroded polytope, minus r), so the fuzzer hunts for the
   polyhedra, radii and rays where the exact corners are not exact.
     byte 0  point count 4 + b % 13
     byte 1  requested radius 2^-(b % 26) (clamped by the build to the
             largest valid one: RE_RADIUS_CLAMP, one patch on a hull)
     byte 2  flags: bit 0 RE_LAYOUT_COMPACT, bit 1 positions rounded to
             float and built as RE_FLOAT32, bit 2 the points offset by
             1e6 (1e3 in float), bit 3 odd rays start inside; bits 4-7
             equal to 5: even rays go along a face (fx_along_face)
             instead of at an aim point
     then    the points, 6 bytes each (three 16-bit coordinates in [-1, 1])
     then    rays, 7 bytes each, at most FX_MAX_RAYS: two vertex ids and a
             fraction (the aim point on the chord between them), a jitter
             of the aim point (two angles and a length in radii), and the
             direction (two angles); a ray that starts inside (flags bit
             3, odd rays) starts on the way from the hull's middle to the
             aim point (the fourth byte the fraction) and goes through
             re_query_exit (fx_exit_ray)
   Inputs whose hull is not a closed 2-manifold (coplanar points), or has
   edges shorter than FX_MIN_EDGE or creases flatter than FX_MIN_SIN or
   than the positions' rounding could make them (where the build may call
   two faces one plane and the reference does not), are skipped. Every
   convex edge is rounded, and for every ray that hits the sharp hull the
   answer agrees with the reference to FX_TOL of the size: the answer's
   point lies on the rounded surface, and the ray does not go deeper than
   FX_TOL into the rounded solid before it (so a ray grazing the surface
   within the tolerance may be answered either way); a rounded hit's
   normal points away from the eroded polytope (to the rounding noise,
   amplified where a cylinder or sphere meets a face: fx_normal); re_query_uv
   gives re_query's answer. A failed check aborts after printing the case. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#define RE_IMPLEMENTATION
#include "rounded_edges.h"
#include "test.h"
#include "test_rounded_util.h"
#include "test_rounded_checks.h"
#include "fuzz_check.h"

#define FX_MAX_RAYS 24
#define FX_TOL 1e-7      /* of the hull's size: the exactness tests' bound */
#define FX_MIN_EDGE 1e-3 /* of the size */
#define FX_MIN_SIN 1e-3  /* sine of the smallest crease angle kept */

static double fx_coord(const uint8_t *b) { return (double)(b[0] | b[1] << 8) / 32767.5 - 1.0; }
static double fx_angle(uint8_t b) { return b * (2 * M_PI / 256); }
static void fx_dir(double th, double z, double out[3])
{
    double w = sqrt(fmax(0.0, 1 - z * z));
    out[0] = w * cos(th), out[1] = w * sin(th), out[2] = z;
}

/* Triangle t's unit normal, and its flat test's tilt bound (the angle its
   plane can turn by when its vertices, up to mag in size, move by their
   rounding eps: RE__FLAT_ROUNDINGS eps mag times its longest edge over
   twice its area, as rounded_edges.h's construction step 2 bounds it). */
static double fx_tri(const tm_mesh_t *m, unsigned t, double eps_mag, double n[3])
{
    double e1[3], e2[3], e3[3], a2, l2;
    tm_sub(m->v + 3 * m->idx[3 * t + 1], m->v + 3 * m->idx[3 * t], e1);
    tm_sub(m->v + 3 * m->idx[3 * t + 2], m->v + 3 * m->idx[3 * t], e2);
    tm_sub(m->v + 3 * m->idx[3 * t + 2], m->v + 3 * m->idx[3 * t + 1], e3);
    tm_cross(e1, e2, n);
    a2 = tm_len(n);
    tm_norm(n);
    l2 = fmax(tm_dot(e1, e1), fmax(tm_dot(e2, e2), tm_dot(e3, e3)));
    return RE__FLAT_ROUNDINGS * eps_mag * sqrt(l2) / a2;
}

/* A closed 2-manifold (each directed edge once, its reverse once, V - E + F
   = 2 over the used vertices) with edges of at least min_edge and creases
   that the build cannot call flat: of sine at least FX_MIN_SIN and twice
   their triangles' tilt bounds (up to RE_FLAT_SIN_LIMIT, where the widened
   flat test stops). *smin: the smallest crease sine (kept as it was when
   larger). */
static int fx_hull_ok(const tm_mesh_t *m, double min_edge, double eps_mag, double *smin)
{
    unsigned nt = m->ni / 3, t, u, k, j, used = 0, ne = 0;
    unsigned char seen[16] = {0};
    for (t = 0; t < nt; t++)
        for (k = 0; k < 3; k++) {
            unsigned a = m->idx[3 * t + k], b = m->idx[3 * t + (k + 1) % 3], fwd = 0, rev = 0;
            double e[3];
            tm_sub(m->v + 3 * b, m->v + 3 * a, e);
            if (tm_len(e) < min_edge) return 0;
            if (a < 16) seen[a] = 1;
            for (u = 0; u < nt; u++)
                for (j = 0; j < 3; j++) {
                    unsigned c = m->idx[3 * u + j], d = m->idx[3 * u + (j + 1) % 3];
                    fwd += c == a && d == b;
                    if (c == b && d == a) { /* the crease between t and u */
                        double n1[3], n2[3], x[3], tilt = fx_tri(m, t, eps_mag, n1) + fx_tri(m, u, eps_mag, n2);
                        rev++;
                        tm_cross(n1, n2, x);
                        if (!(tm_len(x) >= fmax(FX_MIN_SIN, 2 * fmin(tilt, RE_FLAT_SIN_LIMIT)))) return 0;
                        *smin = fmin(*smin, tm_len(x));
                    }
                }
            if (fwd != 1 || rev != 1) return 0;
            ne++;
        }
    for (k = 0; k < 16; k++) used += seen[k];
    return nt >= 4 && (int)used - (int)(ne / 2) + (int)nt == 2;
}

/* tm_erode keeps every pair of the eroded polytope's vertices as a
   candidate segment (all lie in it); the distance needs only its edges,
   the pairs on two common planes, and the fuzzer runs ~5x faster with
   them. An edge missed by the planes' tolerance is shorter than it, so
   the distance moves by less than that. */
static void fx_keep_true_edges(tm_poly_t *P)
{
    int q, ne = 0;
    for (q = 0; q < P->ne; q++) {
        int i = P->e[q][0], j = P->e[q][1];
        unsigned long long a0 = P->mask[i][0] & P->mask[j][0], a1 = P->mask[i][1] & P->mask[j][1];
        if ((a0 && a1) || (a0 & (a0 - 1)) || (a1 & (a1 - 1))) P->e[ne][0] = i, P->e[ne][1] = j, ne++;
    }
    P->ne = ne;
}

/* The reference's distance with facet feet strictly inside the eroded
   polytope (tm_eroded_nearest_tol: the tests' 1e-10 leniency turns
   normals by up to 1e-10 / (r sin) at shallow creases and tiny radii,
   which the fuzzer finds); the true edges are all listed. */
static double fx_sdf(const void *ctx, const double x[3])
{
    double y[3];
    return tm_eroded_nearest_tol((const tm_eroded_t *)ctx, x, y, 0);
}

static void fx_at(const double o[3], const double d[3], double t, double p[3])
{
    p[0] = o[0] + t * d[0], p[1] = o[1] + t * d[1], p[2] = o[2] + t * d[2];
}

/* The deepest the ray goes into the rounded solid over [t0, t1] (the most
   negative distance), sampled finely and refined around the minimum. */
static double fx_deepest(const tm_eroded_t *E, const double o[3], const double d[3], double t0, double t1)
{
    double best = HUGE_VAL, bt = t0, p[3], lo, hi;
    int i, it;
    for (i = 0; i <= 400; i++) {
        double t = t0 + (t1 - t0) * i / 400, s;
        fx_at(o, d, t, p);
        s = fx_sdf(E, p);
        if (s < best) best = s, bt = t;
    }
    /* the distance along a line is convex inside the solid's neighbourhood
       of a convex set: golden-section search around the best sample */
    lo = fmax(t0, bt - (t1 - t0) / 400), hi = fmin(t1, bt + (t1 - t0) / 400);
    for (it = 0; it < 80; it++) {
        double a = lo + 0.382 * (hi - lo), b = lo + 0.618 * (hi - lo), sa, sb;
        fx_at(o, d, a, p);
        sa = fx_sdf(E, p);
        fx_at(o, d, b, p);
        sb = fx_sdf(E, p);
        if (sa < sb) hi = b; else lo = a;
        best = fmin(best, fmin(sa, sb));
    }
    return best;
}

/* One case: the scene built from the hull in world coordinates (mw, the
   local hull offset by off), and the reference in local ones (m, E), where
   its absolute tolerances hold; a world point minus off is exact there. */
typedef struct fx_case_t {
    const re_scene_t *s;
    const tm_mesh_t *mw;
    const tm_eroded_t *E;
    double off[3], scale, mid[3]; /* mid: the vertices' mean (world) */
    double smin;                  /* the hull's smallest crease sine */
    double dmax;                  /* the largest distance from a sphere to its corner's vertex (fx_noise) */
    int exits;                    /* odd rays start inside (re_query_exit) */
    int along;                    /* rays through a vertex or edge point along its face (fx_along_face) */
} fx_case_t;

/* How far each side's eroded polytope may lie from the true one (e,
   fx_normal), in local coordinates: both place their features (sphere
   centres, axes, eroded vertices) from planes crossing at the hull's
   creases and corners, which costs about 450 ulps of the coordinates'
   magnitude mag over the smallest crease sine smin (found: 1.1e-12 for
   the compact layout's solved centres at a crease of sine 1.3e-3,
   1.5e-12 between gcc's and clang's reference at 1.5e-3); the reference
   accepts vertices 1e-11 outside a plane and merges them within 1e-11
   (tm_erode: the library's sphere and the reference's vertex were found
   7e-12 apart in a cluster of eroded vertices); and the build accepts
   eroded vertices RE__CORNER_EPS r |u| outside a plane. Its merge of
   clustered vertices within RE__CORNER_MERGE r |u| only drops vertices
   (the polytope shrinks), so it enters the normal's bound (e_merge), not
   the foot's. r |u| is at most dmax, the largest distance from a sphere
   to its corner's vertex. */
static double fx_noise(double mag, double smin, double r, double dmax)
{
    return 1e-13 * mag / smin + 1e-11 + RE__CORNER_EPS * fmax(r, dmax);
}

/* A rounded hit's outward normal n at p, against the reference, with each
   polytope within e of the true one (fx_noise). Two bounds hold at every
   point and radius:
   - the foot p - r n is a point of the library's polytope, so it lies
     within e (and 1e-6 r, the exactness tests' 1e-6 rad) of the
     reference's: a normal turned by a puts its foot about a r outside,
     unless it turns along a flat face of the polytope;
   - there, where a cylinder or sphere meets a face tangentially, nothing
     sharper holds: the points y1, y2 of two convex sets e apart nearest
     to p (at distances d1, d2) satisfy |y1 - y2|^2 <= e (d1 + d2) (add
     the two projections' variational inequalities), so the normals
     differ by up to (sqrt(e (d1 + d2)) + |d1 - d2|) / d1, about
     sqrt(2 e / r), whichever way the ray comes. Found: 2e-3 rad at a
     seam beside a crease of sine 4e-3 with r = 4.8e-7 and the vertices
     1e-11 apart (an earlier bound, e / (r cos) for a ray at cos to the
     surface, missed it); 5e-4 and 1e-2 at r = 6e-8 at clustered
     corners (once not compared below r = 1e-7 of the size). */
static void fx_normal(const fx_case_t *C, const double p[3], const re_hit_t *h, double mag, int ray)
{
    const tm_eroded_t *E = C->E;
    double y[3], g[3], foot[3], yf[3], d_ref, d_foot, dn, tol_n, r = E->r, e = fx_noise(mag, C->smin, r, C->dmax),
           e_merge = RE__CORNER_MERGE * fmax(r, C->dmax);
    unsigned a;
    for (a = 0; a < 3; a++) foot[a] = p[a] - r * h->normal[a];
    d_foot = fmax(0.0, tm_eroded_nearest_tol(E, foot, yf, 0) + r);
    FUZZ_CHECK(d_foot <= 1e-6 * r + e,
               "ray %d: rounded hit (feature %d %u) at t %.17g, normal (%.12f %.12f %.12f): its foot is %.3g outside the "
               "eroded polytope (r %.9g, e %.3g)", ray, (int)h->feature, h->feature_index, h->t, h->normal[0],
               h->normal[1], h->normal[2], d_foot, r, e);
    d_ref = tm_eroded_nearest_tol(E, p, y, 0) + r;
    tm_sub(p, y, g);
    dn = fabs(g[0] / d_ref - h->normal[0]) + fabs(g[1] / d_ref - h->normal[1]) + fabs(g[2] / d_ref - h->normal[2]);
    tol_n = 1e-6 + (sqrt((e + e_merge) * (r + d_ref)) + fabs(r - d_ref)) / r;
    FUZZ_CHECK(dn <= tol_n,
               "ray %d: rounded hit (feature %d %u) at t %.17g, normal (%.12f %.12f %.12f), the reference's (%.12f %.12f "
               "%.12f), r %.9g, e %.3g", ray, (int)h->feature, h->feature_index, h->t, h->normal[0], h->normal[1],
               h->normal[2], g[0] / d_ref, g[1] / d_ref, g[2] / d_ref, r, e);
}

/* The tolerance of a pushed origin q's height over reference plane g,
   whose coordinates' rounding alone allows tol: the larger of tol and the
   rounding of the library's plane for g's face, plus the reference
   plane's own error, since both planes may stand off the face they stand
   for. The face is the mesh's triangles whose vertices lie within near of
   g; they are exact (their vertices are the input points), and their true
   plane is computed here in __float128 (each product of two edge
   components exact, one rounding per difference). The reference plane's
   part is its distance from the true one at q (tm_hull computes it in
   double from three vertices, which a sliver tilts); the library's is the
   rounding of a plane computed in double from the face's largest
   triangle, as the library's is (construction step 3): 4 DBL_EPSILON
   |e1| |e2| / |e1 x e2| (the normal's rounding, magnified by a sliver)
   times q's distance from that triangle's farthest vertex, which tol
   covers unless the triangle is a sliver. Found: a face of one triangle
   0.0019 high, two of its vertices 2.8e-14 off the reference plane; at a
   rounded hit beside it the reference plane was 2.8e-14 from the true
   one and the library's 3.3e-14 the other way, so the origin stood
   6.1e-14 past the push by the reference (seed
   secondary_origin_above_a_sliver_face, clang's fused build). */
static double fx_height_tol(const fx_case_t *C, int g, const double q[3], double near, double tol)
{
    const tm_mesh_t *m = C->mw;
    const tm_poly_t *P = C->E->P;
    double hq = tm_dot(P->n[g], q) - P->c[g], ref = 0, rounding = 0, largest = 0, v[3][3];
    unsigned t, k, a;
    for (t = 0; t + 2 < m->ni; t += 3) {
        __float128 e1[3], e2[3], n[3], nq = 0, nn = 0;
        double far = 0, l1, l2;
        for (k = 0; k < 3; k++)
            for (a = 0; a < 3; a++) v[k][a] = m->v[3 * m->idx[t + k] + a] - C->off[a]; /* exact (fx_case_t) */
        for (k = 0; k < 3 && fabs(tm_dot(P->n[g], v[k]) - P->c[g]) <= near; k++) {}
        if (k < 3) continue;
        for (a = 0; a < 3; a++) e1[a] = (__float128)v[1][a] - v[0][a], e2[a] = (__float128)v[2][a] - v[0][a];
        n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        for (a = 0; a < 3; a++) nq += n[a] * ((__float128)q[a] - v[0][a]), nn += n[a] * n[a];
        if (!(nn > 0)) continue;
        ref = fmax(ref, fabs((double)nq / sqrt((double)nn) - hq));
        if (!((double)nn > largest)) continue;
        largest = (double)nn;
        l1 = sqrt((double)(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]));
        l2 = sqrt((double)(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]));
        for (k = 0; k < 3; k++) {
            double w[3];
            tm_sub(q, v[k], w);
            far = fmax(far, tm_len(w));
        }
        rounding = 4 * RE__DBL_EPS * l1 * l2 / sqrt(largest) * far;
    }
    return fmax(tol, rounding) + ref;
}

/* Is the origin q outside the reference hull by the push, lo..hi, each
   plane's height to its own tolerance (fx_height_tol, at least tol, so
   only heights tol cannot settle need it: above hi + tol, or, when none
   reaches lo - tol, those of the planes q is near)? *out: the largest
   height. */
static int fx_pushed_out(const fx_case_t *C, const double q[3], double lo, double hi, double tol, double *out)
{
    const tm_poly_t *P = C->E->P;
    double near = 1e-9 * C->scale;
    int g;
    *out = -HUGE_VAL;
    for (g = 0; g < P->np; g++) {
        double h = tm_dot(P->n[g], q) - P->c[g];
        *out = fmax(*out, h);
        if (h > hi + tol && h > hi + fx_height_tol(C, g, q, near, tol)) return 0;
    }
    if (*out >= lo - tol) return 1;
    for (g = 0; g < P->np; g++) {
        double h = tm_dot(P->n[g], q) - P->c[g];
        if (h > -hi - tol && h >= lo - fx_height_tol(C, g, q, near, tol)) return 1;
    }
    return 0;
}
static void fx_secondary(const fx_case_t *C, const double dir[3], const re_hit_t *h, int ray)
{
    double d2[3], org[3], q[3], st[3], dn = tm_dot(dir, h->normal), out, tol, off_line,
           lo = RE_ORIGIN_OFFSET_REL * C->scale, hi = RE_ORIGIN_OFFSET_REL * sqrt(3.0) * C->scale;
    unsigned a;
    for (a = 0; a < 3; a++) d2[a] = dn < 0 ? dir[a] - 2 * dn * h->normal[a] : dir[a];
    re_secondary_origin(C->s, h, d2, org);
    tol = 8 * RE__DBL_EPS * (C->scale + fabs(org[0]) + fabs(org[1]) + fabs(org[2]));
    for (a = 0; a < 3; a++) q[a] = org[a] - C->off[a], st[a] = h->point[a] - C->off[a];
    (void)tm_origin_ok(C->E->P, q, st, d2, lo, hi, tol, &out, &off_line); /* for off_line */
    FUZZ_CHECK(fx_pushed_out(C, q, lo, hi, tol, &out) && off_line <= hi + tol,
               "ray %d: secondary origin of a rounded hit (feature %d %u) is %.17g outside the sharp hull (the push: "
               "%.17g..%.17g, tolerance %.3g, more for sliver faces: fx_height_tol) and %.17g off its ray", ray,
               (int)h->feature, h->feature_index, out, lo, hi, tol, off_line);
}

/* The build's features against the reference hull, once per input
   (rc_features_ok), each polytope within e' of the truth (fx_normal: the
   noise plus the build's merge) and the world coordinates' rounding. */
static void fx_features(const fx_case_t *C)
{
    char why[256];
    double r = C->E->r, mag = C->scale + fabs(C->off[0]) + fabs(C->off[1]) + fabs(C->off[2]),
           e = fx_noise(mag, C->smin, r, C->dmax) + RE__CORNER_MERGE * fmax(r, C->dmax) + 8 * RE__DBL_EPS * mag;
    FUZZ_CHECK(rc_features_ok(C->s, 0, C->E->P, C->mw->v, C->off, r, e, why, sizeof why), "%s", why);
}

/* The _uv form's answer is the plain one's, bit for bit. */
static void fx_same_answer(const re_hit_t *h, const re_hit_t *hu, const char *what, int ray)
{
    FUZZ_CHECK(hu->kind == h->kind && hu->t == h->t && hu->normal[0] == h->normal[0] && hu->normal[1] == h->normal[1] &&
                   hu->normal[2] == h->normal[2],
               "%s ray %d: the _uv query kind %d t %.17g, the plain one kind %d t %.17g", what, ray, (int)hu->kind, hu->t,
               (int)h->kind, h->t);
}

/* An answer that is not a pass-through: its point on the rounded surface,
   and a rounded hit's normal the reference's (fx_normal). */
static void fx_on_surface(const fx_case_t *C, const double o[3], const double dir[3], const re_hit_t *h, double t_host,
                          const char *what, int ray)
{
    double p[3], pw[3], tol = FX_TOL * C->scale;
    unsigned a;
    fx_at(o, dir, h->t, pw);
    for (a = 0; a < 3; a++) p[a] = pw[a] - C->off[a];
    FUZZ_CHECK(fabs(fx_sdf(C->E, p)) <= tol, "%s ray %d: kind %d feature %d at t %.17g is %.3g off the rounded surface "
               "(host t %.17g, r %.17g)", what, ray, (int)h->kind, (int)h->feature, h->t, fx_sdf(C->E, p), t_host, C->E->r);
    if (h->kind == RE_HIT_ROUNDED) {
        fx_normal(C, p, h, C->scale + fabs(pw[0]) + fabs(pw[1]) + fabs(pw[2]), ray);
        char why[256];
        FUZZ_CHECK(rc_feature_ok(C->s, h, FX_TOL * C->scale, C->scale, why, sizeof why), "%s ray %d: %s", what, ray, why);
        fx_secondary(C, dir, h, ray);
    }
}

/* A pass-through: the ray leaves the sharp hull at h.t ("the host
   continues from there"), through the face whose normal the answer gives
   (tm_hull_exit_ok, against all the reference hull's planes). */
static void fx_pass_exit(const fx_case_t *C, const double o[3], const double dir[3], const re_hit_t *h, double t_host,
                         int ray)
{
    double pw[3], p[3], side = 0, dn = 0, tol = FX_TOL * C->scale;
    unsigned a;
    fx_at(o, dir, h->t, pw);
    for (a = 0; a < 3; a++) p[a] = pw[a] - C->off[a];
    FUZZ_CHECK(h->t >= t_host && tm_hull_exit_ok(C->E->P, p, h->normal, tol, &side, &dn),
               "ray %d: pass-through at t %.17g (host %.17g), %.3g outside the sharp hull (tolerance %.3g), normal (%.12f "
               "%.12f %.12f) %.3g from the nearest face's through it (r %.17g)", ray, h->t, t_host, side, tol,
               h->normal[0], h->normal[1], h->normal[2], dn, C->E->r);
}

/* A ray from inside the rounded solid (a point between the hull's middle
   and the aim point, inside the rounded solid by more than the tolerance)
   leaving through the back face the host finds (the first front face of
   the ray reversed from far beyond): re_query_exit must say where it
   leaves the rounded solid, on its surface, at t in [0, t_host], as
   re_query_exit_uv does. A line leaves a convex solid once, so a point on
   the surface past an inside origin is the exit. */
static void fx_exit_ray(const fx_case_t *C, const double tgt[3], double f, const double dir[3], int ray)
{
    const tm_eroded_t *E = C->E;
    double o[3], ol[3], t_host, bu, bv, tol = FX_TOL * C->scale;
    unsigned tri, a;
    re_hit_t h, hu;
    for (a = 0; a < 3; a++) o[a] = C->mid[a] + f * (tgt[a] - C->mid[a]), ol[a] = o[a] - C->off[a];
    if (!(fx_sdf(E, ol) < -tol)) return;
    if (!tm_exit_uv(C->mw, o, dir, 4 * C->scale, &t_host, &tri, &bu, &bv)) return;
    re_query_exit(C->s, o, dir, 0, tri, t_host, &h);
    re_query_exit_uv(C->s, o, dir, 0, tri, t_host, bu, bv, &hu);
    fx_same_answer(&h, &hu, "exit", ray);
    FUZZ_CHECK(h.kind != RE_PASS_THROUGH && h.t >= 0 && h.t <= t_host + tol, /* rounding at a tangent line */
               "exit ray %d from inside: kind %d at t %.17g (host's exit face at %.17g)", ray, (int)h.kind, h.t, t_host);
    fx_on_surface(C, o, dir, &h, t_host, "exit", ray);
}

/* A ray through a vertex or edge point of a hull triangle, lying in its
   plane or tilted off it by 1e-16 to 1e-10 (the flags' mode "along"): it
   only touches the rounded solid, and the capsule contact is a toss of
   the rounding (docs/rounded_edges.md, "Rays along a face"). b[0] picks
   the triangle, b[1] its vertex, b[2] a point on the edge to the next one
   (when odd), b[3] the angle in the plane, b[4] the tilt. */
static void fx_along_face(const fx_case_t *C, const uint8_t *b, double o[3], double dir[3])
{
    static const double tilt[7] = {0, 1e-16, -1e-16, 1e-13, -1e-13, 1e-10, -1e-10};
    const tm_mesh_t *m = C->mw;
    unsigned t = b[0] % (m->ni / 3), k = b[1] % 3, a;
    const double *va = m->v + 3 * m->idx[3 * t + k], *vb = m->v + 3 * m->idx[3 * t + (k + 1) % 3];
    double n[3], e1[3], e2[3], f = b[2] & 1 ? b[2] / 255.0 : 0, th = fx_angle(b[3]), p[3];
    (void)fx_tri(m, t, 0, n);
    tm_sub(vb, va, e1);
    tm_norm(e1);
    tm_cross(n, e1, e2);
    for (a = 0; a < 3; a++) {
        dir[a] = cos(th) * e1[a] + sin(th) * e2[a] + tilt[b[4] % 7] * n[a];
        p[a] = va[a] + f * (vb[a] - va[a]);
        o[a] = p[a] - 3 * C->scale * dir[a];
    }
}

/* One ray: the host's hit on the sharp hull, the query, the reference. */
static void fx_ray(const fx_case_t *C, const uint8_t *b, int ray)
{
    const tm_mesh_t *m = C->mw;
    const tm_eroded_t *E = C->E;
    const double *vx = m->v + 3 * (b[0] % m->nv), *vy = m->v + 3 * (b[1] % m->nv), scale = C->scale;
    double f = b[2] / 255.0, jit[3], dir[3], tgt[3], o[3], ol[3], t_host, bu, bv, t_ref, tol = FX_TOL * scale, deep;
    unsigned tri, a;
    re_hit_t h, hu;
    fx_dir(fx_angle(b[3]), b[4] / 127.5 - 1, jit);
    fx_dir(fx_angle(b[5]), b[6] / 127.5 - 1, dir);
    for (a = 0; a < 3; a++) tgt[a] = vx[a] + f * (vy[a] - vx[a]) + (b[4] & 7) * E->r * jit[a];
    if (C->exits && (ray & 1)) { /* from inside, toward the aim point: the exit query */
        fx_exit_ray(C, tgt, b[3] / 255.0, dir, ray);
        return;
    }
    if (C->along && !(ray & 1)) fx_along_face(C, b, o, dir);
    else
        for (a = 0; a < 3; a++) o[a] = tgt[a] - 3 * scale * dir[a];
    for (a = 0; a < 3; a++) ol[a] = o[a] - C->off[a];
    /* rays along a face: the exact host (tm_hit_exact_uv), since the double
       one's t and slack are noise there */
    if (!(C->along && !(ray & 1) ? tm_hit_exact_uv : tm_hit_uv)(m, o, dir, &t_host, &tri, &bu, &bv)) return;
    re_query(C->s, o, dir, 0, tri, t_host, &h);
    re_query_uv(C->s, o, dir, 0, tri, t_host, bu, bv, &hu);
    fx_same_answer(&h, &hu, "host", ray);
    /* the answer's point is on the rounded surface ... */
    if (h.kind != RE_PASS_THROUGH) fx_on_surface(C, o, dir, &h, t_host, "host", ray);
    else fx_pass_exit(C, o, dir, &h, t_host, ray);
    /* ... and the first one, up to a graze within the tolerance (a ray
       grazing the rounded surface for long the reference cannot follow in
       a fuzzer's time: the exactness tests trace up to 2e6 steps) */
    t_ref = tm_trace_n(fx_sdf, E, ol, dir, 10.0, scale, 20000);
    if (t_ref != t_ref || t_ref == HUGE_VAL) return;
    if (h.kind == RE_PASS_THROUGH) {
        /* the rounded solid missed, or only grazed, up to the face the ray
           leaves the sharp hull by */
        deep = fx_deepest(E, ol, dir, t_ref, t_ref + 4 * scale);
        FUZZ_CHECK(deep >= -tol, "ray %d: pass-through, but the ray goes %.3g deep into the rounded solid from t %.17g "
                   "(host t %.17g, r %.17g)", ray, -deep, t_ref, t_host, E->r);
    } else if (t_ref < h.t - tol) {
        deep = fx_deepest(E, ol, dir, t_ref, h.t);
        FUZZ_CHECK(deep >= -tol, "ray %d: kind %d feature %d at t %.17g, but the ray is %.3g deep in the rounded solid "
                   "from t %.17g (host %.17g, r %.17g)", ray, (int)h.kind, (int)h.feature, h.t, -deep, t_ref, t_host, E->r);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    double pts[16][3], r_req, off;
    int n, i, a, ray;
    float *pos32 = NULL;
    size_t at;
    tm_mesh_t m = {0}, mw = {0};
    static tm_poly_t P;
    tm_eroded_t E;
    fx_case_t C;
    re_mesh_t mesh;
    re_scene_desc_t desc;
    re_scene_t *s = NULL;
    re_diag_t dg;
    re_stats_t st;
    re_result_t rc;
    if (size < 3) return 0;
    n = 4 + data[0] % 13;
    r_req = ldexp(1.0, -(data[1] % 26));
    off = !(data[2] & 4) ? 0.0 : (data[2] & 2) ? 1e3 : 1e6; /* float positions are 6e-5 apart at 1e3 */
    C.off[0] = off, C.off[1] = -off, C.off[2] = off;
    if (size < 3 + 6 * (size_t)n) return 0;
    /* the world points (as floats: those the float build gets), and the
       local ones, the world minus the offset (exact) */
    for (i = 0; i < n; i++)
        for (a = 0; a < 3; a++) {
            double w = fx_coord(data + 3 + 6 * i + 2 * a) + C.off[a];
            if (data[2] & 2) w = (float)w;
            pts[i][a] = w - C.off[a];
        }
    memset(&P, 0, sizeof P);
    tm_hull((const double(*)[3])pts, n, &m, &P);
    C.scale = tm_size(pts[0], (unsigned)n);
    C.smin = 1;
    if (!(C.scale > 0) ||
        !fx_hull_ok(&m, FX_MIN_EDGE * C.scale, ((data[2] & 2) ? RE__FLT_EPS : RE__DBL_EPS) * (off + 1), &C.smin)) {
        tm_free(&m);
        return 0;
    }
    for (i = 0; i < (int)m.nv; i++) tm_vert(&mw, m.v[3 * i] + C.off[0], m.v[3 * i + 1] + C.off[1], m.v[3 * i + 2] + C.off[2]);
    for (i = 0; i < (int)m.ni; i += 3) tm_tri(&mw, m.idx[i], m.idx[i + 1], m.idx[i + 2]);
    memset(&mesh, 0, sizeof mesh);
    memset(&desc, 0, sizeof desc);
    if (data[2] & 2) {
        pos32 = (float *)malloc(sizeof(float) * 3 * mw.nv);
        for (i = 0; i < (int)(3 * mw.nv); i++) pos32[i] = (float)mw.v[i];
        mesh.positions = pos32;
        mesh.position_type = RE_FLOAT32;
    } else
        mesh.positions = mw.v;
    mesh.vertex_count = mw.nv;
    mesh.indices = mw.idx;
    mesh.index_count = mw.ni;
    mesh.radius = r_req * C.scale;
    desc.objects = &mesh;
    desc.object_count = 1;
    desc.layout = (data[2] & 1) ? RE_LAYOUT_COMPACT : RE_LAYOUT_FAST;
    rc = re_build(&desc, &s, &dg);
    FUZZ_CHECK(rc == RE_OK, "a convex hull of %d points (%u triangles) fails to build: %s", n, m.ni / 3, dg.message);
    re_get_stats(s, &st);
    FUZZ_CHECK(st.rounded_edges == st.convex_edges && st.convex_edges == m.ni / 2 && st.concave_edges == 0,
               "a convex hull of %u edges: %llu convex, %llu rounded, %llu concave", m.ni / 2, st.convex_edges, st.rounded_edges,
               st.concave_edges);
    E.P = &P;
    E.r = re_object_radius(s, 0);
    FUZZ_CHECK(E.r > 0 && E.r <= mesh.radius, "radius %.17g for a requested %.17g", E.r, mesh.radius);
    tm_erode(&P, E.r);
    fx_keep_true_edges(&P);
    C.s = s, C.mw = &mw, C.E = &E, C.exits = (data[2] & 8) != 0, C.along = (data[2] >> 4) == 5;
    for (C.dmax = 0, i = 0; i < (int)re_sphere_count(s, 0); i++) {
        re_sphere_t sp;
        double dd[3];
        re_get_sphere(s, 0, (unsigned)i, &sp);
        tm_sub(sp.center, mw.v + 3 * (size_t)sp.vertex, dd);
        C.dmax = fmax(C.dmax, tm_len(dd));
    }
    for (a = 0; a < 3; a++) {
        C.mid[a] = 0;
        for (i = 0; i < (int)mw.nv; i++) C.mid[a] += mw.v[3 * i + a] / mw.nv;
    }
    fx_features(&C);
    for (ray = 0, at = 3 + 6 * (size_t)n; ray < FX_MAX_RAYS && at + 7 <= size; ray++, at += 7) fx_ray(&C, data + at, ray);
    re_free(s);
    free(pos32);
    tm_free(&m);
    tm_free(&mw);
    return 0;
}
