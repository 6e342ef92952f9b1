/* frep_render -- a mini Whitted ray tracer for FRep models (paper §4):
   primary rays, shadow rays, reflection and refraction to a fixed depth,
   Blinn-Phong shading, procedural attribute colours. Models are the
   HyperFun-subset files in examples/models/, plus a black-box fractal.

     build/examples/frep_render --scene cup --mode analytic --width 256 --height 256
     build/examples/frep_render --demo out        (the gallery, into out/)

   --mode picks fr_trace's method: auto analytic step interval sphere.
   Every ray is clipped to the model's fr_bound_box box and traced with
   its fr_prepare model (--unprepared: without it, for comparison; --exact:
   interval bisection without the pixel-footprint hand-over).
   It prints frames per second and rays per second (primary + shadow +
   secondary rays), timed over --frames frames after the first. */
#define IV_IMPLEMENTATION
#include "interval.h"
#define FR_IMPLEMENTATION
#include "frep.h"
#include "ex_args.h"
#include "ex_camera.h"
#include "ex_image.h"
#include "ex_math.h"
#include "ex_render.h"
#include "ex_timer.h"
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_DEPTH 3
#define RAY_EPS 1e-4
/* fr_bound_box searches this box for the solid; models are about 2-7 across */
#define SEARCH_R 5.0
#define BOUND_DEPTH 7
#define FOV_DEG 38.0

typedef struct scene_t {
    const char *name;
    fr_tape_t tape;
    fr_trace_desc_t desc;  /* primary, reflected and refracted rays */
    fr_trace_desc_t shadow; /* shadow rays: any hit, no normal */
    double box[6];         /* the solid's box (lo xyz, hi xyz): every ray is clipped to it */
    fr_prepared_t prep;    /* fr_prepare: what every ray would recompute from the tape */
    int glass;             /* refractive material */
    double floor_z;
    ex_v3_t light;         /* point light */
    ex_v3_t centre;        /* of the box, and the camera's target */
    double radius;         /* of the box's bounding sphere */
    double bound_r2;       /* that radius padded, squared: the renderer's bounding volume (misses_bound) */
    size_t scratch_bytes;  /* fr_trace_scratch_size, once */
} scene_t;

static const char *const scenes[] = {"cup", "blended_cylinders", "tangle_cube", "barth_sextic", "noise_hole",
                                     "metamorphosis", "fractal", NULL};
static const char *const modes[] = {"auto", "analytic", "step", "interval", "sphere", NULL};

/* ---------------------------------------------------------------- the black-box fractal */

/* Menger sponge, 4 levels, as a distance estimate (Lipschitz 1); f = -d. */
static double menger_point(const double p[3], void *user)
{
    double x = fabs(p[0]), y = fabs(p[1]), z = fabs(p[2]), d, s = 1.0;
    int k;
    (void)user;
    d = fmax(x, fmax(y, z)) - 1.0; /* the unit cube */
    for (k = 0; k < 4; k++) {
        double ax = fmod(p[0] * s + 300.0, 2.0) - 1.0, ay = fmod(p[1] * s + 300.0, 2.0) - 1.0;
        double az = fmod(p[2] * s + 300.0, 2.0) - 1.0, rx, ry, rz, c;
        s *= 3.0;
        rx = fabs(1.0 - 3.0 * fabs(ax));
        ry = fabs(1.0 - 3.0 * fabs(ay));
        rz = fabs(1.0 - 3.0 * fabs(az));
        c = (fmin(fmax(rx, ry), fmin(fmax(ry, rz), fmax(rz, rx))) - 1.0) / s;
        if (c > d) d = c;
    }
    return -d;
}

