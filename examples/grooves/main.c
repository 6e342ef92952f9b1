/* grooves — grooved and scratched surfaces with grooves.h beside the same
   grooves built as real geometry.

   Scenes (--scene): parallel (250 V-grooves near to far, the paper's Fig. 14),
   curves (a curved and a straight groove with different perturbations,
   Fig. 2), scratches (thin grooves on polished metal that cross and end:
   the polygon path, §5), tiles (a tiled floor, crossing grout lines,
   Figs. 15-16), bricks (mortar with T junctions and per-facet materials,
   Fig. 21c), frame (a window frame protruding over glass with
   inter-reflection, Fig. 21d), interreflect (inter-reflections in gold
   V-grooves, Fig. 17): these two use gr_shade_indirect() with 2 line
   samples, and the geometry renderer bounces its rays off the same
   weights (mirror fractions, the thin pane's Fresnel terms);
   scratchfield (140 scratches that cross and end, half with ploughed-up
   lips: the polygon path's cost in a render, with a 2-line-sample panel).
   Modes (--mode): ours (grooves.h, 1 sample per pixel: polygons at
   crossings and ends, §5.2-5.5), lines (the same with 2 line samples at
   crossings and ends, §5.6), geometry (Embree mesh of the swept
   cross-sections, --spp samples per pixel).

   build/examples/grooves --scene curves --mode geometry --spp 16 --out c.png
   build/examples/grooves --demo out   → out/grooves_<scene>.png: ours at 1 spp |
                                         (2 line samples at 1 spp: tiles, scratchfield) |
                                         geometry at 1 spp | geometry at 64 spp,
                                         plus each panel on its own */
#define GR_IMPLEMENTATION
#define GR_STATIC
#include "gx_scene.h"

#include "ex_args.h"
#include "ex_image.h"
#include "ex_timer.h"

typedef struct gx_image_t { float *rgb; int w, h; double seconds, build_seconds; long long bytes; } gx_image_t;

enum { GX_OURS = 0, GX_LINES = 1, GX_GEOMETRY = 2 };
static const char *const gx_mode_names[] = {"ours", "lines", "geometry", NULL};

/* Renders one panel; exits with one line on failure. */
static gx_image_t render_mode(const gx_scene_t *s, int mode, int spp, int w, int h, int threads)
{
    int geometry = mode == GX_GEOMETRY;
    gx_image_t im;
    ex_render_desc_t rd;
    gx_ours_t ours;
    gx_geo_t geo;
    double t0 = ex_now();
    char label[64];
    memset(&im, 0, sizeof im);
    im.w = w; im.h = h;
    im.rgb = (float *)malloc(sizeof(float) * 3 * (size_t)w * (size_t)h);
    if (!im.rgb) ex_fail(1, "out of memory for a %dx%d image", w, h);
    memset(&rd, 0, sizeof rd);
    rd.width = w; rd.height = h; rd.threads = threads;
    snprintf(label, sizeof label, "%s %s", s->name, gx_mode_names[mode]);
    rd.label = label;
    if (geometry) {
        if (gx_geo_init(&geo, s, w, h)) ex_fail(1, "%s: cannot set up the geometry renderer", s->name);
        im.build_seconds = ex_now() - t0;
        rd.spp = spp;
        if (ex_render(&rd, gx_geo_pixel, &geo, im.rgb)) ex_fail(1, "%s: render failed", s->name);
        im.bytes = gx_geo_bytes(&geo);
        gx_geo_free(&geo);
    } else {
        if (gx_ours_init(&ours, s, w, h)) ex_fail(1, "%s: cannot set up the grooves.h renderer", s->name);
        /* ours.perturb_normals = 0: the true normals of the sweep (grooves.h's default) */
        ours.line_samples = mode == GX_LINES ? 2 : 0;
        im.build_seconds = ex_now() - t0;
        rd.spp = 1;
        if (ex_render(&rd, gx_ours_pixel, &ours, im.rgb)) ex_fail(1, "%s: render failed", s->name);
        im.bytes = gx_ours_bytes(&ours);
        gx_ours_free(&ours);
    }
    im.seconds = ex_now() - t0;
    printf("  %-12s %-8s %4d spp  build %6.3f s  render %7.2f s  memory %9.1f KiB\n", s->name,
           gx_mode_names[mode], geometry ? spp : 1, im.build_seconds, im.seconds - im.build_seconds,
           im.bytes / 1024.0);
    fflush(stdout);
    return im;
}

