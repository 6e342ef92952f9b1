/* tests/test_rounded_util.h — meshes, host hits and independent oracles for
   the rounded_edges.h tests. Nothing here calls the code under test. */
#ifndef TEST_ROUNDED_UTIL_H
#define TEST_ROUNDED_UTIL_H
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct tm_mesh_t {
    double *v;
    unsigned nv, cap_v;
    unsigned *idx;
    unsigned ni, cap_i;
} tm_mesh_t;

static void tm_free(tm_mesh_t *m) { free(m->v); free(m->idx); memset(m, 0, sizeof *m); }
static unsigned tm_vert(tm_mesh_t *m, double x, double y, double z)
{
    if (m->nv == m->cap_v) { m->cap_v = m->cap_v ? 2 * m->cap_v : 64; m->v = (double *)realloc(m->v, sizeof(double) * 3 * m->cap_v); }
    m->v[3 * m->nv] = x, m->v[3 * m->nv + 1] = y, m->v[3 * m->nv + 2] = z;
    return m->nv++;
}
static void tm_tri(tm_mesh_t *m, unsigned a, unsigned b, unsigned c)
{
    if (m->ni + 3 > m->cap_i) { m->cap_i = m->cap_i ? 2 * m->cap_i : 192; m->idx = (unsigned *)realloc(m->idx, sizeof(unsigned) * m->cap_i); }
    m->idx[m->ni++] = a, m->idx[m->ni++] = b, m->idx[m->ni++] = c;
}
/* quad a b c d counter-clockwise from outside, split along a-c */
static void tm_quad(tm_mesh_t *m, unsigned a, unsigned b, unsigned c, unsigned d) { tm_tri(m, a, b, c); tm_tri(m, a, c, d); }

/* the six faces of a box whose corner i (bit 0: x, 1: y, 2: z at the
   high side) is vertex b[i], wound outward */
static void tm_box_faces(tm_mesh_t *m, const unsigned b[8])
{
    tm_quad(m, b[0], b[2], b[3], b[1]); /* z- */
    tm_quad(m, b[4], b[5], b[7], b[6]); /* z+ */
    tm_quad(m, b[0], b[1], b[5], b[4]); /* y- */
    tm_quad(m, b[2], b[6], b[7], b[3]); /* y+ */
    tm_quad(m, b[0], b[4], b[6], b[2]); /* x- */
    tm_quad(m, b[1], b[3], b[7], b[5]); /* x+ */
}
/* axis-aligned box [lo, hi] */
static void tm_box(tm_mesh_t *m, const double lo[3], const double hi[3])
{
    unsigned b[8], i;
    for (i = 0; i < 8; i++) b[i] = tm_vert(m, i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]);
    tm_box_faces(m, b);
}

static void tm_sub(const double a[3], const double b[3], double o[3]) { o[0] = a[0] - b[0], o[1] = a[1] - b[1], o[2] = a[2] - b[2]; }
static double tm_dot(const double a[3], const double b[3]) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
static void tm_cross(const double a[3], const double b[3], double o[3])
{
    double x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2], z = a[0] * b[1] - a[1] * b[0];
    o[0] = x, o[1] = y, o[2] = z;
}
static double tm_len(const double a[3]) { return sqrt(tm_dot(a, a)); }
static void tm_norm(double a[3]) { double l = tm_len(a); a[0] /= l, a[1] /= l, a[2] /= l; }
/* The size of n points (x, y, z each): their largest extent along an axis. */
static double tm_size(const double *v, unsigned n)
{
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    unsigned k, a;
    for (k = 0; k < n; k++)
        for (a = 0; a < 3; a++) lo[a] = fmin(lo[a], v[3 * k + a]), hi[a] = fmax(hi[a], v[3 * k + a]);
    return fmax(hi[0] - lo[0], fmax(hi[1] - lo[1], hi[2] - lo[2]));
}

/* Brute-force nearest front-face hit (Moller-Trumbore in double), with its
   barycentric coordinates u, v (point = (1-u-v) p0 + u p1 + v p2). */