static int load_scene(scene_t *sc, const char *name, const char *mode, int prepare)
{
    memset(sc, 0, sizeof *sc);
    sc->name = name;
    sc->floor_z = -1.25;
    sc->light = ex_v3(4, -3, 6);
    if (!strcmp(name, "fractal")) {
        fr_builder_t b;
        fr_callback_t cb;
        static const double sc3[3] = {0.9, 0.9, 0.9};
        memset(&cb, 0, sizeof cb);
        cb.point = menger_point;
        fr_builder_init(&b, NULL);
        {
            fr_p3_t p = fr_scale(&b, fr_coords(&b), sc3);
            fr_node_t f = fr_callback(&b, p, &cb);
            if (fr_builder_finish(&b, f, NULL, 0, &sc->tape, NULL) != FR_OK) { fr_builder_free(&b); return -1; }
        }
        fr_builder_free(&b);
        sc->tape.lipschitz = 1.0 / 0.9; /* scaled distance estimate */
    } else {
        char path[512];
        FILE *f;
        char *buf;
        long n;
        fr_parse_desc_t pd;
        fr_diag_t dg;
        static const double half[1] = {0.5};
        snprintf(path, sizeof path, "examples/models/%s.hf", name);
        f = fopen(path, "rb");
        if (!f) { fprintf(stderr, "frep_render: cannot open %s\n", path); return -1; }
        fseek(f, 0, SEEK_END);
        n = ftell(f);
        fseek(f, 0, SEEK_SET);
        buf = (char *)malloc((size_t)n + 1);
        if (!buf || fread(buf, 1, (size_t)n, f) != (size_t)n) { fclose(f); free(buf); return -1; }
        fclose(f);
        memset(&pd, 0, sizeof pd);
        pd.params = half; /* metamorphosis halfway */
        pd.n_params = 1;
        if (fr_parse(buf, (size_t)n, &pd, &sc->tape, &dg) != FR_OK) {
            fprintf(stderr, "frep_render: %s:%d:%d: %s\n", path, dg.line, dg.column, dg.message);
            free(buf);
            return -1;
        }
        free(buf);
    }
    {   /* the solid's box by interval subdivision, once per model: rays clip
           to it inside fr_trace, so most shadow and floor rays cost a slab
           test; black boxes without intervals get the fractal's unit cube */
        static const double lo[3] = {-SEARCH_R, -SEARCH_R, -SEARCH_R}, hi[3] = {SEARCH_R, SEARCH_R, SEARCH_R};
        void *scr = malloc(fr_scratch_size(&sc->tape, FR_EVAL_INTERVAL));
        int k;
        if (!scr || fr_bound_box(&sc->tape, lo, hi, BOUND_DEPTH, scr, sc->box, sc->box + 3) != FR_OK)
            for (k = 0; k < 3; k++) { sc->box[k] = -1.2; sc->box[k + 3] = 1.2; }
        free(scr);
        if (!(sc->box[0] <= sc->box[3])) { fprintf(stderr, "frep_render: %s is empty\n", name); return -1; }
        sc->centre = ex_v3(0.5 * (sc->box[0] + sc->box[3]), 0.5 * (sc->box[1] + sc->box[4]), 0.5 * (sc->box[2] + sc->box[5]));
        sc->radius = 0.5 * ex_len(ex_v3(sc->box[3] - sc->box[0], sc->box[4] - sc->box[1], sc->box[5] - sc->box[2]));
        /* fr_trace pads the box by 2^-20 of its size plus the rounding of o
           (ulps): 1e-5 of the radius holds that padded box with room to spare */
        sc->bound_r2 = (sc->radius * (1 + 1e-5)) * (sc->radius * (1 + 1e-5));
        /* the model stands on the floor; the light keeps its direction */
        sc->floor_z = sc->box[2] - 1e-3 * sc->radius;
        sc->light = ex_add(sc->centre, ex_scale(ex_v3(4, -3, 6), sc->radius / 1.6));
    }
    memset(&sc->desc, 0, sizeof sc->desc);
    sc->desc.method = !strcmp(mode, "analytic") ? FR_METHOD_ANALYTIC
                    : !strcmp(mode, "step") ? FR_METHOD_STEP
                    : !strcmp(mode, "interval") ? FR_METHOD_INTERVAL
                    : !strcmp(mode, "sphere") ? FR_METHOD_SPHERE : FR_METHOD_AUTO;
    sc->desc.tol = 1e-6;
    sc->desc.step = 2.0 * sc->radius / 200.0;
    sc->desc.bounds = sc->box;
    if (prepare && fr_prepare(&sc->tape, sc->box, &sc->prep) == FR_OK) sc->desc.prepared = &sc->prep;
    if (sc->desc.method == FR_METHOD_AUTO && (sc->tape.flags & FR_TAPE_NO_INTERVAL))
        sc->desc.method = sc->tape.lipschitz < HUGE_VAL ? FR_METHOD_SPHERE : FR_METHOD_STEP;
    if (sc->tape.flags & FR_TAPE_NO_GRADIENT) sc->desc.normal = FR_NORMAL_FD;
    sc->scratch_bytes = fr_trace_scratch_size(&sc->tape, &sc->desc);
    sc->shadow = sc->desc;
    sc->shadow.any_hit = 1;
    sc->shadow.normal = FR_NORMAL_NONE;
    sc->glass = !strcmp(name, "tangle_cube");
    return 0;
}

