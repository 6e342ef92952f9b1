/* tests/test_examples_common.c — the example plumbing in examples/common/:
   camera differentials against finite differences, the tile renderer's
   coverage and determinism, an Embree hit on a known triangle, the mesh
   generators against the divergence theorem and their defining equations,
   and the shading lobes against closed-form integrals.
   (Image I/O needs OpenImageIO: `build/examples/sharp_cube_icosphere --selftest`.) */
#include "test.h"

#include <sys/wait.h>

#include "../examples/common/ex_args.c"
#include "../examples/common/ex_camera.c"
#include "../examples/common/ex_embree.c"
#include "../examples/common/ex_mesh.c"
#include "../examples/common/ex_progress.c"
#include "../examples/common/ex_render.c"
#include "../examples/common/ex_shade.c"
#include "../examples/common/ex_timer.c"

/* ---------------------------------------------------------------- camera */

static void camera_rejects_degenerate_frames(void)
{
    ex_camera_t c;
    T_INT_EQ(ex_camera_init(&c, ex_v3(0, 0, 0), ex_v3(0, 0, 0), ex_v3(0, 1, 0), 40, 64, 48), -1);
    T_INT_EQ(ex_camera_init(&c, ex_v3(0, 0, 0), ex_v3(0, 1, 0), ex_v3(0, 1, 0), 40, 64, 48), -1);
    T_INT_EQ(ex_camera_init(&c, ex_v3(0, 0, 0), ex_v3(0, 0, -1), ex_v3(0, 1, 0), 180, 64, 48), -1);
    T_INT_EQ(ex_camera_init(&c, ex_v3(0, 0, 0), ex_v3(0, 0, -1), ex_v3(0, 1, 0), 40, 0, 48), -1);
    T_INT_EQ(ex_camera_init(&c, ex_v3(0, 0, 0), ex_v3(0, 0, -1), ex_v3(0, 1, 0), 40, 64, 48), 0);
}

/* The image's centre looks at `at`; the top edge's centre is vfov/2 above it. */
static void camera_frame_matches_fov(void)
{
    ex_camera_t c;
    ex_v3_t from = ex_v3(1, 2, 3), at = ex_v3(-2, 0.5, -4);
    ex_v3_t want = ex_normalize(ex_sub(at, from)), d;
    T_INT_EQ(ex_camera_init(&c, from, at, ex_v3(0, 1, 0), 50, 320, 200), 0);
    d = ex_camera_dir(&c, 160, 100);
    T_NEAR(ex_dot(d, want), 1.0, 1e-15);
    d = ex_camera_dir(&c, 160, 0);
    T_NEAR(acos(ex_clamp(ex_dot(d, want), -1, 1)) * 180 / EX_PI, 25.0, 1e-9);
    T_GT(d.y, ex_camera_dir(&c, 160, 100).y);                  /* row 0 is the top */
    T_GT(ex_dot(ex_cross(want, ex_v3(0, 1, 0)), ex_camera_dir(&c, 319, 100)), 0); /* x grows to the right */
}

/* rx_d - d is the derivative of the direction per pixel, to second order:
   |D(x+1) - D(x) - D'(x)| <= max|D''| / 2, and |D''| <= 2 k² for pixel pitch k
   on the unit screen plane (normalising f + s·r with |s| <= ~1). */
static void camera_differentials_match_finite_differences(void)
{
    t_rng_t r = {42};
    int i;
    for (i = 0; i < 200; i++) {
        ex_camera_t c;  /* aspect 1:2 .. 2:1, so the screen offsets stay below 2 */
        int hgt = 40 + (int)(t_rng_unit(&r) * 400), w = hgt / 2 + (int)(t_rng_unit(&r) * 1.5 * hgt);
        double fov = t_rng_range(&r, 10, 90), px = t_rng_range(&r, 0, w - 1), py = t_rng_range(&r, 0, hgt - 1);
        double k = 2 * tan(fov * EX_PI / 360) / hgt, h = 1e-3, tol = k * k + 1e-12;
        ex_v3_t from = ex_v3(t_rng_range(&r, -5, 5), t_rng_range(&r, -5, 5), t_rng_range(&r, -5, 5));
        ex_v3_t at = ex_add(from, ex_v3(t_rng_range(&r, -1, 1), t_rng_range(&r, -1, 1), t_rng_range(&r, -1, 1)));
        ex_ray_t ray;
        ex_v3_t ddx, ddy;
        if (ex_camera_init(&c, from, at, ex_v3(0, 1, 0), fov, w, hgt)) continue;
        ray = ex_camera_ray(&c, px, py);
        ddx = ex_scale(ex_sub(ex_camera_dir(&c, px + h, py), ex_camera_dir(&c, px - h, py)), 0.5 / h);
        ddy = ex_scale(ex_sub(ex_camera_dir(&c, px, py + h), ex_camera_dir(&c, px, py - h)), 0.5 / h);
        T_CHECK(ray.has_differentials);
        T_LE(ex_len(ex_sub(ex_sub(ray.rx_d, ray.d), ddx)), tol);
        T_LE(ex_len(ex_sub(ex_sub(ray.ry_d, ray.d), ddy)), tol);
        /* and not trivially small: one pixel pitch k on the screen plane turns the
           direction by k·sin(d, right)·cos(d, forward) */
        T_REL(ex_len(ex_sub(ray.rx_d, ray.d)),
              k * sqrt(1 - ex_dot(ray.d, c.right) * ex_dot(ray.d, c.right)) * ex_dot(ray.d, c.forward), 0.02);
        T_NEAR(ex_len(ray.rx_o), ex_len(ray.o), 0);
    }
}

