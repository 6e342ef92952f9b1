/* grooves.h 2D polygon routines (issue 8, §5.2-5.5): Sutherland-Hodgman
   against convex clip rings, the slab-sweep boolean for general rings, and
   the shoelace area. Oracles: hand-computed areas, the set identities
   |A∩B| + |A\B| = |A| and |A∪B| = |A| + |B| - |A∩B| (each operation is a
   separate pass of the sweep, so a wrong predicate or a lost slab breaks
   them), and an independent raster of even-odd point-in-polygon tests. */
#include "grooves.h"
#include "test.h"
#include "test_even_odd.h"

#define MAXP 64

static gr_polyset_t one_ring(const double *p, int n)
{
    gr_polyset_t s;
    memset(&s, 0, sizeof s);
    s.points = p;
    s.point_count = n;
    return s;
}

/* area of a op b through gr_poly_boolean (asserting GR_OK) */
static double bool_area(const double *a, int na, const double *b, int nb, gr_poly_op_t op)
{
    static unsigned char scratch[1 << 20];
    gr_polyset_t sa = one_ring(a, na), sb = one_ring(b, nb);
    double area = -1;
    int r = gr_poly_boolean(&sa, &sb, op, scratch, sizeof scratch, NULL, 0, NULL, &area);
    T_INT_EQ(r, GR_OK);
    return area;
}

static double clip_area(const double *a, int na, const double *clip, int nc)
{
    double out[2 * 4 * MAXP], work[2 * 4 * MAXP];
    int n = -1, r = gr_poly_clip_convex(a, na, clip, nc, out, work, 4 * MAXP, &n);
    T_INT_EQ(r, GR_OK);
    return gr_poly_area(out, n);
}

/* random star-shaped (generally non-convex, always simple) ring about c,
   radii in [r0, r1] */
static int star(t_rng_t *g, double *p, int n, double cx, double cy, double r0, double r1)
{
    int i;
    /* one angle per sector of 2π/n, jittered by under half a sector: every
       gap stays below π (1.45 x 2π/3 < π), so the ring is simple */
    for (i = 0; i < n; i++) {
        double ang = 2 * M_PI * (i + 0.45 * t_rng_unit(g)) / n, r = t_rng_range(g, r0, r1);
        p[2 * i] = cx + r * cos(ang);
        p[2 * i + 1] = cy + r * sin(ang);
    }
    return n;
}

static void area_square_orientation(void)
{
    const double ccw[] = {0, 0, 2, 0, 2, 3, 0, 3}, cw[] = {0, 0, 0, 3, 2, 3, 2, 0};
    const double line[] = {0, 0, 1, 1, 2, 2, 3, 3};
    T_EQ(gr_poly_area(ccw, 4), 6);
    T_EQ(gr_poly_area(cw, 4), -6);
    T_EQ(gr_poly_area(line, 4), 0);
    T_EQ(gr_poly_area(ccw, 2), 0);
    T_EQ(gr_poly_area(NULL, 4), 0);
}

/* two unit squares offset by (0.5, 0.25): overlap 0.5 x 0.75 = 0.375 */
static void clip_convex_square_square(void)
{
    const double a[] = {0, 0, 1, 0, 1, 1, 0, 1}, b[] = {0.5, 0.25, 1.5, 0.25, 1.5, 1.25, 0.5, 1.25};
    const double bcw[] = {0.5, 0.25, 0.5, 1.25, 1.5, 1.25, 1.5, 0.25};
    T_NEAR(clip_area(a, 4, b, 4), 0.375, 1e-15);
    T_NEAR(clip_area(a, 4, bcw, 4), 0.375, 1e-15); /* clip orientation does not matter */
    T_NEAR(bool_area(a, 4, b, 4, GR_POLY_INTERSECTION), 0.375, 1e-15);
    T_NEAR(bool_area(a, 4, b, 4, GR_POLY_DIFFERENCE), 0.625, 1e-15);
    T_NEAR(bool_area(a, 4, b, 4, GR_POLY_UNION), 1.625, 1e-15);
    T_NEAR(bool_area(a, 4, b, 4, GR_POLY_XOR), 1.25, 1e-15);
}

