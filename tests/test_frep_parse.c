/* frep.h parser: every construct against the same model built through the
   C API, the example models, and bad input (an error with line:column,
   never a crash). */
#include "interval.h"
#define FR_IMPLEMENTATION
#include "frep.h"
#include "test.h"
#include <locale.h>

#define PRELUDE                                                                                                        \
    "m(x[3], a[2]) {\n"                                                                                                \
    "  array c[3], v[3], xt[3], x0[2], y0[2], z0[2], ka[2], kb[2];\n"                                                  \
    "  c = [0.1, -0.2, 0.3]; v = [-0.5, -0.4, -0.3]; xt = x;\n"                                                         \
    "  x0 = [0, 0.5]; y0 = [0, 0.1]; z0 = [0, -0.2]; ka = [2, 3]; kb = [1, 0.7];\n"

static const double C[3] = {0.1, -0.2, 0.3}, V[3] = {-0.5, -0.4, -0.3};
static const double PARAMS[2] = {0.25, -1.5};

typedef fr_node_t (*build_fn)(fr_builder_t *b, fr_p3_t X);

static int parse_text(const char *text, fr_tape_t *t, fr_diag_t *d, double alpha)
{
    fr_parse_desc_t desc = {0};
    desc.params = PARAMS;
    desc.n_params = 2;
    desc.alpha = alpha;
    return fr_parse(text, strlen(text), &desc, t, d);
}

/* parse PRELUDE + body + "}" and compare with the C API model at random points */
static void same_as_api(const char *body, build_fn f, double alpha, double rel)
{
    char text[4096];
    fr_tape_t tp, ta;
    fr_diag_t d;
    fr_builder_t b;
    snprintf(text, sizeof text, "%s  %s\n}\n", PRELUDE, body);
    if (parse_text(text, &tp, &d, alpha) != FR_OK) {
        T_FAIL("parse failed for '%s': %s", body, d.message);
        return;
    }
    fr_builder_init(&b, NULL);
    fr_node_t n = f(&b, fr_coords(&b));
    T_INT_EQ(fr_builder_finish(&b, n, NULL, 0, &ta, &d), FR_OK);
    fr_builder_free(&b);
    double *s1 = malloc(fr_scratch_size(&tp, FR_EVAL_POINT)), *s2 = malloc(fr_scratch_size(&ta, FR_EVAL_POINT));
    t_rng_t r = {42};
    long bad = 0;
    for (long i = 0; i < t_count(500); i++) {
        double p[3] = {t_rng_range(&r, -1.5, 1.5), t_rng_range(&r, -1.5, 1.5), t_rng_range(&r, -1.5, 1.5)};
        double u = fr_eval(&tp, p, s1), w = fr_eval(&ta, p, s2);
        if (!(fabs(u - w) <= rel * (fabs(w) + 1)) && !(isnan(u) && isnan(w)) && bad++ < 2)
            T_FAIL("'%s' at (%g,%g,%g): parsed %.17g, API %.17g", body, p[0], p[1], p[2], u, w);
    }
    T_INT_EQ(bad, 0);
    free(s1);
    free(s2);
    fr_tape_free(&tp);
    fr_tape_free(&ta);
}

static fr_node_t K(fr_builder_t *b, double v) { return fr_const(b, v); }

/* ---------------------------------------------------------- arithmetic */
static fr_node_t api_arith(fr_builder_t *b, fr_p3_t X)
{
    /* x1*2 - x2/3 + (x3 + 1)^3 - x1^2.5 ... written with the C API */
    fr_node_t t = fr_sub(b, fr_mul(b, X.x, K(b, 2)), fr_div(b, X.y, K(b, 3)));
    t = fr_add(b, t, fr_powi(b, fr_add(b, X.z, K(b, 1)), 3));
    t = fr_sub(b, t, fr_powc(b, fr_unary(b, FR_OP_ABS, X.x), 2.5));
    t = fr_add(b, t, fr_negate(b, fr_mul(b, X.y, X.z)));
    return fr_add(b, t, K(b, 0.25 * 4 - 1.5)); /* a[1]*4 + a[2] folded */
}
static void arithmetic_and_parameters(void)
{
    same_as_api("m = x[1]*2 - x[2]/3 + (x[3] + 1)^3 - abs(x[1])^2.5 + -(x[2]*x[3]) + (a[1]*4 + a[2]);", api_arith,
                0, 1e-14);
}
static fr_node_t api_funcs(fr_builder_t *b, fr_p3_t X)
{
    fr_node_t t = fr_add(b, fr_unary(b, FR_OP_SQRT, fr_add(b, fr_unary(b, FR_OP_SQR, X.x), K(b, 1))),
                         fr_unary(b, FR_OP_EXP, X.y));
    t = fr_add(b, t, fr_unary(b, FR_OP_LOG, fr_add(b, X.z, K(b, 2))));
    t = fr_add(b, t, fr_mul(b, fr_unary(b, FR_OP_SIN, X.x), fr_unary(b, FR_OP_COS, X.y)));
    return fr_add(b, t, fr_add(b, fr_unary(b, FR_OP_ABS, X.z), fr_unary(b, FR_OP_ATAN, X.x)));
}
static void functions_and_variables(void)
{
    same_as_api("q = x[1]^2 + 1; r = sqrt(q) + exp(x[2]); r = r + log(x[3] + 2);\n"
                "m = r + sin(x[1])*cos(x[2]) + (abs(x[3]) + atan(x[1]));",
                api_funcs, 0, 1e-14);
}
static fr_node_t api_power_general(fr_builder_t *b, fr_p3_t X)
{
    /* (x1^2+1)^(x2) = exp(x2 log(x1^2+1)); 2^3^2 = 2^9 folded */
    fr_node_t base = fr_add(b, fr_unary(b, FR_OP_SQR, X.x), K(b, 1));
    return fr_add(b, fr_unary(b, FR_OP_EXP, fr_mul(b, X.y, fr_unary(b, FR_OP_LOG, base))), K(b, 512));
}
static void power_right_associative_and_general(void)
{
    same_as_api("m = (x[1]^2 + 1)^x[2] + 2^3^2;", api_power_general, 0, 1e-13);
}