/* ---------------------------------------------------------------- tracing */

/* ex_render starts its threads anew for every frame, so a thread's scratch
   is handed to a key whose destructor frees it when the thread ends (a
   bare __thread pointer leaked one buffer per thread per frame) */
static pthread_key_t scratch_key;
static __thread void *tls_scratch;
static __thread size_t tls_size;
/* rays traced for the current pixel by this thread (pixel() stores them
   per pixel: a shared atomic counter cost a locked add per ray and made
   the threads fight over the scene's cache line) */
static __thread unsigned int tls_rays;

static void *scratch_for(const scene_t *sc)
{
    size_t need = sc->scratch_bytes;
    if (need > tls_size) {
        free(tls_scratch);
        tls_scratch = malloc(need);
        tls_size = tls_scratch ? need : 0;
        pthread_setspecific(scratch_key, tls_scratch);
    }
    return tls_scratch;
}

/* The renderer's own bounding volume, as a ray tracer tests an object's
   before calling its intersector: a ray from outside the sphere around the
   solid's box that passes it by (t >= 0) misses the box fr_trace clips to,
   so fr_trace would report no hit. A handful of flops instead of the call
   (most shadow rays from the floor, reflections towards the sky). */
static int misses_bound(const scene_t *sc, ex_v3_t o, ex_v3_t d)
{
    ex_v3_t oc = ex_sub(o, sc->centre);
    double b = ex_dot(oc, d), c = ex_dot(oc, oc) - sc->bound_r2;
    return c > 0 && (b >= 0 || b * b < c * ex_dot(d, d)); /* outside, and moving away or passing by */
}

/* desc clips the segment to the solid's box (fr_trace_desc_t.bounds);
   tmin >= 0 */
static int trace_model(scene_t *sc, const fr_trace_desc_t *desc, ex_v3_t o, ex_v3_t d, double tmin, double tmax,
                       fr_hit_t *h)
{
    double oo[3] = {o.x, o.y, o.z}, dd[3] = {d.x, d.y, d.z};
    tls_rays++;
    if (misses_bound(sc, o, d)) return 0;
    if (fr_trace(&sc->tape, oo, dd, tmin, tmax, desc, scratch_for(sc), h) != FR_OK) return 0;
    return h->hit;
}

/* procedural attribute colour (paper §4 "Shading"): a position-dependent
   palette, or the tape's attribute outputs when the model defines them */
static ex_v3_t albedo(const scene_t *sc, ex_v3_t p)
{
    if (sc->tape.n_outputs >= 4) {
        double out[FR_MAX_OUTPUTS], pp[3] = {p.x, p.y, p.z};
        void *s = scratch_for(sc);
        fr_eval_outputs(&sc->tape, pp, s, out);
        return ex_v3(ex_clamp(out[1], 0, 1), ex_clamp(out[2], 0, 1), ex_clamp(out[3], 0, 1));
    }
    {
        double u = 0.5 + 0.5 * sin(4.0 * p.z + 2.0 * sin(3.0 * p.x)), v = 0.5 + 0.5 * cos(5.0 * p.y);
        return ex_v3(0.75 - 0.35 * u, 0.35 + 0.3 * v, 0.25 + 0.5 * u * v);
    }
}

static ex_v3_t sky(ex_v3_t d)
{
    double k = ex_clamp(0.5 + 0.5 * d.z / ex_len(d), 0, 1);
    return ex_v3(0.55 + 0.3 * k, 0.65 + 0.25 * k, 0.8 + 0.2 * k);
}

static ex_v3_t shade(scene_t *sc, ex_v3_t o, ex_v3_t d, int depth, int inside);

/* x^n, n >= 1, by squaring: the Phong and Schlick powers without a libm
   pow per shading point (within a few ulps of pow) */
static double pow_n(double x, int n)
{
    double r = 1.0;
    for (; n > 0; n >>= 1, x *= x)
        if (n & 1) r *= x;
    return r;
}

static ex_v3_t blinn_phong(scene_t *sc, ex_v3_t p, ex_v3_t n, ex_v3_t d, ex_v3_t base, int shininess)
{
    ex_v3_t l = ex_sub(sc->light, p), h, col = ex_scale(base, 0.18);
    double dist = ex_len(l), ndl;
    fr_hit_t sh;
    l = ex_scale(l, 1.0 / dist);
    ndl = ex_dot(n, l);
    if (ndl > 0 && !trace_model(sc, &sc->shadow, ex_madd(p, n, RAY_EPS), l, 0, dist, &sh)) { /* shadow ray */
        h = ex_normalize(ex_sub(l, ex_normalize(d)));
        col = ex_add(col, ex_scale(base, 0.85 * ndl));
        col = ex_add(col, ex_scale(ex_v3(1, 1, 1), 0.35 * pow_n(fmax(0, ex_dot(n, h)), shininess)));
    }
    return col;
}

