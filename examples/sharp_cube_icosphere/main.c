/* sharp_cube_icosphere — the baseline scene of the Blender bevel-shader post:
   a cube and an icosphere with sharp edges and glossy materials on a ground
   plane, lit by a large soft key light, a rim light and a sky, path traced
   with Embree. The rounded-edges example renders the same scene with
   filigree's rounded edges; this image is what it is compared against.

   build/examples/sharp_cube_icosphere --demo out   → out/sharp_cube_icosphere.png */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "ex_args.h"
#include "ex_camera.h"
#include "ex_embree.h"
#include "ex_image.h"
#include "ex_mesh.h"
#include "ex_render.h"
#include "ex_shade.h"
#include "ex_timer.h"

enum { GEOM_CUBE, GEOM_ICOSPHERE, GEOM_GROUND, GEOM_COUNT };

typedef struct scene_t {
    RTCDevice dev;
    RTCScene rtc;
    ex_material_t materials[GEOM_COUNT];
    ex_rect_light_t lights[3];
    ex_world_t world;
    ex_camera_t cam;
} scene_t;

static int intersect(void *user, const ex_ray_t *ray, double tmax, ex_surface_t *s)
{
    const scene_t *sc = (const scene_t *)user;
    ex_hit_t h = ex_embree_intersect(sc->rtc, ray->o, ray->d, 0, tmax);
    if (!h.hit) return 0;
    s->t = h.t;
    s->p = ex_madd(ray->o, ray->d, h.t);
    s->ng = s->n = h.ng;    /* sharp: the shading normal is the face normal */
    s->mat = &sc->materials[h.geom_id < GEOM_COUNT ? h.geom_id : GEOM_GROUND];
    return 1;
}

static int occluded(void *user, ex_v3_t o, ex_v3_t d, double tmax)
{
    return ex_embree_occluded(((const scene_t *)user)->rtc, o, d, 0, tmax);
}

static void pixel(void *user, int x, int y, int sample, ex_rng_t *rng, float rgb[3])
{
    const scene_t *sc = (const scene_t *)user;
    double jx, jy;
    ex_ray_t ray;
    ex_v3_t L;
    ex_rng_2d(rng, &jx, &jy);
    ray = ex_camera_ray(&sc->cam, x + jx, y + jy);
    L = ex_radiance(&sc->world, &ray, rng);
    (void)sample;
    rgb[0] = (float)L.x; rgb[1] = (float)L.y; rgb[2] = (float)L.z;
}

static ex_material_t glossy(double r, double g, double b, double f0, double roughness)
{
    ex_material_t m;
    memset(&m, 0, sizeof m);
    m.diffuse = ex_v3(r, g, b);
    m.specular = ex_v3(f0, f0, f0);
    m.roughness = roughness;
    return m;
}

/* Appends mesh m (transformed) to the Embree scene as geometry `expect_id`. */
static int add_object(scene_t *sc, ex_mesh_t *m, double scale, double yaw, ex_v3_t at, unsigned expect_id)
{
    double xf[12];
    unsigned id;
    ex_affine_srt(xf, scale, ex_v3(0, 1, 0), yaw, at);
    ex_mesh_transform(m, xf);
    id = ex_embree_add_mesh(sc->dev, sc->rtc, m->pos, m->nverts, m->idx, m->ntris);
    ex_mesh_free(m);
    return id == expect_id ? 0 : -1;
}