/* ---------------------------------------------------------- set operations */
static fr_node_t sph(fr_builder_t *b, fr_p3_t X) { return fr_sphere(b, X, C, 0.8); }
static fr_node_t cylz(fr_builder_t *b, fr_p3_t X) { return fr_cylinder(b, X, 2, C, 0.3); }
static fr_node_t blk(fr_builder_t *b, fr_p3_t X)
{
    double s[3] = {1, 0.8, 0.6};
    return fr_block(b, X, V, s, 0.0);
}
static fr_node_t api_setops0(fr_builder_t *b, fr_p3_t X)
{
    /* (s | c) & ~k  \ c  evaluated left to right at one precedence level */
    fr_node_t u = fr_union(b, sph(b, X), cylz(b, X), 0);
    u = fr_intersect(b, u, fr_negate(b, blk(b, X)), 0);
    return fr_subtract(b, u, cylz(b, X), 0);
}
static fr_node_t api_setops1(fr_builder_t *b, fr_p3_t X)
{
    double s[3] = {1, 0.8, 0.6};
    fr_node_t u = fr_union(b, sph(b, X), cylz(b, X), 1);
    u = fr_intersect(b, u, fr_negate(b, fr_block(b, X, V, s, 1.0)), 1);
    return fr_subtract(b, u, cylz(b, X), 1);
}
#define SETOPS "m = hfSphere(x, c, 0.8) | hfCylinderZ(x, c, 0.3) & ~hfBlock(x, v, 1, 0.8, 0.6) \\ hfCylinderZ(x, c, 0.3);"
static void set_operators_alpha0(void) { same_as_api(SETOPS, api_setops0, 0, 1e-13); }
static void set_operators_alpha1(void) { same_as_api(SETOPS, api_setops1, 1, 1e-14); }
static fr_node_t api_prec(fr_builder_t *b, fr_p3_t X)
{
    /* | binds loosest: s | (c * 2 + 1) */
    return fr_union(b, sph(b, X), fr_add(b, fr_mul(b, cylz(b, X), K(b, 2)), K(b, 1)), 0);
}
static void set_operators_bind_loosest(void)
{
    same_as_api("m = hfSphere(x, c, 0.8) | hfCylinderZ(x, c, 0.3) * 2 + 1;", api_prec, 0, 1e-13);
}

/* ---------------------------------------------------------- primitives */
#define PRIM(name, text, expr)                                                                                         \
    static fr_node_t api_##name(fr_builder_t *b, fr_p3_t X) { return expr; }                                          \
    static void prim_##name(void) { same_as_api("m = " text ";", api_##name, 0, 1e-13); }
static const double ABC[3] = {0.8, 0.6, 0.5};
PRIM(sphere, "hfSphere(x, c, 0.8)", fr_sphere(b, X, C, 0.8))
PRIM(ellipsoid, "hfEllipsoid(x, c, 0.9, 0.6, 0.4)", fr_ellipsoid(b, X, C, 0.9, 0.6, 0.4))
PRIM(block, "hfBlock(x, v, 1, 0.8, 0.6)", blk(b, X))
PRIM(cylx, "hfCylinderX(x, c, 0.5)", fr_cylinder(b, X, 0, C, 0.5))
PRIM(cyly, "hfCylinderY(x, c, 0.5)", fr_cylinder(b, X, 1, C, 0.5))
PRIM(cylz, "hfCylinderZ(x, c, 0.5)", fr_cylinder(b, X, 2, C, 0.5))
PRIM(conex, "hfConeX(x, c, 0.5)", fr_cone(b, X, 0, C, 0.5))
PRIM(coney, "hfConeY(x, c, 0.5)", fr_cone(b, X, 1, C, 0.5))
PRIM(conez, "hfConeZ(x, c, 0.5)", fr_cone(b, X, 2, C, 0.5))
PRIM(torx, "hfTorusX(x, c, 0.7, 0.2)", fr_torus(b, X, 0, C, 0.7, 0.2))
PRIM(tory, "hfTorusY(x, c, 0.7, 0.2)", fr_torus(b, X, 1, C, 0.7, 0.2))
PRIM(torz, "hfTorusZ(x, c, 0.7, 0.2)", fr_torus(b, X, 2, C, 0.7, 0.2))
PRIM(superell, "hfSuperEll(x, c, 0.8, 0.6, 0.5, 0.5, 0.8)", fr_superellipsoid(b, X, C, ABC, 0.5, 0.8))
static fr_skeleton_t sk(int i, double w, double wt)
{
    static const double X0[2] = {0, 0.5}, Y0[2] = {0, 0.1}, Z0[2] = {0, -0.2};
    fr_skeleton_t s = {{X0[i], Y0[i], Z0[i]}, {X0[i], Y0[i], Z0[i]}, w, wt};
    return s;
}
static fr_node_t api_blobby(fr_builder_t *b, fr_p3_t X)
{
    fr_skeleton_t s[2] = {sk(0, 2, 1), sk(1, 3, 0.7)};
    return fr_skeletal(b, X, FR_KERNEL_BLOBBY, s, 2, 0.5);
}
static fr_node_t api_soft(fr_builder_t *b, fr_p3_t X)
{
    fr_skeleton_t s[2] = {sk(0, 2, 1), sk(1, 3, 1)};
    return fr_skeletal(b, X, FR_KERNEL_SOFT, s, 2, 0.5);
}
static void prim_blobby(void) { same_as_api("m = hfBlobby(x, x0, y0, z0, ka, kb, 0.5);", api_blobby, 0, 1e-13); }
static void prim_soft(void) { same_as_api("m = hfSoft(x, x0, y0, z0, ka, 0.5);", api_soft, 0, 1e-13); }
PRIM(noiseg, "hfNoiseG(x, 2.5, 0.7, 1.4)", fr_noise_gardner(b, X, 2.5, 0.7, 1.4))
PRIM(blenduni, "hfBlendUni(hfSphere(x, c, 0.8), hfCylinderZ(x, c, 0.3), 0.3, 0.5, 0.7)",
     fr_blend_union(b, sph(b, X), cylz(b, X), 0.3, 0.5, 0.7))
