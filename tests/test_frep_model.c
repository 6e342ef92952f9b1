/* frep.h model: every primitive, operation and space map against its closed
   form (written out here from HyperFun's library definitions, independently
   of the builder's lowering), AD gradients against analytic gradients and
   central differences, batch against point evaluation, builder errors. */
#include "interval.h"
#include "frep.h"
#include "test.h"

/* ------------------------------------------------------------ helpers */

typedef fr_node_t (*build_fn)(fr_builder_t *b, fr_p3_t X);
typedef double (*closed_fn)(const double p[3]);
typedef void (*grad_fn)(const double p[3], double g[3]);

static fr_tape_t compile(build_fn f)
{
    fr_builder_t b;
    fr_tape_t t;
    fr_diag_t d;
    fr_builder_init(&b, NULL);
    fr_node_t n = f(&b, fr_coords(&b));
    fr_result_t r = fr_builder_finish(&b, n, NULL, 0, &t, &d);
    if (r != FR_OK) T_FAIL("build failed: %s", d.message);
    fr_builder_free(&b);
    return t;
}

static void rand_point(t_rng_t *r, double p[3], double s)
{
    for (int i = 0; i < 3; i++) p[i] = t_rng_range(r, -s, s);
}

/* |fr_eval - closed| <= rel * (|closed| + scale) at n random points in [-s,s]^3 */
static void check_closed(build_fn f, closed_fn cf, double s, double rel, double scale)
{
    fr_tape_t t = compile(f);
    void *sc = malloc(fr_scratch_size(&t, FR_EVAL_POINT));
    t_rng_t r = {12345};
    long n = t_count(20000), bad = 0;
    for (long i = 0; i < n; i++) {
        double p[3];
        rand_point(&r, p, s);
        double want = cf(p), got = fr_eval(&t, p, sc);
        if (!(fabs(got - want) <= rel * (fabs(want) + scale))) {
            if (bad++ < 3) T_FAIL("at (%g,%g,%g): want %.17g got %.17g", p[0], p[1], p[2], want, got);
        }
    }
    T_INT_EQ(bad, 0);
    free(sc);
    fr_tape_free(&t);
}

/* AD gradient against central differences at n random points */
static void check_grad_cd(build_fn f, double s, double tol)
{
    fr_tape_t t = compile(f);
    void *sc = malloc(fr_scratch_size(&t, FR_EVAL_GRAD));
    t_rng_t r = {777};
    long n = t_count(2000), bad = 0;
    for (long i = 0; i < n; i++) {
        double p[3], g[3], v, h = 1e-5 * s;
        rand_point(&r, p, s);
        T_INT_EQ(fr_eval_grad(&t, p, sc, &v, g), FR_OK);
        T_EQ(v, fr_eval(&t, p, sc));
        for (int k = 0; k < 3; k++) {
            double q[3] = {p[0], p[1], p[2]};
            q[k] = p[k] + h;
            double fp = fr_eval(&t, q, sc);
            q[k] = p[k] - h;
            double fm = fr_eval(&t, q, sc), cd = (fp - fm) / (2 * h);
            if (!(fabs(cd - g[k]) <= tol * (fabs(g[k]) + 1.0))) {
                if (bad++ < 3) T_FAIL("axis %d at (%g,%g,%g): AD %.17g CD %.17g", k, p[0], p[1], p[2], g[k], cd);
            }
        }
    }
    T_INT_EQ(bad, 0);
    free(sc);
    fr_tape_free(&t);
}

/* AD gradient against an analytic gradient, 1e-12 relative to |grad| */
static void check_grad_exact(build_fn f, grad_fn gf, double s)
{
    fr_tape_t t = compile(f);
    void *sc = malloc(fr_scratch_size(&t, FR_EVAL_GRAD));
    t_rng_t r = {999};
    long n = t_count(5000), bad = 0;
    for (long i = 0; i < n; i++) {
        double p[3], g[3], w[3], v;
        rand_point(&r, p, s);
        fr_eval_grad(&t, p, sc, &v, g);
        gf(p, w);
        double norm = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        for (int k = 0; k < 3; k++)
            if (!(fabs(g[k] - w[k]) <= 1e-12 * norm)) {
                if (bad++ < 3) T_FAIL("axis %d: AD %.17g analytic %.17g", k, g[k], w[k]);
            }
    }
    T_INT_EQ(bad, 0);
    free(sc);
    fr_tape_free(&t);
}

static const double C0[3] = {0.1, -0.2, 0.3};
static double sq(double x) { return x * x; }

/* ------------------------------------------------------------ primitives */

static fr_node_t b_sphere(fr_builder_t *b, fr_p3_t X) { return fr_sphere(b, X, C0, 0.8); }
static double c_sphere(const double p[3]) { return 0.64 - sq(p[0] - 0.1) - sq(p[1] + 0.2) - sq(p[2] - 0.3); }
static void g_sphere(const double p[3], double g[3])
{
    for (int i = 0; i < 3; i++) g[i] = -2 * (p[i] - C0[i]);
}
static void sphere_closed_form(void)
{
    check_closed(b_sphere, c_sphere, 2, 1e-14, 1);
    check_grad_exact(b_sphere, g_sphere, 2);
    check_grad_cd(b_sphere, 2, 1e-7);
}

static fr_node_t b_ellipsoid(fr_builder_t *b, fr_p3_t X) { return fr_ellipsoid(b, X, C0, 0.9, 0.6, 0.4); }
static double c_ellipsoid(const double p[3])
{
    return 1 - sq((p[0] - 0.1) / 0.9) - sq((p[1] + 0.2) / 0.6) - sq((p[2] - 0.3) / 0.4);
}
static void g_ellipsoid(const double p[3], double g[3])
{
    g[0] = -2 * (p[0] - 0.1) / 0.81;
    g[1] = -2 * (p[1] + 0.2) / 0.36;
    g[2] = -2 * (p[2] - 0.3) / 0.16;
}
static void ellipsoid_closed_form(void)
{
    check_closed(b_ellipsoid, c_ellipsoid, 2, 1e-14, 1);
    check_grad_exact(b_ellipsoid, g_ellipsoid, 2);
    check_grad_cd(b_ellipsoid, 2, 1e-7);
}

static const double BV[3] = {-0.5, -0.4, -0.3}, BS[3] = {1.0, 0.8, 0.6};
static double c_block_alpha(const double p[3], double al)
{
    double xt = (p[0] + 0.5) * (0.5 - p[0]), yt = (p[1] + 0.4) * (0.4 - p[1]), zt = (p[2] + 0.3) * (0.3 - p[2]);
    if (al == 1) return fmin(fmin(xt, yt), zt);
    double f = xt + yt - sqrt(xt * xt + yt * yt - 2 * al * xt * yt);
    return f + zt - sqrt(f * f + zt * zt - 2 * al * f * zt);
}
static fr_node_t b_block1(fr_builder_t *b, fr_p3_t X) { return fr_block(b, X, BV, BS, 1.0); }
static fr_node_t b_block03(fr_builder_t *b, fr_p3_t X) { return fr_block(b, X, BV, BS, 0.3); }
static double c_block1(const double p[3]) { return c_block_alpha(p, 1); }
static double c_block03(const double p[3]) { return c_block_alpha(p, 0.3); }
static void block_closed_form(void)
{
    check_closed(b_block1, c_block1, 1, 1e-14, 1);
    check_closed(b_block03, c_block03, 1, 1e-12, 1);
    check_grad_cd(b_block03, 1, 1e-6);
}