static int tm_hit_uv(const tm_mesh_t *m, const double o[3], const double d[3], double *t_out, unsigned *tri_out,
                     double *u_out, double *v_out)
{
    unsigned t;
    double best = HUGE_VAL;
    int found = 0;
    for (t = 0; t < m->ni / 3; t++) {
        const double *a = m->v + 3 * m->idx[3 * t], *b = m->v + 3 * m->idx[3 * t + 1], *c = m->v + 3 * m->idx[3 * t + 2];
        double e1[3], e2[3], p[3], q[3], s[3], det, u, v, tt, n[3];
        tm_sub(b, a, e1);
        tm_sub(c, a, e2);
        tm_cross(e1, e2, n);
        /* a back face, or a ray in the face's plane (within rounding: its
           det would be noise, and so t, u, v; fuzz_rounded_exact) */
        if (tm_dot(n, d) >= -1e-12 * tm_len(n) * tm_len(d)) continue;
        tm_cross(d, e2, p);
        det = tm_dot(e1, p);
        if (det == 0) continue;
        tm_sub(o, a, s);
        u = tm_dot(s, p) / det;
        if (u < -1e-12 || u > 1 + 1e-12) continue;
        tm_cross(s, e1, q);
        v = tm_dot(d, q) / det;
        if (v < -1e-12 || u + v > 1 + 1e-12) continue;
        tt = tm_dot(e2, q) / det;
        if (tt > 0 && tt < best) best = tt, *tri_out = t, *u_out = u, *v_out = v, found = 1;
    }
    *t_out = best;
    return found;
}
/* tm_hit_uv with every product and sum in __float128 and u, v inside the
   triangle to 1e-24: the host for rays along a face. A ray 1e-10 off
   a face's plane makes tm_hit_uv's double t noisy by about 1e-16 / 1e-10
   of the size, and its slack accepts a triangle the ray passes beside
   (fuzz_rounded_exact found a point 1e-5 along the ray, past the face's
   edge and 1.1e-6 outside the hull: the host's fault). */
static int tm_hit_exact_uv(const tm_mesh_t *m, const double o[3], const double d[3], double *t_out, unsigned *tri_out,
                           double *u_out, double *v_out)
{
    unsigned t, a;
    __float128 best = 0;
    int found = 0;
    for (t = 0; t < m->ni / 3; t++) {
        const double *A = m->v + 3 * m->idx[3 * t], *B = m->v + 3 * m->idx[3 * t + 1], *C = m->v + 3 * m->idx[3 * t + 2];
        __float128 e1[3], e2[3], n[3], w[3], num = 0, den = 0, tt, d00 = 0, d01 = 0, d11 = 0, d20 = 0, d21 = 0, det, uu, vv;
        for (a = 0; a < 3; a++) e1[a] = (__float128)B[a] - A[a], e2[a] = (__float128)C[a] - A[a];
        n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
        for (a = 0; a < 3; a++) num += n[a] * ((__float128)A[a] - o[a]), den += n[a] * d[a];
        if (!(den < 0)) continue; /* a back face, or a ray in the plane */
        tt = num / den;
        if (!(tt > 0) || (found && !(tt < best))) continue;
        for (a = 0; a < 3; a++) w[a] = (__float128)o[a] + tt * d[a] - A[a];
        for (a = 0; a < 3; a++)
            d00 += e1[a] * e1[a], d01 += e1[a] * e2[a], d11 += e2[a] * e2[a], d20 += w[a] * e1[a], d21 += w[a] * e2[a];
        det = d00 * d11 - d01 * d01;
        uu = (d11 * d20 - d01 * d21) / det, vv = (d00 * d21 - d01 * d20) / det;
        if (uu < -1e-24 || vv < -1e-24 || uu + vv > 1 + 1e-24) continue; /* a ray exactly through a vertex or edge */
        best = tt, found = 1, *tri_out = t, *u_out = (double)uu, *v_out = (double)vv;
    }
    *t_out = found ? (double)best : HUGE_VAL;
    return found;
}
static int tm_hit(const tm_mesh_t *m, const double o[3], const double d[3], double *t_out, unsigned *tri_out)
{
    double u, v;
    return tm_hit_uv(m, o, d, t_out, tri_out, &u, &v);
}

/* The host for a ray from inside: the face where it leaves the sharp mesh
   (the first front face of the ray reversed from far beyond it, `far` in
   units of d), its t and u, v. */