PRIM(blendint, "hfBlendInt(hfSphere(x, c, 0.8), hfCylinderZ(x, c, 0.3), 0.3, 0.5, 0.7)",
     fr_blend_intersect(b, sph(b, X), cylz(b, X), 0.3, 0.5, 0.7))
static void every_primitive_matches_api(void)
{
    prim_sphere(); prim_ellipsoid(); prim_block(); prim_cylx(); prim_cyly(); prim_cylz(); prim_conex();
    prim_coney(); prim_conez(); prim_torx(); prim_tory(); prim_torz(); prim_superell(); prim_blobby(); prim_soft();
    prim_noiseg(); prim_blenduni(); prim_blendint();
}

/* ---------------------------------------------------------- space maps */
#define MAP(name, call, expr)                                                                                          \
    static fr_node_t api_##name(fr_builder_t *b, fr_p3_t X) { return fr_ellipsoid(b, expr, C, 0.9, 0.6, 0.4); }       \
    static void map_##name(void) { same_as_api(call " m = hfEllipsoid(xt, c, 0.9, 0.6, 0.4);", api_##name, 0, 1e-13); }
static const double SH[3] = {0.3, -0.1, 0.2}, SC3[3] = {1.5, 0.5, 2.0};
MAP(shift, "hfShift3D(xt, 0.3, -0.1, 0.2);", fr_translate(b, X, SH))
MAP(scale, "hfScale3D(xt, 1.5, 0.5, 2);", fr_scale(b, X, SC3))
MAP(rotx, "hfRotate3DX(xt, 0.7);", fr_rotate(b, X, 0, 0.7))
MAP(roty, "hfRotate3DY(xt, 0.7);", fr_rotate(b, X, 1, 0.7))
MAP(rotz, "hfRotate3DZ(xt, 0.7);", fr_rotate(b, X, 2, 0.7))
MAP(twx, "hfTwistX(xt, -0.5, 1, 0.2, 1.9);", fr_twist(b, X, 0, -0.5, 1, 0.2, 1.9))
MAP(twy, "hfTwistY(xt, -0.5, 1, 0.2, 1.9);", fr_twist(b, X, 1, -0.5, 1, 0.2, 1.9))
MAP(twz, "hfTwistZ(xt, -0.5, 1, 0.2, 1.9);", fr_twist(b, X, 2, -0.5, 1, 0.2, 1.9))
MAP(tpx, "hfTaperX(xt, -0.5, 1, 0.6, 1.8);", fr_taper(b, X, 0, -0.5, 1, 0.6, 1.8))
MAP(tpy, "hfTaperY(xt, -0.5, 1, 0.6, 1.8);", fr_taper(b, X, 1, -0.5, 1, 0.6, 1.8))
MAP(tpz, "hfTaperZ(xt, -0.5, 1, 0.6, 1.8);", fr_taper(b, X, 2, -0.5, 1, 0.6, 1.8))
MAP(stretch, "hfStretch3D(xt, c, 1.5, 0.5, 2);", fr_stretch(b, X, C, SC3))
MAP(chain, "hfShift3D(xt, 0.3, -0.1, 0.2); t = hfRotate3DZ(xt, 0.7);",
    fr_rotate(b, fr_translate(b, X, SH), 2, 0.7))
static void every_space_map_matches_api(void)
{
    map_shift(); map_scale(); map_rotx(); map_roty(); map_rotz(); map_twx(); map_twy(); map_twz();
    map_tpx(); map_tpy(); map_tpz(); map_stretch(); map_chain();
}

/* ---------------------------------------------------------- arrays and attributes */
static fr_node_t api_arrays(fr_builder_t *b, fr_p3_t X)
{
    double c2[3] = {0.5, 0.25, -1.5}; /* [a[1]*2, a[1], a[2]] */
    return fr_sphere(b, X, c2, 1.0);
}
static void constant_arrays_and_elements(void)
{
    same_as_api("array d[3]; d = [a[1]*2, 0, a[2]]; d[2] = a[1]; m = hfSphere(x, d, 1);", api_arrays, 0, 1e-15);
}
static void attributes_from_third_array(void)
{
    const char *text = "m(x[3], a[1], s[3]) { s[1] = abs(x[1]); s[3] = 0.5; m = 1 - x[1]^2; }";
    fr_tape_t t;
    fr_diag_t d;
    T_INT_EQ(parse_text(text, &t, &d, 0), FR_OK);
    T_INT_EQ(t.n_outputs, 4);
    double out[4], p[3] = {-0.5, 0, 0}, sc[64];
    fr_eval_outputs(&t, p, sc, out);
    T_EQ(out[0], 0.75);
    T_EQ(out[1], 0.5);
    T_EQ(out[2], 0.0);
    T_EQ(out[3], 0.5);
    fr_tape_free(&t);
}