/* clipping a polygon against itself returns it: every subject vertex lies
   on a clip line, the case that breaks strict inside tests */
static void clip_against_itself(void)
{
    t_rng_t g = {12345};
    long trial, n = t_count(2000);
    for (trial = 0; trial < n; trial++) {
        double p[2 * MAXP], a;
        int k = 3 + (int)(t_rng_unit(&g) * 20), i;
        double cx = t_rng_range(&g, -5, 5), cy = t_rng_range(&g, -5, 5), rx = t_rng_range(&g, 0.1, 3);
        double ang[MAXP];
        for (i = 0; i < k; i++) ang[i] = 2 * M_PI * ((double)i + 0.9 * t_rng_unit(&g)) / k; /* sorted: convex */
        for (i = 0; i < k; i++) { p[2 * i] = cx + rx * cos(ang[i]); p[2 * i + 1] = cy + 0.5 * rx * sin(ang[i]); }
        a = gr_poly_area(p, k);
        T_REL(clip_area(p, k, p, k), a, 1e-13);
        T_REL(bool_area(p, k, p, k, GR_POLY_INTERSECTION), a, 1e-13);
        T_REL(bool_area(p, k, p, k, GR_POLY_UNION), a, 1e-13);
        T_LE(bool_area(p, k, p, k, GR_POLY_DIFFERENCE), 1e-13 * a);
        /* a non-convex star against itself through the general routine */
        k = star(&g, p, k, cx, cy, 0.2 * rx, rx);
        a = fabs(gr_poly_area(p, k));
        T_REL(bool_area(p, k, p, k, GR_POLY_INTERSECTION), a, 1e-12);
        T_LE(bool_area(p, k, p, k, GR_POLY_XOR), 1e-12 * a);
    }
}

/* random stars: the sweep's four operations satisfy the set identities,
   and Sutherland-Hodgman agrees with it for a convex clip */
static void boolean_area_conservation(void)
{
    t_rng_t g = {777};
    long trial, n = t_count(3000);
    for (trial = 0; trial < n; trial++) {
        double a[2 * MAXP], b[2 * MAXP], c[2 * MAXP], aa, ab, in, df, un, xo;
        int na = star(&g, a, 3 + (int)(t_rng_unit(&g) * 25), 0, 0, 0.1, 1);
        int nb = star(&g, b, 3 + (int)(t_rng_unit(&g) * 25), t_rng_range(&g, -1, 1), t_rng_range(&g, -1, 1), 0.1, 1);
        int nc = 3 + (int)(t_rng_unit(&g) * 10), i;
        double rc = t_rng_range(&g, 0.2, 1.5), cx = t_rng_range(&g, -1, 1);
        aa = fabs(gr_poly_area(a, na));
        ab = fabs(gr_poly_area(b, nb));
        in = bool_area(a, na, b, nb, GR_POLY_INTERSECTION);
        df = bool_area(a, na, b, nb, GR_POLY_DIFFERENCE);
        un = bool_area(a, na, b, nb, GR_POLY_UNION);
        xo = bool_area(a, na, b, nb, GR_POLY_XOR);
        T_NEAR(in + df, aa, 1e-12);
        T_NEAR(un, aa + ab - in, 1e-12);
        T_NEAR(xo, un - in, 1e-12);
        T_NEAR(bool_area(b, nb, a, na, GR_POLY_INTERSECTION), in, 1e-12); /* symmetric */
        for (i = 0; i < nc; i++) { c[2 * i] = cx + rc * cos(2 * M_PI * i / nc); c[2 * i + 1] = rc * sin(2 * M_PI * i / nc); }
        T_NEAR(clip_area(a, na, c, nc) * (gr_poly_area(a, na) > 0 ? 1 : -1), bool_area(a, na, c, nc, GR_POLY_INTERSECTION), 1e-12);
    }
}