/* On a plane facing the camera at distance z, one pixel spans z·k at the centre. */
static void ray_footprint_is_one_pixel_on_a_facing_plane(void)
{
    ex_camera_t c;
    ex_ray_t ray;
    ex_v3_t dpdx, dpdy, p;
    double z = 7, k;
    T_INT_EQ(ex_camera_init(&c, ex_v3(0, 0, 0), ex_v3(0, 0, -1), ex_v3(0, 1, 0), 60, 400, 300), 0);
    k = 2 * tan(EX_PI / 6) / 300;
    ray = ex_camera_ray(&c, 200, 150);
    p = ex_scale(ray.d, z / -ray.d.z);
    ex_ray_footprint(&ray, p, ex_v3(0, 0, 1), &dpdx, &dpdy);
    T_REL(ex_len(dpdx), z * k, 1e-9);
    T_REL(ex_len(dpdy), z * k, 1e-9);
    T_NEAR(dpdx.y, 0, 1e-12);
    T_LT(dpdy.y, 0);            /* one pixel down */
    ray.has_differentials = 0;
    ex_ray_footprint(&ray, p, ex_v3(0, 0, 1), &dpdx, &dpdy);
    T_EQ(ex_len(dpdx) + ex_len(dpdy), 0);
}

/* ---------------------------------------------------------------- renderer */

typedef struct visit_log_t { int w, spp; int *count; int *samples; } visit_log_t;

static void log_visit(void *user, int x, int y, int sample, ex_rng_t *rng, float rgb[3])
{
    visit_log_t *v = (visit_log_t *)user;
    __atomic_fetch_add(&v->count[y * v->w + x], 1, __ATOMIC_RELAXED);
    __atomic_fetch_or(&v->samples[y * v->w + x], 1 << sample, __ATOMIC_RELAXED);
    rgb[0] = (float)sample;
    rgb[1] = (float)ex_rng_unit(rng);
    rgb[2] = (float)(x + 1000 * y);
}

static void tile_renderer_visits_every_pixel_once_per_sample(void)
{
    const int w = 37, h = 23, spp = 5;   /* sizes that are not multiples of the tile */
    visit_log_t v;
    ex_render_desc_t d;
    float *img = (float *)malloc(sizeof(float) * 3 * w * h);
    int i, bad_count = 0, bad_mask = 0, bad_mean = 0;
    v.w = w; v.spp = spp;
    v.count = (int *)calloc((size_t)(w * h), sizeof(int));
    v.samples = (int *)calloc((size_t)(w * h), sizeof(int));
    memset(&d, 0, sizeof d);
    d.width = w; d.height = h; d.spp = spp; d.threads = 2; d.tile = 8; d.quiet = 1;
    T_INT_EQ(ex_render(&d, log_visit, &v, img), 0);
    for (i = 0; i < w * h; i++) {
        bad_count += v.count[i] != spp;
        bad_mask += v.samples[i] != (1 << spp) - 1;
        bad_mean += img[3 * i] != (float)(spp - 1) / 2 || img[3 * i + 2] != (float)(i % w + 1000 * (i / w));
    }
    T_INT_EQ(bad_count, 0);
    T_INT_EQ(bad_mask, 0);
    T_INT_EQ(bad_mean, 0);
    free(img); free(v.count); free(v.samples);
}

static void tile_renderer_is_deterministic_across_thread_counts(void)
{
    const int w = 61, h = 29, spp = 3, n = 3 * w * h;
    int threads[4] = {1, 2, 3, 7}, t, *count = (int *)calloc((size_t)(w * h), sizeof(int));
    int *samples = (int *)calloc((size_t)(w * h), sizeof(int));
    float *ref = (float *)malloc(sizeof(float) * (size_t)n), *img = (float *)malloc(sizeof(float) * (size_t)n);
    visit_log_t v;
    ex_render_desc_t d;
    v.w = w; v.spp = spp; v.count = count; v.samples = samples;
    memset(&d, 0, sizeof d);
    d.width = w; d.height = h; d.spp = spp; d.seed = 1234; d.quiet = 1; d.tile = 5;
    d.threads = threads[0];
    T_INT_EQ(ex_render(&d, log_visit, &v, ref), 0);
    for (t = 1; t < 4; t++) {
        d.threads = threads[t];
        T_INT_EQ(ex_render(&d, log_visit, &v, img), 0);
        T_INT_EQ(memcmp(ref, img, sizeof(float) * (size_t)n), 0);
    }
    /* another seed gives another image */
    d.seed = 99;
    T_INT_EQ(ex_render(&d, log_visit, &v, img), 0);
    T_CHECK(memcmp(ref, img, sizeof(float) * (size_t)n) != 0);
    d.width = 0;
    fprintf(stderr, "  (an expected error line follows)\n");
    T_INT_EQ(ex_render(&d, log_visit, &v, img), -1);
    free(ref); free(img); free(count); free(samples);
}

