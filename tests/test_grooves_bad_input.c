/* grooves.h bad input: every rejection is a clear code plus a diagnostic
   naming the groove; nothing crashes (the sanitizer pass runs this too). */
#include "grooves.h"
#include "test.h"

static const double PATH[4] = {0.2, 0.2, 0.8, 0.7};
static const double SEC[6] = {-0.01, 0, 0, -0.01, 0.01, 0};

/* Four good grooves; the caller spoils groove 3. */
typedef struct scene_t {
    gr_groove_desc_t g[4];
    gr_grid_desc_t d;
} scene_t;

static void scene(scene_t *s)
{
    int i;
    memset(s, 0, sizeof *s);
    for (i = 0; i < 4; i++) {
        s->g[i].points = PATH;
        s->g[i].point_count = 2;
        s->g[i].section = SEC;
        s->g[i].section_count = 3;
    }
    s->d.grooves = s->g;
    s->d.groove_count = 4;
}

/* The build and the size query both reject it with `want`, naming groove
   `elem` in the message. */
static void expect(const scene_t *s, gr_result_t want, long long elem, const char *text)
{
    gr_grid_t *grid = (gr_grid_t *)1;
    gr_diag_t diag;
    size_t bytes = 123;
    char name[32];
    T_INT_EQ(gr_grid_build(&s->d, &grid, &diag), want);
    T_CHECK(grid == NULL);
    T_INT_EQ(diag.result, want);
    T_INT_EQ(diag.element, elem);
    if (elem >= 0) {
        snprintf(name, sizeof name, "groove %lld:", elem);
        if (!T_CHECK(strstr(diag.message, name) != NULL)) fprintf(stderr, "    message: %s\n", diag.message);
    }
    if (!T_CHECK(strstr(diag.message, text) != NULL)) fprintf(stderr, "    message: %s\n", diag.message);
    T_INT_EQ(gr_grid_size(&s->d, &bytes, NULL), want);
    T_INT_EQ(bytes, 0);
    T_CHECK(strcmp(gr_result_string(want), "unknown result") != 0);
}

static void nan_path_coordinate(void)
{
    scene_t s;
    double p[4] = {0.1, 0.1, NAN, 0.5};
    scene(&s);
    s.g[3].points = p;
    expect(&s, GR_ERR_NOT_FINITE, 3, "path point 1 is not finite");
    p[2] = INFINITY;
    expect(&s, GR_ERR_NOT_FINITE, 3, "not finite");
}

static void nan_section_coordinate(void)
{
    scene_t s;
    double c[6] = {-0.01, 0, 0, NAN, 0.01, 0};
    scene(&s);
    s.g[3].section = c;
    expect(&s, GR_ERR_NOT_FINITE, 3, "cross-section point 1 is not finite");
}

static void section_with_fewer_than_two_points(void)
{
    scene_t s;
    scene(&s);
    s.g[3].section_count = 1;
    expect(&s, GR_ERR_SECTION_POINTS, 3, "cross-section has 1 point");
    s.g[3].section_count = 0;
    expect(&s, GR_ERR_SECTION_POINTS, 3, "cross-section has 0 points");
    s.g[3].section_count = -5;
    expect(&s, GR_ERR_SECTION_POINTS, 3, "cross-section has -5 points");
}

static void section_ends_not_on_surface(void)
{
    scene_t s;
    double first[6] = {-0.01, -0.001, 0, -0.01, 0.01, 0}, last[6] = {-0.01, 0, 0, -0.01, 0.01, 0.002};
    scene(&s);
    s.g[3].section = first;
    expect(&s, GR_ERR_SECTION_ENDS, 3, "first point has w = -0.001");
    s.g[3].section = last;
    expect(&s, GR_ERR_SECTION_ENDS, 3, "last point has w = 0.002");
}

static void section_running_backward(void)
{
    scene_t s;
    double c[6] = {0.01, 0, 0, -0.01, -0.01, 0};
    scene(&s);
    s.g[3].section = c;
    expect(&s, GR_ERR_SECTION_ORDER, 3, "last b is not above its first b");
}

static void zero_length_path(void)
{
    scene_t s;
    double p[6] = {0.3, 0.3, 0.3, 0.3, 0.3, 0.3};
    scene(&s);
    s.g[3].points = p;
    expect(&s, GR_ERR_ZERO_LENGTH_PATH, 3, "zero length");
    s.g[3].point_count = 3;
    expect(&s, GR_ERR_ZERO_LENGTH_PATH, 3, "zero length");
}

