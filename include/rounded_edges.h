/* rounded_edges.h — rounded corners and edges for triangle meshes (part of filigree)

   Rounding cylinders and spheres inside the convex edges and corners of a
   triangle mesh, found from a hit on the sharp mesh (Courtin et al. 2019).

   The rounded solid is exact: near a convex corner it is the erosion of the
   mesh by r followed by a dilation by r, so where k >= 4 face planes meet
   (and their offsets miss one common point) the corner gets the spheres and
   short extra cylinders of the local eroded polytope, not one cracked sphere.
   Concave edges, open boundaries and mixed vertices stay sharp and are
   reported. Details, limits and measurements: docs/rounded_edges.md.

   INTEGRATION WITH A HOST RAY TRACER
     1. Build once: fill re_mesh_t per object (the same vertices/triangles the
        host traces), re_build() (or re_build_sizes() + re_build_into()).
     2. Per ray: the host traces its sharp mesh. On a front-face hit of object
        k, triangle f at t, call re_query(scene, o, dir, k, f, t, &h):
          RE_UNCHANGED     shade the host hit as usual;
          RE_HIT_ROUNDED   shade h.point with h.normal (h.t replaces t);
          RE_PASS_THROUGH  the ray grazes the removed edge volume and leaves
                           the sharp mesh at h.t: trace again from h.t,
                           skipping hits of object k at t <= h.t (the exit
                           face itself), and query again on the next hit.
     3. Secondary rays from a rounded hit start at re_secondary_origin()
        (paper §4, I''), on the sharp mesh, so the host's geometry does not
        shadow the rounded point.
   Rays starting inside an object (refraction) are not supported: the query
   assumes the host hit is where the ray enters the sharp mesh.

   USAGE
     In exactly one C or C++ file:
         #define RE_IMPLEMENTATION
         #include "rounded_edges.h"
     Everywhere else just #include "rounded_edges.h".
   OPTIONS (define before including)
     RE_IMPLEMENTATION  emit the implementation in this translation unit
     RE_STATIC          make every function static (private to this file)
     RE_DEF             linkage of public functions (default extern)
     RE_ASSERT(c)       internal-invariant check (default assert)
     RE_MALLOC(sz,ctx) / RE_FREE(p,ctx)   allocator hooks (default malloc/free)
   CONVENTIONS
     See docs/conventions.md: results are re_result_t codes with RE_OK = 0,
     zero-initialised config structs mean defaults, queries are const,
     allocation-free and thread-safe.

   LICENSE
     MIT, see the end of this file.
*/
#ifndef FILIGREE_RE_H
#define FILIGREE_RE_H

#include <stddef.h>
#include <math.h>
#ifndef RE_DEF
#  ifdef RE_STATIC
#    if defined(__GNUC__) || defined(__clang__)
#      define RE_DEF static __attribute__((unused))
#    else
#      define RE_DEF static
#    endif
#  else
#    define RE_DEF extern
#  endif
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* Result codes. RE_OK is 0; re_result_string() names each. */
typedef enum re_result_t {
    RE_OK = 0,
    RE_ERR_INVALID_ARG,   /* a NULL pointer or an out-of-range parameter */
    RE_ERR_OUT_OF_MEMORY, /* the allocator hook returned NULL */
    RE_ERR_NAN_VERTEX,    /* a used vertex has a NaN or infinite coordinate */
    RE_ERR_INDEX_OUT_OF_RANGE,   /* an index >= vertex_count */
    RE_ERR_BAD_FACE,             /* a polygon with fewer than 3 corners, or sizes
                                    that do not add up to index_count */
    RE_ERR_DEGENERATE_TRIANGLE,  /* zero area: repeated index, zero-length edge,
                                    collinear corners */
    RE_ERR_INCONSISTENT_WINDING, /* two triangles run through an edge the same way */
    RE_ERR_BAD_RADIUS,           /* radius not finite, or <= 0 with no edge radii */
    RE_ERR_RADIUS_TOO_LARGE,     /* RE_RADIUS_REJECT and a radius does not fit */
    RE_ERR_BUFFER_TOO_SMALL,     /* re_build_into() buffers below re_build_sizes() */
    RE_ERR_TOO_LARGE,            /* counts overflow 32-bit ids */
    RE_RESULT_COUNT_
} re_result_t;