/* The raster oracle, with its error bounded: the square holding both rings
   is split into quarters down to cells of 1/2^RAST_DEPTH of its side. A
   cell no edge meets (tested with a margin, so rounding cannot hide a
   crossing) is inside or outside each ring throughout, as its centre is
   (even-odd point-in-polygon); in a cell an edge of one ring meets, that
   ring's side is either, so the cell adds to each operation's lower bound
   its area times the least the operation can be over the unknown sides
   and to its upper bound times the most. The true areas lie between. */
#define RAST_DEPTH 16
typedef struct rast_t {
    const double *p[2];
    int n[2];
    double lo[4], hi[4];
} rast_t;

static int op_value(int op, int ia, int ib) { return op == 0 ? ia && ib : op == 1 ? ia && !ib : op == 2 ? ia || ib : ia != ib; }

/* edge e (ring e & 1, its edge e >> 1) meets the cell [x0, x0 + w] x [y0, y0 + w]
   (grown by a margin)? */
static int edge_meets_cell(const rast_t *R, int e, double x0, double y0, double w)
{
    const double *p = R->p[e & 1];
    int i = e >> 1, n = R->n[e & 1];
    const double *u = p + 2 * i, *v = p + 2 * ((i + 1) % n);
    double m = 1e-9 * w + 1e-12, dx = v[0] - u[0], dy = v[1] - u[1], tol, f, flo = HUGE_VAL, fhi = -HUGE_VAL;
    int k;
    if (fmax(u[0], v[0]) < x0 - m || fmin(u[0], v[0]) > x0 + w + m || fmax(u[1], v[1]) < y0 - m ||
        fmin(u[1], v[1]) > y0 + w + m)
        return 0;
    for (k = 0; k < 4; k++) { /* the corners' sides of the edge's line */
        f = ((x0 + (k & 1) * w) - u[0]) * dy - ((y0 + (k >> 1) * w) - u[1]) * dx;
        flo = fmin(flo, f), fhi = fmax(fhi, f);
    }
    tol = m * (fabs(dx) + fabs(dy));
    return !(flo > tol || fhi < -tol);
}

static void rast_cell(rast_t *R, const int *edges, int ne, double x0, double y0, double w, int depth)
{
    int cut[2] = {0, 0}, in[2], op, i;
    for (i = 0; i < ne; i++) cut[edges[i] & 1] = 1;
    if (ne && depth < RAST_DEPTH) {
        int sub[4 * MAXP], ns, q;
        for (q = 0; q < 4; q++) {
            double cx = x0 + (q & 1) * w / 2, cy = y0 + (q >> 1) * w / 2;
            for (ns = 0, i = 0; i < ne; i++)
                if (edge_meets_cell(R, edges[i], cx, cy, w / 2)) sub[ns++] = edges[i];
            rast_cell(R, sub, ns, cx, cy, w / 2, depth + 1);
        }
        return;
    }
    for (i = 0; i < 2; i++) in[i] = teo_in_ring(R->p[i], R->n[i], x0 + w / 2, y0 + w / 2);
    for (op = 0; op < 4; op++) {
        int least = 1, most = 0, ia, ib;
        for (ia = 0; ia < 2; ia++)
            for (ib = 0; ib < 2; ib++) {
                int v;
                if ((!cut[0] && ia != in[0]) || (!cut[1] && ib != in[1])) continue;
                v = op_value(op, ia, ib);
                least = v < least ? v : least, most = v > most ? v : most;
            }
        R->lo[op] += least * w * w, R->hi[op] += most * w * w;
    }
}

