/* tests/test_rounded_core.c — rounded_edges.h: exactness against independent
   oracles (analytic rounded box; sphere tracing of the eroded polytope),
   C1 continuity, and the stiff and extreme cases of issue 6. */
#define RE_IMPLEMENTATION
#include "rounded_edges.h"
#include "test.h"
#include "test_rounded_util.h"
#include "test_rounded_rays.h"

static void box_exact_vs_analytic(void)
{
    double lo[3] = {-0.5, -0.3, -0.2}, hi[3] = {0.5, 0.3, 0.2};
    box_rays(lo, hi, 0.05, t_count(100000), 1e-9, 1);
}

/* Random convex hulls of 8..14 points on a jittered sphere: vertices of
   degree 3 to 8, with offset planes that miss one common point. */
static void random_convex_polyhedra_vs_eroded(void)
{
    t_rng_t rng = {7};
    int it, nit = (int)t_count(30), deg_hist[16] = {0};
    unsigned long long extra = 0;
    for (it = 0; it < nit; it++) {
        double p[14][3];
        int n = 8 + (int)(t_rng_u64(&rng) % 7), i;
        tm_mesh_t m = {0};
        static tm_poly_t P;
        re_scene_t *s;
        re_diag_t dg;
        re_stats_t st;
        for (i = 0; i < n; i++) {
            double u = t_rng_range(&rng, 0, 2 * M_PI), v = t_rng_range(&rng, -1, 1), w = sqrt(1 - v * v), R = t_rng_range(&rng, 0.8, 1.2);
            p[i][0] = R * w * cos(u), p[i][1] = R * w * sin(u), p[i][2] = R * v;
        }
        tm_hull((const double(*)[3])p, n, &m, &P);
        for (i = 0; i < n; i++) {
            unsigned k, d = 0;
            for (k = 0; k < m.ni; k++) d += m.idx[k] == (unsigned)i;
            if (d < 16) deg_hist[d]++;
        }
        s = build1(&m, 0.03, &dg);
        if (s) { re_get_stats(s, &st); extra += st.extra_cylinders; re_free(s); }
        poly_rays(&m, &P, 0.03, t_count(1500), 1e-7, 100 + (unsigned long long)it, "hull");
        tm_free(&m);
    }
    T_GT(deg_hist[4] + deg_hist[5], 0);
    T_GT(deg_hist[6] + deg_hist[7] + deg_hist[8], 0);
    T_GT(extra, 0); /* exact corners were needed and built */
}

/* A pyramid over a regular k-gon (fan-triangulated base) with its apex off
   centre: the apex has degree k; for k >= 4 its offset planes miss one point. */
static void apex_case(int k, double r)
{
    tm_mesh_t m = {0};
    static tm_poly_t P;
    double p[12][3];
    int i;
    char what[32];
    for (i = 0; i < k; i++) p[i][0] = cos(2 * M_PI * i / k + 0.1 * sin(3.0 * i)), p[i][1] = sin(2 * M_PI * i / k + 0.1 * sin(3.0 * i)), p[i][2] = 0;
    p[k][0] = 0.23, p[k][1] = -0.11, p[k][2] = 0.9;
    /* the base is one plane: tm_hull would list it k-2 times; build by hand */
    for (i = 0; i <= k; i++) tm_vert(&m, p[i][0], p[i][1], p[i][2]);
    for (i = 0; i < k; i++) tm_tri(&m, (unsigned)i, (unsigned)((i + 1) % k), (unsigned)k);
    for (i = 1; i + 1 < k; i++) tm_tri(&m, 0, (unsigned)(i + 1), (unsigned)i);
    P.np = 0;
    for (i = 0; i < k; i++) {
        double e1[3], e2[3], n[3];
        tm_sub(p[(i + 1) % k], p[i], e1);
        tm_sub(p[k], p[i], e2);
        tm_cross(e1, e2, n);
        tm_norm(n);
        memcpy(P.n[P.np], n, sizeof n);
        P.c[P.np++] = tm_dot(n, p[i]);
    }
    P.n[P.np][0] = 0, P.n[P.np][1] = 0, P.n[P.np][2] = -1, P.c[P.np++] = 0;
    snprintf(what, sizeof what, "apex degree %d", k);
    poly_rays(&m, &P, r, t_count(6000), 1e-7, (unsigned long long)k, what);
    tm_free(&m);
}
static void apex_degree_3(void) { apex_case(3, 0.05); }
static void apex_degree_4(void) { apex_case(4, 0.1); }
static void apex_degree_5(void) { apex_case(5, 0.05); }
static void apex_degree_6(void) { apex_case(6, 0.05); }
static void apex_degree_7(void) { apex_case(7, 0.04); }
static void apex_degree_8(void) { apex_case(8, 0.03); }

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(box_exact_vs_analytic),
        T_CASE(random_convex_polyhedra_vs_eroded),
        T_CASE(apex_degree_3), T_CASE(apex_degree_4), T_CASE(apex_degree_5),
        T_CASE(apex_degree_6), T_CASE(apex_degree_7), T_CASE(apex_degree_8),
    };
    return T_RUN(argc, argv, cases);
}