static ex_v3_t shade(scene_t *sc, ex_v3_t o, ex_v3_t d, int depth, int inside)
{
    fr_hit_t h;
    double tfloor = d.z < 0 ? (sc->floor_z - o.z) / d.z : HUGE_VAL;
    int hit = trace_model(sc, &sc->desc, o, d, RAY_EPS, tfloor < HUGE_VAL ? tfloor : 1e30, &h);
    if (hit) {
        ex_v3_t p = ex_v3(h.point[0], h.point[1], h.point[2]), n = ex_v3(h.normal[0], h.normal[1], h.normal[2]);
        ex_v3_t col;
        if (inside) n = ex_neg(n);
        if (ex_dot(n, d) > 0) n = ex_neg(n); /* face the viewer */
        if (sc->glass && depth < MAX_DEPTH) {
            /* Whitted: Schlick-weighted reflection plus refraction (index 1.33) */
            double eta = inside ? 1.33 : 1.0 / 1.33, c = -ex_dot(n, ex_normalize(d)), k, fr;
            ex_v3_t dn = ex_normalize(d), refl = ex_reflect(dn, n), rcol, tcol = ex_v3(0, 0, 0);
            k = 1 - eta * eta * (1 - c * c);
            fr = 0.04 + 0.96 * pow_n(1 - c, 5);
            rcol = shade(sc, ex_madd(p, n, RAY_EPS), refl, depth + 1, inside);
            if (k > 0) {
                ex_v3_t tdir = ex_add(ex_scale(dn, eta), ex_scale(n, eta * c - sqrt(k)));
                tcol = shade(sc, ex_madd(p, n, -RAY_EPS), tdir, depth + 1, !inside);
            } else fr = 1;
            col = ex_add(ex_scale(rcol, fr), ex_scale(ex_mul(tcol, ex_v3(0.85, 0.95, 0.9)), 1 - fr));
            return col;
        }
        col = blinn_phong(sc, p, n, d, albedo(sc, p), 40);
        if (depth < MAX_DEPTH) { /* a little mirror reflection */
            ex_v3_t r = ex_reflect(ex_normalize(d), n);
            col = ex_add(ex_scale(col, 0.8), ex_scale(shade(sc, ex_madd(p, n, RAY_EPS), r, depth + 1, 0), 0.2));
        }
        return col;
    }
    if (tfloor < HUGE_VAL && !inside) { /* checkered floor with shadows and reflection */
        ex_v3_t p = ex_madd(o, d, tfloor), n = ex_v3(0, 0, 1), col;
        int chk = ((int)floor(p.x * 1.5) + (int)floor(p.y * 1.5)) & 1;
        col = blinn_phong(sc, p, n, d, chk ? ex_v3(0.8, 0.8, 0.78) : ex_v3(0.35, 0.38, 0.42), 20);
        if (depth < MAX_DEPTH)
            col = ex_add(ex_scale(col, 0.85), ex_scale(shade(sc, ex_madd(p, n, RAY_EPS), ex_reflect(ex_normalize(d), n),
                                                              depth + 1, 0), 0.15));
        return col;
    }
    return sky(d);
}

typedef struct ctx_t {
    scene_t *sc;
    ex_camera_t cam;
    unsigned int *rays; /* per pixel, summed after each frame */
    int width;
} ctx_t;

static void pixel(void *user, int x, int y, int sample, ex_rng_t *rng, float rgb[3])
{
    ctx_t *c = (ctx_t *)user;
    ex_v3_t col, d = ex_camera_dir(&c->cam, x + 0.5, y + 0.5); /* no ray differentials needed */
    tls_rays = 0;
    col = shade(c->sc, c->cam.eye, d, 0, 0);
    c->rays[(size_t)y * (size_t)c->width + (size_t)x] = tls_rays;
    (void)sample; (void)rng;
    rgb[0] = (float)col.x; rgb[1] = (float)col.y; rgb[2] = (float)col.z;
}