/* the four operations' areas of a and b lie in [lo[op], hi[op]] */
static void raster_bounds(const double *a, int na, const double *b, int nb, double lo[4], double hi[4])
{
    rast_t R;
    int edges[4 * MAXP], ne = 0, i;
    double x0 = HUGE_VAL, y0 = HUGE_VAL, x1 = -HUGE_VAL, y1 = -HUGE_VAL;
    R.p[0] = a, R.p[1] = b, R.n[0] = na, R.n[1] = nb;
    for (i = 0; i < 4; i++) R.lo[i] = R.hi[i] = 0;
    for (i = 0; i < na + nb; i++) {
        const double *q = i < na ? a + 2 * i : b + 2 * (i - na);
        x0 = fmin(x0, q[0]), y0 = fmin(y0, q[1]), x1 = fmax(x1, q[0]), y1 = fmax(y1, q[1]);
    }
    for (i = 0; i < na; i++) edges[ne++] = 2 * i;
    for (i = 0; i < nb; i++) edges[ne++] = 2 * i + 1;
    rast_cell(&R, edges, ne, x0 - 1e-3, y0 - 1e-3, fmax(x1 - x0, y1 - y0) + 2e-3, 0);
    for (i = 0; i < 4; i++) lo[i] = R.lo[i], hi[i] = R.hi[i];
}

static void boolean_vs_raster(void)
{
    t_rng_t g = {4242};
    long trial, n = t_count(12);
    for (trial = 0; trial < n; trial++) {
        double a[2 * MAXP], b[2 * MAXP], lo[4], hi[4];
        int na = star(&g, a, 5 + (int)(t_rng_unit(&g) * 15), 0, 0, 0.2, 1.4);
        int nb = star(&g, b, 5 + (int)(t_rng_unit(&g) * 15), t_rng_range(&g, -0.5, 0.5), t_rng_range(&g, -0.5, 0.5), 0.2, 1);
        int i, op;
        if (trial & 1) /* every other b: random points, a self-intersecting ring (even-odd) */
            for (i = 0; i < 2 * nb; i++) b[i] = t_rng_range(&g, -1.2, 1.2);
        raster_bounds(a, na, b, nb, lo, hi);
        for (op = 0; op < 4; op++) {
            double area = bool_area(a, na, b, nb, (gr_poly_op_t)op);
            T_LE(lo[op] - 1e-12, area);
            T_LE(area, hi[op] + 1e-12);
            T_LE(hi[op] - lo[op], 2e-3); /* the bounds are tight enough to mean something */
        }
    }
}

/* degenerate and collinear inputs, one expected area each */
static void boolean_degenerate(void)
{
    const double sq[] = {0, 0, 1, 0, 1, 1, 0, 1};
    const double right[] = {1, 0, 2, 0, 2, 1, 1, 1};          /* shares an edge */
    const double corner[] = {1, 1, 2, 1, 2, 2, 1, 2};         /* shares a vertex */
    const double halfcol[] = {0, 0, 0.5, 0, 1, 0, 1, 0.5, 1, 1, 0, 1}; /* collinear extra points */
    const double dup[] = {0, 0, 0, 0, 1, 0, 1, 1, 1, 1, 0, 1};           /* repeated points */
    const double flat[] = {0, 0.5, 2, 0.5, 1, 0.5};          /* zero-area ring */
    const double bow[] = {0, 0, 2, 2, 2, 0, 0, 2};            /* bow tie: two triangles of area 1 */
    const double inner[] = {0.25, 0.25, 0.75, 0.25, 0.75, 0.75, 0.25, 0.75}; /* a hole-maker */
    const double slab[] = {-1, 0.25, 3, 0.25, 3, 0.5, -1, 0.5}; /* edges on the square's sides */
    T_NEAR(bool_area(sq, 4, right, 4, GR_POLY_INTERSECTION), 0, 1e-15);
    T_NEAR(bool_area(sq, 4, right, 4, GR_POLY_UNION), 2, 1e-15);
    T_NEAR(bool_area(sq, 4, corner, 4, GR_POLY_UNION), 2, 1e-15);
    T_NEAR(bool_area(sq, 4, corner, 4, GR_POLY_DIFFERENCE), 1, 1e-15);
    T_NEAR(bool_area(halfcol, 6, sq, 4, GR_POLY_XOR), 0, 1e-15);
    T_NEAR(bool_area(dup, 6, sq, 4, GR_POLY_XOR), 0, 1e-15);
    T_NEAR(bool_area(sq, 4, flat, 3, GR_POLY_DIFFERENCE), 1, 1e-15);
    T_NEAR(bool_area(flat, 3, sq, 4, GR_POLY_UNION), 1, 1e-15);
    T_NEAR(bool_area(bow, 4, bow, 4, GR_POLY_UNION), 2, 1e-15);
    T_NEAR(bool_area(bow, 4, sq, 4, GR_POLY_INTERSECTION), 0.5, 1e-15);
    T_NEAR(bool_area(sq, 4, inner, 4, GR_POLY_DIFFERENCE), 0.75, 1e-15); /* a square with a hole */
    T_NEAR(bool_area(sq, 4, slab, 4, GR_POLY_DIFFERENCE), 0.75, 1e-15);
    T_NEAR(clip_area(sq, 4, slab, 4), 0.25, 1e-15);
    T_NEAR(clip_area(halfcol, 6, halfcol, 6), 1, 1e-15); /* collinear clip points */
    T_NEAR(clip_area(sq, 4, flat, 3), 0, 0);              /* zero-area clip: empty */
    T_NEAR(clip_area(flat, 3, sq, 4), 0, 0);
}