/* ---------------------------------------------------------- example models */
static char *read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    char *buf = malloc(1 << 16);
    *len = fread(buf, 1, (1 << 16) - 1, f);
    buf[*len] = 0;
    fclose(f);
    return buf;
}
static void example_models_parse(void)
{
    static const char *files[] = {"cup", "blended_cylinders", "tangle_cube", "barth_sextic", "noise_hole",
                                  "metamorphosis"};
    /* a point inside each solid and one outside */
    /* Barth: inside the spike through the node at (1, 1, 1); the origin is outside */
    static const double in[6][3] = {{0.95, 0, 0.5}, {0.9, 0, 0}, {1.6, 1.6, 0}, {1.5, 1.5, 1.5}, {0.7, 0, 0}, {0, 0, 0}};
    static const double out[6][3] = {{0, 0, 0.5}, {1, 1, 1}, {0, 0, 0}, {2, 0, 0}, {0, 0, 0}, {2, 0, 0}};
    for (int i = 0; i < 6; i++) {
        char path[128];
        size_t len;
        snprintf(path, sizeof path, "examples/models/%s.hf", files[i]);
        char *text = read_file(path, &len);
        if (!text) {
            T_FAIL("cannot read %s (run from the repository root)", path);
            continue;
        }
        fr_tape_t t;
        fr_diag_t d;
        fr_parse_desc_t desc = {0};
        double half[1] = {0.0};
        desc.params = half;
        desc.n_params = 1;
        if (fr_parse(text, len, &desc, &t, &d) != FR_OK) {
            T_FAIL("%s: %s", path, d.message);
            free(text);
            continue;
        }
        double sc[4096];
        T_LE(fr_scratch_size(&t, FR_EVAL_POINT), sizeof sc);
        if (!(fr_eval(&t, in[i], sc) > 0)) T_FAIL("%s: inside point has f = %g", files[i], fr_eval(&t, in[i], sc));
        if (!(fr_eval(&t, out[i], sc) < 0)) T_FAIL("%s: outside point has f = %g", files[i], fr_eval(&t, out[i], sc));
        T_GT(fr_eval(&t, in[i], sc), 0);
        fr_tape_free(&t);
        free(text);
    }
}
static fr_node_t api_tangle(fr_builder_t *b, fr_p3_t X)
{
    fr_node_t s = K(b, 11.8);
    fr_node_t c[3] = {X.x, X.y, X.z};
    fr_node_t acc = FR_NODE_NONE;
    for (int i = 0; i < 3; i++) {
        fr_node_t t = fr_sub(b, fr_powi(b, c[i], 4), fr_mul(b, K(b, 5), fr_powi(b, c[i], 2)));
        acc = i ? fr_add(b, acc, t) : t;
    }
    return fr_negate(b, fr_add(b, acc, s));
}
static void tangle_cube_matches_api(void)
{
    same_as_api("m = -(x[1]^4 - 5*x[1]^2 + x[2]^4 - 5*x[2]^2 + x[3]^4 - 5*x[3]^2 + 11.8);", api_tangle, 0, 1e-14);
}

/* ---------------------------------------------------------- bad input */
typedef struct bad_case_t {
    const char *text;
    const char *needle; /* in the message */
    int line, col;      /* 0: any */
} bad_case_t;

static void bad_input_reports_position(void)
{
    static const bad_case_t cases[] = {
        {"", "empty input", 1, 1},
        {"   \n  -- only a comment\n", "empty input", 0, 0},
        {"m(x[3], a[1]) {\n  m = x[1];\n", "unbalanced braces", 3, 1},
        {"m(x[3], a[1]) {\n  m = (x[1] + 1;\n}", "expected ')'", 2, 16},
        {"m(x[3], a[1]) {\n  m = hfFoo(x, 1);\n}", "unknown function 'hfFoo'", 2, 7},
        {"m(x[3], a[1]) {\n  array c[3]; c = [0,0,0];\n  m = hfSphere(x, c);\n}", "expects 3 arguments, got 2", 3, 7},
        {"m(x[3], a[1]) {\n  m = 1e999;\n}", "out of range", 2, 7},
        {"m(x[3], a[1]) {\n  m = 123456789012345678901234567890123456789012345678901234567890123456789012345;\n}",
         "too long", 2, 7},
        {"m(x[3], a[1]) {\n  m = y + 1;\n}", "unknown variable 'y'", 2, 7},
        {"m(x[3], a[1]) {\n  m = x[4];\n}", "out of range 1..3", 2, 9},
        {"m(x[3], a[1]) {\n  m = x[1] $ 2;\n}", "unexpected character '$'", 2, 12},
        {"m(x[3], a[1]) {\n  q = 1;\n}", "never assigned", 0, 0},
        {"m(x[3], a[1]) { m = 1; } extra", "after the end", 1, 26},
        {"m(x[3], a[1]) { /* open comment", "unterminated comment", 1, 17},
        {"m(x[2], a[1]) { m = 1; }", "x[3]", 1, 5},
        {"m(x[3], a[1]) { array c[3]; c = [x[1], 0, 0]; m = hfSphere(x, c, 1); }", "constants", 0, 0},
        {"m(x[3], a[1]) { array c[3]; c = [0,0,0]; m = hfSphere(x, c, -1); }", "radius", 1, 46},
        {"m(x[3], a[1]) { m = 1 / 0; }", "not finite", 0, 0},
        {"m(x[3], a[1]) { hfShift3D(x, 1, 0, 0); m = 1; }", "cannot change 'x'", 0, 0},
        {"m(x[3], a[1]) { m = x; }", "array 'x' used where a number", 0, 0},
        {"m(x[3], a[1]) { m = m + 1; }", "used before it is set", 0, 0},
        {"\x01\x02\xff\xfe", "unexpected byte 0x01", 1, 1},
        {"m(x[3], a[1]) { m = x[1] + \xc3\xa9; }", "unexpected byte 0xc3", 1, 28},
    };
    int n = (int)(sizeof cases / sizeof cases[0]);
    for (int i = 0; i < n; i++) {
        fr_tape_t t;
        fr_diag_t d;
        fr_result_t r = parse_text(cases[i].text, &t, &d, 0);
        if (r == FR_OK) {
            T_FAIL("case %d accepted: %s", i, cases[i].text);
            fr_tape_free(&t);
            continue;
        }
        T_CHECK(r == FR_ERR_PARSE || r == FR_ERR_INVALID_ARG || r == FR_ERR_LIMIT);
        T_INT_EQ(d.result, r);
        if (!strstr(d.message, cases[i].needle)) T_FAIL("case %d: message '%s' lacks '%s'", i, d.message, cases[i].needle);
        T_GE(d.line, 1);
        T_GE(d.column, 1);
        if (cases[i].line && (d.line != cases[i].line || d.column != cases[i].col))
            T_FAIL("case %d: at %d:%d, want %d:%d (%s)", i, d.line, d.column, cases[i].line, cases[i].col, d.message);
        /* the message starts with line:column */
        char pos[32];
        snprintf(pos, sizeof pos, "%d:%d: ", d.line, d.column);
        T_CHECK(strncmp(d.message, pos, strlen(pos)) == 0);
        T_CHECK(t.code == NULL);
    }
}
/* Literals and comments the models above do not use, and calls whose
   arguments are constants (folded while parsing): the same model as the C
   API's, the constants computed by libm here. */