/* A human-readable name for a result code; never NULL. */
RE_DEF const char *re_result_string(re_result_t r);

/* ---- Input ---------------------------------------------------------------
   One object = one indexed mesh, triangles or polygons (each polygon is
   split as the fan (v0, vi, vi+1); the host must number its triangles the
   same way, polygon by polygon). Triangles are counter-clockwise seen from
   outside. Objects are independent: a kd-tree per object (paper §3.2). */

typedef enum re_scalar_t {
    RE_FLOAT64 = 0, /* positions are double (default) */
    RE_FLOAT32      /* positions are float */
} re_scalar_t;

typedef struct re_mesh_t {
    const void *positions;      /* x,y,z per vertex, object units */
    re_scalar_t position_type;  /* default RE_FLOAT64 */
    size_t position_stride;     /* bytes from one vertex to the next; 0 = packed */
    unsigned vertex_count;
    const unsigned *indices;    /* 32-bit vertex indices */
    unsigned index_count;       /* 3 * triangles, or the sum of face_sizes */
    const unsigned *face_sizes; /* NULL: triangles. Else corners per polygon (>= 3) */
    unsigned face_count;        /* polygons in face_sizes (ignored when NULL) */
    double radius;              /* rounding radius of every convex edge, object
                                   units, > 0 unless edge_radius is given */
    const double *edge_radius;  /* optional, index_count entries: radius of the
                                   edge from indices[j] to the next corner of its
                                   polygon (either of the two half-edges; the
                                   smaller wins). A value <= 0 falls back to
                                   `radius`. Corners join cylinders C1 only with
                                   one radius, so every rounded patch (edges
                                   linked through rounded corners) takes the
                                   smallest radius asked along it (reported). */
} re_mesh_t;

typedef enum re_radius_policy_t {
    RE_RADIUS_CLAMP = 0, /* default: lower a too-large radius to the largest
                            valid one for its patch, report it */
    RE_RADIUS_REJECT     /* fail with RE_ERR_RADIUS_TOO_LARGE naming the element */
} re_radius_policy_t;

typedef enum re_bad_input_t {
    RE_BAD_INPUT_REJECT = 0, /* default: fail on the first bad triangle */
    RE_BAD_INPUT_SKIP        /* skip it (its edges become boundary: sharp), report it */
} re_bad_input_t;

/* What a report is about. Reports are informational (the build succeeded). */
typedef enum re_report_kind_t {
    RE_REPORT_CONCAVE_EDGE = 0,  /* left sharp (issue item 4) */
    RE_REPORT_BOUNDARY_EDGE,     /* open mesh: left sharp */
    RE_REPORT_NONMANIFOLD_EDGE,  /* more than two triangles: left sharp */
    RE_REPORT_MIXED_VERTEX,      /* convex and concave/boundary edges meet: the
                                    vertex and its edges stay sharp */
    RE_REPORT_SHARP_PATCH_EDGE,  /* convex edge left sharp because a corner of
                                    its patch is mixed (see docs: limits) */
    RE_REPORT_RADIUS_CLAMPED,    /* value = new radius */
    RE_REPORT_RADIUS_MISMATCH,   /* unequal edge radii met at a corner; value = radius kept */
    RE_REPORT_SKIPPED_TRIANGLE,  /* RE_BAD_INPUT_SKIP dropped this triangle */
    RE_REPORT_COMPLEX_CORNER     /* more than RE_MAX_CORNER_PLANES face planes
                                    meet: the vertex stays sharp */
} re_report_kind_t;

/* Distinct face planes around one rounded corner, at most (the exact corner
   enumerates plane triples, O(k^4)); vertices with more stay sharp. */
#define RE_MAX_CORNER_PLANES 64

typedef struct re_report_t {
    re_report_kind_t kind;
    unsigned object;
    long long element;  /* triangle, vertex index, or for edges the first vertex */
    long long element2; /* second vertex of an edge, else -1 */
    double value;
    const char *message; /* "object 0 edge 4-7 is concave: left sharp" (valid during the call) */
} re_report_t;

typedef void (*re_report_fn)(void *user, const re_report_t *report);

typedef struct re_scene_desc_t {
    const re_mesh_t *objects;
    unsigned object_count;
    re_radius_policy_t radius_policy; /* default RE_RADIUS_CLAMP */
    re_bad_input_t bad_input;         /* default RE_BAD_INPUT_REJECT */
    re_report_fn report;              /* optional, called during the build */
    void *report_user;
    void *alloc_ctx;                  /* passed to RE_MALLOC/RE_FREE */
} re_scene_desc_t;