/* the trapezoids: disjoint, counter-clockwise, summing to the area, and
   a valid polygon set in their own right (they feed back in) */
static void boolean_trapezoids(void)
{
    static unsigned char scratch[1 << 20];
    static double traps[8 * 4096];
    t_rng_t g = {99};
    long trial, n = t_count(300);
    for (trial = 0; trial < n; trial++) {
        double a[2 * MAXP], b[2 * MAXP], area, sum = 0, again;
        int na = star(&g, a, 4 + (int)(t_rng_unit(&g) * 12), 0, 0, 0.1, 1);
        int nb = star(&g, b, 4 + (int)(t_rng_unit(&g) * 12), 0.3, 0.1, 0.1, 1);
        gr_polyset_t sa = one_ring(a, na), sb = one_ring(b, nb), st, none = one_ring(NULL, 0);
        int nt = -1, nt2 = -1, k;
        T_INT_EQ(gr_poly_boolean(&sa, &sb, GR_POLY_DIFFERENCE, scratch, sizeof scratch, traps, 4096, &nt, &area), GR_OK);
        for (k = 0; k < nt; k++) {
            T_GE(gr_poly_area(traps + 8 * k, 4), -1e-15);
            sum += gr_poly_area(traps + 8 * k, 4);
        }
        T_NEAR(sum, area, 1e-12);
        st = one_ring(traps, 4 * nt);
        st.ring_count = nt;
        T_INT_EQ(gr_poly_boolean(&st, &none, GR_POLY_UNION, scratch, sizeof scratch, NULL, 0, NULL, &again), GR_OK);
        T_NEAR(again, area, 1e-12); /* disjoint: union area = sum */
        T_INT_EQ(gr_poly_boolean(&st, &sb, GR_POLY_INTERSECTION, scratch, sizeof scratch, NULL, 0, NULL, &again), GR_OK);
        T_NEAR(again, 0, 1e-12);    /* a \ b misses b */
        if (nt > 1) {
            T_INT_EQ(gr_poly_boolean(&sa, &sb, GR_POLY_DIFFERENCE, scratch, sizeof scratch, traps, nt - 1, &nt2, &again),
                     GR_ERR_BUFFER_TOO_SMALL);
            T_INT_EQ(nt2, nt);
            T_NEAR(again, area, 0);
        }
    }
}