static fr_node_t api_folded(fr_builder_t *b, fr_p3_t X)
{
    double k = 1e-3 + 2.5E+2 + .5 + sqrt(4.0) + exp(0.5) + log(3.0) + sin(1.0) + cos(1.0) + atan(2.0) + fabs(-7.0);
    return fr_sub(b, K(b, k), X.x);
}
static void literals_comments_and_folded_calls(void)
{
    same_as_api("m = 1e-3 /* a block\n comment */ + 2.5E+2 + .5 -- a line comment\n"
                "  // and another\n"
                "  + sqrt(4) + exp(0.5) + log(3) + sin(1) + cos(1) + atan(2) + abs(-7) - x[1];",
                api_folded, 0, 1e-15);
}

/* Every other message of the parser, each from the input that causes it:
   the code, the message and where it points. Built texts (a name one
   character too long, a variable too many, a skeleton too long, an
   argument too many) after the table. */
typedef struct bad_code_case_t {
    const char *text;
    fr_result_t code;
    const char *needle;
    int line, col; /* 0: any */
} bad_code_case_t;
#define HEAD "m(x[3], a[1]) {\n"
static void check_bad(int i, const char *text, fr_result_t code, const char *needle, int line, int col)
{
    fr_tape_t t;
    fr_diag_t d;
    fr_result_t r = parse_text(text, &t, &d, 0);
    if (r == FR_OK) {
        T_FAIL("case %d accepted: %s", i, text);
        fr_tape_free(&t);
        return;
    }
    if (r != code) T_FAIL("case %d: result %d, want %d (%s)", i, (int)r, (int)code, d.message);
    if (!strstr(d.message, needle)) T_FAIL("case %d: message '%s' lacks '%s'", i, d.message, needle);
    if (line && (d.line != line || d.column != col))
        T_FAIL("case %d: at %d:%d, want %d:%d (%s)", i, d.line, d.column, line, col, d.message);
    T_CHECK(t.code == NULL);
}
static void every_parse_error_names_its_cause(void)
{
    static const bad_code_case_t cases[] = {
        {HEAD "  array c[0];\n}", FR_ERR_PARSE, "array length must be an integer from 1 to 16384", 2, 11},
        {HEAD "  array c[2.5];\n}", FR_ERR_PARSE, "array length must be an integer from 1 to 16384", 2, 11},
        {HEAD "  array c[16384];\n}", FR_ERR_LIMIT, "arrays too large in total", 2, 17},
        {HEAD "  array c[q];\n}", FR_ERR_PARSE, "array length must be a number", 2, 11},
        {HEAD "  array c[3], c[2];\n}", FR_ERR_PARSE, "'c' is already defined", 2, 15},
        {HEAD "  q = 1; array q[2];\n}", FR_ERR_PARSE, "'q' is already defined", 2, 16},
        {HEAD "  m = 10^400;\n}", FR_ERR_PARSE, "constant power is not finite", 0, 0},
        {HEAD "  m = log(0);\n}", FR_ERR_PARSE, "constant function value is not finite", 0, 0},
        {HEAD "  m = x[x[1]];\n}", FR_ERR_PARSE, "array index must be a constant", 2, 9},
        {HEAD "  m = hfBlendUni(x, 1, 0, 1, 1);\n}", FR_ERR_PARSE, "hfBlendUni argument 1 must be a number, not array 'x'", 0, 0},
        {HEAD "  m = hfBlendUni(1, 2, x[1], 1, 1);\n}", FR_ERR_PARSE, "hfBlendUni argument 3 must be a constant", 0, 0},
        {HEAD "  array c[3]; c = [0, 0, 0]; m = hfSphere(1, c, 1);\n}", FR_ERR_PARSE, "hfSphere argument 1 must be an array", 0, 0},
        {HEAD "  array q[2], c[3]; q = [0, 0]; c = [0, 0, 0]; m = hfSphere(q, c, 1);\n}", FR_ERR_PARSE,
         "hfSphere argument 1 must be an array of 3 coordinates", 0, 0},
        {HEAD "  array c[3]; c[1] = 0; m = hfSphere(x, c, 1);\n}", FR_ERR_PARSE, "array 'c' element 2 is used before it is set", 0, 0},
        {HEAD "  array c[2]; c = [0, 0]; m = hfSphere(x, c, 1);\n}", FR_ERR_PARSE, "hfSphere: array 'c' must have 3 elements", 0, 0},
        {HEAD "  array x0[2], y0[2], z0[3], k[2]; x0 = [0, 1]; y0 = [0, 1]; z0 = [0, 1, 2]; k = [1, 1];\n"
              "  m = hfSoft(x, x0, y0, z0, k, 0.5);\n}", FR_ERR_PARSE, "hfSoft: arrays must have equal lengths", 0, 0},
        {HEAD "  m = ", FR_ERR_PARSE, "unexpected end of input in an expression", 0, 0},
        {HEAD "  m = );\n}", FR_ERR_PARSE, "unexpected ')' in an expression", 2, 7},
        {HEAD "  q = 1; m = q[1];\n}", FR_ERR_PARSE, "'q' is not an array", 0, 0},
        {HEAD "  array c[3]; c[1] = 1; m = c[2];\n}", FR_ERR_PARSE, "'c[2]' is used before it is set", 0, 0},
        {HEAD "  m = x ^ 2;\n}", FR_ERR_PARSE, "'^' needs a number on its left", 0, 0},
        {HEAD "  m = x + 1;\n}", FR_ERR_PARSE, "arithmetic on a whole array", 0, 0},
        {HEAD "  m = 1 * a;\n}", FR_ERR_PARSE, "arithmetic on a whole array", 0, 0},
        {HEAD "  x = [1, 2, 3];\n}", FR_ERR_PARSE, "'x' cannot be assigned", 0, 0},
        {HEAD "  array c[3]; c = [1, 2, 3, 4];\n}", FR_ERR_PARSE, "too many elements for 'c[3]'", 0, 0},
        {HEAD "  array c[3]; c = [1, 2];\n}", FR_ERR_PARSE, "'c' has 3 elements, the literal 2", 0, 0},
        {HEAD "  array c[3], e[2]; e = [1, 2]; c = e;\n}", FR_ERR_PARSE, "'c' needs an array of 3 elements", 0, 0},
        {HEAD "  array c[3]; c = 1;\n}", FR_ERR_PARSE, "'c' needs an array of 3 elements", 0, 0},
        {HEAD "  q = 1; q[1] = 2;\n}", FR_ERR_PARSE, "'q' is not an array", 0, 0},
        {HEAD "  a[1] = 2;\n}", FR_ERR_PARSE, "'a' cannot be assigned", 0, 0},
        {HEAD "  q 5;\n}", FR_ERR_PARSE, "(a statement is an assignment or a call)", 2, 5},
        {"m(x[3], a[1], t[8]) { m = 1; }", FR_ERR_PARSE, "at most 7 attributes", 0, 0},
        {"m(x[3], a[0]) { m = 1; }", FR_ERR_PARSE, "bad parameter array length", 0, 0},
        {"m(x[3], a[1], t[1], u[1]) { m = 1; }", FR_ERR_PARSE, "at most three array parameters", 0, 0},
        {HEAD "  m = 1.2.3;\n}", FR_ERR_PARSE, "malformed number '1.2.3'", 2, 7},
        {HEAD "  m = 2e+;\n}", FR_ERR_PARSE, "malformed number '2e+'", 2, 7},
        {HEAD "  m = 1e5.5;\n}", FR_ERR_PARSE, "malformed number '1e5.5'", 2, 7},
        {HEAD "  m = 3E;\n}", FR_ERR_PARSE, "malformed number '3E'", 2, 7},
    };
    int n = (int)(sizeof cases / sizeof cases[0]), i;
    char *text = (char *)malloc(64 * 1024);
    size_t k;
    for (i = 0; i < n; i++) check_bad(i, cases[i].text, cases[i].code, cases[i].needle, cases[i].line, cases[i].col);
    /* a name of FR__P_MAX_NAME characters is one too many (one fewer is
       a name: "unknown variable") */
    k = (size_t)sprintf(text, HEAD "  m = ");
    for (i = 0; i < FR__P_MAX_NAME - 1; i++) text[k++] = 'q';
    strcpy(text + k, " + 1;\n}");
    check_bad(n, text, FR_ERR_PARSE, "unknown variable 'qqqq", 2, 7);
    text[k++] = 'q';
    strcpy(text + k, " + 1;\n}");
    check_bad(n, text, FR_ERR_PARSE, "identifier too long", 0, 0);
    /* the model's name, x, a and FR__P_MAX_SYMS - 3 variables fill the
       table; the next is refused at its name */
    k = (size_t)sprintf(text, HEAD);
    for (i = 0; i < FR__P_MAX_SYMS - 1; i++) k += (size_t)sprintf(text + k, "  q%d = %d;\n", i, i);
    strcpy(text + k, "  m = 1;\n}");
    check_bad(n + 1, text, FR_ERR_LIMIT, "too many variables", 2 + FR__P_MAX_SYMS - 3, 3);
    /* a skeleton of 65 elements */
    k = (size_t)sprintf(text, HEAD "  array x0[65], y0[65], z0[65], k[65];\n");
    {
        static const char *names[4] = {"x0", "y0", "z0", "k"};
        int a;
        for (a = 0; a < 4; a++) {
            k += (size_t)sprintf(text + k, "  %s = [", names[a]);
            for (i = 0; i < 65; i++) k += (size_t)sprintf(text + k, i ? ", %d" : "%d", a == 3 ? 1 : i);
            k += (size_t)sprintf(text + k, "];\n");
        }
    }
    strcpy(text + k, "  m = hfSoft(x, x0, y0, z0, k, 0.5);\n}");
    check_bad(n + 2, text, FR_ERR_LIMIT, "at most 64 skeleton elements per call", 0, 0);
    /* FR__P_MAX_ARGS + 1 arguments */
    k = (size_t)sprintf(text, HEAD "  m = hfSphere(x");
    for (i = 0; i < FR__P_MAX_ARGS; i++) k += (size_t)sprintf(text + k, ", 1");
    strcpy(text + k, ");\n}");
    check_bad(n + 3, text, FR_ERR_PARSE, "hfSphere: too many arguments", 0, 0);
    free(text);
}
#undef HEAD