/* Renders `frames` timed frames after one warm-up; returns fps. */
static double render(scene_t *sc, const ex_args_t *a, int frames, int exact, const char *out_path)
{
    ctx_t c;
    ex_render_desc_t rd;
    float *rgb = (float *)malloc(sizeof(float) * 3 * (size_t)a->width * (size_t)a->height);
    double t, secs;
    unsigned long long rays = 0;
    size_t np = (size_t)a->width * (size_t)a->height, i;
    int f;
    c.sc = sc;
    c.width = a->width;
    c.rays = (unsigned int *)calloc(np, sizeof(unsigned int));
    if (!rgb || !c.rays) { fprintf(stderr, "frep_render: out of memory\n"); exit(1); }
    {   /* frame the solid whole, seen from above front right: 0.9 of the box's
           bounding sphere, since no model fills its box's corners */
        double dist = 0.9 * sc->radius / sin(0.5 * FOV_DEG * M_PI / 180.0);
        ex_v3_t eye = ex_madd(sc->centre, ex_normalize(ex_v3(3.6, -4.6, 2.9)), dist);
        ex_camera_init(&c.cam, eye, sc->centre, ex_v3(0, 0, 1), FOV_DEG, a->width, a->height);
        /* bisection hands over to regula falsi at the pixel's width
           (fr_trace_desc_t.footprint), unless --exact */
        if (!exact) sc->desc.footprint = 2.0 * tan(0.5 * FOV_DEG * M_PI / 180.0) / a->height;
    }
    memset(&rd, 0, sizeof rd);
    rd.width = a->width; rd.height = a->height; rd.spp = 1; rd.threads = a->threads; rd.quiet = 1;
    rd.label = sc->name;
    ex_render(&rd, pixel, &c, rgb); /* warm-up, and the image */
    t = ex_now();
    for (f = 0; f < frames; f++) {
        ex_render(&rd, pixel, &c, rgb);
        for (i = 0; i < np; i++) rays += c.rays[i];
    }
    secs = ex_now() - t;
    printf("%-18s %-9s %dx%d: %7.2f fps, %10.0f rays/s (%.2f rays/pixel)\n", sc->name,
           modes[sc->desc.method], a->width, a->height, frames / secs, (double)rays / secs,
           (double)rays / frames / (double)np);
    if (out_path && ex_image_write(out_path, rgb, a->width, a->height) == 0) printf("  wrote %s\n", out_path);
    free(c.rays);
    free(rgb);
    return frames / secs;
}

int main(int argc, char **argv)
{
    ex_args_t a;
    ex_args_spec_t spec;
    int frames = 3, exact = 0, unprepared = 0;
    ex_flag_t extra[3];
    memset(&a, 0, sizeof a);
    memset(&spec, 0, sizeof spec);
    a.width = 256; a.height = 256; a.spp = 1;
    extra[0].name = "frames"; extra[0].kind = EX_FLAG_INT; extra[0].value = &frames;
    extra[0].help = "timed frames after the warm-up (default 3)";
    extra[1].name = "exact"; extra[1].kind = EX_FLAG_BOOL; extra[1].value = &exact;
    extra[1].help = "interval bisection to the tolerance, without the pixel-footprint hand-over";
    extra[2].name = "unprepared"; extra[2].kind = EX_FLAG_BOOL; extra[2].value = &unprepared;
    extra[2].help = "trace the tape without fr_prepare's prepared model (for comparison)";
    spec.summary = "a Whitted ray tracer for FRep models (fr_trace), printing fps and rays/s";
    spec.scenes = scenes; spec.modes = modes; spec.extra = extra; spec.nextra = 3;
    ex_args_parse(argc, argv, &spec, &a);
    if (pthread_key_create(&scratch_key, free)) { fprintf(stderr, "frep_render: no thread key\n"); return 1; }
    if (frames < 1) frames = 1;
    if (a.demo_dir) {
        int k;
        for (k = 0; scenes[k]; k++) {
            scene_t sc;
            char name[128], path[4096];
            if (load_scene(&sc, scenes[k], "auto", 1)) return 1;
            snprintf(name, sizeof name, "frep_%s.png", scenes[k]);
            ex_args_output(&a, name, path, sizeof path);
            render(&sc, &a, 1, 0, path);
            fr_prepared_free(&sc.prep);
            fr_tape_free(&sc.tape);
        }
        return 0;
    }
    {
        scene_t sc;
        char path[4096];
        if (load_scene(&sc, a.scene ? a.scene : "cup", a.mode ? a.mode : "auto", !unprepared)) return 1;
        render(&sc, &a, frames, exact, a.out ? ex_args_output(&a, "frep_render.png", path, sizeof path) : NULL);
        fr_prepared_free(&sc.prep);
        fr_tape_free(&sc.tape);
    }
    return 0;
}
