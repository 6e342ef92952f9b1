/* rounded_edges.h — rounded corners and edges for triangle meshes (part of filigree)

   Rounding cylinders and spheres inside the convex edges and corners of a
   triangle mesh, found from a hit on the sharp mesh (Courtin et al. 2019).

   The rounded solid is exact: near a convex corner it is the erosion of the
   mesh by r followed by a dilation by r, so where k >= 4 face planes meet
   (and their offsets miss one common point) the corner gets the spheres and
   short extra cylinders of the local eroded polytope, not one cracked sphere.
   Concave edges, open boundaries and mixed vertices stay sharp and are
   reported. Solids that touch at a shared vertex or edge (voxel art,
   welded parts) are rounded each on its own. Details, limits and
   measurements: docs/rounded_edges.md.

   INTEGRATION WITH A HOST RAY TRACER
     1. Build once: fill re_mesh_t per object (the same vertices/triangles the
        host traces), re_build() (or re_build_sizes() + re_build_into()).
     2. Per ray: the host traces its sharp mesh. On a front-face hit of object
        k, triangle f at t, call re_query(scene, o, dir, k, f, t, &h), or
        re_query_uv(..., t, u, v, &h) with the hit's barycentrics (Embree's
        hit.u, hit.v), which answers a hit on a face's flat part at once:
          RE_UNCHANGED     shade the host hit as usual;
          RE_HIT_ROUNDED   shade h.point with h.normal (h.t replaces t);
          RE_PASS_THROUGH  the ray grazes the removed edge volume and leaves
                           the sharp mesh at h.t: trace again from h.t,
                           skipping hits of object k at t <= h.t (the exit
                           face itself), and query again on the next hit.
     3. Secondary rays from a rounded hit start at re_secondary_origin()
        (paper §4, I''), on the sharp mesh, so the host's geometry does not
        shadow the rounded point.
     4. Rays from inside (refraction): a back-face hit goes to
        re_query_exit() / re_query_exit_uv(), which say where the ray
        leaves the rounded solid (or that it runs outside it there).
   INSTANCES: build one object per prototype mesh and query in its space:
   map the ray there with the instance's inverse (o' = A^-1 (o - T),
   d' = A^-1 d, in double; t is unchanged) and map the answer back
   (point A p + T, normal A^-T n normalised; re_secondary_origin() in the
   prototype's space too). Radii are in the prototype's units: a
   non-uniform scale stretches the rounding with the mesh.

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
     RE_NO_HUGEPAGES    do not ask for huge pages (below)
     RE_NO_BANDS        no per-triangle bands: re_query_uv() then answers as
                        re_query() does, through the kd-tree on every hit; the
                        build skips their step and the scene their 4 bytes per
                        triangle (for hosts that only call re_query())
     RE_NO_BASELINES    leave out the bevel-shader baselines (re_bevel_blog,
                        re_bevel_cycles and their types)
     RE_NO_COMPACT      leave out RE_LAYOUT_COMPACT (re_build() then rejects
                        it): the query loses its layout tests
     RE_SET_CAP         most corners one query holds (default 1024; 12 bytes
                        each on the query's stack, touched only as far as
                        the query uses them; at least 16). A query that had
                        to drop a corner says so:
                        re_hit_t.flags gets RE_HIT_INCOMPLETE. Only finely
                        tessellated faces under large radii come near it
                        (docs/rounded_edges.md, Limits)
   MEMORY
     re_build() and re_build_sizes() allocate their scratch and scene blocks
     with RE_MALLOC. On Linux, with the default allocator, they ask the
     kernel (madvise MADV_HUGEPAGE) to back the 2 MiB-aligned inside of each
     block of 4 MiB or more with transparent huge pages: the fresh pages a
     build touches (several hundred bytes per triangle) then cost one fault per
     2 MiB, not one per 4 KiB. Nothing else changes; the kernel may decline.
     With RE_NO_HUGEPAGES, a user RE_MALLOC, or re_build_into() the memory
     is left as it comes.
   THREADS
     Queries are const and thread-safe. A build runs on the calling thread
     unless desc.parallel is set with desc.threads >= 2: re_build() and
     re_build_sizes() then hand the objects to that many tasks (largest
     first, each to the task with the fewest triangles so far) and the host
     runs them on its threads; many objects gain up to the thread count. A
     scene of one object splits that object's three longest steps instead
     (its corners, their radius bounds and the kd-tree's two halves, a
     third to a half of its build) into up to `threads` tasks each, run by
     the host one step after another (the benchmark's icospheres, 102k
     triangles, build 1.1-1.3x faster on two threads, its blocks
     1.1-1.2x); those steps take up to 64 bytes per rounded edge more
     memory for the kd-tree's second half, and a mark per face plane per
     task. The scene is the same, byte for byte, as built on one thread.
     Then:
     RE_MALLOC/RE_FREE and desc.report are called from the host's threads,
     at the same time (they must be thread-safe; the reports of different
     objects interleave, each object's own come in order); every task holds
     its own scratch (peak memory up to `threads` objects' scratch); a
     failure reports the lowest-numbered failing object, as on one thread,
     though later objects may have been built (and reported) before the
     build returns. re_build_into() always runs on the calling thread.
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
    RE_ERR_BAD_SCALE,            /* an object's size outside [RE_SIZE_MIN, RE_SIZE_MAX] */
    RE_RESULT_COUNT_
} re_result_t;

/* The object sizes (diagonals of the used vertices' box) the build takes;
   outside them it fails with RE_ERR_BAD_SCALE naming the size. Above
   about 3e39 the detection radii, walk reaches and kd splits, stored as
   float and bfloat16, overflow (the build succeeded and every rounded hit
   came back unchanged); from 1e78 the face normals' squared lengths
   overflow and every edge read as concave; below about 1e-79 the squared
   cross products are subnormal and hits moved by 2e-5 of the size. The
   margins are three orders of magnitude above, nineteen below. */
#define RE_SIZE_MAX 1e36
#define RE_SIZE_MIN 1e-60

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
    size_t position_stride;     /* bytes from one vertex to the next; 0 = packed.
                                   Any count: positions are read by memcpy, so
                                   neither they nor the stride need alignment */
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
                                   smaller wins). A value <= 0, NaN or
                                   infinite falls back to `radius` (with none:
                                   RE_ERR_BAD_RADIUS naming a vertex of the
                                   edge). Corners join cylinders C1 only with
                                   one radius, so every rounded patch (edges
                                   linked through rounded corners) takes the
                                   smallest radius asked along it (reported). */
    int weld;                   /* 0 (default): vertices are matched by index.
                                   1: vertices at the same position (exactly,
                                   after conversion to double; -0 = +0) are one
                                   for the build, so a mesh split at every
                                   face for its normals or UVs (a game asset's
                                   24-vertex cube) rounds as if welded. Costs
                                   3-5 ints per vertex (a map and a hash
                                   table) during step 1 of the build; nothing
                                   in the scene. Triangle
                                   ids, and what the host traces, do not
                                   change. Reports name the first vertex at
                                   a position. Solids that then share a
                                   vertex or an edge round each on its own
                                   (docs: construction, step 2a). */
    double flat_sin;            /* 0 (default): automatic. Else the sine of the
                                   angle between two faces' normals at or below
                                   which their edge is flat (the faces are one
                                   plane, like a quad's diagonal), in
                                   (0, RE_FLAT_SIN_LIMIT]; it raises the
                                   automatic value, never lowers it (an angle
                                   within the positions' rounding is noise,
                                   not a crease).
                                   Automatic is the positions' own rounding: a
                                   few units in the last place of the float or
                                   double coordinates over the triangles'
                                   heights, at most RE_FLAT_SIN_LIMIT. Faces
                                   this joins into a curved group take 1e-9
                                   instead (construction step 2b). Set it for
                                   doubles that carry coarser rounding (a
                                   turned box read
                                   from an OBJ file with 6 decimals tilts its
                                   quads' halves by up to 2e-6: 1e-5 joins
                                   them; docs/rounded_edges.md, construction
                                   step 2). */
} re_mesh_t;

/* The largest re_mesh_t.flat_sin accepted (0.57 degrees): above it, faces
   joined into one plane would be creases and the rounding would be tangent
   to a plane the mesh does not have. */
#define RE_FLAT_SIN_LIMIT 1e-2

typedef enum re_radius_policy_t {
    RE_RADIUS_CLAMP = 0, /* default: lower a too-large radius to the largest
                            valid one for its patch, report it */
    RE_RADIUS_REJECT     /* fail with RE_ERR_RADIUS_TOO_LARGE naming the element */
} re_radius_policy_t;

typedef enum re_bad_input_t {
    RE_BAD_INPUT_REJECT = 0, /* default: fail on the first bad triangle */
    RE_BAD_INPUT_SKIP        /* skip it (its edges become boundary: sharp), report
                                it; an inconsistently wound edge stays sharp */
} re_bad_input_t;

/* What a report is about. Reports are informational (the build succeeded). */
typedef enum re_report_kind_t {
    RE_REPORT_CONCAVE_EDGE = 0,  /* left sharp (issue item 4) */
    RE_REPORT_BOUNDARY_EDGE,     /* open mesh: left sharp */
    RE_REPORT_NONMANIFOLD_EDGE,  /* more than two triangles: left sharp */
    RE_REPORT_MIXED_VERTEX,      /* convex and concave/boundary edges meet: the
                                    vertex and its edges stay sharp */
    RE_REPORT_SHARP_PATCH_EDGE,  /* convex edge left sharp because a corner of
                                    its patch is mixed, complex or
                                    unroundable (see docs: limits) */
    RE_REPORT_RADIUS_CLAMPED,    /* value = new radius; element: the edge
                                    (both vertices) or the vertex (element2
                                    -1) that limits it, or a triangle of
                                    the same object in the rounding's way
                                    (element2 -2) */
    RE_REPORT_RADIUS_MISMATCH,   /* unequal edge radii met at a corner; value = radius kept */
    RE_REPORT_SKIPPED_TRIANGLE,  /* RE_BAD_INPUT_SKIP dropped this triangle */
    RE_REPORT_COMPLEX_CORNER,    /* more than RE_MAX_CORNER_PLANES face planes
                                    meet: the vertex and its patch stay
                                    sharp */
    RE_REPORT_UNROUNDABLE_CORNER /* a corner within the plane limit whose fan
                                    or eroded corner could not be built (a
                                    face plane recurs around it, or plane
                                    triples too ill-conditioned to resolve);
                                    value = its plane count; stays sharp */
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
    const char *message; /* "edge 4-7 is concave: left sharp" (valid during the call) */
} re_report_t;

typedef void (*re_report_fn)(void *user, const re_report_t *report);

/* Memory against query time (docs/rounded_edges.md, "Storage"). The answers
   agree to about 1e-9 r either way. */
typedef enum re_layout_t {
    RE_LAYOUT_FAST = 0, /* default: sphere centres stored as doubles, the
                           kd-tree split for query time */
    RE_LAYOUT_COMPACT   /* sphere centres solved at query time from three face
                           planes (24 bytes less per sphere), one-byte
                           detection radii, 16-bit sphere distances, a
                           shallower kd-tree; 54-64 instead of 73-96 bytes
                           per rounded edge on the benchmark scenes, 1.1-1.5x
                           the instructions of re_query */
} re_layout_t;

/* Building objects on the host's threads (THREADS at the top). The host
   calls task(task_ctx, i) once for every i in [0, count), on its own
   threads, in any order and at the same time if it likes, and returns when
   every call has returned: a thread pool's parallel-for. A task it skips
   fails the build (RE_ERR_INVALID_ARG names it). */
typedef void (*re_task_fn)(void *task_ctx, unsigned i);
typedef void (*re_parallel_fn)(void *user, unsigned count, re_task_fn task, void *task_ctx);

/* Tasks a build is split into, at most. */
#define RE_MAX_BUILD_TASKS 64

typedef struct re_scene_desc_t {
    const re_mesh_t *objects;
    unsigned object_count;
    re_radius_policy_t radius_policy; /* default RE_RADIUS_CLAMP */
    re_bad_input_t bad_input;         /* default RE_BAD_INPUT_REJECT */
    re_report_fn report;              /* optional, called during the build */
    void *report_user;
    void *alloc_ctx;                  /* passed to RE_MALLOC/RE_FREE */
    re_layout_t layout;               /* default RE_LAYOUT_FAST */
    re_parallel_fn parallel;          /* optional: re_build() and
                                         re_build_sizes() split the objects
                                         into `threads` tasks run by it (one
                                         object: its longest steps); NULL:
                                         all on the calling thread */
    void *parallel_user;              /* passed to parallel */
    unsigned threads;                 /* tasks (the host's threads); 0 or 1:
                                         the calling thread; more than the
                                         objects or RE_MAX_BUILD_TASKS count
                                         as that many */
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
    unsigned long long rounded_corners;    /* mesh vertices with a rounded corner, once per
                                              solid where solids touch (a vertex inside a
                                              straight chain, on its cylinder, has none: see
                                              re_cylinder_t) */
    unsigned long long mixed_vertices;
    unsigned long long spheres, cylinders; /* cylinders include the extra ones */
    unsigned long long extra_cylinders;    /* exact-corner cylinders (degree >= 4) */
    unsigned long long clamped;            /* patches whose radius was lowered */
    unsigned long long kd_nodes;
    unsigned long long kd_leaves;          /* leaves of the detection kd-trees */
    unsigned long long kd_leaf_refs;       /* edge references held by the leaves (an
                                              edge whose detection box straddles a
                                              split is held by both sides) */
    size_t bytes;                          /* whole scene, header included: every
                                              array a query reads (docs/rounded_edges.md,
                                              "Memory"). Bytes per rounded edge =
                                              bytes / rounded_edges */
} re_stats_t;

typedef struct re_scene_t re_scene_t; /* opaque; lives in one block */

/* Exact sizes for re_build_into(). Runs the analysis once, in working
   memory taken from RE_MALLOC (desc->alloc_ctx) and freed before returning,
   all but the per-triangle bands (their size is fixed; their working memory
   is counted): it costs about 0.7-0.85 of a build. On the host's threads
   with desc.parallel (THREADS). */
RE_DEF re_result_t re_build_sizes(const re_scene_desc_t *desc, re_sizes_t *sizes,
                                  re_diag_t *diag);
/* Build into caller buffers (sizes from re_build_sizes(); `scene_mem` and
   `scratch` aligned to 16 bytes, as malloc gives them: RE_ERR_INVALID_ARG
   otherwise). *scene points into scene_mem; nothing to free. Runs on the
   calling thread (desc.parallel is not used). */
RE_DEF re_result_t re_build_into(const re_scene_desc_t *desc, void *scene_mem,
                                 size_t scene_bytes, void *scratch, size_t scratch_bytes,
                                 re_scene_t **scene, re_diag_t *diag);
/* Build with RE_MALLOC (desc->alloc_ctx); release with re_free(). On the
   host's threads with desc.parallel (THREADS). */
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
    double normal[3];      /* unit, outward: the rounded surface's for
                              RE_HIT_ROUNDED, the exit face's for
                              RE_PASS_THROUGH, the hit face's for RE_UNCHANGED
                              on a face of a rounded patch; zero otherwise
                              (use the host's own normal) */
    re_feature_t feature;
    unsigned feature_index;
    unsigned object;
    unsigned flags;        /* RE_HIT_INCOMPLETE or 0 */
} re_hit_t;

/* re_hit_t.flags: the query met more corners than it holds (RE_SET_CAP)
   and dropped some, so the answer can be sharp or off where a dropped
   corner's rounding was the nearest. Never set on the benchmark scenes;
   see docs/rounded_edges.md, Limits. */
#define RE_HIT_INCOMPLETE 1u

/* The host found `dir`-ray (o + t*dir) hits `triangle` of `object` at t_host,
   from outside. Returns out->kind (also the return value). Pure, const,
   allocation-free, thread-safe. Bad ids or non-finite rays give RE_UNCHANGED. */
RE_DEF re_hit_kind_t re_query(const re_scene_t *scene, const double o[3],
                              const double dir[3], unsigned object, unsigned triangle,
                              double t_host, re_hit_t *out);

/* re_query() for a host that knows the barycentric coordinates of its hit:
   point = (1-u-v) p0 + u p1 + v p2, with p0, p1, p2 the triangle's corners
   in index order (Embree's hit.u, hit.v). Same answers; a hit on the flat
   part of its face, away from every rounding, is recognised from (u, v)
   and three per-triangle bands (query step 0, docs/rounded_edges.md) and
   returns RE_UNCHANGED at once, without the kd-tree. u, v may carry a
   float tracer's error (RE__BAND_MARGIN). */
RE_DEF re_hit_kind_t re_query_uv(const re_scene_t *scene, const double o[3],
                                 const double dir[3], unsigned object, unsigned triangle,
                                 double t_host, double u, double v, re_hit_t *out);

/* Rays from inside (refraction: a ray that entered the rounded solid and
   now leaves it). The host found the ray leaving the sharp mesh through
   `triangle` of `object` at t_host (a back-face hit, dir . normal > 0). The
   query asks the ray reversed at that face, which enters there:
     RE_UNCHANGED     the ray leaves through the flat face at t_host (normal:
                      the face's, outward; zero if the face has no rounding);
     RE_HIT_ROUNDED   it leaves through the rounding earlier, at h.t in
                      [0, t_host] (a float host's late t_host may put it
                      just beyond, as in re_query): h.point, outward
                      h.normal, feature;
     RE_PASS_THROUGH  near this face the ray runs outside the rounded solid
                      (its origin lies in the removed volume, not inside it):
                      h.t = t_host, trace on past the face, skipping it.
   The answer is the last crossing of the rounded surface before the face,
   so it is the exit when the origin lies inside the rounded solid. From an
   origin in the removed volume, RE_UNCHANGED and RE_HIT_ROUNDED say that
   the segment meets the rounded solid and where it leaves it, not where it
   enters it: an occlusion answer. Pure, const, allocation-free,
   thread-safe. */
RE_DEF re_hit_kind_t re_query_exit(const re_scene_t *scene, const double o[3],
                                   const double dir[3], unsigned object, unsigned triangle,
                                   double t_host, re_hit_t *out);
/* re_query_exit() with the back-face hit's barycentrics (as re_query_uv). */
RE_DEF re_hit_kind_t re_query_exit_uv(const re_scene_t *scene, const double o[3],
                                      const double dir[3], unsigned object, unsigned triangle,
                                      double t_host, double u, double v, re_hit_t *out);

/* Origin on the sharp mesh (I'' of paper §4) for a secondary ray leaving a
   RE_HIT_ROUNDED hit along `dir` (dir . hit->normal > 0): where that ray
   leaves the sharp mesh (among the planes of the hit feature's corners and
   of the corners the query's walk reaches along the ray; the rounded patch
   is convex), pushed out along the crossed face's normal by
   RE_ORIGIN_OFFSET_REL times the object's size so the host's own
   self-intersection guard is not needed. A ray that leaves through a face
   the hit lies on (a seam), or runs along it within rounding, starts at
   the hit itself, moved down onto that face if above it. For other kinds:
   hit->point pushed out the same way. A dir into the solid (dir .
   hit->normal < 0 by more than rounding, 8 ulps of |dir|; e.g. refraction)
   gets hit->point itself: the exit walk assumes a ray leaving the rounded
   surface (it gave points up to 66 sizes away). A tangent dir (dir .
   hit->normal = 0) leaves. */
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
    unsigned vertex; /* mesh vertex of the corner it belongs to (where solids
                        touch at a vertex, each solid's corner names it) */
} re_sphere_t;

typedef struct re_cylinder_t {
    double a[3], b[3];   /* axis end points = centres of spheres sa, sb */
    double radius;
    double n0[3], n1[3]; /* unit normals of the two faces it joins */
    unsigned sa, sb;     /* sphere indices */
    long long edge_v0, edge_v1; /* the mesh edge, or -1 for an extra cylinder.
                                   A straight edge split by vertices where only
                                   its two faces meet is one cylinder: each of
                                   its segments gives that whole cylinder, with
                                   the chain's end vertices here, and the
                                   vertices inside the chain have no sphere */
} re_cylinder_t;

RE_DEF unsigned re_object_count(const re_scene_t *scene);
RE_DEF unsigned re_sphere_count(const re_scene_t *scene, unsigned object);
RE_DEF unsigned re_cylinder_count(const re_scene_t *scene, unsigned object);
/* Return 0 (and leave *out untouched) for an out-of-range index. */
RE_DEF int re_get_sphere(const re_scene_t *scene, unsigned object, unsigned i,
                         re_sphere_t *out);
RE_DEF int re_get_cylinder(const re_scene_t *scene, unsigned object, unsigned i,
                           re_cylinder_t *out);

/* Small vector helpers, inline because the query calls them per candidate. */
static inline double re__dot(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
static inline void re__sub(const double a[3], const double b[3], double out[3])
{
    out[0] = a[0] - b[0];
    out[1] = a[1] - b[1];
    out[2] = a[2] - b[2];
}
static inline void re__cross(const double a[3], const double b[3], double out[3])
{
    double x = a[1] * b[2] - a[2] * b[1], y = a[2] * b[0] - a[0] * b[2],
           z = a[0] * b[1] - a[1] * b[0];
    out[0] = x;
    out[1] = y;
    out[2] = z;
}
/* out = a + s*b */
static inline void re__madd(const double a[3], double s, const double b[3], double out[3])
{
    out[0] = a[0] + s * b[0];
    out[1] = a[1] + s * b[1];
    out[2] = a[2] + s * b[2];
}
static inline double re__len(const double a[3]) { return sqrt(re__dot(a, a)); }



/* ==== [section: baselines] (owned by the baselines/example helper) ==== */
#ifndef RE_NO_BASELINES
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
/* The same restricted to the host object `object` (Cycles' local BVH query):
   the nearest hit on that object only. Optional (re_bevel_cycles_desc_t). */
typedef int (*re_trace_object_fn)(void *user, unsigned object, const double origin[3], const double dir[3],
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
    /* Optional: the probes then trace P's object alone (called with the
       same user pointer), as Cycles does. With the any-object trace only,
       a surface of P's object that coincides with another object's (a box
       resting on a floor: its bottom face and the floor) or lies within
       RE_BEVEL_STEP_REL R behind it is missed, and other objects' hits
       use up RE_BEVEL_MAX_HITS. */
    re_trace_object_fn trace_object;
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
   Hits on other objects are skipped (with desc->trace_object they are
   never found). RE_ERR_INVALID_ARG as above. */
RE_DEF re_result_t re_bevel_cycles(const re_bevel_cycles_desc_t *desc, const double p[3],
                                   const double n[3], unsigned object, re_trace_fn trace,
                                   void *user, re_bevel_result_t *out);
#endif /* RE_NO_BASELINES */
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

#include <stdio.h>  /* snprintf for diagnostics; nothing is printed */
#include <string.h>

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
#  if defined(__linux__) && !defined(RE_NO_HUGEPAGES)
#    include <sys/mman.h> /* MADV_HUGEPAGE is declared unless the compiler is in strict ISO mode */
#    ifdef MADV_HUGEPAGE
#      define RE__HUGEPAGES 1
#    endif
#  endif
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
    case RE_ERR_BAD_SCALE: return "object size outside [RE_SIZE_MIN, RE_SIZE_MAX]";
    case RE_RESULT_COUNT_: break;
    }
    return "unknown result";
}

/* min/max without libm's NaN handling (inputs here are finite): inlined */
static double re__max(double a, double b) { return a > b ? a : b; }
static double re__min(double a, double b) { return a < b ? a : b; }

/* ---- Tolerances (all relative; see docs/rounded_edges.md "Tolerances") ---- */

/* Detection's zone test is inlined into its loop, and its copy for the
   rare checks of answers kept out of the query's body (re__zone_holds):
   left to itself, gcc called it out of line from the loop. */
#if defined(__GNUC__) || defined(__clang__)
#define RE__HOT_INLINE __attribute__((always_inline)) inline
#define RE__NOINLINE __attribute__((noinline))
#else
#define RE__HOT_INLINE inline
#define RE__NOINLINE
#endif

/* DBL_EPSILON and FLT_EPSILON: the units of the rounding-scaled tolerances
   below (for the flat test the positions' own type decides which). */
#define RE__DBL_EPS 2.220446049250313e-16
#define RE__FLT_EPS 1.1920928955078125e-07

/* Two faces are coplanar (their edge is "flat", e.g. a quad diagonal) when
   the sine of the angle between their normals is below RE__FLAT_SIN (far
   below any modelled dihedral: 179.9 degrees is 1.7e-3), or below what the
   rounding of their vertices can tilt them by. Moving a vertex by one
   rounding of its coordinates (eps * M: eps the positions' type's epsilon,
   M its largest coordinate magnitude) tilts its triangle by up to
   eps * M / h, h the triangle's smallest altitude; two faces whose tilt is
   within RE__FLAT_ROUNDINGS of that, summed over both triangles, are
   coplanar too, up to RE__FLAT_SIN_WIDE. Float positions need it
   everywhere: a rotated float box's quads are not planar (their halves
   tilt by ~1e-7 at the origin, 1e-4 at 1e3 sizes from it), and the thin
   triangles of an n-gon's fan far more; their edges would be concave and
   leave every corner sharp. Doubles need it far from the origin (at 3e5,
   pieces 0.03 high tilt by ~2e-9 and would meet at convex edges no radius
   fits). Thin triangles widen it most, so a finely tessellated curved
   surface could chain into one "plane": re__flat_chains (step 2b) sends
   such groups back to RE__FLAT_SIN. re_mesh_t.flat_sin raises this to one
   value where it is larger. */
#define RE__FLAT_SIN 1e-9
#define RE__FLAT_ROUNDINGS 4.0
/* The largest widened sine (0.57 degrees, RE_FLAT_SIN_LIMIT): no rounding
   makes creases above it. */
#define RE__FLAT_SIN_WIDE RE_FLAT_SIN_LIMIT
/* A group of faces joined by flat edges whose normals spread by more than
   this times the largest tolerance of its triangles (their rounding's
   tilt, or re_mesh_t.flat_sin) is a curved surface, not one noisy plane
   (re__flat_chains): a noisy plane's pieces each tilt by at most their
   tolerance, so two of them by at most twice the largest. */
#define RE__FLAT_CHAIN 2.0
/* A triangle is degenerate when |cross(e1, e2)| <= this * (longest edge)^2,
   i.e. its smallest angle is below about 1e-12 rad. */
#define RE__DEGENERATE_REL 1e-12
/* Three face planes are treated as parallel when |det(n_i, n_j, n_l)| is
   below this (their offsets would meet at a point farther than 1e12 radii). */
#define RE__PARALLEL_DET 1e-12
/* Feasibility of eroded-corner vertices, in units of r times
   max(1, |u|) (u = vertex position relative to the corner, per unit radius). */
#define RE__CORNER_EPS 1e-9
/* Eroded-corner vertices closer than this, in the same units (r times
   max(1, |u|)), are one vertex. Why larger than RE__CORNER_EPS: four or more
   face planes through nearly one eroded point (the symmetric degree-5/6
   corners of an icosphere, after float rounding or a rigid transform
   perturbed them by ~1e-7 of the coordinates) give plane triples whose
   points all pass the feasibility test, yet lie 1e-9..1e-8 apart; merged
   only within RE__CORNER_EPS they outnumbered the k - 2 vertices a k-plane
   corner can have, and the corner was left sharp. Merging drops vertices,
   moving the rounded surface by at most 1e-7 r max(1, |u|) (|u| reaches
   tens of thousands at nearly flat corners): far below a pixel, though
   where a cylinder or sphere meets a face tangentially a move of e turns
   the normal by up to sqrt(2 e / r) (docs: Limits). The relative form
   scales with r and with |u|, as the solve's rounding does. */
#define RE__CORNER_MERGE 1e-7
/* A requested radius up to r_max * (1 + this) counts as valid (the largest
   valid radius is then used as is, with zero-length cylinders). */
#define RE__RADIUS_SLACK 1e-9
/* Rounding slack of a plane-side test n.x - c, in units of the magnitudes
   that enter it (|c| + |x|): a few ulps of the inputs. */
#define RE__SIDE_ULPS (64.0 * RE__DBL_EPS)
/* The flat-part test's slack (query step 2), in the same units: the
   rounding of evaluating n.q - (c - r) with q = I - r n_f, |n_i| <= 1, is
   at most 6 u (|q|_1 + |c| + r) (q's madd 2 u |q|_1, the dot product
   gamma_3 |q|_1, c - r and the difference u each; u = DBL_EPS / 2), so
   4 DBL_EPS covers it and calls flat every point the exact test calls
   flat (the bands of query step 0 stay inside what this test calls
   flat). Why not RE__SIDE_ULPS: a point outside a shifted plane by less
   than the slack is called flat, and along the face that band is the
   slack over the sine between the two faces; at coordinates of 1e6 and
   r of 5e-8, 64 ulps were 1.2 r, and a host hit 5 r inside the removed
   volume beside a sharp corner (faces at sine 0.32) came back unchanged
   (fuzz_rounded_exact). */
#define RE__FLAT_ULPS (4.0 * RE__DBL_EPS)
/* A pass-through's exit X is checked against the set's reach
   (re__exit_on_edge_of) when the ray stays within RE__ALONG_FACE_R r +
   RE__ALONG_FACE_ULPS |I, X|_1 (1 + |X - I| / r) of one face plane of the
   set from I to X. A capsule contact is lost to rounding only when the
   ray meets the capsule within its features' placement noise (ulps of the
   coordinates), so it runs along a face at a slope of at most about that
   noise over r: it has sunk below the face by at most the noise times
   |X - I| / r (a ray at 1e-10 to a face, r = 5e-8 of the size, 7e-11 deep
   at its far edge: rays_along_a_face_through_its_vertices). Others meet a
   capsule first and skip the check. */
#define RE__ALONG_FACE_R 1e-3
/* The slab check runs only where a lost contact could turn a normal by
   more than this (radians): radii far below the coordinates' size. */
#define RE__SLAB_ANGLE 1e-4
/* A rounded hit whose normal is within acos(RE__SLAB_COS) of a face's is
   checked for lying in that face's slab (re__hit_in_slab): such bogus
   entries meet the capsule just past the tangent line, sqrt(2 depth / r)
   off the face's normal, the depth a ray along the face reaches below it. */
#define RE__SLAB_COS 0.5
/* A ray and a capsule's axis whose directions' squared sine is below this
   are parallel for their closest approach (re__ray_seg_approach): it
   starts from the ray's first point instead of the normal equations. */
#define RE__PARALLEL_SIN2 1e-12
#define RE__ALONG_FACE_ULPS (1024.0 * RE__DBL_EPS)
/* A host that traces in float reports t late or early by ~1e-7 relative;
   when its hit point lands just inside a rounding capsule (next to the
   tangent line), the capsule entry up to this fraction of t_host before
   the host's t is accepted, so the rounded hit is still computed exactly
   in double from the ray itself. */
#define RE__HOST_T_SLACK 1e-5
/* Most steps of the adjacency-graph walk one query takes when a grazing ray
   travels along the removed volume (paper §3.1). */
#define RE__MAX_WALK 64
/* Most corners one query holds (its set, re__set_t): the corners on the
   hit's face plane whose detection cylinders contain the hit, and those
   the walk adds. A finely tessellated round rim under a large radius puts
   hundreds of them within reach of one point (a 512-gon prism at r = 0.4
   of its radius: 188 detected, 66 of them needed); 64 dropped some
   (found by review, 2026-12-06). 12 KiB of stack with its table
   (re__set_t); a corner dropped sets re__set_t.full, and the answer's
   RE_HIT_INCOMPLETE. */
#ifndef RE_SET_CAP
#define RE_SET_CAP 1024
#endif
#if RE_SET_CAP < 16
#error "RE_SET_CAP: a query needs room for at least 16 corners"
#endif
#define RE__SET_CAP ((unsigned)(RE_SET_CAP))

#define RE__NONE 0xFFFFFFFFu

/* ---- Stored structure ------------------------------------------------------ */

typedef struct re__plane_t {
    double n[3]; /* unit outward normal */
    double c;    /* n.x = c on the face; n.x <= c inside */
} re__plane_t;

/* P's height over plane g: positive outside. */
static double re__side_of(const re__plane_t *g, const double P[3]) { return re__dot(g->n, P) - g->c; }

/* A rounding sphere is its corner (re__object_t.s_corner) and, in the
   compact layout, 2 bytes saying where its centre comes from
   (re__object_t.sinfo). Most centres are the point where three of the
   corner's face planes, shifted inward by r, meet (a vertex of the eroded
   polytope, "Memory" in docs/rounded_edges.md): the info holds the three
   plane slots (bits 0-4, 5-9, 10-14) and re__centre() solves for it at
   query time. A centre that is not such a triple point (a vertex inside a
   straight edge, k = 2), whose slots do not fit 5 bits (corners of more
   than 32 planes), or whose triple point the build could not reproduce
   within RE__SPHERE_SOLVE_REL, is stored: info = RE__SPH_STORED, centre in
   `xsph` at its rank in the ascending list `xsid`. The fast layout stores
   every centre, xsph in sphere order. */
#define RE__SPH_STORED 0x8000u

/* A rounding cylinder between two sphere centres; its corners are the
   spheres' (re__object_t.s_corner). Cylinders [0, n_edge_cyls) round mesh edges, the
   rest are extra (exact-corner) cylinders inside one corner. */
typedef struct re__cyl_t {
    unsigned s[2]; /* spheres at the axis ends */
    unsigned p[2]; /* the two offset planes it joins */
} re__cyl_t;
/* An edge cylinder as stored: its planes here, 8 bytes (p[0] is the face
   on the left leaving the edge's lower vertex, p[1] leaving the upper);
   s[0], the sphere at the lower vertex, grows with the cylinder id (edges
   are numbered by their lower vertex), so it is packed apart
   (re__object_t.c_s0). The fast layout keeps s[1] whole (s1w); the
   compact one as s[1] - s[0] in 16 bits (re__object_t.ds1): spheres are
   numbered in vertex order, and an edge's vertices seldom lie 65535
   spheres apart; those that do are listed in xs1 (re__cyl_s1). */
typedef struct re__ecyl_t {
    unsigned p[2];
} re__ecyl_t;
#define RE__DS1_FAR 0xFFFFu

/* An extra (exact-corner) cylinder, 4 bytes (its corner is in
   re__object_t.x_corner): both ends are spheres of one corner and both
   planes are its own, so it keeps local slots: spheres sfirst + s[i],
   planes re__corner_plane(p[i]). A corner's extra cylinders are numbered
   consecutively, so its reference list holds only the first. */
typedef struct re__xcyl_t {
    unsigned char p[2], s[2];
} re__xcyl_t;

/* A rounded mesh vertex, 8 bytes; its monotone ids are packed apart
   (re__object_t: k_first, k_sfirst, k_rid; its vertex id in cvertex).
   refs[first ...]: np edge cylinders (cylinder j joins planes j and j+1),
   each as id << 1 | (1 if the corner is the edge's lower vertex);
   its nx extra cylinders are xfirst ... (packed, only in objects that have
   extra cylinders); its ns spheres are sfirst ...; its radius radii[rid]. The mesh vertex itself
   is not stored: every test that needs it uses the first sphere centre with
   a radius widened by their distance (docs/rounded_edges.md, "Memory"). */
typedef struct re__corner_t {
    float walk;    /* adjacency walk (query step 4): a removed point near this
                      corner lies within `walk` of sphere sfirst (face reach + r +
                      |sphere - vertex|, rounded up to float) */
    unsigned char np, ns, nx;
    unsigned char clear; /* re_secondary_origin's gate: within walk times
                            re__clear_radius(clear) of sphere sfirst, a point
                            on one of the corner's faces is inside every face
                            bordering it (re__exit_clearance) */
} re__corner_t;

/* kd-tree node (§3.2), 8 bytes. Inner node: info = axis | right child << 2
   (the left child follows the node), data = the split as a float bit
   pattern, relative to the object's origin. Leaf: info = 3 | first << 2,
   data = the smallest edge cylinder id of the leaf, its base; the list
   leaf16[first ...] is its count n, then n ids as offsets from the base
   (2 bytes a reference: a leaf's edges are neighbours in space, and their
   ids seldom span 65536). A list that does not fit is cut into runs that
   do: bit 15 of a run's count says another run follows, starting with its
   own base in two 16-bit halves (re__kd_narrow). */
typedef struct re__node_t {
    unsigned info, data;
} re__node_t;

/* An array of ids stored in blocks of RE__PK_BLOCK: per block a base and one
   byte per entry, id = base + byte (255: RE__NONE), about 1.1 bytes an id
   where neighbouring entries have nearby ids (a triangle's plane: planes are
   numbered in triangle order; a corner's vertex: corners are numbered in
   vertex order). A block whose ids span more than 254 keeps them whole:
   base = RE__PK_FULL | its offset in `full`. */
#define RE__PK_BLOCK 32u
#define RE__PK_FULL 0x80000000u
/* Largest span of a block kept as bytes (254: 255 is RE__NONE), the
   largest span of a kd leaf run (re__kd_narrow), the plane slots a solved
   sphere centre may use (5 bits, re__object_t.sinfo) and the largest
   sphere distance of an edge cylinder's ends kept in 16 bits. Tests lower
   them to run the fallbacks (tests/test_rounded_packing.c). */
#ifndef RE__PK_SPAN
#define RE__PK_SPAN 254u
#endif
#ifndef RE__LEAF_RUN_SPAN
#define RE__LEAF_RUN_SPAN 0xFFFFu
#endif
#ifndef RE__SOLVED_SLOTS
#define RE__SOLVED_SLOTS 32u
#endif
#ifndef RE__DS1_SPAN /* largest s[1] - s[0] kept in 16 bits (re__ecyl_t) */
#define RE__DS1_SPAN 0xFFFEu
#endif
typedef struct re__pk_t {
    const unsigned *base;
    const unsigned char *off;
    const unsigned *full;
} re__pk_t;

static inline unsigned re__pk_get(const re__pk_t *p, unsigned i)
{
    unsigned b = p->base[i / RE__PK_BLOCK];
    unsigned char d;
    if (b & RE__PK_FULL) return p->full[(b & ~RE__PK_FULL) + i % RE__PK_BLOCK];
    d = p->off[i];
    return d == 255u ? RE__NONE : b + d;
}

/* re__pk_get for arrays that never hold RE__NONE (monotone ids). */
static inline unsigned re__pk_id(const re__pk_t *p, unsigned i)
{
    unsigned b = p->base[i / RE__PK_BLOCK];
    if (b & RE__PK_FULL) return p->full[(b & ~RE__PK_FULL) + i % RE__PK_BLOCK];
    return b + p->off[i];
}

/* Whether object o / the build uses RE_LAYOUT_COMPACT: a constant 0 with
   RE_NO_COMPACT, so the compiler drops that layout's branches. */
#ifdef RE_NO_COMPACT
#define RE__COMPACT(o) 0
#define RE__WANT_COMPACT(desc) 0
#else
#define RE__COMPACT(o) ((o)->compact)
#define RE__WANT_COMPACT(desc) ((desc)->layout == RE_LAYOUT_COMPACT)
#endif

typedef struct re__object_t {
    unsigned n_tris, n_planes, n_spheres, n_xsph, n_cyls, n_edge_cyls, n_corners, n_refs, n_nodes, n_leaf16, n_radii;
    int compact; /* RE_LAYOUT_COMPACT: sphere centres solved (re__cptr) */
    double size; /* bounding-box diagonal: the object's length scale */
    double rmax;
    double origin[3]; /* kd splits are floats relative to this (bounding-box centre) */
    re__pk_t tri_plane; /* per triangle: plane id, RE__NONE if not rounded nearby */
    re__pk_t cvertex;   /* per corner: its mesh vertex (enumeration only) */
    re__pk_t k_first, k_sfirst, k_rid, k_xfirst; /* per corner: re__corner_t */
    re__pk_t c_s0;      /* per edge cylinder: re__ecyl_t */
    re__pk_t s_corner;  /* per sphere: its corner */
    re__pk_t x_corner;  /* per extra cylinder: its corner */
    const unsigned char *bands; /* 4 per triangle, in units of 1/RE__BAND_STEPS,
                                   rounded up: the barycentric band along the
                                   edge opposite corner k (k < 3), and the cap
                                   at the corners (3); query step 0 */
    const re__plane_t *planes;
    const unsigned short *sinfo; /* compact layout: per sphere (RE__SPH_STORED) */
    const unsigned *xsid; /* compact layout: the stored spheres, ascending */
    const double *xsph; /* 3 per stored sphere centre (every one in the fast layout) */
    const re__ecyl_t *cyls;   /* edge cylinders [0, n_edge_cyls) */
    const unsigned *s1w;      /* fast layout: per edge cylinder, s[1] */
    const unsigned short *ds1; /* compact layout: per edge cylinder, s[1] - s[0], or RE__DS1_FAR */
    const unsigned *xs1;      /* 2 per far cylinder, ascending: its id, its s[1] */
    unsigned n_xs1;
    const re__xcyl_t *xcyls;  /* extra cylinders [n_edge_cyls, n_cyls) */
    const unsigned short *det; /* fast layout: 2 per edge cylinder, as the upper
                          halves of floats rounded up (re__det): detection
                          radius around the mesh edge's line, and the reach
                          past its end spheres along the axis (query step 1) */
    const unsigned char *det8; /* compact layout: the same in one byte each (re__det8) */
    unsigned det_e0;           /* compact layout: re__det8's exponent base */
    const re__corner_t *corners;
    const double *radii; /* one per rounded patch */
    const unsigned *refs;
    const re__node_t *nodes;
    const unsigned short *leaf16; /* kd leaf lists (re__node_t) */
    size_t bytes; /* the block's size (the scene's stats hold the counts) */
    void *block;  /* RE_MALLOC'd storage (re_build) or NULL */
} re__object_t;

struct re_scene_t {
    unsigned n_objects;
    re__object_t *objects;
    void *alloc_ctx;
    int owned; /* built by re_build(): free with re_free() */
    re_stats_t stats;
};

/* ---- Arena over a caller buffer --------------------------------------------- */

typedef struct re__arena_t {
    unsigned char *base;
    size_t cap, used, high;
} re__arena_t;

static void *re__take(re__arena_t *a, size_t bytes)
{
    size_t off = (a->used + 15u) & ~(size_t)15u;
    if (off > a->cap || bytes > a->cap - off) return NULL;
    a->used = off + bytes;
    if (a->used > a->high) a->high = a->used;
    return a->base + off;
}

/* Huge pages for a block from the default malloc (MEMORY, at the top). A
   build writes its blocks once, front to back, so on a virtual machine
   whose 4 KiB faults cost several microseconds (the benchmark measures
   this) the faults weigh more than the build's arithmetic. */
#define RE__HUGE_PAGE ((size_t)2 << 20)
/* The whole huge pages inside [p, p + bytes): [*a, *b), empty (a == b)
   for blocks under two huge pages, whose rounding would mostly be waste. */
static void re__huge_range(size_t p, size_t bytes, size_t *a, size_t *b)
{
    *a = *b = 0;
    if (bytes < 2 * RE__HUGE_PAGE || p > (size_t)-1 - bytes) return;
    *a = (p + RE__HUGE_PAGE - 1) & ~(RE__HUGE_PAGE - 1);
    *b = (p + bytes) & ~(RE__HUGE_PAGE - 1);
}
static void re__advise_huge(void *p, size_t bytes)
{
    size_t a, b;
    re__huge_range((size_t)p, bytes, &a, &b);
#ifdef RE__HUGEPAGES
    if (p && b > a) (void)madvise((void *)a, b - a, MADV_HUGEPAGE);
#else
    (void)a, (void)b;
#endif
}

#define RE__TAKE(ptr, type, count)                                                   \
    do {                                                                             \
        (ptr) = (type *)re__take(ar, sizeof(type) * (size_t)(count) + 1u);           \
        if (!(ptr)) return re__fail(an, RE_ERR_BUFFER_TOO_SMALL, -1, "scratch buffer too small"); \
    } while (0)

/* ---- Analysis state (scratch) ------------------------------------------------ */

typedef struct re__edge_t {
    unsigned v[2];  /* v[0] < v[1] */
    unsigned he[2]; /* half-edges 3*t+k (edge k of triangle t runs tri[k] -> tri[k+1]) */
    unsigned count; /* triangles using it */
    unsigned char cls;
    unsigned char rounded;
} re__edge_t;

enum { RE__E_FLAT, RE__E_CONVEX, RE__E_CONCAVE, RE__E_BOUNDARY, RE__E_NONMANIFOLD };
enum { RE__V_NONE, RE__V_CORNER, RE__V_SHARP };

typedef struct re__an_t {
    const re_scene_desc_t *desc;
    const re_mesh_t *m;
    unsigned obj;
    int sizing; /* re_build_sizes(): steps whose output has a fixed size only take their scratch */
    unsigned inner; /* tasks the longest steps split into on the host's threads (THREADS); 1: none */
    re_diag_t *diag;
    unsigned V, T, E;
    unsigned V0;            /* the mesh's vertex count: ids from V0 on are fans split off (step 2a) */
    const unsigned *vorig;  /* per split-off vertex (id - V0): the mesh vertex it was, NULL if none */
    int fins;               /* some edge has more than two triangles (step 2) */
    int fans_split;         /* step 2a ran */
    int fans_wanted;        /* step 4 found a vertex with several fans before step 2a ran */
    unsigned char *vwhy;    /* per vertex: why step 4 left it sharp (RE__WHY_*), reported by re__corner_reports */
    unsigned long long reports, report_skip; /* reports made; the first report_skip were delivered by an
                                                earlier attempt (re__build_object) and are not repeated */
    const double *pos; /* 3 per vertex: the caller's array itself when it is packed doubles */
    unsigned *tri, *tsrc, *tplane;
    double *tn, *tarea;
    unsigned char *tbad;
    re__edge_t *edges;
    unsigned *he_edge;
    unsigned *voff, *vinc;
    unsigned char *vstate;
    unsigned *vcorner;
    /* per candidate corner */
    unsigned nc;
    unsigned *c_vertex, *c_pfirst, *c_sfirst, *c_xfirst;
    unsigned char *c_np, *c_ns, *c_nx;
    unsigned *c_planes, *c_edges; /* fan-ordered planes / crossing edges */
    unsigned *c_x;                /* extra cylinders: pairs of plane slots */
    unsigned char *c_start;       /* per plane slot j: sphere (local, < 64) where edge j starts */
    double *su;                   /* unit-radius sphere offsets, 3 per sphere */
    unsigned *s_tri;              /* per sphere: the plane slots it solves from
                                     (re__object_t.sinfo), RE__NONE if none */
    unsigned ns_total, nx_total, np_total;
    unsigned char *edge_end; /* 2 per edge: local sphere index (< 64) at the v[0], v[1] side; 255 = none */
    unsigned n_planes;
    re__plane_t *planes;
    unsigned *plane_used;
    re_stats_t st;
    double size;
    double origin[3]; /* bounding-box centre */
    double flat_k;    /* RE__FLAT_ROUNDINGS eps M L of the object (re__coplanar) */
} re__an_t;

/* The mesh's id of analysis vertex v (step 2a splits vertices): every
   report, diagnostic and enumeration names mesh vertices. */
static unsigned re__vid(const re__an_t *an, unsigned v) { return v < an->V0 ? v : an->vorig[v - an->V0]; }

/* Fill the diagnostic (if any) and return r: object < 0 for the build as a
   whole (the message as it is), element -1 when there is none to name. */
static re_result_t re__diag_fail(re_diag_t *diag, re_result_t r, long long object, long long element, const char *msg)
{
    if (diag) {
        diag->result = r;
        diag->element = element;
        diag->object = object < 0 ? 0u : (unsigned)object;
        if (object < 0) snprintf(diag->message, sizeof diag->message, "%s", msg);
        else snprintf(diag->message, sizeof diag->message, "object %u: %.138s", (unsigned)object, msg);
    }
    return r;
}
static re_result_t re__fail(re__an_t *an, re_result_t r, long long element, const char *msg)
{
    return re__diag_fail(an->diag, r, an->obj, element, msg);
}

static void re__report(re__an_t *an, re_report_kind_t kind, long long e1, long long e2,
                       double value, const char *msg)
{
    re_report_t rep;
    if (an->reports++ < an->report_skip || !an->desc->report) return;
    rep.kind = kind;
    rep.object = an->obj;
    rep.element = e1;
    rep.element2 = e2;
    rep.value = value;
    rep.message = msg;
    an->desc->report(an->desc->report_user, &rep);
}

static int re__finite3(const double p[3])
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

static unsigned re__uf_find(unsigned *uf, unsigned i)
{
    while (uf[i] != i) {
        uf[i] = uf[uf[i]];
        i = uf[i];
    }
    return i;
}
static void re__uf_join(unsigned *uf, unsigned a, unsigned b)
{
    a = re__uf_find(uf, a);
    b = re__uf_find(uf, b);
    if (a != b) uf[a < b ? b : a] = a < b ? a : b;
}

/* Triangle count after splitting polygons into fans; 0 and an error code on bad sizes. */
static re_result_t re__count_tris(const re_mesh_t *m, unsigned *T, long long *bad)
{
    unsigned long long sum = 0, tris = 0;
    unsigned f;
    *bad = -1;
    if (!m->face_sizes) {
        if (m->index_count % 3u) return RE_ERR_BAD_FACE;
        /* the same limit as for polygons: 4 T must fit the 32-bit loop
           counters (found by review: 1.4e9 triangles passed) */
        if (m->index_count / 3u >= 0x40000000u) return RE_ERR_TOO_LARGE;
        *T = m->index_count / 3u;
        return RE_OK;
    }
    for (f = 0; f < m->face_count; f++) {
        if (m->face_sizes[f] < 3u) {
            *bad = f;
            return RE_ERR_BAD_FACE;
        }
        sum += m->face_sizes[f];
        tris += m->face_sizes[f] - 2u;
    }
    if (sum != m->index_count) return RE_ERR_BAD_FACE;
    if (tris >= 0x40000000ull) return RE_ERR_TOO_LARGE;
    *T = (unsigned)tris;
    return RE_OK;
}

static void re__read_pos(const re_mesh_t *m, unsigned i, double out[3])
{
    size_t stride = m->position_stride;
    const unsigned char *base = (const unsigned char *)m->positions;
    /* memcpy: a stride need not keep the scalars aligned */
    if (m->position_type == RE_FLOAT32) {
        float p[3];
        memcpy(p, base + (stride ? stride : 3 * sizeof(float)) * i, sizeof p);
        out[0] = p[0];
        out[1] = p[1];
        out[2] = p[2];
    } else {
        memcpy(out, base + (stride ? stride : 3 * sizeof(double)) * i, 3 * sizeof(double));
    }
}

/* Step 1a (re_mesh_t.weld): each vertex's first vertex at the same position
   (exact in double, -0 = +0, NaN and infinities never match: they are
   reported as themselves), through open addressing at load <= 1/2. */
static unsigned long long re__pos_hash(const double p[3])
{
    unsigned long long h = 0x243F6A8885A308D3ull, x;
    unsigned a;
    for (a = 0; a < 3; a++) {
        double c = p[a] + 0.0; /* -0 -> +0 */
        memcpy(&x, &c, sizeof x);
        h = (h ^ x) * 0x9E3779B97F4A7C15ull;
        h ^= h >> 29;
    }
    return h;
}
static re_result_t re__weld_map(re__an_t *an, re__arena_t *ar, unsigned **map_out)
{
    unsigned V = an->V, i, *map, *slot;
    size_t cap = 16, mask, j;
    while (cap < 2 * (size_t)V) cap <<= 1;
    mask = cap - 1;
    RE__TAKE(map, unsigned, V);
    RE__TAKE(slot, unsigned, cap);
    for (j = 0; j < cap; j++) slot[j] = RE__NONE;
    for (i = 0; i < V; i++) {
        const double *p = an->pos + 3 * (size_t)i;
        map[i] = i;
        if (!re__finite3(p)) continue;
        for (j = (size_t)re__pos_hash(p) & mask;; j = (j + 1) & mask) {
            const double *q;
            if (slot[j] == RE__NONE) {
                slot[j] = i;
                break;
            }
            q = an->pos + 3 * (size_t)slot[j];
            if (q[0] == p[0] && q[1] == p[1] && q[2] == p[2]) {
                map[i] = slot[j];
                break;
            }
        }
    }
    *map_out = map;
    return RE_OK;
}

/* Step 1: fan-split polygons, validate, face normals. */
/* Triangle t (its indices in an->tri) checked and measured: RE_OK with
   its unit normal and doubled area, and the box lo, hi grown by its
   vertices; else the error that names it (msg, *elem: the triangle, or the
   vertex with a NaN), its indices mapped through weld (NULL: none) when
   they are in range. */
static re_result_t re__measure_triangle(re__an_t *an, unsigned t, const unsigned *weld, double lo[3], double hi[3], char *msg,
                                        size_t msg_size, long long *elem)
{
    unsigned *tr = an->tri + 3 * (size_t)t, k;
    double e1[3], e2[3], e3[3], cr[3], len, lmax;
    *elem = t;
    for (k = 0; k < 3; k++)
        if (tr[k] >= an->V) {
            snprintf(msg, msg_size, "triangle %u has vertex index %u >= vertex_count %u", t, tr[k], an->V);
            return RE_ERR_INDEX_OUT_OF_RANGE;
        }
    if (weld)
        for (k = 0; k < 3; k++) tr[k] = weld[tr[k]];
    for (k = 0; k < 3; k++)
        if (!re__finite3(an->pos + 3 * (size_t)tr[k])) {
            snprintf(msg, msg_size, "triangle %u uses vertex %u, which has a NaN or infinite coordinate", t, tr[k]);
            *elem = tr[k];
            return RE_ERR_NAN_VERTEX;
        }
    re__sub(an->pos + 3 * (size_t)tr[1], an->pos + 3 * (size_t)tr[0], e1);
    re__sub(an->pos + 3 * (size_t)tr[2], an->pos + 3 * (size_t)tr[0], e2);
    re__sub(an->pos + 3 * (size_t)tr[2], an->pos + 3 * (size_t)tr[1], e3);
    re__cross(e1, e2, cr);
    len = re__len(cr);
    lmax = re__max(re__dot(e1, e1), re__max(re__dot(e2, e2), re__dot(e3, e3)));
    if (!(len > RE__DEGENERATE_REL * lmax)) {
        double emax = 0;
        for (k = 0; k < 3; k++) emax = re__max(emax, re__max(fabs(e1[k]), fabs(e2[k])));
        if (emax > RE_SIZE_MAX || (emax > 0 && emax < RE_SIZE_MIN)) { /* its squares left double's range */
            snprintf(msg, msg_size, "triangle %u (vertices %u %u %u) has edges of %g, outside [%g, %g]", t, tr[0], tr[1], tr[2],
                     emax, RE_SIZE_MIN, RE_SIZE_MAX);
            return RE_ERR_BAD_SCALE;
        }
        snprintf(msg, msg_size, "triangle %u (vertices %u %u %u) is degenerate (zero area or zero-length edge)", t, tr[0], tr[1],
                 tr[2]);
        return RE_ERR_DEGENERATE_TRIANGLE;
    }
    an->tn[3 * (size_t)t] = cr[0] / len;
    an->tn[3 * (size_t)t + 1] = cr[1] / len;
    an->tn[3 * (size_t)t + 2] = cr[2] / len;
    an->tarea[t] = len;
    for (k = 0; k < 3; k++) {
        const double *p = an->pos + 3 * (size_t)tr[k];
        lo[0] = re__min(lo[0], p[0]), lo[1] = re__min(lo[1], p[1]), lo[2] = re__min(lo[2], p[2]);
        hi[0] = re__max(hi[0], p[0]), hi[1] = re__max(hi[1], p[1]), hi[2] = re__max(hi[2], p[2]);
    }
    return RE_OK;
}

static re_result_t re__triangles(re__an_t *an, re__arena_t *ar)
{
    const re_mesh_t *m = an->m;
    unsigned t = 0, f, nf, base = 0, i, k, *weld = NULL;
    double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    size_t mark;
    re_result_t rc;
    char msg[128];
    if (m->position_type == RE_FLOAT64 && (m->position_stride == 0 || m->position_stride == 3 * sizeof(double)) &&
        !((size_t)m->positions % sizeof(double)))
        an->pos = (const double *)m->positions; /* no copy: fewer fresh scratch pages */
    else {
        double *pos;
        RE__TAKE(pos, double, 3 * (size_t)an->V);
        for (i = 0; i < an->V; i++) re__read_pos(m, i, pos + 3 * (size_t)i);
        an->pos = pos;
    }
    RE__TAKE(an->tri, unsigned, 3 * (size_t)an->T);
    if (m->edge_radius) RE__TAKE(an->tsrc, unsigned, 3 * (size_t)an->T); /* read by re__edge_request only */
    RE__TAKE(an->tn, double, 3 * (size_t)an->T);
    RE__TAKE(an->tarea, double, an->T);
    RE__TAKE(an->tbad, unsigned char, an->T);
    mark = ar->used;
    if (m->weld && (rc = re__weld_map(an, ar, &weld)) != RE_OK) return rc;
    nf = m->face_sizes ? m->face_count : an->T;
    for (f = 0; f < nf; f++) {
        unsigned n = m->face_sizes ? m->face_sizes[f] : 3u, j;
        for (j = 1; j + 1 < n; j++, t++) { /* the polygon as a fan */
            unsigned *tr = an->tri + 3 * (size_t)t;
            long long elem;
            tr[0] = m->indices[base];
            tr[1] = m->indices[base + j];
            tr[2] = m->indices[base + j + 1];
            if (an->tsrc) { /* index positions of the polygon's own edges (fan diagonals have none) */
                unsigned *src = an->tsrc + 3 * (size_t)t;
                src[0] = j == 1 ? base : RE__NONE;
                src[1] = base + j;
                src[2] = j + 2 == n ? base + j + 1 : RE__NONE;
            }
            an->tbad[t] = 0;
            if ((rc = re__measure_triangle(an, t, weld, lo, hi, msg, sizeof msg, &elem)) == RE_OK) continue;
            if (an->desc->bad_input != RE_BAD_INPUT_SKIP) return re__fail(an, rc, elem, msg);
            an->tbad[t] = 1;
            re__report(an, RE_REPORT_SKIPPED_TRIANGLE, t, -1, 0.0, msg);
        }
        base += n;
    }
    ar->used = mark; /* the weld map */
    an->size = 0;
    if (lo[0] <= hi[0]) {
        double dd[3];
        re__sub(hi, lo, dd);
        an->size = re__len(dd);
        for (k = 0; k < 3; k++) an->origin[k] = 0.5 * (lo[k] + hi[k]);
    }
    return RE_OK;
}

/* In-place heapsort, allocation-free: libc's qsort may malloc a buffer
   (glibc does from 1 KiB), outside RE_MALLOC and the caller's scratch.
   Not stable; every sort here orders values whose equal keys are equal
   bits, so the result is the one qsort gave. cmp as qsort's. */
static void re__sort_swap(unsigned char *a, unsigned char *b, size_t size)
{
    while (size--) {
        unsigned char t = *a;
        *a++ = *b, *b++ = t;
    }
}
static void re__sift_down(unsigned char *base, size_t size, int (*cmp)(const void *, const void *), size_t i, size_t n)
{
    for (;;) {
        size_t c = 2 * i + 1;
        if (c >= n) return;
        if (c + 1 < n && cmp(base + c * size, base + (c + 1) * size) < 0) c++;
        if (!(cmp(base + i * size, base + c * size) < 0)) return;
        re__sort_swap(base + i * size, base + c * size, size);
        i = c;
    }
}
static void re__sort(void *base_v, size_t n, size_t size, int (*cmp)(const void *, const void *))
{
    unsigned char *base = (unsigned char *)base_v;
    size_t i;
    if (n < 2) return;
    for (i = n / 2; i-- > 0;) re__sift_down(base, size, cmp, i, n);
    for (i = n - 1; i > 0; i--) {
        re__sort_swap(base, base + i * size, size);
        re__sift_down(base, size, cmp, 0, i);
    }
}

static int re__cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}
static int re__cmp_u64(const void *a, const void *b)
{
    unsigned long long x = *(const unsigned long long *)a, y = *(const unsigned long long *)b;
    return x < y ? -1 : x > y;
}

/* Step 2: edges from half-edges (bucketed by the smaller vertex), and their
   class from the two face normals. */
/* The tilt the rounding of triangle t's coordinates can give its normal:
   RE__FLAT_ROUNDINGS * eps * M / h (eps the positions' type's epsilon, M
   its largest coordinate magnitude, h its smallest altitude). */
static double re__tilt_bound(const re__an_t *an, unsigned t)
{
    double m = 0, l2 = 0, d[3], eps = an->m->position_type == RE_FLOAT32 ? RE__FLT_EPS : RE__DBL_EPS;
    unsigned k, a;
    for (k = 0; k < 3; k++) {
        const double *p = an->pos + 3 * (size_t)an->tri[3 * t + k];
        re__sub(an->pos + 3 * (size_t)an->tri[3 * t + (k + 1) % 3], p, d);
        l2 = re__max(l2, re__dot(d, d));
        for (a = 0; a < 3; a++) m = re__max(m, fabs(p[a]));
    }
    return RE__FLAT_ROUNDINGS * eps * m * sqrt(l2) / an->tarea[t]; /* M / h: tarea is twice the area */
}
/* Whether the faces of triangles t0 and t1, whose normals' cross product
   has length sn, are coplanar: 1 by the strict test (RE__FLAT_SIN, or the
   smaller re_mesh_t.flat_sin), 2 only by the widened one (widen = 1: both
   triangles' rounding tolerance, re__tilt_bound, up to RE__FLAT_SIN_WIDE,
   or re_mesh_t.flat_sin when that is larger), 0 if not. A flat_sin below
   the rounding does not make its noise a crease: two planes that far
   within their vertices' rounding of each other cross anywhere along the
   face (the angle 1e-7, the offset 1e-8: 0.1 away), so the query's
   flat-part test and the bands would disagree there. */
static int re__coplanar(const re__an_t *an, unsigned t0, unsigned t1, double sn, int widen)
{
    double fs = an->m->flat_sin, a0 = an->tarea[t0], a1 = an->tarea[t1];
    if (sn <= (fs > 0 && fs < RE__FLAT_SIN ? fs : RE__FLAT_SIN)) return 1;
    if (!widen) return 0;
    if (fs > 0 && sn <= fs) return 2;
    /* above the object-wide bound (an->flat_k / (twice the area), each
       triangle: its M and longest edge at most the object's) nothing is
       flat: the common case of real creases skips the two bounds below */
    if (sn > RE__FLAT_SIN_WIDE || sn * a0 * a1 > an->flat_k * (a0 + a1)) return 0;
    return sn <= re__tilt_bound(an, t0) + re__tilt_bound(an, t1) ? 2 : 0;
}

/* The class of a two-triangle edge from their normals: flat (re__coplanar;
   *wide set when only the widened test says so), convex or concave (also
   when folded back flat). */
static unsigned char re__fold_class(const re__an_t *an, const re__edge_t *ed, int widen, int *wide)
{
    unsigned h0 = ed->he[0], h1 = ed->he[1], t0 = h0 / 3, t1 = h1 / 3;
    const double *na = an->tn + 3 * (size_t)t0, *nb = an->tn + 3 * (size_t)t1;
    double cr[3], e3[3];
    int flat;
    re__cross(na, nb, cr);
    /* the edge as triangle t0 runs it */
    re__sub(an->pos + 3 * (size_t)an->tri[3 * t0 + (h0 % 3 + 1) % 3], an->pos + 3 * (size_t)an->tri[3 * t0 + h0 % 3], e3);
    flat = re__coplanar(an, t0, t1, re__len(cr), widen);
    if (wide) *wide = flat == 2;
    if (flat) return re__dot(na, nb) > 0 ? RE__E_FLAT : RE__E_CONCAVE; /* folded back: sharp */
    return re__dot(cr, e3) > 0 ? RE__E_CONVEX : RE__E_CONCAVE;
}

/* Triangles joined by flat edges, as union-find roots in uf, and per root
   its group's largest triangle in best (the best-conditioned normal). */
static void re__flat_groups(const re__an_t *an, unsigned *uf, unsigned *best)
{
    unsigned T = an->T, t, i;
    for (t = 0; t < T; t++) uf[t] = t, best[t] = RE__NONE;
    for (i = 0; i < an->E; i++)
        if (an->edges[i].cls == RE__E_FLAT) re__uf_join(uf, an->edges[i].he[0] / 3, an->edges[i].he[1] / 3);
    for (t = 0; t < T; t++) {
        unsigned r;
        if (an->tbad[t]) continue;
        r = re__uf_find(uf, t);
        if (best[r] == RE__NONE || an->tarea[t] > an->tarea[best[r]]) best[r] = t;
    }
}

/* Step 2b: faces joined by widened flat edges must stay one plane. A curved
   surface tessellated about as finely as its triangles' rounding tolerance
   (float positions: a cylinder of 8 000 sides creases by 7.9e-4 rad, and
   its facets' tolerance is about that) would chain through its "flat"
   creases into one plane, which step 3 gives one normal (its largest
   triangle's): the 8 000-gon got 32 spheres instead of 16 000, its rims
   rounded against a few normals, its radius clamped to 0.0032 of 0.05. A
   group of triangles joined by flat edges whose normals spread (the
   largest sine between a member's normal and that normal) by more than
   RE__FLAT_CHAIN times its members' largest tolerance is such a surface,
   not one noisy plane: all its widened flat edges take the strict test,
   which leaves it as it was without the widening (exact where the facets
   are exactly planar; sharp and reported where the rounding folds pieces
   concave). Groups of a few facets within the limit stay joined. Runs only
   when some edge is flat by the widening. */
static re_result_t re__flat_chains(re__an_t *an, re__arena_t *ar)
{
    unsigned T = an->T, E = an->E, t, i, *uf, *best;
    double *spread, *bound;
    size_t mark = ar->used;
    RE__TAKE(uf, unsigned, T);
    RE__TAKE(best, unsigned, T);
    RE__TAKE(spread, double, T);
    RE__TAKE(bound, double, T);
    re__flat_groups(an, uf, best);
    for (t = 0; t < T; t++) spread[t] = bound[t] = 0;
    for (t = 0; t < T; t++) {
        unsigned r;
        double cr[3];
        if (an->tbad[t]) continue;
        r = re__uf_find(uf, t);
        re__cross(an->tn + 3 * (size_t)t, an->tn + 3 * (size_t)best[r], cr);
        spread[r] = re__max(spread[r], re__len(cr));
        bound[r] = re__max(bound[r], re__max(an->m->flat_sin, re__min(RE__FLAT_SIN_WIDE, re__tilt_bound(an, t))));
    }
    for (i = 0; i < E; i++) {
        re__edge_t *ed = &an->edges[i];
        unsigned r;
        if (ed->cls != RE__E_FLAT) continue;
        r = re__uf_find(uf, ed->he[0] / 3);
        if (spread[r] > RE__FLAT_CHAIN * bound[r]) ed->cls = re__fold_class(an, ed, 0, NULL);
    }
    ar->used = mark;
    return RE_OK;
}

/* The half-edges of good triangles in buckets by their lower vertex:
   key = higher vertex << 32 | half-edge; bucket i ends at cnt[i] and
   starts at cnt[i - 1] (0 for the first). Every he_edge becomes RE__NONE. */
static void re__edge_buckets(re__an_t *an, unsigned *cnt, unsigned long long *key)
{
    unsigned V = an->V, T = an->T, t, k, i;
    memset(cnt, 0, sizeof(unsigned) * ((size_t)V + 1));
    for (t = 0; t < T; t++)
        for (k = 0; k < 3; k++) {
            unsigned a = an->tri[3 * t + k], b = an->tri[3 * t + (k + 1) % 3];
            an->he_edge[3 * t + k] = RE__NONE;
            if (!an->tbad[t]) cnt[(a < b ? a : b) + 1]++;
        }
    for (i = 0; i < V; i++) cnt[i + 1] += cnt[i];
    for (t = 0; t < T; t++)
        for (k = 0; k < 3; k++) {
            unsigned a = an->tri[3 * t + k], b = an->tri[3 * t + (k + 1) % 3];
            if (an->tbad[t]) continue;
            key[cnt[a < b ? a : b]++] = ((unsigned long long)(a < b ? b : a) << 32) | (3u * t + k);
        }
}

/* key[s, e) ascending. */
static void re__sort_bucket(unsigned long long *key, unsigned s, unsigned e)
{
    unsigned x, y;
    if (e - s > 64) {
        re__sort(key + s, e - s, sizeof *key, re__cmp_u64);
        return;
    }
    /* up to a 24-gon fan's apex (47): insertion sort beats re__sort's calls;
       the keys are unique, so the order is the same */
    for (x = s + 1; x < e; x++)
        for (y = x; y > s && key[y - 1] > key[y]; y--) {
            unsigned long long tmp = key[y];
            key[y] = key[y - 1], key[y - 1] = tmp;
        }
}

/* The class of edge ed from its half-edges; *widened counts folds the
   flat test widened (re__fold_class). Two triangles running through it
   the same way: RE_ERR_INCONSISTENT_WINDING naming the second, or under
   the skip policy a non-manifold edge. */
static re_result_t re__classify_edge(re__an_t *an, re__edge_t *ed, unsigned *widened)
{
    char msg[160];
    if (ed->count == 1) {
        ed->cls = RE__E_BOUNDARY;
    } else if (ed->count > 2) {
        ed->cls = RE__E_NONMANIFOLD;
        an->fins = 1;
    } else {
        unsigned h0 = ed->he[0], h1 = ed->he[1];
        unsigned t0 = h0 / 3, t1 = h1 / 3;
        unsigned a0 = an->tri[3 * t0 + h0 % 3], a1 = an->tri[3 * t1 + h1 % 3];
        if (a0 == a1) {
            snprintf(msg, sizeof msg, "triangles %u and %u run through edge %u-%u the same way (inconsistent winding)",
                     t0, t1, re__vid(an, ed->v[0]), re__vid(an, ed->v[1]));
            if (an->desc->bad_input != RE_BAD_INPUT_SKIP) return re__fail(an, RE_ERR_INCONSISTENT_WINDING, t1, msg);
            ed->cls = RE__E_NONMANIFOLD;
        } else {
            int wide = 0;
            ed->cls = re__fold_class(an, ed, 1, &wide);
            *widened += (unsigned)wide;
        }
    }
    return RE_OK;
}

static re_result_t re__edges(re__an_t *an, re__arena_t *ar)
{
    unsigned V = an->V, T = an->T, k, i, E = 0, widened = 0;
    unsigned *cnt;
    unsigned long long *key;
    size_t mark;
    double M = 0;
    for (k = 0; k < 3; k++) M = re__max(M, fabs(an->origin[k]));
    an->flat_k = RE__FLAT_ROUNDINGS * (an->m->position_type == RE_FLOAT32 ? RE__FLT_EPS : RE__DBL_EPS) *
                 (M + 0.5 * an->size) * an->size;
    RE__TAKE(an->he_edge, unsigned, 3 * (size_t)T);
    RE__TAKE(an->edges, re__edge_t, 3 * (size_t)T);
    mark = ar->used; /* the buckets are scratch of this step only */
    RE__TAKE(cnt, unsigned, (size_t)V + 1);
    RE__TAKE(key, unsigned long long, 3 * (size_t)T);
    re__edge_buckets(an, cnt, key);
    for (i = 0; i < V; i++) {
        unsigned s = i ? cnt[i - 1] : 0, e = cnt[i], j;
        re__sort_bucket(key, s, e);
        for (j = s; j < e;) { /* the half-edges to one higher vertex make an edge */
            unsigned hi = (unsigned)(key[j] >> 32);
            re__edge_t *ed = &an->edges[E];
            re_result_t rc;
            ed->v[0] = i;
            ed->v[1] = hi;
            ed->count = 0;
            ed->rounded = 0;
            for (; j < e && (unsigned)(key[j] >> 32) == hi; j++) {
                unsigned he = (unsigned)(key[j] & 0xFFFFFFFFu);
                if (ed->count < 2) ed->he[ed->count] = he;
                ed->count++;
                an->he_edge[he] = E;
            }
            if ((rc = re__classify_edge(an, ed, &widened)) != RE_OK) return rc;
            E++;
        }
    }
    an->E = E;
    ar->used = mark;
    if (widened) return re__flat_chains(an, ar);
    return RE_OK;
}

/* Step 2's counts and reports, once the edges are final (after step 2a). */
static void re__edge_reports(re__an_t *an)
{
    unsigned i;
    char msg[160];
    an->st.edges += an->E;
    for (i = 0; i < an->E; i++) {
        const re__edge_t *ed = &an->edges[i];
        unsigned a = re__vid(an, ed->v[0]), b = re__vid(an, ed->v[1]);
        switch (ed->cls) {
        case RE__E_FLAT: an->st.flat_edges++; break;
        case RE__E_CONVEX: an->st.convex_edges++; break;
        case RE__E_CONCAVE:
            an->st.concave_edges++;
            snprintf(msg, sizeof msg, "edge %u-%u is concave: left sharp", a, b);
            re__report(an, RE_REPORT_CONCAVE_EDGE, a, b, 0.0, msg);
            break;
        case RE__E_BOUNDARY:
            an->st.boundary_edges++;
            snprintf(msg, sizeof msg, "edge %u-%u is a boundary (open mesh%s): left sharp", a, b,
                     an->m->weld ? "" : ", or vertices repeated per face: see re_mesh_t.weld");
            re__report(an, RE_REPORT_BOUNDARY_EDGE, a, b, 0.0, msg);
            break;
        default:
            an->st.nonmanifold_edges++;
            snprintf(msg, sizeof msg, "edge %u-%u is non-manifold (%u triangles) or inconsistently wound: left sharp",
                     a, b, ed->count);
            re__report(an, RE_REPORT_NONMANIFOLD_EDGE, a, b, 0.0, msg);
            break;
        }
    }
}

/* Step 2a: one vertex per closed fan. Solids that touch at a vertex
   (voxel art's diagonal neighbours; touching parts welded with
   re_mesh_t.weld) share it, and a vertex with several fans has no corner:
   it would stay sharp, and with it (step 5) both solids' whole patches.
   The fans are the classes of the vertex's triangle corners joined across
   its manifold edges and across the pairs re__pair_fins() finds on edges
   of more than two triangles (solids touching along an edge). A fan is
   closed when each of its corners' two edges at the vertex is manifold or
   paired. Where a vertex has several fans, each closed fan gets a vertex
   of its own (ids from V on, which re__vid() maps back to it) and the open
   ones (an open mesh's, a loose triangle's, a fin's) keep it between them;
   where all are closed, the fan of its first triangle corner keeps it.
   The paired edges are manifold once their ends are split: step 2 runs
   again. Runs only when there is something to find: after step 2 when an
   edge has more than two triangles, else when step 4 finds a vertex with
   convex edges and several fans (free for the common mesh, which has
   neither; step 4 then runs again). */
static unsigned re__corner_at(const re__an_t *an, unsigned t, unsigned v)
{
    const unsigned *tr = an->tri + 3 * (size_t)t;
    return 3 * t + (tr[0] == v ? 0u : tr[1] == v ? 1u : 2u);
}
/* The half-edge arriving at corner c's vertex (a half-edge's id is its
   start corner's, so the one leaving it is c itself). */
static unsigned re__he_arriving(unsigned c) { return c % 3 ? c - 1 : c + 2; }
static int re__joins_fans(const re__edge_t *ed) { return ed->count == 2 && ed->cls != RE__E_NONMANIFOLD; }
enum { RE__FANS_ONE, RE__FANS_SPLIT, RE__FANS_SPLIT_OPEN }; /* per vertex in re__split_fans: one fan, several, some open */

/* Step 2a on an edge of more than two triangles (solids touching along
   it): its triangles, in angle order around it, pair up as the solids they
   bound, and the corners of each pair are joined at both its ends as if
   the pair were the edge's only triangles. Around a closed solid's edge
   its two triangles run it opposite ways, and seen along the edge (v[0]
   to v[1]) the one running it forward has its solid turning clockwise
   from it: its partner is the one before it. An edge whose triangles do
   not alternate (a fin, a book) or lie at one angle pairs nothing. The
   half-edges paired are marked in `paired`. */
#define RE__MAX_FIN 64 /* triangles on one edge, at most, for the pairing */
static void re__pair_fin(const re__an_t *an, unsigned *uf, unsigned char *paired, const unsigned *list, unsigned n)
{
    const re__edge_t *ed = &an->edges[an->he_edge[list[0]]];
    const double *a = an->pos + 3 * (size_t)ed->v[0], *b = an->pos + 3 * (size_t)ed->v[1];
    double e[3], u1[3], u2[3], ax[3] = {0, 0, 0}, ang[RE__MAX_FIN];
    unsigned h[RE__MAX_FIN], i, j, k;
    if (n % 2 || n > RE__MAX_FIN) return;
    re__sub(b, a, e);
    k = fabs(e[0]) <= fabs(e[1]) && fabs(e[0]) <= fabs(e[2]) ? 0u : fabs(e[1]) <= fabs(e[2]) ? 1u : 2u;
    ax[k] = 1;
    re__cross(e, ax, u1);
    re__cross(e, u1, u2);
    for (i = 0; i < n; i++) { /* insertion sort by the angle of the third corner around the edge */
        unsigned hh = list[i];
        const double *c = an->pos + 3 * (size_t)an->tri[re__he_arriving(hh)];
        double w[3], x;
        re__sub(c, a, w);
        x = atan2(re__dot(w, u2), re__dot(w, u1));
        for (j = i; j > 0 && ang[j - 1] > x; j--) ang[j] = ang[j - 1], h[j] = h[j - 1];
        ang[j] = x, h[j] = hh;
    }
    for (i = 0; i < n; i++) {
        int fwd = an->tri[h[i]] == ed->v[0], prev_fwd = an->tri[h[(i + n - 1) % n]] == ed->v[0];
        if (fwd == prev_fwd || ang[i] == ang[(i + n - 1) % n]) return;
    }
    for (i = 0; i < n; i++) {
        unsigned p = h[(i + n - 1) % n];
        if (an->tri[h[i]] != ed->v[0]) continue;
        for (k = 0; k < 2; k++) re__uf_join(uf, re__corner_at(an, h[i] / 3, ed->v[k]), re__corner_at(an, p / 3, ed->v[k]));
        paired[h[i]] = paired[p] = 1;
    }
}
/* re__pair_fin() on every edge of more than two triangles, its half-edges
   bucketed by edge. */
static re_result_t re__pair_fins(re__an_t *an, re__arena_t *ar, unsigned *uf, unsigned char *paired)
{
    unsigned N = 3 * an->T, E = an->E, c, i, *off, *list;
    size_t mark = ar->used;
    RE__TAKE(off, unsigned, (size_t)E + 1);
    memset(off, 0, sizeof(unsigned) * ((size_t)E + 1));
    for (c = 0; c < N; c++)
        if (!an->tbad[c / 3] && an->edges[an->he_edge[c]].count > 2) off[an->he_edge[c] + 1]++;
    for (i = 0; i < E; i++) off[i + 1] += off[i];
    RE__TAKE(list, unsigned, off[E]);
    for (c = 0; c < N; c++)
        if (!an->tbad[c / 3] && an->edges[an->he_edge[c]].count > 2) list[off[an->he_edge[c]]++] = c;
    for (i = 0; i < E; i++) /* off[i] is now the end of edge i's half-edges, which start at the end of i - 1's */
        if (an->edges[i].count > 2) re__pair_fin(an, uf, paired, list + (i ? off[i - 1] : 0), an->edges[i].count);
    ar->used = mark;
    return RE_OK;
}

static re_result_t re__split_fans(re__an_t *an, re__arena_t *ar)
{
    unsigned T = an->T, V = an->V, N = 3 * T, c, i, j, n_split = 0, n_new = 0, *uf, *first, *fan_id, *vorig;
    unsigned char *state, *paired, *fan_open;
    double *pos;
    size_t mark = ar->used;
    re_result_t rc;
    an->fans_split = 1;
    RE__TAKE(uf, unsigned, N);
    for (c = 0; c < N; c++) uf[c] = c;
    for (i = 0; i < an->E; i++) {
        const re__edge_t *ed = &an->edges[i];
        if (!re__joins_fans(ed)) continue;
        for (j = 0; j < 2; j++)
            re__uf_join(uf, re__corner_at(an, ed->he[0] / 3, ed->v[j]), re__corner_at(an, ed->he[1] / 3, ed->v[j]));
    }
    RE__TAKE(paired, unsigned char, N);
    memset(paired, 0, N);
    if (an->fins && (rc = re__pair_fins(an, ar, uf, paired)) != RE_OK) return rc;
    RE__TAKE(first, unsigned, V);
    RE__TAKE(state, unsigned char, V);
    memset(first, 0xFF, sizeof(unsigned) * V);
    memset(state, RE__FANS_ONE, V);
    for (c = 0; c < N; c++) {
        unsigned v = an->tri[c], r;
        if (an->tbad[c / 3]) continue;
        r = re__uf_find(uf, c);
        if (first[v] == RE__NONE) first[v] = r;
        else if (first[v] != r && state[v] == RE__FANS_ONE) state[v] = RE__FANS_SPLIT, n_split++;
    }
    if (!n_split) {
        ar->used = mark;
        return RE_OK;
    }
    RE__TAKE(fan_open, unsigned char, N);
    memset(fan_open, 0, N);
    for (c = 0; c < N; c++) { /* open: a corner's half-edge joined to no neighbour */
        unsigned v = an->tri[c], q;
        if (an->tbad[c / 3] || state[v] == RE__FANS_ONE) continue;
        for (q = 0; q < 2; q++) { /* the half-edge leaving v, the one arriving */
            unsigned h = q ? re__he_arriving(c) : c;
            if (!re__joins_fans(&an->edges[an->he_edge[h]]) && !paired[h])
                fan_open[re__uf_find(uf, c)] = 1, state[v] = RE__FANS_SPLIT_OPEN;
        }
    }
    RE__TAKE(fan_id, unsigned, N);
    RE__TAKE(vorig, unsigned, N);
    for (c = 0; c < N; c++) {
        unsigned v = an->tri[c], r;
        if (an->tbad[c / 3] || state[v] == RE__FANS_ONE) continue;
        r = re__uf_find(uf, c);
        if (state[v] == RE__FANS_SPLIT_OPEN ? fan_open[r] : r == first[v]) continue; /* keeps v */
        if (r == c) { /* a fan's lowest corner is its root (re__uf_join keeps the lower) */
            if ((unsigned long long)V + n_new >= 0x7FFFFFFFu) return re__fail(an, RE_ERR_TOO_LARGE, -1, "too many vertices");
            vorig[n_new] = v;
            fan_id[c] = V + n_new++;
        }
        an->tri[c] = fan_id[r];
    }
    if (!n_new) return RE_OK;
    RE__TAKE(pos, double, 3 * ((size_t)V + n_new));
    memcpy(pos, an->pos, sizeof(double) * 3 * (size_t)V);
    for (i = 0; i < n_new; i++) memcpy(pos + 3 * ((size_t)V + i), an->pos + 3 * (size_t)vorig[i], sizeof(double) * 3);
    an->pos = pos;
    an->vorig = vorig;
    an->V = V + n_new;
    return re__edges(an, ar); /* the same edges, their ends split (the step's scratch stays taken) */
}

/* Step 3: face planes = groups of triangles joined by flat edges; the
   largest triangle of a group gives its normal (the best-conditioned cross
   product). */
static re_result_t re__planes(re__an_t *an, re__arena_t *ar)
{
    unsigned T = an->T, t, *uf, *best;
    size_t mark;
    RE__TAKE(an->tplane, unsigned, T);
    RE__TAKE(an->planes, re__plane_t, T);
    mark = ar->used;
    RE__TAKE(uf, unsigned, T);
    RE__TAKE(best, unsigned, T);
    re__flat_groups(an, uf, best);
    an->n_planes = 0;
    for (t = 0; t < T; t++) an->tplane[t] = RE__NONE;
    for (t = 0; t < T; t++)
        if (!an->tbad[t] && uf[t] == t) {
            re__plane_t *p = &an->planes[an->n_planes];
            const double *n = an->tn + 3 * (size_t)best[t];
            p->n[0] = n[0];
            p->n[1] = n[1];
            p->n[2] = n[2];
            p->c = re__dot(n, an->pos + 3 * (size_t)an->tri[3 * best[t]]);
            an->tplane[t] = an->n_planes++;
        }
    for (t = 0; t < T; t++)
        if (!an->tbad[t]) an->tplane[t] = an->tplane[re__uf_find(uf, t)];
    ar->used = mark;
    return RE_OK;
}

/* Eroded-corner helpers (re__erode_corner). The planes are a corner's k
   face planes in fan order, N(s) = planes[pl[s]].n; u is per unit radius. */
#define RE__N(s) (an->planes[pl[s]].n)

/* u where the planes of slots i < j < l, shifted inward by 1, meet
   (Cramer's rule); 0 when they are near parallel. */
static int re__erode_solve(const re__an_t *an, const unsigned *pl, unsigned i, unsigned j, unsigned l, double u[3])
{
    double a[3], b[3], cc[3], det;
    unsigned q;
    re__cross(RE__N(j), RE__N(l), a);
    det = re__dot(RE__N(i), a);
    if (fabs(det) <= RE__PARALLEL_DET) return 0;
    re__cross(RE__N(l), RE__N(i), b);
    re__cross(RE__N(i), RE__N(j), cc);
    for (q = 0; q < 3; q++) u[q] = -(a[q] + b[q] + cc[q]) / det;
    return 1;
}

/* Is u inside every shifted plane, to RE__CORNER_EPS? Then *mk holds the
   planes through it (to the same tolerance) and *worst its largest
   violation. */
static int re__erode_feasible(const re__an_t *an, const unsigned *pl, unsigned k, const double u[3], unsigned long long *mk,
                              double *worst)
{
    double tol = RE__CORNER_EPS * re__max(1.0, re__len(u));
    unsigned g;
    *mk = 0;
    *worst = -HUGE_VAL;
    for (g = 0; g < k; g++) {
        double sg = re__dot(RE__N(g), u) + 1.0;
        *worst = re__max(*worst, sg);
        if (sg > tol) return 0;
        if (sg > -tol) *mk |= 1ull << g;
    }
    return 1;
}

/* Add the feasible vertex u of triple tri (i | j << 8 | l << 16) to the
   corner's *ns vertices, or merge it into one within RE__CORNER_MERGE (a
   near-concurrent cluster: the union of the planes through them, the most
   feasible point). 0 when a new vertex would pass cap. */
static int re__erode_keep(double *su, unsigned *stri, double *viol, unsigned long long *mask, unsigned *ns, unsigned cap,
                          const double u[3], unsigned long long mk, double worst, unsigned tri)
{
    double lim = RE__CORNER_MERGE * re__max(1.0, re__len(u));
    unsigned q;
    for (q = 0; q < *ns; q++) {
        double dd[3];
        re__sub(su + 3 * q, u, dd);
        if (re__len(dd) <= lim) break;
    }
    if (q < *ns) {
        mask[q] |= mk;
        if (worst < viol[q]) su[3 * q] = u[0], su[3 * q + 1] = u[1], su[3 * q + 2] = u[2], viol[q] = worst, stri[q] = tri;
        return 1;
    }
    if (*ns == cap) return 0;
    su[3 * q] = u[0], su[3 * q + 1] = u[1], su[3 * q + 2] = u[2];
    stri[q] = tri, viol[q] = worst, mask[q] = mk;
    (*ns)++;
    return 1;
}

/* Every plane triple, O(k^4): the reference method, and the fallback of
   re__erode_walk. Returns the vertex count, 0 if none or over cap. */
static unsigned re__erode_triples(const re__an_t *an, const unsigned *pl, unsigned k, double *su, unsigned *stri, double *viol,
                                  unsigned long long *mask, unsigned cap)
{
    unsigned i, j, l, ns = 0;
    for (i = 0; i < k; i++)
        for (j = i + 1; j < k; j++)
            for (l = j + 1; l < k; l++) {
                double u[3], worst;
                unsigned long long mk;
                if (!re__erode_solve(an, pl, i, j, l, u) || !re__erode_feasible(an, pl, k, u, &mk, &worst)) continue;
                if (!re__erode_keep(su, stri, viol, mask, &ns, cap, u, mk, worst, i | j << 8 | l << 16)) return 0;
            }
    return ns;
}

/* The plane among slots a+1 .. b-1 (cyclic, the far side of the diagonal
   a-b) that a point moving from w along d meets first, or RE__NONE. The
   shifted plane g is met at s = (-1 - n_g.w) / (n_g.d) when n_g.d > 0. */
static unsigned re__erode_next(const re__an_t *an, const unsigned *pl, unsigned k, unsigned a, unsigned b, const double w[3],
                               const double d[3])
{
    unsigned g, best = RE__NONE;
    double bs = HUGE_VAL;
    for (g = (a + 1) % k; g != b; g = (g + 1) % k) {
        double nd = re__dot(RE__N(g), d), sg;
        if (!(nd > 0)) continue;
        sg = (-1.0 - re__dot(RE__N(g), w)) / nd;
        if (sg < bs) bs = sg, best = g;
    }
    return best;
}

/* The same vertices in O(k^2), for any k <= RE_MAX_CORNER_PLANES. The
   normals of a convex corner, in fan order, are a convex spherical
   polygon; the eroded vertices are the triangles of its triangulation
   whose points violate no other plane (its spherical Delaunay
   triangulation), and the triangulation's dual is a tree. So walk it:
   coming back toward the corner along the eroded edge of planes 0 and 1
   (parallel to the mesh edge between them), the first other plane met
   closes the first triangle;
   across each of its sides that is a diagonal, the eroded edge of the
   side's two planes leads away from the triangle's third plane to the
   next triangle, the first plane met on the far side of the diagonal
   (re__erode_next). The k - 2 triples are then solved and checked as in
   re__erode_triples, in its order; 0 (use re__erode_triples) when a
   plane is missing, a solve is near parallel or a point fails the check:
   near-degenerate corners keep the reference method. Within a cluster
   of near-concurrent planes the two methods may keep different points of
   it (RE__CORNER_MERGE apart at most). */
/* The triple of plane slots x, y, z as a key that orders triples as the
   triples method visits them: smallest << 16 | middle << 8 | largest. */
static unsigned re__triple_key(unsigned x, unsigned y, unsigned z)
{
    unsigned lo = x < y ? x : y, hi = x < y ? y : x;
    if (z < lo) return z << 16 | lo << 8 | hi;
    if (z > hi) return lo << 16 | hi << 8 | z;
    return lo << 16 | z << 8 | hi;
}

static unsigned re__erode_walk(const re__an_t *an, const unsigned *pl, unsigned k, const double out0[3], double *su,
                               unsigned *stri, double *viol, unsigned long long *mask, unsigned cap)
{
    /* triangle t: its triple's key and point; tasks (x, y, z, t): the
       diagonal x -> y (fan order) of triangle t, whose third plane z lies
       outside x+1 .. y-1 */
    unsigned key[RE_MAX_CORNER_PLANES], order[RE_MAX_CORNER_PLANES], task[RE_MAX_CORNER_PLANES][4], nt = 0, sp = 0, i, j, ns = 0;
    double tu[RE_MAX_CORNER_PLANES][3], d[3], p[3], cs = re__dot(RE__N(0), RE__N(1));
    unsigned c;
    /* the eroded edge of planes 0 and 1 runs through p along the mesh edge
       between them (out0); coming back along it toward the corner, the
       first other plane met closes the first triangle */
    re__cross(RE__N(0), RE__N(1), d);
    if (re__dot(d, out0) >= 0) d[0] = -d[0], d[1] = -d[1], d[2] = -d[2];
    for (i = 0; i < 3; i++) p[i] = -(RE__N(0)[i] + RE__N(1)[i]) / (1 + cs);
    c = re__erode_next(an, pl, k, 1, 0, p, d);
    if (c == RE__NONE) return 0;
    key[nt] = re__triple_key(0, 1, c);
    if (!re__erode_solve(an, pl, 0, 1, c, tu[nt])) return 0;
    if (c > 2) task[sp][0] = 1, task[sp][1] = c, task[sp][2] = 0, task[sp++][3] = nt;
    if (c < k - 1) task[sp][0] = c, task[sp][1] = 0, task[sp][2] = 1, task[sp++][3] = nt;
    nt++;
    while (sp) {
        unsigned x, y, z, m, t;
        sp--;
        x = task[sp][0], y = task[sp][1], z = task[sp][2], t = task[sp][3];
        /* along the eroded edge of x and y, away from z's plane */
        re__cross(RE__N(x), RE__N(y), d);
        if (re__dot(RE__N(z), d) > 0) d[0] = -d[0], d[1] = -d[1], d[2] = -d[2];
        m = re__erode_next(an, pl, k, x, y, tu[t], d);
        if (m == RE__NONE || nt == k - 2 || sp + 2 > RE_MAX_CORNER_PLANES) return 0;
        key[nt] = re__triple_key(x, m, y);
        if (!re__erode_solve(an, pl, key[nt] >> 16, key[nt] >> 8 & 255u, key[nt] & 255u, tu[nt])) return 0;
        if ((x + 1) % k != m) task[sp][0] = x, task[sp][1] = m, task[sp][2] = y, task[sp++][3] = nt;
        if ((m + 1) % k != y) task[sp][0] = m, task[sp][1] = y, task[sp][2] = x, task[sp++][3] = nt;
        nt++;
    }
    if (nt != k - 2) return 0;
    /* checked and kept in the triples method's order */
    for (i = 0; i < nt; i++) {
        for (j = i; j > 0 && key[order[j - 1]] > key[i]; j--) order[j] = order[j - 1];
        order[j] = i;
    }
    for (i = 0; i < nt; i++) {
        unsigned t = order[i], kt = key[t];
        double worst;
        unsigned long long mk;
        if (!re__erode_feasible(an, pl, k, tu[t], &mk, &worst) ||
            !re__erode_keep(su, stri, viol, mask, &ns, cap, tu[t], mk, worst, kt >> 16 | (kt >> 8 & 255u) << 8 | (kt & 255u) << 16))
            return 0;
    }
    return ns;
}

/* Two distinct vertices of an eroded corner share at most two planes, so
   two kept vertices whose masks share three are one point to the masks'
   tolerance (RE__CORNER_EPS), however far apart the solves put them.
   Where creases are nearly flat (an off-centre roof apex of 6 to 8 planes
   at 179.8 to 179.99 degrees) the walk's vertices lie 1e-7 to 1e-5 apart,
   each within RE__CORNER_EPS of every plane: unmerged, every plane pair
   looked like an eroded edge, the extra cylinders outgrew their cap, and
   the corner and through it the whole solid stayed sharp, reported as an
   ill-conditioned corner (found by review, 2026-12-06). Merged into the
   one with the smaller violation, masks united; a corner whose triples
   are well conditioned has nothing to merge. */
static int re__three_bits(unsigned long long m)
{
    m &= m - 1;
    m &= m - 1;
    return m != 0;
}
static void re__erode_merge_same(double *su, unsigned *stri, double *viol, unsigned long long *mask, unsigned *ns)
{
    unsigned a, b, n = *ns;
    for (a = 0; a < n; a++)
        for (b = a + 1; b < n;) {
            if (!re__three_bits(mask[a] & mask[b])) { b++; continue; }
            mask[a] |= mask[b];
            if (viol[b] < viol[a]) su[3 * a] = su[3 * b], su[3 * a + 1] = su[3 * b + 1], su[3 * a + 2] = su[3 * b + 2], viol[a] = viol[b], stri[a] = stri[b];
            n--;
            su[3 * b] = su[3 * n], su[3 * b + 1] = su[3 * n + 1], su[3 * b + 2] = su[3 * n + 2];
            stri[b] = stri[n], viol[b] = viol[n], mask[b] = mask[n];
        }
    *ns = n;
}

/* Where each mesh-edge cylinder of corner c starts: the eroded vertex on
   planes j and j+1 (on: the kept vertices on each plane) nearest to the
   corner's vertex along the edge. 0 when an edge has none. */
static int re__erode_edge_starts(re__an_t *an, unsigned c, const double *su, unsigned ns, const unsigned long long *on,
                                 unsigned char *start)
{
    unsigned k = an->c_np[c], i, j, vc = an->c_vertex[c];
    const unsigned *ed = an->c_edges + an->c_pfirst[c];
    const double *v = an->pos + 3 * (size_t)vc;
    for (j = 0; j < k; j++) {
        const re__edge_t *e = &an->edges[ed[j]];
        unsigned other = e->v[0] == vc ? e->v[1] : e->v[0], best = RE__NONE;
        unsigned long long both = on[j] & on[(j + 1) % k];
        double dir[3], bp = HUGE_VAL;
        re__sub(an->pos + 3 * (size_t)other, v, dir);
        for (i = 0; i < ns; i++)
            if (both >> i & 1u) {
                double pr = re__dot(su + 3 * i, dir);
                if (pr < bp) bp = pr, best = i;
            }
        if (best == RE__NONE) return 0;
        start[j] = (unsigned char)best;
        an->edge_end[2 * ed[j] + (e->v[0] == vc ? 0u : 1u)] = (unsigned char)best;
    }
    return 1;
}

/* The extra cylinders of a corner of k planes pl: finite eroded edges
   between non-neighbouring planes, the pair's two extreme vertices along
   their line, into xs (4 entries each), *nx of them. 0 when more than cap. */
static int re__erode_extra_edges(const re__an_t *an, const unsigned *pl, unsigned k, const double *su, unsigned ns,
                                 const unsigned long long *on, unsigned cap, unsigned *xs, unsigned *nx)
{
    unsigned i, j;
    *nx = 0;
    for (i = 0; i < k; i++)
        for (j = i + 2; j < k; j++) {
            unsigned long long both = on[i] & on[j];
            unsigned lo = RE__NONE, hi = RE__NONE, q;
            double ax[3], plo = HUGE_VAL, phi = -HUGE_VAL, dd[3];
            if (i == 0 && j == k - 1) continue; /* neighbours through the wrap */
            if (!(both & (both - 1))) continue; /* fewer than two vertices on both planes: no edge (most pairs) */
            re__cross(RE__N(i), RE__N(j), ax);
            for (q = 0; q < ns; q++)
                if (both >> q & 1u) {
                    double pr = re__dot(su + 3 * q, ax);
                    if (pr < plo) plo = pr, lo = q;
                    if (pr > phi) phi = pr, hi = q;
                }
            if (lo == RE__NONE || lo == hi) continue;
            re__sub(su + 3 * lo, su + 3 * hi, dd);
            if (re__len(dd) <= RE__CORNER_EPS * re__max(1.0, re__len(su + 3 * lo))) continue;
            if (*nx == cap) return 0;
            xs[4 * *nx] = i, xs[4 * *nx + 1] = j, xs[4 * *nx + 2] = lo, xs[4 * *nx + 3] = hi;
            (*nx)++;
        }
    return 1;
}

/* The eroded corner at unit radius (issue item 1, exact corners). With the
   k face planes n_i.(x - v) = 0 around v shifted inward by 1, the local
   eroded polytope E_v = {u : n_i.u <= -1} has finite vertices where three
   or more shifted planes meet (the sphere centres) and finite edges
   between non-neighbouring planes (the extra cylinders); the edges between
   fan neighbours i, i+1 are rays along the mesh edges (the paper's cylinder
   axes, v + d*H, §3). Every plane passes through v, so E_v scales with r:
   spheres sit at v + r*u. A walk over the triangulation of the normals
   (re__erode_walk), or all plane triples (re__erode_triples), k <= 64. */
static int re__erode_corner(re__an_t *an, unsigned c)
{
    unsigned k = an->c_np[c], i, j, ns = 0, nx = 0, attempt;
    const unsigned *pl = an->c_planes + an->c_pfirst[c];
    const unsigned *ed = an->c_edges + an->c_pfirst[c];
    double *su = an->su + 3 * (size_t)an->c_sfirst[c];
    unsigned *stri = an->s_tri + an->c_sfirst[c];
    unsigned char *start = an->c_start + an->c_pfirst[c];
    unsigned *xs = an->c_x + 4 * (size_t)an->c_xfirst[c];
    unsigned cap = k; /* a k-plane corner has at most k - 2 eroded vertices (k = 2: one) */
    unsigned long long mask[RE_MAX_CORNER_PLANES];
    unsigned long long on[RE_MAX_CORNER_PLANES]; /* per plane: the kept vertices on it (bit i: vertex i; ns <= k <= 64) */
    double viol[RE_MAX_CORNER_PLANES]; /* worst plane violation of each kept vertex */
    const double *v = an->pos + 3 * (size_t)an->c_vertex[c];
    if (k == 2) {
        /* a vertex inside a straight convex edge: no corner, one sphere on the
           axis (at v + d*H) so the two cylinders meet */
        double cs = re__dot(RE__N(0), RE__N(1));
        for (i = 0; i < 3; i++) su[i] = -(RE__N(0)[i] + RE__N(1)[i]) / (1 + cs);
        stri[0] = RE__NONE; /* on two planes only: its centre is stored */
        mask[0] = 3ull;
        ns = 1;
    } else {
        /* the walk needs the outward direction of the mesh edge between
           planes 0 and 1 (edge ed[0]) */
        const re__edge_t *e0 = &an->edges[ed[0]];
        double out0[3];
        re__sub(an->pos + 3 * (size_t)(e0->v[0] == an->c_vertex[c] ? e0->v[1] : e0->v[0]), v, out0);
        ns = re__erode_walk(an, pl, k, out0, su, stri, viol, mask, cap);
        if (!ns) ns = re__erode_triples(an, pl, k, su, stri, viol, mask, cap);
        if (!ns) return 0;
    }
    /* first as found; if the edges do not fit (a mesh edge without its
       start, more extra cylinders than the cap), once more after merging
       the vertices that are one point (re__erode_merge_same) */
    for (attempt = 0;; attempt++) {
        if (attempt) re__erode_merge_same(su, stri, viol, mask, &ns);
        /* the masks transposed, for the pair tests: a plane pair's
           vertices are then one AND */
        for (j = 0; j < k; j++) on[j] = 0;
        for (i = 0; i < ns; i++)
            for (j = 0; j < k; j++) on[j] |= (mask[i] >> j & 1u) << i;
        if (re__erode_edge_starts(an, c, su, ns, on, start) && re__erode_extra_edges(an, pl, k, su, ns, on, cap, xs, &nx))
            break;
        if (attempt) return 0;
    }
    an->c_ns[c] = (unsigned char)ns;
    an->c_nx[c] = (unsigned char)nx;
    return 1;
}
#undef RE__N

/* Why step 4 left a vertex sharp (re__an_t.vwhy). */
enum { RE__WHY_NONE, RE__WHY_MIXED, RE__WHY_FANS, RE__WHY_COMPLEX, RE__WHY_NOT_SIMPLE, RE__WHY_ERODE };

/* From triangle t around vertex v, across the edge that arrives at v
   (forward) or the one that leaves it: the next triangle, RE__NONE at an
   edge of other than two triangles; *h is the half-edge crossed. */
static unsigned re__fan_step(const re__an_t *an, unsigned v, unsigned t, int forward, unsigned *h)
{
    unsigned c = re__corner_at(an, t, v);
    const re__edge_t *ed;
    *h = forward ? re__he_arriving(c) : c;
    ed = &an->edges[an->he_edge[*h]];
    return ed->count != 2 ? RE__NONE : (ed->he[0] == *h ? ed->he[1] : ed->he[0]) / 3;
}
/* The first triangle of v's first edge: where its fan walks start. */
static unsigned re__fan_start(const re__an_t *an, unsigned v) { return an->edges[an->vinc[an->voff[v]]].he[0] / 3; }

/* The closed fan around vertex v (deg edges) forward from re__fan_start:
   its size, its triangles in tfan and the half-edges crossed in hfan; 0
   when it is open or runs past deg. */
static unsigned re__walk_fan(const re__an_t *an, unsigned v, unsigned deg, unsigned *tfan, unsigned *hfan)
{
    unsigned t0 = re__fan_start(an, v), t = t0, m = 0, h, next;
    do {
        next = re__fan_step(an, v, t, 1, &h);
        if (m == deg || next == RE__NONE) return 0;
        tfan[m] = t, hfan[m++] = h;
        t = next;
    } while (t != t0);
    return m;
}
/* Whether the ntri triangles around v (its edges of at most two) form
   more than one fan: the fan through re__fan_start, walked both ways,
   holds fewer. */
static int re__several_fans(const re__an_t *an, unsigned v, unsigned ntri)
{
    unsigned t0 = re__fan_start(an, v), m = 1, h, t, dir;
    for (dir = 0; dir < 2; dir++) {
        for (t = t0; (t = re__fan_step(an, v, t, !dir, &h)) != RE__NONE && t != t0 && m <= ntri;) m++;
        if (t == t0) break; /* closed */
    }
    return m != ntri;
}

/* Step 4 from vertex v0 to v1: each candidate corner's fan, its planes and
   its eroded corner, written densely from plane, sphere and extra-cylinder
   slot off[0], off[1], off[2] on (advanced past what they use). The slot
   arrays are sized by the vertex degrees (an upper bound); each corner
   takes only what it uses: k plane slots, ns spheres, nx extra cylinders
   (its erosion may write up to k of each, past the end, before the next
   corner overwrites them). The used prefix is dense, so the build touches
   (and page-faults in) about half the memory of degree-sized slots; the
   fresh pages cost more than the arithmetic on them. tfan and hfan hold
   a fan (the largest degree). 0 when a vertex has several fans and step
   2a has not run yet (the step is then run again after it). */
static int re__corner_span(re__an_t *an, unsigned v0, unsigned v1, unsigned *tfan, unsigned *hfan, unsigned off[3])
{
    unsigned v, i, j;
    for (v = v0; v < v1; v++) {
        unsigned c = an->vcorner[v], deg, m, i0, k = 0, ok = 1, too_many = 0;
        if (c == RE__NONE) continue;
        deg = an->voff[v + 1] - an->voff[v];
        an->c_vertex[c] = v;
        an->c_pfirst[c] = off[0];
        an->c_sfirst[c] = off[1];
        an->c_xfirst[c] = off[2];
        an->c_np[c] = 0;
        an->c_ns[c] = an->c_nx[c] = 0;
        m = re__walk_fan(an, v, deg, tfan, hfan);
        if (m != deg) {
            if (!an->fans_split) return 0;
            an->vstate[v] = RE__V_SHARP;
            an->vwhy[v] = RE__WHY_FANS;
            continue;
        }
        for (i0 = 0; i0 < m; i0++)
            if (an->tplane[tfan[i0]] != an->tplane[tfan[(i0 + m - 1) % m]]) break;
        for (i = 0; i < m && ok; i++) {
            unsigned a = tfan[(i0 + i) % m], b = tfan[(i0 + i + 1) % m];
            unsigned e = an->he_edge[hfan[(i0 + i) % m]];
            int change = an->tplane[a] != an->tplane[b];
            if (change != (an->edges[e].cls == RE__E_CONVEX)) ok = 0;
            if (!change) continue;
            if (k == RE_MAX_CORNER_PLANES) { ok = 0, too_many = 1; break; }
            an->c_planes[an->c_pfirst[c] + k] = an->tplane[a];
            an->c_edges[an->c_pfirst[c] + k] = e;
            k++;
        }
        for (i = 0; i < k && ok; i++)
            for (j = i + 1; j < k; j++)
                if (an->c_planes[an->c_pfirst[c] + i] == an->c_planes[an->c_pfirst[c] + j]) ok = 0;
        an->c_np[c] = (unsigned char)(k > 255 ? 255 : k);
        if (too_many) {
            an->vstate[v] = RE__V_SHARP;
            an->vwhy[v] = RE__WHY_COMPLEX;
        } else if (!ok || k < 2) {
            an->vstate[v] = RE__V_SHARP;
            an->vwhy[v] = RE__WHY_NOT_SIMPLE;
        } else if (!re__erode_corner(an, c)) {
            an->vstate[v] = RE__V_SHARP;
            an->vwhy[v] = RE__WHY_ERODE;
        }
        off[0] += k;
        off[1] += an->c_ns[c];
        off[2] += an->c_nx[c];
    }
    return 1;
}

/* Step 4's corners split into spans of vertices on the host's threads
   (THREADS). Span w writes its slots from the degree sum of the corners
   before it (an upper bound of what they use), then each span's slots are
   moved down to follow the previous span's, so the arrays are the ones
   one span writes, byte for byte. */
#ifndef RE__SPAN_MIN_SLOTS /* plane slots per span at least: a span is worth a task (the fuzz target lowers it) */
#define RE__SPAN_MIN_SLOTS 4096u
#endif

typedef struct re__span_job_t {
    re__an_t *an;
    unsigned *fan;    /* 2 * fan_cap per span */
    unsigned fan_cap;
    unsigned v[RE_MAX_BUILD_TASKS + 1];   /* span w: vertices v[w] .. v[w + 1] - 1 */
    unsigned c[RE_MAX_BUILD_TASKS + 1];   /* its corners c[w] .. c[w + 1] - 1 */
    unsigned off[RE_MAX_BUILD_TASKS][3];  /* its slots: first, then past the used ones */
    unsigned base[RE_MAX_BUILD_TASKS][3];
    unsigned char ran[RE_MAX_BUILD_TASKS], whole[RE_MAX_BUILD_TASKS];
} re__span_job_t;

static void re__span_task(void *ctx, unsigned w)
{
    re__span_job_t *J = (re__span_job_t *)ctx;
    unsigned *fan = J->fan + 2 * (size_t)J->fan_cap * w;
    J->ran[w] = 1;
    J->whole[w] = (unsigned char)re__corner_span(J->an, J->v[w], J->v[w + 1], fan, fan + J->fan_cap, J->off[w]);
}

/* Runs fn(ctx, w) for w in [0, n), on the host's threads when n > 1; a
   task the host did not run (ran[w] still 0) fails the build. */
static re_result_t re__run_split(re__an_t *an, unsigned n, re_task_fn fn, void *ctx, const unsigned char *ran)
{
    unsigned w;
    char msg[80];
    if (n > 1) an->desc->parallel(an->desc->parallel_user, n, fn, ctx);
    else fn(ctx, 0);
    for (w = 0; w < n; w++)
        if (!ran[w]) {
            snprintf(msg, sizeof msg, "desc.parallel returned without running task %u of %u", w, n);
            return re__fail(an, RE_ERR_INVALID_ARG, -1, msg);
        }
    return RE_OK;
}

/* Moves n slots of `size` bytes each from slot `from` to slot `to` (<= from). */
static void re__slide(void *arr, size_t size, unsigned from, unsigned to, unsigned n)
{
    if (from != to && n) memmove((unsigned char *)arr + size * to, (unsigned char *)arr + size * from, size * n);
}

/* Spans of about equal degree sums (the work is about linear in it): span
   w starts at vertex J->v[w], corner J->c[w] and slot J->base[w] (the
   degree sum of the corners before it). */
static void re__span_layout(const re__an_t *an, unsigned n, re__span_job_t *J)
{
    unsigned v, c, w, q, slots = 0;
    for (v = 0, c = 0, w = 0; w < n; v++) {
        /* span w starts at the first vertex whose slots before it reach w / n of all (empty spans at the end) */
        while (w < n && (v == an->V || (unsigned long long)slots * n >= (unsigned long long)an->np_total * w)) {
            J->v[w] = v, J->c[w] = c, J->ran[w] = J->whole[w] = 0;
            for (q = 0; q < 3; q++) J->off[w][q] = J->base[w][q] = slots;
            w++;
        }
        if (v < an->V && an->vcorner[v] != RE__NONE) slots += an->voff[v + 1] - an->voff[v], c++;
    }
    J->v[n] = an->V, J->c[n] = an->nc;
}

/* Each span's slots moved down to follow the previous span's, and its
   corners' first slots with them. */
static void re__span_close(re__an_t *an, unsigned n, const re__span_job_t *J)
{
    unsigned w, c, q, dense[3] = {0, 0, 0};
    for (w = 0; w < n; w++) {
        unsigned used[3];
        for (q = 0; q < 3; q++) used[q] = J->off[w][q] - J->base[w][q];
        re__slide(an->c_planes, sizeof *an->c_planes, J->base[w][0], dense[0], used[0]);
        re__slide(an->c_edges, sizeof *an->c_edges, J->base[w][0], dense[0], used[0]);
        re__slide(an->c_start, sizeof *an->c_start, J->base[w][0], dense[0], used[0]);
        re__slide(an->su, 3 * sizeof *an->su, J->base[w][1], dense[1], used[1]);
        re__slide(an->s_tri, sizeof *an->s_tri, J->base[w][1], dense[1], used[1]);
        re__slide(an->c_x, 4 * sizeof *an->c_x, J->base[w][2], dense[2], used[2]);
        for (c = J->c[w]; c < J->c[w + 1]; c++) {
            an->c_pfirst[c] -= J->base[w][0] - dense[0];
            an->c_sfirst[c] -= J->base[w][1] - dense[1];
            an->c_xfirst[c] -= J->base[w][2] - dense[2];
        }
        for (q = 0; q < 3; q++) dense[q] += used[q];
    }
}

static re_result_t re__corner_spans(re__an_t *an, unsigned *fan0, unsigned fan_cap)
{
    re__span_job_t J;
    unsigned n = an->inner, w, off[3] = {0, 0, 0};
    re_result_t rc;
    if (n > an->np_total / RE__SPAN_MIN_SLOTS) n = an->np_total / RE__SPAN_MIN_SLOTS;
    if (n < 2) { /* on this thread */
        if (!re__corner_span(an, 0, an->V, fan0, fan0 + fan_cap, off)) an->fans_wanted = 1;
        return RE_OK;
    }
    J.an = an;
    J.fan_cap = fan_cap;
    if (!(J.fan = (unsigned *)RE_MALLOC(sizeof(unsigned) * 2 * (size_t)fan_cap * n, an->desc->alloc_ctx)))
        return re__fail(an, RE_ERR_OUT_OF_MEMORY, -1, "out of memory");
    re__span_layout(an, n, &J);
    rc = re__run_split(an, n, re__span_task, &J, J.ran);
    RE_FREE(J.fan, an->desc->alloc_ctx);
    if (rc != RE_OK) return rc;
    for (w = 0; w < n; w++)
        if (!J.whole[w]) {
            an->fans_wanted = 1;
            return RE_OK;
        }
    re__span_close(an, n, &J);
    return RE_OK;
}

/* Step 4: vertices. A corner candidate has only flat and convex edges, at
   least one convex, and a single closed fan; its distinct planes in fan
   order are eroded by re__erode_corner(). Mixed vertices stay sharp. A
   vertex with convex edges whose triangles form several fans (a candidate's
   fan walk, which the step does anyway, falls short; a mixed vertex is
   walked for it, re__several_fans): before step 2a has run, the step stops
   there with fans_wanted set (the caller splits the fans and runs it
   again). Reports wait for re__corner_reports(), so that a stopped run
   has made none. */
static re_result_t re__corners(re__an_t *an, re__arena_t *ar)
{
    size_t mark;
    unsigned V = an->V, E = an->E, i, v, maxdeg = 0;
    unsigned *tfan;
    re_result_t rc;
    RE__TAKE(an->voff, unsigned, (size_t)V + 1);
    RE__TAKE(an->vinc, unsigned, 2 * (size_t)E + 1);
    RE__TAKE(an->vstate, unsigned char, V);
    RE__TAKE(an->vcorner, unsigned, V);
    RE__TAKE(an->vwhy, unsigned char, V);
    RE__TAKE(an->edge_end, unsigned char, 2 * (size_t)E + 1);
    memset(an->voff, 0, sizeof(unsigned) * ((size_t)V + 1));
    for (i = 0; i < E; i++) an->voff[an->edges[i].v[0] + 1]++, an->voff[an->edges[i].v[1] + 1]++;
    for (v = 0; v < V; v++) an->voff[v + 1] += an->voff[v];
    for (i = 0; i < E; i++) {
        unsigned a = an->edges[i].v[0], b = an->edges[i].v[1];
        an->vinc[an->voff[a]++] = i;
        an->vinc[an->voff[b]++] = i;
        an->edge_end[2 * i] = an->edge_end[2 * i + 1] = 255;
    }
    for (v = V; v > 0; v--) an->voff[v] = an->voff[v - 1];
    an->voff[0] = 0;
    /* candidate count and plane slots */
    an->nc = 0;
    an->np_total = 0;
    for (v = 0; v < V; v++) {
        unsigned conv = 0, bad = 0, ends = 0, deg = an->voff[v + 1] - an->voff[v];
        an->vstate[v] = RE__V_NONE;
        an->vcorner[v] = RE__NONE;
        an->vwhy[v] = RE__WHY_NONE;
        for (i = an->voff[v]; i < an->voff[v + 1]; i++) {
            const re__edge_t *ed = &an->edges[an->vinc[i]];
            if (ed->cls == RE__E_CONVEX) conv++;
            else if (ed->cls != RE__E_FLAT) bad++;
            ends += ed->count; /* two per triangle at v */
        }
        if (conv && bad) {
            if (!an->fans_split && re__several_fans(an, v, ends / 2)) {
                an->fans_wanted = 1; /* a fan of its own may round once split */
                return RE_OK;
            }
            an->vstate[v] = RE__V_SHARP;
            an->vwhy[v] = RE__WHY_MIXED;
        } else if (conv) {
            an->vstate[v] = RE__V_CORNER;
            an->vcorner[v] = an->nc++;
            an->np_total += deg;
            if (deg > maxdeg) maxdeg = deg;
        }
    }
    RE__TAKE(an->c_vertex, unsigned, an->nc);
    RE__TAKE(an->c_pfirst, unsigned, an->nc);
    RE__TAKE(an->c_sfirst, unsigned, an->nc);
    RE__TAKE(an->c_xfirst, unsigned, an->nc);
    RE__TAKE(an->c_np, unsigned char, an->nc);
    RE__TAKE(an->c_ns, unsigned char, an->nc);
    RE__TAKE(an->c_nx, unsigned char, an->nc);
    RE__TAKE(an->c_planes, unsigned, an->np_total);
    RE__TAKE(an->c_edges, unsigned, an->np_total);
    RE__TAKE(an->c_start, unsigned char, an->np_total);
    RE__TAKE(an->su, double, 3 * (size_t)an->np_total);
    RE__TAKE(an->s_tri, unsigned, an->np_total);
    RE__TAKE(an->c_x, unsigned, 4 * (size_t)an->np_total);
    mark = ar->used; /* the fan walk's arrays are scratch of this step only */
    RE__TAKE(tfan, unsigned, 2 * (size_t)maxdeg + 2);
    rc = re__corner_spans(an, tfan, maxdeg + 1);
    ar->used = mark;
    return rc;
}

/* Step 4's counts and reports, in vertex order. */
static void re__corner_reports(re__an_t *an)
{
    unsigned v;
    char msg[192];
    for (v = 0; v < an->V; v++) {
        unsigned id, k;
        if (an->vwhy[v] == RE__WHY_NONE) continue;
        id = re__vid(an, v);
        k = an->vcorner[v] == RE__NONE ? 0u : an->c_np[an->vcorner[v]];
        switch (an->vwhy[v]) {
        case RE__WHY_MIXED:
            an->st.mixed_vertices++;
            snprintf(msg, sizeof msg, "vertex %u joins convex and concave/boundary/non-manifold edges: left sharp", id);
            re__report(an, RE_REPORT_MIXED_VERTEX, id, -1, 0.0, msg);
            break;
        case RE__WHY_FANS:
            an->st.mixed_vertices++;
            snprintf(msg, sizeof msg, "vertex %u is non-manifold (its triangles form more than one fan): left sharp", id);
            re__report(an, RE_REPORT_MIXED_VERTEX, id, -1, 0.0, msg);
            break;
        case RE__WHY_COMPLEX:
            snprintf(msg, sizeof msg, "vertex %u: corner too complex to round (more than %d face planes): left sharp", id,
                     RE_MAX_CORNER_PLANES);
            re__report(an, RE_REPORT_COMPLEX_CORNER, id, -1, (double)k, msg);
            break;
        case RE__WHY_NOT_SIMPLE:
            snprintf(msg, sizeof msg, "vertex %u: its %u face planes do not form a simple convex fan: left sharp", id, k);
            re__report(an, RE_REPORT_UNROUNDABLE_CORNER, id, -1, (double)k, msg);
            break;
        case RE__WHY_ERODE:
            snprintf(msg, sizeof msg,
                     "vertex %u: eroded corner of its %u face planes could not be resolved numerically (ill-conditioned plane triples): "
                     "left sharp", id, k);
            re__report(an, RE_REPORT_UNROUNDABLE_CORNER, id, -1, (double)k, msg);
            break;
        default: break;
        }
    }
}

/* Step 5: a convex edge is rounded when both ends are corners; a corner
   with a convex edge that cannot be rounded cannot be eroded consistently,
   so it turns sharp too, and so on along its patch. */
static re_result_t re__propagate(re__an_t *an, re__arena_t *ar)
{
    unsigned *queue, qn = 0, v, i;
    unsigned char *inq;
    char msg[160];
    size_t mark = ar->used;
    RE__TAKE(queue, unsigned, an->V + 1);
    RE__TAKE(inq, unsigned char, an->V + 1);
    for (v = 0; v < an->V; v++) {
        inq[v] = an->vstate[v] == RE__V_CORNER;
        if (inq[v]) queue[qn++] = v;
    }
    while (qn) {
        v = queue[--qn];
        inq[v] = 0;
        if (an->vstate[v] != RE__V_CORNER) continue;
        for (i = an->voff[v]; i < an->voff[v + 1]; i++) {
            const re__edge_t *e = &an->edges[an->vinc[i]];
            unsigned o = e->v[0] == v ? e->v[1] : e->v[0];
            if (e->cls == RE__E_CONVEX && an->vstate[o] != RE__V_CORNER) break;
        }
        if (i == an->voff[v + 1]) continue;
        an->vstate[v] = RE__V_SHARP;
        for (i = an->voff[v]; i < an->voff[v + 1]; i++) {
            const re__edge_t *e = &an->edges[an->vinc[i]];
            unsigned o = e->v[0] == v ? e->v[1] : e->v[0];
            if (e->cls == RE__E_CONVEX && an->vstate[o] == RE__V_CORNER && !inq[o]) inq[o] = 1, queue[qn++] = o;
        }
    }
    for (i = 0; i < an->E; i++) {
        re__edge_t *e = &an->edges[i];
        if (e->cls != RE__E_CONVEX) continue;
        e->rounded = an->vstate[e->v[0]] == RE__V_CORNER && an->vstate[e->v[1]] == RE__V_CORNER;
        if (!e->rounded) {
            snprintf(msg, sizeof msg, "convex edge %u-%u left sharp: a corner of its patch is mixed, open or too complex",
                     re__vid(an, e->v[0]), re__vid(an, e->v[1]));
            re__report(an, RE_REPORT_SHARP_PATCH_EDGE, re__vid(an, e->v[0]), re__vid(an, e->v[1]), 0.0, msg);
        } else
            an->st.rounded_edges++;
    }
    ar->used = mark;
    return RE_OK;
}

static double re__edge_request(const re__an_t *an, const re__edge_t *e)
{
    double r = HUGE_VAL;
    unsigned q;
    if (an->m->edge_radius)
        for (q = 0; q < 2 && q < e->count; q++) {
            unsigned src = an->tsrc[e->he[q]];
            if (src != RE__NONE && an->m->edge_radius[src] > 0) r = re__min(r, an->m->edge_radius[src]);
        }
    return r == HUGE_VAL ? an->m->radius : r;
}

/* A straight rounded edge split by vertices where only its two face planes
   meet (k = 2) is one rounding cylinder: from corner c along edge e, step
   over such vertices to the corner at the far end of the chain. Returns it
   (RE__NONE for a closed chain) and the chain's last edge in *last. */
static unsigned re__chain_end(const re__an_t *an, unsigned c, unsigned e, unsigned *last)
{
    unsigned v = an->c_vertex[c], steps = 0;
    for (;;) {
        const re__edge_t *ed = &an->edges[e];
        unsigned w = ed->v[0] == v ? ed->v[1] : ed->v[0], cw = an->vcorner[w], q, nx = RE__NONE;
        *last = e;
        if (an->c_np[cw] != 2) return cw;
        if (cw == c || ++steps > an->V) return RE__NONE;
        for (q = an->voff[w]; q < an->voff[w + 1]; q++)
            if (an->vinc[q] != e && an->edges[an->vinc[q]].rounded) nx = an->vinc[q];
        if (nx == RE__NONE) return RE__NONE;
        v = w, e = nx;
    }
}

/* Unit-radius offset of the sphere where rounded edge e meets corner c. */
static const double *re__edge_su(const re__an_t *an, unsigned c, unsigned e)
{
    const re__edge_t *ed = &an->edges[e];
    return an->su + 3 * (size_t)(an->c_sfirst[c] + an->edge_end[2 * e + (ed->v[0] == an->c_vertex[c] ? 0u : 1u)]);
}

/* The bound corner c puts on its patch's radius (request req): its spheres
   must stay inside the shifted planes of the neighbouring corners, and
   along a straight chain the chain must be as long as its two set-backs.
   Returns the first smallest one in the order the planes are met, with
   what limits it in lim[0] (a vertex) and lim[1] (the chain's far vertex,
   -1 for a plane), HUGE_VAL if none. pmark holds c + 1 for the planes
   already seen from c (caller's scratch, per plane). */
static double re__corner_bound(const re__an_t *an, unsigned c, double req, unsigned *pmark, long long lim[2])
{
    unsigned v = an->c_vertex[c], q, s, g;
    double umax = 0, skip, spread = 0, slack, best = HUGE_VAL;
    const double *u0 = an->su + 3 * (size_t)an->c_sfirst[c];
    lim[0] = lim[1] = -1;
    /* a vertex inside a straight edge: its sphere ends up between the
       chain's end spheres (re__chain_axes), which are checked */
    if (an->vstate[v] != RE__V_CORNER || an->c_np[c] == 2) return best;
    /* a plane farther than req (1 + |u|) from v cannot bound the radius
       below the request (n.u + 1 <= |u| + 1), so it cannot clamp it:
       skipped before its plane and sphere loops */
    for (s = 0; s < an->c_ns[c]; s++) {
        double du[3];
        umax = re__max(umax, re__len(u0 + 3 * (size_t)s));
        re__sub(u0 + 3 * (size_t)s, u0, du);
        spread = re__max(spread, re__len(du));
    }
    skip = req * (umax + 1) * (1 + 1e-9);
    /* every n.u + 1 below is at most n.u0 + 1 + spread (|n| = 1), up to
       the rounding of the dot products (RE__SIDE_ULPS of the magnitudes) */
    slack = RE__SIDE_ULPS * (2 + umax + spread);
    for (s = 0; s < an->c_np[c]; s++) pmark[an->c_planes[an->c_pfirst[c] + s]] = c + 1;
    for (q = an->voff[v]; q < an->voff[v + 1]; q++) {
        const re__edge_t *e = &an->edges[an->vinc[q]];
        unsigned w, cw;
        if (!e->rounded) continue;
        w = e->v[0] == v ? e->v[1] : e->v[0];
        cw = an->vcorner[w];
        if (an->c_np[cw] == 2) {
            /* a straight chain: its far corner bounds the radius, by the
               chain's length (the edge bound) and by its planes */
            unsigned last, cb = re__chain_end(an, c, an->vinc[q], &last);
            double dir[3], du[3], L, den;
            if (cb == RE__NONE) continue;
            w = an->c_vertex[cb];
            cw = cb;
            re__sub(an->pos + 3 * (size_t)w, an->pos + 3 * (size_t)v, dir);
            L = re__len(dir);
            re__sub(re__edge_su(an, c, an->vinc[q]), re__edge_su(an, cb, last), du);
            den = re__dot(du, dir) / L;
            if (den > 0 && L / den < best) best = L / den, lim[0] = re__vid(an, v), lim[1] = re__vid(an, w);
        }
        for (g = 0; g < an->c_np[cw]; g++) {
            unsigned pi = an->c_planes[an->c_pfirst[cw] + g];
            const re__plane_t *pl = &an->planes[pi];
            double b, amax = 0;
            /* a plane of c itself, or one seen from another neighbour
               already (it would give the same bound again) */
            if (pmark[pi] == c + 1) continue;
            pmark[pi] = c + 1;
            b = pl->c - re__dot(pl->n, an->pos + 3 * (size_t)v);
            if (b < 0 || b >= skip) continue; /* not locally convex, or too far to matter */
            /* nor does a plane whose bound b / amax is at least the
               request by the bound on amax from the first sphere (on a
               fine mesh nearly every one: the corner's spheres lie
               close together, and the plane barely leans in) */
            if (b >= req * (re__dot(pl->n, u0) + 1 + spread + slack) * (1 + 1e-9)) continue;
            /* b / a decreases with a (and so does its rounding), so the
               sphere that leans farthest into the plane bounds r */
            for (s = 0; s < an->c_ns[c]; s++)
                amax = re__max(amax, re__dot(pl->n, an->su + 3 * (size_t)(an->c_sfirst[c] + s)) + 1.0);
            if (amax > 0 && b / amax < best) best = b / amax, lim[0] = re__vid(an, v), lim[1] = -1;
        }
    }
    return best;
}

/* Every corner's bound (re__corner_bound), in spans of corners on the
   host's threads (THREADS), each span with plane marks of its own. */
#ifndef RE__SPAN_MIN_CORNERS /* corners per span at least */
#define RE__SPAN_MIN_CORNERS 2048u
#endif

typedef struct re__bound_job_t {
    const re__an_t *an;
    const double *req;      /* per patch root: the requested radius */
    const unsigned *patch;  /* per corner: its patch root */
    double *bound;          /* per corner: its bound */
    long long *lim;         /* per corner: 2, what limits it */
    unsigned *pmark[RE_MAX_BUILD_TASKS];
    unsigned c[RE_MAX_BUILD_TASKS + 1]; /* span w: corners c[w] .. c[w + 1] - 1 */
    unsigned char ran[RE_MAX_BUILD_TASKS];
} re__bound_job_t;

static void re__bound_task(void *ctx, unsigned w)
{
    re__bound_job_t *J = (re__bound_job_t *)ctx;
    unsigned c;
    J->ran[w] = 1;
    for (c = J->c[w]; c < J->c[w + 1]; c++)
        J->bound[c] = re__corner_bound(J->an, c, J->req[J->patch[c]], J->pmark[w], J->lim + 2 * (size_t)c);
}

static re_result_t re__corner_bounds(re__an_t *an, re__bound_job_t *J, unsigned *pmark0)
{
    unsigned n = an->inner, w;
    size_t marks = (size_t)an->n_planes + 1;
    unsigned *more = NULL;
    re_result_t rc;
    if (n > an->nc / RE__SPAN_MIN_CORNERS) n = an->nc / RE__SPAN_MIN_CORNERS;
    if (n < 1) n = 1;
    if (n > 1) {
        if (!(more = (unsigned *)RE_MALLOC(sizeof(unsigned) * marks * (n - 1), an->desc->alloc_ctx)))
            return re__fail(an, RE_ERR_OUT_OF_MEMORY, -1, "out of memory");
        memset(more, 0, sizeof(unsigned) * marks * (n - 1));
    }
    for (w = 0; w < n; w++) {
        J->c[w] = (unsigned)((unsigned long long)an->nc * w / n);
        J->pmark[w] = w ? more + marks * (w - 1) : pmark0;
        J->ran[w] = 0;
    }
    J->c[n] = an->nc;
    rc = re__run_split(an, n, re__bound_task, J, J->ran);
    if (more) RE_FREE(more, an->desc->alloc_ctx);
    return rc;
}

/* Step 6: one radius per patch (corners linked by rounded edges) and its
   largest valid value. Everything at a corner scales linearly with r, so
   each constraint gives a bound r <= b directly:
   - an edge must be at least as long as its two set-backs (the cylinder
     from s_a to s_b must not turn over);
   - a corner's spheres must stay inside the shifted planes of the
     neighbouring corners (a slab thinner than 2r, a short prism). */
/* Per patch (indexed by its root corner in uf): the radius asked (the
   smallest along it), whether edges asked different ones, and the largest
   radius that fits with the corners or edge that limit it. */
typedef struct re__patch_limits_t {
    double *req, *rmax;
    long long *lim0, *lim1; /* the limiting edge's vertices, or the vertex and -1 */
    long long *ltri;        /* the triangle of another plane that limits it (re__reach_bounds), or -1 */
    unsigned char *mism;
} re__patch_limits_t;

/* Joins each rounded edge's corners into patches (uf), and gathers each
   patch's request and the bound its edges put on it: an edge no longer
   than its two set-backs (edges of straight chains are bounded from the
   chain's ends, by re__corner_bounds). */
static re_result_t re__patch_requests(re__an_t *an, unsigned *uf, re__patch_limits_t *P)
{
    unsigned i;
    char msg[160];
    for (i = 0; i < an->E; i++) {
        const re__edge_t *e = &an->edges[i];
        double rq;
        if (!e->rounded) continue;
        rq = re__edge_request(an, e);
        if (!(rq > 0) || !isfinite(rq)) {
            snprintf(msg, sizeof msg, "edge %u-%u has radius %g (must be finite and > 0)", re__vid(an, e->v[0]), re__vid(an, e->v[1]), rq);
            return re__fail(an, RE_ERR_BAD_RADIUS, re__vid(an, e->v[0]), msg);
        }
        re__uf_join(uf, an->vcorner[e->v[0]], an->vcorner[e->v[1]]);
    }
    for (i = 0; i < an->E; i++) {
        const re__edge_t *e = &an->edges[i];
        unsigned p, ca, cb;
        double rq, L, den, dir[3], du[3];
        if (!e->rounded) continue;
        ca = an->vcorner[e->v[0]];
        cb = an->vcorner[e->v[1]];
        p = re__uf_find(uf, ca);
        rq = re__edge_request(an, e);
        if (P->req[p] != HUGE_VAL && P->req[p] != rq) P->mism[p] = 1;
        P->req[p] = re__min(P->req[p], rq);
        if (an->c_np[ca] == 2 || an->c_np[cb] == 2) continue; /* part of a chain: bounded from its ends */
        re__sub(an->pos + 3 * (size_t)e->v[1], an->pos + 3 * (size_t)e->v[0], dir);
        L = re__len(dir);
        re__sub(an->su + 3 * (size_t)(an->c_sfirst[ca] + an->edge_end[2 * i]),
                an->su + 3 * (size_t)(an->c_sfirst[cb] + an->edge_end[2 * i + 1]), du);
        den = re__dot(du, dir) / L;
        if (den > 0 && L / den < P->rmax[p])
            P->rmax[p] = L / den, P->lim0[p] = re__vid(an, e->v[0]), P->lim1[p] = re__vid(an, e->v[1]);
    }
    return RE_OK;
}

/* ---- Step 6b (docs: construction step 7, "the rest of the object") -------

   The bounds above look at a corner's neighbours only. A face of another
   part of the same object can lie where a rounding removes material: a
   pocket 0.1 from a rounded edge of r = 0.3 has its wall inside the
   edge's removed volume, and the rounding would cut through it.

   Only objects that can have such faces are checked. A closed object whose
   every edge is flat or a rounded convex edge is locally convex everywhere,
   so each of its closed parts is a convex solid (Tietze's theorem): its
   removed volumes lie inside that solid and nothing of the object is there.
   Any other object (a concave edge, a boundary, a fin, a convex edge left
   sharp) is checked against its own triangles.

   The zones, each growing linearly with r (so a face entering the zone at r
   bounds the patch's radius by where it enters):
   - Edge e with planes n0, n1: the cylinder is tangent to both planes at
     depths (0, r k) and (r k, 0), k = 1 - n0.n1, and its removed volume
     lies between the edge and the arc, so on the edge's side of the chord
     between those tangent lines: depth d0 + d1 <= r k, with d0, d1 >= 0
     inside every face plane at its two end corners and between the
     planes across the edge at its ends (the cylinder beyond them lies
     within the corners' balls, below). Bound: the least (d0 + d1) / k
     over the part of a face inside those planes.
   - Corner c: its spheres' centres lie at v + r u, so its removed volume
     lies within r (1 + max |u|) of v, inside its own planes and those of
     the corners its rounded edges lead to. Bound: the least
     |p - v| / (1 + max |u|) over the part of a face inside them.
   For faces of the patch's own shell (triangles joined to it across
   edges) the zones are closed: a face that only touches one of their
   planes from outside (a boss standing on the strip a rounding removes)
   bounds the radius too. For other shells they are open: a solid that
   only touches this one (at a vertex, step 2a, or resting on a face)
   gives up that contact, as when it is built apart (and as in an object
   not checked), while a part of it inside the zone still bounds the
   radius. "On a plane" means within RE__REACH_ULPS of the object's
   magnitude (RE__REACH_FLT_ULPS for float positions). Faces of the patch
   itself (a plane of any of its corners) are left to the local bounds
   above: a patch's faces are bounded by its rounded edges, locally
   convex, and would otherwise be caught by the corner's ball (the far
   sides of a fine prism). So are planes shared by several patches. The
   bounds are conservative: the
   chord zone holds the removed volume with room, the corner's ball more
   so, so a face near a corner can clamp the radius to below what would
   fit. Candidates come from a bounding-volume tree over the triangles'
   boxes, built only for the objects checked, queried piece by piece
   along a long edge. */
#define RE__REACH_ULPS (64.0 * RE__DBL_EPS)
/* the same for float positions, in units of FLT_EPSILON (they were
   rounded to float before the planes were fitted) */
#define RE__REACH_FLT_ULPS 4.0
/* triangles per leaf of the tree */
#define RE__TBVH_LEAF 4u
/* vertices of a triangle clipped by up to 4 RE_MAX_CORNER_PLANES + 3 planes */
#define RE__CLIP_MAX (6u + 4u * RE_MAX_CORNER_PLANES)
/* planes a corner's zone is clipped by: its own and its neighbours' */
#define RE__CORNER_CLIP_PLANES (4u * RE_MAX_CORNER_PLANES)

/* Per plane, the patch whose corners have it (RE__NONE: none; RE__MULTI:
   several): such faces are left to the local bounds (see above). */
#define RE__MULTI (RE__NONE - 1u)
/* no patch met yet (re__reach_bounds) */
#define RE__UNSEEN (RE__NONE - 2u)

typedef struct re__tbvh_node_t {
    double lo[3], hi[3];
    unsigned first, count; /* a leaf's triangles: idx[first .. first + count); count 0: children node + 1 and first */
    unsigned patch;        /* the patch of all its triangles (plane_patch), RE__MULTI when they differ */
} re__tbvh_node_t;

typedef struct re__tbvh_t {
    re__tbvh_node_t *nodes;
    unsigned *idx;  /* triangles, leaf by leaf */
    double *box;    /* 6 per triangle: lo, hi */
    unsigned *cand; /* a query's answer */
} re__tbvh_t;

/* 1 when the object may have faces inside a removed volume (see above). */
static int re__may_reach_own_faces(const re__an_t *an)
{
    unsigned i;
    for (i = 0; i < an->E; i++) {
        const re__edge_t *e = &an->edges[i];
        if (e->cls != RE__E_FLAT && !(e->cls == RE__E_CONVEX && e->rounded)) return 1;
    }
    return 0;
}

/* The centroid coordinate of triangle idx[i] along axis a (times 2). */
static double re__tbvh_key(const re__tbvh_t *B, unsigned i, unsigned a)
{
    const double *b = B->box + 6 * (size_t)B->idx[i];
    return b[a] + b[3 + a];
}

/* Reorders idx[lo .. hi) so that idx[mid] holds the triangle of median key
   along axis a, smaller keys before it and larger after (quickselect). */
static void re__tbvh_select(re__tbvh_t *B, unsigned lo, unsigned hi, unsigned mid, unsigned a)
{
    while (hi - lo > 1) {
        double pivot = re__tbvh_key(B, (lo + hi) / 2, a);
        unsigned i = lo, j = hi - 1, t;
        while (i <= j) {
            while (re__tbvh_key(B, i, a) < pivot) i++;
            while (re__tbvh_key(B, j, a) > pivot) j--;
            if (i <= j) {
                t = B->idx[i], B->idx[i] = B->idx[j], B->idx[j] = t;
                i++;
                if (j == 0) break;
                j--;
            }
        }
        if (mid <= j) hi = j + 1;
        else if (mid >= i) lo = i;
        else return;
    }
}

/* The tree over the triangles that some patch must be checked against:
   with a plane (not skipped), not on planes of several patches, and not on
   the planes of `only` (the object's one patch, RE__NONE if it has more).
   Median splits along the longest axis of the boxes' extent. Returns its
   node count. */
static unsigned re__tbvh_build(const re__an_t *an, re__tbvh_t *B, const unsigned *plane_patch, unsigned only)
{
    unsigned t, n = 0, nn = 1, k, sp = 0;
    unsigned stack[2 * 64][2], node_of[2 * 64]; /* depth-first: at most depth + 1 entries */
    for (t = 0; t < an->T; t++) {
        double *b = B->box + 6 * (size_t)t;
        const double *p0, *p1, *p2;
        unsigned pp;
        if (an->tbad[t] || an->tplane[t] == RE__NONE) continue;
        pp = plane_patch[an->tplane[t]];
        if (pp == RE__MULTI || (only != RE__NONE && pp == only)) continue;
        p0 = an->pos + 3 * (size_t)an->tri[3 * (size_t)t];
        p1 = an->pos + 3 * (size_t)an->tri[3 * (size_t)t + 1];
        p2 = an->pos + 3 * (size_t)an->tri[3 * (size_t)t + 2];
        for (k = 0; k < 3; k++) {
            b[k] = re__min(p0[k], re__min(p1[k], p2[k]));
            b[3 + k] = re__max(p0[k], re__max(p1[k], p2[k]));
        }
        B->idx[n++] = t;
    }
    if (!n) return 0;
    stack[0][0] = 0, stack[0][1] = n, node_of[0] = 0, sp = 1;
    while (sp) {
        unsigned lo, hi, id, i, a = 0;
        re__tbvh_node_t *nd;
        sp--;
        lo = stack[sp][0], hi = stack[sp][1], id = node_of[sp];
        nd = &B->nodes[id];
        for (k = 0; k < 3; k++) nd->lo[k] = HUGE_VAL, nd->hi[k] = -HUGE_VAL;
        nd->patch = plane_patch[an->tplane[B->idx[lo]]];
        for (i = lo; i < hi; i++) {
            const double *b = B->box + 6 * (size_t)B->idx[i];
            for (k = 0; k < 3; k++) nd->lo[k] = re__min(nd->lo[k], b[k]), nd->hi[k] = re__max(nd->hi[k], b[3 + k]);
            if (plane_patch[an->tplane[B->idx[i]]] != nd->patch) nd->patch = RE__MULTI;
        }
        /* median splits halve the count: the depth stays under 64 */
        if (hi - lo <= RE__TBVH_LEAF || sp + 2 > 2 * 64) {
            nd->first = lo, nd->count = hi - lo;
            continue;
        }
        for (k = 1; k < 3; k++)
            if (nd->hi[k] - nd->lo[k] > nd->hi[a] - nd->lo[a]) a = k;
        re__tbvh_select(B, lo, hi, (lo + hi) / 2, a);
        nd->count = 0;
        nd->first = nn; /* children: nn (left half) and nn + 1 */
        stack[sp][0] = (lo + hi) / 2, stack[sp][1] = hi, node_of[sp] = nn + 1, sp++;
        stack[sp][0] = lo, stack[sp][1] = (lo + hi) / 2, node_of[sp] = nn, sp++;
        nn += 2;
    }
    return nn;
}

/* The triangles whose boxes meet [lo, hi], into B->cand; returns how many.
   Subtrees whose triangles all belong to patch `skip` are left out: a
   patch's own faces are never candidates, and a fine patch's fans would
   otherwise be met by each of its edges (a 6 000-gon prism with a far box
   in one object: 2.8 s before, construction step 7). */
static unsigned re__tbvh_query(const re__tbvh_t *B, const double lo[3], const double hi[3], unsigned skip)
{
    unsigned stack[2 * 64 + 2], sp = 1, n = 0, i, k;
    stack[0] = 0;
    while (sp) {
        const re__tbvh_node_t *nd = &B->nodes[stack[--sp]];
        int out = nd->patch == skip;
        for (k = 0; k < 3; k++) out |= nd->lo[k] > hi[k] || nd->hi[k] < lo[k];
        if (out) continue;
        if (nd->count) {
            for (i = nd->first; i < nd->first + nd->count; i++) {
                const double *b = B->box + 6 * (size_t)B->idx[i];
                int o = 0;
                for (k = 0; k < 3; k++) o |= b[k] > hi[k] || b[3 + k] < lo[k];
                if (!o) B->cand[n++] = B->idx[i];
            }
        } else {
            stack[sp++] = nd->first;
            stack[sp++] = nd->first + 1;
        }
    }
    return n;
}

/* Triangle t clipped to the part inside every plane of pl[0 .. np)
   (depth c - n.p at least -slack: slack > 0 makes the planes closed,
   slack < 0 open): its vertices into poly (3 per vertex, room for
   RE__CLIP_MAX), their count returned (0: nothing left; 1 or 2: it only
   touches there). */
static unsigned re__clip_inside(const re__an_t *an, unsigned t, const re__plane_t *pls, unsigned np, double slack,
                                double *poly, double *tmp)
{
    unsigned n = 3, j, i, k;
    for (k = 0; k < 3; k++)
        for (j = 0; j < 3; j++) poly[3 * k + j] = an->pos[3 * (size_t)an->tri[3 * (size_t)t + k] + j];
    for (j = 0; j < np && n >= 1; j++) {
        const re__plane_t *pl = &pls[j];
        unsigned m = 0;
        for (i = 0; i < n; i++) {
            const double *a = poly + 3 * i, *b = poly + 3 * ((i + 1) % n);
            double da = pl->c - re__dot(pl->n, a) + slack, db = pl->c - re__dot(pl->n, b) + slack;
            if (da >= 0 && m < RE__CLIP_MAX) tmp[3 * m] = a[0], tmp[3 * m + 1] = a[1], tmp[3 * m + 2] = a[2], m++;
            if ((da >= 0) != (db >= 0) && m < RE__CLIP_MAX) {
                double s = da / (da - db);
                for (k = 0; k < 3; k++) tmp[3 * m + k] = a[k] + s * (b[k] - a[k]);
                m++;
            }
        }
        memcpy(poly, tmp, sizeof(double) * 3 * m);
        n = m;
    }
    return n;
}

/* Squared distance from p to the segment a -> a + ab, with inv_l2 = 1 / |ab|^2
   (0 for a point): the walk tests many corners against one segment, so the
   division is hoisted out (it was the hottest instruction of re_query). */
static double re__dist2_segment(const double p[3], const double a[3], const double ab[3], double inv_l2)
{
    double ap[3], t, q[3];
    re__sub(p, a, ap);
    t = re__dot(ap, ab) * inv_l2;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    re__madd(a, t, ab, q);
    re__sub(p, q, q);
    return re__dot(q, q);
}

/* Distance from v to the convex planar polygon poly (n vertices; 1: a
   point, 2: a segment). */
static double re__dist_polygon(const double *poly, unsigned n, const double v[3])
{
    double nrm[3] = {0, 0, 0}, best = HUGE_VAL, d[3], len;
    unsigned i, inside = 1;
    for (i = 1; i + 1 < n; i++) {
        double a[3], b[3], c[3];
        re__sub(poly + 3 * i, poly, a);
        re__sub(poly + 3 * (i + 1), poly, b);
        re__cross(a, b, c);
        nrm[0] += c[0], nrm[1] += c[1], nrm[2] += c[2];
    }
    len = re__len(nrm);
    for (i = 0; i < n; i++) {
        const double *a = poly + 3 * i, *b = poly + 3 * ((i + 1) % n);
        double ab[3], av[3], c[3], L2;
        re__sub(b, a, ab);
        re__sub(v, a, av);
        re__cross(ab, av, c);
        if (len > 0 && re__dot(c, nrm) < 0) inside = 0;
        L2 = re__dot(ab, ab);
        best = re__min(best, sqrt(re__dist2_segment(v, a, ab, L2 > 0 ? 1 / L2 : 0)));
    }
    if (inside && len > 0) {
        re__sub(v, poly, d);
        best = re__min(best, fabs(re__dot(d, nrm)) / len);
    }
    return best;
}

/* The bound the object's other faces put on rounded edge i of patch p
   (see above), at most bmax (the patch's smallest so far); *tri the
   limiting triangle. */
static double re__edge_reach_bound(const re__an_t *an, re__tbvh_t *B, const unsigned *plane_patch, const unsigned *shell,
                                   unsigned p, unsigned i, double req, double bmax, double tol, long long *tri, double *poly,
                                   double *tmp)
{
    const re__edge_t *e = &an->edges[i];
    const re__plane_t *P0 = &an->planes[an->tplane[e->he[0] / 3]], *P1 = &an->planes[an->tplane[e->he[1] / 3]];
    const double *va = an->pos + 3 * (size_t)e->v[0], *vb = an->pos + 3 * (size_t)e->v[1];
    unsigned np = 1, q, j, n, nc, k, piece, pieces;
    re__plane_t pls[2 * RE_MAX_CORNER_PLANES + 3];
    double cs = re__dot(P0->n, P1->n), kk = 1 - cs, ell, dir[3], len, over, ext = 0;
    /* pls[0]: the chord at the smallest bound so far, d0 + d1 <= bmax k:
       a face beyond it cannot lower the bound, and most candidates fail on
       it first */
    for (k = 0; k < 3; k++) pls[0].n[k] = -(P0->n[k] + P1->n[k]);
    for (q = 0; q < 2; q++) {
        unsigned c = an->vcorner[e->v[q]];
        for (j = 0; j < an->c_np[c]; j++) pls[np++] = an->planes[an->c_planes[an->c_pfirst[c] + j]];
    }
    /* between the planes across the edge at its two ends, moved out to
       the end spheres' centres where those lie beyond them: past them the
       corners' balls (a chain's next segment) take over */
    re__sub(vb, va, dir);
    len = re__len(dir);
    if (!(kk > 0) || !(len > 0)) return bmax;
    for (k = 0; k < 3; k++) dir[k] /= len;
    for (k = 0; k < 3; k++) pls[np].n[k] = dir[k], pls[np + 1].n[k] = -dir[k];
    pls[np].c = re__dot(dir, vb), pls[np + 1].c = -re__dot(dir, va);
    for (q = 0; q < 2; q++) {
        if (an->edge_end[2 * (size_t)i + q] == 255) continue;
        over = req * re__dot(dir, re__edge_su(an, an->vcorner[e->v[q]], i)) * (q ? 1 : -1) * (1 + 1e-9);
        if (over > 0) pls[np + (q ? 0u : 1u)].c += over, ext = re__max(ext, over);
    }
    np += 2;
    /* the tangent lines lie r tan(phi / 2) from the edge; a long edge is
       searched in pieces about that long (an oblique edge's box would hold
       most of a fine mesh) */
    ell = cs > -1 ? req * sqrt(kk / (1 + cs)) * (1 + 1e-9) + tol : HUGE_VAL;
    pieces = ell < HUGE_VAL && len > ell ? (unsigned)re__min(16.0, ceil(len / ell)) : 1u;
    for (piece = 0; piece < pieces; piece++) {
        double lo[3], hi[3], a = (double)piece / pieces, b = (double)(piece + 1) / pieces;
        for (k = 0; k < 3; k++) {
            double x0 = va[k] + a * (vb[k] - va[k]), x1 = va[k] + b * (vb[k] - va[k]);
            lo[k] = re__min(x0, x1) - ell - (piece == 0 || piece + 1 == pieces ? ext : 0);
            hi[k] = re__max(x0, x1) + ell + (piece == 0 || piece + 1 == pieces ? ext : 0);
        }
        nc = re__tbvh_query(B, lo, hi, p);
        for (q = 0; q < nc; q++) {
            unsigned t = B->cand[q], pp = plane_patch[an->tplane[t]];
            if (pp == p || pp == RE__MULTI) continue;
            pls[0].c = bmax * kk - P0->c - P1->c;
            n = re__clip_inside(an, t, pls, np, shell[t] == shell[e->he[0] / 3] ? tol : -tol, poly, tmp);
            for (j = 0; j < n; j++) {
                const double *x = poly + 3 * j;
                double bound = re__max(0.0, (P0->c - re__dot(P0->n, x) + P1->c - re__dot(P1->n, x)) / kk);
                if (bound < bmax) bmax = bound, *tri = t;
            }
        }
    }
    return bmax;
}

/* The same for corner c of patch p: the least |x - v| / (1 + max |u|). */
static double re__corner_reach_bound(const re__an_t *an, re__tbvh_t *B, const unsigned *plane_patch, const unsigned *shell,
                                     unsigned p, unsigned c, double req, double bmax, double tol, long long *tri,
                                     double *poly, double *tmp)
{
    const unsigned *planes = an->c_planes + an->c_pfirst[c];
    const double *v = an->pos + 3 * (size_t)an->c_vertex[c];
    unsigned np = an->c_np[c], s, q, n, k, nc, own = RE__NONE, vi = an->c_vertex[c];
    re__plane_t pls[RE__CORNER_CLIP_PLANES];
    double umax = 0, reach, lo[3], hi[3];
    for (q = 0; q < np; q++) pls[q] = an->planes[planes[q]];
    /* and the planes of the corners its rounded edges lead to: the solid
       lies inside them near c as the slab bound assumes (a box's top
       corner's cone would reach below its bottom face) */
    for (q = an->voff[vi]; q < an->voff[vi + 1]; q++) {
        const re__edge_t *e = &an->edges[an->vinc[q]];
        unsigned cw, j;
        if (!e->rounded) continue;
        cw = an->vcorner[e->v[0] == vi ? e->v[1] : e->v[0]];
        for (j = 0; j < an->c_np[cw] && np < RE__CORNER_CLIP_PLANES; j++) pls[np++] = an->planes[an->c_planes[an->c_pfirst[cw] + j]];
    }
    for (q = an->voff[an->c_vertex[c]]; q < an->voff[an->c_vertex[c] + 1] && own == RE__NONE; q++)
        own = shell[an->edges[an->vinc[q]].he[0] / 3];
    for (s = 0; s < an->c_ns[c]; s++) umax = re__max(umax, re__len(an->su + 3 * (size_t)(an->c_sfirst[c] + s)));
    reach = req * (1 + umax) * (1 + 1e-9) + tol;
    for (k = 0; k < 3; k++) lo[k] = v[k] - reach, hi[k] = v[k] + reach;
    nc = re__tbvh_query(B, lo, hi, p);
    for (q = 0; q < nc; q++) {
        unsigned t = B->cand[q], pp = plane_patch[an->tplane[t]];
        double b;
        if (pp == p || pp == RE__MULTI) continue;
        if (!(n = re__clip_inside(an, t, pls, np, shell[t] == own ? tol : -tol, poly, tmp))) continue;
        b = re__dist_polygon(poly, n, v) / (1 + umax);
        if (b < bmax) bmax = b, *tri = t;
    }
    return bmax;
}

/* Step 6b for a whole object: lowers P->rmax of each patch to what its
   edges' and corners' zones allow (see above), naming the triangle. */
static re_result_t re__reach_bounds(re__an_t *an, re__arena_t *ar, const unsigned *patch, re__patch_limits_t *P)
{
    re__tbvh_t B;
    unsigned i, c, j, *plane_patch, *shell, only = RE__UNSEEN;
    double tol, M = 0, poly[3 * RE__CLIP_MAX], tmp[3 * RE__CLIP_MAX];
    size_t mark = ar->used;
    if (!re__may_reach_own_faces(an)) return RE_OK;
    RE__TAKE(plane_patch, unsigned, an->n_planes + 1);
    for (i = 0; i < an->n_planes; i++) plane_patch[i] = RE__NONE;
    for (c = 0; c < an->nc; c++) {
        if (an->vstate[an->c_vertex[c]] != RE__V_CORNER || P->req[patch[c]] == HUGE_VAL) continue;
        only = only == RE__UNSEEN || only == patch[c] ? patch[c] : RE__NONE; /* RE__NONE: several */
        for (j = 0; j < an->c_np[c]; j++) {
            unsigned *pp = &plane_patch[an->c_planes[an->c_pfirst[c] + j]];
            *pp = *pp == RE__NONE || *pp == patch[c] ? patch[c] : RE__MULTI;
        }
    }
    RE__TAKE(B.nodes, re__tbvh_node_t, 2 * (size_t)an->T + 1);
    RE__TAKE(B.idx, unsigned, an->T);
    RE__TAKE(B.box, double, 6 * (size_t)an->T);
    RE__TAKE(B.cand, unsigned, an->T);
    if (only == RE__UNSEEN || !re__tbvh_build(an, &B, plane_patch, only)) { ar->used = mark; return RE_OK; }
    /* shells: triangles joined across edges (the tree's triangles only
       need it, but the joins run over all) */
    RE__TAKE(shell, unsigned, an->T + 1);
    for (i = 0; i < an->T; i++) shell[i] = i;
    for (i = 0; i < an->E; i++)
        if (an->edges[i].count >= 2) re__uf_join(shell, an->edges[i].he[0] / 3, an->edges[i].he[1] / 3);
    for (i = 0; i < an->T; i++) shell[i] = re__uf_find(shell, i);
    for (i = 0; i < 3; i++) M = re__max(M, fabs(an->origin[i]));
    tol = (an->m->position_type == RE_FLOAT32 ? RE__REACH_FLT_ULPS * RE__FLT_EPS : RE__REACH_ULPS) * (M + an->size);
    for (i = 0; i < an->E; i++) {
        const re__edge_t *e = &an->edges[i];
        unsigned p;
        long long tri = -1;
        double b;
        if (!e->rounded) continue;
        p = patch[an->vcorner[e->v[0]]];
        if (P->req[p] == HUGE_VAL) continue;
        b = re__edge_reach_bound(an, &B, plane_patch, shell, p, i, P->req[p], re__min(P->rmax[p], P->req[p]), tol, &tri, poly,
                                 tmp);
        if (tri >= 0 && b < P->rmax[p])
            P->rmax[p] = b, P->ltri[p] = tri, P->lim0[p] = re__vid(an, e->v[0]), P->lim1[p] = re__vid(an, e->v[1]);
    }
    for (c = 0; c < an->nc; c++) {
        unsigned p = patch[c];
        long long tri = -1;
        double b;
        if (an->vstate[an->c_vertex[c]] != RE__V_CORNER || an->c_np[c] < 3 || P->req[p] == HUGE_VAL) continue;
        b = re__corner_reach_bound(an, &B, plane_patch, shell, p, c, P->req[p], re__min(P->rmax[p], P->req[p]), tol, &tri,
                                   poly, tmp);
        if (tri >= 0 && b < P->rmax[p]) P->rmax[p] = b, P->ltri[p] = tri, P->lim0[p] = re__vid(an, an->c_vertex[c]), P->lim1[p] = -1;
    }
    ar->used = mark;
    return RE_OK;
}

/* Each patch's radius r[root] (0 elsewhere): its request, reported when
   its edges asked for different ones, and clamped to what fits (reported)
   or rejected, as the radius policy says, when it is larger. */
static re_result_t re__patch_radius(re__an_t *an, const unsigned *uf, const re__patch_limits_t *P, double *r)
{
    unsigned c;
    char msg[160];
    for (c = 0; c < an->nc; c++) {
        r[c] = 0;
        if (uf[c] != c || P->req[c] == HUGE_VAL) continue;
        r[c] = P->req[c];
        if (P->mism[c]) {
            snprintf(msg, sizeof msg, "unequal edge radii meet in the patch of vertex %u: all use %g", re__vid(an, an->c_vertex[c]),
                     P->req[c]);
            re__report(an, RE_REPORT_RADIUS_MISMATCH, re__vid(an, an->c_vertex[c]), -1, P->req[c], msg);
        }
        if (P->req[c] > P->rmax[c] * (1 + RE__RADIUS_SLACK)) {
            long long el = P->lim0[c], el2 = P->lim1[c];
            if (P->ltri[c] >= 0 && P->lim1[c] >= 0)
                snprintf(msg, sizeof msg, "radius %.17g too large: the rounding of edge %lld-%lld would cut triangle %lld (largest %.17g)",
                         P->req[c], P->lim0[c], P->lim1[c], P->ltri[c], P->rmax[c]);
            else if (P->ltri[c] >= 0)
                snprintf(msg, sizeof msg, "radius %.17g too large: the rounding at vertex %lld would cut triangle %lld (largest %.17g)",
                         P->req[c], P->lim0[c], P->ltri[c], P->rmax[c]);
            else if (P->lim1[c] >= 0)
                snprintf(msg, sizeof msg, "radius %.17g too large: edge %lld-%lld is shorter than its two set-backs (largest %.17g)",
                         P->req[c], P->lim0[c], P->lim1[c], P->rmax[c]);
            else
                snprintf(msg, sizeof msg, "radius %.17g too large at vertex %lld: the solid is thinner than 2r there (largest %.17g)",
                         P->req[c], P->lim0[c], P->rmax[c]);
            if (P->ltri[c] >= 0) el = P->ltri[c], el2 = -2; /* the triangle in the way */
            if (an->desc->radius_policy == RE_RADIUS_REJECT) return re__fail(an, RE_ERR_RADIUS_TOO_LARGE, el, msg);
            r[c] = P->rmax[c];
            an->st.clamped++;
            re__report(an, RE_REPORT_RADIUS_CLAMPED, el, el2, r[c], msg);
        }
    }
    return RE_OK;
}

/* A patch where no radius fits (largest 0: a neighbouring face plane
   through the corner itself, e.g. where the coordinates' rounding far from
   the origin tilted the coplanar pieces of a face against each other)
   stays sharp, every corner and edge of it, rather than rounded with r = 0
   (docs: construction step 7). */
static void re__sharpen_unroundable(re__an_t *an, unsigned *uf, const double *req, const double *r)
{
    unsigned c, i, zeroed = 0;
    char msg[160];
    for (c = 0; c < an->nc; c++) {
        unsigned p = re__uf_find(uf, c);
        if (req[p] == HUGE_VAL || r[p] > 0 || an->vstate[an->c_vertex[c]] != RE__V_CORNER) continue;
        an->vstate[an->c_vertex[c]] = RE__V_SHARP;
        zeroed = 1;
    }
    for (i = 0; i < an->E && zeroed; i++) {
        re__edge_t *e = &an->edges[i];
        if (!e->rounded || an->vstate[e->v[0]] == RE__V_CORNER) continue;
        e->rounded = 0;
        an->st.rounded_edges--;
        snprintf(msg, sizeof msg, "convex edge %u-%u left sharp: no radius above 0 fits its patch", re__vid(an, e->v[0]),
                 re__vid(an, e->v[1]));
        re__report(an, RE_REPORT_SHARP_PATCH_EDGE, re__vid(an, e->v[0]), re__vid(an, e->v[1]), 0.0, msg);
    }
}

static re_result_t re__radii(re__an_t *an, re__arena_t *ar, double **patch_r_out, unsigned **uf_out)
{
    unsigned *uf, c, *pmark, *patch, nc = an->nc;
    re__bound_job_t job;
    re__patch_limits_t P;
    re_result_t rc;
    double *r;
    size_t mark;
    RE__TAKE(uf, unsigned, nc + 1);
    RE__TAKE(r, double, nc + 1);
    mark = ar->used; /* the rest is scratch of this step only */
    RE__TAKE(P.req, double, nc + 1);
    RE__TAKE(P.rmax, double, nc + 1);
    RE__TAKE(P.lim0, long long, nc + 1);
    RE__TAKE(P.lim1, long long, nc + 1);
    RE__TAKE(P.mism, unsigned char, nc + 1);
    RE__TAKE(P.ltri, long long, nc + 1);
    RE__TAKE(pmark, unsigned, an->n_planes + 1);
    memset(pmark, 0, sizeof(unsigned) * (an->n_planes + 1));
    for (c = 0; c < nc; c++)
        uf[c] = c, P.req[c] = HUGE_VAL, P.rmax[c] = HUGE_VAL, P.mism[c] = 0, P.lim0[c] = P.lim1[c] = P.ltri[c] = -1;
    if ((rc = re__patch_requests(an, uf, &P)) != RE_OK) return rc;
    RE__TAKE(patch, unsigned, nc + 1);
    RE__TAKE(job.bound, double, nc + 1);
    RE__TAKE(job.lim, long long, 2 * (size_t)nc + 1);
    for (c = 0; c < nc; c++) patch[c] = re__uf_find(uf, c); /* the tasks only read them */
    job.an = an, job.req = P.req, job.patch = patch;
    if ((rc = re__corner_bounds(an, &job, pmark)) != RE_OK) return rc;
    /* the first smallest bound of each patch, in corner order as before */
    for (c = 0; c < nc; c++) {
        unsigned q = patch[c];
        if (job.bound[c] < P.rmax[q]) P.rmax[q] = job.bound[c], P.lim0[q] = job.lim[2 * c], P.lim1[q] = job.lim[2 * c + 1];
    }
    if ((rc = re__reach_bounds(an, ar, patch, &P)) != RE_OK) return rc;
    if ((rc = re__patch_radius(an, uf, &P, r)) != RE_OK) return rc;
    re__sharpen_unroundable(an, uf, P.req, r);
    *patch_r_out = r;
    *uf_out = uf;
    ar->used = mark;
    return RE_OK;
}

/* ---- kd-tree over the rounded edges' detection boxes (paper §3.2) ----------

   A query knows its point I, so it reads exactly one leaf: the tree is a
   point-location tree whose leaves list the detection boxes containing any
   point of the leaf's cell. A box that straddles a split goes to both
   sides. The paper splits the longest axis in the middle; with boxes of
   very different sizes (long block edges, short knob edges) that stopped
   splitting early and left ~70 boxes in the leaf an average query met. We
   keep the longest axis of the cell but place the split by a binned
   surface-area-style cost for point queries: a cell is reached in
   proportion to its length along the axis, so a split at x costs
   RE__KD_STEP + (len_left * n_left + len_right * n_right) / len, against
   n for a leaf. Coordinates are relative to the object's origin, so float
   splits (8-byte nodes) keep their resolution far from the world origin;
   the partition and the query compare the same doubles with the same
   float, so a point always finds every box that contains it. */

#define RE__KD_LEAF 2     /* never split a cell with this many boxes or fewer */
#define RE__KD_DEPTH 48
#define RE__KD_BINS 16
/* Cost of one node step, in units of one candidate test: 1 for query time;
   RE_LAYOUT_COMPACT charges 4, because a split also costs a node and the
   duplicated references (at 1 boxes-42k keeps 3x the nodes, 6 bytes per
   rounded edge, for 7% fewer query instructions; the example's small
   objects get leaves a few times larger). */
#define RE__KD_STEP 1.0
#define RE__KD_STEP_COMPACT 4.0
#define RE__KD_DUP 2u     /* leaf references at most this times the boxes (memory) */
/* RE_LAYOUT_FAST spends bytes for speed on small objects: this many leaf
   references on top of RE__KD_DUP per box. On an object of a few hundred
   edges whose detection boxes overlap (the example's icosphere of 120
   edges) the budget, not the cost, stopped the splits, and a query tested
   21 candidates; with these 7 (docs/rounded_edges.md, construction step
   8). A large object's tree, and its build time, are as before. */
#define RE__KD_DUP_EXTRA 256u
#define RE__KD_SAMPLE 64u
/* Nodes the tree may take, from its reference capacity. Not reached: a
   split puts every box on at least one side and needs both sides smaller,
   so every leaf holds a box and there are fewer than 2 x references nodes
   (and the budget keeps the references within their capacity).
   test_rounded_parallel lowers it so that a tree built on threads meets it
   (re__kd_build_top). */
#ifndef RE__KD_NODE_CAP
#define RE__KD_NODE_CAP(refs) (2 * (refs))
#endif

typedef struct re__kd_t {
    const double *box; /* 6 per primitive, relative to the origin: lo[3], hi[3] */
    re__node_t *nodes;
    unsigned n_nodes, cap_nodes;
    unsigned *leafrefs;
    unsigned n_leafrefs, cap_leafrefs;
    unsigned *tmp;
    unsigned n_tmp, cap_tmp;
    unsigned n_leaves;
    int compact; /* RE_LAYOUT_COMPACT */
} re__kd_t;

static unsigned re__kd_leaf(re__kd_t *kd, const unsigned *list, unsigned n)
{
    unsigned id = kd->n_nodes++, i;
    kd->nodes[id].info = 3u | (kd->n_leafrefs << 2);
    kd->nodes[id].data = n;
    for (i = 0; i < n; i++) kd->leafrefs[kd->n_leafrefs++] = list[i];
    kd->n_leaves++;
    return id;
}

/* How a node of n boxes (`list` in kd->tmp, cell [lo_in, hi_in]) splits:
   0 for a leaf; else the axis, the plane, and the children's lists (nl
   boxes from kd->n_tmp, nr from kd->n_tmp + n) within `budget`. */
static int re__kd_split(const re__kd_t *kd, unsigned list_at, unsigned n, const double lo_in[3], const double hi_in[3],
                        unsigned budget, int depth, unsigned *axis_out, float *split_out, unsigned *nl_out, unsigned *nr_out)
{
    const unsigned *list = kd->tmp + list_at;
    double lo[3], hi[3], len = 0, best = (double)n, w, scale, step_cost = RE__COMPACT(kd) ? RE__KD_STEP_COMPACT : RE__KD_STEP;
    unsigned i, a, axis = 0, nl = 0, nr = 0, k, bk = 0;
    /* the cost is estimated from at most ~RE__KD_SAMPLE boxes (the
       partition itself is exact), so a level costs one pass over the boxes */
    unsigned step = n > 2 * RE__KD_SAMPLE ? n / RE__KD_SAMPLE : 1u;
    unsigned cl[RE__KD_BINS], ch[RE__KD_BINS];
    float split;
    if (n <= RE__KD_LEAF || depth >= RE__KD_DEPTH || kd->n_tmp + 2 * n > kd->cap_tmp || kd->n_nodes + 3 > kd->cap_nodes)
        return 0;
    /* the cell shrunk to the boxes it holds */
    {
        double l0 = HUGE_VAL, l1 = HUGE_VAL, l2 = HUGE_VAL, h0 = -HUGE_VAL, h1 = -HUGE_VAL, h2 = -HUGE_VAL;
        for (i = 0; i < n; i += step) {
            const double *bx = kd->box + 6 * (size_t)list[i];
            l0 = re__min(l0, bx[0]), l1 = re__min(l1, bx[1]), l2 = re__min(l2, bx[2]);
            h0 = re__max(h0, bx[3]), h1 = re__max(h1, bx[4]), h2 = re__max(h2, bx[5]);
        }
        lo[0] = re__max(l0, lo_in[0]), lo[1] = re__max(l1, lo_in[1]), lo[2] = re__max(l2, lo_in[2]);
        hi[0] = re__min(h0, hi_in[0]), hi[1] = re__min(h1, hi_in[1]), hi[2] = re__min(h2, hi_in[2]);
    }
    /* the longest axis first (§3.2); when no plane across it pays (every
       box spans the cell that way, as along one edge split into many
       segments) the next longest, so such a cell is not left a leaf */
    {
        unsigned order[3] = {0, 1, 2}, o, swap, ns = (n + step - 1) / step;
        for (a = 0; a < 2; a++) /* by extent, longest first; ties keep x, y, z */
            for (o = a + 1; o < 3; o++)
                if (hi[order[o]] - lo[order[o]] > hi[order[a]] - lo[order[a]]) swap = order[a], order[a] = order[o], order[o] = swap;
        scale = (double)n / (double)ns;
        for (o = 0; o < 3 && !bk; o++) {
            unsigned sl = 0, sh = 0;
            axis = order[o];
            len = hi[axis] - lo[axis];
            if (!(len > 0)) break;
            /* binned cost: cl[b] boxes start in bin b, ch[b] end in it */
            w = RE__KD_BINS / len;
            memset(cl, 0, sizeof cl);
            memset(ch, 0, sizeof ch);
            for (i = 0; i < n; i += step) {
                double x0 = (kd->box[6 * list[i] + axis] - lo[axis]) * w, x1 = (kd->box[6 * list[i] + 3 + axis] - lo[axis]) * w;
                cl[x0 <= 0 ? 0u : x0 >= RE__KD_BINS - 1 ? RE__KD_BINS - 1u : (unsigned)x0]++;
                ch[x1 <= 0 ? 0u : x1 >= RE__KD_BINS - 1 ? RE__KD_BINS - 1u : (unsigned)x1]++;
            }
            for (k = 1; k < RE__KD_BINS; k++) {
                double c;
                sl += cl[k - 1]; /* boxes starting left of plane k: on the left */
                sh += ch[k - 1]; /* boxes ending left of plane k: not on the right */
                c = step_cost + scale * ((double)k * sl + (double)(RE__KD_BINS - k) * (ns - sh)) / RE__KD_BINS;
                if (c < best) best = c, bk = k;
            }
        }
    }
    if (!bk) return 0;
    split = (float)(lo[axis] + len * bk / RE__KD_BINS);
    /* one pass: the left list from n_tmp, the right one from n_tmp + n;
       each id is written to both and kept where it belongs (no branch to
       mispredict: which side a box goes to is as good as random) */
    {
        unsigned *tl = kd->tmp + kd->n_tmp, *tr = tl + n;
        const double s = (double)split;
        for (i = 0; i < n; i++) {
            unsigned id_i = list[i];
            const double *bx = kd->box + 6 * (size_t)id_i;
            tl[nl] = id_i;
            nl += bx[axis] <= s;
            tr[nr] = id_i;
            nr += bx[3 + axis] >= s;
        }
    }
    /* no progress, or over the memory budget for duplicates */
    if (nl == n || nr == n || nl + nr > budget) return 0;
    *axis_out = axis, *split_out = split, *nl_out = nl, *nr_out = nr;
    return 1;
}

/* The left child's share of a split node's reference budget: its boxes
   and, of the duplicates the budget allows, its part in proportion. */
static unsigned re__kd_left_budget(unsigned budget, unsigned nl, unsigned nr)
{
    return nl + (unsigned)((double)(budget - nl - nr) * nl / (nl + nr));
}

/* A split node (its right child's id is filled in later); its children's
   lists (n + nr entries at kd->n_tmp, re__kd_split) are kept. */
static unsigned re__kd_inner(re__kd_t *kd, unsigned axis, float split, unsigned n, unsigned nr)
{
    unsigned id = kd->n_nodes++;
    kd->n_tmp += n + nr;
    kd->nodes[id].info = axis;
    memcpy(&kd->nodes[id].data, &split, sizeof split);
    return id;
}

/* `list` lives in kd->tmp; children's lists are pushed after it and popped.
   [lo, hi] is the node's cell; its leaves may hold at most `budget` >= n
   references in all, shared between the children in proportion to their
   sizes, so no subtree starves another of duplicates. */
static unsigned re__kd_build(re__kd_t *kd, unsigned list_at, unsigned n, const double lo_in[3], const double hi_in[3],
                             unsigned budget, int depth)
{
    unsigned axis, nl, nr, a, id, mark = kd->n_tmp;
    float split;
    if (kd->n_nodes + 1 > kd->cap_nodes) return RE__NONE;
    if (re__kd_split(kd, list_at, n, lo_in, hi_in, budget, depth, &axis, &split, &nl, &nr)) {
        unsigned left_at = kd->n_tmp, right_at = kd->n_tmp + n, r;
        unsigned bl = re__kd_left_budget(budget, nl, nr);
        double clo[3], chi[3];
        id = re__kd_inner(kd, axis, split, n, nr);
        for (a = 0; a < 3; a++) clo[a] = lo_in[a], chi[a] = hi_in[a];
        chi[axis] = (double)split;
        if (re__kd_build(kd, left_at, nl, clo, chi, bl, depth + 1) == RE__NONE) return RE__NONE;
        chi[axis] = hi_in[axis];
        clo[axis] = (double)split;
        r = re__kd_build(kd, right_at, nr, clo, chi, budget - bl, depth + 1);
        if (r == RE__NONE) return RE__NONE;
        kd->nodes[id].info = axis | (r << 2);
        kd->n_tmp = mark;
        return id;
    }
    if (kd->n_leafrefs + n > kd->cap_leafrefs) return RE__NONE;
    return re__kd_leaf(kd, kd->tmp + list_at, n);
}

/* The kd-tree on the host's threads (THREADS): the root's two subtrees at
   once, the right one into arrays of its own, then appended after the left
   one with its node ids and list offsets moved: the nodes and lists the
   recursion writes on one thread, in its order. Each side sees the list
   scratch (kd->tmp) at the offsets it has there; the node and reference
   capacities, whose tests see the counts the other side leaves, cannot
   have mattered when the whole tree stays clear of them, else the tree is
   built again on this thread. */
#ifndef RE__KD_SPLIT_MIN /* boxes at least for two tasks */
#define RE__KD_SPLIT_MIN 4096u
#endif

typedef struct re__kd_job_t {
    re__kd_t side[2];
    unsigned at[2], n[2], budget[2], root[2];
    double lo[2][3], hi[2][3];
    unsigned char ran[2];
} re__kd_job_t;

static void re__kd_task(void *ctx, unsigned w)
{
    re__kd_job_t *J = (re__kd_job_t *)ctx;
    J->ran[w] = 1;
    J->root[w] = re__kd_build(&J->side[w], J->at[w], J->n[w], J->lo[w], J->hi[w], J->budget[w], 1);
}

/* The right side's nodes and references appended after the left side's. */
static void re__kd_append(re__kd_t *kd, const re__kd_t *right)
{
    unsigned i, nb = kd->n_nodes, rb = kd->n_leafrefs;
    for (i = 0; i < right->n_nodes; i++) {
        unsigned info = right->nodes[i].info;
        kd->nodes[nb + i].info = (info & 3u) | (((info >> 2) + ((info & 3u) == 3u ? rb : nb)) << 2);
        kd->nodes[nb + i].data = right->nodes[i].data;
    }
    memcpy(kd->leafrefs + rb, right->leafrefs, sizeof(unsigned) * right->n_leafrefs);
    kd->n_nodes += right->n_nodes;
    kd->n_leafrefs += right->n_leafrefs;
    kd->n_leaves += right->n_leaves;
}

/* The whole tree over kd->tmp[0 .. n) (kd empty); *root RE__NONE when its
   scratch was short. */
static re_result_t re__kd_build_top(re__an_t *an, re__kd_t *kd, unsigned n, const double lo[3], const double hi[3],
                                    unsigned budget, unsigned *root)
{
    re__kd_job_t J;
    re__kd_t *R = &J.side[1];
    unsigned axis, nl, nr, a;
    float split;
    void *mem;
    re_result_t rc;
    *root = RE__NONE;
    if (an->inner < 2 || n < RE__KD_SPLIT_MIN || !re__kd_split(kd, 0, n, lo, hi, budget, 0, &axis, &split, &nl, &nr)) {
        *root = re__kd_build(kd, 0, n, lo, hi, budget, 0);
        return RE_OK;
    }
    re__kd_inner(kd, axis, split, n, nr); /* the root, as re__kd_build makes it */
    J.at[0] = n, J.at[1] = 2 * n, J.n[0] = nl, J.n[1] = nr;
    J.budget[0] = re__kd_left_budget(budget, nl, nr);
    J.budget[1] = budget - J.budget[0];
    for (a = 0; a < 3; a++) J.lo[0][a] = J.lo[1][a] = lo[a], J.hi[0][a] = J.hi[1][a] = hi[a];
    J.hi[0][axis] = J.lo[1][axis] = (double)split;
    J.side[0] = *kd;
    *R = *kd;
    mem = RE_MALLOC(sizeof(re__node_t) * (size_t)kd->cap_nodes + sizeof(unsigned) * ((size_t)kd->cap_leafrefs + kd->cap_tmp),
                    an->desc->alloc_ctx);
    if (!mem) return re__fail(an, RE_ERR_OUT_OF_MEMORY, -1, "out of memory");
    R->nodes = (re__node_t *)mem;
    R->leafrefs = (unsigned *)(R->nodes + kd->cap_nodes);
    R->tmp = R->leafrefs + kd->cap_leafrefs;
    memcpy(R->tmp + J.at[1], kd->tmp + J.at[1], sizeof(unsigned) * nr);
    R->n_nodes = R->n_leafrefs = R->n_leaves = 0;
    J.ran[0] = J.ran[1] = 0;
    rc = re__run_split(an, 2, re__kd_task, &J, J.ran);
    if (rc == RE_OK && J.root[0] != RE__NONE && J.root[1] != RE__NONE &&
        (unsigned long long)J.side[0].n_nodes + R->n_nodes + 3 <= kd->cap_nodes &&
        (unsigned long long)J.side[0].n_leafrefs + R->n_leafrefs <= kd->cap_leafrefs) {
        kd->n_nodes = J.side[0].n_nodes;
        kd->n_leafrefs = J.side[0].n_leafrefs;
        kd->n_leaves = J.side[0].n_leaves;
        kd->nodes[0].info = axis | (kd->n_nodes << 2); /* the right subtree's root follows the left subtree */
        re__kd_append(kd, R);
        kd->n_tmp = n;
        *root = 0;
    } else if (rc == RE_OK) { /* near a capacity: on this thread */
        kd->n_nodes = kd->n_leafrefs = kd->n_leaves = 0;
        kd->n_tmp = n;
        *root = re__kd_build(kd, 0, n, lo, hi, budget, 0);
    }
    RE_FREE(mem, an->desc->alloc_ctx);
    return rc;
}

/* The leaves' lists in 16-bit form (re__node_t), written to nodes16 and
   out when they are not NULL; returns the number of 16-bit entries. A list
   is cut, in its order, into runs whose ids span at most 65535 and that
   hold at most 32767 ids: the first run's base is the node's data, each
   further run starts with its base in two halves, low first. */
static size_t re__kd_narrow(const re__kd_t *kd, re__node_t *nodes16, unsigned short *out)
{
    size_t at = 0;
    unsigned id, i, j;
    for (id = 0; id < kd->n_nodes; id++) {
        const re__node_t *nd = &kd->nodes[id];
        const unsigned *l = kd->leafrefs + (nd->info >> 2);
        unsigned n = nd->data;
        if ((nd->info & 3u) != 3u) continue;
        if (nodes16) nodes16[id].info = 3u | (unsigned)(at << 2), nodes16[id].data = 0;
        for (i = 0, j = 0; i == 0 || i < n; i = j) {
            unsigned lo = n ? l[i] : 0, hi = lo;
            for (j = i; j < n && j - i < 0x7FFFu; j++) {
                unsigned nlo = l[j] < lo ? l[j] : lo, nhi = l[j] > hi ? l[j] : hi;
                if (nhi - nlo > RE__LEAF_RUN_SPAN) break;
                lo = nlo, hi = nhi;
            }
            if (i > 0) {
                if (out) out[at] = (unsigned short)(lo & 0xFFFFu), out[at + 1] = (unsigned short)(lo >> 16);
                at += 2;
            } else if (nodes16) nodes16[id].data = lo;
            if (out) {
                unsigned q;
                out[at] = (unsigned short)((j - i) | (j < n ? 0x8000u : 0u));
                for (q = i; q < j; q++) out[at + 1 + q - i] = (unsigned short)(l[q] - lo);
            }
            at += 1 + (size_t)(j - i);
            if (j == 0) break; /* an empty leaf: one empty run */
        }
    }
    return at;
}

/* The point where the three planes, shifted inward by r, meet (Cramer's
   rule), solved relative to org (the object's bounding-box centre) so it
   keeps its precision at coordinates near 1e6. The build (re__final_spheres) and
   the query (re__centre) both call this, on the same stored planes. */
static void re__solve3(const re__plane_t *A, const re__plane_t *B, const re__plane_t *C, double r, const double org[3],
                       double x[3])
{
    double bc[3], ca[3], ab[3], det, da, db, dc;
    unsigned q;
    re__cross(B->n, C->n, bc);
    re__cross(C->n, A->n, ca);
    re__cross(A->n, B->n, ab);
    det = re__dot(A->n, bc);
    da = A->c - r - re__dot(A->n, org);
    db = B->c - r - re__dot(B->n, org);
    dc = C->c - r - re__dot(C->n, org);
    for (q = 0; q < 3; q++) x[q] = org[q] + (da * bc[q] + db * ca[q] + dc * ab[q]) / det;
}

#define RE__ALIGN(x) (((x) + 15u) & ~(size_t)15u)
/* Past an array of `bytes` written at *at: its alignment padding zeroed,
   so that a block's bytes are the same whatever memory it was given. */
static void re__skip(unsigned char **at, size_t bytes)
{
    memset(*at + bytes, 0, RE__ALIGN(bytes) - bytes);
    *at += RE__ALIGN(bytes);
}

/* Packing of id arrays (re__pk_t): the block's smallest id is its base.
   RE__NONE is the largest unsigned, so the smallest id needs no test for
   it, and the largest is taken plus one, where RE__NONE wraps to 0: no
   branch, and a whole block's loop (a constant count) vectorises. */
static void re__pk_range(const unsigned *ids, unsigned m, unsigned *lo, unsigned *hi1)
{
    unsigned i, l = RE__NONE, h = 0;
    for (i = 0; i < m; i++) {
        l = ids[i] < l ? ids[i] : l;
        h = ids[i] + 1u > h ? ids[i] + 1u : h;
    }
    *lo = l, *hi1 = h;
}
static int re__pk_block(const unsigned *ids, unsigned n, unsigned b, unsigned *base)
{
    unsigned lo, hi1, m = n - b * RE__PK_BLOCK;
    if (m >= RE__PK_BLOCK) re__pk_range(ids + b * RE__PK_BLOCK, RE__PK_BLOCK, &lo, &hi1);
    else re__pk_range(ids + b * RE__PK_BLOCK, m, &lo, &hi1);
    *base = lo == RE__NONE ? 0 : lo;
    return lo == RE__NONE || (hi1 - 1u - lo <= RE__PK_SPAN && hi1 - 1u < RE__PK_FULL);
}
static unsigned re__pk_full_blocks(const unsigned *ids, unsigned n)
{
    unsigned b, nf = 0, base;
    for (b = 0; b * RE__PK_BLOCK < n; b++) nf += re__pk_block(ids, n, b, &base) ? 0u : 1u;
    return nf;
}
static size_t re__pk_bytes(unsigned n, unsigned n_full)
{
    return RE__ALIGN(sizeof(unsigned) * ((n + RE__PK_BLOCK - 1) / RE__PK_BLOCK)) + RE__ALIGN(n) +
           RE__ALIGN(sizeof(unsigned) * RE__PK_BLOCK * (size_t)n_full);
}
/* Writes the packed form of ids[n] at *at (re__pk_bytes(n, full blocks)). */
static re__pk_t re__pk_put(unsigned char **at, const unsigned *ids, unsigned n, unsigned n_full)
{
    re__pk_t p;
    unsigned *base = (unsigned *)*at, b, i, nf = 0, nb = (n + RE__PK_BLOCK - 1) / RE__PK_BLOCK;
    unsigned char *off = *at + RE__ALIGN(sizeof(unsigned) * nb);
    unsigned *full = (unsigned *)(off + RE__ALIGN(n));
    unsigned char *pad = *at;
    re__skip(&pad, sizeof(unsigned) * nb);
    re__skip(&pad, n);
    re__skip(&pad, sizeof(unsigned) * RE__PK_BLOCK * (size_t)n_full);
    for (b = 0; b < nb; b++) {
        unsigned lo;
        if (re__pk_block(ids, n, b, &lo)) {
            base[b] = lo;
            for (i = b * RE__PK_BLOCK; i < n && i < (b + 1) * RE__PK_BLOCK; i++)
                off[i] = ids[i] == RE__NONE ? (unsigned char)255 : (unsigned char)(ids[i] - lo);
        } else {
            base[b] = RE__PK_FULL | (nf * RE__PK_BLOCK);
            for (i = b * RE__PK_BLOCK; i < (b + 1) * RE__PK_BLOCK; i++) {
                full[nf * RE__PK_BLOCK + i % RE__PK_BLOCK] = i < n ? ids[i] : RE__NONE;
                if (i < n) off[i] = 0;
            }
            nf++;
        }
    }
    *at += re__pk_bytes(n, n_full);
    p.base = base, p.off = off, p.full = full;
    return p;
}

/* ---- Step 7: final arrays, packed into one block ------------------------------ */

/* The packed id arrays of an object (re__pk_t), in re__final_t.pk. */
enum {
    RE__PKA_TRI_PLANE, RE__PKA_CVERTEX, RE__PKA_K_FIRST, RE__PKA_K_SFIRST, RE__PKA_K_RID, RE__PKA_K_XFIRST,
    RE__PKA_S_CORNER, RE__PKA_X_CORNER, RE__PKA_C_S0, RE__PKA_N
};

typedef struct re__final_t {
    unsigned n_corners, n_spheres, n_cyls, n_edge_cyls, n_planes, n_refs, n_radii;
    unsigned *pk[RE__PKA_N], pk_n[RE__PKA_N], pk_full[RE__PKA_N]; /* ids, count, full blocks */
    unsigned char *bands;
    re__plane_t *planes;
    double *sph; /* 3 per sphere: the centres the query will compute */
    unsigned short *sinfo;
    unsigned *xsid;
    double *xsph;
    unsigned n_xsph;
    re__cyl_t *cyls;
    re__xcyl_t *xcyls;
    unsigned short *det;
    unsigned char *det8;
    unsigned det_e0;
    unsigned n_xs1; /* edge cylinders whose s[1] - s[0] does not fit 16 bits */
    re__corner_t *corners;
    double *radii;
    unsigned *refs;
    re__kd_t kd;
    size_t n_leaf16; /* 16-bit entries of the leaf lists (re__kd_narrow) */
} re__final_t;

/* x rounded up to a float: the stored detection radii only ever err large */
static float re__float_up(double x)
{
    float f = (float)x;
    if ((double)f < x) { /* nextafterf(f, HUGE_VALF) by the bits: it was 1% of a build */
        unsigned b;
        memcpy(&b, &f, sizeof b);
        b = f == 0 ? 1u : f > 0 ? b + 1u : b - 1u;
        memcpy(&f, &b, sizeof f);
    }
    return f;
}

/* A positive x rounded up to the upper 16 bits of a float (8 exponent bits,
   7 mantissa bits: at most 0.8% too large), for the detection radii, which
   only ever err large (re__det reads them back). */
static unsigned short re__det_up(double x)
{
    float f = re__float_up(x);
    unsigned b;
    memcpy(&b, &f, sizeof b);
    if (b & 0xFFFFu) b += 0x10000u; /* positive: rounds the magnitude up */
    return (unsigned short)(b >> 16);
}
static double re__det(unsigned short h)
{
    unsigned b = (unsigned)h << 16;
    float f;
    memcpy(&f, &b, sizeof f);
    return (double)f;
}
/* The compact layout's detection radii: one byte, a 4-bit exponent above
   the object's base e0 (a float's biased exponent) and a 4-bit mantissa,
   rounded up (at most 6.25% too large; below 2^(e0 - 127) they become that
   value). e0 is chosen so the largest radius of the object fits. */
static unsigned re__det8_exp(double x)
{
    float f = re__float_up(x);
    unsigned b, ex, m;
    memcpy(&b, &f, sizeof b);
    ex = b >> 23, m = (b >> 19) & 15u;
    if (b & 0x7FFFFu) m++;
    return m == 16u ? ex + 1u : ex;
}
static unsigned char re__det8_up(double x, unsigned e0)
{
    float f = re__float_up(x);
    unsigned b, ex, m;
    memcpy(&b, &f, sizeof b);
    ex = b >> 23, m = (b >> 19) & 15u;
    if (b & 0x7FFFFu) m++;
    if (m == 16u) m = 0, ex++;
    if (ex < e0) return 0;
    RE_ASSERT(ex - e0 <= 15u);
    return (unsigned char)((ex - e0) << 4 | m);
}
static double re__det8(unsigned char h, unsigned e0)
{
    unsigned b = (e0 + (unsigned)(h >> 4)) << 23 | (unsigned)(h & 15u) << 19;
    float f;
    memcpy(&f, &b, sizeof f);
    return (double)f;
}

/* Build-time check of the sphere centres the query solves for: a triple
   point is used when it lies within this times r (plus 64 ulp of the
   vertex's coordinates) of v + r*u, the centre the erosion found; else the
   centre is stored. RE__CORNER_MERGE already moves the surface by up to
   1e-7 r max(1, |u|). */
#define RE__SPHERE_SOLVE_REL 1e-9
/* ... plus the coordinates' rounding, up to this much of r (as far as
   RE__CORNER_MERGE moves the surface); a centre the solve misses by more
   is stored (found by fuzz_rounded_exact, 2026-12-06) */
#define RE__SPHERE_SOLVE_CAP 1e-7

/* Per-triangle bands (query step 0): 4 bytes per triangle, widths in units
   of 1 / RE__BAND_STEPS; none with RE_NO_BANDS. */
#define RE__BAND_STEPS 255.0
#ifdef RE_NO_BANDS
#define RE__BAND_BYTES 0u
#else
#define RE__BAND_BYTES 4u
#endif

#ifndef RE_NO_BANDS
/* Query step 0: per-triangle bands. The flat part of face f is the face
   shrunk by the half-planes H_g = {x : n_g.x <= c_g - r (1 - n_g.n_f)} of
   the planes g of its corners (the offset of the eroded face; query step 2
   tests the same lines). Near a rounded edge between f and g the face
   outside H_g is a strip along the edge; its triangles are found by a walk
   over the face's flat edges from the edge's own triangle (the part of a
   convex face outside a half-plane is convex, so they are connected). The
   cut-off part of such a triangle is a polygon whose barycentric
   coordinates follow from the three signed distances alone. At a corner
   with four or more planes, the planes that are not its edges' neighbours
   cut the face only inside the corner's face reach rho of the vertex (the
   shrunk polygon runs through the projected sphere centres there), so each
   triangle at the vertex gets a cap piece rho / altitude instead, and a
   triangle of the face within rho of the vertex that does not touch it is
   always queried. A piece is excluded by a band along one of the
   triangle's edges (lambda_k <= beta_k) or by the cap shared by its three
   corners (some lambda_k >= 1 - gamma): the hit is flat when every
   barycentric coordinate lies in (beta_k, 1 - gamma). Every edge's band on
   its own triangle is set first; then each other piece goes to the band
   that loses the least area to it (on a box face the bands skip 99% of
   the flat part; the narrowest band per piece, without the cap, 74%).
   Bands err only wide:
   rounded up to 1/RE__BAND_STEPS, plus RE__BAND_MARGIN for a float host's
   u, v. */
#define RE__IN_CHAIN 4u /* re__bandwork_t.cover: the edge is one segment of a straight chain */
#define RE__BAND_MARGIN 1e-6
/* Share of the triangle's area behind band a of width b: an edge band
   1 - (1 - b)^2, the three corner caps 3 b^2. */
static double re__band_area(unsigned a, double b) { return a < 3 ? b * (2 - b) : 3 * b * b; }
static void re__band_take(double *beta, const double need[4])
{
    unsigned a, kb = 0;
    double best = HUGE_VAL;
    if (need[0] <= beta[0] || need[1] <= beta[1] || need[2] <= beta[2] || need[3] <= beta[3]) return; /* held already */
    for (a = 0; a < 4; a++) {
        double grow = need[a] > beta[a] ? re__band_area(a, re__min(need[a], 1.0)) - re__band_area(a, beta[a]) : 0;
        if (grow < best || (grow == best && need[a] < need[kb])) best = grow, kb = a;
    }
    beta[kb] = re__max(beta[kb], need[kb]);
}

typedef struct re__bandwork_t {
    unsigned *nb; /* 3 per triangle: the neighbour across its flat edge k, or RE__NONE */
    double *ih;   /* 3 per triangle: 1 / its altitude from corner k */
    double *beta;
    unsigned *stamp, *queue, st;
    /* with straight chains (vertices where only two planes meet) only:
       chain[e] links rounded edge e to the rest of its chain (union-find,
       the root its first edge), cover[e] says which sides of e a walk of
       its chain has reached (bit h: the face of half-edge he[h]) */
    unsigned *chain;
    unsigned char *cover;
} re__bandwork_t;

/* The collinear segments of a straight chain share their two planes and
   radius, hence their strips: the chain's first edge walks them, and marks
   the sides of the chain's edges that its walk reaches on triangle t. */
static void re__chain_cover(const re__an_t *an, re__bandwork_t *B, unsigned t, unsigned root)
{
    unsigned k;
    for (k = 0; k < 3; k++) {
        unsigned e = an->he_edge[3 * t + k];
        if (e != RE__NONE && an->edges[e].rounded && re__uf_find(B->chain, e) == root)
            B->cover[e] |= (unsigned char)(an->edges[e].he[0] == 3 * t + k ? 1u : 2u);
    }
}

/* The strip of face f (plane fi) outside H_g, from the triangle of
   half-edge he on (the edge between f and g). On that triangle the strip
   runs along its own edge, so it is a band of width r tan(theta/2) (theta
   the angle between the normals) over the altitude: no piece (re__bands
   sets it). Beyond it, across the face's flat edges, the cut-off polygons
   are pieces. */
static void re__band_strip(const re__an_t *an, re__bandwork_t *B, unsigned fi, const re__plane_t *G, double r, unsigned he,
                           unsigned chain_root)
{
    const re__plane_t *P = &an->planes[fi];
    double cs = re__dot(G->n, P->n), lim = G->c - r * (1 - cs);
    unsigned qh = 0, qt = 0, t0 = he / 3;
    if (B->nb[3 * (size_t)t0] == RE__NONE && B->nb[3 * (size_t)t0 + 1] == RE__NONE && B->nb[3 * (size_t)t0 + 2] == RE__NONE)
        return; /* alone on its face: nothing beyond the own band */
    B->st++;
    B->stamp[t0] = B->st;
    B->queue[qt++] = t0;
    while (qh < qt) {
        /* unrolled over the three corners (k, k + 1 mod 3): the same
           operations in the same order as a loop, without its index
           arithmetic; this walk is a third of a blocks build */
        unsigned tt = B->queue[qh++];
        const unsigned *tv = an->tri + 3 * (size_t)tt, *nb = B->nb + 3 * (size_t)tt;
        double sd[3], need[4];
        int o0, o1, o2;
        sd[0] = re__dot(G->n, an->pos + 3 * (size_t)tv[0]) - lim;
        sd[1] = re__dot(G->n, an->pos + 3 * (size_t)tv[1]) - lim;
        sd[2] = re__dot(G->n, an->pos + 3 * (size_t)tv[2]) - lim;
        o0 = sd[0] > 0, o1 = sd[1] > 0, o2 = sd[2] > 0;
        if (chain_root != RE__NONE) re__chain_cover(an, B, tt, chain_root);
        if (tt != t0 || chain_root != RE__NONE) {
            if (!(o0 | o1 | o2)) continue; /* not cut (cannot happen: it shares an outside corner) */
            /* the cut-off polygon: the outside corners and the crossings of
               the edges that change sign, in barycentric coordinates;
               need[a] is its largest lambda_a, and the cap needs 1 - its
               smallest lambda_a when one corner a alone is outside (else
               the cap cannot hold it) */
            need[0] = o0 ? 1.0 : 0.0, need[1] = o1 ? 1.0 : 0.0, need[2] = o2 ? 1.0 : 0.0, need[3] = 1;
            if (o0 != o1) { /* lambda_k = 1 - tau, lambda_k2 = tau */
                double tau = sd[0] / (sd[0] - sd[1]);
                need[0] = re__max(need[0], 1 - tau), need[1] = re__max(need[1], tau);
            }
            if (o1 != o2) {
                double tau = sd[1] / (sd[1] - sd[2]);
                need[1] = re__max(need[1], 1 - tau), need[2] = re__max(need[2], tau);
            }
            if (o2 != o0) {
                double tau = sd[2] / (sd[2] - sd[0]);
                need[2] = re__max(need[2], 1 - tau), need[0] = re__max(need[0], tau);
            }
            if (o0 + o1 + o2 == 1) {
                unsigned a0 = o0 ? 0u : o1 ? 1u : 2u, ap = (a0 + 2) % 3, an2 = (a0 + 1) % 3;
                /* crossings on the edges (a0, an2) and (ap, a0): lambda_a0 = 1 - tau there */
                double ta = sd[a0] / (sd[a0] - sd[an2]), tb = sd[ap] / (sd[ap] - sd[a0]);
                need[3] = re__max(ta, 1 - tb);
            }
            re__band_take(B->beta + 4 * (size_t)tt, need);
        }
        /* on across the face's flat edges that the cut-off part reaches (an
           edge with a corner outside H_g) */
        if (nb[0] != RE__NONE && (o0 | o1) && B->stamp[nb[0]] != B->st) B->stamp[nb[0]] = B->st, B->queue[qt++] = nb[0];
        if (nb[1] != RE__NONE && (o1 | o2) && B->stamp[nb[1]] != B->st) B->stamp[nb[1]] = B->st, B->queue[qt++] = nb[1];
        if (nb[2] != RE__NONE && (o2 | o0) && B->stamp[nb[2]] != B->st) B->stamp[nb[2]] = B->st, B->queue[qt++] = nb[2];
    }
}

/* Distance from p to triangle t's closest point, bounded below by the
   distance to its plane and to its edges (exact enough for a reach test:
   it errs low only where the point projects inside, where it is exact). */
static double re__point_tri_dist(const re__an_t *an, unsigned t, const double p[3])
{
    const double *a = an->pos + 3 * (size_t)an->tri[3 * t], *b = an->pos + 3 * (size_t)an->tri[3 * t + 1],
                 *c = an->pos + 3 * (size_t)an->tri[3 * t + 2];
    const double *vs[3];
    double best = HUGE_VAL, n[3], e[3], q[3];
    unsigned k;
    int inside = 1;
    vs[0] = a, vs[1] = b, vs[2] = c;
    n[0] = an->tn[3 * (size_t)t], n[1] = an->tn[3 * (size_t)t + 1], n[2] = an->tn[3 * (size_t)t + 2];
    for (k = 0; k < 3; k++) {
        const double *u = vs[k], *w = vs[(k + 1) % 3];
        double ab[3], ap[3], cr[3], tt, l2;
        re__sub(w, u, ab);
        re__sub(p, u, ap);
        re__cross(ab, ap, cr);
        if (re__dot(cr, n) < 0) inside = 0;
        l2 = re__dot(ab, ab);
        tt = l2 > 0 ? re__max(0.0, re__min(1.0, re__dot(ap, ab) / l2)) : 0;
        re__madd(u, tt, ab, q);
        re__sub(p, q, e);
        best = re__min(best, re__len(e));
    }
    if (inside) {
        re__sub(p, a, e);
        return fabs(re__dot(e, n));
    }
    return best;
}

/* The bands' arrays, in the arena's order: F->bands stays, the rest from
   *mark on is scratch of this step. re_build_sizes() takes them without
   running the step: the scratch high-water mark is all it needs of them. */
static re_result_t re__bands_take(re__an_t *an, re__arena_t *ar, re__final_t *F, re__bandwork_t *B, size_t *mark)
{
    unsigned c;
    RE__TAKE(F->bands, unsigned char, RE__BAND_BYTES * (size_t)an->T);
    *mark = ar->used;
    RE__TAKE(B->nb, unsigned, 3 * (size_t)an->T + 1);
    RE__TAKE(B->beta, double, 4 * (size_t)an->T + 1);
    RE__TAKE(B->ih, double, 3 * (size_t)an->T + 1);
    RE__TAKE(B->stamp, unsigned, (size_t)an->T + 1);
    RE__TAKE(B->queue, unsigned, (size_t)an->T + 1);
    B->chain = NULL;
    B->cover = NULL;
    for (c = 0; c < an->nc && an->c_np[c] != 2; c++) {}
    if (c < an->nc) { /* straight chains */
        RE__TAKE(B->chain, unsigned, (size_t)an->E + 1);
        RE__TAKE(B->cover, unsigned char, (size_t)an->E + 1);
    }
    return RE_OK;
}

/* Per triangle: its neighbour across each flat edge (B->nb, RE__NONE
   across any other) and 1 / its altitude from each corner (B->ih). Returns
   whether any edge is flat. */
static unsigned re__band_tables(const re__an_t *an, re__bandwork_t *B)
{
    unsigned t, k, any_flat = 0;
    for (t = 0; t < an->T; t++)
        for (k = 0; k < 3; k++) {
            unsigned e = an->he_edge[3 * t + k];
            B->nb[3 * (size_t)t + k] = e == RE__NONE || an->edges[e].cls != RE__E_FLAT ? RE__NONE
                                       : an->edges[e].he[0] / 3 == t ? an->edges[e].he[1] / 3 : an->edges[e].he[0] / 3;
            any_flat |= B->nb[3 * (size_t)t + k] != RE__NONE;
        }
    for (t = 0; t < an->T; t++)
        for (k = 0; k < 3; k++) {
            double ed[3];
            if (an->tbad[t]) { B->ih[3 * (size_t)t + k] = 0; continue; }
            re__sub(an->pos + 3 * (size_t)an->tri[3 * t + (k + 2) % 3], an->pos + 3 * (size_t)an->tri[3 * t + (k + 1) % 3], ed);
            B->ih[3 * (size_t)t + k] = re__len(ed) / an->tarea[t]; /* 1 / the altitude from corner k */
        }
    return any_flat;
}

/* Straight chains (B->chain): their edges joined at the vertices inside
   them, which have two rounded edges (re__chain_end's steps). */
static void re__band_chains(const re__an_t *an, re__bandwork_t *B)
{
    unsigned i, c, j;
    for (i = 0; i < an->E; i++) B->chain[i] = i, B->cover[i] = 0;
    for (c = 0; c < an->nc; c++) {
        unsigned v = an->c_vertex[c], e0 = RE__NONE, e1 = RE__NONE;
        if (an->c_np[c] != 2) continue;
        for (j = an->voff[v]; j < an->voff[v + 1]; j++)
            if (an->edges[an->vinc[j]].rounded) { if (e0 == RE__NONE) e0 = an->vinc[j]; else e1 = an->vinc[j]; }
        if (e1 == RE__NONE) continue;
        re__uf_join(B->chain, e0, e1);
        B->cover[e0] |= RE__IN_CHAIN, B->cover[e1] |= RE__IN_CHAIN;
    }
}

/* The band each rounded edge's strip needs on its own two triangles: the
   strip's width over the altitude from the corner opposite the edge, on
   both faces alike: r tan(theta/2), tan(theta/2) = (1 - cos) / sin. */
static void re__own_strips(const re__an_t *an, re__bandwork_t *B, const double *patch_r, unsigned *uf)
{
    unsigned i, h;
    for (i = 0; i < an->E; i++) {
        const re__edge_t *e = &an->edges[i];
        double r, cs, sn, w;
        if (!e->rounded) continue;
        r = patch_r[re__uf_find(uf, an->vcorner[e->v[0]])];
        cs = re__dot(an->planes[an->tplane[e->he[1] / 3]].n, an->planes[an->tplane[e->he[0] / 3]].n);
        sn = sqrt(re__max(0.0, 1 - cs * cs));
        w = sn > 0 ? r * (1 - cs) / sn : 0.0;
        for (h = 0; h < 2; h++) {
            unsigned t0 = e->he[h] / 3, m0 = (e->he[h] % 3 + 2) % 3;
            B->beta[4 * (size_t)t0 + m0] = re__max(B->beta[4 * (size_t)t0 + m0], sn > 0 ? w * B->ih[3 * (size_t)t0 + m0] : 1.0);
        }
    }
}

/* The pieces of the strips beyond their own triangles (re__band_strip), on
   faces of several triangles. */
static void re__far_strips(const re__an_t *an, re__bandwork_t *B, const double *patch_r, unsigned *uf)
{
    unsigned i, h;
    for (i = 0; i < an->E; i++) {
        const re__edge_t *e = &an->edges[i];
        unsigned t0, t1, root = RE__NONE;
        double r;
        if (!e->rounded) continue;
        r = patch_r[re__uf_find(uf, an->vcorner[e->v[0]])];
        t0 = e->he[0] / 3, t1 = e->he[1] / 3;
        /* a straight chain's strips are walked once, by its first edge
           (walking them from every segment was quadratic in its length) */
        if (B->cover && (B->cover[i] & RE__IN_CHAIN) && re__uf_find(B->chain, i) == i) root = i;
        for (h = 0; h < 2; h++) {
            if (root == RE__NONE && B->cover && (B->cover[i] & (1u << h))) continue; /* its chain's walk reached it */
            re__band_strip(an, B, an->tplane[h ? t1 : t0], &an->planes[an->tplane[h ? t0 : t1]], r, e->he[h], root);
        }
    }
}

/* The cap of triangle tt at its corner kv (vertex v): the disc of radius
   rho around v, within rho / h_m of the two edges through it (h_m the
   altitude from corner m, twice the area over the opposite edge), and of
   corner kv itself. The face's other triangles within rho that do not
   touch v are always queried (bands 1). */
static void re__corner_cap(const re__an_t *an, re__bandwork_t *B, unsigned v, unsigned tt, unsigned kv, double rho)
{
    unsigned qh = 0, qt = 0, m, k;
    double need[4];
    for (m = 0; m < 3; m++) need[m] = m == kv ? 1.0 : rho * B->ih[3 * (size_t)tt + m];
    need[3] = rho * B->ih[3 * (size_t)tt + kv];
    re__band_take(B->beta + 4 * (size_t)tt, need);
    if (B->nb[3 * (size_t)tt] == RE__NONE && B->nb[3 * (size_t)tt + 1] == RE__NONE && B->nb[3 * (size_t)tt + 2] == RE__NONE)
        return; /* alone on its face */
    B->st++;
    B->stamp[tt] = B->st;
    B->queue[qt++] = tt;
    while (qh < qt) {
        unsigned t2 = B->queue[qh++];
        for (k = 0; k < 3; k++) {
            unsigned o2 = B->nb[3 * (size_t)t2 + k];
            if (o2 == RE__NONE || B->stamp[o2] == B->st) continue;
            B->stamp[o2] = B->st;
            if (an->tri[3 * o2] == v || an->tri[3 * o2 + 1] == v || an->tri[3 * o2 + 2] == v) {
                B->queue[qt++] = o2; /* a fan triangle of v: its own cap */
                continue;
            }
            if (re__point_tri_dist(an, o2, an->pos + 3 * (size_t)v) > rho) continue;
            B->beta[4 * (size_t)o2] = B->beta[4 * (size_t)o2 + 1] = B->beta[4 * (size_t)o2 + 2] = 1;
            B->queue[qt++] = o2;
        }
    }
}

/* Caps at corners with planes that are not edge neighbours (4 or more),
   of radius the corner's face reach (without detection's margin), on each
   triangle at the corner once: the one whose half-edge leaves v. */
static void re__corner_caps(const re__an_t *an, re__bandwork_t *B, const unsigned *fc, const double *reach)
{
    unsigned c, j, h;
    for (c = 0; c < an->nc; c++) {
        unsigned v = an->c_vertex[c];
        double rho;
        if (fc[c] == RE__NONE || an->c_np[c] < 4) continue;
        rho = reach[fc[c]] / 1.5;
        for (j = an->voff[v]; j < an->voff[v + 1]; j++) {
            const re__edge_t *e = &an->edges[an->vinc[j]];
            for (h = 0; h < 2 && h < e->count; h++) {
                unsigned tt = e->he[h] / 3;
                if (an->tri[e->he[h]] != v || an->tplane[tt] == RE__NONE) continue;
                re__corner_cap(an, B, v, tt, e->he[h] % 3, rho);
            }
        }
    }
}

/* Query step 0's bands (docs: "Per-triangle bands"): per triangle, the
   barycentric band along each edge that the rounding can reach and a cap
   at the corners, rounded up to 1/RE__BAND_STEPS, into F->bands. */
static re_result_t re__bands(re__an_t *an, re__arena_t *ar, const unsigned *fc, const double *patch_r, unsigned *uf,
                             const double *reach, re__final_t *F)
{
    unsigned T = an->T, t, k, any_flat;
    size_t mark;
    re__bandwork_t B;
    re_result_t rc = re__bands_take(an, ar, F, &B, &mark);
    if (rc != RE_OK) return rc;
    any_flat = re__band_tables(an, &B);
    B.st = 0;
    if (B.chain) re__band_chains(an, &B);
    for (t = 0; t < 4 * T; t++) B.beta[t] = 0;
    for (t = 0; t < T; t++) B.stamp[t] = 0;
    /* the strips of each rounded edge, on both its faces: first every
       edge's band on its own triangles, then the pieces beyond them, each
       assigned at once to the band that loses the least area (the own
       bands, the widest, are in place by then, so a corner piece joins
       one of them or the cap). Without flat edges (every face one
       triangle, as on an icosphere) no strip reaches past its own
       triangle: every triangle is alone on its face */
    re__own_strips(an, &B, patch_r, uf);
    if (any_flat) re__far_strips(an, &B, patch_r, uf);
    re__corner_caps(an, &B, fc, reach);
    for (t = 0; t < T; t++)
        for (k = 0; k < 4; k++) {
            double b = B.beta[4 * t + k];
            double q = b > 0 ? ceil((b + RE__BAND_MARGIN) * RE__BAND_STEPS) : 0;
            F->bands[4 * t + k] = (unsigned char)(q > RE__BAND_STEPS ? RE__BAND_STEPS : q);
        }
    ar->used = mark;
    return RE_OK;
}

#endif /* RE_NO_BANDS */

/* The spheres of the vertices inside the straight chain that leaves corner
   ca by edge first and ends at corner cb by edge last (cb = RE__NONE: it
   has no far corner). Each sits on the chain's axis; one that lies beyond
   the span of the chain's end spheres (a short first segment) is moved to
   the nearer of them. */
static void re__chain_spheres(re__an_t *an, const unsigned *fc, const unsigned *sbase, const double *patch_r, unsigned *uf,
                              unsigned ca, unsigned first, unsigned cb, unsigned last, unsigned *csph)
{
    unsigned v = an->c_vertex[ca], e = first, steps = 0, sa = RE__NONE, sb = RE__NONE;
    /* the chain's end spheres, for its segments' cylinders (csph) */
    if (cb != RE__NONE && cb != ca && fc[ca] != RE__NONE && fc[cb] != RE__NONE) {
        sa = sbase[ca] + an->edge_end[2 * first + (an->edges[first].v[0] == an->c_vertex[ca] ? 0u : 1u)];
        sb = sbase[cb] + an->edge_end[2 * last + (an->edges[last].v[0] == an->c_vertex[cb] ? 0u : 1u)];
    }
    for (;;) {
        const re__edge_t *ed = &an->edges[e];
        unsigned w = ed->v[0] == v ? ed->v[1] : ed->v[0], c = an->vcorner[w], q, nx = RE__NONE, e0 = RE__NONE, e1 = RE__NONE;
        if (sa != RE__NONE) csph[2 * e] = ed->v[0] == v ? sa : sb, csph[2 * e + 1] = ed->v[0] == v ? sb : sa;
        if (an->c_np[c] != 2 || ++steps > an->V) return;
        for (q = an->voff[w]; q < an->voff[w + 1]; q++)
            if (an->edges[an->vinc[q]].rounded) {
                if (an->vinc[q] != e) nx = an->vinc[q];
                if (e0 == RE__NONE) e0 = an->vinc[q]; else e1 = an->vinc[q];
            }
        if (fc[c] != RE__NONE && e1 != RE__NONE && cb != RE__NONE) {
            /* the chain's ends as seen from c: by its first rounded edge e0,
               then by its second (c was entered by e, from ca) */
            unsigned x0 = e0 == e ? ca : cb, l0 = e0 == e ? first : last, x1 = e0 == e ? cb : ca, l1 = e0 == e ? last : first, a;
            double r = patch_r[re__uf_find(uf, c)], pa[3], pb[3], pc[3], ab[3], t, L2;
            re__madd(an->pos + 3 * (size_t)an->c_vertex[x0], r, re__edge_su(an, x0, l0), pa);
            re__madd(an->pos + 3 * (size_t)an->c_vertex[x1], r, re__edge_su(an, x1, l1), pb);
            re__madd(an->pos + 3 * (size_t)w, r, an->su + 3 * (size_t)an->c_sfirst[c], pc);
            re__sub(pb, pa, ab);
            L2 = re__dot(ab, ab);
            re__sub(pc, pa, pc);
            t = L2 > 0 ? re__dot(pc, ab) / L2 : -1; /* ends at one point (the largest radius): there */
            if (!(t >= 0 && t <= 1))
                for (a = 0; a < 3; a++)
                    an->su[3 * (size_t)an->c_sfirst[c] + a] = ((t < 0 ? pa[a] : pb[a]) - an->pos[3 * (size_t)w + a]) / r;
        }
        if (nx == RE__NONE) return;
        v = w, e = nx;
    }
}

/* Does the compact layout store edge cylinder cy's second sphere as a
   16-bit step from its first (re__object_t.ds1), or in the list xs1? */
static int re__s1_near(const re__cyl_t *cy) { return cy->s[1] > cy->s[0] && cy->s[1] - cy->s[0] <= RE__DS1_SPAN; }
static unsigned re__count_xs1(const re__final_t *F)
{
    unsigned i, n = 0;
    for (i = 0; i < F->n_edge_cyls; i++) n += re__s1_near(&F->cyls[i]) ? 0u : 1u;
    return n;
}

/* A corner that re__drop_chain_corners leaves out: two planes, and no edge
   cylinder ends at its sphere (used: per sphere, one does). */
static int re__chain_inner(const re__final_t *F, const unsigned char *used, unsigned k)
{
    const re__corner_t *K = &F->corners[k];
    unsigned s, sf = F->pk[RE__PKA_K_SFIRST][k], reached = 0;
    for (s = 0; s < K->ns; s++) reached |= used[sf + s];
    return K->np == 2 && K->nx == 0 && !reached;
}

/* Drops the corners inside straight chains once every cylinder of their
   chain spans it (re__chain_respan): their spheres lie on the chain's axis,
   inside its cylinder, and no cylinder, reference or walk reaches them any
   more, yet each cost a corner record, two references and a stored centre
   (about 55 bytes a segment: a finely split edge took 79-84 bytes per
   rounded edge, over the 64 of the compact layout's budget). Only corners
   of two planes none of whose spheres an edge cylinder ends at go; the
   kept corners and spheres are renumbered in order, in place (a new index
   never exceeds the old one), after every step that reads the analysis'
   per-corner arrays, which some of these alias (re__numbering_t.fc_id). A
   scene without such corners is left bit for bit as it was. */
static re_result_t re__drop_chain_corners(re__an_t *an, re__arena_t *ar, re__final_t *F)
{
    unsigned *newc, *news, k, s, i, nk = 0, nsph = 0, nref = 0, nx = 0, ndrop = 0;
    unsigned char *used;
    RE__TAKE(used, unsigned char, F->n_spheres);
    memset(used, 0, F->n_spheres);
    for (i = 0; i < F->n_edge_cyls; i++) used[F->cyls[i].s[0]] = used[F->cyls[i].s[1]] = 1;
    for (k = 0; k < F->n_corners; k++) ndrop += (unsigned)re__chain_inner(F, used, k);
    if (!ndrop) return RE_OK;
    RE__TAKE(newc, unsigned, F->n_corners);
    RE__TAKE(news, unsigned, F->n_spheres);
    for (k = 0; k < F->n_corners; k++) {
        re__corner_t K = F->corners[k];
        unsigned sf = F->pk[RE__PKA_K_SFIRST][k], rf = F->pk[RE__PKA_K_FIRST][k];
        if (re__chain_inner(F, used, k)) {
            newc[k] = RE__NONE;
            for (s = 0; s < K.ns; s++) news[sf + s] = RE__NONE;
            continue;
        }
        newc[k] = nk;
        F->corners[nk] = K;
        F->pk[RE__PKA_CVERTEX][nk] = F->pk[RE__PKA_CVERTEX][k];
        F->pk[RE__PKA_K_FIRST][nk] = nref;
        F->pk[RE__PKA_K_SFIRST][nk] = nsph;
        if (F->pk_n[RE__PKA_K_RID]) F->pk[RE__PKA_K_RID][nk] = F->pk[RE__PKA_K_RID][k];
        if (F->pk_n[RE__PKA_K_XFIRST]) F->pk[RE__PKA_K_XFIRST][nk] = F->pk[RE__PKA_K_XFIRST][k];
        for (i = 0; i < K.np; i++) F->refs[nref++] = F->refs[rf + i];
        for (s = 0; s < K.ns; s++) {
            news[sf + s] = nsph;
            F->pk[RE__PKA_S_CORNER][nsph] = nk;
            if (F->sinfo) F->sinfo[nsph] = F->sinfo[sf + s];
            if (F->xsph == F->sph) memmove(F->sph + 3 * (size_t)nsph, F->sph + 3 * (size_t)(sf + s), 3 * sizeof(double));
            nsph++;
        }
        nk++;
    }
    /* the stored centres: every sphere's in the fast layout (moved above),
       the listed ones in the compact layout */
    if (F->xsph != F->sph) {
        for (i = 0; i < F->n_xsph; i++) {
            if (news[F->xsid[i]] == RE__NONE) continue;
            F->xsid[nx] = news[F->xsid[i]];
            memmove(F->xsph + 3 * (size_t)nx, F->xsph + 3 * (size_t)i, 3 * sizeof(double));
            nx++;
        }
        F->n_xsph = nx;
    } else {
        F->n_xsph = nsph;
    }
    for (i = 0; i < F->n_edge_cyls; i++) {
        F->cyls[i].s[0] = news[F->cyls[i].s[0]], F->cyls[i].s[1] = news[F->cyls[i].s[1]];
        F->pk[RE__PKA_C_S0][i] = F->cyls[i].s[0];
    }
    for (i = 0; i < F->pk_n[RE__PKA_X_CORNER]; i++) F->pk[RE__PKA_X_CORNER][i] = newc[F->pk[RE__PKA_X_CORNER][i]];
    F->n_corners = nk, F->n_spheres = nsph, F->n_refs = nref;
    F->pk_n[RE__PKA_CVERTEX] = F->pk_n[RE__PKA_K_FIRST] = F->pk_n[RE__PKA_K_SFIRST] = nk;
    if (F->pk_n[RE__PKA_K_RID]) F->pk_n[RE__PKA_K_RID] = nk;
    if (F->pk_n[RE__PKA_K_XFIRST]) F->pk_n[RE__PKA_K_XFIRST] = nk;
    F->pk_n[RE__PKA_S_CORNER] = nsph;
    F->n_xs1 = re__count_xs1(F);
    for (i = 0; i < RE__PKA_N; i++) F->pk_full[i] = re__pk_full_blocks(F->pk[i], F->pk_n[i]);
    return RE_OK;
}

/* The gate's radius as a fraction of walk in one byte, logarithmic:
   code q > 0 stands for 2^((q - 128) / 16) (2^-8 .. 2^8 in steps of
   4.4%), 0 for none; the code rounds down, so the radius only errs small. */
static double re__clear_frac(unsigned i)
{
    /* 2^(i/16), rounded down in the 7th digit */
    static const double frac[16] = {1.0,      1.044273, 1.090507, 1.138788, 1.189207, 1.241857, 1.296839, 1.354255,
                                     1.414213, 1.476826, 1.542210, 1.610490, 1.681792, 1.756252, 1.834008, 1.915206};
    return frac[i & 15u];
}
static double re__clear_radius(unsigned q)
{
    int e = (int)q - 128;
    return q ? ldexp(re__clear_frac((unsigned)e), e >> 4) : 0.0; /* e >> 4 floors: e = 16 (e >> 4) + (e & 15) */
}
static unsigned char re__clear_code(double ratio)
{
    int e, q;
    double m;
    if (!(ratio > 0)) return 0;
    m = 2 * frexp(ratio, &e), e--; /* ratio = m 2^e, m in [1, 2) */
    if (e >= 8) return 255;
    if (e < -8) return 0;
    for (q = 15; q > 0 && re__clear_frac((unsigned)q) > m; q--) {} /* the largest 2^(q/16) <= m */
    q += 128 + 16 * e;
    return (unsigned char)(q < 1 ? 0 : q);
}

/* Orthonormal t, b completing unit n (Duff et al. 2017, "Building an
   orthonormal basis, revisited"): branch-free apart from the sign, exact for
   axis-aligned n, so the baselines' probes on a box face run along its edges. */
static void re__frame(const double n[3], double t[3], double b[3])
{
    double s = n[2] >= 0 ? 1.0 : -1.0;
    double a = -1.0 / (s + n[2]);
    double c = n[0] * n[1] * a;
    t[0] = 1.0 + s * n[0] * n[0] * a; t[1] = s * c; t[2] = -s * n[0];
    b[0] = c; b[1] = s + n[1] * n[1] * a; b[2] = -n[1];
}

/* A face plane bordered by more planes than this gets an angular tree of
   them in re__exit_clearance: otherwise each of a fine polygon's corners
   reads all its neighbours (a 12 000-gon prism's caps: 1.15 s of a 1.2 s
   build). */
#define RE__CLEAR_TREE_MIN 64u
/* bordering planes per leaf of that tree */
#define RE__CLEAR_LEAF 8u

/* A bordering plane h of face plane g, seen in g: the in-plane distance
   from a point X of g to the line g meets h in is
   (c_h - n_h.X) / sin = a - u.(X - o)_g - (cos / sin) (n_g.(X - o)),
   o the tree's origin, u the unit direction of n_h's part in g. */
typedef struct re__clear_line_t {
    double phi;   /* angle of u in g's basis (the sort key: first member) */
    double u[2];  /* u in g's basis */
    double a;     /* the distance from o, signed (HUGE_VAL where h is parallel to g; -HUGE_VAL where u cannot follow sn: never skipped) */
    double k, s;  /* |cos| / sin and 1 / sin (0 where parallel) */
    double sn;    /* sin, as re__exit_clearance computes it (0 where parallel) */
    unsigned h;
} re__clear_line_t;

/* Over a run of sorted lines: the least a, the largest k and s; the
   angles' ends come from the run's first and last lines. */
typedef struct re__clear_node_t {
    double amin, kmax, smax;
    unsigned first, last;
} re__clear_node_t;

/* The tree of one face plane: nodes[1 .. 2 p2) in heap order, leaf
   p2 + b over lines [b L, (b + 1) L) of its sorted run. */
typedef struct re__clear_tree_t {
    double o[3], n[3], e1[3], e2[3]; /* origin, g's normal, a basis of g */
    double cmax; /* the largest |c| of g and its neighbours and |o|: the rounding scale */
    re__clear_node_t *nodes;
    re__clear_line_t *lines; /* the bordering planes, sorted by phi */
    unsigned p2;
} re__clear_tree_t;

/* What re__clear_tree_min knows of X: its place in the tree's basis. */
typedef struct re__clear_at_t {
    double P[2], plen, phi; /* in g, from o */
    double z;               /* |n_g.(X - o)| */
    double eta;             /* 1e-9 of the rounding scale */
} re__clear_at_t;

/* A lower bound on the distances from X to node nd's lines (HUGE_VAL when
   it has none): a - u.P - k z, with u.P at most |P| when P's angle lies
   within the run's and at one of its ends' otherwise (u.P is largest
   nearest P's direction), less eta s for the rounding. */
static double re__clear_bound(const re__clear_line_t *lines, const re__clear_node_t *nd, const re__clear_at_t *X)
{
    const re__clear_line_t *l0, *l1;
    double reach;
    if (nd->first > nd->last) return HUGE_VAL;
    l0 = &lines[nd->first], l1 = &lines[nd->last];
    if (X->phi >= l0->phi && X->phi <= l1->phi) reach = X->plen;
    else reach = re__max(l0->u[0] * X->P[0] + l0->u[1] * X->P[1], l1->u[0] * X->P[0] + l1->u[1] * X->P[1]);
    return nd->amin - reach - nd->kmax * X->z - nd->smax * X->eta;
}

/* The least in-plane distance (see re__exit_clearance) from x (on g) to the
   lines of g's bordering planes in tree T, skipping planes marked
   owner[h] == mark, when below D; else D. Subtrees whose lower bound
   exceeds D are skipped (the bound gives up 1e-9 of the rounding scale
   over sin to be safe), the nearer child first; the distances themselves
   are the brute loop's. */
static double re__clear_tree_min(const re__final_t *F, const re__clear_tree_t *T, const unsigned *owner, unsigned mark,
                                 const double x[3], double D)
{
    const re__clear_line_t *lines = T->lines;
    re__clear_at_t X;
    double d3[3], bnd[2 * 32 + 2];
    unsigned stack[2 * 32 + 2], sp = 1;
    re__sub(x, T->o, d3);
    X.P[0] = re__dot(T->e1, d3), X.P[1] = re__dot(T->e2, d3);
    X.plen = sqrt(X.P[0] * X.P[0] + X.P[1] * X.P[1]);
    X.phi = atan2(X.P[1], X.P[0]);
    X.z = fabs(re__dot(T->n, d3));
    X.eta = 1e-9 * (T->cmax + re__len(d3));
    stack[0] = 1, bnd[0] = re__clear_bound(lines, &T->nodes[1], &X);
    while (sp) {
        unsigned i = stack[--sp];
        const re__clear_node_t *nd = &T->nodes[i];
        if (bnd[sp] > D) continue;
        if (i >= T->p2) {
            unsigned q;
            for (q = nd->first; q <= nd->last; q++) {
                const re__plane_t *h = &F->planes[lines[q].h];
                if (owner[lines[q].h] == mark || !(lines[q].sn > 0)) continue;
                D = re__min(D, re__max(0.0, h->c - re__dot(h->n, x)) / lines[q].sn);
            }
        } else {
            double b0 = re__clear_bound(lines, &T->nodes[2 * i], &X), b1 = re__clear_bound(lines, &T->nodes[2 * i + 1], &X);
            unsigned near = b0 <= b1 ? 2 * i : 2 * i + 1;
            stack[sp] = 4 * i + 1 - near, bnd[sp++] = b0 <= b1 ? b1 : b0;
            stack[sp] = near, bnd[sp++] = b0 <= b1 ? b0 : b1;
        }
    }
    return D;
}

/* Corner k's own planes (its face planes, one per reference) into own;
   returns how many. */
static unsigned re__corner_own_planes(const re__final_t *F, unsigned k, unsigned *own)
{
    const unsigned *ref = F->refs + F->pk[RE__PKA_K_FIRST][k];
    unsigned j, np = F->corners[k].np;
    for (j = 0; j < np; j++) own[j] = F->cyls[ref[j] >> 1].p[ref[j] & 1u ? 0 : 1];
    return np;
}

/* c0 (corner k's first sphere centre) seen on plane g. */
static void re__clear_foot(const re__final_t *F, unsigned k, const re__plane_t *g, double out[3])
{
    const double *c0 = F->sph + 3 * (size_t)F->pk[RE__PKA_K_SFIRST][k];
    re__madd(c0, g->c - re__dot(g->n, c0), g->n, out);
}

/* The angular tree of face plane g over its bordering planes adj[0 .. m)
   (see re__clear_tree_min), its origin o on g. */
static void re__clear_tree_build(const re__final_t *F, unsigned g, const unsigned *adj, unsigned m, const double o[3],
                                 re__clear_tree_t *T, re__clear_line_t *lines, re__clear_node_t *nodes)
{
    const re__plane_t *G = &F->planes[g];
    unsigned q, i, p2 = 1;
    memcpy(T->o, o, sizeof T->o);
    memcpy(T->n, G->n, sizeof T->n);
    re__frame(G->n, T->e1, T->e2);
    T->cmax = re__max(fabs(G->c), re__len(o));
    for (q = 0; q < m; q++) {
        const re__plane_t *h = &F->planes[adj[q]];
        re__clear_line_t *l = &lines[q];
        double cs = re__dot(G->n, h->n), w0 = re__dot(T->e1, h->n), w1 = re__dot(T->e2, h->n), wl = sqrt(w0 * w0 + w1 * w1);
        l->h = adj[q];
        l->sn = sqrt(re__max(0.0, 1 - cs * cs));
        T->cmax = re__max(T->cmax, fabs(h->c));
        /* the distance divides by sn, the bound's u by wl: they agree to
           (wl - sn) / sn of u.P, within the slack (1e-9 of the scale over sn)
           while |wl - sn| <= 1e-10. A crease a few 1e-8 off flat has
           cos^2 rounded by 2^-53, sn then 40% off wl (|wl - sn| ~ 1e-16 /
           sn): such a line's node is never skipped (a = -HUGE_VAL; also
           where sn > 0 but wl = 0, which the leaf still reads) */
        if (l->sn > 0 && wl > 0 && fabs(wl - l->sn) <= 1e-10) {
            l->u[0] = w0 / wl, l->u[1] = w1 / wl;
            l->s = 1 / l->sn, l->k = fabs(cs) * l->s;
            l->a = (h->c - re__dot(h->n, o)) * l->s;
        } else
            l->u[0] = 1, l->u[1] = 0, l->s = l->k = 0, l->a = l->sn > 0 ? -HUGE_VAL : HUGE_VAL;
        l->phi = atan2(l->u[1], l->u[0]);
    }
    re__sort(lines, m, sizeof *lines, re__cmp_double);
    while (p2 * RE__CLEAR_LEAF < m) p2 *= 2;
    T->nodes = nodes, T->p2 = p2;
    for (i = 0; i < p2; i++) { /* leaves; an empty one has first > last */
        re__clear_node_t *nd = &nodes[p2 + i];
        unsigned first = i * RE__CLEAR_LEAF, end = first + RE__CLEAR_LEAF < m ? first + RE__CLEAR_LEAF : m;
        nd->first = first < m ? first : 1, nd->last = first < m ? end - 1 : 0;
        nd->amin = HUGE_VAL, nd->kmax = nd->smax = 0;
        for (q = first; q < end; q++) {
            nd->amin = re__min(nd->amin, lines[q].a);
            nd->kmax = re__max(nd->kmax, lines[q].k), nd->smax = re__max(nd->smax, lines[q].s);
        }
    }
    for (i = p2 - 1; i >= 1; i--) {
        re__clear_node_t *nd = &nodes[i];
        const re__clear_node_t *l = &nodes[2 * i], *r = &nodes[2 * i + 1];
        nd->amin = re__min(l->amin, r->amin);
        nd->kmax = re__max(l->kmax, r->kmax), nd->smax = re__max(l->smax, r->smax);
        nd->first = l->first, nd->last = r->first <= r->last ? r->last : l->last;
    }
}

/* Each corner's gate for re_secondary_origin (re__corner_t.clear): D, the
   smallest distance, within one of the corner's face planes g, from the
   first sphere's foot on g to a line where g meets a plane h that borders
   it (across an edge of g's polygon) and is not one of the corner's own
   planes, relative to walk (re__clear_code), rounded down. A point X on g
   that lies inside the corner's own planes and within D of that foot lies
   inside every face bordering g, so on face g of the convex patch (a
   convex polygon is the intersection of its edges' half-planes): where a
   ray from inside leaves the sharp mesh. Faces border across edge
   cylinders (within a patch every polygon edge is a rounded convex
   edge). Measured in the plane, not from the sphere in space: a plane h
   at a shallow crease to g passes close to the sphere, yet cuts g one
   edge farther away. */
static re_result_t re__exit_clearance(re__an_t *an, re__arena_t *ar, re__final_t *F)
{
    unsigned *start, *adj, *owner, *tix, i, k, j, q, np, nt = 0, own[RE_MAX_CORNER_PLANES];
    re__clear_tree_t *trees = NULL;
    double *osum = NULL;
    size_t mark = ar->used;
    RE__TAKE(start, unsigned, F->n_planes + 2);
    RE__TAKE(adj, unsigned, 2 * (size_t)F->n_edge_cyls);
    RE__TAKE(owner, unsigned, F->n_planes + 1); /* plane p is corner k's own when owner[p] == k + 1 */
    memset(start, 0, sizeof(unsigned) * (F->n_planes + 2));
    memset(owner, 0, sizeof(unsigned) * (F->n_planes + 1));
    for (i = 0; i < F->n_edge_cyls; i++) start[F->cyls[i].p[0] + 2]++, start[F->cyls[i].p[1] + 2]++;
    for (i = 2; i < F->n_planes + 2; i++) start[i] += start[i - 1];
    for (i = 0; i < F->n_edge_cyls; i++) { /* plane p's neighbours: adj[start[p] .. start[p + 1]) */
        unsigned p0 = F->cyls[i].p[0], p1 = F->cyls[i].p[1];
        adj[start[p0 + 1]++] = p1;
        adj[start[p1 + 1]++] = p0;
    }
    /* each neighbour once: the segments of a straight chain (construction
       step 7) are cylinders between the same two planes, 64 000 of them on
       a finely split edge, and every corner on the chain reads the list */
    for (i = 0, j = 0, q = 0; i < F->n_planes; i++) {
        unsigned end = start[i + 1];
        start[i] = j;
        for (; q < end; q++)
            if (owner[adj[q]] != i + 1) owner[adj[q]] = i + 1, adj[j++] = adj[q];
    }
    start[F->n_planes] = j;
    memset(owner, 0, sizeof(unsigned) * (F->n_planes + 1));
    /* planes with many neighbours (a fine polygon's face) get an angular
       tree, its origin the mean of their corners' feet */
    RE__TAKE(tix, unsigned, F->n_planes + 1);
    for (i = 0; i < F->n_planes; i++) tix[i] = start[i + 1] - start[i] > RE__CLEAR_TREE_MIN ? nt++ : RE__NONE;
    if (nt) {
        RE__TAKE(trees, re__clear_tree_t, nt);
        RE__TAKE(osum, double, 4 * (size_t)nt);
        memset(osum, 0, sizeof(double) * 4 * nt);
        for (k = 0; k < F->n_corners; k++)
            for (np = re__corner_own_planes(F, k, own), j = 0; j < np; j++) {
                double *o, x[3];
                if (tix[own[j]] == RE__NONE) continue;
                o = osum + 4 * (size_t)tix[own[j]];
                re__clear_foot(F, k, &F->planes[own[j]], x);
                o[0] += x[0], o[1] += x[1], o[2] += x[2], o[3] += 1;
            }
        for (i = 0; i < F->n_planes; i++) {
            unsigned m = start[i + 1] - start[i], p2 = 1;
            double *o, oc[3];
            re__clear_line_t *lines;
            re__clear_node_t *nodes;
            if (tix[i] == RE__NONE) continue;
            o = osum + 4 * (size_t)tix[i];
            while (p2 * RE__CLEAR_LEAF < m) p2 *= 2;
            RE__TAKE(lines, re__clear_line_t, m);
            RE__TAKE(nodes, re__clear_node_t, 2 * (size_t)p2);
            for (q = 0; q < 3; q++) oc[q] = o[3] > 0 ? o[q] / o[3] : F->planes[i].c * F->planes[i].n[q];
            re__clear_tree_build(F, i, adj + start[i], m, oc, &trees[tix[i]], lines, nodes);
            trees[tix[i]].lines = lines;
        }
    }
    for (k = 0; k < F->n_corners; k++) {
        re__corner_t *K = &F->corners[k];
        double D = HUGE_VAL, c0g[3];
        for (np = re__corner_own_planes(F, k, own), j = 0; j < np; j++) owner[own[j]] = k + 1;
        for (j = 0; j < np; j++) {
            const re__plane_t *g = &F->planes[own[j]];
            if (tix[own[j]] != RE__NONE) continue; /* after the short lists: D is smaller then */
            re__clear_foot(F, k, g, c0g); /* the sphere seen on face g */
            for (q = start[own[j]]; q < start[own[j] + 1]; q++) {
                const re__plane_t *h = &F->planes[adj[q]];
                double cs, sn;
                if (owner[adj[q]] == k + 1) continue;
                /* in plane g, the line where h cuts it lies (c_h - n_h.c0g) / sin
                   from c0g: a point of g closer than that is inside h */
                cs = re__dot(g->n, h->n), sn = sqrt(re__max(0.0, 1 - cs * cs));
                if (sn > 0) D = re__min(D, re__max(0.0, h->c - re__dot(h->n, c0g)) / sn);
            }
        }
        for (j = 0; j < np; j++)
            if (tix[own[j]] != RE__NONE) {
                re__clear_foot(F, k, &F->planes[own[j]], c0g);
                D = re__clear_tree_min(F, &trees[tix[own[j]]], owner, k + 1, c0g, D);
            }
        K->clear = re__clear_code(D / (double)K->walk);
    }
    ar->used = mark;
    return RE_OK;
}

/* What the steps of re__finish pass on to each other: where the analysis'
   rounded corners, spheres, cylinders, planes and patches go in the scene's
   arrays, and each corner's detection reach. */
typedef struct re__numbering_t {
    unsigned *fc;    /* per analysis corner: its corner id, RE__NONE when it is not rounded */
    unsigned *sbase; /* per analysis corner: its first sphere */
    unsigned *xbase; /* per analysis corner: its first extra cylinder */
    unsigned *rmap;  /* per patch root (re__uf_find): the patch's number */
    unsigned *prid;  /* per patch: its radius id in F->radii */
    unsigned *ecyl;  /* per edge: its cylinder, RE__NONE when it is not rounded */
    unsigned *pmap;  /* per analysis plane: its id, RE__NONE when no corner uses it */
    unsigned *csph;  /* with straight chains: each segment's chain end spheres, 2 per edge; else NULL */
    double *reach;   /* per corner: its face reach with margin (detection, bands) */
    double *dmax;    /* per corner: the largest |sphere centre - vertex| */
    unsigned npatch;
    int pm_id, fc_id; /* pmap, fc are the identity: the analysis' arrays serve */
} re__numbering_t;

/* Numbers the rounded corners in vertex order, their spheres, references,
   edge and extra cylinders, and their patches; marks the planes they use. */
static re_result_t re__number_features(re__an_t *an, re__arena_t *ar, unsigned *uf, re__final_t *F, re__numbering_t *N)
{
    unsigned c, i, j, ns = 0, ncyl = 0, nref = 0, nco = 0;
    RE__TAKE(N->fc, unsigned, an->nc + 1);
    RE__TAKE(N->sbase, unsigned, an->nc + 1);
    RE__TAKE(N->xbase, unsigned, an->nc + 1);
    RE__TAKE(N->rmap, unsigned, an->nc + 1);
    RE__TAKE(N->prid, unsigned, an->nc + 1);
    RE__TAKE(N->ecyl, unsigned, an->E + 1);
    RE__TAKE(N->pmap, unsigned, an->n_planes + 1);
    for (i = 0; i < an->n_planes; i++) N->pmap[i] = RE__NONE;
    for (i = 0; i < an->E; i++) N->ecyl[i] = an->edges[i].rounded ? ncyl++ : RE__NONE;
    F->n_edge_cyls = ncyl;
    for (c = 0; c < an->nc; c++) N->rmap[c] = RE__NONE;
    for (c = 0; c < an->nc; c++) {
        unsigned p;
        N->fc[c] = RE__NONE;
        if (an->vstate[an->c_vertex[c]] != RE__V_CORNER) continue;
        N->fc[c] = nco++;
        N->sbase[c] = ns;
        ns += an->c_ns[c];
        N->xbase[c] = ncyl;
        ncyl += an->c_nx[c];
        nref += (unsigned)an->c_np[c];
        p = re__uf_find(uf, c);
        if (N->rmap[p] == RE__NONE) N->rmap[p] = N->npatch++;
        for (j = 0; j < an->c_np[c]; j++) N->pmap[an->c_planes[an->c_pfirst[c] + j]] = 0; /* used; re__number_planes */
    }
    F->n_corners = nco;
    F->n_spheres = ns;
    F->n_xsph = 0;
    F->n_cyls = ncyl;
    F->n_refs = nref;
    return RE_OK;
}

/* A vertex inside a straight edge (k = 2) has its sphere on the chain's
   axis; where the chain's end spheres are set back past it (a short first
   segment), it is moved along the axis into their span, which leaves the
   union of capsules unchanged and keeps it inside. Each chain is walked
   from one of its end corners, twice (once to find the far end, once for
   the vertices inside): linear in its length, where walking to both ends
   from every vertex inside was quadratic (a box whose faces are fine
   grids). N->csph stays NULL without such vertices. */
static re_result_t re__chain_axes(re__an_t *an, re__arena_t *ar, const double *patch_r, unsigned *uf, re__numbering_t *N)
{
    unsigned c, i;
    for (c = 0; c < an->nc && an->c_np[c] != 2; c++) {}
    if (c == an->nc) return RE_OK;
    RE__TAKE(N->csph, unsigned, 2 * (size_t)an->E + 1);
    for (i = 0; i < 2 * an->E; i++) N->csph[i] = RE__NONE;
    for (c = 0; c < an->nc; c++) {
        unsigned v = an->c_vertex[c], q;
        if (an->c_np[c] == 2) continue;
        for (q = an->voff[v]; q < an->voff[v + 1]; q++) {
            unsigned e = an->vinc[q], w, last, cb;
            if (!an->edges[e].rounded) continue;
            w = an->edges[e].v[0] == v ? an->edges[e].v[1] : an->edges[e].v[0];
            if (an->c_np[an->vcorner[w]] != 2) continue;
            cb = re__chain_end(an, c, e, &last);
            /* once per chain: from its lower end, or from its only end */
            if (cb != RE__NONE && (cb < c || (cb == c && last < e))) continue;
            re__chain_spheres(an, N->fc, N->sbase, patch_r, uf, c, e, cb, last, N->csph);
        }
    }
    return RE_OK;
}

/* The planes the corners use, numbered in triangle order (re__pk_t). */
static void re__number_planes(const re__an_t *an, re__final_t *F, unsigned *pmap)
{
    unsigned i;
    F->n_planes = 0;
    for (i = 0; i < an->T; i++) {
        unsigned q = an->tplane[i];
        if (q != RE__NONE && pmap[q] == 0) pmap[q] = RE__PK_FULL | F->n_planes++;
    }
    for (i = 0; i < an->n_planes; i++) pmap[i] = pmap[i] == RE__NONE ? RE__NONE : pmap[i] & ~RE__PK_FULL;
}

/* Radii are shared between patches of equal radius (one-radius objects
   need no radius ids: re__k_radius): F->radii ascending, N->prid[patch]
   its id. */
static re_result_t re__patch_radii(re__an_t *an, re__arena_t *ar, const double *patch_r, unsigned *uf, re__final_t *F,
                                   re__numbering_t *N)
{
    double *pr;
    unsigned c, i;
    RE__TAKE(pr, double, N->npatch + 1);
    for (c = 0; c < an->nc; c++)
        if (N->fc[c] != RE__NONE) {
            unsigned root = re__uf_find(uf, c);
            pr[N->rmap[root]] = patch_r[root];
        }
    RE__TAKE(F->radii, double, N->npatch + 1);
    memcpy(F->radii, pr, sizeof(double) * N->npatch);
    re__sort(F->radii, N->npatch, sizeof(double), re__cmp_double);
    F->n_radii = 0;
    for (i = 0; i < N->npatch; i++)
        if (F->n_radii == 0 || F->radii[F->n_radii - 1] != F->radii[i]) F->radii[F->n_radii++] = F->radii[i];
    for (i = 0; i < N->npatch; i++) {
        unsigned rl = 0, rh = F->n_radii;
        while (rh - rl > 1) {
            unsigned mid = rl + (rh - rl) / 2;
            if (F->radii[mid] <= pr[i]) rl = mid; else rh = mid;
        }
        N->prid[i] = rl;
    }
    return RE_OK;
}

/* The scene's arrays, in scratch (re__pack copies them into the block), and
   the planes and the triangles' plane ids in their final numbering. */
static re_result_t re__take_final(re__an_t *an, re__arena_t *ar, re__final_t *F, re__numbering_t *N)
{
    unsigned i, nco = F->n_corners, ns = F->n_spheres, ncyl = F->n_cyls;
    F->pk_n[RE__PKA_TRI_PLANE] = an->T;
    F->pk_n[RE__PKA_CVERTEX] = F->pk_n[RE__PKA_K_FIRST] = F->pk_n[RE__PKA_K_SFIRST] = nco;
    F->pk_n[RE__PKA_K_RID] = F->n_radii > 1 ? nco : 0u;
    F->pk_n[RE__PKA_K_XFIRST] = ncyl > F->n_edge_cyls ? nco : 0u;
    F->pk_n[RE__PKA_S_CORNER] = ns;
    F->pk_n[RE__PKA_X_CORNER] = ncyl - F->n_edge_cyls;
    F->pk_n[RE__PKA_C_S0] = F->n_edge_cyls;
    /* Fewer fresh scratch pages (each first touch is a page fault, which
       costs as much as thousands of instructions):
       - where every plane is used, pmap is the identity (both number in
         triangle order): the planes and the triangles' plane ids are the
         analysis' own arrays;
       - where every candidate corner is rounded, fc is the identity: the
         corners' vertices, first references (c_pfirst, the prefix sums of
         their plane counts) and first spheres are the analysis' arrays;
       - the centres overwrite the unit offsets they come from (sbase[c] <=
         c_sfirst[c], both ascending, and nothing reads su after the corner
         loop of re__final_corners);
       - sphere infos and stored ids only in the compact layout, which
         stores them. */
    for (i = 0; i < an->n_planes && N->pmap[i] == i; i++) {}
    N->pm_id = i == an->n_planes;
    N->fc_id = nco == an->nc; /* fc[c] = c: numbered in order */
    for (i = 0; i < RE__PKA_N; i++) {
        if (N->pm_id && i == RE__PKA_TRI_PLANE) F->pk[i] = an->tplane;
        else if (N->fc_id && !an->vorig && i == RE__PKA_CVERTEX) F->pk[i] = an->c_vertex; /* else mesh ids: re__vid */
        else if (N->fc_id && i == RE__PKA_K_FIRST) F->pk[i] = an->c_pfirst;
        else if (N->fc_id && i == RE__PKA_K_SFIRST) F->pk[i] = N->sbase;
        else RE__TAKE(F->pk[i], unsigned, F->pk_n[i]);
    }
    if (N->pm_id) F->planes = an->planes;
    else RE__TAKE(F->planes, re__plane_t, F->n_planes);
    F->sph = an->su;
    if (RE__WANT_COMPACT(an->desc)) {
        RE__TAKE(F->sinfo, unsigned short, ns);
        RE__TAKE(F->xsid, unsigned, ns);
    }
    if (RE__WANT_COMPACT(an->desc)) RE__TAKE(F->xsph, double, 3 * (size_t)ns);
    else F->xsph = F->sph; /* every centre stored, in sphere order: the same array */
    RE__TAKE(F->cyls, re__cyl_t, F->n_edge_cyls);
    RE__TAKE(F->xcyls, re__xcyl_t, ncyl - F->n_edge_cyls);
    if (RE__WANT_COMPACT(an->desc)) RE__TAKE(F->det8, unsigned char, 2 * (size_t)F->n_edge_cyls);
    else RE__TAKE(F->det, unsigned short, 2 * (size_t)F->n_edge_cyls);
    RE__TAKE(F->corners, re__corner_t, nco);
    RE__TAKE(F->refs, unsigned, F->n_refs);
    RE__TAKE(N->reach, double, nco + 1);
    RE__TAKE(N->dmax, double, nco + 1);
    for (i = 0; i < an->T && !N->pm_id; i++)
        F->pk[RE__PKA_TRI_PLANE][i] = an->tplane[i] == RE__NONE ? RE__NONE : N->pmap[an->tplane[i]];
    if (!N->pm_id)
        for (i = 0; i < an->n_planes; i++)
            if (N->pmap[i] != RE__NONE) F->planes[N->pmap[i]] = an->planes[i];
    return RE_OK;
}

/* Corner c's sphere centres (radius r, vertex v) into F, each either
   stored or, in the compact layout, marked as solved from three of its
   face planes (the query's qslot numbering) when that gives the same point
   to RE__SPHERE_SOLVE_REL. Returns the largest |centre - v| and, in
   *freach, the corner zone's reach on its faces: on a face g through a
   centre, the zone is the hull of v and the eroded vertices seen from
   above, their tangential offsets. */
static double re__final_spheres(const re__an_t *an, re__final_t *F, const re__numbering_t *N, unsigned c, double r,
                                const unsigned *qslot, double *freach)
{
    const double *v = an->pos + 3 * (size_t)an->c_vertex[c];
    unsigned pf = an->c_pfirst[c], j, k, kid = N->fc[c];
    double dm = 0;
    for (j = 0; j < an->c_ns[c]; j++) {
        unsigned sid = N->sbase[c] + j, tri = an->s_tri[an->c_sfirst[c] + j];
        double *sp = F->sph + 3 * (size_t)sid, dd[3], u[3], x[3], lu;
        const double *su = an->su + 3 * (size_t)(an->c_sfirst[c] + j);
        unsigned short info = RE__SPH_STORED;
        u[0] = su[0], u[1] = su[1], u[2] = su[2]; /* before sp is written: F->sph is su's own memory */
        re__madd(v, r, u, sp);
        F->pk[RE__PKA_S_CORNER][sid] = kid;
        if (tri != RE__NONE && RE__WANT_COMPACT(an->desc) && qslot[tri & 255u] < RE__SOLVED_SLOTS &&
            qslot[tri >> 8 & 255u] < RE__SOLVED_SLOTS && qslot[tri >> 16] < RE__SOLVED_SLOTS) {
            /* the coordinates' rounding (64 ulps of |v|), but never more
               than RE__SPHERE_SOLVE_CAP r: far from the origin with a tiny
               r it reached 0.7 r, and the cylinders between solved centres
               left the faces (a grazing ray read a removed volume no
               rounded surface closed: a pass-through into the solid) */
            double tol = RE__SPHERE_SOLVE_REL * r +
                         re__min(64 * RE__DBL_EPS * (fabs(v[0]) + fabs(v[1]) + fabs(v[2])), RE__SPHERE_SOLVE_CAP * r);
            re__solve3(&an->planes[an->c_planes[pf + (tri & 255u)]], &an->planes[an->c_planes[pf + (tri >> 8 & 255u)]],
                       &an->planes[an->c_planes[pf + (tri >> 16)]], r, an->origin, x);
            re__sub(x, sp, dd);
            if (fabs(dd[0]) <= tol && fabs(dd[1]) <= tol && fabs(dd[2]) <= tol) {
                sp[0] = x[0], sp[1] = x[1], sp[2] = x[2];
                info = (unsigned short)(qslot[tri & 255u] | qslot[tri >> 8 & 255u] << 5 | qslot[tri >> 16] << 10);
            }
        }
        if (F->sinfo) F->sinfo[sid] = info;
        if (info == RE__SPH_STORED) {
            if (F->xsid) F->xsid[F->n_xsph] = sid;
            if (F->xsph != F->sph) memcpy(F->xsph + 3 * (size_t)F->n_xsph, sp, 3 * sizeof(double));
            F->n_xsph++;
        }
        re__sub(sp, v, dd);
        dm = re__max(dm, re__len(dd));
        /* the reach from the erosion's own offset u (per unit radius), not
           sp - v: far from the origin that difference carries the
           coordinates' rounding (6e-11 at 1e6), above the tangency test's
           1e-9 r, so no centre counted, the reach fell to the edges'
           strips, and the corner caps of the bands (query step 0) missed
           removed points (a degree-5 corner at offset 1e6, r 2^-7 of the
           size: reach 0.013 for 0.031; fuzz_rounded_exact, seed
           band_cap_far_from_the_origin) */
        lu = re__len(u);
        for (k = 0; k < an->c_np[c]; k++) {
            const double *n = an->planes[an->c_planes[pf + k]].n;
            double h = re__dot(n, u), tg[3];
            if (fabs(h + 1) > RE__CORNER_EPS * re__max(1.0, lu)) continue;
            re__madd(u, -h, n, tg);
            *freach = re__max(*freach, r * re__len(tg));
        }
    }
    return dm;
}

/* Along each edge of corner c the strip between the edge and the tangent
   line is sqrt(d^2 - r^2) wide, d = distance from the axis to the edge:
   freach widened to cover it. */
static double re__strip_reach(const re__an_t *an, const re__final_t *F, const re__numbering_t *N, unsigned c, double r,
                              double freach)
{
    const double *v = an->pos + 3 * (size_t)an->c_vertex[c];
    unsigned pf = an->c_pfirst[c], j;
    for (j = 0; j < an->c_np[c]; j++) {
        const re__edge_t *e = &an->edges[an->c_edges[pf + j]];
        const double *sp = F->sph + 3 * (size_t)(N->sbase[c] + an->c_start[pf + j]);
        double dd[3], ed[3], cr[3], dist;
        unsigned o2 = e->v[0] == an->c_vertex[c] ? e->v[1] : e->v[0];
        re__sub(sp, v, dd);
        re__sub(an->pos + 3 * (size_t)o2, v, ed);
        re__cross(dd, ed, cr);
        dist = re__len(cr) / re__len(ed);
        freach = re__max(freach, sqrt(re__max(dist * dist - r * r, 0.0)));
    }
    return freach;
}

/* Each rounded corner's record, references, sphere centres, reaches and
   extra cylinders, in its final numbering. */
static void re__final_corners(re__an_t *an, re__final_t *F, re__numbering_t *N, const double *patch_r, unsigned *uf)
{
    unsigned c, j, nref = 0, qslot[RE_MAX_CORNER_PLANES];
    for (c = 0; c < an->nc; c++) {
        re__corner_t *K;
        double r, freach = 0, dm;
        unsigned pf = an->c_pfirst[c], kid = N->fc[c], root;
        if (kid == RE__NONE) continue;
        K = &F->corners[kid];
        root = re__uf_find(uf, c);
        r = patch_r[root];
        if (F->pk_n[RE__PKA_K_RID]) F->pk[RE__PKA_K_RID][kid] = N->prid[N->rmap[root]];
        RE_ASSERT(!N->fc_id || (kid == c && an->c_pfirst[c] == nref));
        if (F->pk[RE__PKA_CVERTEX] != an->c_vertex) F->pk[RE__PKA_CVERTEX][kid] = re__vid(an, an->c_vertex[c]);
        if (!N->fc_id) {
            F->pk[RE__PKA_K_FIRST][kid] = nref;
            F->pk[RE__PKA_K_SFIRST][kid] = N->sbase[c];
        }
        K->np = an->c_np[c];
        K->ns = an->c_ns[c];
        K->nx = an->c_nx[c];
        K->clear = 0;
        for (j = 0; j < K->np; j++) {
            const re__edge_t *e = &an->edges[an->c_edges[pf + j]];
            F->refs[nref++] = N->ecyl[an->c_edges[pf + j]] << 1 | (e->v[0] == an->c_vertex[c] ? 1u : 0u);
        }
        /* the query numbers a corner's planes by its edges (re__corner_plane:
           plane j is the face whose half-edge of edge j leaves the corner);
           qslot maps the fan slots of c_planes to those. That face is fan
           slot j + 1's: re__corners walks the fan across each edge from the
           triangle whose half-edge arrives at v (slot j, whose plane ends
           there) to the one whose half-edge leaves it, the first of the
           next plane (slot j + 1, the first slot's after the last) */
        for (j = 0; j < K->np; j++) qslot[j + 1 < K->np ? j + 1 : 0] = j;
        dm = re__final_spheres(an, F, N, c, r, qslot, &freach);
        freach = re__strip_reach(an, F, N, c, r, freach);
        /* 1.5: margin over the bound (0.7 fails the exactness tests) */
        N->reach[kid] = 1.5 * freach;
        N->dmax[kid] = dm;
        /* the walk measures from the first sphere, not from v: widen by |s - v| */
        K->walk = re__float_up((N->reach[kid] + r + dm) * (1 + 1e-6));
        if (F->pk_n[RE__PKA_K_XFIRST]) F->pk[RE__PKA_K_XFIRST][kid] = N->xbase[c];
        for (j = 0; j < K->nx; j++) {
            const unsigned *x = an->c_x + 4 * (size_t)(an->c_xfirst[c] + j);
            re__xcyl_t *xc = &F->xcyls[N->xbase[c] + j - F->n_edge_cyls];
            F->pk[RE__PKA_X_CORNER][N->xbase[c] + j - F->n_edge_cyls] = kid;
            xc->p[0] = (unsigned char)qslot[x[0]];
            xc->p[1] = (unsigned char)qslot[x[1]];
            xc->s[0] = (unsigned char)x[2];
            xc->s[1] = (unsigned char)x[3];
        }
    }
    RE_ASSERT(RE__WANT_COMPACT(an->desc) || F->n_xsph == F->n_spheres); /* re__cptr reads xsph by sphere id */
}

/* Each rounded edge's cylinder: its end spheres and its two faces. */
static void re__final_edge_cyls(const re__an_t *an, re__final_t *F, const re__numbering_t *N)
{
    unsigned i;
    for (i = 0; i < an->E; i++) {
        const re__edge_t *e = &an->edges[i];
        re__cyl_t *cy;
        unsigned h0, h1;
        if (N->ecyl[i] == RE__NONE) continue;
        cy = &F->cyls[N->ecyl[i]];
        cy->s[0] = N->sbase[an->vcorner[e->v[0]]] + an->edge_end[2 * i];
        cy->s[1] = N->sbase[an->vcorner[e->v[1]]] + an->edge_end[2 * i + 1];
        /* p[0]: the face whose triangle runs v[0] -> v[1], on the left of
           the edge leaving v[0] (seen from outside); p[1] is on the left
           leaving v[1]. Around a corner every face plane is on the left of
           exactly one of its edges, so the query reads each once. */
        h0 = an->tri[e->he[0]] == e->v[0] ? e->he[0] : e->he[1];
        h1 = h0 == e->he[0] ? e->he[1] : e->he[0];
        cy->p[0] = N->pmap[an->tplane[h0 / 3]];
        cy->p[1] = N->pmap[an->tplane[h1 / 3]];
        F->pk[RE__PKA_C_S0][N->ecyl[i]] = cy->s[0];
    }
}

/* Detection (§3.1): the removed zone on a face lies within g, the larger
   face reach of the edge's two corners, of the mesh edge. The query tests
   the distance to the edge's line (from the two face planes, so the
   vertices need not be stored) and the axial position along the rounding
   axis: within g of the edge's vertices, so within m of its end spheres,
   m - g the larger offset of a vertex from its end sphere along the axis.
   Both are rounded up (bfloat16, or one byte on a shared exponent in the
   compact layout). The kd box (relative to the origin, box[6 i ..], and
   their hull [lo, hi]) holds that set: the axis extended by M at both
   ends, widened by M, where M - g, the larger dmax of the two corners, is
   at least |sphere - vertex| (the edge line is that close to the axis). */
/* Edge cylinder i's reach across, g (returned, without margin), and *M =
   g + the larger dmax of its two corners, with the 1e-6 margin. */
static double re__det_reaches(const re__final_t *F, const re__numbering_t *N, unsigned i, double *M)
{
    unsigned ka = F->pk[RE__PKA_S_CORNER][F->cyls[i].s[0]], kb = F->pk[RE__PKA_S_CORNER][F->cyls[i].s[1]];
    double g = re__max(N->reach[ka], N->reach[kb]);
    *M = (g + re__max(N->dmax[ka], N->dmax[kb])) * (1 + 1e-6);
    return g;
}

static re_result_t re__detection_boxes(re__an_t *an, re__arena_t *ar, re__final_t *F, const re__numbering_t *N, double *box,
                                       double lo[3], double hi[3])
{
    unsigned char *cshort = NULL; /* with straight chains: per edge cylinder, its box's ends at split vertices */
    unsigned i, a, ei;
    for (i = 0; i < 3; i++) lo[i] = HUGE_VAL, hi[i] = -HUGE_VAL;
    F->det_e0 = 1;
    if (F->det8) { /* the largest M fits re__det8 (re__det8_exp is monotone: one call for it) */
        double most = 0, M;
        unsigned ex;
        for (i = 0; i < F->n_edge_cyls; i++) {
            (void)re__det_reaches(F, N, i, &M);
            most = re__max(most, M);
        }
        ex = re__det8_exp(most);
        F->det_e0 = ex > 16u ? ex - 15u : 1u;
    }
    /* a segment inside a straight chain (re__chain_respan: its cylinder
       spans the chain) is detected only along its own span, and the
       segments' boxes join along the chain: at a split vertex the box is
       not extended by M, and it is the tight box of the cylinder of radius
       M around the axis (a box widened by M along the axis too held a point
       of a finely split edge in hundreds of segments' boxes) */
    if (N->csph) {
        RE__TAKE(cshort, unsigned char, F->n_edge_cyls + 1);
        for (i = 0; i < F->n_edge_cyls; i++) cshort[i] = 0;
        for (i = 0; i < an->E; i++)
            if (N->ecyl[i] != RE__NONE && N->csph[2 * i] != RE__NONE)
                cshort[N->ecyl[i]] = (unsigned char)(4u | (an->c_np[an->vcorner[an->edges[i].v[0]]] == 2 ? 1u : 0u) |
                                                     (an->c_np[an->vcorner[an->edges[i].v[1]]] == 2 ? 2u : 0u));
    }
    for (i = 0, ei = 0; i < F->n_edge_cyls; i++, ei++) {
        const double *s0 = F->sph + 3 * (size_t)F->cyls[i].s[0], *s1 = F->sph + 3 * (size_t)F->cyls[i].s[1];
        double u[3], L, e0[3], e1[3], d0[3], d1[3], m, M, g = re__det_reaches(F, N, i, &M);
        while (N->ecyl[ei] != i) ei++; /* cylinders are numbered in edge order (re__numbering) */
        re__sub(s1, s0, u);
        L = re__len(u);
        if (L > 0) u[0] /= L, u[1] /= L, u[2] /= L;
        re__sub(an->pos + 3 * (size_t)an->edges[ei].v[0], s0, d0);
        re__sub(an->pos + 3 * (size_t)an->edges[ei].v[1], s1, d1);
        /* at most M. A straight chain's segment has offset 0 at a split
           vertex (its sphere lies beside it); the query measures from the
           chain's end spheres (re__chain_respan, after this step), and the
           segment's zone, held to its own span by its box, lies between
           them */
        m = re__min(M, (g + re__max(fabs(re__dot(d0, u)), fabs(re__dot(d1, u)))) * (1 + 1e-6));
        g *= 1 + 1e-6;
        if (F->det8) {
            F->det8[2 * i] = re__det8_up(g, F->det_e0);
            F->det8[2 * i + 1] = re__det8_up(m, F->det_e0);
            M = re__det8(re__det8_up(M, F->det_e0), F->det_e0);
        } else {
            F->det[2 * i] = re__det_up(g);
            F->det[2 * i + 1] = re__det_up(m);
            M = re__det(re__det_up(M));
        }
        /* the box from M (as rounded up for storage, like g and m) */
        re__madd(s0, cshort && (cshort[i] & 1u) ? 0.0 : -M, u, e0);
        re__madd(s1, cshort && (cshort[i] & 2u) ? 0.0 : M, u, e1);
        for (a = 0; a < 3; a++) {
            /* across the axis only, for a chain's segment; rounded up */
            double wa = cshort && cshort[i] ? M * sqrt(re__max(0.0, 1 - u[a] * u[a])) * (1 + 1e-9) + 1e-12 * M : M;
            box[6 * i + a] = re__min(e0[a], e1[a]) - wa - an->origin[a];
            box[6 * i + 3 + a] = re__max(e0[a], e1[a]) + wa - an->origin[a];
            lo[a] = re__min(lo[a], box[6 * i + a]);
            hi[a] = re__max(hi[a], box[6 * i + 3 + a]);
        }
    }
    return RE_OK;
}

/* The detection radii and the kd-tree over the edge cylinders' boxes
   (§3.2), its leaf lists narrowed to 16 bits; the boxes and partition
   lists are scratch of this step only. */
static re_result_t re__detection_tree(re__an_t *an, re__arena_t *ar, re__final_t *F, const re__numbering_t *N)
{
    double *box, lo[3], hi[3];
    unsigned i, root, budget = RE__KD_DUP * F->n_edge_cyls + (RE__WANT_COMPACT(an->desc) ? 0u : RE__KD_DUP_EXTRA);
    size_t kd_mark;
    re_result_t rc;
    F->kd.cap_leafrefs = budget + 64;
    F->kd.cap_nodes = RE__KD_NODE_CAP(F->kd.cap_leafrefs);
    F->kd.cap_tmp = 6 * F->n_edge_cyls + 64;
    if (F->kd.cap_nodes >= 0x3FFFFFFFu) return re__fail(an, RE_ERR_TOO_LARGE, -1, "too many rounded edges for the kd-tree");
    RE__TAKE(F->kd.nodes, re__node_t, F->kd.cap_nodes);
    RE__TAKE(F->kd.leafrefs, unsigned, F->kd.cap_leafrefs);
    kd_mark = ar->used;
    RE__TAKE(box, double, 6 * (size_t)F->n_edge_cyls + 1);
    if ((rc = re__detection_boxes(an, ar, F, N, box, lo, hi)) != RE_OK) return rc;
    F->kd.box = box;
    F->kd.compact = RE__WANT_COMPACT(an->desc);
    F->kd.n_nodes = F->kd.n_leafrefs = F->kd.n_leaves = 0;
    RE__TAKE(F->kd.tmp, unsigned, F->kd.cap_tmp);
    for (i = 0; i < F->n_edge_cyls; i++) F->kd.tmp[i] = i;
    F->kd.n_tmp = F->n_edge_cyls;
    if ((rc = re__kd_build_top(an, &F->kd, F->n_edge_cyls, lo, hi, budget, &root)) != RE_OK) return rc;
    /* past its capacities (not with the real ones, RE__KD_NODE_CAP): not a
       scratch shortage, which re_build() would retry */
    if (root == RE__NONE) return re__fail(an, RE_ERR_TOO_LARGE, -1, "kd-tree past its node capacity");
    F->kd.box = NULL;
    F->kd.tmp = NULL;
    ar->used = kd_mark;
    F->n_leaf16 = re__kd_narrow(&F->kd, NULL, NULL);
    if (F->n_leaf16 >= 0x3FFFFFFFu) return re__fail(an, RE_ERR_TOO_LARGE, -1, "too many rounded edges for the kd-tree");
    return RE_OK;
}

/* A straight chain is one rounding cylinder between its end corners (its
   inner spheres lie on the axis, inside it): each segment's cylinder spans
   the whole chain, so a query near the chain meets its two end corners,
   not every split vertex on the way, and its walk crosses the chain in one
   step. Detection stays local: the kd boxes and detection radii come from
   the segment's own spheres (re__detection_boxes, before this). */
static void re__chain_respan(const re__an_t *an, re__final_t *F, const re__numbering_t *N)
{
    unsigned i;
    for (i = 0; i < an->E; i++) {
        unsigned c = N->ecyl[i];
        if (c == RE__NONE || N->csph[2 * i] == RE__NONE) continue;
        F->cyls[c].s[0] = N->csph[2 * i];
        F->cyls[c].s[1] = N->csph[2 * i + 1];
        F->pk[RE__PKA_C_S0][c] = N->csph[2 * i];
    }
    F->n_xs1 = re__count_xs1(F);
    F->pk_full[RE__PKA_C_S0] = re__pk_full_blocks(F->pk[RE__PKA_C_S0], F->pk_n[RE__PKA_C_S0]);
}

/* The scene's arrays for one object from its analysis (docs: construction,
   steps 7-9): numbering, corners and spheres, cylinders, the exit gate,
   detection and its kd-tree, straight chains, bands. */
static re_result_t re__finish(re__an_t *an, re__arena_t *ar, const double *patch_r, unsigned *uf, re__final_t *F)
{
    re__numbering_t N;
    re_result_t rc;
    unsigned i;
    memset(&N, 0, sizeof N);
    if ((rc = re__number_features(an, ar, uf, F, &N)) != RE_OK || (rc = re__chain_axes(an, ar, patch_r, uf, &N)) != RE_OK)
        return rc;
    re__number_planes(an, F, N.pmap);
    if ((rc = re__patch_radii(an, ar, patch_r, uf, F, &N)) != RE_OK || (rc = re__take_final(an, ar, F, &N)) != RE_OK)
        return rc;
    re__final_corners(an, F, &N, patch_r, uf);
    re__final_edge_cyls(an, F, &N);
    F->n_xs1 = re__count_xs1(F);
    for (i = 0; i < RE__PKA_N; i++) F->pk_full[i] = re__pk_full_blocks(F->pk[i], F->pk_n[i]);
    if ((rc = re__exit_clearance(an, ar, F)) != RE_OK || (rc = re__detection_tree(an, ar, F, &N)) != RE_OK) return rc;
    if (N.csph) re__chain_respan(an, F, &N);
#ifndef RE_NO_BANDS
    if (an->sizing) { /* the bands' bytes are 4 per triangle: only their scratch counts */
        re__bandwork_t B;
        size_t mark;
        if ((rc = re__bands_take(an, ar, F, &B, &mark)) != RE_OK) return rc;
        ar->used = mark;
    } else if ((rc = re__bands(an, ar, N.fc, patch_r, uf, N.reach, F)) != RE_OK)
        return rc;
#endif
    if (N.csph && (rc = re__drop_chain_corners(an, ar, F)) != RE_OK) return rc;
    an->st.rounded_corners += F->n_corners;
    an->st.spheres += F->n_spheres;
    an->st.cylinders += F->n_cyls;
    an->st.extra_cylinders += F->n_cyls - F->n_edge_cyls;
    an->st.kd_nodes += F->kd.n_nodes;
    an->st.kd_leaves += F->kd.n_leaves;
    an->st.kd_leaf_refs += F->kd.n_leafrefs;
    return RE_OK;
}

static size_t re__object_bytes(const re__an_t *an, const re__final_t *F)
{
    size_t b = 0;
    unsigned i;
    for (i = 0; i < RE__PKA_N; i++) b += re__pk_bytes(F->pk_n[i], F->pk_full[i]);
    return b + RE__ALIGN(RE__BAND_BYTES * (size_t)an->T) + RE__ALIGN(sizeof(re__plane_t) * F->n_planes) +
           (RE__WANT_COMPACT(an->desc) ? RE__ALIGN(sizeof(unsigned short) * F->n_spheres) + RE__ALIGN(sizeof(unsigned) * F->n_xsph) : 0) +
           RE__ALIGN(sizeof(double) * 3 * F->n_xsph) +
           RE__ALIGN(sizeof(re__ecyl_t) * F->n_edge_cyls) +
           (RE__WANT_COMPACT(an->desc)
                ? RE__ALIGN(sizeof(unsigned short) * F->n_edge_cyls) + RE__ALIGN(sizeof(unsigned) * 2 * (size_t)F->n_xs1)
                : RE__ALIGN(sizeof(unsigned) * F->n_edge_cyls)) +
           RE__ALIGN(sizeof(re__xcyl_t) * (F->n_cyls - F->n_edge_cyls)) +
           (RE__WANT_COMPACT(an->desc) ? RE__ALIGN(2 * (size_t)F->n_edge_cyls) : RE__ALIGN(sizeof(unsigned short) * 2 * F->n_edge_cyls)) +
           RE__ALIGN(sizeof(re__corner_t) * F->n_corners) + RE__ALIGN(sizeof(double) * F->n_radii) +
           RE__ALIGN(sizeof(unsigned) * F->n_refs) + RE__ALIGN(sizeof(re__node_t) * F->kd.n_nodes) +
           RE__ALIGN(sizeof(unsigned short) * F->n_leaf16);
}

static void *re__put(unsigned char **at, const void *src, size_t bytes)
{
    void *dst = *at;
    if (bytes) memcpy(dst, src, bytes);
    re__skip(at, bytes);
    return dst;
}

static void re__pack(const re__an_t *an, const re__final_t *F, unsigned char *mem, re__object_t *o)
{
    unsigned char *at = mem;
    unsigned c;
    o->n_tris = an->T;
    o->n_planes = F->n_planes;
    o->n_spheres = F->n_spheres;
    o->n_xsph = F->n_xsph;
    o->compact = RE__WANT_COMPACT(an->desc);
    o->n_cyls = F->n_cyls;
    o->n_edge_cyls = F->n_edge_cyls;
    o->n_corners = F->n_corners;
    o->n_refs = F->n_refs;
    o->n_nodes = F->kd.n_nodes;
    o->n_leaf16 = (unsigned)F->n_leaf16;
    o->n_radii = F->n_radii;
    o->size = an->size;
    for (c = 0; c < 3; c++) o->origin[c] = an->origin[c];
#define RE__PUT_PK(field, a) o->field = re__pk_put(&at, F->pk[a], F->pk_n[a], F->pk_full[a])
    RE__PUT_PK(tri_plane, RE__PKA_TRI_PLANE);
    RE__PUT_PK(cvertex, RE__PKA_CVERTEX);
    RE__PUT_PK(k_first, RE__PKA_K_FIRST);
    RE__PUT_PK(k_sfirst, RE__PKA_K_SFIRST);
    RE__PUT_PK(k_rid, RE__PKA_K_RID);
    RE__PUT_PK(k_xfirst, RE__PKA_K_XFIRST);
    RE__PUT_PK(c_s0, RE__PKA_C_S0);
    RE__PUT_PK(s_corner, RE__PKA_S_CORNER);
    RE__PUT_PK(x_corner, RE__PKA_X_CORNER);
#undef RE__PUT_PK
    o->bands = RE__BAND_BYTES ? (const unsigned char *)re__put(&at, F->bands, RE__BAND_BYTES * (size_t)an->T) : NULL;
    o->planes = (const re__plane_t *)re__put(&at, F->planes, sizeof(re__plane_t) * F->n_planes);
    o->sinfo = NULL, o->xsid = NULL;
    if (RE__COMPACT(o)) {
        o->sinfo = (const unsigned short *)re__put(&at, F->sinfo, sizeof(unsigned short) * F->n_spheres);
        o->xsid = (const unsigned *)re__put(&at, F->xsid, sizeof(unsigned) * F->n_xsph);
    }
    o->xsph = (const double *)re__put(&at, F->xsph, sizeof(double) * 3 * F->n_xsph);
    {
        re__ecyl_t *ec = (re__ecyl_t *)at;
        unsigned short *ds;
        unsigned *xs, nx = 0;
        for (c = 0; c < F->n_edge_cyls; c++) ec[c].p[0] = F->cyls[c].p[0], ec[c].p[1] = F->cyls[c].p[1];
        o->cyls = ec;
        re__skip(&at, sizeof(re__ecyl_t) * F->n_edge_cyls);
        o->s1w = NULL, o->ds1 = NULL, o->xs1 = NULL, o->n_xs1 = 0;
        if (!RE__COMPACT(o)) {
            unsigned *w = (unsigned *)at;
            for (c = 0; c < F->n_edge_cyls; c++) w[c] = F->cyls[c].s[1];
            o->s1w = w;
            re__skip(&at, sizeof(unsigned) * F->n_edge_cyls);
        }
        ds = (unsigned short *)at;
        xs = (unsigned *)(at + RE__ALIGN(sizeof(unsigned short) * F->n_edge_cyls));
        for (c = 0; RE__COMPACT(o) && c < F->n_edge_cyls; c++) {
            ds[c] = (unsigned short)(re__s1_near(&F->cyls[c]) ? F->cyls[c].s[1] - F->cyls[c].s[0] : RE__DS1_FAR);
            if (ds[c] == RE__DS1_FAR) xs[2 * nx] = c, xs[2 * nx + 1] = F->cyls[c].s[1], nx++;
        }
        if (RE__COMPACT(o)) {
            RE_ASSERT(nx == F->n_xs1);
            re__skip(&at, sizeof(unsigned short) * F->n_edge_cyls);
            re__skip(&at, sizeof(unsigned) * 2 * (size_t)nx);
            o->ds1 = ds, o->xs1 = xs, o->n_xs1 = nx;
        }
    }
    o->xcyls = (const re__xcyl_t *)re__put(&at, F->xcyls, sizeof(re__xcyl_t) * (F->n_cyls - F->n_edge_cyls));
    o->det = NULL, o->det8 = NULL, o->det_e0 = F->det_e0;
    if (RE__COMPACT(o))
        o->det8 = (const unsigned char *)re__put(&at, F->det8, 2 * (size_t)F->n_edge_cyls);
    else
        o->det = (const unsigned short *)re__put(&at, F->det, sizeof(unsigned short) * 2 * F->n_edge_cyls);
    o->corners = (const re__corner_t *)re__put(&at, F->corners, sizeof(re__corner_t) * F->n_corners);
    o->radii = (const double *)re__put(&at, F->radii, sizeof(double) * F->n_radii);
    o->refs = (const unsigned *)re__put(&at, F->refs, sizeof(unsigned) * F->n_refs);
    o->nodes = (const re__node_t *)re__put(&at, F->kd.nodes, sizeof(re__node_t) * F->kd.n_nodes);
    o->leaf16 = (const unsigned short *)at;
    re__kd_narrow(&F->kd, (re__node_t *)o->nodes, (unsigned short *)at);
    re__skip(&at, sizeof(unsigned short) * F->n_leaf16);
    o->rmax = 0;
    for (c = 0; c < F->n_radii; c++) o->rmax = re__max(o->rmax, F->radii[c]);
}

/* ---- Per-object driver --------------------------------------------------------- */

/* re_build()'s first scratch size for an object; when it is short the
   build doubles it and analyses the object again. Tests lower the bound
   to run that retry (tests/test_rounded_packing.c). */
#ifndef RE__SCRATCH_PER_TRIANGLE
#define RE__SCRATCH_PER_TRIANGLE 1800u
#endif
#ifndef RE__SCRATCH_BASE
#define RE__SCRATCH_BASE 65536u
#endif
static size_t re__scratch_bound(const re_mesh_t *m)
{
    unsigned T = 0;
    long long bad;
    if (re__count_tris(m, &T, &bad) != RE_OK) T = 0;
    return 128u * (size_t)m->vertex_count + RE__SCRATCH_PER_TRIANGLE * (size_t)T + RE__SCRATCH_BASE;
}

static re_result_t re__analyze(const re_scene_desc_t *desc, unsigned obj, int sizing, unsigned inner, re__arena_t *ar,
                               re_diag_t *diag, re__an_t *an, re__final_t *F, unsigned long long report_skip)
{
    const re_mesh_t *m = &desc->objects[obj];
    re_result_t rc;
    double *patch_r = NULL; /* set by re__radii (initialised for gcc's -O1/-O3 -Wmaybe-uninitialized) */
    unsigned *uf = NULL;
    long long bad;
    char msg[128];
    memset(an, 0, sizeof *an);
    memset(F, 0, sizeof *F);
    an->desc = desc;
    an->m = m;
    an->obj = obj;
    an->sizing = sizing;
    an->inner = inner ? inner : 1u;
    an->diag = diag;
    an->report_skip = report_skip;
    if ((m->vertex_count && !m->positions) || (m->index_count && !m->indices) ||
        (m->position_type != RE_FLOAT64 && m->position_type != RE_FLOAT32))
        return re__fail(an, RE_ERR_INVALID_ARG, -1, "NULL positions/indices or unknown position_type");
    if (m->position_stride && m->position_stride < 3 * (m->position_type == RE_FLOAT32 ? sizeof(float) : sizeof(double)))
        return re__fail(an, RE_ERR_INVALID_ARG, -1, "position_stride smaller than one vertex");
    if (!m->edge_radius && !(m->radius > 0 && isfinite(m->radius))) {
        snprintf(msg, sizeof msg, "radius %g must be finite and > 0", m->radius);
        return re__fail(an, RE_ERR_BAD_RADIUS, -1, msg);
    }
    if (!isfinite(m->radius)) return re__fail(an, RE_ERR_BAD_RADIUS, -1, "radius is not finite");
    if (!(m->flat_sin >= 0 && m->flat_sin <= RE_FLAT_SIN_LIMIT)) {
        snprintf(msg, sizeof msg, "flat_sin %g must be 0 (automatic) or in (0, %g]", m->flat_sin, RE_FLAT_SIN_LIMIT);
        return re__fail(an, RE_ERR_INVALID_ARG, -1, msg);
    }
    rc = re__count_tris(m, &an->T, &bad);
    if (rc == RE_ERR_BAD_FACE) {
        if (bad >= 0) snprintf(msg, sizeof msg, "polygon %lld has fewer than 3 corners", bad);
        else snprintf(msg, sizeof msg, "index_count %u is not 3 * triangles or the sum of face_sizes", m->index_count);
        return re__fail(an, rc, bad, msg);
    }
    if (rc != RE_OK) return re__fail(an, rc, -1, "too many triangles");
    an->V = an->V0 = m->vertex_count;
    if (an->V >= 0x7FFFFFFFu) return re__fail(an, RE_ERR_TOO_LARGE, -1, "too many vertices");
    an->st.triangles = an->T;
    if ((rc = re__triangles(an, ar)) != RE_OK) return rc;
    if (an->size > 0 && !(an->size >= RE_SIZE_MIN && an->size <= RE_SIZE_MAX)) {
        snprintf(msg, sizeof msg, "size %g outside [%g, %g]: scale the object's positions", an->size, RE_SIZE_MIN, RE_SIZE_MAX);
        return re__fail(an, RE_ERR_BAD_SCALE, -1, msg);
    }
    if ((rc = re__edges(an, ar)) != RE_OK) return rc;
    if (an->fins && (rc = re__split_fans(an, ar)) != RE_OK) return rc;
    if ((rc = re__planes(an, ar)) != RE_OK) return rc; /* per triangle: the same after step 2a */
    if ((rc = re__corners(an, ar)) != RE_OK) return rc;
    if (an->fans_wanted && ((rc = re__split_fans(an, ar)) != RE_OK || (rc = re__corners(an, ar)) != RE_OK)) return rc;
    re__edge_reports(an);
    re__corner_reports(an);
    if ((rc = re__propagate(an, ar)) != RE_OK) return rc;
    if ((rc = re__radii(an, ar, &patch_r, &uf)) != RE_OK) return rc;
    return re__finish(an, ar, patch_r, uf, F);
}

static void re__add_stats(re_stats_t *a, const re_stats_t *b)
{
    a->triangles += b->triangles;
    a->edges += b->edges;
    a->flat_edges += b->flat_edges;
    a->convex_edges += b->convex_edges;
    a->concave_edges += b->concave_edges;
    a->boundary_edges += b->boundary_edges;
    a->nonmanifold_edges += b->nonmanifold_edges;
    a->rounded_edges += b->rounded_edges;
    a->rounded_corners += b->rounded_corners;
    a->mixed_vertices += b->mixed_vertices;
    a->spheres += b->spheres;
    a->cylinders += b->cylinders;
    a->extra_cylinders += b->extra_cylinders;
    a->clamped += b->clamped;
    a->kd_nodes += b->kd_nodes;
    a->kd_leaves += b->kd_leaves;
    a->kd_leaf_refs += b->kd_leaf_refs;
    a->bytes += b->bytes;
}

static re_result_t re__check_desc(const re_scene_desc_t *desc, re_diag_t *diag)
{
    if (diag) {
        diag->result = RE_OK;
        diag->element = -1;
        diag->object = 0;
        diag->message[0] = 0;
    }
    if (!desc || (desc->object_count && !desc->objects) || desc->object_count >= 0x10000000u ||
        (desc->radius_policy != RE_RADIUS_CLAMP && desc->radius_policy != RE_RADIUS_REJECT) ||
        (desc->bad_input != RE_BAD_INPUT_REJECT && desc->bad_input != RE_BAD_INPUT_SKIP) ||
        (desc->layout != RE_LAYOUT_FAST && desc->layout != RE_LAYOUT_COMPACT))
        return re__diag_fail(diag, RE_ERR_INVALID_ARG, -1, -1, "NULL desc/objects or an unknown policy or layout value");
#ifdef RE_NO_COMPACT
    if (desc->layout == RE_LAYOUT_COMPACT)
        return re__diag_fail(diag, RE_ERR_INVALID_ARG, -1, -1, "RE_LAYOUT_COMPACT is compiled out (RE_NO_COMPACT)");
#endif
    return RE_OK;
}

static size_t re__header_bytes(unsigned n) { return RE__ALIGN(sizeof(re_scene_t)) + RE__ALIGN(sizeof(re__object_t) * n); }

/* One task of re_build() or re_build_sizes() (THREADS): the objects it
   owns, in increasing order, through one scratch buffer of its own. */
typedef struct re__task_t {
    re_result_t rc;
    int ran;             /* the host called it */
    unsigned failed;     /* the object that failed (rc != RE_OK) */
    re_diag_t diag;
    re_stats_t st;       /* its objects' counts and bytes, summed */
    size_t high;         /* sizing: the largest scratch use */
} re__task_t;

typedef struct re__tasks_t {
    const re_scene_desc_t *desc;
    re_scene_t *S;          /* the scene to fill; NULL: sizes only */
    const unsigned char *owner; /* each object's task; NULL: one task */
    re__task_t *task;
    unsigned inner;             /* one task: its objects' steps split this many ways (re__an_t.inner) */
} re__tasks_t;

static int re__owns(const re__tasks_t *J, unsigned w, unsigned i) { return !J->owner || J->owner[i] == w; }

/* Analyse object i in the task's scratch (grown and retried when its bound
   was short) and, when building, pack it into a block of its own. */
static re_result_t re__build_object(const re__tasks_t *J, re__task_t *W, unsigned i, void **scratch, size_t *cap)
{
    const re_scene_desc_t *desc = J->desc;
    re__an_t an;
    re__final_t F;
    re__arena_t ar;
    re_result_t rc;
    size_t need;
    unsigned long long made = 0;
    for (;;) {
        if (!*scratch) { /* fresh (advised once), else the previous object's */
            if (!(*scratch = RE_MALLOC(*cap, desc->alloc_ctx))) return RE_ERR_OUT_OF_MEMORY;
            re__advise_huge(*scratch, *cap);
        }
        ar.base = (unsigned char *)*scratch;
        ar.cap = *cap;
        ar.used = ar.high = 0;
        rc = re__analyze(desc, i, !J->S, J->inner, &ar, &W->diag, &an, &F, made);
        if (rc != RE_ERR_BUFFER_TOO_SMALL) break;
        made = an.reports; /* delivered: the next attempt makes them again, silently */
        RE_FREE(*scratch, desc->alloc_ctx); /* the bound was short: grow, retry */
        *scratch = NULL;
        *cap *= 2;
    }
    if (rc != RE_OK) return rc;
    need = re__object_bytes(&an, &F);
    an.st.bytes = need;
    re__add_stats(&W->st, &an.st);
    if (!J->S) {
        if (ar.high + 16 > W->high) W->high = ar.high + 16;
        return RE_OK;
    }
    J->S->objects[i].block = need ? RE_MALLOC(need, desc->alloc_ctx) : NULL;
    if (need && !J->S->objects[i].block) return RE_ERR_OUT_OF_MEMORY;
    re__advise_huge(J->S->objects[i].block, need);
    re__pack(&an, &F, (unsigned char *)J->S->objects[i].block, &J->S->objects[i]);
    J->S->objects[i].bytes = need;
    return RE_OK;
}

/* re_task_fn: task w builds (or sizes) its objects; it stops at its first
   failure, which is then the lowest-numbered failing object it owns. */
static void re__run_task(void *ctx, unsigned w)
{
    const re__tasks_t *J = (const re__tasks_t *)ctx;
    const re_scene_desc_t *desc = J->desc;
    re__task_t *W = &J->task[w];
    void *scratch = NULL;
    size_t cap = 0;
    unsigned i;
    W->ran = 1;
    for (i = 0; i < desc->object_count; i++) {
        size_t b = re__owns(J, w, i) ? re__scratch_bound(&desc->objects[i]) : 0;
        if (b > cap) cap = b;
    }
    for (i = 0; i < desc->object_count && W->rc == RE_OK; i++)
        if (re__owns(J, w, i) && (W->rc = re__build_object(J, W, i, &scratch, &cap)) != RE_OK) W->failed = i;
    if (scratch) RE_FREE(scratch, desc->alloc_ctx);
}

/* The objects' tasks: largest first (by index count, ties by number), each
   to the task with the least so far (ties to the lowest task), so that
   equal objects share the tasks evenly. */
static re_result_t re__assign_tasks(const re_scene_desc_t *desc, unsigned k, unsigned char *owner)
{
    unsigned long long *key, load[RE_MAX_BUILD_TASKS];
    unsigned i, w, n = desc->object_count;
    if (!(key = (unsigned long long *)RE_MALLOC(sizeof *key * n, desc->alloc_ctx))) return RE_ERR_OUT_OF_MEMORY;
    for (i = 0; i < n; i++) key[i] = ((unsigned long long)(0xFFFFFFFFu - desc->objects[i].index_count) << 28) | i;
    re__sort(key, n, sizeof *key, re__cmp_u64);
    memset(load, 0, sizeof load);
    for (i = 0; i < n; i++) {
        unsigned o = (unsigned)(key[i] & 0x0FFFFFFFu), best = 0;
        for (w = 1; w < k; w++)
            if (load[w] < load[best]) best = w;
        owner[o] = (unsigned char)best;
        load[best] += (unsigned long long)desc->objects[o].index_count + 1;
    }
    RE_FREE(key, desc->alloc_ctx);
    return RE_OK;
}

/* Run the build (S) or the sizing (S NULL) of every object, on the host's
   threads when desc asks for it; on failure, the lowest failing object's
   diagnostic goes to diag. The objects' stats are added to *st; sizing
   keeps the largest scratch use in *high. */
static re_result_t re__run_tasks(const re_scene_desc_t *desc, re_scene_t *S, re_diag_t *diag, re_stats_t *st, size_t *high)
{
    re__tasks_t J;
    re__task_t one, *task = &one;
    unsigned char *owner = NULL;
    unsigned k = desc->parallel ? desc->threads : 1, w, first = 0;
    re_result_t rc = RE_OK;
    if (k > RE_MAX_BUILD_TASKS) k = RE_MAX_BUILD_TASKS;
    J.inner = desc->object_count == 1 && k > 1 ? k : 1u; /* one object: its steps are split instead */
    if (k > desc->object_count) k = desc->object_count;
    if (k > 1) {
        size_t tb = RE__ALIGN(sizeof(re__task_t) * k);
        if (!(task = (re__task_t *)RE_MALLOC(tb + desc->object_count, desc->alloc_ctx))) return re__diag_fail(diag, RE_ERR_OUT_OF_MEMORY, -1, -1, "out of memory");
        owner = (unsigned char *)task + tb;
        if ((rc = re__assign_tasks(desc, k, owner)) != RE_OK) {
            RE_FREE(task, desc->alloc_ctx);
            return re__diag_fail(diag, RE_ERR_OUT_OF_MEMORY, -1, -1, "out of memory");
        }
    } else k = 1;
    memset(task, 0, sizeof *task * k);
    J.desc = desc, J.S = S, J.owner = owner, J.task = task;
    if (k > 1) desc->parallel(desc->parallel_user, k, re__run_task, &J);
    else re__run_task(&J, 0);
    for (w = 0; w < k; w++)
        if (!task[w].ran) { /* a host parallel-for that skipped a task: its objects are missing */
            char msg[80];
            snprintf(msg, sizeof msg, "desc.parallel returned without running task %u of %u", w, k);
            if (task != &one) RE_FREE(task, desc->alloc_ctx);
            return re__diag_fail(diag, RE_ERR_INVALID_ARG, -1, -1, msg);
        }
    for (w = 0; w < k; w++) {
        if (task[w].rc != RE_OK && (rc == RE_OK || task[w].failed < first)) {
            rc = task[w].rc;
            first = task[w].failed;
            *diag = task[w].diag;
        }
        re__add_stats(st, &task[w].st);
        if (task[w].high > *high) *high = task[w].high;
    }
    if (rc == RE_ERR_OUT_OF_MEMORY) re__diag_fail(diag, rc, first, -1, "out of memory");
    if (task != &one) RE_FREE(task, desc->alloc_ctx);
    return rc;
}

RE_DEF re_result_t re_build_sizes(const re_scene_desc_t *desc, re_sizes_t *sizes, re_diag_t *diag)
{
    re_result_t rc = re__check_desc(desc, diag);
    re_diag_t dg;
    re_stats_t st;
    size_t high = 0;
    if (rc != RE_OK) return rc;
    if (!sizes) return re__diag_fail(diag, RE_ERR_INVALID_ARG, -1, -1, "NULL sizes");
    memset(&st, 0, sizeof st);
    if ((rc = re__run_tasks(desc, NULL, diag ? diag : &dg, &st, &high)) != RE_OK) return rc;
    sizes->scene_bytes = re__header_bytes(desc->object_count) + st.bytes;
    sizes->scratch_bytes = high;
    return RE_OK;
}

RE_DEF re_result_t re_build_into(const re_scene_desc_t *desc, void *scene_mem, size_t scene_bytes,
                                 void *scratch, size_t scratch_bytes, re_scene_t **scene, re_diag_t *diag)
{
    re_result_t rc = re__check_desc(desc, diag);
    unsigned char *at;
    re_scene_t *S;
    unsigned i;
    if (rc != RE_OK) return rc;
    if (!scene || !scene_mem || (!scratch && scratch_bytes))
        return re__diag_fail(diag, RE_ERR_INVALID_ARG, -1, -1, "NULL scene or scene_mem, or NULL scratch with scratch_bytes > 0");
    if (((size_t)scene_mem | (size_t)scratch) & 15u)
        return re__diag_fail(diag, RE_ERR_INVALID_ARG, -1, -1, "scene_mem or scratch is not 16-byte aligned");
    *scene = NULL;
    if (scene_bytes < re__header_bytes(desc->object_count))
        return re__diag_fail(diag, RE_ERR_BUFFER_TOO_SMALL, -1, -1, "scene_bytes smaller than re_build_sizes() asked");
    S = (re_scene_t *)scene_mem;
    /* the whole header, its alignment gaps too: the block's bytes are then
       the same whatever the buffer held (re__skip does it past each array) */
    memset(S, 0, re__header_bytes(desc->object_count));
    S->n_objects = desc->object_count;
    S->objects = (re__object_t *)((unsigned char *)scene_mem + RE__ALIGN(sizeof(re_scene_t)));
    S->alloc_ctx = desc->alloc_ctx;
    at = (unsigned char *)scene_mem + re__header_bytes(desc->object_count);
    for (i = 0; i < desc->object_count; i++) {
        re__an_t an;
        re__final_t F;
        re__arena_t ar;
        size_t need;
        ar.base = (unsigned char *)scratch;
        ar.cap = scratch_bytes;
        ar.used = ar.high = 0;
        rc = re__analyze(desc, i, 0, 1, &ar, diag, &an, &F, 0);
        if (rc != RE_OK) return rc;
        need = re__object_bytes(&an, &F);
        if ((size_t)(at - (unsigned char *)scene_mem) + need > scene_bytes)
            return re__diag_fail(diag, RE_ERR_BUFFER_TOO_SMALL, i, -1, "scene_bytes smaller than re_build_sizes() asked");
        re__pack(&an, &F, at, &S->objects[i]);
        at += need;
        an.st.bytes = need;
        S->objects[i].bytes = need;
        re__add_stats(&S->stats, &an.st);
    }
    S->stats.bytes = (size_t)(at - (unsigned char *)scene_mem);
    *scene = S;
    return RE_OK;
}

RE_DEF void re_free(re_scene_t *scene)
{
    unsigned i;
    if (!scene || !scene->owned) return;
    for (i = 0; i < scene->n_objects; i++)
        if (scene->objects[i].block) RE_FREE(scene->objects[i].block, scene->alloc_ctx);
    RE_FREE(scene, scene->alloc_ctx);
}

RE_DEF re_result_t re_build(const re_scene_desc_t *desc, re_scene_t **scene, re_diag_t *diag)
{
    re_result_t rc = re__check_desc(desc, diag);
    re_diag_t dg;
    size_t hb, high = 0;
    re_scene_t *S;
    if (rc != RE_OK) return rc;
    if (!scene) return re__diag_fail(diag, RE_ERR_INVALID_ARG, -1, -1, "NULL scene");
    *scene = NULL;
    hb = re__header_bytes(desc->object_count);
    S = (re_scene_t *)RE_MALLOC(hb, desc->alloc_ctx);
    if (!S) return re__diag_fail(diag, RE_ERR_OUT_OF_MEMORY, -1, -1, "out of memory");
    memset(S, 0, hb);
    S->n_objects = desc->object_count;
    S->objects = (re__object_t *)((unsigned char *)S + RE__ALIGN(sizeof(re_scene_t)));
    S->alloc_ctx = desc->alloc_ctx;
    S->owned = 1;
    S->stats.bytes = hb;
    if ((rc = re__run_tasks(desc, S, diag ? diag : &dg, &S->stats, &high)) != RE_OK) {
        re_free(S);
        return rc;
    }
    *scene = S;
    return RE_OK;
}

RE_DEF void re_get_stats(const re_scene_t *scene, re_stats_t *stats)
{
    if (!stats) return;
    memset(stats, 0, sizeof *stats);
    if (scene) *stats = scene->stats;
}

RE_DEF double re_object_radius(const re_scene_t *scene, unsigned object)
{
    return scene && object < scene->n_objects ? scene->objects[object].rmax : 0.0;
}

/* ---- Query ------------------------------------------------------------------------ */

/* The roots s0 <= s1 of |w + s dp|^2 = r^2 (A = |dp|^2, B = dp.w); 0
   when the ray misses, or A is 0 (for a cylinder: parallel to the axis,
   where only the spheres matter) or not a number. They are taken from the ray's closest approach
   sc = -B/A: the offset there, w + sc dp, is at most about r long where
   the ray meets the surface, so r^2 minus its square is exact to ulps of
   r^2, where the usual discriminant B^2 - A (|w|^2 - r^2) carries ulps of
   |w|^2. From I a size away that one could not tell a tangent ray missing
   by 1e-11 from one meeting the surface, and a ray lying in a face and
   grazing its flat part took a cylinder's normal 2e-9 past the tangent
   line (5e-3 rad at r = 5e-7 of the size; fuzz_rounded_exact); here a
   tangent contact is placed to sqrt(ulps r). One division, not two. */
static inline int re__quadric_roots(const double w[3], const double dp[3], double A, double B, double r, double *s0, double *s1)
{
    double ia, sc, m[3], h;
    if (!(A > 0)) return 0;
    ia = 1 / A, sc = -B * ia;
    re__madd(w, sc, dp, m);
    h = (r * r - re__dot(m, m)) * ia;
    if (!(h >= 0)) return 0;
    h = sqrt(h);
    *s0 = sc - h, *s1 = sc + h;
    return 1;
}

/* Where a ray with roots s0 < s1 (A as in re__quadric_roots, the ray's
   own |d|^2 in dd) meets a capsule of radius r when entries before smin
   <= 0 are not accepted (RE__HOST_T_SLACK): s0, or smin when the ray is
   inside there by at most the slack's length |smin| |d| (a late host's
   point, just past the surface), or HUGE_VAL. Deeper inside at smin, the
   host's hit lies well inside the capsule, which a closed mesh never
   allows: a self-intersecting one put the clamped point 0.248 deep in a
   cylinder of r = 0.25 (fuzz_rounded_build), a rounded hit off its own
   feature. (r^2 - |w + smin d|^2 = A (smin - s0)(s1 - smin), about 2 r
   times the depth.) */
static double re__capsule_entry(double s0, double s1, double A, double dd, double r, double smin)
{
    if (s0 >= smin) return s0;
    if (s1 < smin || A * (smin - s0) * (s1 - smin) > -2 * r * smin * sqrt(dd)) return HUGE_VAL;
    return smin;
}

/* Entry of the ray I + s*d into a sphere: the smaller root (not before
   smin <= 0, see re__capsule_entry), or HUGE_VAL. */
static double re__sphere_entry(const double I[3], const double d[3], const double c[3], double r, double smin)
{
    double w[3], A = re__dot(d, d), s0, s1;
    re__sub(I, c, w);
    if (!re__quadric_roots(w, d, A, re__dot(d, w), r, &s0, &s1)) return HUGE_VAL;
    return re__capsule_entry(s0, s1, A, A, r, smin);
}

/* Entry into the side of the finite cylinder of radius r around a -> b;
   *h gets the axial position of the entry point as a fraction of |b - a|.
   The axis is left unnormalised (projections divide by |b - a|^2 once):
   this runs for every candidate capsule of every query, and a square root
   and three divisions per call showed in the render profile. */
static double re__cyl_entry(const double I[3], const double d[3], const double a[3], const double b[3],
                            double r, double smin, double *h)
{
    double u[3], w[3], dp[3], wp[3], L2, inv, du, wu, A, s0, s1, hh;
    re__sub(b, a, u);
    L2 = re__dot(u, u);
    if (!(L2 > 0)) return HUGE_VAL;
    inv = 1 / L2;
    re__sub(I, a, w);
    du = re__dot(d, u);
    wu = re__dot(w, u);
    re__madd(d, -du * inv, u, dp);
    re__madd(w, -wu * inv, u, wp);
    A = re__dot(dp, dp);
    if (!re__quadric_roots(wp, dp, A, re__dot(dp, wp), r, &s0, &s1)) return HUGE_VAL;
    if (s0 < smin && (s0 = re__capsule_entry(s0, s1, A, re__dot(d, d), r, smin)) == HUGE_VAL) return HUGE_VAL;
    hh = wu + s0 * du;
    if (hh < 0 || hh > L2) return HUGE_VAL; /* beyond the span: a sphere cap */
    *h = hh * inv;
    return s0;
}

static double re__dist2_halfline(const double p[3], const double a[3], const double d[3])
{
    double ap[3], t, q[3];
    re__sub(p, a, ap);
    t = re__max(0.0, re__dot(ap, d) / re__dot(d, d));
    re__madd(a, t, d, q);
    re__sub(p, q, q);
    return re__dot(q, q);
}

/* A corner with the packed ids most uses need (re__corner_t); its radius
   and first extra cylinder are read where they are used
   (re__k_radius, re__k_xfirst). */
typedef struct re__kv_t {
    unsigned k, first, sfirst, np, ns, nx;
} re__kv_t;

static re__kv_t re__kview(const re__object_t *o, unsigned k)
{
    re__kv_t v;
    const re__corner_t *K = &o->corners[k];
    v.k = k;
    v.first = re__pk_id(&o->k_first, k);
    v.sfirst = re__pk_id(&o->k_sfirst, k);
    v.np = K->np, v.ns = K->ns, v.nx = K->nx;
    return v;
}
static unsigned re__s_corner(const re__object_t *o, unsigned s) { return re__pk_id(&o->s_corner, s); }
/* s[1] of edge cylinder c, whose s[0] is s0 (re__ecyl_t). */
static unsigned re__cyl_s1(const re__object_t *o, unsigned c, unsigned s0)
{
    unsigned d, lo = 0, hi = o->n_xs1;
    if (!RE__COMPACT(o)) return o->s1w[c];
    d = o->ds1[c];
    if (d != RE__DS1_FAR) return s0 + d;
    while (hi - lo > 1) {
        unsigned mid = lo + (hi - lo) / 2;
        if (o->xs1[2 * mid] <= c) lo = mid; else hi = mid;
    }
    return o->xs1[2 * lo + 1];
}
/* The end sphere of a corner's reference (re__corner_t.refs) that is not
   the corner's own. */
static unsigned re__far_sphere(const re__object_t *o, unsigned ref)
{
    unsigned c = ref >> 1;
    if (!RE__COMPACT(o) && (ref & 1u)) return o->s1w[c];
    return ref & 1u ? re__cyl_s1(o, c, re__pk_id(&o->c_s0, c)) : re__pk_id(&o->c_s0, c);
}
static double re__k_radius(const re__object_t *o, unsigned k)
{
    return o->radii[o->n_radii == 1 ? 0u : re__pk_id(&o->k_rid, k)];
}
static unsigned re__k_xfirst(const re__object_t *o, unsigned k) { return re__pk_id(&o->k_xfirst, k); }


/* Face plane j < np of a corner: the one on the left of its edge cylinder j
   leaving the corner (re__final_edge_cyls orders each cylinder's planes so), which
   lists every plane of the corner once. */
static unsigned re__corner_plane(const re__object_t *o, const re__kv_t *K, unsigned j)
{
    unsigned ref = o->refs[K->first + j];
    return o->cyls[ref >> 1].p[ref & 1u ? 0 : 1];
}

/* Index in xsph of a stored centre (compact layout): its rank in xsid. */
static unsigned re__xsph_rank(const re__object_t *o, unsigned s)
{
    unsigned lo = 0, hi = o->n_xsph;
    while (hi - lo > 1) {
        unsigned mid = lo + (hi - lo) / 2;
        if (o->xsid[mid] <= s) lo = mid; else hi = mid;
    }
    return lo;
}

/* Centre of sphere s: stored, or solved from its three plane slots. */
static void re__centre(const re__object_t *o, unsigned s, double x[3])
{
    unsigned info;
    re__kv_t K;
    if (!RE__COMPACT(o) || (o->sinfo[s] & RE__SPH_STORED)) {
        memcpy(x, o->xsph + 3 * (size_t)(RE__COMPACT(o) ? re__xsph_rank(o, s) : s), 3 * sizeof(double));
        return;
    }
    info = o->sinfo[s];
    K = re__kview(o, re__s_corner(o, s));
    re__solve3(&o->planes[re__corner_plane(o, &K, info & 31u)], &o->planes[re__corner_plane(o, &K, info >> 5 & 31u)],
               &o->planes[re__corner_plane(o, &K, info >> 10 & 31u)], re__k_radius(o, K.k), o->origin, x);
}

/* Global sphere ids of cylinder c's axis ends (edge or extra). */
static void re__cyl_spheres(const re__object_t *o, unsigned c, unsigned s[2])
{
    const re__xcyl_t *x;
    unsigned sf;
    if (c < o->n_edge_cyls) { s[0] = re__pk_id(&o->c_s0, c), s[1] = re__cyl_s1(o, c, s[0]); return; }
    x = &o->xcyls[c - o->n_edge_cyls];
    sf = re__pk_id(&o->k_sfirst, re__pk_id(&o->x_corner, c - o->n_edge_cyls));
    s[0] = sf + x->s[0], s[1] = sf + x->s[1];
}

/* Cylinder c (edge or extra) with global sphere and plane ids. */
static re__cyl_t re__cyl(const re__object_t *o, unsigned c)
{
    re__cyl_t cy;
    const re__xcyl_t *x;
    re__kv_t K;
    unsigned i;
    if (c < o->n_edge_cyls) {
        cy.s[0] = re__pk_id(&o->c_s0, c), cy.s[1] = re__cyl_s1(o, c, cy.s[0]), cy.p[0] = o->cyls[c].p[0], cy.p[1] = o->cyls[c].p[1];
        return cy;
    }
    x = &o->xcyls[c - o->n_edge_cyls];
    K = re__kview(o, re__pk_id(&o->x_corner, c - o->n_edge_cyls));
    for (i = 0; i < 2; i++) cy.s[i] = K.sfirst + x->s[i], cy.p[i] = re__corner_plane(o, &K, x->p[i]);
    return cy;
}

static int re__corner_has_plane(const re__object_t *o, const re__kv_t *K, unsigned f)
{
    unsigned j;
    for (j = 0; j < K->np; j++)
        if (re__corner_plane(o, K, j) == f) return 1;
    return 0;
}

/* The corners a query works on. "Is w in the set?" is asked for every
   candidate the detection and the walk meet: up to RE__SET_SCAN corners,
   a 64-bit filter of their ids mostly answers it without a search; past
   that (a finely tessellated rim under a large radius: hundreds of
   corners, where the scans were 90% of a query's time) an open-addressed
   table of their positions, filled once when the set outgrows the scan.
   Only the first RE__SET_SCAN slots of c and, past them, the table are
   ever written: nothing is cleared for the common small set. */
#define RE__SET_SCAN 64u
#define RE__SET_TAB (2u * RE__SET_CAP) /* table slots: at most half full */
typedef struct re__set_t {
    unsigned c[RE__SET_CAP], n;
    unsigned full; /* a corner was dropped: the set was at RE__SET_CAP */
    unsigned long long bloom;
    unsigned tab[RE__SET_TAB]; /* past RE__SET_SCAN: position + 1 of the corner hashed there, 0 empty */
} re__set_t;

static void re__set_init(re__set_t *S)
{
    S->n = 0;
    S->full = 0;
    S->bloom = 0;
}

static unsigned long long re__bloom_bit(unsigned c) { return 1ull << ((c * 0x9E3779B1u) >> 26); }
static unsigned re__set_slot(unsigned c) { return (c * 0x9E3779B1u) % RE__SET_TAB; }

/* The table slot of corner w: the one holding it, or the empty one where
   its probe (linear, from re__set_slot) ends. */
static unsigned re__set_probe(const re__set_t *S, unsigned w)
{
    unsigned q;
    for (q = re__set_slot(w); S->tab[q] && S->c[S->tab[q] - 1u] != w; q = (q + 1u) % RE__SET_TAB) {}
    return q;
}

/* re__set_find past RE__SET_SCAN corners: the table, out of the common path. */
RE__NOINLINE static unsigned re__set_find_in_table(const re__set_t *S, unsigned w)
{
    unsigned q = re__set_probe(S, w);
    return S->tab[q] ? S->tab[q] - 1u : S->n;
}

/* Position of corner w in the set, or n. */
static inline unsigned re__set_find(const re__set_t *S, unsigned w)
{
    unsigned q;
    if (S->n > RE__SET_SCAN) return re__set_find_in_table(S, w);
    if (!(S->bloom & re__bloom_bit(w))) return S->n;
    for (q = 0; q < S->n && S->c[q] != w; q++) {}
    return q;
}

/* Enters position i of the set into the table (its corner is not there
   yet: the set holds each corner once). */
static void re__set_hash(re__set_t *S, unsigned i) { S->tab[re__set_probe(S, S->c[i])] = i + 1u; }

static int re__set_add(re__set_t *S, unsigned c)
{
    unsigned i;
    if (re__set_find(S, c) < S->n) return 0;
    if (S->n == RE__SET_CAP) {
        S->full = 1;
        return 0;
    }
    S->c[S->n++] = c;
    S->bloom |= re__bloom_bit(c);
    if (S->n == RE__SET_SCAN + 1u) { /* outgrew the scan: the table, from here on */
        memset(S->tab, 0, sizeof S->tab);
        for (i = 0; i < S->n; i++) re__set_hash(S, i);
    } else if (S->n > RE__SET_SCAN + 1u)
        re__set_hash(S, S->n - 1u);
    return 1;
}

/* Is I (on plane f) on the flat part of its face, i.e. is I - r*n_f inside
   every shifted plane of the corners around it? (erosion + dilation: the
   flat part is the offset of the eroded face.) */
static int re__on_flat_part(const re__object_t *o, const re__set_t *S, unsigned f, const double I[3])
{
    const re__plane_t *pf = &o->planes[f];
    unsigned i, j;
    for (i = 0; i < S->n; i++) {
        re__kv_t K = re__kview(o, S->c[i]);
        double q[3], mag, r = re__k_radius(o, K.k);
        re__madd(I, -r, pf->n, q);
        mag = fabs(q[0]) + fabs(q[1]) + fabs(q[2]);
        for (j = 0; j < K.np; j++) {
            unsigned gi = re__corner_plane(o, &K, j);
            const re__plane_t *g = &o->planes[gi];
            if (gi == f) continue;
            if (re__dot(g->n, q) - (g->c - r) > RE__FLAT_ULPS * (fabs(g->c) + mag + r)) return 0;
        }
    }
    return 1;
}

/* Sphere centres solved during one query, direct-mapped by id: detection,
   the one-edge path, the walk and the capsule search ask for the same few
   spheres again and again (a box corner's sphere ends all three of its
   edges), and each solve is about 100 instructions. */
#define RE__CC 16u
typedef struct re__best_t {
    double s;
    double smin; /* earliest entry accepted (<= 0): the host's t may be late */
    re_feature_t kind;
    unsigned index;
    double h; /* axial position for cylinders, as a fraction of the axis */
    unsigned cvalid; /* bit k: cid[k], cx[k] hold a centre */
    unsigned cid[RE__CC];
    double cx[RE__CC][3];
} re__best_t;

/* Centre of sphere s for the query: the stored one (RE_LAYOUT_FAST stores
   every centre, in sphere order), else solved once into the cache. The
   pointer into the cache holds until another sphere of the same slot is
   asked for (re__cpair keeps the first of two). */
static inline const double *re__cptr(const re__object_t *o, re__best_t *b, unsigned s)
{
    unsigned k;
    if (!RE__COMPACT(o)) return o->xsph + 3 * (size_t)s;
    if (o->sinfo[s] & RE__SPH_STORED) return o->xsph + 3 * (size_t)re__xsph_rank(o, s);
    k = s & (RE__CC - 1u);
    if (!(b->cvalid >> k & 1u) || b->cid[k] != s) b->cvalid |= 1u << k, b->cid[k] = s, re__centre(o, s, b->cx[k]);
    return b->cx[k];
}
static inline void re__cpair(const re__object_t *o, re__best_t *b, unsigned s0, unsigned s1, const double **p0, const double **p1,
                             double keep[3])
{
    *p0 = re__cptr(o, b, s0);
    if (RE__COMPACT(o) && !((s0 ^ s1) & (RE__CC - 1u)) && !(o->sinfo[s0] & RE__SPH_STORED))
        keep[0] = (*p0)[0], keep[1] = (*p0)[1], keep[2] = (*p0)[2], *p0 = keep;
    *p1 = re__cptr(o, b, s1);
}

static void re__try_sphere(const re__object_t *o, unsigned s, double r, const double I[3], const double d[3], re__best_t *b)
{
    double e = re__sphere_entry(I, d, re__cptr(o, b, s), r, b->smin);
    if (e < b->s) b->s = e, b->kind = RE_FEATURE_SPHERE, b->index = s;
}

static void re__try_cyl(const re__object_t *o, unsigned c, double r, const double I[3], const double d[3], re__best_t *b)
{
    double h = 0, keep[3], e;
    const double *a, *z;
    unsigned sp[2];
    re__cyl_spheres(o, c, sp);
    re__cpair(o, b, sp[0], sp[1], &a, &z, keep);
    e = re__cyl_entry(I, d, a, z, r, b->smin, &h);
    if (e < b->s) b->s = e, b->kind = RE_FEATURE_CYLINDER, b->index = c, b->h = h;
}

/* First entry into the rounded solid among the features of the corners in
   `set`: the solid is the union of the capsules around the eroded
   polytope's vertices and edges and the flat slabs, and past I the ray is
   inside the sharp mesh, so only capsules can be entered (docs: "Query"). */
static void re__nearest_feature(const re__object_t *o, const re__set_t *S, const double I[3], const double d[3],
                                re__best_t *b)
{
    unsigned i, j;
    b->s = HUGE_VAL;
    b->kind = RE_FEATURE_FACE;
    b->index = 0;
    b->h = 0;
    for (i = 0; i < S->n; i++) {
        re__kv_t K = re__kview(o, S->c[i]);
        const unsigned *ref = o->refs + K.first;
        double r = re__k_radius(o, K.k);
        for (j = 0; j < K.ns; j++) re__try_sphere(o, K.sfirst + j, r, I, d, b);
        for (j = 0; j < K.np; j++) {
            unsigned c = ref[j] >> 1, far = re__far_sphere(o, ref[j]);
            unsigned q = re__set_find(S, re__s_corner(o, far));
            /* each feature once: an edge between two corners of the set is
               tried from the first of them, and the far end sphere only when
               its corner is not in the set (else it is one of that
               corner's own spheres) */
            if (q < i) continue;
            re__try_cyl(o, c, r, I, d, b);
            if (q == S->n) re__try_sphere(o, far, r, I, d, b);
        }
        for (j = 0; j < K.nx; j++) re__try_cyl(o, re__k_xfirst(o, K.k) + j, r, I, d, b);
    }
}

/* Where the ray leaves the sharp mesh: the first shifted-out plane among
   the corners' faces (the mesh is convex around a rounded corner). The
   candidates are compared as fractions, one division at the end. The
   walk's rounds (re__query_kd, re_secondary_origin) only add corners to
   S, so each call scans the planes of the corners added since the last
   (from E->from on) and keeps the first crossing so far: the comparisons
   of a scan of the whole set, in its order, each made once. */
typedef struct re__exit_t {
    double bn, bd;  /* the first crossing so far is at bn / bd */
    unsigned plane; /* its plane, RE__NONE before any */
    unsigned from;  /* S's corners before this one are scanned */
} re__exit_t;

static void re__exit_init(re__exit_t *E) { E->bn = HUGE_VAL, E->bd = 1, E->plane = RE__NONE, E->from = 0; }

static double re__exit(const re__object_t *o, const re__set_t *S, const double I[3], const double d[3], re__exit_t *E,
                       unsigned *plane)
{
    unsigned i, j;
    for (i = E->from; i < S->n; i++) {
        re__kv_t K = re__kview(o, S->c[i]);
        for (j = 0; j < K.np; j++) {
            unsigned gi = re__corner_plane(o, &K, j);
            const re__plane_t *g = &o->planes[gi];
            double nd = re__dot(g->n, d), num;
            if (!(nd > 0)) continue;
            num = re__max(0.0, g->c - re__dot(g->n, I));
            if (num * E->bd < E->bn * nd) E->bn = num, E->bd = nd, E->plane = gi;
        }
    }
    E->from = S->n;
    *plane = E->plane;
    return E->plane == RE__NONE ? HUGE_VAL : E->bn / E->bd;
}

static void re__feature_normal(const re__object_t *o, re__best_t *b, const double P[3], double nrm[3])
{
    double c[3], len;
    if (b->kind == RE_FEATURE_SPHERE) {
        re__sub(P, re__cptr(o, b, b->index), nrm);
    } else {
        unsigned sp[2];
        double keep[3], u[3], L2, t;
        const double *a, *z;
        int near_a = b->h <= 0.5;
        re__cyl_spheres(o, b->index, sp);
        re__cpair(o, b, sp[0], sp[1], &a, &z, keep);
        re__sub(z, a, u);
        /* P's offset from the axis, from the nearer end (b->h picks it): the
           axis point a + h u is off along the axis by ulps of h times the
           axis length, which turns the normal by that over r (an edge 1e6
           long, r 6e-8: 2e-3 rad; fuzz_rounded_build) */
        L2 = re__dot(u, u);
        re__sub(P, near_a ? a : z, c);
        t = L2 > 0 ? re__dot(c, u) / L2 : 0; /* the axis point's offset from that end, clamped to the span */
        t = near_a ? re__max(0.0, re__min(1.0, t)) : re__max(-1.0, re__min(0.0, t));
        re__madd(c, -t, u, nrm);
    }
    len = re__len(nrm);
    if (len > 0) nrm[0] /= len, nrm[1] /= len, nrm[2] /= len;
}

/* The answer "the host's hit stands", before any point or normal. */
static void re__unchanged(re_hit_t *out, unsigned object, unsigned triangle, double t_host)
{
    memset(out, 0, sizeof *out);
    out->kind = RE_UNCHANGED;
    out->t = t_host;
    out->object = object;
    out->feature = RE_FEATURE_FACE;
    out->feature_index = triangle;
}

/* Query step 0: every barycentric coordinate beyond its band (re__bands):
   the hit is on the flat part of its face. Never, without bands. */
static int re__band_flat(const re__object_t *o, unsigned triangle, double u, double v)
{
#ifdef RE_NO_BANDS
    (void)o, (void)triangle, (void)u, (void)v;
    return 0;
#else
    const unsigned char *b = o->bands + 4 * (size_t)triangle;
    double l0 = (1 - u - v) * RE__BAND_STEPS, l1 = u * RE__BAND_STEPS, l2 = v * RE__BAND_STEPS,
           cap = RE__BAND_STEPS - (double)b[3];
    return l0 > (double)b[0] && l1 > (double)b[1] && l2 > (double)b[2] && l0 < cap && l1 < cap && l2 < cap;
#endif
}

/* Is X within edge cylinder c's detection zone (paper §3.1's detection
   cylinder, widened to cover the exact corners)? *si0, *si1 get the
   cylinder's end spheres. */
static RE__HOT_INLINE int re__in_zone(const re__object_t *o, unsigned c, const double X[3], re__best_t *best,
                                      unsigned *si0, unsigned *si1)
{
    const re__ecyl_t *cy = &o->cyls[c];
    const re__plane_t *P0 = &o->planes[cy->p[0]], *P1 = &o->planes[cy->p[1]];
    double g = RE__COMPACT(o) ? re__det8(o->det8[2 * c], o->det_e0) : re__det(o->det[2 * c]), m, keep[3], u[3], w[3], L2, t, a0, a1, cs;
    const double *s0, *s1;
    unsigned sa, sb;
    /* across first: distance to the mesh edge's line, from the two face
       planes' signed distances a0, a1: (a0^2 + a1^2 - 2 a0 a1 cos) / sin^2.
       It rejects most of a leaf's edges, and the face planes are shared by
       many edges (warm in cache) where the end spheres are not: the render
       profile showed the loop waiting on the sphere loads. */
    a0 = re__dot(P0->n, X) - P0->c;
    /* the line lies in both planes, so it is at least |a0| and |a1| away:
       (a0^2 + a1^2 - 2 a0 a1 cos) - a0^2 sin^2 = (a1 - a0 cos)^2 >= 0. Most
       candidates fail on one plane, before the other plane and cos are read */
    if (a0 * a0 > g * g) return 0;
    a1 = re__dot(P1->n, X) - P1->c;
    if (a1 * a1 > g * g) return 0;
    cs = re__dot(P0->n, P1->n);
    if (a0 * a0 + a1 * a1 - 2 * a0 * a1 * cs > g * g * (1 - cs * cs)) return 0;
    /* along the axis: within m of the end spheres */
    m = RE__COMPACT(o) ? re__det8(o->det8[2 * c + 1], o->det_e0) : re__det(o->det[2 * c + 1]);
    sa = re__pk_id(&o->c_s0, c);
    sb = re__cyl_s1(o, c, sa);
    *si0 = sa, *si1 = sb;
    re__cpair(o, best, sa, sb, &s0, &s1, keep);
    re__sub(s1, s0, u);
    re__sub(X, s0, w);
    L2 = re__dot(u, u);
    t = re__dot(w, u);
    return !((t < 0 && t * t > m * m * L2) || (t > L2 && (t - L2) * (t - L2) > m * m * L2));
}

/* re__in_zone for the rare checks of answers (re__one_edge,
   re__exit_on_edge_of), a call of its own kept out of the query's body. */
RE__NOINLINE static int re__zone_holds(const re__object_t *o, unsigned c, const double X[3], re__best_t *best)
{
    unsigned s0, s1;
    return re__in_zone(o, c, X, best, &s0, &s1);
}

/* Query step 1 for edge cylinder c of I's kd leaf: is I within its
   detection zone? Adds the corners that have plane f to S, and sets *c0
   when f is one of the edge's own faces; returns 1 if detected. */
static inline unsigned re__detect(const re__object_t *o, unsigned c, const double I[3], unsigned f, re__set_t *S,
                                  re__best_t *best, unsigned *c0)
{
    const re__ecyl_t *cy = &o->cyls[c];
    unsigned ka, kb, si0, si1;
    re__kv_t Ka, Kb;
    if (!re__in_zone(o, c, I, best, &si0, &si1)) return 0;
    ka = re__s_corner(o, si0), kb = re__s_corner(o, si1);
    if (cy->p[0] == f || cy->p[1] == f) { /* both corners have plane f */
        re__set_add(S, ka);
        re__set_add(S, kb);
        *c0 = c;
        return 1;
    }
    Ka = re__kview(o, ka), Kb = re__kview(o, kb);
    if (re__corner_has_plane(o, &Ka, f)) re__set_add(S, ka);
    if (re__corner_has_plane(o, &Kb, f)) re__set_add(S, kb);
    return 1;
}

/* The walk (paper section 3.1, grazing rays): add to S the corners next to
   its own in the adjacency graph whose reach comes within the segment
   I -> I + s dir, or the whole half-line when s is HUGE_VAL (nothing found
   yet: the ray runs along the edges, out of reach of the set's faces).
   1 when the set grew. Each call expands the corners from *from on, those
   added since the last: from round to round the segment only shortens
   (the nearest hit and the exit only come earlier as S grows), so a
   neighbour an earlier round left out stays out, and the old corners
   would add nothing. */
static int re__walk_grow(const re__object_t *o, re__set_t *S, re__best_t *b, const double I[3], const double dir[3],
                         double s, unsigned *from)
{
    double P[3], IP[3], inv_l2;
    unsigned i, j;
    int grown = 0;
    re__madd(I, s < HUGE_VAL ? s : 0.0, dir, P);
    re__sub(P, I, IP);
    inv_l2 = re__dot(IP, IP) > 0 ? 1 / re__dot(IP, IP) : 0;
    for (i = *from; i < S->n; i++) {
        re__kv_t K = re__kview(o, S->c[i]);
        for (j = 0; j < K.np; j++) {
            unsigned w = re__s_corner(o, re__far_sphere(o, o->refs[K.first + j]));
            double g, d2;
            const double *wc;
            /* a corner already in the set is skipped before its record and
               sphere are loaded (cache misses were most of the walk's cost
               in the render profile; the set is small) */
            if (re__set_find(S, w) < S->n) continue;
            /* removed points lie within r of the removed zone on the faces
               (below a flat point the ball of radius r is solid), and that
               zone lies within the face reach of its corner: `walk` bounds
               both, from the corner's first sphere */
            wc = re__cptr(o, b, re__pk_id(&o->k_sfirst, w));
            g = (double)o->corners[w].walk;
            d2 = s < HUGE_VAL ? re__dist2_segment(wc, I, IP, inv_l2) : re__dist2_halfline(wc, I, dir);
            if (d2 <= g * g && re__set_add(S, w)) grown = 1;
        }
    }
    *from = S->n;
    return grown;
}

/* What re_query and re_query_uv do before detection: out becomes the
   answer "unchanged" with I and, on a face of a rounded patch, its plane's
   normal. Returns the object when detection must decide (*f its face
   plane), NULL when the answer is final. It is inlined into both entry
   points, so the common flat hit of re_query_uv (query step 0) returns
   without the call into re__query_kd. A finite I = o + t_host dir implies a
   finite dir (inf * 0 and inf * t are not finite), so dir is not tested. */
static inline const re__object_t *re__query_start(const re_scene_t *scene, const double o3[3], const double dir[3],
                                                  unsigned object, unsigned triangle, double t_host, re_hit_t *out,
                                                  double I[3], unsigned *f)
{
    const re__object_t *o;
    re__unchanged(out, object, triangle, t_host);
    if (!scene || !o3 || !dir || object >= scene->n_objects) return NULL;
    re__madd(o3, t_host, dir, I);
    out->point[0] = I[0], out->point[1] = I[1], out->point[2] = I[2];
    o = &scene->objects[object];
    if (triangle >= o->n_tris || !re__finite3(I) || !o->n_nodes) return NULL;
    *f = re__pk_get(&o->tri_plane, triangle);
    if (*f == RE__NONE) return NULL;
    out->normal[0] = o->planes[*f].n[0], out->normal[1] = o->planes[*f].n[1], out->normal[2] = o->planes[*f].n[2];
    return o;
}

/* Query step 1: the kd-tree leaf holding I, then each edge cylinder of it
   whose detection zone holds I (re__detect; paper §3.1's detection
   cylinders, widened to cover the exact corners). Returns how many. */
static unsigned re__detect_leaf(const re__object_t *o, unsigned f, const double I[3], re__set_t *S, re__best_t *best,
                                unsigned *c0)
{
    const unsigned short *leaf;
    unsigned node, base, i, ndet = 0;
    double Ir[3];
    re__sub(I, o->origin, Ir); /* the splits' frame (see re__kd_build) */
    for (node = 0; (o->nodes[node].info & 3u) != 3u;) {
        const re__node_t *nd = &o->nodes[node];
        float sp;
        memcpy(&sp, &nd->data, sizeof sp);
        node = Ir[nd->info & 3u] <= (double)sp ? node + 1 : nd->info >> 2;
    }
    leaf = o->leaf16 + (o->nodes[node].info >> 2);
    base = o->nodes[node].data;
    for (;;) {
        unsigned cnt = leaf[0] & 0x7FFFu, more = leaf[0] >> 15;
        for (i = 0; i < cnt; i++) ndet += re__detect(o, base + leaf[1 + i], I, f, S, best, c0);
        leaf += 1 + cnt;
        if (!more) break;
        base = leaf[0] | (unsigned)leaf[1] << 16;
        leaf += 2;
    }
    return ndet;
}

/* One edge found (cylinder c0, its two corners in S), away from its
   corners (the common case): inside the removed volume around the middle
   of an edge the only surfaces are its rounding cylinder and its two
   faces. If the ray meets one of them before coming within walk reach of
   either corner, that is the answer (1: best, *s_exit, *exit_plane hold
   it); else (0) the general search decides. */
static int re__one_edge(const re__object_t *o, const re__set_t *S, unsigned c0, const double I[3], const double dir[3],
                        re__best_t *best, double *s_exit, unsigned *exit_plane)
{
    const re__ecyl_t *cy = &o->cyls[c0];
    double P[3], IP[3], inv_l2, nd0, nd1, e0 = HUGE_VAL, e1 = HUGE_VAL, sc;
    const re__plane_t *P0 = &o->planes[cy->p[0]], *P1 = &o->planes[cy->p[1]];
    unsigned i;
    best->s = HUGE_VAL;
    best->kind = RE_FEATURE_FACE;
    best->index = 0;
    best->h = 0;
    re__try_cyl(o, c0, re__k_radius(o, S->c[0]), I, dir, best);
    nd0 = re__dot(P0->n, dir), nd1 = re__dot(P1->n, dir);
    if (nd0 > 0) e0 = re__max(0.0, P0->c - re__dot(P0->n, I)) / nd0;
    if (nd1 > 0) e1 = re__max(0.0, P1->c - re__dot(P1->n, I)) / nd1;
    *s_exit = re__min(e0, e1);
    *exit_plane = e0 <= e1 ? cy->p[0] : cy->p[1];
    sc = re__min(best->s, *s_exit);
    if (!(sc < HUGE_VAL)) return 0;
    re__madd(I, sc, dir, P);
    re__sub(P, I, IP);
    inv_l2 = re__dot(IP, IP) > 0 ? 1 / re__dot(IP, IP) : 0;
    for (i = 0; i < 2; i++) {
        double wk = (double)o->corners[S->c[i]].walk;
        if (re__dist2_segment(re__cptr(o, best, re__pk_id(&o->k_sfirst, S->c[i])), I, IP, inv_l2) <= wk * wk) return 0;
    }
    /* a pass-through leaves within the edge's zone, unless the ray runs
       along a face out of it (re__exit_on_edge_of): the general search decides */
    return best->s <= *s_exit || re__zone_holds(o, c0, P, best);
}

/* For a ray running in face g's plane from I to a pass-through's exit X
   on plane h: is X where such a ray can leave the mesh, on an edge of g
   that borders h (any edge of g when h is g: a ray entering near an edge
   of g and leaving by g beside it)? Checked against the edges of S's
   corners: X within `walk` of the corner or within the edge's detection
   zone (the removed volume near a corner lies within its walk, near an
   edge's middle within the edge's zone, and the walk, re__walk_grow, adds
   each corner the ray comes near). The exit is out of reach when the ray
   ran along g on its flat part, touching the rounded solid without
   entering it: a tangent contact with a capsule that its rounding lost (a
   ray through a vertex lying in a face: fuzz_rounded_exact, 2026-12-06).
   Past that contact g is the surface, and S's planes say nothing of where
   the mesh ends. Neither test alone bounds it: at a narrow corner the walk
   spans the faces' reach, up to the object's size (walk 2.83 at a degree-5
   vertex of a hull of size 1.9: an exit 0.93 outside the mesh), and an
   exit 0.71 outside lay in the zone of an edge of another face; a ray in
   g's plane "leaving" by g far on was 0.97 outside, within a walk. */
static int re__exit_on_edge_of(const re__object_t *o, const re__set_t *S, re__best_t *b, const double X[3], unsigned g,
                               unsigned h)
{
    unsigned i, j;
    for (i = 0; i < S->n; i++) {
        unsigned k = S->c[i];
        re__kv_t K = re__kview(o, k);
        int near = -1;
        for (j = 0; j < K.np; j++) {
            unsigned c = o->refs[K.first + j] >> 1, p0 = o->cyls[c].p[0], p1 = o->cyls[c].p[1];
            if (!(g != h ? (p0 == g && p1 == h) || (p0 == h && p1 == g) : p0 == g || p1 == g)) continue;
            if (near < 0) {
                double wk = (double)o->corners[k].walk, d[3];
                re__sub(X, re__cptr(o, b, re__pk_id(&o->k_sfirst, k)), d);
                near = re__dot(d, d) <= wk * wk;
            }
            if (near || re__zone_holds(o, c, X, b)) return 1;
        }
    }
    return 0;
}

/* How far below a face a ray whose capsule contact rounding lost can sink
   over a run L, coordinates of magnitude mag (|I|_1 + |X|_1): at a slope
   of at most the features' noise over r, RE__ALONG_FACE_ULPS mag (1 + L / r). */
static double re__lost_depth(double mag, double L, double r) { return RE__ALONG_FACE_ULPS * mag * (1 + L / r); }

/* How far from a face plane such a ray can run from I to X: that depth
   plus RE__ALONG_FACE_R r. */
static double re__along_tol(const double I[3], const double X[3], double r)
{
    double D[3], mag = fabs(I[0]) + fabs(I[1]) + fabs(I[2]) + fabs(X[0]) + fabs(X[1]) + fabs(X[2]);
    re__sub(X, I, D);
    return RE__ALONG_FACE_R * r + re__lost_depth(mag, re__len(D), r);
}

/* The plane of S the segment I -> X lies in most nearly (the face a ray
   out of reach ran along, re__exit_on_edge_of), in *dmin the segment's largest
   distance from it, in *rmin the smallest radius of S's corners. */
static unsigned re__plane_along(const re__object_t *o, const re__set_t *S, const double I[3], const double X[3], double *dmin,
                                double *rmin)
{
    unsigned i, j, best = RE__NONE;
    *dmin = *rmin = HUGE_VAL;
    for (i = 0; i < S->n; i++) {
        re__kv_t K = re__kview(o, S->c[i]);
        *rmin = re__min(*rmin, re__k_radius(o, K.k));
        for (j = 0; j < K.np; j++) {
            unsigned gi = re__corner_plane(o, &K, j);
            const re__plane_t *g = &o->planes[gi];
            double dv = re__max(fabs(re__side_of(g, I)), fabs(re__side_of(g, X)));
            if (dv < *dmin) *dmin = dv, best = gi;
        }
    }
    return best;
}

/* Does the ray run in plane g (index gi) from I and "leave" by g itself at
   X, more than a radius on? Such an exit is noise: a ray lying in a plane
   crosses it anywhere (a ray in a face's plane through a vertex "left" by
   it 0.97 outside the mesh, within an edge's zone). A ray that starts
   below g and leaves by it a little on, across a strip near an edge of g,
   is a true exit. */
static int re__runs_in(const re__object_t *o, unsigned gi, unsigned h, const double I[3], const double X[3], double r)
{
    const re__plane_t *g = &o->planes[gi];
    double D[3];
    re__sub(X, I, D);
    return gi == h && re__dot(D, D) > r * r &&
           fabs(re__side_of(g, I)) <= re__lost_depth(fabs(I[0]) + fabs(I[1]) + fabs(I[2]), 0, r);
}

/* Where does the ray I + s d, along face g (index gi), first lie inside the
   rounded solid before s_end, as judged from g's flat part: below g by
   more than the rounding of that depth (RE__FLAT_ULPS of the magnitudes,
   mag = |I|_1 + |X|_1, as the flat test) and less than the smallest
   radius of S, with its foot on g, moved down by each corner's radius,
   strictly inside every other shifted plane of S (re__on_flat_part's
   test with re__hit_in_slab's strict slack). There the ball of radius r under g's flat part holds the
   ray. Each condition is linear in s, so they meet in an interval; its
   start, or HUGE_VAL when it is empty or the ray does not sink. */
static double re__sinks_in_flat(const re__object_t *o, const re__set_t *S, unsigned gi, const double I[3], const double d[3],
                                double s_end, double mag)
{
    const re__plane_t *g = &o->planes[gi];
    double gd = re__dot(g->n, d), d0 = g->c - re__dot(g->n, I), tau = RE__FLAT_ULPS * (fabs(g->c) + mag);
    double lo, hi = s_end, rmin = HUGE_VAL;
    unsigned i, j;
    if (!(gd < 0)) return HUGE_VAL; /* depth d0 - s gd grows only when the ray heads below g */
    lo = re__max(0.0, (tau - d0) / -gd);
    for (i = 0; i < S->n; i++) {
        re__kv_t K = re__kview(o, S->c[i]);
        double rq = re__k_radius(o, K.k);
        rmin = re__min(rmin, rq);
        for (j = 0; j < K.np; j++) {
            unsigned hk = re__corner_plane(o, &K, j);
            const re__plane_t *h = &o->planes[hk];
            double gh = re__dot(h->n, g->n), a, b;
            if (hk == gi) continue;
            /* n_h . (I + s d + (d0 - s gd - rq) n_g) - (c_h - rq) + slack < 0 */
            a = re__dot(h->n, I) + (d0 - rq) * gh - (h->c - rq) + RE__FLAT_ULPS * (fabs(h->c) + mag + rq);
            b = re__dot(h->n, d) - gd * gh;
            if (b > 0) hi = re__min(hi, -a / b);
            else if (b < 0) lo = re__max(lo, -a / b);
            else if (!(a < 0)) return HUGE_VAL;
        }
    }
    hi = re__min(hi, (rmin - d0) / -gd);
    return lo < hi ? lo : HUGE_VAL;
}

/* Closest approach of the ray segment I + s d, s in [s0, s1], to the
   segment a + h u, h in [0, 1] (the clamped normal equations, solved for
   s, then h, then s again: Ericson, Real-Time Collision Detection §5.1.9).
   Returns the squared distance; *s, *h the parameters. */
static double re__ray_seg_approach(const double I[3], const double d[3], double s0, double s1, const double a[3],
                                   const double u[3], double *s, double *h)
{
    double w[3], A = re__dot(d, d), B = re__dot(d, u), C = re__dot(u, u), D, E, det, P[3], Q[3];
    re__sub(I, a, w);
    D = re__dot(d, w), E = re__dot(u, w), det = A * C - B * B;
    *s = det > RE__PARALLEL_SIN2 * A * C ? (B * E - C * D) / det : s0; /* parallel: the earliest point */
    *s = re__max(s0, re__min(s1, *s));
    *h = C > 0 ? re__max(0.0, re__min(1.0, (*s * B + E) / C)) : 0;
    *s = re__max(s0, re__min(s1, (*h * B - D) / A));
    *h = C > 0 ? re__max(0.0, re__min(1.0, (*s * B + E) / C)) : 0;
    re__madd(I, *s, d, P);
    re__madd(a, *h, u, Q);
    re__sub(P, Q, w);
    return re__dot(w, w);
}

/* Is the ray's closest approach I + s d to a capsule, A the nearest point
   of its axis, a contact on g's seam: within tau of g's plane, and the
   capsule's normal there within acos(RE__SLAB_COS) of g's? A ray
   inside the solid also passes near capsules, from below (the far side of
   a shallow crease's cylinder, 2 r under the faces). */
static int re__on_seam_of(const re__plane_t *g, const double I[3], const double d[3], double s, const double A[3],
                          double tau)
{
    double P[3], nrm[3], len;
    re__madd(I, s, d, P);
    re__sub(P, A, nrm);
    len = re__len(nrm);
    return fabs(re__side_of(g, P)) <= tau && re__dot(g->n, nrm) >= RE__SLAB_COS * len;
}

/* The capsule of an edge or corner of face g (index gi) that the ray
   I + s d, s in [s0, s1], comes closest to on g's seam (re__on_seam_of),
   measured by the distance's excess over the capsule's radius: its closest
   approach goes into b as the hit (s, kind, index, h). Returns that excess
   (HUGE_VAL: none). The contact a tangent ray's rounding lost is there. */
static double re__nearest_contact(const re__object_t *o, const re__set_t *S, re__best_t *b, unsigned gi, const double I[3],
                                  const double d[3], double s0, double s1, double tau)
{
    const re__plane_t *g = &o->planes[gi];
    double best = HUGE_VAL, zero[3] = {0, 0, 0};
    unsigned i, j;
    for (i = 0; i < S->n; i++) {
        re__kv_t K = re__kview(o, S->c[i]);
        double r = re__k_radius(o, K.k), s, h, e, A[3];
        if (!re__corner_has_plane(o, &K, gi)) continue;
        for (j = 0; j < K.ns; j++) {
            const double *C = re__cptr(o, b, K.sfirst + j);
            e = sqrt(re__ray_seg_approach(I, d, s0, s1, C, zero, &s, &h)) - r;
            if (e < best && re__on_seam_of(g, I, d, s, C, tau))
                best = e, b->s = s, b->kind = RE_FEATURE_SPHERE, b->index = K.sfirst + j, b->h = 0;
        }
        for (j = 0; j < K.np + K.nx; j++) {
            unsigned c = j < K.np ? o->refs[K.first + j] >> 1 : re__k_xfirst(o, K.k) + (j - K.np), sp[2];
            re__cyl_t cy = re__cyl(o, c);
            double keep[3], u[3];
            const double *a, *z;
            if (cy.p[0] != gi && cy.p[1] != gi) continue;
            re__cyl_spheres(o, c, sp);
            re__cpair(o, b, sp[0], sp[1], &a, &z, keep);
            re__sub(z, a, u);
            e = sqrt(re__ray_seg_approach(I, d, s0, s1, a, u, &s, &h)) - r;
            re__madd(a, h, u, A);
            if (e < best && re__on_seam_of(g, I, d, s, A, tau))
                best = e, b->s = s, b->kind = RE_FEATURE_CYLINDER, b->index = c, b->h = h;
        }
    }
    return best;
}

/* A ray along face g (index gi: the ray within re__along_tol of its plane
   from I to I + s_end d) that the search let pass, or let hit a capsule
   at s_end, but that sinks into the rounded solid under g's flat part
   before (re__sinks_in_flat) entered it on the way, at a tangent contact
   its rounding lost by less than the features' noise: the closest
   approach to a capsule of g's edges and corners on g's seam, within
   that noise (RE__SIDE_ULPS of the magnitudes), is the hit (1; b holds
   it). The capsule's normal there is turned past the seam by the ray's
   slope, so a reflection about it sinks into g: re_secondary_origin
   starts such a ray at the contact (re__leaves_on_face). Found by
   fuzz_rounded_exact at offset 1e6, r 2^-22 of the size: a cylinder
   passed 1.8e-11 outside at its seam with g, then the ray 4.5 r deep
   under g (a pass-through), or 2 r deep on to another capsule, entered
   from inside (ray_sinking_past_a_lost_tangent_contact). 0: the answer
   stands. */
static int re__lost_entry(const re__object_t *o, const re__set_t *S, re__best_t *b, unsigned gi, const double I[3],
                          const double d[3], double s_end)
{
    re__best_t c = *b;
    double X[3], mag, s_in, tau;
    re__madd(I, s_end, d, X);
    mag = fabs(I[0]) + fabs(I[1]) + fabs(I[2]) + fabs(X[0]) + fabs(X[1]) + fabs(X[2]);
    tau = RE__SIDE_ULPS * (fabs(o->planes[gi].c) + mag);
    s_in = re__sinks_in_flat(o, S, gi, I, d, s_end, mag);
    if (!(s_in < HUGE_VAL) || !(re__nearest_contact(o, S, &c, gi, I, d, b->smin, s_in, tau) <= tau)) return 0;
    *b = c;
    return 1;
}

/* re__lost_entry for a rounded hit at b.s past I, on the face the ray runs
   along from I to it, if any. */
RE__NOINLINE static int re__hit_after_lost_entry(const re__object_t *o, const re__set_t *S, re__best_t *b, const double I[3],
                                                 const double d[3])
{
    double X[3], dmin, rmin;
    unsigned along;
    re__madd(I, b->s, d, X);
    along = re__plane_along(o, S, I, X, &dmin, &rmin);
    return along != RE__NONE && dmin <= re__along_tol(I, X, rmin) && re__lost_entry(o, S, b, along, I, d, b->s);
}

/* A pass-through whose exit is out of the set's reach (re__exit_on_edge_of),
   or no answer at all (neither a capsule nor a plane of S ahead: the ray
   left the set's reach, so I is not on a flat part either), leaves at I
   instead, through the host's face f there: the ray runs along a face and
   only touches the rounded solid, and the host, tracing on from I, finds
   where it really leaves the mesh (if anywhere: it runs in a face's
   plane). Only a ray near a plane of S all the way can be out of reach
   (RE__ALONG_FACE_R: one deeper meets a capsule), so other pass-throughs
   skip the edge tests. */
static void re__exit_within_reach(const re__object_t *o, const re__set_t *S, re__best_t *b, const double I[3],
                                  const double dir[3], unsigned f, double *s_exit, unsigned *exit_plane)
{
    double X[3], dmin, rmin;
    unsigned along;
    int runs_along;
    if (!(*s_exit < b->s) && b->s < HUGE_VAL) return; /* a rounded hit */
    if (*s_exit < HUGE_VAL) re__madd(I, *s_exit, dir, X);
    else re__madd(I, o->size / re__len(dir), dir, X); /* a size along, to find the face it runs in */
    along = re__plane_along(o, S, I, X, &dmin, &rmin);
    if (along == RE__NONE) return;
    runs_along = dmin <= re__along_tol(I, X, rmin);
    if (runs_along && re__lost_entry(o, S, b, along, I, dir, re__min(*s_exit, o->size / re__len(dir)))) return;
    if (*s_exit < HUGE_VAL && (!runs_along || (!re__runs_in(o, along, *exit_plane, I, X, rmin) &&
                                               re__exit_on_edge_of(o, S, b, X, along, *exit_plane))))
        return;
    *s_exit = 0;
    *exit_plane = f;
}

/* re__hit_in_slab's test below for any hit of an object of one radius
   (I and X in its box, |X - I| at most its diagonal): for every radius of
   the renders it says no, without a lookup or a call. */
static inline int re__slab_check_needed(const re__object_t *o)
{
    double r = o->radii[0], mag = 2 * (fabs(o->origin[0]) + fabs(o->origin[1]) + fabs(o->origin[2]) + 3 * o->size);
    return o->n_radii != 1 || 2 * re__lost_depth(mag, o->size, r) > RE__SLAB_ANGLE * RE__SLAB_ANGLE * r;
}

/* Is the rounded hit X = I + best.s dir (on feature best) inside the slab
   under one of its feature's faces g: X below g, with g's normal within
   acos(RE__SLAB_COS) of nx, the ray within re__along_tol of g from I to X,
   and X over g's flat part (moved onto g and down by r, strictly inside
   every other shifted plane of S's corners by re__on_flat_part's slack:
   a hit just past a tangent line, or beside a sharp corner far out, stays
   a hit)? Such a capsule "entry" lies inside the rounded solid: the ray
   ran along g inside it, having met the surface at a tangent contact that
   rounding lost (fuzz_rounded_exact's rays along a face: a cylinder
   entered from the slab 1.66 sizes on, its normal 0.079 rad off). A
   capsule entered from g's slab belongs to an edge or corner of g, so only
   the feature's own faces are tried. Returns g, or RE__NONE. */
RE__NOINLINE static unsigned re__hit_in_slab(const re__object_t *o, const re__set_t *S, re__best_t *best, const double I[3],
                                             const double dir[3])
{
    double X[3], nx[3], mag, r, tol;
    unsigned nc, i, q, k, gi, kc;
    re__kv_t K;
    re__cyl_t cy;
    int is_cyl = best->kind == RE_FEATURE_CYLINDER;
    kc = is_cyl ? (best->index < o->n_edge_cyls ? re__s_corner(o, re__pk_id(&o->c_s0, best->index))
                                                : re__pk_id(&o->x_corner, best->index - o->n_edge_cyls))
                : re__s_corner(o, best->index);
    r = re__k_radius(o, kc);
    re__madd(I, best->s, dir, X);
    /* the capsule's normal turns by sqrt(2 depth / r) at the lost depth (by
       X): below RE__SLAB_ANGLE (every radius of the renders) nothing to mend */
    if (2 * re__lost_depth(fabs(I[0]) + fabs(I[1]) + fabs(I[2]) + fabs(X[0]) + fabs(X[1]) + fabs(X[2]), best->s * re__len(dir), r) <=
        RE__SLAB_ANGLE * RE__SLAB_ANGLE * r)
        return RE__NONE;
    re__feature_normal(o, best, X, nx);
    mag = fabs(X[0]) + fabs(X[1]) + fabs(X[2]); /* the flat test's slack */
    K = re__kview(o, kc);
    if (is_cyl) cy = re__cyl(o, best->index), nc = 2;
    else nc = K.np;
    tol = re__along_tol(I, X, r);
    for (i = 0; i < nc; i++) {
        const re__plane_t *g = &o->planes[gi = is_cyl ? cy.p[i] : re__corner_plane(o, &K, i)];
        double h = -re__side_of(g, X), Y[3];
        int flat = 1;
        if (re__dot(g->n, nx) < RE__SLAB_COS || !(h > RE__FLAT_ULPS * (fabs(g->c) + mag + r)) || !(h <= tol) ||
            !(fabs(re__side_of(g, I)) <= tol))
            continue;
        re__madd(X, h - r, g->n, Y); /* onto g, then down r: a point of the eroded face if X is over its flat part */
        for (q = 0; q < S->n && flat; q++) {
            re__kv_t Q = re__kview(o, S->c[q]);
            double rq = re__k_radius(o, Q.k);
            for (k = 0; k < Q.np && flat; k++) {
                unsigned hi = re__corner_plane(o, &Q, k);
                const re__plane_t *hp = &o->planes[hi];
                if (hi != gi && !(re__dot(hp->n, Y) - (hp->c - rq) < -RE__FLAT_ULPS * (fabs(hp->c) + mag + rq))) flat = 0;
            }
        }
        if (flat) return gi;
    }
    return RE__NONE;
}

/* Query step 5: the rounded hit at best.s, the pass-through at s_exit
   (the host goes on from the sharp mesh's face there), or unchanged. */
static re_hit_kind_t re__answer(const re__object_t *o, re__best_t *best, double s_exit, unsigned exit_plane, const double I[3],
                                const double dir[3], double t_host, re_hit_t *out)
{
    if (best->s <= s_exit && best->s < HUGE_VAL) {
        out->kind = RE_HIT_ROUNDED;
        out->t = t_host + best->s;
        re__madd(I, best->s, dir, out->point);
        re__feature_normal(o, best, out->point, out->normal);
        out->feature = best->kind;
        out->feature_index = best->index;
    } else if (s_exit < HUGE_VAL) {
        const re__plane_t *g = &o->planes[exit_plane];
        out->kind = RE_PASS_THROUGH;
        out->t = t_host + s_exit;
        re__madd(I, s_exit, dir, out->point);
        out->normal[0] = g->n[0], out->normal[1] = g->n[1], out->normal[2] = g->n[2];
    }
    return out->kind;
}

/* A host's t a little early (float tracers: ~1e-7 relative) leaves I just
   outside face f's plane, beside the true crossing. Past I the search
   assumes the ray is inside the sharp mesh, which holds only from the
   plane on: next to a rounding's tangent line the flat-part test failed
   and the ray's entry through the face was never considered (a pass-through
   into the solid, or a rounded hit inside it with its normal 0.4 rad off;
   found by review, 2026-12-06). So an I outside the plane by more than the
   plane test's rounding is moved along the ray onto it, when that is at
   most RE__HOST_T_SLACK t_host; returns the distance moved (in t). A late
   t (I inside) is left to the capsule search's slack (best.smin). The
   rounding counts I's own, o + t_host dir's: ulps of |o| + |t_host dir|,
   up to |I| + 2 |t_host dir|. A ray along f (an exact host, 1e-10 to the
   face) whose I was off by that rounding alone was moved 3.6e-6 along it,
   over the edge it leaves by and out of the mesh (fuzz_rounded_exact:
   a pass-through 9.4e-7 outside, through the wrong face). */
static double re__onto_face(const re__object_t *o, unsigned f, const double I[3], const double dir[3], double t_host,
                            double Ip[3])
{
    const re__plane_t *pf = &o->planes[f];
    double h = re__side_of(pf, I), nd = re__dot(pf->n, dir), sf;
    double mag = fabs(I[0]) + fabs(I[1]) + fabs(I[2]) + 2 * fabs(t_host) * (fabs(dir[0]) + fabs(dir[1]) + fabs(dir[2]));
    Ip[0] = I[0], Ip[1] = I[1], Ip[2] = I[2];
    if (!(h > RE__FLAT_ULPS * (fabs(pf->c) + mag)) || !(nd < 0)) return 0;
    sf = -h / nd;
    if (!(sf <= RE__HOST_T_SLACK * fabs(t_host))) return 0;
    re__madd(I, sf, dir, Ip);
    return sf;
}

/* The answer's RE_HIT_INCOMPLETE when the query dropped a corner (RE_SET_CAP). */
static re_hit_kind_t re__flag_dropped(const re__set_t *S, re_hit_t *out, re_hit_kind_t kind)
{
    if (S->full) out->flags |= RE_HIT_INCOMPLETE;
    return kind;
}

/* Query steps 1-5 for a hit I0 on face plane f of object o (out holds the
   answer "unchanged" from re__query_start). */
static re_hit_kind_t re__query_kd(const re__object_t *o, unsigned f, const double I0[3], const double dir[3], double t_host,
                                  re_hit_t *out)
{
    re__set_t S;
    re__exit_t E;
    unsigned iter, exit_plane, ndet, c0 = RE__NONE, walked = 0;
    re__best_t best;
    double s_exit, I[3], t_on = t_host + re__onto_face(o, f, I0, dir, t_host, I);
    re__set_init(&S);
    best.cvalid = 0;
    ndet = re__detect_leaf(o, f, I, &S, &best, &c0);
    if (!S.n || re__on_flat_part(o, &S, f, I)) return re__flag_dropped(&S, out, RE_UNCHANGED);
    best.smin = -RE__HOST_T_SLACK * fabs(t_host);
    if (ndet == 1 && c0 != RE__NONE && S.n == 2 && re__one_edge(o, &S, c0, I, dir, &best, &s_exit, &exit_plane))
        return re__flag_dropped(&S, out, re__answer(o, &best, s_exit, exit_plane, I, dir, t_on, out));
    /* inside the removed volume: nearest capsule or the exit, walking the
       adjacency graph (cylinder -> corner) while the ray runs toward corners
       not yet in the set (grazing rays, §3.1) */
    re__exit_init(&E);
    for (iter = 0;; iter++) {
        re__nearest_feature(o, &S, I, dir, &best);
        s_exit = re__exit(o, &S, I, dir, &E, &exit_plane);
        if (iter == RE__MAX_WALK || !re__walk_grow(o, &S, &best, I, dir, re__min(best.s, s_exit), &walked)) break;
    }
    re__exit_within_reach(o, &S, &best, I, dir, f, &s_exit, &exit_plane);
    /* a rounded hit past I: not from inside a slab (re__hit_in_slab). Before I
       (a late host's t, best.smin) the ray met the capsule next to where it
       crossed the host's face, and that hit stands */
    if (best.s <= s_exit && best.s > 0 && best.s < HUGE_VAL && re__slab_check_needed(o) &&
        !re__hit_after_lost_entry(o, &S, &best, I, dir)) {
        unsigned g = re__hit_in_slab(o, &S, &best, I, dir);
        if (g != RE__NONE) best.s = HUGE_VAL, s_exit = 0, exit_plane = g;
    }
    return re__flag_dropped(&S, out, re__answer(o, &best, s_exit, exit_plane, I, dir, t_on, out));
}

/* re_query and re_query_uv (with_uv: the host's barycentrics first). */
static re_hit_kind_t re__query(const re_scene_t *scene, const double o3[3], const double dir[3], unsigned object,
                               unsigned triangle, double t_host, int with_uv, double u, double v, re_hit_t *out)
{
    const re__object_t *o;
    double I[3];
    unsigned f = 0;
    o = re__query_start(scene, o3, dir, object, triangle, t_host, out, I, &f);
    if (!o || (with_uv && re__band_flat(o, triangle, u, v))) return RE_UNCHANGED;
    return re__query_kd(o, f, I, dir, t_host, out);
}

/* re_query_exit and re_query_exit_uv: the query of the ray reversed at the
   exit face (it enters there), its answer turned back into the forward
   ray's t. */
static re_hit_kind_t re__query_exit(const re_scene_t *scene, const double o3[3], const double dir[3], unsigned object,
                                    unsigned triangle, double t_host, int with_uv, double u, double v, re_hit_t *out)
{
    const re__object_t *o;
    double I[3], back[3];
    unsigned f = 0;
    re_hit_t face;
    o = re__query_start(scene, o3, dir, object, triangle, t_host, out, I, &f);
    if (!o || (with_uv && re__band_flat(o, triangle, u, v))) return RE_UNCHANGED;
    face = *out;
    back[0] = -dir[0], back[1] = -dir[1], back[2] = -dir[2];
    switch (re__query_kd(o, f, I, back, t_host, out)) {
    case RE_UNCHANGED: return RE_UNCHANGED;
    case RE_HIT_ROUNDED: {
        double t = t_host - (out->t - t_host); /* out->t = t_host + s along the reversed ray */
        if (t >= 0) {
            out->t = t;
            return RE_HIT_ROUNDED;
        }
        break; /* met behind the origin: the ray starts outside the rounded solid */
    }
    case RE_PASS_THROUGH: break;
    }
    face.flags = out->flags;
    *out = face;
    out->kind = RE_PASS_THROUGH;
    return RE_PASS_THROUGH;
}

/* A direction whose largest component lies outside [1/RE__DIR_UNIT_RANGE,
   RE__DIR_UNIT_RANGE] is queried as dir 2^e with t in units of 2^-e (e
   brings that component into [1, 2)): exact scalings, the same ray and
   points, but |dir|^2 and the capsule and plane products neither overflow
   nor underflow (at |dir| = 1e+-200 a third of the rounded hits came back
   unchanged or with the point left on the sharp face). Other directions
   are queried as given, bit for bit: re__dir_plain says which, in three
   compares (every query asks it). re__dir_scale returns e (0: query dir
   itself, ds not written). */
#define RE__DIR_UNIT_RANGE 65536.0
static inline double re__dir_largest(const double dir[3])
{
    return re__max(fabs(dir[0]), re__max(fabs(dir[1]), fabs(dir[2])));
}
static inline int re__dir_plain(const double dir[3])
{
    double m;
    if (!dir) return 1;
    m = re__dir_largest(dir);
    return (m >= 1 / RE__DIR_UNIT_RANGE && m <= RE__DIR_UNIT_RANGE) || !(m > 0 && m < HUGE_VAL);
}
static int re__dir_scale(const double dir[3], double ds[3])
{
    int e, k;
    if (re__dir_plain(dir)) return 0;
    (void)frexp(re__dir_largest(dir), &e);
    e = 1 - e;
    for (k = 0; k < 3; k++) ds[k] = ldexp(dir[k], e);
    return e;
}

/* A query whose direction needs rescaling (re__dir_plain is 0), in the
   scaled units and back (from_inside: the exit queries, the reversed ray). */
static re_hit_kind_t re__query_scaled(const re_scene_t *scene, const double o3[3], const double dir[3], unsigned object,
                                      unsigned triangle, double t_host, int from_inside, int with_uv, double u, double v,
                                      re_hit_t *out)
{
    double ds[3];
    int e = re__dir_scale(dir, ds);
    re_hit_kind_t kind;
    t_host = ldexp(t_host, -e);
    kind = from_inside ? re__query_exit(scene, o3, ds, object, triangle, t_host, with_uv, u, v, out)
                       : re__query(scene, o3, ds, object, triangle, t_host, with_uv, u, v, out);
    out->t = ldexp(out->t, e);
    return kind;
}

RE_DEF re_hit_kind_t re_query(const re_scene_t *scene, const double o3[3], const double dir[3], unsigned object,
                              unsigned triangle, double t_host, re_hit_t *out)
{
    if (!out) return RE_UNCHANGED;
    if (re__dir_plain(dir)) return re__query(scene, o3, dir, object, triangle, t_host, 0, 0, 0, out);
    return re__query_scaled(scene, o3, dir, object, triangle, t_host, 0, 0, 0, 0, out);
}

RE_DEF re_hit_kind_t re_query_uv(const re_scene_t *scene, const double o3[3], const double dir[3], unsigned object,
                                 unsigned triangle, double t_host, double u, double v, re_hit_t *out)
{
    if (!out) return RE_UNCHANGED;
    if (re__dir_plain(dir)) return re__query(scene, o3, dir, object, triangle, t_host, 1, u, v, out);
    return re__query_scaled(scene, o3, dir, object, triangle, t_host, 0, 1, u, v, out);
}

RE_DEF re_hit_kind_t re_query_exit(const re_scene_t *scene, const double o[3], const double dir[3], unsigned object,
                                   unsigned triangle, double t_host, re_hit_t *out)
{
    if (!out) return RE_UNCHANGED;
    if (re__dir_plain(dir)) return re__query_exit(scene, o, dir, object, triangle, t_host, 0, 0, 0, out);
    return re__query_scaled(scene, o, dir, object, triangle, t_host, 1, 0, 0, 0, out);
}

RE_DEF re_hit_kind_t re_query_exit_uv(const re_scene_t *scene, const double o[3], const double dir[3], unsigned object,
                                      unsigned triangle, double t_host, double u, double v, re_hit_t *out)
{
    if (!out) return RE_UNCHANGED;
    if (re__dir_plain(dir)) return re__query_exit(scene, o, dir, object, triangle, t_host, 1, u, v, out);
    return re__query_scaled(scene, o, dir, object, triangle, t_host, 1, 1, u, v, out);
}

/* Is I + s dir, on plane `plane` of a corner of S and inside all of S's
   planes, surely on that face of the sharp mesh (within the corner's gate
   of its first sphere's foot on the face, re__exit_clearance)? Then no
   walk can find an earlier exit. */
static int re__exit_on_face(const re__object_t *o, const re__set_t *S, re__best_t *b, const double I[3],
                            const double dir[3], double s, unsigned plane)
{
    const re__plane_t *pg = &o->planes[plane];
    double X[3], d[3], g;
    unsigned q;
    if (!(s < HUGE_VAL)) return 0;
    re__madd(I, s, dir, X);
    for (q = 0; q < S->n; q++) {
        re__kv_t K = re__kview(o, S->c[q]);
        const double *c0;
        if (!re__corner_has_plane(o, &K, plane)) continue;
        g = (double)o->corners[K.k].walk * re__clear_radius(o->corners[K.k].clear);
        c0 = re__cptr(o, b, K.sfirst);
        re__sub(X, c0, d);
        re__madd(d, re__dot(pg->n, c0) - pg->c, pg->n, d); /* from the sphere's foot on the face */
        if (re__dot(d, d) <= g * g) return 1;
    }
    return 0;
}

/* A direction counts as into the solid when dir . normal < -RE__INTO_SOLID_EPS |dir|;
   a tangent one (0: a reflection of a ray that grazes along the rounding,
   or within rounding of it) leaves, as the rounded solid is convex. Until
   2026-12-06 a direction exactly tangent got the unpushed hit point
   (found by fuzz_rounded_exact's short run in make test). */
#define RE__INTO_SOLID_EPS (8.0 * RE__DBL_EPS)
/* Bound on how far a capsule's axis may lie from r below one of its
   corner's planes, relative to r (re__may_run_along_face's filter): above
   the centres' solve tolerance (RE__SPHERE_SOLVE_CAP) and the erosion's
   feasibility (RE__CORNER_EPS). */
#define RE__SEAM_NOISE_R 1e-6

/* Can the ray from a rounded hit P (normal n, on a capsule of S) along dir
   run along or under a plane g of S that P lies on (within tau <=
   max(2 RE__FLAT_ULPS mag, push / 2) of it)? Such a capsule's axis lies r
   below g up to the centres' noise (RE__SEAM_NOISE_R r), so n . n_g >= 1 -
   (tau / r + noise), |n - n_g|^2 <= 2 (tau / r + noise), and dir . n <=
   |dir| |n - n_g| when dir . n_g <= 0. Other directions (nearly all) skip
   re__leaves_on_face and re__along_out_of_reach. */
static int re__may_run_along_face(const re__object_t *o, const re__set_t *S, const double P[3], const double n[3],
                                  const double dir[3], double push)
{
    double mag = fabs(P[0]) + fabs(P[1]) + fabs(P[2]), r = re__k_radius(o, S->c[0]);
    double turn = sqrt(2 * (re__max(2 * RE__FLAT_ULPS * mag, 0.5 * push) / r + RE__SEAM_NOISE_R));
    return re__dot(dir, n) <= (RE__INTO_SOLID_EPS + turn) * re__len(dir);
}

/* Does the rounded hit P (coordinates of magnitude mag, |P|_1) lie on
   plane g, within half the origin's push or the plane test's rounding
   (RE__FLAT_ULPS of the magnitudes) if larger? A ray leaving through g
   there starts at P (re__leaves_on_face, re__along_out_of_reach). */
static int re__hit_on_plane(const re__plane_t *g, const double P[3], double mag, double push)
{
    return fabs(re__side_of(g, P)) <= re__max(RE__FLAT_ULPS * (fabs(g->c) + mag), 0.5 * push);
}

/* Does the ray from a rounded hit P along dir (past re__may_run_along_face),
   whose walk found its exit s_exit on, leave the sharp mesh at P itself
   instead, through a plane g of S that P lies on (a seam, where a capsule
   meets g's flat part: within half the origin's push, or the rounding of
   the test, RE__FLAT_ULPS of the magnitudes, if larger)? It does when it
   would otherwise sink under g's flat part before s_exit
   (re__sinks_in_flat): inside the rounded solid, so the direction left it
   only up to the capsule normal's turn at the seam. That is the
   reflection of a ray along g about the normal of a lost contact
   (re__lost_entry), turned past the seam by the ray's slope: the walk
   followed it along g, inside the sharp mesh by noise, to a crossing 0.33
   of the size outside the mesh (fuzz_rounded_exact, rays along a face at
   r 2^-6 of the size). A ray heading under g toward its edge stays in the
   removed volume, and its walk stands; so does a hit farther from g's
   plane (at offset 1e6 and r 2^-25 of the size a hit 0.3 r inside g, its
   origin then inside the sharp mesh). 1 and *plane g. */
static int re__leaves_on_face(const re__object_t *o, const re__set_t *S, const double P[3], const double dir[3],
                              double s_exit, double push, unsigned *plane)
{
    double mag = fabs(P[0]) + fabs(P[1]) + fabs(P[2]), s_end, X[3];
    unsigned i, j;
    s_end = re__min(s_exit, o->size / re__len(dir));
    re__madd(P, s_end, dir, X);
    for (i = 0; i < S->n; i++) {
        re__kv_t K = re__kview(o, S->c[i]);
        for (j = 0; j < K.np; j++) {
            unsigned gi = re__corner_plane(o, &K, j);
            const re__plane_t *g = &o->planes[gi];
            if (re__dot(g->n, dir) > 0 || !re__hit_on_plane(g, P, mag, push)) continue;
            if (re__sinks_in_flat(o, S, gi, P, dir, s_end, mag + fabs(X[0]) + fabs(X[1]) + fabs(X[2])) < HUGE_VAL)
                return *plane = gi, 1;
        }
    }
    return 0;
}

/* The origin of a ray that leaves through plane g at the hit P, before
   the push: P moved down onto g when above it (so the origin stands out of
   the mesh by the push, not by the push and P's height), P itself when
   below (moved up, the origin would leave the ray by that depth and the
   push: 9e-15 past a push of 3.46e-9 at a seam hit sinking into its face,
   fuzz_rounded_exact, seed seam_hit_below_its_face). side: P's height
   over g, n_g . P - c_g. */
static void re__down_onto(const re__plane_t *g, const double P[3], double side, double origin[3])
{
    re__madd(P, -re__max(0.0, side), g->n, origin);
}

/* Does the rounded hit P lie on the plane g its ray leaves by: below g by
   no more than the plane test's rounding (RE__FLAT_ULPS of the
   magnitudes), above it by no more than the features' noise (RE__SIDE_ULPS,
   or half the push if larger: a capsule may stand out of its faces by the
   centres' noise)? Then the ray leaves through g at P itself, and the
   origin starts there (re__down_onto). From rounding alone the crossing
   side / (dir . n_g) means nothing: a reflection along g (dir . n_g =
   1e-16, P 1e-16 below g) crossed 1.14 sizes on, past g's far edge, its
   origin 0.54 outside the mesh; and a hit 6.9e-15 above g left its origin
   that much more than the push outside (fuzz_rounded_exact, seeds
   reflection_along_a_face_from_its_seam, hit_above_its_exit_plane). Below
   g by more, the crossing stands: started at P, the origin would lie inside
   the mesh by that depth less the push (at offset 1e6 a hit 1.7e-8 below g
   against a push of 2e-9, seed seam_hit_far_out_keeps_its_walk). side:
   P's height over g (re__side_of). */
static int re__on_exit_plane(const re__plane_t *g, const double P[3], double side, double push)
{
    double mag = fabs(g->c) + fabs(P[0]) + fabs(P[1]) + fabs(P[2]);
    return side >= -RE__FLAT_ULPS * mag && side <= re__max(RE__SIDE_ULPS * mag, 0.5 * push);
}

/* A hit P below its exit plane g by more than re__on_exit_plane allows but
   within half the push, whose crossing X = P + s dir of g lies on no edge
   of g that the set reaches (re__exit_on_edge_of, as for a pass-through
   along a face): the ray ran along g, on the mesh's surface, and rounding
   put the crossing past g's far edge (a direction rising by 1e-17 from a
   hit 1e-9 below g crossed 1e8 sizes on; reflection_along_a_face_from_below_its_seam).
   It leaves through g at P, its origin then outside the mesh by at least
   half the push. Only such hits reach the edge test (side: P's height
   over g). */
static int re__crossing_out_of_reach(const re__object_t *o, const re__set_t *S, re__best_t *b, unsigned g, const double P[3],
                                     double side, const double dir[3], double s, double push)
{
    double X[3];
    if (!(side >= -0.5 * push)) return 0;
    re__madd(P, s, dir, X);
    return !re__exit_on_edge_of(o, S, b, X, g, g);
}

/* A ray from the rounded hit P (past re__may_run_along_face), on a plane
   a of S (within half the push, or the plane test's rounding if larger,
   as in re__leaves_on_face), that runs along a to its exit X = P + s dir
   on plane h (within re__along_tol of a all the way, as a pass-through's
   re__exit_within_reach) and whose exit lies on no edge of a bordering h
   that the set reaches (re__exit_on_edge_of): it runs on the mesh's
   surface, and the crossing of h, which S's planes put there, is not
   where it leaves. It leaves at P through a (returned; RE__NONE when the
   walk's exit stands). Found: a reflection at a cylinder's end, where its
   sphere meets face a, along a to within 3e-17 of a's plane (sinking too
   slowly for re__sinks_in_flat), its walk's exit by a plane of the far
   corner 0.013 outside the mesh (fuzz_rounded_exact, rays along a face at
   r 2^-6 of the size, unfused builds; seed
   reflection_along_a_face_from_a_cylinder_end). */
static unsigned re__along_out_of_reach(const re__object_t *o, const re__set_t *S, re__best_t *b, const double P[3],
                                       const double dir[3], double s, unsigned h, double push)
{
    double X[3], dmin, rmin, mag = fabs(P[0]) + fabs(P[1]) + fabs(P[2]);
    unsigned a;
    const re__plane_t *g;
    re__madd(P, s, dir, X);
    a = re__plane_along(o, S, P, X, &dmin, &rmin);
    if (a == RE__NONE || !(dmin <= re__along_tol(P, X, rmin))) return RE__NONE;
    g = &o->planes[a];
    if (!re__hit_on_plane(g, P, mag, push) || re__exit_on_edge_of(o, S, b, X, a, h))
        return RE__NONE;
    return a;
}

RE_DEF void re_secondary_origin(const re_scene_t *scene, const re_hit_t *hit, const double dir[3], double origin[3])
{
    const re__object_t *o;
    re__set_t S;
    re__exit_t E;
    re__best_t b;
    unsigned plane, iter, walked = 0;
    double s, push, ds[3];
    const double *nrm;
    int level;
    if (!origin) return;
    if (!hit) return;
    if (dir && re__dir_scale(dir, ds) != 0) dir = ds; /* the same ray (s only changes its units) */
    origin[0] = hit->point[0], origin[1] = hit->point[1], origin[2] = hit->point[2];
    if (!scene || hit->object >= scene->n_objects) return;
    o = &scene->objects[hit->object];
    push = RE_ORIGIN_OFFSET_REL * o->size;
    nrm = hit->normal;
    if (hit->kind == RE_HIT_ROUNDED && dir) { /* into the solid beyond rounding: the point itself */
        double dn = re__dot(dir, nrm);
        if (dn != dn || (dn < 0 && dn * dn > RE__INTO_SOLID_EPS * RE__INTO_SOLID_EPS * re__dot(dir, dir))) return;
    }
    if (hit->kind == RE_HIT_ROUNDED && dir) {
        re__set_init(&S);
        if (hit->feature == RE_FEATURE_SPHERE && hit->feature_index < o->n_spheres) {
            re__set_add(&S, re__s_corner(o, hit->feature_index));
        } else if (hit->feature == RE_FEATURE_CYLINDER && hit->feature_index < o->n_cyls) {
            unsigned sp[2];
            re__cyl_spheres(o, hit->feature_index, sp);
            re__set_add(&S, re__s_corner(o, sp[0]));
            re__set_add(&S, re__s_corner(o, sp[1]));
        }
        b.cvalid = 0;
        re__exit_init(&E);
        for (iter = 0;; iter++) { /* the planes the ray may leave by: the walk, as in the query */
            s = re__exit(o, &S, hit->point, dir, &E, &plane);
            if (!iter && re__exit_on_face(o, &S, &b, hit->point, dir, s, plane)) break;
            if (iter == RE__MAX_WALK || !re__walk_grow(o, &S, &b, hit->point, dir, s, &walked)) break;
        }
        level = S.n && re__may_run_along_face(o, &S, hit->point, nrm, dir, push);
        if (level && re__leaves_on_face(o, &S, hit->point, dir, s, push, &plane)) { /* at P, through that face */
            const re__plane_t *g = &o->planes[plane];
            re__down_onto(g, hit->point, re__side_of(g, hit->point), origin);
            nrm = g->n;
        } else if (s < HUGE_VAL) {
            const re__plane_t *g = &o->planes[plane];
            double side = re__side_of(g, hit->point);
            unsigned along;
            if (re__on_exit_plane(g, hit->point, side, push) ||
                re__crossing_out_of_reach(o, &S, &b, plane, hit->point, side, dir, s, push)) {
                re__down_onto(g, hit->point, side, origin);
            } else if (level && (along = re__along_out_of_reach(o, &S, &b, hit->point, dir, s, plane, push)) != RE__NONE) {
                g = &o->planes[along];
                re__down_onto(g, hit->point, re__side_of(g, hit->point), origin);
            } else {
                re__madd(hit->point, s, dir, origin);
            }
            nrm = g->n;
        }
    }
    re__madd(origin, push, nrm, origin);
}

RE_DEF unsigned re_object_count(const re_scene_t *scene) { return scene ? scene->n_objects : 0u; }
RE_DEF unsigned re_sphere_count(const re_scene_t *scene, unsigned object)
{
    return scene && object < scene->n_objects ? scene->objects[object].n_spheres : 0u;
}
RE_DEF unsigned re_cylinder_count(const re_scene_t *scene, unsigned object)
{
    return scene && object < scene->n_objects ? scene->objects[object].n_cyls : 0u;
}
RE_DEF int re_get_sphere(const re_scene_t *scene, unsigned object, unsigned i, re_sphere_t *out)
{
    const re__object_t *o;
    if (!scene || !out || object >= scene->n_objects || i >= scene->objects[object].n_spheres) return 0;
    o = &scene->objects[object];
    re__centre(o, i, out->center);
    out->radius = re__k_radius(o, re__s_corner(o, i));
    out->vertex = re__pk_get(&o->cvertex, re__s_corner(o, i));
    return 1;
}
RE_DEF int re_get_cylinder(const re_scene_t *scene, unsigned object, unsigned i, re_cylinder_t *out)
{
    const re__object_t *o;
    re__cyl_t cyv;
    const re__cyl_t *cy = &cyv;
    unsigned a;
    if (!scene || !out || object >= scene->n_objects || i >= scene->objects[object].n_cyls) return 0;
    o = &scene->objects[object];
    cyv = re__cyl(o, i);
    re__centre(o, cy->s[0], out->a);
    re__centre(o, cy->s[1], out->b);
    for (a = 0; a < 3; a++) {
        out->n0[a] = o->planes[cy->p[0]].n[a];
        out->n1[a] = o->planes[cy->p[1]].n[a];
    }
    out->radius = re__k_radius(o, re__s_corner(o, cy->s[0]));
    out->sa = cy->s[0];
    out->sb = cy->s[1];
    out->edge_v0 = i >= o->n_edge_cyls ? -1 : (long long)re__pk_get(&o->cvertex, re__s_corner(o, cy->s[0]));
    out->edge_v1 = i >= o->n_edge_cyls ? -1 : (long long)re__pk_get(&o->cvertex, re__s_corner(o, cy->s[1]));
    return 1;
}


/* ==== [section: baselines] (owned by the baselines/example helper) ==== */
#ifndef RE_NO_BASELINES
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
    /* the 32 bits reversed by swapping halves, bytes, nibbles, pairs and
       bits (a bit-by-bit loop cost the 4-sample bevel ~900 instructions a
       shading point, a quarter of its own work, where a renderer reads a
       table) */
    unsigned long long r = i & 0xFFFFFFFFull;
    r = ((r >> 16) | (r << 16)) & 0xFFFFFFFFull;
    r = ((r & 0x00FF00FFull) << 8) | ((r >> 8) & 0x00FF00FFull);
    r = ((r & 0x0F0F0F0Full) << 4) | ((r >> 4) & 0x0F0F0F0Full);
    r = ((r & 0x33333333ull) << 2) | ((r >> 2) & 0x33333333ull);
    r = ((r & 0x55555555ull) << 1) | ((r >> 1) & 0x55555555ull);
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
    re__frame(nu, t, b);
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
    re__frame(axes[0], axes[1], axes[2]);
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
            if (desc->trace_object ? !desc->trace_object(user, object, o, d, tmin, 2.0 * h, &hit)
                                   : !trace(user, o, d, tmin, 2.0 * h, &hit))
                break;
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
#endif /* RE_NO_BASELINES */
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