/* A locale whose decimal point is a comma: de_DE.UTF-8 (or fr_FR) if the
   system has one, else de_DE compiled by localedef (Debian's locales
   package, installed by scripts/deps.sh test) into a temporary LOCPATH.
   NULL when neither works. */
static const char *comma_locale(char *dir)
{
    static const char *names[] = {"de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8", "fr_FR.utf8"};
    char cmd[256];
    size_t i;
    dir[0] = 0;
    for (i = 0; i < sizeof names / sizeof names[0]; i++)
        if (setlocale(LC_NUMERIC, names[i]) && localeconv()->decimal_point[0] == ',') return names[i];
    strcpy(dir, "/tmp/filigree_locale_XXXXXX");
    if (!mkdtemp(dir)) return dir[0] = 0, NULL;
    snprintf(cmd, sizeof cmd, "localedef -i de_DE -f UTF-8 '%s/de_DE.UTF-8' > /dev/null 2>&1", dir);
    if (system(cmd) == -1) return NULL;
    setenv("LOCPATH", dir, 1);
    if (setlocale(LC_NUMERIC, "de_DE.UTF-8") && localeconv()->decimal_point[0] == ',') return "de_DE.UTF-8";
    return NULL;
}

/* Parses "m = <lit>;" and returns the constant, or NAN on a parse error. */
static double literal_value(const char *lit)
{
    char text[200];
    fr_tape_t t;
    fr_diag_t d;
    double v, sc[64];
    snprintf(text, sizeof text, "m(x[3], a[1]) { m = %s; }", lit);
    if (parse_text(text, &t, &d, 0) != FR_OK) return NAN;
    T_LE(fr_scratch_size(&t, FR_EVAL_POINT), sizeof sc);
    v = fr_eval(&t, C, sc);
    fr_tape_free(&t);
    return v;
}