static int tm_exit_uv(const tm_mesh_t *m, const double o[3], const double d[3], double far, double *t_out,
                      unsigned *tri_out, double *u_out, double *v_out)
{
    double o2[3], d2[3], t2;
    int a;
    for (a = 0; a < 3; a++) o2[a] = o[a] + far * d[a], d2[a] = -d[a];
    if (!tm_hit_uv(m, o2, d2, &t2, tri_out, u_out, v_out)) return 0;
    *t_out = far - t2;
    return 1;
}

/* tm_hull_exit_ok for the box of centre c and half sizes half: p lies
   within tol of its boundary (*side, the largest of |p - c| - half) and a
   face within tol of p has normal n (*dn, the smallest L1 difference). */
static int tm_box_exit_ok(const double c[3], const double half[3], const double p[3], const double n[3], double tol,
                          double *side, double *dn)
{
    int a;
    *side = -HUGE_VAL, *dn = HUGE_VAL;
    for (a = 0; a < 3; a++) {
        double s = fabs(p[a] - c[a]) - half[a];
        *side = fmax(*side, s);
        if (fabs(s) <= tol) /* face a on p's side: normal +-e_a */
            *dn = fmin(*dn, fabs(n[0] - (a == 0 ? copysign(1.0, p[a] - c[a]) : 0.0)) +
                                fabs(n[1] - (a == 1 ? copysign(1.0, p[a] - c[a]) : 0.0)) +
                                fabs(n[2] - (a == 2 ? copysign(1.0, p[a] - c[a]) : 0.0)));
    }
    return fabs(*side) <= tol && *dn <= 1e-6;
}
/* ---- Oracle 1: the analytic rounded box (inner box (+) ball) ---- */
static double tm_rbox_sdf(const double c[3], const double half[3], double r, const double p[3])
{
    double q[3], m = -HUGE_VAL, o = 0;
    int i;
    for (i = 0; i < 3; i++) {
        q[i] = fabs(p[i] - c[i]) - (half[i] - r);
        m = fmax(m, q[i]);
        o += q[i] > 0 ? q[i] * q[i] : 0;
    }
    return sqrt(o) + fmin(m, 0.0) - r;
}
static void tm_rbox_normal(const double c[3], const double half[3], double r, const double p[3], double n[3])
{
    double q[3];
    int i, k = 0;
    (void)r;
    for (i = 0; i < 3; i++) q[i] = fabs(p[i] - c[i]) - (half[i] - r);
    if (q[0] > 0 || q[1] > 0 || q[2] > 0) {
        for (i = 0; i < 3; i++) n[i] = q[i] > 0 ? (p[i] > c[i] ? q[i] : -q[i]) : 0;
        tm_norm(n);
        return;
    }
    for (i = 1; i < 3; i++) if (q[i] > q[k]) k = i;
    n[0] = n[1] = n[2] = 0;
    n[k] = p[k] > c[k] ? 1 : -1;
}

/* Sphere tracing of an exact distance (1-Lipschitz), then the residual.
   Returns the first t with sdf <= eps*scale, or where the step no longer
   moves t (a long d: the distance is then below t's ulp times |d|), or
   HUGE_VAL beyond tmax; after max_steps steps (a ray grazing the surface
   for long) NAN. */
typedef double (*tm_sdf_fn)(const void *ctx, const double p[3]);
static double tm_trace_n(tm_sdf_fn f, const void *ctx, const double o[3], const double d[3], double tmax, double scale,
                         long max_steps)
{
    double t = 0, dl = tm_len(d), p[3];
    long it;
    for (it = 0; it < max_steps; it++) {
        double s;
        p[0] = o[0] + t * d[0], p[1] = o[1] + t * d[1], p[2] = o[2] + t * d[2];
        s = f(ctx, p);
        if (s <= 1e-15 * scale || t + s / dl == t) return t;
        t += s / dl;
        if (t > tmax) return HUGE_VAL;
    }
    return NAN;
}
static double tm_trace(tm_sdf_fn f, const void *ctx, const double o[3], const double d[3], double tmax, double scale)
{
    double t = tm_trace_n(f, ctx, o, d, tmax, scale, 2000000);
    return t == t ? t : HUGE_VAL;
}

/* ---- Oracle 2: distance to the eroded polytope E = {x : n_i.x <= c_i - r}.
   Every candidate below is a point set inside E (a feasible projection onto
   a facet plane, a segment between two vertices of E, a vertex), and the nearest point of E lies on one of them, so the minimum
   over candidates is the distance. Vertices come from all plane triples
   (global, nothing shared with the library's per-corner construction). ---- */