/* The diagnostic filled when a build fails (docs/conventions.md). */
typedef struct re_diag_t {
    re_result_t result;
    long long element; /* offending triangle/vertex, -1 if none */
    unsigned object;
    char message[160];
} re_diag_t;

/* ---- Build ---------------------------------------------------------------- */

typedef struct re_sizes_t {
    size_t scene_bytes;   /* the buffer re_build_into() needs for the scene */
    size_t scratch_bytes; /* temporary buffer re_build_into() needs */
} re_sizes_t;

typedef struct re_stats_t {
    unsigned long long triangles, edges;
    unsigned long long flat_edges, convex_edges, concave_edges, boundary_edges,
        nonmanifold_edges;
    unsigned long long rounded_edges;      /* convex edges that got a cylinder */
    unsigned long long rounded_corners;    /* mesh vertices with a rounded corner */
    unsigned long long mixed_vertices;
    unsigned long long spheres, cylinders; /* cylinders include the extra ones */
    unsigned long long extra_cylinders;    /* exact-corner cylinders (degree >= 4) */
    unsigned long long clamped;            /* patches whose radius was lowered */
    unsigned long long kd_nodes;
    size_t bytes;                          /* whole scene, header included */
} re_stats_t;

typedef struct re_scene_t re_scene_t; /* opaque; lives in one block */

/* Sizes for re_build_into(). Runs the analysis (about half a build). */
RE_DEF re_result_t re_build_sizes(const re_scene_desc_t *desc, re_sizes_t *sizes,
                                  re_diag_t *diag);
/* Build into caller buffers (sizes from re_build_sizes(); `scene_mem` aligned
   to 16 bytes). *scene points into scene_mem; nothing to free. */
RE_DEF re_result_t re_build_into(const re_scene_desc_t *desc, void *scene_mem,
                                 size_t scene_bytes, void *scratch, size_t scratch_bytes,
                                 re_scene_t **scene, re_diag_t *diag);
/* Build with RE_MALLOC (desc->alloc_ctx); release with re_free(). */
RE_DEF re_result_t re_build(const re_scene_desc_t *desc, re_scene_t **scene,
                            re_diag_t *diag);
RE_DEF void re_free(re_scene_t *scene);
RE_DEF void re_get_stats(const re_scene_t *scene, re_stats_t *stats);
/* The largest radius used by object `object`'s rounded patches after
   clamping (0 when it has no rounded edge). */
RE_DEF double re_object_radius(const re_scene_t *scene, unsigned object);

/* ---- Query ---------------------------------------------------------------- */

typedef enum re_hit_kind_t {
    RE_UNCHANGED = 0, /* the host's hit stands (outside every rounded zone) */
    RE_HIT_ROUNDED,   /* the ray hits the rounded surface at out->t */
    RE_PASS_THROUGH   /* the ray crosses the removed volume and leaves the sharp
                         mesh at out->t: the host continues from there */
} re_hit_kind_t;

typedef enum re_feature_t {
    RE_FEATURE_FACE = 0, /* flat part of a face (RE_UNCHANGED) */
    RE_FEATURE_CYLINDER, /* index: re_get_cylinder() */
    RE_FEATURE_SPHERE    /* index: re_get_sphere() */
} re_feature_t;

typedef struct re_hit_t {
    re_hit_kind_t kind;
    double t;              /* in units of the caller's dir */
    double point[3];       /* o + t*dir */
    double normal[3];      /* unit, outward: rounded-surface normal for
                              RE_HIT_ROUNDED, else the face normal */
    re_feature_t feature;
    unsigned feature_index;
    unsigned object;
} re_hit_t;

/* The host found `dir`-ray (o + t*dir) hits `triangle` of `object` at t_host,
   from outside. Returns out->kind (also the return value). Pure, const,
   allocation-free, thread-safe. Bad ids or non-finite rays give RE_UNCHANGED. */
RE_DEF re_hit_kind_t re_query(const re_scene_t *scene, const double o[3],
                              const double dir[3], unsigned object, unsigned triangle,
                              double t_host, re_hit_t *out);