static fr_node_t b_cyl_x(fr_builder_t *b, fr_p3_t X) { return fr_cylinder(b, X, 0, C0, 0.5); }
static fr_node_t b_cyl_y(fr_builder_t *b, fr_p3_t X) { return fr_cylinder(b, X, 1, C0, 0.5); }
static fr_node_t b_cyl_z(fr_builder_t *b, fr_p3_t X) { return fr_cylinder(b, X, 2, C0, 0.5); }
static double c_cyl_x(const double p[3]) { return 0.25 - sq(p[1] + 0.2) - sq(p[2] - 0.3); }
static double c_cyl_y(const double p[3]) { return 0.25 - sq(p[0] - 0.1) - sq(p[2] - 0.3); }
static double c_cyl_z(const double p[3]) { return 0.25 - sq(p[0] - 0.1) - sq(p[1] + 0.2); }
static fr_node_t b_ecyl_y(fr_builder_t *b, fr_p3_t X) { return fr_ell_cylinder(b, X, 1, C0, 0.5, 0.25); }
static double c_ecyl_y(const double p[3]) { return 1 - sq((p[0] - 0.1) / 0.5) - sq((p[2] - 0.3) / 0.25); }
static const double AX_Q[3] = {0.2, 0.1, -0.1}, AX_D[3] = {1, 2, 2};
static fr_node_t b_cyl_axis(fr_builder_t *b, fr_p3_t X) { return fr_cylinder_axis(b, X, AX_Q, AX_D, 0.4); }
static double c_cyl_axis(const double p[3])
{
    double d[3] = {p[0] - 0.2, p[1] - 0.1, p[2] + 0.1}, u[3] = {1 / 3.0, 2 / 3.0, 2 / 3.0};
    double cr[3] = {d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2], d[0] * u[1] - d[1] * u[0]};
    return 0.16 - (cr[0] * cr[0] + cr[1] * cr[1] + cr[2] * cr[2]);
}
static void g_cyl_z(const double p[3], double g[3])
{
    g[0] = -2 * (p[0] - 0.1);
    g[1] = -2 * (p[1] + 0.2);
    g[2] = 0;
}
static void cylinders_closed_form(void)
{
    check_closed(b_cyl_x, c_cyl_x, 2, 1e-14, 1);
    check_closed(b_cyl_y, c_cyl_y, 2, 1e-14, 1);
    check_closed(b_cyl_z, c_cyl_z, 2, 1e-14, 1);
    check_closed(b_ecyl_y, c_ecyl_y, 2, 1e-14, 1);
    check_closed(b_cyl_axis, c_cyl_axis, 2, 1e-13, 1);
    check_grad_exact(b_cyl_z, g_cyl_z, 2);
    check_grad_cd(b_cyl_axis, 2, 1e-7);
}

static fr_node_t b_cone_z(fr_builder_t *b, fr_p3_t X) { return fr_cone(b, X, 2, C0, 0.5); }
static double c_cone_z(const double p[3]) { return sq(p[2] - 0.3) - sq((p[0] - 0.1) / 0.5) - sq((p[1] + 0.2) / 0.5); }
static fr_node_t b_cone_x(fr_builder_t *b, fr_p3_t X) { return fr_cone(b, X, 0, C0, 2.0); }
static double c_cone_x(const double p[3]) { return sq(p[0] - 0.1) - sq((p[1] + 0.2) / 2) - sq((p[2] - 0.3) / 2); }
static void g_cone_z(const double p[3], double g[3])
{
    g[0] = -2 * (p[0] - 0.1) / 0.25;
    g[1] = -2 * (p[1] + 0.2) / 0.25;
    g[2] = 2 * (p[2] - 0.3);
}
static void cone_closed_form(void)
{
    check_closed(b_cone_z, c_cone_z, 2, 1e-14, 1);
    check_closed(b_cone_x, c_cone_x, 2, 1e-14, 1);
    check_grad_exact(b_cone_z, g_cone_z, 2);
}

static fr_node_t b_torus_x(fr_builder_t *b, fr_p3_t X) { return fr_torus(b, X, 0, C0, 0.7, 0.2); }
static fr_node_t b_torus_y(fr_builder_t *b, fr_p3_t X) { return fr_torus(b, X, 1, C0, 0.7, 0.2); }
static fr_node_t b_torus_z(fr_builder_t *b, fr_p3_t X) { return fr_torus(b, X, 2, C0, 0.7, 0.2); }
static double torus_hf(double ax, double o1, double o2)
{
    return 0.04 - ax * ax - o1 * o1 - o2 * o2 - 0.49 + 2 * 0.7 * sqrt(o1 * o1 + o2 * o2);
}
static double c_torus_x(const double p[3]) { return torus_hf(p[0] - 0.1, p[1] + 0.2, p[2] - 0.3); }
static double c_torus_y(const double p[3]) { return torus_hf(p[1] + 0.2, p[0] - 0.1, p[2] - 0.3); }
static double c_torus_z(const double p[3]) { return torus_hf(p[2] - 0.3, p[0] - 0.1, p[1] + 0.2); }
static void g_torus_z(const double p[3], double g[3])
{
    double x = p[0] - 0.1, y = p[1] + 0.2, z = p[2] - 0.3, rho = sqrt(x * x + y * y);
    g[0] = -2 * x + 1.4 * x / rho;
    g[1] = -2 * y + 1.4 * y / rho;
    g[2] = -2 * z;
}
static void torus_closed_form(void)
{
    check_closed(b_torus_x, c_torus_x, 2, 1e-14, 1);
    check_closed(b_torus_y, c_torus_y, 2, 1e-14, 1);
    check_closed(b_torus_z, c_torus_z, 2, 1e-14, 1);
    check_grad_exact(b_torus_z, g_torus_z, 2);
    check_grad_cd(b_torus_x, 2, 1e-6);
}

static const double HN[3] = {0.3, -0.4, 1.2};
static fr_node_t b_half(fr_builder_t *b, fr_p3_t X) { return fr_halfspace(b, X, HN, 0.25); }
static double c_half(const double p[3]) { return 0.25 - (0.3 * p[0] - 0.4 * p[1] + 1.2 * p[2]); }
static void g_half(const double p[3], double g[3])
{
    (void)p;
    for (int i = 0; i < 3; i++) g[i] = -HN[i];
}
static void halfspace_closed_form(void)
{
    check_closed(b_half, c_half, 3, 1e-14, 1);
    check_grad_exact(b_half, g_half, 3);
}

static const double SE_ABC[3] = {0.8, 0.6, 0.5};
static fr_node_t b_superell(fr_builder_t *b, fr_p3_t X) { return fr_superellipsoid(b, X, C0, SE_ABC, 0.5, 0.8); }
static double c_superell(const double p[3])
{
    double s1 = 0.5, s2 = 0.8;
    double xt = (p[0] - 0.1) / 0.8, yt = (p[1] + 0.2) / 0.6, zt = (p[2] - 0.3) / 0.5;
    double xp = pow(fabs(xt), 2 / s2), yp = pow(fabs(yt), 2 / s2), zp = pow(fabs(zt), 2 / s1);
    return 1 - pow(xp + yp, s2 / s1) - zp;
}
static void superellipsoid_closed_form(void)
{
    check_closed(b_superell, c_superell, 1.5, 1e-13, 1);
    check_grad_cd(b_superell, 1.5, 1e-5);
}

/* ------------------------------------------------------------ skeletal */

static const double BX[3] = {0, 0.5, -0.3}, BY[3] = {0, 0.1, 0.4}, BZ[3] = {0, -0.2, 0.2};
static const double BA[3] = {2, 3, 4}, BB[3] = {1, 0.7, 1.2};
static fr_skeleton_t pts(int i, double width, double weight)
{
    fr_skeleton_t s;
    s.a[0] = s.b[0] = BX[i];
    s.a[1] = s.b[1] = BY[i];
    s.a[2] = s.b[2] = BZ[i];
    s.width = width;
    s.weight = weight;
    return s;
}
static double r2_pt(const double p[3], int i) { return sq(p[0] - BX[i]) + sq(p[1] - BY[i]) + sq(p[2] - BZ[i]); }