/* Stiff: nearly coincident edges. The unit square against itself moved
   by δ = 1e-13: the overlap is exactly 1 - δ (to rounding of the moved
   coordinates, 2^-52 each), the xor 2δ. */
static void stiff_near_coincident(void)
{
    const double sq[] = {0, 0, 1, 0, 1, 1, 0, 1}, dl = 1e-13;
    const double mv[] = {dl, 0, 1 + dl, 0, 1 + dl, 1, dl, 1};
    const double rot[] = {0, 0, 1, 1e-15, 1 - 1e-15, 1, 0, 1}; /* a sliver-thin tilt */
    T_NEAR(bool_area(sq, 4, mv, 4, GR_POLY_INTERSECTION), 1 - dl, 4e-16);
    T_NEAR(bool_area(sq, 4, mv, 4, GR_POLY_XOR), 2 * dl, 4e-16);
    T_NEAR(clip_area(sq, 4, mv, 4), 1 - dl, 4e-16);
    T_NEAR(bool_area(sq, 4, rot, 4, GR_POLY_DIFFERENCE), 1e-15, 4e-16);
}

/* Stiff: far from the origin. A unit square at 1e6 has coordinates with
   ulp 1.2e-10; areas of unit size then carry errors of that order. */
static void stiff_far_from_origin(void)
{
    const double o = 1e6;
    const double a[] = {o, o, o + 1, o, o + 1, o + 1, o, o + 1};
    const double b[] = {o + 0.5, o + 0.25, o + 1.5, o + 0.25, o + 1.5, o + 1.25, o + 0.5, o + 1.25};
    T_NEAR(bool_area(a, 4, b, 4, GR_POLY_INTERSECTION), 0.375, 1e-9);
    T_NEAR(bool_area(a, 4, b, 4, GR_POLY_UNION), 1.625, 1e-9);
    T_NEAR(clip_area(a, 4, b, 4), 0.375, 1e-9);
}

/* several rings in one set unite: three overlapping squares as one set
   against the same union built pairwise through the trapezoid output */
static void boolean_multi_ring_sets(void)
{
    static unsigned char scratch[1 << 20];
    static double t1[8 * 512];
    const double three[] = {0, 0, 2, 0, 2, 2, 0, 2, 1, 1, 3, 1, 3, 3, 1, 3, 1.5, -1, 2.5, -1, 2.5, 4, 1.5, 4};
    const int sizes[] = {4, 4, 4};
    gr_polyset_t all = one_ring(three, 12), none = one_ring(NULL, 0), ab, c = one_ring(three + 16, 4), first2;
    double area, area2;
    int nt = 0;
    all.ring_sizes = sizes;
    all.ring_count = 3;
    T_INT_EQ(gr_poly_boolean(&all, &none, GR_POLY_UNION, scratch, sizeof scratch, NULL, 0, NULL, &area), GR_OK);
    first2 = one_ring(three, 4);
    ab = one_ring(three + 8, 4);
    T_INT_EQ(gr_poly_boolean(&first2, &ab, GR_POLY_UNION, scratch, sizeof scratch, t1, 512, &nt, NULL), GR_OK);
    ab = one_ring(t1, 4 * nt);
    ab.ring_count = nt;
    T_INT_EQ(gr_poly_boolean(&ab, &c, GR_POLY_UNION, scratch, sizeof scratch, NULL, 0, NULL, &area2), GR_OK);
    T_NEAR(area, area2, 1e-14);
    /* C (x in [1.5, 2.5], v in [-1, 4], area 5) overlaps A ∪ B in x in
       [1.5, 2] for v in [0, 3] and x in [2, 2.5] for v in [1, 3]: 1.5 + 1 */
    T_NEAR(area, 7 + 5 - 2.5, 1e-14);
}