/* Stratified draws: every point is in [0,1)², a pixel's n samples fill the
   4×4 cells of the square evenly (R2 sets have discrepancy O(log n / n)), and
   across many pixels the k-th draw is uniform (mean 1/2, variance 1/12). */
static void rng_2d_is_stratified_and_uniform(void)
{
    const int n = 64;
    int px, k, bad_range = 0, worst_cell = 0;
    double sum = 0, sum2 = 0;
    long cnt = 0;
    for (px = 0; px < 200; px++)
        for (k = 0; k < 3; k++) {
            int cells[16] = {0}, s, c;
            for (s = 0; s < n; s++) {
                ex_rng_t r = ex_rng_for_pixel(5, px, 7, s, n);
                double u = 0, v = 0;
                int j;
                for (j = 0; j <= k; j++) ex_rng_2d(&r, &u, &v);
                bad_range += !(u >= 0 && u < 1 && v >= 0 && v < 1);
                cells[(int)(u * 4) * 4 + (int)(v * 4)]++;
                sum += u + v; sum2 += u * u + v * v; cnt += 2;
            }
            for (c = 0; c < 16; c++) worst_cell = abs(cells[c] - n / 16) > worst_cell ? abs(cells[c] - n / 16) : worst_cell;
        }
    T_INT_EQ(bad_range, 0);
    T_LE(worst_cell, 2);          /* 4 expected per cell; independent draws would reach 5+ */
    T_NEAR(sum / cnt, 0.5, 0.01);
    T_NEAR(sum2 / cnt - 0.25, 1.0 / 12, 0.005);
    {
        ex_rng_t a = ex_rng_for_sample(5, 1, 2, 3);  /* count 0: plain random, still in range */
        double u, v;
        ex_rng_2d(&a, &u, &v);
        T_CHECK(u >= 0 && u < 1 && v >= 0 && v < 1);
    }
}

/* ---------------------------------------------------------------- Embree */

static void embree_hits_a_known_triangle(void)
{
    /* two triangles in z = 0, CCW seen from +z; the ray hits the second */
    static const float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 0, 0, 6, 0, 0, 5, 1, 0};
    static const uint32_t idx[] = {3, 4, 5, 0, 1, 2};
    RTCDevice dev = ex_embree_device();
    RTCScene scn;
    ex_hit_t h;
    unsigned id;
    T_CHECK(dev != NULL);
    if (!dev) return;
    scn = rtcNewScene(dev);
    id = ex_embree_add_mesh(dev, scn, pos, 6, idx, 2);
    T_INT_EQ(id, 0);
    T_INT_EQ(ex_embree_commit(dev, scn), 0);
    h = ex_embree_intersect(scn, ex_v3(0.25, 0.125, 2), ex_v3(0, 0, -0.5), 0, INFINITY);
    T_INT_EQ(h.hit, 1);
    T_NEAR(h.t, 4.0, 1e-6);                  /* t in units of the caller's d */
    T_INT_EQ(h.prim_id, 1);
    T_INT_EQ(h.geom_id, 0);
    T_NEAR(h.ng.x, 0, 1e-12); T_NEAR(h.ng.y, 0, 1e-12); T_NEAR(h.ng.z, 1, 1e-12);
    T_NEAR(h.u, 0.25, 1e-6); T_NEAR(h.v, 0.125, 1e-6);
    h = ex_embree_intersect(scn, ex_v3(0.25, 0.125, 2), ex_v3(0, 0, -0.5), 0, 3.9);
    T_INT_EQ(h.hit, 0);
    h = ex_embree_intersect(scn, ex_v3(0.9, 0.9, 2), ex_v3(0, 0, -1), 0, INFINITY);
    T_INT_EQ(h.hit, 0);                     /* outside the triangle (u + v > 1) */
    T_INT_EQ(ex_embree_occluded(scn, ex_v3(5.2, 0.2, -1), ex_v3(0, 0, 1), 0, 1.5), 1);
    T_INT_EQ(ex_embree_occluded(scn, ex_v3(5.2, 0.2, -1), ex_v3(0, 0, 1), 0, 0.5), 0);
    ex_embree_release(dev, scn);
}