typedef struct tm_poly_t {
    int np; /* <= 128 */
    double n[128][3], c[128];
    int nv;
    double v[512][3];
    unsigned long long mask[512][2];
    int ne;
    int e[8192][2];
} tm_poly_t;

/* The point where planes i, j, k of P, each moved in by r, meet, solved
   and checked against every plane in __float128: the double planes' own
   polytope, to the rounding of its vertices to double. A double solve's
   error grows as 1/det where three planes are nearly parallel (found by
   fuzz_rounded_exact: at r = 5e-8, three planes within 2e-3 rad of each
   other gave a vertex 4e-8 outside four planes, accepted by a tolerance
   of the solve's size, and the reference's nearest point moved 0.3 r).
   x comes in as the double solve, off by at most err: planes it lies
   deeper in than 1e-6 + err need no quad check. *mk gets the planes
   within 1e-9 of the point. Returns 0 where the point lies outside a
   plane. */
static int tm_eroded_vertex(const tm_poly_t *P, double r, int i, int j, int k, double err, double x[3],
                            unsigned long long mk[2])
{
    const int id[3] = {i, j, k};
    __float128 n[3][3], c[3], a[3], b[3], cc[3], det, xq[3];
    int g, q;
    for (g = 0; g < 3; g++) {
        for (q = 0; q < 3; q++) n[g][q] = P->n[id[g]][q];
        c[g] = (__float128)P->c[id[g]] - r;
    }
    for (q = 0; q < 3; q++) {
        int u = (q + 1) % 3, w = (q + 2) % 3;
        a[q] = n[1][u] * n[2][w] - n[1][w] * n[2][u];
        b[q] = n[2][u] * n[0][w] - n[2][w] * n[0][u];
        cc[q] = n[0][u] * n[1][w] - n[0][w] * n[1][u];
    }
    det = n[0][0] * a[0] + n[0][1] * a[1] + n[0][2] * a[2];
    for (q = 0; q < 3; q++) xq[q] = (c[0] * a[q] + c[1] * b[q] + c[2] * cc[q]) / det;
    mk[0] = mk[1] = 0;
    for (g = 0; g < P->np; g++) {
        __float128 sv = -((__float128)P->c[g] - r);
        if (tm_dot(P->n[g], x) - (P->c[g] - r) < -(1e-6 + err)) continue;
        for (q = 0; q < 3; q++) sv += (__float128)P->n[g][q] * xq[q];
        /* 1e-11 outside, as tm_erode always allowed: at the largest
           valid radius the polytope shrinks to a point or a segment, which
           the double planes may miss by their own rounding (the library's
           clamped radius is a double too). The quad solve's own error lies
           far below that down to the det of 1e-12 that tm_erode keeps. */
        if (sv > 1e-11) return 0;
        if (sv > -1e-9) mk[g >> 6] |= 1ull << (g & 63);
    }
    for (q = 0; q < 3; q++) x[q] = (double)xq[q];
    return 1;
}