static int build_scene(scene_t *sc, int width, int height)
{
    ex_mesh_t cube, ico, ground;
    memset(&cube, 0, sizeof cube); memset(&ico, 0, sizeof ico); memset(&ground, 0, sizeof ground);
    sc->dev = ex_embree_device();
    if (!sc->dev) return -1;
    sc->rtc = rtcNewScene(sc->dev);
    if (ex_mesh_cube(&cube) || ex_mesh_icosphere(&ico, 1) || ex_mesh_ground(&ground, 40)) {
        ex_mesh_free(&cube); ex_mesh_free(&ico); ex_mesh_free(&ground);
        fprintf(stderr, "sharp_cube_icosphere: out of memory building meshes\n");
        return -1;
    }
    if (add_object(sc, &cube, 0.85, 0.6, ex_v3(-1.25, 0.85, 0.0), GEOM_CUBE) ||
        add_object(sc, &ico, 1.0, 0.3, ex_v3(1.25, 1.0, 0.1), GEOM_ICOSPHERE) ||
        add_object(sc, &ground, 1.0, 0.0, ex_v3(0, 0, 0), GEOM_GROUND) || ex_embree_commit(sc->dev, sc->rtc))
        return -1;

    sc->materials[GEOM_CUBE] = glossy(0.62, 0.08, 0.05, 0.05, 0.18);      /* red lacquer */
    sc->materials[GEOM_ICOSPHERE] = glossy(0.08, 0.22, 0.55, 0.05, 0.18); /* blue lacquer */
    sc->materials[GEOM_GROUND] = glossy(0.40, 0.39, 0.37, 0.03, 0.5);     /* warm grey floor */

    /* key: a large soft box overhead, a little in front: top faces and the
       edges between top and front faces would catch it */
    sc->lights[0].corner = ex_v3(-3.0, 6.0, 0.0);
    sc->lights[0].edge_u = ex_v3(6.0, 0, 0);
    sc->lights[0].edge_v = ex_v3(0, 0, 4.0);
    sc->lights[0].radiance = ex_v3(2.6, 2.5, 2.3);
    /* fill: a tall panel on the left, facing the objects */
    sc->lights[1].corner = ex_v3(-6.5, 0.3, 4.5);
    sc->lights[1].edge_u = ex_v3(1.6, 0, -2.4);
    sc->lights[1].edge_v = ex_v3(0, 3.5, 0);
    sc->lights[1].radiance = ex_v3(2.2, 2.3, 2.6);
    /* rim: a strip behind on the right, grazing the far vertical edges.
       A rect light emits on the side of edge_u × edge_v. */
    sc->lights[2].corner = ex_v3(8.0, 1.5, -3.5);
    sc->lights[2].edge_u = ex_v3(0, 3.0, 0);
    sc->lights[2].edge_v = ex_v3(-2.0, 0, -2.5);
    sc->lights[2].radiance = ex_v3(4.5, 4.2, 3.8);

    memset(&sc->world, 0, sizeof sc->world);
    sc->world.intersect = intersect;
    sc->world.occluded = occluded;
    sc->world.user = sc;
    sc->world.lights = sc->lights;
    sc->world.nlights = 3;
    sc->world.env.zenith = ex_v3(0.10, 0.11, 0.13);
    sc->world.env.horizon = ex_v3(0.16, 0.16, 0.17);
    sc->world.env.ground = ex_v3(0.05, 0.05, 0.05);
    sc->world.max_bounces = 1;   /* one bounce of floor light; deeper paths add noise, not looks */

    return ex_camera_init(&sc->cam, ex_v3(0.4, 4.0, 7.6), ex_v3(0.0, 0.7, 0.0), ex_v3(0, 1, 0), 30.0, width, height);
}

static int selftest(void)
{
    const char *tmp = getenv("TMPDIR");
    int failed = ex_image_selftest(tmp && *tmp ? tmp : "/tmp");
    printf("%d passed, %d failed\n", 4 - failed, failed);
    return failed ? 1 : 0;
}

int main(int argc, char **argv)
{
    ex_args_t args;
    ex_args_spec_t spec;
    ex_render_desc_t rd;
    ex_timer_t tm;
    scene_t sc;
    char path[4096];
    float *rgb;
    size_t len;

    memset(&args, 0, sizeof args);
    args.width = 640; args.height = 400; args.spp = 64;
    memset(&spec, 0, sizeof spec);
    spec.summary = "sharp-edged cube and icosphere, the rounded-edges baseline (renders with Embree)";
    ex_args_parse(argc, argv, &spec, &args);
    if (args.selftest) return selftest();
    ex_args_output(&args, "sharp_cube_icosphere.png", path, sizeof path);
    if (ex_image_check_path(path)) return 1;

    ex_timer_start(&tm);
    memset(&sc, 0, sizeof sc);
    if (build_scene(&sc, args.width, args.height)) { ex_embree_release(sc.dev, sc.rtc); return 1; }
    ex_timer_phase(&tm, "build scene");

    rgb = (float *)malloc(sizeof(float) * 3 * (size_t)args.width * (size_t)args.height);
    if (!rgb) ex_fail(1, "out of memory for a %dx%d image", args.width, args.height);
    memset(&rd, 0, sizeof rd);
    rd.width = args.width; rd.height = args.height; rd.spp = args.spp; rd.threads = args.threads;
    rd.label = "sharp_cube_icosphere";
    if (ex_render(&rd, pixel, &sc, rgb)) return 1;
    ex_timer_phase(&tm, "render");

    len = strlen(path);
    /* PNG gets the display transform; EXR keeps linear radiance */
    if (len < 4 || strcasecmp(path + len - 4, ".exr") != 0) ex_image_tonemap(rgb, args.width, args.height, 0.0);
    if (ex_image_write(path, rgb, args.width, args.height)) { free(rgb); ex_embree_release(sc.dev, sc.rtc); return 1; }
    ex_timer_phase(&tm, "write");
    printf("sharp_cube_icosphere: %dx%d, %d spp\n", args.width, args.height, args.spp);
    ex_report_written(path, ex_timer_total(&tm));
    free(rgb);
    ex_embree_release(sc.dev, sc.rtc);
    return 0;
}