/* Numeric literals read as C's strtod reads them in the "C" locale, bit
   for bit, whatever LC_NUMERIC the host set: a host that calls
   setlocale(LC_ALL, "") in Germany has a decimal comma, and until
   2026-12-05 every model with a decimal point then failed ("malformed
   number '0.5'"). 20 000 random literals (1-25 digits, the point
   anywhere or nowhere, exponents to +-330) in the "C" locale and in a
   comma locale; the cup parses in both. */
static void numbers_read_alike_in_every_locale(void)
{
    t_rng_t g = {1905};
    long n = t_count(20000), i, compared = 0;
    char dir[64], lit[64];
    static char lits[20000][40];
    static double want[20000];
    const char *comma;
    int pass;
    if (n > 20000) n = 20000;
    setlocale(LC_NUMERIC, "C");
    for (i = 0; i < n; i++) {
        int nd = 1 + (int)(t_rng_unit(&g) * 25), at = (int)(t_rng_unit(&g) * (nd + 2)) - 1, k, m = 0;
        for (k = 0; k < nd; k++) {
            if (k == at) lit[m++] = '.';
            lit[m++] = (char)('0' + (int)(t_rng_unit(&g) * 10));
        }
        if (at == nd) lit[m++] = '.';
        if (t_rng_unit(&g) < 0.6) m += sprintf(lit + m, "%s%s%d", t_rng_unit(&g) < 0.5 ? "e" : "E",
                                                t_rng_unit(&g) < 0.3 ? "+" : t_rng_unit(&g) < 0.5 ? "-" : "",
                                                (int)(t_rng_unit(&g) * 331));
        lit[m] = 0;
        strcpy(lits[i], lit);
        want[i] = strtod(lit, NULL);
    }
    comma = comma_locale(dir);
    if (!comma) T_FAIL("no locale with a decimal comma (install Debian's locales package: scripts/deps.sh test)");
    for (pass = 0; pass < 2; pass++) {
        setlocale(LC_NUMERIC, pass == 0 ? "C" : comma ? comma : "C");
        for (i = 0; i < n; i++) {
            double v = literal_value(lits[i]);
            if (!(fabs(want[i]) <= 1e300)) {
                if (!isnan(v)) T_FAIL("'%.39s' (%g) accepted, out of range", lits[i], want[i]);
                continue;
            }
            if (memcmp(&v, &want[i], sizeof v) != 0)
                T_FAIL("locale %s: '%.39s' read as %.17g, strtod in C gives %.17g", pass ? comma : "C", lits[i], v, want[i]);
            compared++;
        }
        T_CHECK(!isnan(literal_value("0.5")));
    }
    T_GT(compared, n);
    {
        size_t len;
        char *text = read_file("examples/models/cup.hf", &len);
        fr_tape_t t;
        fr_diag_t d;
        fr_parse_desc_t desc = {0};
        if (T_CHECK(text != NULL)) {
            if (fr_parse(text, len, &desc, &t, &d) != FR_OK) T_FAIL("cup.hf in %s: %s", comma, d.message);
            else fr_tape_free(&t);
            free(text);
        }
    }
    setlocale(LC_NUMERIC, "C");
    if (dir[0]) {
        char cmd[128];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
        T_INT_EQ(system(cmd), 0);
    }
}

/* Literals of every length around the buffer's end, with and without an
   exponent and its sign: FR__P_MAX_NUMBER - 3 characters are read (as
   strtod reads them), longer ones are "number too long". The fuzzer
   found (2026-12-06) that an 'e' and its sign in the last two slots
   wrote the NUL one past the buffer; under ASan this test overflowed
   before the mend. */