static void wrong_point_count_for_kind(void)
{
    scene_t s;
    double p[8] = {0, 0, 0.1, 0.1, 0.2, 0, 0.3, 0.1};
    scene(&s);
    s.g[3].points = p;
    s.g[3].point_count = 1;
    expect(&s, GR_ERR_PATH_POINTS, 3, "path has 1 point; a polyline needs at least 2");
#ifndef GR_NO_CURVES
    s.g[3].kind = GR_PATH_QUADRATIC;
    s.g[3].point_count = 4;
    expect(&s, GR_ERR_PATH_POINTS, 3, "path has 4 points; a quadratic chain needs 2k+1");
    s.g[3].kind = GR_PATH_CUBIC;
    s.g[3].point_count = 3;
    expect(&s, GR_ERR_PATH_POINTS, 3, "path has 3 points; a cubic chain needs 3k+1");
#endif
    s.g[3].kind = (gr_path_kind_t)9;
    s.g[3].point_count = 2;
    expect(&s, GR_ERR_INVALID_ARG, 3, "unknown path kind");
}

static double halve(double t, void *u) { (void)u; return 0.5 + 0 * t; }

static void perturbation_without_bound(void)
{
    scene_t s;
    scene(&s);
    s.g[3].perturb = halve;
    expect(&s, GR_ERR_PERTURBATION, 3, "perturb_max > 0");
    s.g[3].perturb_max = NAN;
    expect(&s, GR_ERR_PERTURBATION, 3, "perturb_max > 0");
    s.g[3].perturb_max = -1;
    expect(&s, GR_ERR_PERTURBATION, 3, "perturb_max > 0");
}

static void null_arrays(void)
{
    scene_t s;
    scene(&s);
    s.g[3].points = NULL;
    expect(&s, GR_ERR_INVALID_ARG, 3, "points is NULL");
    scene(&s);
    s.g[3].section = NULL;
    expect(&s, GR_ERR_INVALID_ARG, 3, "section is NULL");
    T_INT_EQ(gr_grid_build(NULL, NULL, NULL), GR_ERR_INVALID_ARG);
    T_INT_EQ(gr_grid_size(&s.d, NULL, NULL), GR_ERR_INVALID_ARG);
    gr_grid_free(NULL);
}

static void empty_grids(void)
{
    scene_t s;
    scene(&s);
    s.d.groove_count = 0;
    expect(&s, GR_ERR_EMPTY_GRID, -1, "no grooves");
    s.d.groove_count = 4;
    s.d.grooves = NULL;
    expect(&s, GR_ERR_EMPTY_GRID, -1, "no grooves");
    scene(&s);
    s.d.domain[0] = 1; s.d.domain[1] = 0; s.d.domain[2] = 1; s.d.domain[3] = 1;
    expect(&s, GR_ERR_EMPTY_GRID, -1, "domain is empty");
    s.d.domain[2] = NAN;
    expect(&s, GR_ERR_NOT_FINITE, -1, "domain is not finite");
    scene(&s);
    s.d.cells_u = -1;
    expect(&s, GR_ERR_INVALID_ARG, -1, "cells_u");
}

/* Build into a caller buffer that is one byte short: refused, untouched
   beyond its size (ASan would see an overflow). */
static void buffer_too_small(void)
{
    scene_t s;
    size_t bytes = 0;
    void *buf;
    gr_grid_t *grid = NULL;
    gr_diag_t diag;
    scene(&s);
    if (!T_INT_EQ(gr_grid_size(&s.d, &bytes, NULL), GR_OK)) return;
    buf = malloc(bytes - 1);
    T_INT_EQ(gr_grid_build_into(&s.d, buf, bytes - 1, &grid, &diag), GR_ERR_BUFFER_TOO_SMALL);
    T_CHECK(grid == NULL);
    free(buf);
    buf = malloc(bytes);
    T_INT_EQ(gr_grid_build_into(&s.d, buf, bytes, &grid, &diag), GR_OK);
    T_CHECK(grid == (gr_grid_t *)buf);
    gr_grid_free(grid); /* a caller buffer: ignored */
    free(buf);
}

/* Query rejections: NULLs, NaN footprint, NaN light, light_count out of
   range, scratch too small. */