/* Origin on the sharp mesh (I'' of paper §4) for a secondary ray leaving a
   RE_HIT_ROUNDED hit along `dir` (dir . hit->normal > 0): where that ray
   leaves the sharp mesh, pushed out along the crossed face's normal by
   RE_ORIGIN_OFFSET_REL times the object's size so the host's own
   self-intersection guard is not needed. For other kinds: hit->point pushed
   out the same way. */
#define RE_ORIGIN_OFFSET_REL 1e-9
RE_DEF void re_secondary_origin(const re_scene_t *scene, const re_hit_t *hit,
                                const double dir[3], double origin[3]);

/* ---- Enumeration (tessellation, debugging) --------------------------------
   The rounded surface of a patch is: the flat faces shrunk inward, a
   cylinder of `radius` around every segment, a sphere at every centre. A
   cylinder's visible arc runs from normal n0 to normal n1 (the two offset
   faces it joins); extra cylinders (exact corners) have edge_v = -1. */
typedef struct re_sphere_t {
    double center[3];
    double radius;
    unsigned vertex; /* mesh vertex of the corner it belongs to */
} re_sphere_t;

typedef struct re_cylinder_t {
    double a[3], b[3];   /* axis end points = centres of spheres sa, sb */
    double radius;
    double n0[3], n1[3]; /* unit normals of the two faces it joins */
    unsigned sa, sb;     /* sphere indices */
    long long edge_v0, edge_v1; /* the mesh edge, or -1 for an extra cylinder */
} re_cylinder_t;

RE_DEF unsigned re_object_count(const re_scene_t *scene);
RE_DEF unsigned re_sphere_count(const re_scene_t *scene, unsigned object);
RE_DEF unsigned re_cylinder_count(const re_scene_t *scene, unsigned object);
/* Return 0 (and leave *out untouched) for an out-of-range index. */
RE_DEF int re_get_sphere(const re_scene_t *scene, unsigned object, unsigned i,
                         re_sphere_t *out);
RE_DEF int re_get_cylinder(const re_scene_t *scene, unsigned object, unsigned i,
                           re_cylinder_t *out);


/* ==== [section: baselines] (owned by the baselines/example helper) ==== */
/* ---- Bevel-shader baselines (issue 6, item 3) --------------------------
   Two normal-only "bevel" shaders that the rounded-edge method is compared
   with. They do not change the geometry: they return a shading normal for a
   hit P with outward normal N on the sharp mesh, by casting probe rays
   through a host-supplied trace callback, so any renderer can run them.
   Both are pure and allocation-free; the caller passes the sample count and
   a seed, so they are deterministic and thread-safe (if the callback is).
   Details and measured behaviour: docs/rounded_edges.md, "Bevel baselines". */

/* One hit reported by the host's tracer. */
typedef struct re_trace_hit_t {
    double t;         /* ray parameter of the hit, in units of the ray's dir */
    double normal[3]; /* unit geometric normal pointing OUT of the solid (the
                         triangle's right-hand normal), not flipped toward the ray */
    unsigned object;  /* host object id of the hit primitive */
} re_trace_hit_t;

/* Host ray cast: the nearest hit with tmin < t < tmax along origin + t*dir.
   Returns nonzero and fills *hit when there is one, 0 otherwise. It must be
   safe to call from several threads at once if the baselines are. */
typedef int (*re_trace_fn)(void *user, const double origin[3], const double dir[3],
                           double tmin, double tmax, re_trace_hit_t *hit);

/* The bevel shader of the OSL blog post (bevel_shader_osl_blog.txt): from the
   point P - delta*N below the surface, cast rays along N + perturb*d, d in the
   tangent disk, and average N with the normals they hit. */
typedef struct re_bevel_blog_desc_t {
    double delta;   /* depth of the probe origin below P along -N, scene units.
                       Required, > 0 (the blog's Delta). */
    double perturb; /* tangent of the probe cone's half angle (the blog's Perturb),
                       > 0. Default (0): 1, which gives a blend band of width
                       about delta on each face of a right-angle edge, i.e. the
                       width of a rounding of radius delta. */
    int rays;       /* probe rays, >= 1. Default (0): 27, the blog's Divisions = 3. */
    unsigned seed;  /* rotates the direction set; every value is valid */
} re_bevel_blog_desc_t;