static fr_node_t b_blobby(fr_builder_t *b, fr_p3_t X)
{
    fr_skeleton_t s[3];
    for (int i = 0; i < 3; i++) s[i] = pts(i, BA[i], BB[i]);
    return fr_skeletal(b, X, FR_KERNEL_BLOBBY, s, 3, 0.5);
}
static double c_blobby(const double p[3])
{
    double f = 0;
    for (int i = 0; i < 3; i++) f += BB[i] * exp(-BA[i] * r2_pt(p, i));
    return f - 0.5;
}
static void g_blobby(const double p[3], double g[3])
{
    double C[3][3] = {{BX[0], BY[0], BZ[0]}, {BX[1], BY[1], BZ[1]}, {BX[2], BY[2], BZ[2]}};
    g[0] = g[1] = g[2] = 0;
    for (int i = 0; i < 3; i++) {
        double e = BB[i] * exp(-BA[i] * r2_pt(p, i));
        for (int k = 0; k < 3; k++) g[k] += e * -2 * BA[i] * (p[k] - C[i][k]);
    }
}
static fr_node_t b_metaball(fr_builder_t *b, fr_p3_t X)
{
    fr_skeleton_t s[3];
    for (int i = 0; i < 3; i++) s[i] = pts(i, 0.6 + 0.2 * i, BB[i]);
    return fr_skeletal(b, X, FR_KERNEL_METABALL, s, 3, 0.3);
}
static double c_metaball(const double p[3])
{
    double f = 0;
    for (int i = 0; i < 3; i++) {
        double R = 0.6 + 0.2 * i, r = sqrt(r2_pt(p, i));
        if (r <= R / 3) f += BB[i] * (1 - 3 * r * r / (R * R));
        else if (r <= R) f += BB[i] * 1.5 * sq(1 - r / R);
    }
    return f - 0.3;
}
static fr_node_t b_soft(fr_builder_t *b, fr_p3_t X)
{
    fr_skeleton_t s[3];
    for (int i = 0; i < 3; i++) s[i] = pts(i, 0.5 + 0.25 * i, 1.0);
    return fr_skeletal(b, X, FR_KERNEL_SOFT, s, 3, 0.4);
}
static double c_soft(const double p[3])
{
    /* hfSoft, as HyperFun writes it */
    double f = 0;
    for (int i = 0; i < 3; i++) {
        double d = 0.5 + 0.25 * i, r2 = r2_pt(p, i), r4 = r2 * r2, d2 = d * d, d4 = d2 * d2;
        if (sqrt(r2) <= d) f += 1 - 22. * r2 / (9. * d2) + 17. * r4 / (9. * d4) - 4. * r4 * r2 / (9. * d4 * d2);
    }
    return f - 0.4;
}
static const double SA[3] = {-0.4, 0.1, 0.0}, SB[3] = {0.5, -0.2, 0.3};
static fr_skeleton_t seg(double width, double weight)
{
    fr_skeleton_t s;
    for (int i = 0; i < 3; i++) {
        s.a[i] = SA[i];
        s.b[i] = SB[i];
    }
    s.width = width;
    s.weight = weight;
    return s;
}
/* squared distance to segment, by projecting and clamping in the test */
static double r2_seg(const double p[3])
{
    double ab[3], ap[3], l2 = 0, t = 0;
    for (int i = 0; i < 3; i++) {
        ab[i] = SB[i] - SA[i];
        ap[i] = p[i] - SA[i];
        l2 += ab[i] * ab[i];
        t += ap[i] * ab[i];
    }
    t = t / l2 < 0 ? 0 : t / l2 > 1 ? 1 : t / l2;
    return sq(ap[0] - t * ab[0]) + sq(ap[1] - t * ab[1]) + sq(ap[2] - t * ab[2]);
}
static fr_node_t b_blobby_seg(fr_builder_t *b, fr_p3_t X)
{
    fr_skeleton_t s = seg(3.0, 1.5);
    return fr_skeletal(b, X, FR_KERNEL_BLOBBY, &s, 1, 0.5);
}
static double c_blobby_seg(const double p[3]) { return 1.5 * exp(-3 * r2_seg(p)) - 0.5; }
static fr_node_t b_soft_seg(fr_builder_t *b, fr_p3_t X)
{
    fr_skeleton_t s = seg(0.7, 1.0);
    return fr_skeletal(b, X, FR_KERNEL_SOFT, &s, 1, 0.3);
}
static double c_soft_seg(const double p[3])
{
    double s = r2_seg(p) / 0.49;
    return (s <= 1 ? 1 - 22 * s / 9 + 17 * s * s / 9 - 4 * s * s * s / 9 : 0) - 0.3;
}
static fr_node_t b_meta_seg(fr_builder_t *b, fr_p3_t X)
{
    fr_skeleton_t s = seg(0.9, 1.0);
    return fr_skeletal(b, X, FR_KERNEL_METABALL, &s, 1, 0.3);
}
static double c_meta_seg(const double p[3])
{
    double q = sqrt(r2_seg(p)) / 0.9;
    return (q <= 1 / 3.0 ? 1 - 3 * q * q : q <= 1 ? 1.5 * sq(1 - q) : 0) - 0.3;
}
static void skeletal_points_closed_form(void)
{
    check_closed(b_blobby, c_blobby, 1.5, 1e-13, 1);
    check_closed(b_metaball, c_metaball, 1.5, 1e-13, 1);
    check_closed(b_soft, c_soft, 1.5, 1e-13, 1);
    check_grad_exact(b_blobby, g_blobby, 1.5);
    check_grad_cd(b_soft, 1.5, 1e-6);
    check_grad_cd(b_metaball, 1.5, 1e-6);
}
static void skeletal_segments_closed_form(void)
{
    check_closed(b_blobby_seg, c_blobby_seg, 1.5, 1e-13, 1);
    check_closed(b_soft_seg, c_soft_seg, 1.5, 1e-13, 1);
    check_closed(b_meta_seg, c_meta_seg, 1.5, 1e-13, 1);
    check_grad_cd(b_blobby_seg, 1.5, 1e-6);
}

/* convolution: oracle is Gauss-Legendre quadrature of the Cauchy kernel
   along the segment in __float128 (composite, 64 panels x 8 nodes) */