static void bad_queries(void)
{
    scene_t s;
    gr_grid_t *grid = NULL;
    gr_query_t q;
    gr_facet_list_t l;
    size_t need;
    void *scratch;
    double light[3] = {0, 0, 1};
    scene(&s);
    if (!T_INT_EQ(gr_grid_build(&s.d, &grid, NULL), GR_OK)) return;
    need = gr_query_scratch_bytes(grid);
    scratch = malloc(need);
    memset(&q, 0, sizeof q);
    q.footprint.center[0] = 0.5;
    q.footprint.center[1] = 0.45;
    q.footprint.axis1[0] = 0.01;
    q.footprint.view[2] = 1;
    T_INT_EQ(gr_query(grid, &q, scratch, need, &l), GR_OK);
    T_INT_EQ(gr_query(NULL, &q, scratch, need, &l), GR_ERR_INVALID_ARG);
    T_INT_EQ(gr_query(grid, NULL, scratch, need, &l), GR_ERR_INVALID_ARG);
    T_INT_EQ(gr_query(grid, &q, NULL, need, &l), GR_ERR_INVALID_ARG);
    T_INT_EQ(gr_query(grid, &q, scratch, need, NULL), GR_ERR_INVALID_ARG);
    T_INT_EQ(gr_query(grid, &q, scratch, need - 1, &l), GR_ERR_BUFFER_TOO_SMALL);
    q.footprint.center[0] = NAN;
    T_INT_EQ(gr_query(grid, &q, scratch, need, &l), GR_ERR_NOT_FINITE);
    q.footprint.center[0] = 0.5;
    q.footprint.view[0] = INFINITY;
    T_INT_EQ(gr_query(grid, &q, scratch, need, &l), GR_ERR_NOT_FINITE);
    q.footprint.view[0] = 0;
    q.light_count = 1;
    T_INT_EQ(gr_query(grid, &q, scratch, need, &l), GR_ERR_INVALID_ARG); /* lights NULL */
    q.lights = light;
    q.light_count = GR_MAX_LIGHTS + 1;
    T_INT_EQ(gr_query(grid, &q, scratch, need, &l), GR_ERR_INVALID_ARG);
    q.light_count = -1;
    T_INT_EQ(gr_query(grid, &q, scratch, need, &l), GR_ERR_INVALID_ARG);
    q.light_count = 1;
    /* line_samples out of 0..32 whatever the footprint meets (it was
       checked only when a footprint was handed to line samples) */
    q.line_samples = GR_LINE_MAX_SAMPLES + 1;
    T_INT_EQ(gr_query(grid, &q, scratch, need, &l), GR_ERR_INVALID_ARG);
    q.line_samples = -1;
    T_INT_EQ(gr_query(grid, &q, scratch, need, &l), GR_ERR_INVALID_ARG);
    q.line_samples = GR_LINE_MAX_SAMPLES;
    T_INT_EQ(gr_query(grid, &q, scratch, need, &l), GR_OK);
    q.line_samples = 0;
    light[1] = NAN;
    T_INT_EQ(gr_query(grid, &q, scratch, need, &l), GR_ERR_NOT_FINITE);
    free(scratch);
    gr_grid_free(grid);
}

/* Differentials: NaN, degenerate parameterisation, zero direction. */
static void bad_differentials(void)
{
    gr_differentials_t rd;
    gr_footprint_t fp;
    memset(&rd, 0, sizeof rd);
    rd.n[2] = 1;
    rd.dpdu[0] = 1;
    rd.dpdv[1] = 1;
    rd.dir[2] = -1;
    rd.rx_dir[2] = -1;
    rd.ry_dir[2] = -1;
    T_INT_EQ(gr_footprint_from_differentials(&rd, &fp, NULL), GR_OK);
    T_INT_EQ(gr_footprint_from_differentials(NULL, &fp, NULL), GR_ERR_INVALID_ARG);
    rd.p[1] = NAN;
    T_INT_EQ(gr_footprint_from_differentials(&rd, &fp, NULL), GR_ERR_NOT_FINITE);
    rd.p[1] = 0;
    rd.dpdv[0] = 1; rd.dpdv[1] = 0; /* parallel to dp/du */
    T_INT_EQ(gr_footprint_from_differentials(&rd, &fp, NULL), GR_ERR_INVALID_ARG);
    rd.dpdv[0] = 0; rd.dpdv[1] = 1;
    rd.dir[2] = 0;
    T_INT_EQ(gr_footprint_from_differentials(&rd, &fp, NULL), GR_ERR_INVALID_ARG);
    rd.dir[2] = -1;
    rd.filter_radius = -1;
    T_INT_EQ(gr_footprint_from_differentials(&rd, &fp, NULL), GR_ERR_NOT_FINITE);
}

static void result_strings(void)
{
    int r;
    for (r = 0; r < GR_RESULT_COUNT_; r++) T_CHECK(strcmp(gr_result_string((gr_result_t)r), "unknown result") != 0);
    T_CHECK(strcmp(gr_result_string((gr_result_t)999), "unknown result") == 0);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(nan_path_coordinate),
        T_CASE(nan_section_coordinate),
        T_CASE(section_with_fewer_than_two_points),
        T_CASE(section_ends_not_on_surface),
        T_CASE(section_running_backward),
        T_CASE(zero_length_path),
        T_CASE(wrong_point_count_for_kind),
        T_CASE(perturbation_without_bound),
        T_CASE(null_arrays),
        T_CASE(empty_grids),
        T_CASE(buffer_too_small),
        T_CASE(bad_queries),
        T_CASE(bad_differentials),
        T_CASE(result_strings),
    };
    return T_RUN(argc, argv, cases);
}