static void tm_erode(tm_poly_t *P, double r)
{
    int i, j, k, g, q;
    P->nv = 0;
    for (i = 0; i < P->np; i++)
        for (j = i + 1; j < P->np; j++)
            for (k = j + 1; k < P->np; k++) {
                double a[3], b[3], cc[3], x[3], det, feas, ci = P->c[i] - r, cj = P->c[j] - r, ck = P->c[k] - r;
                int ok = 1;
                unsigned long long mk[2];
                tm_cross(P->n[j], P->n[k], a);
                tm_cross(P->n[k], P->n[i], b);
                tm_cross(P->n[i], P->n[j], cc);
                det = tm_dot(P->n[i], a);
                if (fabs(det) < 1e-12) continue;
                for (q = 0; q < 3; q++) x[q] = (ci * a[q] + cj * b[q] + ck * cc[q]) / det;
                /* a double pre-filter, lenient by far more than the solve's
                   rounding (large where two of the planes are nearly
                   parallel); tm_eroded_vertex decides */
                feas = fmax(1e-9, 1024 * DBL_EPSILON * (fabs(ci) + fabs(cj) + fabs(ck)) / fabs(det));
                for (g = 0; g < P->np && ok; g++)
                    if (tm_dot(P->n[g], x) - (P->c[g] - r) > feas) ok = 0;
                if (!ok || !tm_eroded_vertex(P, r, i, j, k, feas, x, mk)) continue;
                for (q = 0; q < P->nv; q++) { double dd[3]; tm_sub(P->v[q], x, dd); if (tm_len(dd) < 1e-11) break; }
                if (q < P->nv) { P->mask[q][0] |= mk[0], P->mask[q][1] |= mk[1]; continue; }
                if (P->nv == 512) continue;
                P->mask[P->nv][0] = mk[0], P->mask[P->nv][1] = mk[1];
                memcpy(P->v[P->nv++], x, sizeof x);
            }
    P->ne = 0;
    for (i = 0; i < P->nv; i++)
        for (j = i + 1; j < P->nv; j++) {
            /* every segment between two points of E lies in E (convexity), so
               all pairs are safe candidates and the true edges are among them;
               for large polytopes keep the pairs sharing two planes (loose tolerance) */
            unsigned long long a0 = P->mask[i][0] & P->mask[j][0], a1 = P->mask[i][1] & P->mask[j][1];
            int two = (a0 && a1) || (a0 & (a0 - 1)) || (a1 & (a1 - 1));
            if ((P->nv <= 64 || two) && P->ne < 8192) P->e[P->ne][0] = i, P->e[P->ne][1] = j, P->ne++;
        }
}
/* A pass-through's exit point p and normal n on the hull of planes P: p
   lies within tol of the hull's boundary (*side, its largest plane side)
   and some face within tol of p has normal n (*dn, the smallest L1
   difference). A line meets a convex hull's boundary at its entry and its
   exit only, so past the entry such a point is the exit. */
static int tm_hull_exit_ok(const tm_poly_t *P, const double p[3], const double n[3], double tol, double *side, double *dn)
{
    int g;
    *side = -HUGE_VAL, *dn = HUGE_VAL;
    for (g = 0; g < P->np; g++) *side = fmax(*side, tm_dot(P->n[g], p) - P->c[g]);
    for (g = 0; g < P->np; g++)
        if (fabs(tm_dot(P->n[g], p) - P->c[g]) <= tol)
            *dn = fmin(*dn, fabs(P->n[g][0] - n[0]) + fabs(P->n[g][1] - n[1]) + fabs(P->n[g][2] - n[2]));
    return fabs(*side) <= tol && *dn <= 1e-6;
}
/* A secondary-ray origin org for the ray start + t d leaving the hull of
   planes P: whether it lies outside the hull by between push_lo - tol and
   push_hi + tol (*out, its largest plane side) and within push_hi + tol of
   the ray's line (*off_line). */
static int tm_origin_ok(const tm_poly_t *P, const double org[3], const double start[3], const double d[3], double push_lo,
                        double push_hi, double tol, double *out, double *off_line)
{
    double w[3], x[3];
    int g;
    *out = -HUGE_VAL;
    for (g = 0; g < P->np; g++) *out = fmax(*out, tm_dot(P->n[g], org) - P->c[g]);
    tm_sub(org, start, w);
    tm_cross(w, d, x);
    *off_line = tm_len(x) / tm_len(d);
    return *out >= push_lo - tol && *out <= push_hi + tol && *off_line <= push_hi + tol;
}
/* The point of segment ab nearest to p in q; returns its distance. */
static double tm_seg_nearest(const double p[3], const double a[3], const double b[3], double q[3])
{
    double ab[3], ap[3], bp[3], t, dq[3];
    tm_sub(b, a, ab); tm_sub(p, a, ap); tm_sub(p, b, bp);
    t = tm_dot(ab, ab) > 0 ? tm_dot(ap, ab) / tm_dot(ab, ab) : 0;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    /* from the nearer end: t's rounding moves q along the segment by ulps
       of its length times t, which turns p - q by that over |p - q| (an
       edge 1e6 long, r 6e-8: 2.5e-3 rad from a; fuzz_rounded_build) */
    if (t <= 0.5) q[0] = a[0] + t * ab[0], q[1] = a[1] + t * ab[1], q[2] = a[2] + t * ab[2];
    else {
        double u = tm_dot(ab, ab) > 0 ? -tm_dot(bp, ab) / tm_dot(ab, ab) : 0; /* 1 - t, from b */
        u = u < 0 ? 0 : u > 1 ? 1 : u;
        q[0] = b[0] - u * ab[0], q[1] = b[1] - u * ab[1], q[2] = b[2] - u * ab[2];
    }
    tm_sub(q, p, dq);
    return tm_len(dq);
}
/* A point p with normal n on the surface around segment ab (a sphere when
   a == b): *dist its distance from the segment, *dn the L1 difference
   between n and the direction from the segment's nearest point to p. */