static fr_node_t b_conv(fr_builder_t *b, fr_p3_t X)
{
    fr_skeleton_t s = seg(2.0, 0.8);
    return fr_convolution(b, X, &s, 1, 0.2);
}
static double c_conv(const double p[3])
{
    static const double xg[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
    static const double wg[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
    __float128 sum = 0, l2 = 0;
    for (int i = 0; i < 3; i++) l2 += (__float128)(SB[i] - SA[i]) * (SB[i] - SA[i]);
    int panels = 64;
    for (int k = 0; k < panels; k++)
        for (int j = 0; j < 8; j++) {
            __float128 x = j < 4 ? -(__float128)xg[3 - j] : (__float128)xg[j - 4];
            __float128 w = j < 4 ? wg[3 - j] : wg[j - 4];
            __float128 t = ((__float128)k + (x + 1) / 2) / panels, r2 = 0;
            for (int i = 0; i < 3; i++) {
                __float128 q = SA[i] + t * (SB[i] - SA[i]) - p[i];
                r2 += q * q;
            }
            __float128 den = 1 + 4 * r2;
            sum += w / (2 * panels) / (den * den);
        }
    /* dt in arc length: multiply by the segment length */
    double l = sqrt((double)l2);
    return (double)(0.8 * sum) * l - 0.2;
}
static void convolution_segment_quadrature(void)
{
    check_closed(b_conv, c_conv, 1.5, 1e-9, 0.01);
    check_grad_cd(b_conv, 1.5, 1e-6);
}

/* ------------------------------------------------------------ noise */

static const double NOFF[3] = {0, 0, 0};
static fr_node_t b_noise(fr_builder_t *b, fr_p3_t X) { return fr_noise(b, X, 0.7, 3.0, NOFF); }
static void gradient_noise_bounds(void)
{
    fr_tape_t t = compile(b_noise);
    void *sc = malloc(fr_scratch_size(&t, FR_EVAL_GRAD));
    t_rng_t r = {5};
    long n = t_count(100000);
    double maxv = 0, maxl = 0;
    for (long i = 0; i < n; i++) {
        double p[3], q[3];
        rand_point(&r, p, 10);
        for (int k = 0; k < 3; k++) q[k] = p[k] + t_rng_range(&r, -1e-3, 1e-3);
        double a = fr_eval(&t, p, sc), b = fr_eval(&t, q, sc);
        double l1 = fabs(p[0] - q[0]) + fabs(p[1] - q[1]) + fabs(p[2] - q[2]);
        if (fabs(a) > maxv) maxv = fabs(a);
        if (fabs(a - b) / l1 > maxl) maxl = fabs(a - b) / l1;
    }
    /* documented: |n| <= 2 amp, |n(u)-n(v)| <= 8.5 amp freq |u-v|_1 */
    T_LE(maxv, 2 * 0.7);
    T_LE(maxl, 8.5 * 0.7 * 3.0);
    T_GT(maxv, 0.1); /* not identically zero */
    /* gradient noise vanishes at lattice points (freq * p integer) */
    for (int i = -3; i <= 3; i++) {
        double p[3] = {i / 3.0, (i + 1) / 3.0, 2 * i / 3.0};
        T_NEAR(fr_eval(&t, p, sc), 0.0, 1e-15);
    }
    free(sc);
    fr_tape_free(&t);
    check_grad_cd(b_noise, 2, 1e-5);
}

static fr_node_t b_gardner(fr_builder_t *b, fr_p3_t X) { return fr_noise_gardner(b, X, 2.5, 0.7, 1.4); }
static double c_gardner(const double p[3])
{
    double a1 = 2.5, a2 = 0.7, ph = 1.4;
    double sx = sin(a2 * p[0]), sy = sin(a2 * p[1]), sz = sin(a2 * p[2]), a1d = a1 / 1.17;
    double sx2 = a1d * sin(a2 * p[0] / 1.35 + ph * sz), sy2 = a1d * sin(a2 * p[1] / 1.35 + ph * sx),
           sz2 = a1d * sin(a2 * p[2] / 1.35 + ph * sy);
    return (a1 * sx + sx2) * (a1 * sy + sy2) * (a1 * sz + sz2);
}
static void gardner_noise_closed_form(void)
{
    check_closed(b_gardner, c_gardner, 5, 1e-12, 1);
    check_grad_cd(b_gardner, 5, 1e-6);
}

/* ------------------------------------------------------------ operations */

static const double C1[3] = {0.4, 0, 0};
static fr_node_t s1(fr_builder_t *b, fr_p3_t X) { return fr_sphere(b, X, C0, 0.8); }
static fr_node_t s2(fr_builder_t *b, fr_p3_t X) { return fr_ellipsoid(b, X, C1, 0.5, 0.9, 0.7); }
static double f1(const double p[3]) { return c_sphere(p); }
static double f2(const double p[3]) { return 1 - sq((p[0] - 0.4) / 0.5) - sq(p[1] / 0.9) - sq(p[2] / 0.7); }
static double r_uni(double a, double b, double al)
{
    return al == 1 ? fmax(a, b) : a + b + sqrt(a * a + b * b - 2 * al * a * b);
}
static double r_int(double a, double b, double al)
{
    return al == 1 ? fmin(a, b) : a + b - sqrt(a * a + b * b - 2 * al * a * b);
}

#define ROP_CASE(name, expr_b, expr_c)                                                                                 \
    static fr_node_t b_##name(fr_builder_t *b, fr_p3_t X) { return expr_b; }                                          \
    static double c_##name(const double p[3]) { return expr_c; }
ROP_CASE(uni0, fr_union(b, s1(b, X), s2(b, X), 0.0), r_uni(f1(p), f2(p), 0.0))
ROP_CASE(uni05, fr_union(b, s1(b, X), s2(b, X), 0.5), r_uni(f1(p), f2(p), 0.5))
ROP_CASE(uni1, fr_union(b, s1(b, X), s2(b, X), 1.0), fmax(f1(p), f2(p)))
ROP_CASE(int0, fr_intersect(b, s1(b, X), s2(b, X), 0.0), r_int(f1(p), f2(p), 0.0))
ROP_CASE(int05, fr_intersect(b, s1(b, X), s2(b, X), 0.5), r_int(f1(p), f2(p), 0.5))
ROP_CASE(int1, fr_intersect(b, s1(b, X), s2(b, X), 1.0), fmin(f1(p), f2(p)))
ROP_CASE(sub0, fr_subtract(b, s1(b, X), s2(b, X), 0.0), r_int(f1(p), -f2(p), 0.0))
ROP_CASE(sub1, fr_subtract(b, s1(b, X), s2(b, X), 1.0), fmin(f1(p), -f2(p)))
ROP_CASE(neg, fr_negate(b, s1(b, X)), -f1(p))
ROP_CASE(bu, fr_blend_union(b, s1(b, X), s2(b, X), 0.3, 0.5, 0.7),
         f1(p) + f2(p) + sqrt(f1(p) * f1(p) + f2(p) * f2(p)) + 0.3 / (1 + sq(f1(p) / 0.5) + sq(f2(p) / 0.7)))
ROP_CASE(bi, fr_blend_intersect(b, s1(b, X), s2(b, X), 0.3, 0.5, 0.7),
         f1(p) + f2(p) - sqrt(f1(p) * f1(p) + f2(p) * f2(p)) + 0.3 / (1 + sq(f1(p) / 0.5) + sq(f2(p) / 0.7)))
ROP_CASE(off, fr_offset(b, s1(b, X), 0.25), f1(p) + 0.25)
ROP_CASE(morph, fr_morph(b, s1(b, X), s2(b, X), 0.3), 0.7 * f1(p) + 0.3 * f2(p))
static double smax_k(double a, double b, double k)
{
    double h = fmax(k - fabs(a - b), 0) / k;
    return fmax(a, b) + h * h * k / 4;
}
ROP_CASE(smu, fr_smooth_union(b, s1(b, X), s2(b, X), 0.4), smax_k(f1(p), f2(p), 0.4))
ROP_CASE(smi, fr_smooth_intersect(b, s1(b, X), s2(b, X), 0.4), -smax_k(-f1(p), -f2(p), 0.4))

static void r_functions_closed_form(void)
{
    check_closed(b_uni0, c_uni0, 2, 1e-13, 1);
    check_closed(b_uni05, c_uni05, 2, 1e-13, 1);
    check_closed(b_uni1, c_uni1, 2, 1e-14, 1);
    check_closed(b_int0, c_int0, 2, 1e-13, 1);
    check_closed(b_int05, c_int05, 2, 1e-13, 1);
    check_closed(b_int1, c_int1, 2, 1e-14, 1);
    check_closed(b_sub0, c_sub0, 2, 1e-13, 1);
    check_closed(b_sub1, c_sub1, 2, 1e-14, 1);
    check_closed(b_neg, c_neg, 2, 1e-14, 1);
    check_grad_cd(b_uni05, 2, 1e-6);
    check_grad_cd(b_int0, 2, 1e-6);
    check_grad_cd(b_sub0, 2, 1e-6);
}
static void r_union_gradient_analytic(void)
{
    /* d/dp of f1+f2+sqrt(f1^2+f2^2-2a f1 f2), chain rule written out here */
    fr_tape_t t = compile(b_uni05);
    void *sc = malloc(fr_scratch_size(&t, FR_EVAL_GRAD));
    t_rng_t r = {3};
    long bad = 0;
    for (long i = 0; i < t_count(5000); i++) {
        double p[3], g[3], v, w[3];
        rand_point(&r, p, 2);
        double a = f1(p), c = f2(p), s = sqrt(a * a + c * c - a * c);
        double g1[3] = {-2 * (p[0] - 0.1), -2 * (p[1] + 0.2), -2 * (p[2] - 0.3)};
        double g2[3] = {-2 * (p[0] - 0.4) / 0.25, -2 * p[1] / 0.81, -2 * p[2] / 0.49};
        for (int k = 0; k < 3; k++)
            w[k] = g1[k] + g2[k] + ((a - 0.5 * c) * g1[k] + (c - 0.5 * a) * g2[k]) / s;
        fr_eval_grad(&t, p, sc, &v, g);
        double nrm = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
        for (int k = 0; k < 3; k++)
            if (!(fabs(g[k] - w[k]) <= 1e-12 * nrm) && bad++ < 3) T_FAIL("AD %.17g analytic %.17g", g[k], w[k]);
    }
    T_INT_EQ(bad, 0);
    free(sc);
    fr_tape_free(&t);
}
static void blends_offset_morph_closed_form(void)
{
    check_closed(b_bu, c_bu, 2, 1e-13, 1);
    check_closed(b_bi, c_bi, 2, 1e-13, 1);
    check_closed(b_off, c_off, 2, 1e-14, 1);
    check_closed(b_morph, c_morph, 2, 1e-14, 1);
    check_grad_cd(b_bu, 2, 1e-6);
    check_grad_cd(b_morph, 2, 1e-7);
}
static void smooth_min_max_closed_form(void)
{
    check_closed(b_smu, c_smu, 2, 1e-14, 1);
    check_closed(b_smi, c_smi, 2, 1e-14, 1);
    check_grad_cd(b_smu, 2, 1e-6);
    check_grad_cd(b_smi, 2, 1e-6);
}

/* ------------------------------------------------------------ space maps */
/* Each map is applied to the off-centre ellipsoid s2; the closed form maps
   the point as HyperFun's definition says and evaluates f2 there. */
static double f2_at(double x, double y, double z)
{
    double q[3] = {x, y, z};
    return f2(q);
}
static const double TD[3] = {0.3, -0.1, 0.2}, SC[3] = {1.5, 0.5, 2.0}, STC[3] = {0.1, 0.2, -0.3};
ROP_CASE(shift, s2(b, fr_translate(b, X, TD)), f2_at(p[0] - 0.3, p[1] + 0.1, p[2] - 0.2))
ROP_CASE(scale, s2(b, fr_scale(b, X, SC)), f2_at(p[0] / 1.5, p[1] / 0.5, p[2] / 2.0))
ROP_CASE(rotx, s2(b, fr_rotate(b, X, 0, 0.7)),
         f2_at(p[0], p[1] * cos(0.7) + p[2] * sin(0.7), -p[1] * sin(0.7) + p[2] * cos(0.7)))
ROP_CASE(roty, s2(b, fr_rotate(b, X, 1, 0.7)),
         f2_at(-p[2] * sin(0.7) + p[0] * cos(0.7), p[1], p[2] * cos(0.7) + p[0] * sin(0.7)))
ROP_CASE(rotz, s2(b, fr_rotate(b, X, 2, 0.7)),
         f2_at(p[0] * cos(0.7) + p[1] * sin(0.7), -p[0] * sin(0.7) + p[1] * cos(0.7), p[2]))
static double twist_th(double s) { return (1 - (s + 0.5) / 1.5) * 0.2 + (s + 0.5) / 1.5 * 1.9; }
ROP_CASE(twz, s2(b, fr_twist(b, X, 2, -0.5, 1.0, 0.2, 1.9)),
         f2_at(p[0] * cos(twist_th(p[2])) + p[1] * sin(twist_th(p[2])),
               -p[0] * sin(twist_th(p[2])) + p[1] * cos(twist_th(p[2])), p[2]))
ROP_CASE(twx, s2(b, fr_twist(b, X, 0, -0.5, 1.0, 0.2, 1.9)),
         f2_at(p[0], p[1] * cos(twist_th(p[0])) + p[2] * sin(twist_th(p[0])),
               -p[1] * sin(twist_th(p[0])) + p[2] * cos(twist_th(p[0]))))
ROP_CASE(twy, s2(b, fr_twist(b, X, 1, -0.5, 1.0, 0.2, 1.9)),
         f2_at(-p[2] * sin(twist_th(p[1])) + p[0] * cos(twist_th(p[1])), p[1],
               p[2] * cos(twist_th(p[1])) + p[0] * sin(twist_th(p[1]))))
static double taper_scale(double s)
{
    /* hfTaper: s1 below x1, s2 above x2, linear between */
    if (s < -0.5) return 0.6;
    if (s > 1.0) return 1.8;
    double t = (s + 0.5) / 1.5;
    return (1 - t) * 0.6 + t * 1.8;
}
ROP_CASE(tpx, s2(b, fr_taper(b, X, 0, -0.5, 1.0, 0.6, 1.8)),
         f2_at(p[0], p[1] / taper_scale(p[0]), p[2] / taper_scale(p[0])))
ROP_CASE(tpy, s2(b, fr_taper(b, X, 1, -0.5, 1.0, 0.6, 1.8)),
         f2_at(p[0] / taper_scale(p[1]), p[1], p[2] / taper_scale(p[1])))
ROP_CASE(tpz, s2(b, fr_taper(b, X, 2, -0.5, 1.0, 0.6, 1.8)),
         f2_at(p[0] / taper_scale(p[2]), p[1] / taper_scale(p[2]), p[2]))
ROP_CASE(stretch, s2(b, fr_stretch(b, X, STC, SC)),
         f2_at(0.1 + (p[0] - 0.1) / 1.5, 0.2 + (p[1] - 0.2) / 0.5, -0.3 + (p[2] + 0.3) / 2.0))
ROP_CASE(bendz, s2(b, fr_bend(b, X, 2, 0.8)),
         f2_at(p[0] * cos(0.8 * p[0]) + p[1] * sin(0.8 * p[0]), -p[0] * sin(0.8 * p[0]) + p[1] * cos(0.8 * p[0]),
               p[2]))
static const double AM[9] = {0.5, 0.1, 0, -0.2, 1.1, 0.3, 0, 0.4, 0.9}, AT[3] = {0.1, 0.2, 0.3};
ROP_CASE(affine, s2(b, fr_affine(b, X, AM, AT)),
         f2_at(0.5 * p[0] + 0.1 * p[1] + 0.1, -0.2 * p[0] + 1.1 * p[1] + 0.3 * p[2] + 0.2,
               0.4 * p[1] + 0.9 * p[2] + 0.3))

static void affine_maps_closed_form(void)
{
    check_closed(b_shift, c_shift, 2, 1e-14, 1);
    check_closed(b_scale, c_scale, 2, 1e-14, 1);
    check_closed(b_rotx, c_rotx, 2, 1e-13, 1);
    check_closed(b_roty, c_roty, 2, 1e-13, 1);
    check_closed(b_rotz, c_rotz, 2, 1e-13, 1);
    check_closed(b_affine, c_affine, 2, 1e-13, 1);
    check_grad_cd(b_rotx, 2, 1e-7);
    check_grad_cd(b_affine, 2, 1e-7);
}
static void twist_taper_stretch_bend_closed_form(void)
{
    check_closed(b_twz, c_twz, 2, 1e-12, 1);
    check_closed(b_twx, c_twx, 2, 1e-12, 1);
    check_closed(b_twy, c_twy, 2, 1e-12, 1);
    check_closed(b_tpx, c_tpx, 2, 1e-12, 1);
    check_closed(b_tpy, c_tpy, 2, 1e-12, 1);
    check_closed(b_tpz, c_tpz, 2, 1e-12, 1);
    check_closed(b_stretch, c_stretch, 2, 1e-13, 1);
    check_closed(b_bendz, c_bendz, 2, 1e-12, 1);
    check_grad_cd(b_twz, 2, 1e-6);
    check_grad_cd(b_tpx, 2, 1e-6);
    check_grad_cd(b_bendz, 2, 1e-6);
}

/* ------------------------------------------------------------ elementary */
static fr_node_t b_elem(fr_builder_t *b, fr_p3_t X)
{
    /* exp(-x^2) + log(2+sin y) + cos(z)^3 + atan(x y) + (|x|+0.5)^1.5 + x/(2+y^2) + ... */
    fr_node_t t1 = fr_unary(b, FR_OP_EXP, fr_unary(b, FR_OP_NEG, fr_unary(b, FR_OP_SQR, X.x)));
    fr_node_t t2 = fr_unary(b, FR_OP_LOG, fr_add(b, fr_const(b, 2), fr_unary(b, FR_OP_SIN, X.y)));
    fr_node_t t3 = fr_powi(b, fr_unary(b, FR_OP_COS, X.z), 3);
    fr_node_t t4 = fr_unary(b, FR_OP_ATAN, fr_mul(b, X.x, X.y));
    fr_node_t t5 = fr_powc(b, fr_add(b, fr_unary(b, FR_OP_ABS, X.x), fr_const(b, 0.5)), 1.5);
    fr_node_t t6 = fr_div(b, X.x, fr_add(b, fr_const(b, 2), fr_unary(b, FR_OP_SQR, X.y)));
    fr_node_t t7 = fr_sub(b, fr_binary(b, FR_OP_MAX, X.x, X.y), fr_binary(b, FR_OP_MIN, X.y, X.z));
    fr_node_t t8 = fr_powi(b, fr_add(b, fr_const(b, 1.5), X.x), -2);
    return fr_add(b, fr_add(b, fr_add(b, t1, t2), fr_add(b, t3, t4)),
                  fr_add(b, fr_add(b, t5, t6), fr_add(b, fr_unary(b, FR_OP_SQRT, fr_add(b, fr_const(b, 3), X.z)),
                                                          fr_add(b, t7, t8))));
}
static double c_elem(const double p[3])
{
    return exp(-p[0] * p[0]) + log(2 + sin(p[1])) + pow(cos(p[2]), 3) + atan(p[0] * p[1]) + pow(fabs(p[0]) + 0.5, 1.5) +
           p[0] / (2 + p[1] * p[1]) + sqrt(3 + p[2]) + fmax(p[0], p[1]) - fmin(p[1], p[2]) + 1 / sq(1.5 + p[0]);
}
static void g_elem(const double p[3], double g[3])
{
    double x = p[0], y = p[1], z = p[2];
    g[0] = -2 * x * exp(-x * x) + y / (1 + x * x * y * y) + 1 / (2 + y * y) + (x >= y ? 1 : 0) - 2 / pow(1.5 + x, 3) +
           1.5 * sqrt(fabs(x) + 0.5) * (x < 0 ? -1 : 1);
    g[1] = cos(y) / (2 + sin(y)) + x / (1 + x * x * y * y) - 2 * x * y / sq(2 + y * y) + (x >= y ? 0 : 1) -
           (y <= z ? 1 : 0);
    g[2] = -3 * sq(cos(z)) * sin(z) + 0.5 / sqrt(3 + z) - (y <= z ? 0 : 1);
}
static void elementary_ops_closed_form(void)
{
    check_closed(b_elem, c_elem, 1, 1e-13, 1);
    check_grad_exact(b_elem, g_elem, 1);
    check_grad_cd(b_elem, 1, 1e-6);
}

/* ------------------------------------------------------------ callbacks */
static double cb_point(const double p[3], void *u)
{
    double r = *(const double *)u;
    return r * r - p[0] * p[0] - p[1] * p[1] - p[2] * p[2];
}
static double cb_grad(const double p[3], void *u, double g[3])
{
    for (int i = 0; i < 3; i++) g[i] = -2 * p[i];
    return cb_point(p, u);
}
static iv_t cb_interval(const iv_t box[3], void *u)
{
    double r = *(const double *)u;
    iv_t s = iv_add(iv_add(iv_sqr(box[0]), iv_sqr(box[1])), iv_sqr(box[2]));
    return iv_sub(iv_point(r * r), s);
}
static double cb_radius = 0.9;
static fr_node_t b_cb_point_only(fr_builder_t *b, fr_p3_t X)
{
    fr_callback_t cb = {cb_point, NULL, NULL, &cb_radius};
    return fr_callback(b, fr_translate(b, X, TD), &cb);
}
static double c_cb(const double p[3]) { return 0.81 - sq(p[0] - 0.3) - sq(p[1] + 0.1) - sq(p[2] - 0.2); }
static fr_node_t b_cb_full(fr_builder_t *b, fr_p3_t X)
{
    fr_callback_t cb = {cb_point, cb_grad, cb_interval, &cb_radius};
    return fr_callback(b, fr_translate(b, X, TD), &cb);
}
static void callback_point_only_reports_no_interval(void)
{
    check_closed(b_cb_point_only, c_cb, 2, 1e-14, 1);
    fr_tape_t t = compile(b_cb_point_only);
    T_CHECK(t.flags & FR_TAPE_NO_INTERVAL);
    T_CHECK(t.flags & FR_TAPE_NO_GRADIENT);
    void *sc = malloc(fr_scratch_size(&t, FR_EVAL_PRUNE) + fr_scratch_size(&t, FR_EVAL_GRAD) + 4096);
    iv_t box[3] = {{0, 1}, {0, 1}, {0, 1}}, o;
    double p[3] = {0.1, 0.2, 0.3}, v, g[3];
    T_INT_EQ(fr_eval_interval(&t, box, sc, &o), FR_ERR_NO_INTERVAL);
    T_INT_EQ(fr_eval_grad(&t, p, sc, &v, g), FR_ERR_NO_GRADIENT);
    iv_affine_t ap[3] = {iv_affine_const(0), iv_affine_const(0), iv_affine_const(0)}, ao;
    T_INT_EQ(fr_eval_affine(&t, ap, sc, &ao), FR_ERR_NO_INTERVAL);
    fr_instr_t buf[64];
    fr_tape_t pr;
    T_INT_EQ(fr_prune(&t, box, sc, buf, 64, &pr, NULL), FR_ERR_NO_INTERVAL);
    T_CHECK(strstr(fr_result_string(FR_ERR_NO_INTERVAL), "interval") != NULL);
    free(sc);
    fr_tape_free(&t);
}
static void callback_with_interval_and_gradient(void)
{
    fr_tape_t t = compile(b_cb_full);
    T_INT_EQ(t.flags & (FR_TAPE_NO_INTERVAL | FR_TAPE_NO_GRADIENT), 0);
    void *sc = malloc(fr_scratch_size(&t, FR_EVAL_AFFINE) + fr_scratch_size(&t, FR_EVAL_GRAD));
    iv_t box[3] = {{0, 1}, {-1, 0}, {0.5, 0.6}}, o;
    T_INT_EQ(fr_eval_interval(&t, box, sc, &o), FR_OK);
    double lo = 0.81 - 0.49 - 0.81 - 0.16, hi = 0.81 - 0 - 0 - 0.09; /* box shifted by TD */
    T_LE(o.lo, lo);
    T_GE(o.hi, hi);
    check_grad_cd(b_cb_full, 2, 1e-7);
    free(sc);
    fr_tape_free(&t);
}

/* ------------------------------------------------------------ attributes, SDF, Lipschitz */
static void attributes_evaluated_with_shape(void)
{
    fr_builder_t b;
    fr_tape_t t;
    fr_builder_init(&b, NULL);
    fr_p3_t X = fr_coords(&b);
    fr_node_t shape = fr_sphere(&b, X, C0, 0.8);
    fr_node_t attrs[3] = {fr_unary(&b, FR_OP_ABS, X.x), fr_unary(&b, FR_OP_SIN, fr_mul(&b, X.y, fr_const(&b, 5))),
                          fr_const(&b, 0.25)};
    T_INT_EQ(fr_builder_finish(&b, shape, attrs, 3, &t, NULL), FR_OK);
    T_INT_EQ(t.n_outputs, 4);
    double out[4], p[3] = {-0.3, 0.2, 0.7}, sc[64];
    T_LE(fr_scratch_size(&t, FR_EVAL_POINT), sizeof sc);
    fr_eval_outputs(&t, p, sc, out);
    T_NEAR(out[0], c_sphere(p), 1e-15);
    T_EQ(out[1], 0.3);
    T_NEAR(out[2], sin(1.0), 1e-15);
    T_EQ(out[3], 0.25);
    fr_tape_free(&t);
    fr_builder_free(&b);
}
static void sdf_wrap_and_lipschitz_flag(void)
{
    fr_builder_t b;
    fr_tape_t t;
    fr_builder_init(&b, NULL);
    fr_p3_t X = fr_coords(&b);
    /* exact sphere SDF |p| - 1 and box-ish max-norm slab, both Lipschitz 1 */
    fr_node_t len = fr_unary(&b, FR_OP_SQRT, fr_add(&b, fr_add(&b, fr_unary(&b, FR_OP_SQR, X.x),
                                                                fr_unary(&b, FR_OP_SQR, X.y)),
                                                   fr_unary(&b, FR_OP_SQR, X.z)));
    fr_node_t sph = fr_from_sdf(&b, fr_sub(&b, len, fr_const(&b, 1)), 1.0);
    fr_node_t slab = fr_sub(&b, fr_const(&b, 0.5), fr_unary(&b, FR_OP_ABS, X.z)); /* L = 1 by the rules */
    fr_node_t f = fr_intersect(&b, sph, slab, 1.0);
    T_INT_EQ(fr_builder_finish(&b, f, NULL, 0, &t, NULL), FR_OK);
    T_EQ(t.lipschitz, 1.0);
    double p[3] = {0.3, 0.4, 0}, sc[64];
    T_NEAR(fr_eval(&t, p, sc), 0.5, 1e-15); /* min(1 - 0.5, 0.5) */
    fr_tape_free(&t);
    /* an algebraic sphere has no finite bound by the rules */
    fr_builder_free(&b);
    fr_tape_t u = compile(b_sphere);
    T_CHECK(isinf(u.lipschitz));
    fr_tape_free(&u);
    /* the bound holds on samples for the SDF model */
}

/* ------------------------------------------------------------ batch */
static fr_node_t b_mix(fr_builder_t *b, fr_p3_t X)
{
    fr_node_t u = fr_blend_union(b, b_twz(b, X), b_gardner(b, X), 0.2, 1, 1);
    return fr_smooth_union(b, fr_union(b, u, b_blobby(b, X), 0.3), b_noise(b, X), 0.3);
}
static void batch_matches_point(void)
{
    fr_tape_t t = compile(b_mix);
    size_t n = 1000 + 7;
    double *x = malloc(n * sizeof(double)), *y = malloc(n * sizeof(double)), *z = malloc(n * sizeof(double));
    double *out = malloc(n * sizeof(double));
    void *sb = malloc(fr_scratch_size(&t, FR_EVAL_BATCH)), *sp = malloc(fr_scratch_size(&t, FR_EVAL_POINT));
    t_rng_t r = {8};
    for (size_t i = 0; i < n; i++) {
        x[i] = t_rng_range(&r, -2, 2);
        y[i] = t_rng_range(&r, -2, 2);
        z[i] = t_rng_range(&r, -2, 2);
    }
    fr_eval_batch(&t, n, x, y, z, out, sb);
    long bad = 0;
    for (size_t i = 0; i < n; i++) {
        double p[3] = {x[i], y[i], z[i]}, v = fr_eval(&t, p, sp);
        if (!(fabs(v - out[i]) <= 1e-13 * (fabs(v) + 1))) bad++;
    }
    T_INT_EQ(bad, 0);
    free(x); free(y); free(z); free(out); free(sb); free(sp);
    fr_tape_free(&t);
}

/* Every opcode through the batch evaluator, each in a tape of its own (a
   sum would let a NaN of one hide another's error): the batch loop has
   its own switch over the opcodes, and NEG, ATAN, MIN, MAX, POWC, the
   callback and others had never gone through it in a test. */
static int g_op;
static fr_node_t b_one_op(fr_builder_t *b, fr_p3_t X)
{
    fr_node_t a = fr_sub(b, fr_add(b, X.x, fr_mul(b, fr_const(b, 0.7), X.y)), fr_mul(b, fr_const(b, 0.2), X.z));
    fr_node_t c = fr_sub(b, fr_mul(b, X.y, X.z), fr_mul(b, fr_const(b, 0.3), X.x));
    fr_node_t pos = fr_add(b, fr_unary(b, FR_OP_SQR, a), fr_const(b, 0.5)); /* > 0: sqrt, log, powc */
    switch (g_op) {
    case FR_OP_SQRT: case FR_OP_LOG: return fr_unary(b, (fr_op_t)g_op, pos);
    case FR_OP_POWI: return fr_add(b, fr_powi(b, a, 3), fr_powi(b, pos, -2));
    case FR_OP_POWC: return fr_powc(b, pos, 1.7);
    case FR_OP_RUNI: return fr_add(b, fr_union(b, a, c, 0.5), fr_union(b, a, c, 1.0));
    case FR_OP_RINT: return fr_add(b, fr_intersect(b, a, c, 0.5), fr_intersect(b, a, c, 1.0));
    case FR_OP_SMAX: return fr_smooth_union(b, a, c, 0.3);
    case FR_OP_SMIN: return fr_smooth_intersect(b, a, c, 0.3);
    case FR_OP_NOISE: return b_noise(b, X);
    case FR_OP_CALL: return b_cb_point_only(b, X);
    default: return g_op < FR_OP_ADD ? fr_unary(b, (fr_op_t)g_op, a) : fr_binary(b, (fr_op_t)g_op, a, c);
    }
}
static void batch_matches_point_every_opcode(void)
{
    size_t n = 300 + 5, i;
    double x[305], y[305], z[305], out[305];
    t_rng_t r = {81};
    for (i = 0; i < n; i++) x[i] = t_rng_range(&r, -2, 2), y[i] = t_rng_range(&r, -2, 2), z[i] = t_rng_range(&r, -2, 2);
    for (g_op = FR_OP_NEG; g_op < FR_OP_COUNT_; g_op++) {
        fr_tape_t t = compile(b_one_op);
        void *sb = malloc(fr_scratch_size(&t, FR_EVAL_BATCH)), *sp = malloc(fr_scratch_size(&t, FR_EVAL_POINT));
        long bad = 0;
        unsigned k, seen = 0;
        for (k = 0; k < t.n_code; k++) seen |= t.code[k].op == (unsigned)g_op;
        T_CHECK(seen); /* the tape holds the opcode under test */
        fr_eval_batch(&t, n, x, y, z, out, sb);
        for (i = 0; i < n; i++) {
            double p[3] = {x[i], y[i], z[i]}, v = fr_eval(&t, p, sp);
            if (!(fabs(v - out[i]) <= 1e-13 * (fabs(v) + 1))) bad++;
        }
        if (!T_INT_EQ(bad, 0)) fprintf(stderr, "    opcode %d: %ld of %zu points differ\n", g_op, bad, n);
        free(sb), free(sp);
        fr_tape_free(&t);
    }
}

/* fr_result_string (T_RESULT_NAMES) */
static void result_strings(void) { T_RESULT_NAMES(fr_result_string, fr_result_t, FR_RESULT_COUNT_); }

/* ------------------------------------------------------------ builder */
static void builder_rejects_bad_parameters_with_message(void)
{
    fr_builder_t b;
    fr_tape_t t;
    fr_diag_t d;
    fr_builder_init(&b, NULL);
    fr_p3_t X = fr_coords(&b);
    fr_node_t ok = fr_sphere(&b, X, C0, 1);
    fr_node_t bad = fr_sphere(&b, X, C0, -1);
    T_CHECK(ok != FR_NODE_NONE);
    T_CHECK(bad == FR_NODE_NONE);
    /* sticky: later nodes fail too, finishing reports the first error */
    T_CHECK(fr_union(&b, ok, ok, 0) == FR_NODE_NONE);
    T_INT_EQ(fr_builder_finish(&b, ok, NULL, 0, &t, &d), FR_ERR_INVALID_ARG);
    T_INT_EQ(d.result, FR_ERR_INVALID_ARG);
    T_CHECK(strstr(d.message, "sphere") && strstr(d.message, "radius"));
    T_GE(d.element, 0);
    fr_builder_free(&b);

    struct { const char *what; int code; } cases[] = {{"alpha", 0}, {"axis", 1}, {"zero", 2}, {"node", 3},
                                                      {"finite", 4}, {"taper", 5}, {"segment", 6},
                                                      {"ellipsoid: half-axes must be finite and > 0", 7},
                                                      {"block: edge lengths must be finite and > 0", 8},
                                                      {"elliptic cylinder: radii must be finite and > 0", 9},
                                                      {"torus: radii must be finite and > 0", 10},
                                                      {"superellipsoid: half-axes and shape exponents", 11},
                                                      {"skeletal: unknown kernel", 12},
                                                      {"element 1: non-finite point or width <= 0", 13},
                                                      {"noise: amplitude must be finite", 14},
                                                      {"hfNoiseG: parameters must be finite", 15},
                                                      {"a0 must be finite, a1 and a2 finite and non-zero", 16},
                                                      {"twist: parameters must be finite with s1 != s2", 17},
                                                      {"fr_unary: not a unary opcode", 18},
                                                      {"sphere: invalid point node", 19}};
    int n_cases = (int)(sizeof cases / sizeof cases[0]);
    for (int i = 0; i < n_cases; i++) {
        fr_builder_init(&b, NULL);
        X = fr_coords(&b);
        double nanv[3] = {NAN, 0, 0}, z3[3] = {0, 0, 0};
        fr_skeleton_t s = seg(1, 1);
        s.b[0] = s.a[0]; s.b[1] = s.a[1]; s.b[2] = s.a[2];
        fr_node_t n = 0;
        switch (cases[i].code) {
        case 0: n = fr_union(&b, X.x, X.y, 1.5); break;
        case 1: n = fr_cylinder(&b, X, 3, C0, 1); break;
        case 2: n = fr_halfspace(&b, X, z3, 0); break;
        case 3: n = fr_add(&b, X.x, 12345u); break;
        case 4: n = fr_sphere(&b, X, nanv, 1); break;
        case 5: n = fr_taper(&b, X, 0, 1, 0, 1, 1).x; break;
        case 6: n = fr_convolution(&b, X, &s, 1, 0.1); break;
        case 7: n = fr_ellipsoid(&b, X, C0, 1, 0, 1); break;
        case 8: { double size[3] = {1, -1, 1}; n = fr_block(&b, X, C0, size, 0); } break;
        case 9: n = fr_ell_cylinder(&b, X, 2, C0, 1, INFINITY); break;
        case 10: n = fr_torus(&b, X, 2, C0, NAN, 0.2); break;
        case 11: { double abc[3] = {1, 1, 1}; n = fr_superellipsoid(&b, X, C0, abc, 0, 1); } break;
        case 12: { fr_skeleton_t e = seg(1, 1); n = fr_skeletal(&b, X, (fr_kernel_t)7, &e, 1, 0.5); } break;
        case 13: { fr_skeleton_t e[2] = {seg(1, 1), seg(1, 1)}; e[1].width = 0; n = fr_skeletal(&b, X, FR_KERNEL_SOFT, e, 2, 0.5); } break;
        case 14: n = fr_noise(&b, X, NAN, 1, z3); break;
        case 15: n = fr_noise_gardner(&b, X, 1, INFINITY, 0); break;
        case 16: n = fr_blend_union(&b, X.x, X.y, 1, 0, 1); break;
        case 17: n = fr_twist(&b, X, 2, 1, 1, 0, 1).x; break;
        case 18: n = fr_unary(&b, FR_OP_ADD, X.x); break;
        case 19: { fr_p3_t Y = X; Y.y = 4242u; n = fr_sphere(&b, Y, C0, 1); } break;
        }
        T_CHECK(n == FR_NODE_NONE);
        T_INT_EQ(fr_builder_finish(&b, X.x, NULL, 0, &t, &d), FR_ERR_INVALID_ARG);
        if (!strstr(d.message, cases[i].what) && (cases[i].code >= 7 || !strstr(d.message, "invalid")))
            T_FAIL("case %d message '%s' lacks '%s'", i, d.message, cases[i].what);
        fr_builder_free(&b);
    }
    T_INT_EQ(fr_builder_init(NULL, NULL), FR_ERR_INVALID_ARG);
    T_CHECK(strcmp(fr_result_string((fr_result_t)999), "unknown result") == 0);
}
static void builder_limit_and_dead_code(void)
{
    fr_builder_t b;
    fr_builder_desc_t desc = {0};
    fr_tape_t t;
    fr_diag_t d;
    desc.max_nodes = 10;
    fr_builder_init(&b, &desc);
    fr_p3_t X = fr_coords(&b);
    fr_node_t n = fr_sphere(&b, X, C0, 1);
    T_CHECK(n == FR_NODE_NONE);
    T_INT_EQ(fr_builder_finish(&b, X.x, NULL, 0, &t, &d), FR_ERR_LIMIT);
    fr_builder_free(&b);
    /* unused nodes are dropped: a tape holds only what its outputs use */
    fr_builder_init(&b, NULL);
    X = fr_coords(&b);
    fr_sphere(&b, X, C0, 1);
    fr_node_t keep = fr_add(&b, X.x, fr_const(&b, 1));
    T_INT_EQ(fr_builder_finish(&b, keep, NULL, 0, &t, NULL), FR_OK);
    T_INT_EQ(t.n_code, 3);
    fr_tape_free(&t);
    fr_builder_free(&b);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(sphere_closed_form), T_CASE(ellipsoid_closed_form), T_CASE(block_closed_form),
        T_CASE(cylinders_closed_form), T_CASE(cone_closed_form), T_CASE(torus_closed_form),
        T_CASE(halfspace_closed_form), T_CASE(superellipsoid_closed_form), T_CASE(skeletal_points_closed_form),
        T_CASE(skeletal_segments_closed_form), T_CASE(convolution_segment_quadrature), T_CASE(gradient_noise_bounds),
        T_CASE(gardner_noise_closed_form), T_CASE(r_functions_closed_form), T_CASE(r_union_gradient_analytic),
        T_CASE(blends_offset_morph_closed_form), T_CASE(smooth_min_max_closed_form),
        T_CASE(affine_maps_closed_form), T_CASE(twist_taper_stretch_bend_closed_form),
        T_CASE(elementary_ops_closed_form), T_CASE(callback_point_only_reports_no_interval),
        T_CASE(callback_with_interval_and_gradient), T_CASE(attributes_evaluated_with_shape),
        T_CASE(sdf_wrap_and_lipschitz_flag), T_CASE(batch_matches_point), T_CASE(batch_matches_point_every_opcode), T_CASE(result_strings),
        T_CASE(builder_rejects_bad_parameters_with_message), T_CASE(builder_limit_and_dead_code),
    };
    return T_RUN(argc, argv, cases);
}