static void long_literals_end_at_the_limit(void)
{
    static const char *tails[] = {"", "e+5", "e-5", "e5", "E+", ".5", "e+"};
    const int most = FR__P_MAX_NUMBER - 3;
    char lit[128], text[256];
    int len, k, tail;
    for (tail = 0; tail < (int)(sizeof tails / sizeof tails[0]); tail++)
        for (len = most - 8; len <= FR__P_MAX_NUMBER + 8; len++) {
            int digits = len - (int)strlen(tails[tail]);
            int well_formed = strcmp(tails[tail], "E+") != 0 && strcmp(tails[tail], "e+") != 0;
            fr_tape_t t;
            fr_diag_t d;
            lit[0] = '1';
            for (k = 1; k < digits; k++) lit[k] = '0';
            strcpy(lit + digits, tails[tail]);
            if (len > most) {
                snprintf(text, sizeof text, "m(x[3], a[1]) { m = %s; }", lit);
                if (parse_text(text, &t, &d, 0) == FR_OK) {
                    T_FAIL("%d characters '%.12s...%s' accepted, limit %d", len, lit, tails[tail], most);
                    fr_tape_free(&t);
                } else if (!strstr(d.message, "number too long"))
                    T_FAIL("%d characters '...%s': '%s', want 'number too long'", len, tails[tail], d.message);
            } else if (well_formed) {
                double v = literal_value(lit), want = strtod(lit, NULL);
                if (memcmp(&v, &want, sizeof v) != 0)
                    T_FAIL("%d characters '...%s' read as %.17g, strtod %.17g", len, tails[tail], v, want);
            } else if (!isnan(literal_value(lit)))
                T_FAIL("%d characters '...%s' (malformed) accepted", len, tails[tail]);
        }
}

static void deep_nesting_is_a_limit_not_a_crash(void)
{
    size_t n = 100000;
    char *text = malloc(n * 2 + 64);
    size_t k = (size_t)sprintf(text, "m(x[3], a[1]) { m = ");
    for (size_t i = 0; i < n; i++) text[k++] = '(';
    text[k++] = '1';
    for (size_t i = 0; i < n; i++) text[k++] = ')';
    strcpy(text + k, "; }");
    fr_tape_t t;
    fr_diag_t d;
    T_INT_EQ(fr_parse(text, strlen(text), NULL, &t, &d), FR_ERR_LIMIT);
    T_CHECK(strstr(d.message, "nested") != NULL);
    /* ~ chains too */
    k = (size_t)sprintf(text, "m(x[3], a[1]) { m = ");
    for (size_t i = 0; i < n; i++) text[k++] = '~';
    strcpy(text + k, "x[1]; }");
    T_INT_EQ(fr_parse(text, strlen(text), NULL, &t, &d), FR_ERR_LIMIT);
    free(text);
}
static void length_is_respected_without_terminator(void)
{
    /* the text is not NUL-terminated: only len bytes may be read */
    const char *full = "m(x[3], a[1]) { m = 1 - x[1]^2; }";
    size_t len = strlen(full);
    char *buf = malloc(len); /* exactly len bytes, ASan catches any overread */
    memcpy(buf, full, len);
    fr_tape_t t;
    fr_diag_t d;
    T_INT_EQ(fr_parse(buf, len, NULL, &t, &d), FR_OK);
    fr_tape_free(&t);
    T_INT_EQ(fr_parse(buf, len - 1, NULL, &t, &d), FR_ERR_PARSE); /* lost the closing brace */
    free(buf);
    fr_parse_desc_t desc = {0};
    desc.alpha = 2;
    T_INT_EQ(fr_parse(full, len, &desc, &t, &d), FR_ERR_INVALID_ARG);
    T_INT_EQ(fr_parse(full, len, NULL, NULL, &d), FR_ERR_INVALID_ARG);
}
static void random_garbage_never_crashes(void)
{
    t_rng_t r = {99};
    static const char alphabet[] = "m(x[3],a[1]){}=;+-*/^|&\\~0123456789.e hfSphereBlobyx\n[]";
    long ok = 0, errs = 0;
    for (long i = 0; i < t_count(20000); i++) {
        char buf[128];
        size_t n = (size_t)(t_rng_u64(&r) % sizeof buf);
        for (size_t k = 0; k < n; k++)
            buf[k] = (i & 1) ? (char)(t_rng_u64(&r) & 255) : alphabet[t_rng_u64(&r) % (sizeof alphabet - 1)];
        fr_tape_t t;
        fr_diag_t d;
        fr_result_t res = fr_parse(buf, n, NULL, &t, &d);
        if (res == FR_OK) {
            ok++;
            fr_tape_free(&t);
        } else {
            errs++;
            if (d.message[0] == 0) T_FAIL("empty message for result %d", (int)res);
        }
    }
    T_EQ(ok + errs, t_count(20000));
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(arithmetic_and_parameters),    T_CASE(functions_and_variables),
        T_CASE(power_right_associative_and_general), T_CASE(set_operators_alpha0),
        T_CASE(set_operators_alpha1),         T_CASE(set_operators_bind_loosest),
        T_CASE(every_primitive_matches_api),  T_CASE(every_space_map_matches_api),
        T_CASE(constant_arrays_and_elements), T_CASE(attributes_from_third_array),
        T_CASE(example_models_parse),         T_CASE(tangle_cube_matches_api),
        T_CASE(bad_input_reports_position),   T_CASE(deep_nesting_is_a_limit_not_a_crash),
        T_CASE(literals_comments_and_folded_calls), T_CASE(every_parse_error_names_its_cause),
        T_CASE(numbers_read_alike_in_every_locale), T_CASE(long_literals_end_at_the_limit),
        T_CASE(length_is_respected_without_terminator), T_CASE(random_garbage_never_crashes),
    };
    return T_RUN(argc, argv, cases);
}