/* A Cycles-style bevel (Blender's Bevel node): points on the surface of the
   same object within a sphere of radius R around P are found by rays across
   that sphere, through disks sampled with the cubic falloff along one of
   three axes, and their normals are averaged with Cycles' weights (cubic
   falloff of the distance to P, power-heuristic MIS over the three axes). */
typedef struct re_bevel_cycles_desc_t {
    double radius; /* R, scene units. Required, > 0. */
    int samples;   /* disk samples, >= 1. Default (0): 4, Cycles' default. */
    unsigned seed; /* rotates the sample set; every value is valid */
} re_bevel_cycles_desc_t;

typedef struct re_bevel_result_t {
    double normal[3]; /* unit shading normal; N itself when no probe found a surface */
    int rays;         /* calls made to the trace callback */
    int hits;         /* hits that contributed to the average */
} re_bevel_result_t;

/* Most hits on the same object taken along one Cycles-style probe segment
   (Cycles keeps a random subset of 4; a closed mesh gives at most 2 within a
   sphere smaller than its features, so we keep the first 8 in ray order). */
#define RE_BEVEL_MAX_HITS 8
/* After a hit, the next one along a Cycles-style probe is searched from
   t + RE_BEVEL_STEP_REL * R: far above float tracers' self-intersection
   error for R down to 1e-3 of the object, and small enough that two distinct
   surfaces closer than it along one probe count once. */
#define RE_BEVEL_STEP_REL 1e-4

/* Blog bevel at P (on the surface) with unit outward normal n. Returns
   RE_ERR_INVALID_ARG for NULL pointers, a non-finite or non-positive delta or
   perturb, or rays < 0 (out is then untouched). */
RE_DEF re_result_t re_bevel_blog(const re_bevel_blog_desc_t *desc, const double p[3],
                                 const double n[3], re_trace_fn trace, void *user,
                                 re_bevel_result_t *out);
/* Cycles-style bevel at P (on object `object`) with unit outward normal n.
   Hits on other objects are skipped. RE_ERR_INVALID_ARG as above. */
RE_DEF re_result_t re_bevel_cycles(const re_bevel_cycles_desc_t *desc, const double p[3],
                                   const double n[3], unsigned object, re_trace_fn trace,
                                   void *user, re_bevel_result_t *out);
/* ==== [end section: baselines] ==== */

#ifdef __cplusplus
}
#endif

#endif /* FILIGREE_RE_H */

/* ======================================================================== */
/*                              IMPLEMENTATION                              */
/* ======================================================================== */
#ifdef RE_IMPLEMENTATION
#ifndef FILIGREE_RE_IMPLEMENTATION_DONE
#define FILIGREE_RE_IMPLEMENTATION_DONE

#ifndef RE_ASSERT
#  include <assert.h>
#  define RE_ASSERT(c) assert(c)
#endif
#if defined(RE_MALLOC) != defined(RE_FREE)
#  error "define both RE_MALLOC and RE_FREE, or neither"
#endif
#ifndef RE_MALLOC
#  include <stdlib.h>
#  define RE_MALLOC(sz, ctx) ((void)(ctx), malloc(sz))
#  define RE_FREE(p, ctx) ((void)(ctx), free(p))
#endif