static void embree_refuses_out_of_range_indices(void)
{
    static const float pos[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    static const uint32_t idx[] = {0, 1, 3};
    RTCDevice dev = ex_embree_device();
    RTCScene scn;
    if (!dev) { T_CHECK(dev != NULL); return; }
    scn = rtcNewScene(dev);
    fprintf(stderr, "  (an expected error line follows)\n");
    T_INT_EQ(ex_embree_add_mesh(dev, scn, pos, 3, idx, 1), RTC_INVALID_GEOMETRY_ID);
    ex_embree_release(dev, scn);
}

/* ---------------------------------------------------------------- meshes */

/* Volume by the divergence theorem: sum of det(a, b, c) / 6 over triangles. */
static double mesh_volume(const ex_mesh_t *m)
{
    double v = 0;
    size_t t;
    for (t = 0; t < m->ntris; t++) {
        ex_v3_t a = ex__mesh_vertex(m, m->idx[3 * t]), b = ex__mesh_vertex(m, m->idx[3 * t + 1]);
        ex_v3_t c = ex__mesh_vertex(m, m->idx[3 * t + 2]);
        v += ex_dot(a, ex_cross(b, c)) / 6;
    }
    return v;
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* Closed and consistently oriented: every directed edge occurs exactly once
   and its reverse exactly once. Returns the number of violations. */
static long mesh_open_edges(const ex_mesh_t *m)
{
    size_t n = 3 * m->ntris, i;
    uint64_t *e = (uint64_t *)malloc(sizeof(uint64_t) * n);
    long bad = 0;
    for (i = 0; i < n; i++) {
        uint64_t a = m->idx[i], b = m->idx[i % 3 == 2 ? i - 2 : i + 1];
        e[i] = a << 32 | b;
    }
    qsort(e, n, sizeof *e, cmp_u64);
    for (i = 0; i < n; i++) {
        uint64_t rev = (e[i] & 0xffffffffu) << 32 | e[i] >> 32;
        if (i + 1 < n && e[i + 1] == e[i]) bad++;
        if (!bsearch(&rev, e, n, sizeof *e, cmp_u64)) bad++;
    }
    free(e);
    return bad;
}

static void cube_is_closed_outward_with_volume_8(void)
{
    ex_mesh_t m = {0};
    size_t i;
    T_INT_EQ(ex_mesh_cube(&m), 0);
    T_INT_EQ(m.ntris, 12);
    T_INT_EQ(m.nverts, 8);
    T_INT_EQ(mesh_open_edges(&m), 0);
    T_NEAR(mesh_volume(&m), 8.0, 1e-12);
    for (i = 0; i < 3 * m.nverts; i++) T_EQ(fabs(m.pos[i]), 1);
    ex_mesh_free(&m);
}

static void icosphere_counts_and_unit_radius(void)
{
    int k;
    double prev_vol = 0;
    for (k = 0; k <= 4; k++) {
        ex_mesh_t m = {0};
        size_t i;
        double worst = 0, vol;
        T_INT_EQ(ex_mesh_icosphere(&m, k), 0);
        T_INT_EQ(m.nverts, 10 * (1 << (2 * k)) + 2);
        T_INT_EQ(m.ntris, 20 * (1 << (2 * k)));
        for (i = 0; i < m.nverts; i++) worst = fmax(worst, fabs(ex_len(ex__mesh_vertex(&m, (uint32_t)i)) - 1));
        T_LE(worst, 2e-7);   /* float storage */
        T_INT_EQ(mesh_open_edges(&m), 0);
        vol = mesh_volume(&m);
        /* inscribed polyhedron: below the ball, and above the icosahedron's 2.536 */
        T_LT(vol, 4 * EX_PI / 3);
        T_GE(vol, 2.53);
        T_GT(vol, prev_vol);   /* refinement only adds volume */
        prev_vol = vol;
        if (k == 4) T_REL(vol, 4 * EX_PI / 3, 3e-3);
        ex_mesh_free(&m);
    }
    {
        ex_mesh_t m = {0};
        T_INT_EQ(ex_mesh_icosphere(&m, 9), -1);
    }
}

/* Every vertex lies at distance r from the inner box; volume approaches the
   Minkowski sum a³ + 6a²r + 3πar² + 4πr³/3 with a = 2 - 2r from below. */
static void rounded_cube_lies_on_the_rounded_box(void)
{
    double radii[3] = {0.1, 0.4, 1.0};
    int j;
    for (j = 0; j < 3; j++) {
        double r = radii[j], a = 2 - 2 * r, c = 1 - r, exact, vol, worst = 0;
        ex_mesh_t m = {0};
        size_t i;
        T_INT_EQ(ex_mesh_rounded_cube(&m, r, 16), 0);
        for (i = 0; i < m.nverts; i++) {
            ex_v3_t p = ex__mesh_vertex(&m, (uint32_t)i);
            ex_v3_t in = ex_v3(ex_clamp(p.x, -c, c), ex_clamp(p.y, -c, c), ex_clamp(p.z, -c, c));
            worst = fmax(worst, fabs(ex_len(ex_sub(p, in)) - r));
        }
        T_LE(worst, 4e-7);
        T_INT_EQ(mesh_open_edges(&m), 0);
        exact = a * a * a + 6 * a * a * r + 3 * EX_PI * a * r * r + 4 * EX_PI * r * r * r / 3;
        vol = mesh_volume(&m);
        T_LT(vol, exact);
        T_REL(vol, exact, 3e-3);
        ex_mesh_free(&m);
    }
}

static void transform_and_append_keep_meshes_outward(void)
{
    ex_mesh_t a = {0}, b = {0};
    double mirror[12] = {-1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, srt[12];
    T_INT_EQ(ex_mesh_cube(&a), 0);
    T_INT_EQ(ex_mesh_cube(&b), 0);
    ex_mesh_transform(&a, mirror);                 /* det < 0: winding must flip */
    T_NEAR(mesh_volume(&a), 8.0, 1e-12);
    ex_affine_srt(srt, 0.5, ex_v3(1, 1, 0), 0.7, ex_v3(10, 0, 0));
    ex_mesh_transform(&b, srt);
    T_NEAR(mesh_volume(&b), 1.0, 1e-6);
    T_INT_EQ(ex_mesh_append(&a, &b), 0);
    T_INT_EQ(a.nverts, 16);
    T_INT_EQ(a.ntris, 24);
    T_INT_EQ(mesh_open_edges(&a), 0);
    T_NEAR(mesh_volume(&a), 9.0, 1e-6);
    ex_mesh_free(&a);
    ex_mesh_free(&b);
}

static void obj_writer_writes_every_vertex_and_face(void)
{
    ex_mesh_t m = {0};
    char line[256];
    const char *tmp = getenv("TMPDIR");
    char path[4096];
    int nv = 0, nf = 0, max_index = 0;
    FILE *f;
    snprintf(path, sizeof path, "%s/test_examples_common_%d.obj", tmp && *tmp ? tmp : "/tmp", (int)getpid());
    T_INT_EQ(ex_mesh_cube(&m), 0);
    T_INT_EQ(ex_mesh_write_obj(&m, path), 0);
    f = fopen(path, "r");
    T_CHECK(f != NULL);
    if (!f) return;
    while (fgets(line, sizeof line, f)) {
        int a, b, c;
        if (line[0] == 'v') nv++;
        if (line[0] == 'f' && sscanf(line + 1, "%d %d %d", &a, &b, &c) == 3) {
            nf++;
            max_index = a > max_index ? a : max_index;
            max_index = b > max_index ? b : max_index;
            max_index = c > max_index ? c : max_index;
        }
    }
    fclose(f);
    remove(path);
    T_INT_EQ(nv, 8);
    T_INT_EQ(nf, 12);
    T_INT_EQ(max_index, 8);   /* OBJ indices are 1-based */
    fprintf(stderr, "  (an expected error line follows)\n");
    T_INT_EQ(ex_mesh_write_obj(&m, "/nonexistent-filigree-dir/x.obj"), -1);
    ex_mesh_free(&m);
}

/* ---------------------------------------------------------------- arguments */

static void args_parse_common_and_extra_flags(void)
{
    char *argv[] = {"prog", "--width=320", "--height", "200", "--spp", "4", "--mode", "b",
                    "--radius", "0.25", "--wire", "--name=x", "--count", "-7", NULL};
    static const char *const modes[] = {"a", "b", NULL};
    double radius = 1;
    int wire = 0, count = 0;
    const char *name = "default";
    ex_flag_t extra[4] = {{"radius", EX_FLAG_DOUBLE, NULL, "r"}, {"wire", EX_FLAG_BOOL, NULL, "w"},
                          {"name", EX_FLAG_STRING, NULL, "n"}, {"count", EX_FLAG_INT, NULL, "c"}};
    ex_args_spec_t spec;
    ex_args_t a;
    extra[0].value = &radius; extra[1].value = &wire; extra[2].value = &name; extra[3].value = &count;
    memset(&spec, 0, sizeof spec);
    spec.modes = modes; spec.extra = extra; spec.nextra = 4;
    memset(&a, 0, sizeof a);
    a.width = 1; a.height = 1; a.spp = 1;
    ex_args_parse(14, argv, &spec, &a);
    T_INT_EQ(a.width, 320); T_INT_EQ(a.height, 200); T_INT_EQ(a.spp, 4);
    T_CHECK(a.mode && !strcmp(a.mode, "b"));
    T_EQ(radius, 0.25); T_INT_EQ(wire, 1); T_CHECK(!strcmp(name, "x")); T_INT_EQ(count, -7);
    T_CHECK(a.demo_dir == NULL && a.out == NULL && !a.selftest);
}

/* Runs ex_args_parse on argv in a child (stderr silenced); returns its exit status. */
static int args_exit_status(int argc, char **argv)
{
    static const char *const modes[] = {"a", NULL};
    pid_t pid;
    int st = 0;
    fflush(NULL);
    pid = fork();
    if (pid == 0) {
        ex_args_spec_t spec;
        ex_args_t a;
        if (!freopen("/dev/null", "w", stderr) || !freopen("/dev/null", "w", stdout)) _exit(99);
        memset(&spec, 0, sizeof spec);
        spec.modes = modes;
        memset(&a, 0, sizeof a);
        a.width = a.height = a.spp = 1;
        ex_args_parse(argc, argv, &spec, &a);
        _exit(0);
    }
    if (pid < 0 || waitpid(pid, &st, 0) != pid || !WIFEXITED(st)) return -1;
    return WEXITSTATUS(st);
}

static void args_bad_input_exits_2_and_help_exits_0(void)
{
    char *unknown[] = {"prog", "--bogus", NULL}, *badint[] = {"prog", "--width", "12x", NULL};
    char *range[] = {"prog", "--spp", "0", NULL}, *missing[] = {"prog", "--height", NULL};
    char *mode[] = {"prog", "--mode", "zzz", NULL}, *stray[] = {"prog", "file.png", NULL};
    char *help[] = {"prog", "--help", NULL}, *ok[] = {"prog", "--mode", "a", NULL};
    T_INT_EQ(args_exit_status(2, unknown), 2);
    T_INT_EQ(args_exit_status(3, badint), 2);
    T_INT_EQ(args_exit_status(3, range), 2);
    T_INT_EQ(args_exit_status(2, missing), 2);
    T_INT_EQ(args_exit_status(3, mode), 2);
    T_INT_EQ(args_exit_status(2, stray), 2);
    T_INT_EQ(args_exit_status(2, help), 0);
    T_INT_EQ(args_exit_status(3, ok), 0);
}

/* ---------------------------------------------------------------- shading */

/* White Lambertian: f·cos/pdf is exactly the albedo for every sample. */
static void lambert_sampling_weight_is_albedo(void)
{
    ex_material_t m;
    ex_rng_t rng = ex_rng_for_sample(1, 2, 3, 4);
    ex_v3_t n = ex_normalize(ex_v3(0.3, 1, -0.2)), wo = ex_normalize(ex_v3(-0.5, 0.7, 0.1));
    int i, bad = 0;
    memset(&m, 0, sizeof m);
    m.diffuse = ex_v3(0.7, 0.7, 0.7);
    for (i = 0; i < 2000; i++) {
        ex_v3_t wi, wgt;
        double pdf;
        if (!ex_bsdf_sample(&m, n, wo, &rng, &wi, &wgt, &pdf)) continue;
        bad += fabs(wgt.x - 0.7) > 1e-9 || ex_dot(wi, n) <= 0;
    }
    T_INT_EQ(bad, 0);
}

/* Glass (ex_material_t.ior): refraction obeys Snell's law in the plane of
   incidence, reflection is the mirror direction, and the share of
   reflections is the Fresnel reflectance: 0.04 at normal incidence for
   index 1.5, only the s-part (rp = 0) at Brewster's angle, 1 beyond the
   critical angle from inside. */
static void dielectric_obeys_snell_and_fresnel(void)
{
    static const double eta_in[2] = {1 / 1.5, 1.5};
    ex_rng_t rng = ex_rng_for_sample(5, 6, 7, 8);
    ex_v3_t n = ex_normalize(ex_v3(0.2, 1, 0.3));
    int i, k, bad = 0;
    for (k = 0; k < 2; k++)
        for (i = 0; i < 4000; i++) {
            double a = acos(ex_rng_unit(&rng)), sin_i = sin(a), eta = eta_in[k];
            ex_v3_t t, b, wo, wi;
            int through;
            ex_onb(n, &t, &b);
            wo = ex_normalize(ex_add(ex_scale(n, cos(a)), ex_scale(t, sin_i)));
            wi = ex__shade_dielectric(n, wo, eta, &rng, &through);
            bad += fabs(ex_len(wi) - 1) > 1e-12 || fabs(ex_dot(wi, b)) > 1e-12; /* unit, in the plane of n and wo */
            if (through) {
                double sin_t = ex_len(ex_sub(wi, ex_scale(n, ex_dot(wi, n))));
                bad += ex_dot(wi, n) >= 0 || fabs(sin_t - eta * sin_i) > 1e-12 || eta * sin_i > 1;
            } else
                bad += fabs(ex_dot(wi, n) - ex_dot(wo, n)) > 1e-12 || /* the mirror: wi + wo along n */
                       ex_len(ex_sub(ex_add(wi, wo), ex_scale(n, ex_dot(ex_add(wi, wo), n)))) > 1e-12;
        }
    T_INT_EQ(bad, 0);
    {
        /* shares of reflection against the closed forms, 200 000 draws each */
        double brewster = atan(1.5), critical = asin(1 / 1.5), cases[3][3] = {{0, 1 / 1.5, 0.04}, {brewster, 1 / 1.5, 0}, {critical + 0.05, 1.5, 1}};
        double cb = cos(brewster), ct = cos(asin(sin(brewster) / 1.5)), rs = (cb / 1.5 - ct) / (cb / 1.5 + ct);
        cases[1][2] = 0.5 * rs * rs; /* rp = 0 there */
        for (k = 0; k < 3; k++) {
            ex_v3_t t, b, wo;
            long refl = 0, m = 200000, j;
            double p = cases[k][2], sd = sqrt(p * (1 - p) / (double)m);
            ex_onb(n, &t, &b);
            wo = ex_normalize(ex_add(ex_scale(n, cos(cases[k][0])), ex_scale(t, sin(cases[k][0]))));
            for (j = 0; j < m; j++) {
                int through;
                ex__shade_dielectric(n, wo, cases[k][1], &rng, &through);
                refl += !through;
            }
            T_NEAR((double)refl / (double)m, p, 5 * sd + 1e-12);
        }
    }
}

/* The sampling density integrates to at most 1 over the sphere (exactly 1
   minus what GGX sends under the horizon); checked by uniform sphere
   quadrature, and the sampled-weight estimate of the albedo matches the
   uniform-quadrature estimate (eval and sample agree). */
static void glossy_pdf_and_weights_are_consistent(void)
{
    ex_material_t m;
    ex_v3_t n = ex_v3(0, 0, 1), wo = ex_normalize(ex_v3(0.4, 0, 1));
    ex_rng_t rng = ex_rng_for_sample(7, 0, 0, 0);
    long i, N = t_count(400000);
    double pdf_sum = 0, alb_uniform = 0, alb_sampled = 0;
    memset(&m, 0, sizeof m);
    m.diffuse = ex_v3(0.3, 0.3, 0.3);
    m.specular = ex_v3(0.04, 0.04, 0.04);
    m.roughness = 0.5;
    for (i = 0; i < N; i++) {
        double z = 2 * ex_rng_unit(&rng) - 1, phi = 2 * EX_PI * ex_rng_unit(&rng), s = sqrt(1 - z * z), pdf;
        ex_v3_t wi = ex_v3(s * cos(phi), s * sin(phi), z), f, wgt;
        f = ex_bsdf_eval(&m, n, wo, wi, &pdf);
        pdf_sum += pdf * 4 * EX_PI;
        alb_uniform += f.x * 4 * EX_PI;
        if (ex_bsdf_sample(&m, n, wo, &rng, &wi, &wgt, &pdf)) alb_sampled += wgt.x;
    }
    pdf_sum /= (double)N; alb_uniform /= (double)N; alb_sampled /= (double)N;
    T_LE(pdf_sum, 1.02);
    T_GE(pdf_sum, 0.9);
    T_NEAR(alb_sampled, alb_uniform, 0.03);
    T_LT(alb_uniform, 1.0);        /* energy conserving */
}

static void rect_light_hit_and_front_side_only(void)
{
    ex_rect_light_t l;
    memset(&l, 0, sizeof l);
    l.corner = ex_v3(-1, 4, -1); l.edge_u = ex_v3(2, 0, 0); l.edge_v = ex_v3(0, 0, 2); /* u×v = -y */
    T_NEAR(ex_rect_light_hit(&l, ex_v3(0.5, 0, 0.5), ex_v3(0, 1, 0)), 4.0, 1e-12);
    T_EQ(ex_rect_light_hit(&l, ex_v3(1.5, 0, 0.5), ex_v3(0, 1, 0)), 0);  /* misses */
    T_EQ(ex_rect_light_hit(&l, ex_v3(0.5, 8, 0.5), ex_v3(0, -1, 0)), 0); /* behind */
    {
        /* ex_rect_light_toward: seen from the target it is hit at the centre's distance */
        t_rng_t r = {11};
        int i;
        for (i = 0; i < 50; i++) {
            ex_v3_t c = ex_v3(t_rng_range(&r, -5, 5), t_rng_range(&r, -5, 5), t_rng_range(&r, -5, 5));
            ex_v3_t target = ex_v3(t_rng_range(&r, -5, 5), t_rng_range(&r, -5, 5), t_rng_range(&r, -5, 5));
            ex_rect_light_t k = ex_rect_light_toward(c, target, 2, 1, ex_v3(1, 1, 1));
            ex_v3_t d = ex_normalize(ex_sub(c, target));
            T_REL(ex_rect_light_hit(&k, target, d), ex_len(ex_sub(c, target)), 1e-9);
            T_EQ(ex_rect_light_hit(&k, ex_madd(c, d, 3), ex_neg(d)), 0);     /* dark from behind */
            T_REL(ex_len(ex_cross(k.edge_u, k.edge_v)), 2.0, 1e-12);          /* area */
        }
    }
}

/* A floor y = 0 under one square light, no occluders: the path tracer's
   direct light (NEE + BSDF sampling combined by MIS) must match the
   irradiance integral done independently, by the closed-form form factor
   for a Lambertian floor and by midpoint quadrature over the light's area
   for a glossy one. */
static const ex_material_t *floor_mat_;
static int floor_hit(void *user, const ex_ray_t *r, double tmax, ex_surface_t *s)
{
    double t;
    (void)user;
    if (!(r->d.y < 0) || !(r->o.y > 0)) return 0;
    t = -r->o.y / r->d.y;
    if (t >= tmax) return 0;
    s->t = t;
    s->p = ex_madd(r->o, r->d, t);
    s->p.y = 0;
    s->n = s->ng = ex_v3(0, 1, 0);
    s->mat = floor_mat_;
    return 1;
}
static int never_occluded(void *user, ex_v3_t o, ex_v3_t d, double tmax)
{
    (void)user; (void)o; (void)d; (void)tmax;
    return 0;
}

/* Form factor from a point to a parallel a×b rectangle at height c with one
   corner straight above it (Howell's catalogue, configuration B-3). */
static double corner_form_factor(double a, double b, double c)
{
    double A = a / c, B = b / c, sa = sqrt(1 + A * A), sb = sqrt(1 + B * B);
    return (A / sa * atan(B / sa) + B / sb * atan(A / sb)) / (2 * EX_PI);
}

static double mean_radiance(const ex_world_t *w, ex_v3_t eye, long n)
{
    double sum = 0;
    long i;
    for (i = 0; i < n; i++) {
        ex_rng_t rng = ex_rng_for_pixel(3, 0, 0, (int)i, (int)n);
        ex_ray_t ray;
        memset(&ray, 0, sizeof ray);
        ray.o = eye;
        ray.d = ex_normalize(ex_sub(ex_v3(0, 0, 0), eye));
        sum += ex_radiance(w, &ray, &rng).x;
    }
    return sum / (double)n;
}

static void direct_light_matches_the_irradiance_integral(void)
{
    ex_rect_light_t light;
    ex_world_t w;
    ex_material_t m;
    const double h = 1.5, half = 1.0, Le = 3.0;
    ex_v3_t eye = ex_v3(1.8, 1.0, 1.2);
    long n = t_count(40000), i, j, q = 400;
    double want, got;
    memset(&light, 0, sizeof light);
    light.corner = ex_v3(-half, h, -half);
    light.edge_u = ex_v3(2 * half, 0, 0);   /* u×v = -y: faces the floor */
    light.edge_v = ex_v3(0, 0, 2 * half);
    light.radiance = ex_v3(Le, Le, Le);
    memset(&w, 0, sizeof w);
    w.intersect = floor_hit; w.occluded = never_occluded;
    w.lights = &light; w.nlights = 1; w.max_bounces = -1;
    memset(&m, 0, sizeof m);
    m.diffuse = ex_v3(0.5, 0.5, 0.5);
    floor_mat_ = &m;
    /* Lambertian: L = albedo · Le · F, the light split into four corner rectangles */
    want = 0.5 * Le * 4 * corner_form_factor(half, half, h);
    got = mean_radiance(&w, eye, n);
    T_REL(got, want, 0.01);
    /* glossy: quadrature of f·cos_i · Le · cos_l / d² over the light */
    m.specular = ex_v3(0.5, 0.5, 0.5);
    m.roughness = 0.35;
    want = 0;
    for (i = 0; i < q; i++)
        for (j = 0; j < q; j++) {
            ex_v3_t x = ex_v3(-half + 2 * half * (i + 0.5) / q, h, -half + 2 * half * (j + 0.5) / q);
            ex_v3_t wi = ex_normalize(x), wo = ex_normalize(eye);
            double d2 = ex_dot(x, x), cos_l = h / sqrt(d2), dA = 4 * half * half / (double)(q * q);
            want += ex_bsdf_eval(&m, ex_v3(0, 1, 0), wo, wi, NULL).x * Le * cos_l / d2 * dA;
        }
    got = mean_radiance(&w, eye, n);
    T_REL(got, want, 0.01);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(camera_rejects_degenerate_frames),
        T_CASE(camera_frame_matches_fov),
        T_CASE(camera_differentials_match_finite_differences),
        T_CASE(ray_footprint_is_one_pixel_on_a_facing_plane),
        T_CASE(tile_renderer_visits_every_pixel_once_per_sample),
        T_CASE(tile_renderer_is_deterministic_across_thread_counts),
        T_CASE(rng_2d_is_stratified_and_uniform),
        T_CASE(embree_hits_a_known_triangle),
        T_CASE(embree_refuses_out_of_range_indices),
        T_CASE(cube_is_closed_outward_with_volume_8),
        T_CASE(icosphere_counts_and_unit_radius),
        T_CASE(rounded_cube_lies_on_the_rounded_box),
        T_CASE(transform_and_append_keep_meshes_outward),
        T_CASE(obj_writer_writes_every_vertex_and_face),
        T_CASE(args_parse_common_and_extra_flags),
        T_CASE(args_bad_input_exits_2_and_help_exits_0),
        T_CASE(lambert_sampling_weight_is_albedo),
        T_CASE(glossy_pdf_and_weights_are_consistent),
        T_CASE(dielectric_obeys_snell_and_fresnel),
        T_CASE(rect_light_hit_and_front_side_only),
        T_CASE(direct_light_matches_the_irradiance_integral),
    };
    return T_RUN(argc, argv, cases);
}
