/* examples/rounded_edges — a path tracer that renders the same scene sharp,
   with rounded edges (rounded_edges.h), with the two bevel-shader baselines,
   or as a tessellated rounded mesh, and prints for each mode the share of
   rays that hit chamfers, the render time, the build time and the memory.

     build/examples/rounded_edges --scene article --mode rounded --out a.png
     build/examples/rounded_edges --scene blocks --mode bevel-cycles-4
     build/examples/rounded_edges --scene cornell --mode tess-5 --spp 64
     build/examples/rounded_edges --demo out        (the gallery)

   Modes: sharp, rounded, rounded-compact (RE_LAYOUT_COMPACT), bevel-blog-N, bevel-cycles-N, tess-N (N >= 1).
   Scenes: article (the bevel-shader post's cube and icosphere), glass (the
   same with a glass cube: rays refract through its rounded edges, in and
   out), blocks (play blocks with knobs, 250 142 triangles), cornell (a
   Cornell box seen from inside: the room is one rounded box around the
   camera). */
#define RE_IMPLEMENTATION
#define RX_SCENE_IMPLEMENTATION
#define RX_TESS_IMPLEMENTATION
#define RX_RENDER_IMPLEMENTATION
#include "rounded_edges.h"
#include "rx_scene.h"
#include "rx_tess.h"
#include "rx_render.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ex_args.h"
#include "ex_image.h"
#include "ex_timer.h"

/* One render of scene s in mode m; prints the mode's line of figures and
   writes the tone-mapped image to path (when not NULL). The linear image is
   returned in *rgb_out (caller frees) when rgb_out is not NULL. */
static int render_one(const rx_scene_t *s, rx_mode_t m, const ex_args_t *a, const char *path, float **rgb_out)
{
    rx_world_t w;
    char name[64];
    float *rgb;
    double t0 = ex_now(), secs;
    if (rx_world_build(&w, s, m, a->width, a->height, a->threads)) return -1;
    rgb = (float *)malloc(sizeof(float) * 3 * (size_t)a->width * (size_t)a->height);
    if (!rgb) { rx_world_free(&w); fprintf(stderr, "out of memory\n"); return -1; }
    secs = rx_world_render(&w, a->spp, a->threads, 1, 0, rgb);
    if (secs < 0) { free(rgb); rx_world_free(&w); return -1; }
    printf("  %-16s %9zu tris  build %7.3f s (rounding %.3f s)  memory %7.2f MB (Embree %.2f + rounding %.2f)  "
           "render %6.2f s  chamfer rays %5.2f%% of %lld\n",
           rx_mode_name(m, name, sizeof name), w.triangles, w.build_seconds, w.round_seconds,
           (double)(w.embree_bytes + (long long)w.round_bytes) / 1048576.0, (double)w.embree_bytes / 1048576.0,
           (double)w.round_bytes / 1048576.0, secs, w.rays ? 100.0 * (double)w.chamfer_rays / (double)w.rays : 0.0,
           w.rays);
    if (m.kind == RX_ROUNDED)
        printf("  %-16s %llu rounded edges, %llu spheres, %llu cylinders (%llu extra), %lld edges/vertices left sharp\n",
               "", w.round_stats.rounded_edges, w.round_stats.spheres, w.round_stats.cylinders,
               w.round_stats.extra_cylinders, w.concave_reports);
    if (m.kind == RX_TESS && w.tess_sharp_objects)
        printf("  %-16s %d objects not fully rounded by the build: tessellated sharp\n", "", w.tess_sharp_objects);
    rx_world_free(&w);
    if (path) {
        float *img = rgb;
        if (rgb_out) {
            img = (float *)malloc(sizeof(float) * 3 * (size_t)a->width * (size_t)a->height);
            if (!img) { free(rgb); fprintf(stderr, "out of memory\n"); return -1; }
            memcpy(img, rgb, sizeof(float) * 3 * (size_t)a->width * (size_t)a->height);
        }
        ex_image_tonemap(img, a->width, a->height, 0);
        if (ex_image_write(path, img, a->width, a->height)) { if (img != rgb) free(img); free(rgb); return -1; }
        ex_report_written(path, ex_now() - t0);
        if (img != rgb) free(img);
    }
    if (rgb_out) *rgb_out = rgb;
    else free(rgb);
    return 0;
}