static void tm_capsule_point(const double p[3], const double n[3], const double a[3], const double b[3], double *dist,
                             double *dn)
{
    double q[3], w[3];
    int k;
    *dist = tm_seg_nearest(p, a, b, q);
    tm_sub(p, q, w);
    for (*dn = 0, k = 0; k < 3; k++) *dn += fabs(w[k] / *dist - n[k]);
}
typedef struct tm_eroded_t { const tm_poly_t *P; double r; } tm_eroded_t;
/* The signed distance to the rounded solid E (+) ball(r) at x, and in y the
   point of E nearest to x (x itself inside E), so that outside E the
   outward normal is (x - y) / |x - y|. A facet's foot counts when it lies
   within foot_tol of the other planes: the tests' 1e-10 may only
   underestimate the distance, near a crease of sine sin by about
   (foot_tol / sin)^2 / r, and turn the normal by foot_tol / (r sin); 0
   takes the edges' and vertices' distance there instead (exact when they
   are all listed, as they are up to 64 vertices). */
static double tm_eroded_nearest_tol(const tm_eroded_t *E, const double x[3], double y[3], double foot_tol)
{
    const tm_poly_t *P = E->P;
    double best = HUGE_VAL, inside = -HUGE_VAL, q[3];
    int g, k;
    for (g = 0; g < P->np; g++) inside = fmax(inside, tm_dot(P->n[g], x) - (P->c[g] - E->r));
    memcpy(y, x, 3 * sizeof(double));
    if (inside <= 0) return inside - E->r;
    for (g = 0; g < P->np; g++) {
        double h = tm_dot(P->n[g], x) - (P->c[g] - E->r);
        int ok = 1;
        if (h <= 0 || h >= best) continue;
        q[0] = x[0] - h * P->n[g][0], q[1] = x[1] - h * P->n[g][1], q[2] = x[2] - h * P->n[g][2];
        for (k = 0; k < P->np && ok; k++)
            if (k != g && tm_dot(P->n[k], q) - (P->c[k] - E->r) > foot_tol) ok = 0;
        if (ok) best = h, memcpy(y, q, sizeof q);
    }
    for (k = 0; k < P->ne; k++) {
        double s = tm_seg_nearest(x, P->v[P->e[k][0]], P->v[P->e[k][1]], q);
        if (s < best) best = s, memcpy(y, q, sizeof q);
    }
    for (k = 0; k < P->nv; k++) {
        double dd[3], s;
        tm_sub(x, P->v[k], dd);
        s = tm_len(dd);
        if (s < best) best = s, memcpy(y, P->v[k], sizeof q);
    }
    return best - E->r;
}
static double tm_eroded_nearest(const tm_eroded_t *E, const double x[3], double y[3])
{
    return tm_eroded_nearest_tol(E, x, y, 1e-10);
}
static double tm_eroded_sdf(const void *ctx, const double x[3])
{
    double y[3];
    return tm_eroded_nearest((const tm_eroded_t *)ctx, x, y);
}

/* Convex hull of points (brute force over triples; points in general
   position), as an outward-wound triangle mesh plus its planes. */
static void tm_hull(const double (*p)[3], int n, tm_mesh_t *m, tm_poly_t *P);

/* A random unit vector, uniform on the sphere. */
static void tm_rand_dir(t_rng_t *rng, double out[3])
{
    double u = t_rng_range(rng, 0, 2 * M_PI), v = t_rng_range(rng, -1, 1), w = sqrt(1 - v * v);
    out[0] = w * cos(u), out[1] = w * sin(u), out[2] = v;
}
/* n <= 64 points on a jittered sphere (radius rmin..rmax, uniform in
   direction) and their hull: convex polyhedra with vertices of degree 3
   to 8 whose offset planes miss one common point. Include after test.h. */
