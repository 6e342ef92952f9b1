/* tests/test_rounded_checks.h — checks of rounded_edges.h's answers and
   features against the reference geometry of test_rounded_util.h, shared
   by the ray batteries (test_rounded_rays.h) and the fuzz target
   (fuzz_rounded_exact.c). Each returns 1 when the check holds, else 0 with
   the reason in msg. Include after rounded_edges.h and test_rounded_util.h. */
#ifndef TEST_ROUNDED_CHECKS_H
#define TEST_ROUNDED_CHECKS_H
#include <stdio.h>
#include <string.h>

/* A rounded hit names its feature (re_get_sphere, re_get_cylinder): its
   point lies at the feature's radius from the sphere's centre or the
   cylinder's axis segment (within tol; tm_capsule_point: the foot not past
   the segment's ends), and its normal points from there to it, to 1e-9
   plus 16 ulps of the coordinates' magnitude (the point's, plus scale)
   over the radius: at an offset of 1e6 and r = 1e-6 of the size that
   rounding alone turns it by 1e-4. */
static int rc_feature_ok(const re_scene_t *s, const re_hit_t *h, double tol, double scale, char *msg, size_t n)
{
    double dist = -1, dn = HUGE_VAL, rad = -1, tol_n,
           mag = scale + fabs(h->point[0]) + fabs(h->point[1]) + fabs(h->point[2]);
    re_sphere_t sp;
    re_cylinder_t cy;
    if (h->feature == RE_FEATURE_SPHERE && re_get_sphere(s, h->object, h->feature_index, &sp))
        tm_capsule_point(h->point, h->normal, sp.center, sp.center, &dist, &dn), rad = sp.radius;
    else if (h->feature == RE_FEATURE_CYLINDER && re_get_cylinder(s, h->object, h->feature_index, &cy))
        tm_capsule_point(h->point, h->normal, cy.a, cy.b, &dist, &dn), rad = cy.radius;
    tol_n = 1e-9 + 16 * RE__DBL_EPS * mag / rad;
    if (rad > 0 && fabs(dist - rad) <= tol && dn <= tol_n) return 1;
    snprintf(msg, n, "rounded hit at t %.17g lies %.17g from its feature %d %u (radius %.17g), normal %.3g off the feature's "
             "(tolerance %.3g)", h->t, dist, (int)h->feature, h->feature_index, rad, dn, tol_n);
    return 0;
}

/* The plane of P with unit normal n (L1 within 1e-9), or -1. */
static int rc_plane_of(const tm_poly_t *P, const double n[3])
{
    int g;
    for (g = 0; g < P->np; g++)
        if (fabs(P->n[g][0] - n[0]) + fabs(P->n[g][1] - n[1]) + fabs(P->n[g][2] - n[2]) <= 1e-9) return g;
    return -1;
}

/* Object obj's features, as re_get_sphere() and re_get_cylinder() list
   them, on the convex hull of planes P (its creases sharper than 1e-9 in
   normal), whose coordinates are the scene's minus off, rounded with
   radius r, each within e of the truth: every sphere has radius r and its
   centre on the eroded polytope, inside every face plane by r and on at
   least three of them; every cylinder runs from its sphere sa's centre to
   sb's, joins two faces (n0, n1 their normals) whose planes lie r from
   both axis ends, and names a mesh edge lying on both faces (vertices of
   pos, the scene's coordinates), or none (-1: an extra cylinder of an
   exact corner). */
static int rc_features_ok(const re_scene_t *s, unsigned obj, const tm_poly_t *P, const double *pos, const double off[3],
                          double r, double e, char *msg, size_t n)
{
    unsigned i, ns = re_sphere_count(s, obj), nc = re_cylinder_count(s, obj), a;
    int g;
    for (i = 0; i < ns; i++) {
        re_sphere_t sp;
        double c[3], side = -HUGE_VAL;
        int on = 0;
        re_get_sphere(s, obj, i, &sp);
        for (a = 0; a < 3; a++) c[a] = sp.center[a] - off[a];
        for (g = 0; g < P->np; g++) {
            double h = tm_dot(P->n[g], c) - P->c[g] + r;
            side = fmax(side, h), on += fabs(h) <= e;
        }
        if (!(sp.radius == r && side <= e && on >= 3)) {
            snprintf(msg, n, "sphere %u (vertex %u): radius %.17g (the object's %.17g), %.3g outside the eroded polytope, "
                     "on %d of its planes (e %.3g)", i, sp.vertex, sp.radius, r, side, on, e);
            return 0;
        }
    }
    for (i = 0; i < nc; i++) {
        re_cylinder_t cy;
        re_sphere_t sa, sb;
        int g0, g1, ok, end;
        re_get_cylinder(s, obj, i, &cy);
        re_get_sphere(s, obj, cy.sa, &sa);
        re_get_sphere(s, obj, cy.sb, &sb);
        g0 = rc_plane_of(P, cy.n0), g1 = rc_plane_of(P, cy.n1);
        ok = cy.radius == r && !memcmp(cy.a, sa.center, sizeof cy.a) && !memcmp(cy.b, sb.center, sizeof cy.b) && g0 >= 0 &&
             g1 >= 0 && g0 != g1;
        for (end = 0; end < 2 && ok; end++) { /* both axis ends r inside both faces */
            const double *x = end ? cy.b : cy.a;
            double q[3];
            for (a = 0; a < 3; a++) q[a] = x[a] - off[a];
            ok = fabs(tm_dot(P->n[g0], q) - P->c[g0] + r) <= e && fabs(tm_dot(P->n[g1], q) - P->c[g1] + r) <= e;
        }
        if (ok && cy.edge_v0 >= 0) { /* its mesh edge lies on both faces */
            ok = cy.edge_v1 >= 0 && cy.edge_v0 != cy.edge_v1;
            for (end = 0; end < 4 && ok; end++) {
                const double *v = pos + 3 * (end & 1 ? cy.edge_v1 : cy.edge_v0);
                double q[3];
                int pg = end < 2 ? g0 : g1;
                for (a = 0; a < 3; a++) q[a] = v[a] - off[a];
                ok = fabs(tm_dot(P->n[pg], q) - P->c[pg]) <= e;
            }
        }
        if (!ok) {
            snprintf(msg, n, "cylinder %u (spheres %u %u, edge %lld-%lld): not on the reference's faces (planes %d %d, "
                     "e %.3g)", i, cy.sa, cy.sb, cy.edge_v0, cy.edge_v1, g0, g1, e);
            return 0;
        }
    }
    return 1;
}
#endif