#ifdef __cplusplus
extern "C" {
#endif

RE_DEF const char *re_result_string(re_result_t r)
{
    switch (r) {
    case RE_OK: return "ok";
    case RE_ERR_INVALID_ARG: return "invalid argument";
    case RE_ERR_OUT_OF_MEMORY: return "out of memory";
    case RE_ERR_NAN_VERTEX: return "vertex with a NaN or infinite coordinate";
    case RE_ERR_INDEX_OUT_OF_RANGE: return "vertex index out of range";
    case RE_ERR_BAD_FACE: return "bad polygon size";
    case RE_ERR_DEGENERATE_TRIANGLE: return "degenerate (zero-area) triangle";
    case RE_ERR_INCONSISTENT_WINDING: return "inconsistent triangle winding";
    case RE_ERR_BAD_RADIUS: return "radius not finite or not positive";
    case RE_ERR_RADIUS_TOO_LARGE: return "radius too large for the geometry";
    case RE_ERR_BUFFER_TOO_SMALL: return "buffer smaller than re_build_sizes() asked";
    case RE_ERR_TOO_LARGE: return "mesh too large for 32-bit ids";
    case RE_RESULT_COUNT_: break;
    }
    return "unknown result";
}

/* ==== [section: baselines] (owned by the baselines/example helper) ==== */
/* ---- Bevel-shader baselines: implementation ---------------------------- */

#define RE__BV_PI 3.14159265358979323846
/* The golden angle pi(3 - sqrt 5): successive spiral points never line up. */
#define RE__BV_GOLDEN_ANGLE 2.39996322972865332223
/* Convergence of the cubic-falloff radius solve, on the dimensionless x = r/R. */
#define RE__BV_ROOT_EPS 1e-13

static double re__bv_dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* Unit a into out; returns 0 (out untouched) when a is zero or not finite. */
static int re__bv_unit(const double a[3], double out[3])
{
    double len = sqrt(re__bv_dot(a, a));
    if (!(len > 0) || !(len < HUGE_VAL)) return 0;
    out[0] = a[0] / len; out[1] = a[1] / len; out[2] = a[2] / len;
    return 1;
}

/* Orthonormal t, b completing unit n (Duff et al. 2017, "Building an
   orthonormal basis, revisited"): branch-free apart from the sign, exact for
   axis-aligned n, so probes on a box face run along its edges. */
static void re__bv_frame(const double n[3], double t[3], double b[3])
{
    double s = n[2] >= 0 ? 1.0 : -1.0;
    double a = -1.0 / (s + n[2]);
    double c = n[0] * n[1] * a;
    t[0] = 1.0 + s * n[0] * n[0] * a; t[1] = s * c; t[2] = -s * n[0];
    b[0] = c; b[1] = s + n[1] * n[1] * a; b[2] = -n[1];
}

/* Seed -> uniform [0,1): splitmix64 finaliser, so nearby seeds decorrelate. */
static double re__bv_seed_unit(unsigned seed, unsigned long long stream)
{
    unsigned long long z = (unsigned long long)seed * 0x9E3779B97F4A7C15ull + stream;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) * (1.0 / 9007199254740992.0);
}

/* Van der Corput radical inverse in base 2 (the Hammersley second coordinate). */
static double re__bv_radical_inverse(unsigned i)
{
    unsigned long long v = i & 0xFFFFFFFFull, r = 0;
    int k;
    for (k = 0; k < 32; k++) { r = (r << 1) | (v & 1u); v >>= 1; }
    return (double)r * (1.0 / 4294967296.0);
}

static double re__bv_frac(double x) { return x - floor(x); }

static int re__bv_check_common(const double p[3], const double n[3], re_trace_fn trace,
                               const void *desc, const re_bevel_result_t *out)
{
    int k;
    if (!desc || !p || !n || !trace || !out) return 0;
    for (k = 0; k < 3; k++)
        if (!(p[k] - p[k] == 0) || !(n[k] - n[k] == 0)) return 0; /* NaN or Inf */
    return re__bv_dot(n, n) > 0;
}

RE_DEF re_result_t re_bevel_blog(const re_bevel_blog_desc_t *desc, const double p[3],
                                 const double n[3], re_trace_fn trace, void *user,
                                 re_bevel_result_t *out)
{
    double nu[3], t[3], b[3], o[3], sum[3], perturb, phi0;
    int rays, i, k, hits = 0;
    if (!re__bv_check_common(p, n, trace, desc, out)) return RE_ERR_INVALID_ARG;
    perturb = desc->perturb == 0 ? 1.0 : desc->perturb;
    rays = desc->rays == 0 ? 27 : desc->rays;
    if (!(desc->delta > 0) || !(desc->delta < HUGE_VAL) || !(perturb > 0) || !(perturb < HUGE_VAL)
        || rays < 1)
        return RE_ERR_INVALID_ARG;
    if (!re__bv_unit(n, nu)) return RE_ERR_INVALID_ARG;
    re__bv_frame(nu, t, b);
    /* Blog, line 10: the probe origin lies delta below P along -N. */
    for (k = 0; k < 3; k++) { o[k] = p[k] - desc->delta * nu[k]; sum[k] = nu[k]; }
    /* The blog perturbs N by Perlin noise, which it calls "rather awful" for
       its uneven spread. We use a Vogel (golden-angle) spiral instead: the
       i-th offset lies at radius sqrt((i + 1/2)/rays) of the unit tangent
       disk, so the directions cover the cone N + perturb*disk with uniform
       density for any ray count; the seed rotates the spiral. */
    phi0 = 2.0 * RE__BV_PI * re__bv_seed_unit(desc->seed, 1);
    for (i = 0; i < rays; i++) {
        double rho = perturb * sqrt(((double)i + 0.5) / (double)rays);
        double phi = phi0 + RE__BV_GOLDEN_ANGLE * (double)i;
        double cp = rho * cos(phi), sp = rho * sin(phi), d[3], s;
        re_trace_hit_t h;
        for (k = 0; k < 3; k++) d[k] = nu[k] + cp * t[k] + sp * b[k];
        if (!trace(user, o, d, 0.0, HUGE_VAL, &h)) continue;
        /* The blog subtracts OSL's N at the hit, which faces the probe ray;
           adding the hit normal turned along the probe is the same, whatever
           side the host's normal points to. */
        s = re__bv_dot(h.normal, d) >= 0 ? 1.0 : -1.0;
        for (k = 0; k < 3; k++) sum[k] += s * h.normal[k];
        hits++;
    }
    /* The blog divides by the count, then normalises: the division does not
       change the direction, so we only normalise. */
    if (!re__bv_unit(sum, out->normal))
        for (k = 0; k < 3; k++) out->normal[k] = nu[k];
    out->rays = rays;
    out->hits = hits;
    return RE_OK;
}