static void tm_random_hull(t_rng_t *rng, int n, double rmin, double rmax, tm_mesh_t *m, tm_poly_t *P)
{
    double p[64][3];
    int i;
    for (i = 0; i < n && i < 64; i++) {
        double u = t_rng_range(rng, 0, 2 * M_PI), v = t_rng_range(rng, -1, 1), w = sqrt(1 - v * v), R = t_rng_range(rng, rmin, rmax);
        p[i][0] = R * w * cos(u), p[i][1] = R * w * sin(u), p[i][2] = R * v;
    }
    tm_hull((const double(*)[3])p, i, m, P);
}

static void tm_hull(const double (*p)[3], int n, tm_mesh_t *m, tm_poly_t *P)
{
    int i, j, k, q;
    for (i = 0; i < n; i++) tm_vert(m, p[i][0], p[i][1], p[i][2]);
    P->np = 0;
    for (i = 0; i < n; i++)
        for (j = i + 1; j < n; j++)
            for (k = j + 1; k < n; k++) {
                double e1[3], e2[3], nn[3], c;
                int pos = 0, neg = 0;
                tm_sub(p[j], p[i], e1); tm_sub(p[k], p[i], e2); tm_cross(e1, e2, nn); tm_norm(nn);
                c = tm_dot(nn, p[i]);
                for (q = 0; q < n; q++) {
                    double s = tm_dot(nn, p[q]) - c;
                    if (q == i || q == j || q == k) continue;
                    if (s > 1e-12) pos++; else if (s < -1e-12) neg++;
                }
                if (pos && neg) continue;
                if (pos) { tm_tri(m, (unsigned)i, (unsigned)k, (unsigned)j); nn[0] = -nn[0], nn[1] = -nn[1], nn[2] = -nn[2]; c = -c; }
                else tm_tri(m, (unsigned)i, (unsigned)j, (unsigned)k);
                if (P->np < 128) { memcpy(P->n[P->np], nn, sizeof nn); P->c[P->np++] = c; }
            }
}

/* Flip triangles of a convex mesh whose normal points toward the centroid. */
static void tm_orient_outward(tm_mesh_t *m)
{
    double c[3] = {0, 0, 0};
    unsigned i, t;
    for (i = 0; i < m->nv; i++) c[0] += m->v[3 * i] / m->nv, c[1] += m->v[3 * i + 1] / m->nv, c[2] += m->v[3 * i + 2] / m->nv;
    for (t = 0; t < m->ni / 3; t++) {
        const double *A = m->v + 3 * m->idx[3 * t], *B = m->v + 3 * m->idx[3 * t + 1], *C = m->v + 3 * m->idx[3 * t + 2];
        double e1[3], e2[3], nn[3], g[3];
        tm_sub(B, A, e1); tm_sub(C, A, e2); tm_cross(e1, e2, nn);
        g[0] = (A[0] + B[0] + C[0]) / 3 - c[0], g[1] = (A[1] + B[1] + C[1]) / 3 - c[1], g[2] = (A[2] + B[2] + C[2]) / 3 - c[2];
        if (tm_dot(nn, g) < 0) { unsigned x = m->idx[3 * t + 1]; m->idx[3 * t + 1] = m->idx[3 * t + 2]; m->idx[3 * t + 2] = x; }
    }
}

/* Prism: convex polygon (x, z) pairs counter-clockwise seen from +y... built
   so faces wind outward; extruded over y in [-h, h]. Planes go to P. */
static void tm_prism(tm_mesh_t *m, tm_poly_t *P, const double (*q)[2], int n, double h)
{
    unsigned b = m->nv;
    int i;
    for (i = 0; i < n; i++) tm_vert(m, q[i][0], -h, q[i][1]);
    for (i = 0; i < n; i++) tm_vert(m, q[i][0], h, q[i][1]);
    for (i = 0; i < n; i++) {
        unsigned a = b + (unsigned)i, c = b + (unsigned)((i + 1) % n);
        tm_quad(m, a, c, c + (unsigned)n, a + (unsigned)n);
    }
    for (i = 1; i + 1 < n; i++) {
        tm_tri(m, b, b + (unsigned)i + 1, b + (unsigned)i);
        tm_tri(m, b + (unsigned)n, b + (unsigned)n + (unsigned)i, b + (unsigned)n + (unsigned)i + 1);
    }
    tm_orient_outward(m);
    if (P) {
        unsigned t;
        P->np = 0;
        for (t = 0; t < m->ni / 3 && P->np < 128; t++) {
            const double *A = m->v + 3 * m->idx[3 * t], *B = m->v + 3 * m->idx[3 * t + 1], *C = m->v + 3 * m->idx[3 * t + 2];
            double e1[3], e2[3], nn[3];
            int g, dup = 0;
            tm_sub(B, A, e1); tm_sub(C, A, e2); tm_cross(e1, e2, nn); tm_norm(nn);
            for (g = 0; g < P->np; g++) if (tm_dot(P->n[g], nn) > 1 - 1e-15 && fabs(P->c[g] - tm_dot(nn, A)) < 1e-14) dup = 1;
            if (dup) continue;
            memcpy(P->n[P->np], nn, sizeof nn);
            P->c[P->np++] = tm_dot(nn, A);
        }
    }
}