/* Copies the crop [cx, cx+cw) x [cy, cy+ch) of src (sw wide) into dst (dw
   wide) at column dx. */
static void blit(float *dst, int dw, int dx, const float *src, int sw, int cx, int cy, int cw, int ch)
{
    int y;
    for (y = 0; y < ch; y++)
        memcpy(dst + 3 * ((size_t)y * (size_t)dw + (size_t)dx), src + 3 * ((size_t)(cy + y) * (size_t)sw + (size_t)cx),
               sizeof(float) * 3 * (size_t)cw);
}

/* The gallery: every scene sharp and rounded, and the baselines side by side. */
static int demo(const ex_args_t *base, double radius_scale)
{
    static const char *const scenes[4] = {"article", "glass", "blocks", "cornell"};
    static const int spp[4] = {16, 64, 8, 16};
    char path[4096], file[128];
    int i;
    for (i = 0; i < 4; i++) {
        rx_scene_t s;
        ex_args_t a = *base;
        rx_mode_t m;
        a.spp = spp[i];
        if (rx_scene_make(&s, scenes[i], radius_scale)) return -1;
        printf("scene %s: %zu triangles, %d objects\n", scenes[i], rx_scene_triangles(&s), s.nobj);
        memset(&m, 0, sizeof m);
        m.kind = RX_SHARP;
        snprintf(file, sizeof file, "rounded_edges_%s_sharp.png", scenes[i]);
        if (render_one(&s, m, &a, ex_args_output_extra(&a, file, path, sizeof path), NULL)) { rx_scene_free(&s); return -1; }
        m.kind = RX_ROUNDED;
        snprintf(file, sizeof file, "rounded_edges_%s_rounded.png", scenes[i]);
        if (render_one(&s, m, &a, ex_args_output_extra(&a, file, path, sizeof path), NULL)) { rx_scene_free(&s); return -1; }
        rx_scene_free(&s);
    }
    {
        /* Close-up of the article's cube corner: sharp | rounded | blog-27 | cycles-4, cropped and side by side. */
        static const char *const modes[4] = {"sharp", "rounded", "bevel-blog-27", "bevel-cycles-4"};
        rx_scene_t s;
        ex_args_t a = *base;
        int k, cw, ch;
        float *strip;
        double t0;
        a.spp = 16;
        if (rx_scene_make(&s, "article", radius_scale)) return -1;
        s.eye = ex_v3(-0.3, 3.3, 4.0); /* the cube's front top corner, (-1.56, 2, 1.39) */
        s.at = ex_v3(-1.45, 1.85, 1.2);
        s.vfov = 22;
        cw = a.width / 2;
        ch = a.height;
        strip = (float *)calloc((size_t)4 * (size_t)cw * (size_t)ch * 3, sizeof(float));
        if (!strip) { rx_scene_free(&s); fprintf(stderr, "out of memory\n"); return -1; }
        printf("scene article close-up: the baselines side by side\n");
        t0 = ex_now();
        for (k = 0; k < 4; k++) {
            rx_mode_t m;
            float *rgb;
            rx_mode_parse(modes[k], &m);
            if (render_one(&s, m, &a, NULL, &rgb)) { free(strip); rx_scene_free(&s); return -1; }
            blit(strip, 4 * cw, k * cw, rgb, a.width, a.width / 4, 0, cw, ch);
            free(rgb);
        }
        ex_image_tonemap(strip, 4 * cw, ch, 0);
        ex_args_output_extra(&a, "rounded_edges_baselines.png", path, sizeof path);
        if (ex_image_write(path, strip, 4 * cw, ch)) { free(strip); rx_scene_free(&s); return -1; }
        ex_report_written(path, ex_now() - t0);
        printf("  (left to right: %s, %s, %s, %s)\n", modes[0], modes[1], modes[2], modes[3]);
        free(strip);
        rx_scene_free(&s);
    }
    return 0;
}