static void bad_input(void)
{
    static unsigned char scratch[1 << 16];
    const double sq[] = {0, 0, 1, 0, 1, 1, 0, 1}, ell[] = {0, 0, 2, 0, 2, 1, 1, 1, 1, 2, 0, 2};
    const double star5[] = {0, 1, 0.588, -0.809, -0.951, 0.309, 0.951, 0.309, -0.588, -0.809};
    double nan_sq[] = {0, 0, 1, 0, 1, 1, 0, 1}, out[64], work[64], area;
    const int sizes[] = {3, 3};
    gr_polyset_t a = one_ring(sq, 4), bad = one_ring(sq, 4);
    int n = 7;
    nan_sq[3] = NAN;
    T_INT_EQ(gr_poly_clip_convex(sq, 4, ell, 6, out, work, 32, &n), GR_ERR_INVALID_ARG); /* L: not convex */
    T_INT_EQ(n, 0);
    T_INT_EQ(gr_poly_clip_convex(sq, 4, star5, 5, out, work, 32, &n), GR_ERR_INVALID_ARG); /* winds twice */
    T_INT_EQ(gr_poly_clip_convex(sq, 4, sq, 2, out, work, 32, &n), GR_ERR_INVALID_ARG);
    T_INT_EQ(gr_poly_clip_convex(nan_sq, 4, sq, 4, out, work, 32, &n), GR_ERR_NOT_FINITE);
    T_INT_EQ(gr_poly_clip_convex(sq, 4, sq, 4, out, work, 3, &n), GR_ERR_BUFFER_TOO_SMALL);
    T_INT_EQ(gr_poly_clip_convex(sq, 4, sq, 4, NULL, work, 32, &n), GR_ERR_INVALID_ARG);
    T_INT_EQ(gr_poly_boolean(&a, NULL, GR_POLY_UNION, scratch, sizeof scratch, NULL, 0, NULL, &area), GR_ERR_INVALID_ARG);
    T_INT_EQ(gr_poly_boolean(&a, &a, (gr_poly_op_t)9, scratch, sizeof scratch, NULL, 0, NULL, &area), GR_ERR_INVALID_ARG);
    bad.ring_sizes = sizes;
    bad.ring_count = 2; /* 3 + 3 != 4 points */
    T_INT_EQ(gr_poly_boolean(&a, &bad, GR_POLY_UNION, scratch, sizeof scratch, NULL, 0, NULL, &area), GR_ERR_INVALID_ARG);
    bad = one_ring(sq, 4);
    bad.ring_count = 3; /* 4 points do not split into 3 equal rings */
    T_INT_EQ(gr_poly_boolean(&a, &bad, GR_POLY_UNION, scratch, sizeof scratch, NULL, 0, NULL, &area), GR_ERR_INVALID_ARG);
    bad = one_ring(nan_sq, 4);
    T_INT_EQ(gr_poly_boolean(&a, &bad, GR_POLY_UNION, scratch, sizeof scratch, NULL, 0, NULL, &area), GR_ERR_NOT_FINITE);
    T_INT_EQ(gr_poly_boolean(&a, &a, GR_POLY_UNION, scratch, gr_poly_boolean_scratch_bytes(8) - 1, NULL, 0, NULL, &area),
             GR_ERR_BUFFER_TOO_SMALL);
    T_INT_EQ(gr_poly_boolean(&a, &a, GR_POLY_UNION, scratch, gr_poly_boolean_scratch_bytes(8), NULL, 0, NULL, &area), GR_OK);
    T_NEAR(area, 1, 0);
}

int main(int argc, char **argv)
{
    static const t_case_t cases[] = {
        T_CASE(area_square_orientation), T_CASE(clip_convex_square_square), T_CASE(clip_against_itself),
        T_CASE(boolean_area_conservation), T_CASE(boolean_vs_raster), T_CASE(boolean_degenerate),
        T_CASE(boolean_trapezoids), T_CASE(stiff_near_coincident), T_CASE(stiff_far_from_origin),
        T_CASE(boolean_multi_ring_sets), T_CASE(bad_input),
    };
    return T_RUN(argc, argv, cases);
}