/* Icosphere of radius R: icosahedron, each triangle split in 4, `level` times. */
static unsigned tm_mid(tm_mesh_t *m, unsigned a, unsigned b, double R)
{
    double p[3];
    unsigned i;
    p[0] = m->v[3 * a] + m->v[3 * b], p[1] = m->v[3 * a + 1] + m->v[3 * b + 1], p[2] = m->v[3 * a + 2] + m->v[3 * b + 2];
    tm_norm(p);
    p[0] *= R, p[1] *= R, p[2] *= R;
    for (i = 0; i < m->nv; i++)
        if (m->v[3 * i] == p[0] && m->v[3 * i + 1] == p[1] && m->v[3 * i + 2] == p[2]) return i;
    return tm_vert(m, p[0], p[1], p[2]);
}
static void tm_icosphere(tm_mesh_t *m, int level, double R)
{
    static const unsigned f[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                      {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                      {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    double t = (1 + sqrt(5.0)) / 2;
    double v[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                       {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    int i, l;
    tm_mesh_t cur = {0};
    for (i = 0; i < 12; i++) { tm_norm(v[i]); tm_vert(&cur, R * v[i][0], R * v[i][1], R * v[i][2]); }
    for (i = 0; i < 20; i++) tm_tri(&cur, f[i][0], f[i][1], f[i][2]);
    for (l = 0; l < level; l++) {
        tm_mesh_t nx = {0};
        unsigned k;
        for (k = 0; k < cur.nv; k++) tm_vert(&nx, cur.v[3 * k], cur.v[3 * k + 1], cur.v[3 * k + 2]);
        for (k = 0; k < cur.ni; k += 3) {
            unsigned a = cur.idx[k], b = cur.idx[k + 1], c = cur.idx[k + 2];
            unsigned ab = tm_mid(&nx, a, b, R), bc = tm_mid(&nx, b, c, R), ca = tm_mid(&nx, c, a, R);
            tm_tri(&nx, a, ab, ca); tm_tri(&nx, b, bc, ab); tm_tri(&nx, c, ca, bc); tm_tri(&nx, ab, bc, ca);
        }
        tm_free(&cur);
        cur = nx;
    }
    tm_orient_outward(&cur);
    for (i = 0; i < (int)cur.nv; i++) tm_vert(m, cur.v[3 * i], cur.v[3 * i + 1], cur.v[3 * i + 2]);
    {
        unsigned base = m->nv - cur.nv, k;
        for (k = 0; k < cur.ni; k += 3) tm_tri(m, base + cur.idx[k], base + cur.idx[k + 1], base + cur.idx[k + 2]);
    }
    tm_free(&cur);
}
/* planes of a convex triangle mesh (one per triangle) */
static void tm_planes(const tm_mesh_t *m, tm_poly_t *P)
{
    unsigned t;
    P->np = 0;
    for (t = 0; t < m->ni / 3 && P->np < 128; t++) {
        const double *A = m->v + 3 * m->idx[3 * t], *B = m->v + 3 * m->idx[3 * t + 1], *C = m->v + 3 * m->idx[3 * t + 2];
        double e1[3], e2[3], nn[3];
        tm_sub(B, A, e1); tm_sub(C, A, e2); tm_cross(e1, e2, nn); tm_norm(nn);
        memcpy(P->n[P->np], nn, sizeof nn);
        P->c[P->np++] = tm_dot(nn, A);
    }
}
#endif