/* --selftest: mode names round-trip; every scene builds in rounded,
   tess-1 and both bevel modes and, rendered small, has rays that hit
   chamfers (the bevel modes: rays whose normal the bevel changed; the
   Cycles-style one traces through an Embree context filter, which the
   scene must allow). Prints one line per check; returns the number of
   failures. */
static int selftest(void)
{
    static const char *const modes[] = {"sharp", "rounded", "bevel-blog-8", "bevel-cycles-4", "tess-3"};
    static const char *const scenes[] = {"article", "glass", "blocks", "cornell"};
    int fails = 0, i, k;
    for (i = 0; i < 5; i++) {
        rx_mode_t m;
        char buf[64];
        int ok = !rx_mode_parse(modes[i], &m) && !strcmp(rx_mode_name(m, buf, sizeof buf), modes[i]);
        printf("%s mode name %s round-trips\n", ok ? "ok  " : "FAIL", modes[i]);
        fails += !ok;
    }
    for (i = 0; i < 4; i++) {
        rx_scene_t s;
        if (rx_scene_make(&s, scenes[i], 1.0)) { printf("FAIL scene %s builds\n", scenes[i]); fails++; continue; }
        for (k = 0; k < 4; k++) {
            static const char *const built[4] = {"rounded", "tess-1", "bevel-blog-8", "bevel-cycles-4"};
            rx_world_t w;
            rx_mode_t m;
            float rgb[3 * 48 * 30];
            int ok;
            rx_mode_parse(built[k], &m);
            ok = !rx_world_build(&w, &s, m, 48, 30, 0);
            if (ok) {
                ok = rx_world_render(&w, 2, 0, 1, 1, rgb) >= 0 && w.chamfer_rays > 0;
                rx_world_free(&w);
            }
            printf("%s scene %s, mode %s: builds, renders, has chamfer rays\n", ok ? "ok  " : "FAIL", scenes[i], built[k]);
            fails += !ok;
        }
        rx_scene_free(&s);
    }
    return fails;
}

int main(int argc, char **argv)
{
    static const char *const scenes[] = {"article", "glass", "blocks", "cornell", NULL};
    ex_args_t a;
    ex_args_spec_t spec;
    double radius_scale = 1.0;
    ex_flag_t extra[1];
    rx_scene_t s;
    rx_mode_t m;
    char path[4096], file[128];
    memset(&a, 0, sizeof a);
    a.width = 480;
    a.height = 300;
    a.spp = 16;
    a.scene = "article";
    a.mode = "rounded";
    extra[0].name = "radius-scale";
    extra[0].kind = EX_FLAG_DOUBLE;
    extra[0].value = &radius_scale;
    extra[0].help = "multiply every rounding radius (default 1)";
    memset(&spec, 0, sizeof spec);
    spec.summary = "rounded edges (rounded_edges.h) beside sharp, bevel-shader and tessellated renders; "
                   "modes: sharp, rounded, rounded-compact, bevel-blog-N, bevel-cycles-N, tess-N";
    spec.scenes = scenes;
    spec.extra = extra;
    spec.nextra = 1;
    ex_args_parse(argc, argv, &spec, &a);
    if (!(radius_scale > 0) || radius_scale > 10) ex_fail(2, "--radius-scale must be in (0, 10], got %g", radius_scale);
    if (a.selftest) return selftest() ? 1 : 0;
    if (a.demo_dir) return demo(&a, radius_scale) ? 1 : 0;
    if (rx_mode_parse(a.mode, &m))
        ex_fail(2, "unknown mode '%s' (sharp, rounded, rounded-compact, bevel-blog-N, bevel-cycles-N, tess-N with N >= 1)", a.mode);
    snprintf(file, sizeof file, "rounded_edges_%s_%s.png", a.scene, a.mode);
    ex_args_output(&a, file, path, sizeof path);
    if (rx_scene_make(&s, a.scene, radius_scale)) return 1;
    printf("scene %s: %zu triangles, %d objects\n", a.scene, rx_scene_triangles(&s), s.nobj);
    if (render_one(&s, m, &a, path, NULL)) { rx_scene_free(&s); return 1; }
    rx_scene_free(&s);
    return 0;
}
