/* tests/test_frep_trace_models.h -- models and helpers shared by the ray
   tests of frep.h (tests/test_frep_trace.c, tests/test_frep_prepared.c).
   Include after frep.h and test.h. */
#ifndef FILIGREE_TEST_FREP_TRACE_MODELS_H
#define FILIGREE_TEST_FREP_TRACE_MODELS_H

typedef struct model_t {
    fr_tape_t tape;
    void *scratch;
} model_t;

static void model_finish(model_t *m, fr_builder_t *b, fr_node_t shape)
{
    fr_diag_t dg;
    fr_result_t r = fr_builder_finish(b, shape, NULL, 0, &m->tape, &dg);
    if (r != FR_OK) T_FAIL("builder: %s", dg.message);
    fr_builder_free(b);
    m->scratch = malloc(fr_trace_scratch_size(&m->tape, NULL));
}

static void model_free(model_t *m)
{
    free(m->scratch);
    fr_tape_free(&m->tape);
}

/* HyperFun sphere r^2 - |p - c|^2 (polynomial). */
static void make_sphere(model_t *m, const double c[3], double r)
{
    fr_builder_t b;
    fr_builder_init(&b, NULL);
    model_finish(m, &b, fr_sphere(&b, fr_coords(&b), c, r));
}

/* A torus about the z axis as a user polynomial (degree 4) in the point
   nodes (x, y, z): 4 R^2 (x^2 + y^2) - (x^2 + y^2 + z^2 + R^2 - r^2)^2 >= 0
   inside. */
static fr_node_t torus_poly_node(fr_builder_t *b, fr_node_t x, fr_node_t y, fr_node_t z, double R, double r)
{
    fr_node_t rho2 = fr_add(b, fr_unary(b, FR_OP_SQR, x), fr_unary(b, FR_OP_SQR, y));
    fr_node_t s = fr_add(b, fr_add(b, rho2, fr_unary(b, FR_OP_SQR, z)), fr_const(b, R * R - r * r));
    return fr_sub(b, fr_mul(b, fr_const(b, 4 * R * R), rho2), fr_unary(b, FR_OP_SQR, s));
}

static void make_torus_poly(model_t *m, double R, double r)
{
    fr_builder_t b;
    fr_p3_t p;
    fr_builder_init(&b, NULL);
    p = fr_coords(&b);
    model_finish(m, &b, torus_poly_node(&b, p.x, p.y, p.z, R, r));
}

/* The quartic torus R = 1, r = 0.3 united with a ball of radius 0.5 at
   its centre: a CSG of a Taylor-program leaf and a quadric. */
static void make_torus_and_ball(model_t *m)
{
    static const double c0[3] = {0, 0, 0};
    fr_builder_t b;
    fr_p3_t p;
    fr_builder_init(&b, NULL);
    p = fr_coords(&b);
    model_finish(m, &b, fr_union(&b, torus_poly_node(&b, p.x, p.y, p.z, 1, 0.3), fr_sphere(&b, p, c0, 0.5), 0));
}

/* HyperFun's torus (with a square root: not polynomial). */
static void make_torus_hf(model_t *m, double R, double r)
{
    fr_builder_t b;
    static const double c[3] = {0, 0, 0};
    fr_builder_init(&b, NULL);
    model_finish(m, &b, fr_torus(&b, fr_coords(&b), 2, c, R, r));
}

static fr_hit_t trace(model_t *m, const double o[3], const double d[3], double t0, double t1, fr_trace_desc_t desc)
{
    fr_hit_t h;
    fr_result_t r = fr_trace(&m->tape, o, d, t0, t1, &desc, m->scratch, &h);
    if (r != FR_OK) { T_FAIL("fr_trace: %s", fr_result_string(r)); h.hit = 0; }
    return h;
}

static fr_trace_desc_t method(fr_method_t m, double tol)
{
    fr_trace_desc_t d;
    memset(&d, 0, sizeof d);
    d.method = m;
    d.tol = tol;
    return d;
}

/* -(x^4 - 5x^2 + y^4 - 5y^2 + z^4 - 5z^2 + 11.8), >= 0 in the tubes; its
   extent along each axis is +-sqrt((5 + sqrt(27.8)) / 2) = +-2.2663 */
#define TANGLE_EXTENT 2.2662656
static void make_tangle(model_t *m)
{
    fr_builder_t b;
    fr_p3_t p;
    fr_node_t f = FR_NODE_NONE;
    int k;
    fr_builder_init(&b, NULL);
    p = fr_coords(&b);
    for (k = 0; k < 3; k++) {
        fr_node_t x = k == 0 ? p.x : k == 1 ? p.y : p.z;
        fr_node_t term = fr_sub(&b, fr_powi(&b, x, 4), fr_mul(&b, fr_const(&b, 5), fr_unary(&b, FR_OP_SQR, x)));
        f = k == 0 ? term : fr_add(&b, f, term);
    }
    model_finish(m, &b, fr_negate(&b, fr_add(&b, f, fr_const(&b, 11.8))));
}

#endif