/* Cubic falloff (R - r)^3 up to its normalisation 10/(pi R^5), which cancels
   in the ratio Cycles takes (svm_bevel: bssrdf_cubic_pdf(r) / pdf(disk_r)). */
static double re__bv_cubic(double radius, double r)
{
    double f = radius - r;
    return r < radius ? f * f * f : 0.0;
}

/* Disk radius x = r/R with the cubic falloff's CDF equal to u:
   10x^2 - 20x^3 + 15x^4 - 4x^5 = u (the integral of 2 pi r (R - r)^3,
   normalised). No closed form; safeguarded Newton (the derivative is
   20x(1-x)^3), as Cycles solves it with Newton-Raphson. */
static double re__bv_cubic_radius(double u)
{
    double lo = 0.0, hi = 1.0, x = sqrt(u / 10.0);
    int it;
    if (x >= 1.0) x = 0.5;
    for (it = 0; it < 100; it++) {
        double x2 = x * x;
        double g = x2 * (10.0 + x * (-20.0 + x * (15.0 - 4.0 * x))) - u;
        double om = 1.0 - x, dg = 20.0 * x * om * om * om, xn;
        if (g < 0) lo = x; else hi = x;
        xn = dg > 0 ? x - g / dg : 0.5 * (lo + hi);
        if (!(xn > lo && xn < hi)) xn = 0.5 * (lo + hi);
        if (fabs(xn - x) <= RE__BV_ROOT_EPS) { x = xn; break; }
        x = xn;
    }
    return x;
}