static void write_png(const char *path, float *rgb, int w, int h, double exposure, double seconds)
{
    ex_image_tonemap(rgb, w, h, exposure);
    if (ex_image_write(path, rgb, w, h)) exit(1);
    ex_report_written(path, seconds);
}

/* Panels side by side with a 4-pixel dark gap. */
static float *side_by_side(gx_image_t *p, int n, int *W)
{
    int i, y, gap = 4, w = p[0].w, h = p[0].h;
    float *out;
    *W = n * w + (n - 1) * gap;
    out = (float *)calloc((size_t)*W * (size_t)h * 3, sizeof(float));
    if (!out) ex_fail(1, "out of memory for the gallery image");
    for (i = 0; i < n; i++)
        for (y = 0; y < h; y++)
            memcpy(out + 3 * ((size_t)y * *W + (size_t)i * (w + gap)), p[i].rgb + 3 * (size_t)y * w, sizeof(float) * 3 * w);
    return out;
}

/* The gallery: per scene ours | geometry 1 spp | geometry 64 spp; scenes
   with lines_panel (the tiled floor, issue 8's Figures 15-16, and the
   scratch field) also with 2 line samples, second. */
static void demo(const ex_args_t *a)
{
    int si, i, W;
    char probe[4096];
    ex_args_output_extra(a, "grooves_parallel.png", probe, sizeof probe); /* fail now, not after rendering */
    for (si = 0; gx_scene_names[si]; si++) {
        gx_scene_t s;
        gx_image_t p[4];
        int modes[4], spps[4], np = 0;
        char path[4096], name[128];
        double t0 = ex_now();
        float *all;
        if (a->scene && strcmp(a->scene, gx_scene_names[si])) continue;
        if (gx_scene_make(&s, gx_scene_names[si])) ex_fail(1, "out of memory building scene %s", gx_scene_names[si]);
        printf("%s: %s, %dx%d\n", s.name, s.title, a->width, a->height);
        modes[np] = GX_OURS; spps[np++] = 1;
        if (s.lines_panel) { modes[np] = GX_LINES; spps[np++] = 1; }
        modes[np] = GX_GEOMETRY; spps[np++] = 1;
        modes[np] = GX_GEOMETRY; spps[np++] = 64;
        for (i = 0; i < np; i++) p[i] = render_mode(&s, modes[i], spps[i], a->width, a->height, a->threads);
        all = side_by_side(p, np, &W);
        snprintf(name, sizeof name, "grooves_%s.png", s.name);
        write_png(ex_args_output_extra(a, name, path, sizeof path), all, W, a->height, s.exposure, ex_now() - t0);
        free(all);
        for (i = 0; i < np; i++) {
            snprintf(name, sizeof name, "grooves_%s_%s%d.png", s.name, gx_mode_names[modes[i]], spps[i]);
            write_png(ex_args_output_extra(a, name, path, sizeof path), p[i].rgb, p[i].w, p[i].h, s.exposure,
                      p[i].seconds);
            free(p[i].rgb);
        }
        gx_scene_free(&s);
    }
}

int main(int argc, char **argv)
{
    ex_args_t a;
    ex_args_spec_t spec;
    memset(&a, 0, sizeof a);
    a.width = 400; a.height = 250; a.spp = 16;
    memset(&spec, 0, sizeof spec);
    spec.summary = "grooved surfaces: grooves.h at 1 spp beside the grooves as Embree geometry";
    spec.scenes = gx_scene_names;
    spec.modes = gx_mode_names;
    ex_args_parse(argc, argv, &spec, &a);
    if (a.selftest) ex_fail(2, "--selftest: the grooves example has none (see tests/test_grooves_oracle*.c)");
    if (a.demo_dir && !a.out) {
        demo(&a);
        return 0;
    }
    {
        gx_scene_t s;
        gx_image_t im;
        int mode = a.mode && !strcmp(a.mode, "geometry") ? GX_GEOMETRY : a.mode && !strcmp(a.mode, "lines") ? GX_LINES
                                                                                                           : GX_OURS;
        char path[4096], name[128];
        const char *scene = a.scene ? a.scene : "parallel";
        snprintf(name, sizeof name, "grooves_%s_%s.png", scene, gx_mode_names[mode]);
        ex_args_output(&a, name, path, sizeof path);
        if (gx_scene_make(&s, scene)) ex_fail(1, "out of memory building scene %s", scene);
        im = render_mode(&s, mode, a.spp, a.width, a.height, a.threads);
        write_png(path, im.rgb, im.w, im.h, s.exposure, im.seconds);
        free(im.rgb);
        gx_scene_free(&s);
    }
    return 0;
}