RE_DEF re_result_t re_bevel_cycles(const re_bevel_cycles_desc_t *desc, const double p[3],
                                   const double n[3], unsigned object, re_trace_fn trace,
                                   void *user, re_bevel_result_t *out)
{
    /* pick probabilities of the three disk axes (N, T, B), as Cycles */
    static const double pick[3] = {0.5, 0.25, 0.25};
    double axes[3][3], sum[3] = {0, 0, 0}, R, step, off_u, off_v;
    int samples, i, k, calls = 0, hits = 0;
    if (!re__bv_check_common(p, n, trace, desc, out)) return RE_ERR_INVALID_ARG;
    R = desc->radius;
    samples = desc->samples == 0 ? 4 : desc->samples;
    if (!(R > 0) || !(R < HUGE_VAL) || samples < 1) return RE_ERR_INVALID_ARG;
    if (!re__bv_unit(n, axes[0])) return RE_ERR_INVALID_ARG;
    re__bv_frame(axes[0], axes[1], axes[2]);
    step = RE_BEVEL_STEP_REL * R;
    /* Hammersley points (i + 1/2)/n, radical inverse of i, shifted by a
       seeded Cranley-Patterson rotation: stratified, and unbiased over seeds. */
    off_u = re__bv_seed_unit(desc->seed, 2);
    off_v = re__bv_seed_unit(desc->seed, 3);
    for (i = 0; i < samples; i++) {
        double u = re__bv_frac(((double)i + 0.5) / (double)samples + off_u);
        double v = re__bv_frac(re__bv_radical_inverse((unsigned)i) + off_v);
        const double *dn, *dt, *db;
        double rd, h, phi, o[3], d[3], tmin, pdf_disk;
        int a, nh;
        /* Axis choice: N with probability 1/2, T and B with 1/4 each; u is
           reused for the azimuth after rescaling, as in Cycles. */
        if (u < 0.5) { a = 0; u *= 2.0; }
        else if (u < 0.75) { a = 1; u = (u - 0.5) * 4.0; }
        else { a = 2; u = (u - 0.75) * 4.0; }
        dn = axes[a]; dt = axes[(a + 1) % 3]; db = axes[(a + 2) % 3];
        rd = re__bv_cubic_radius(v) * R;
        if (!(rd < R)) continue; /* u at the top of [0,1): zero-weight sample */
        /* The probe crosses the whole sphere: it starts at height h above the
           disk point and runs 2h along -axis. */
        h = sqrt(R * R - rd * rd);
        phi = 2.0 * RE__BV_PI * u;
        for (k = 0; k < 3; k++) {
            o[k] = p[k] + h * dn[k] + rd * (cos(phi) * dt[k] + sin(phi) * db[k]);
            d[k] = -dn[k];
        }
        pdf_disk = re__bv_cubic(R, rd);
        tmin = 0.0;
        for (nh = 0; nh < RE_BEVEL_MAX_HITS; nh++) {
            re_trace_hit_t hit;
            double pdf[3], hp[3], dist, w;
            calls++;
            if (!trace(user, o, d, tmin, 2.0 * h, &hit)) break;
            tmin = hit.t + step;
            if (hit.object != object) continue; /* same object only, as Cycles' local BVH query */
            for (k = 0; k < 3; k++) {
                pdf[k] = pick[k] * fabs(re__bv_dot(axes[k], hit.normal));
                hp[k] = o[k] + hit.t * d[k] - p[k];
            }
            /* Power-heuristic MIS over the three axes; the disk densities are
               left out of pdf[] and corrected by the falloff ratio below:
               summed over the axes, the estimator is unbiased for the
               falloff-weighted integral of n over the surface in the sphere. */
            w = pdf[a] / (pdf[0] * pdf[0] + pdf[1] * pdf[1] + pdf[2] * pdf[2]);
            if (!(w > 0) || !(w < HUGE_VAL)) continue;
            dist = sqrt(re__bv_dot(hp, hp));
            w *= re__bv_cubic(R, dist) / pdf_disk;
            for (k = 0; k < 3; k++) sum[k] += w * hit.normal[k];
            hits++;
        }
    }
    if (!re__bv_unit(sum, out->normal))
        for (k = 0; k < 3; k++) out->normal[k] = axes[0][k];
    out->rays = calls;
    out->hits = hits;
    return RE_OK;
}
/* ==== [end section: baselines] ==== */

#ifdef __cplusplus
}
#endif

#endif /* FILIGREE_RE_IMPLEMENTATION_DONE */
#endif /* RE_IMPLEMENTATION */

/*
MIT License

Copyright (c) 2026 the filigree authors

Permission is hereby granted, free of charge, to any person obtaining a copy of
this software and associated documentation files (the "Software"), to deal in
the Software without restriction, including without limitation the rights to
use, copy, modify, merge, publish, distribute, sublicense, and/or sell copies
of the Software, and to permit persons to whom the Software is furnished to do
so, subject to the following conditions:

The above copyright notice and this permission notice shall be included in all
copies or substantial portions of the Software.

THE SOFTWARE IS PROVIDED "AS IS", WITHOUT WARRANTY OF ANY KIND, EXPRESS OR
IMPLIED, INCLUDING BUT NOT LIMITED TO THE WARRANTIES OF MERCHANTABILITY,
FITNESS FOR A PARTICULAR PURPOSE AND NONINFRINGEMENT. IN NO EVENT SHALL THE
AUTHORS OR COPYRIGHT HOLDERS BE LIABLE FOR ANY CLAIM, DAMAGES OR OTHER
LIABILITY, WHETHER IN AN ACTION OF CONTRACT, TORT OR OTHERWISE, ARISING FROM,
OUT OF OR IN CONNECTION WITH THE SOFTWARE OR THE USE OR OTHER DEALINGS IN THE
SOFTWARE.
*/
