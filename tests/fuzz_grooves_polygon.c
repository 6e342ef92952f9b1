/* libFuzzer target for gr_poly_boolean (make fuzz; a short run in make
   test). test_grooves_polygon checks random star-shaped rings against set
   identities and a raster; here the fuzzer steers rings on a small integer
   grid, where vertices coincide, edges overlap along their length, rings
   touch at points and cross themselves: the inputs a slab sweep gets wrong.
     byte 0  bits 0-1 the operation; bit 2 the points split into several
             rings per set (ring sizes from the bytes after the counts);
             bits 3-5 the grid's scale 2^{-30, -10, 0, 10, 30, 0, 0, 0};
             bits 6-7 the offset {0, 1e6, -3e5, 0} added to x and y
     byte 1  a's point count (b % 25), byte 2 b's (b % 25)
     then    with bit 2, one byte per ring, its size 1 + b % 8 (rings of one
             or two points are allowed and enclose nothing)
     then    the points, one byte each: x = b % 17 - 8, y = b / 17 % 17 - 8
             (bytes past the end are 0)
   Coordinates are off + k 2^e for small integers k, exact doubles, so the
   orientation tests on them are exact and the oracle is too.
   Checks: GR_OK; the four operations' areas satisfy the set identities
   |A ∪ B| + |A ∩ B| = |A| + |B|, |A \ B| = |A ∪ B| - |B|, |A xor B| =
   |A ∪ B| - |A ∩ B| (|A| and |B| each as the union with the empty set);
   the trapezoids have a horizontal bottom and top, their sides left to
   right (their corners counter-clockwise), sum to the area, and at sample
   points away from every edge and every slab height (vertex heights and
   edge crossings) exactly one trapezoid holds a point of a op b and none
   holds any other, where membership is the independent even-odd crossing
   number of each ring (a point lies in a set when it lies in any of its
   rings); one trapezoid less than needed gives GR_ERR_BUFFER_TOO_SMALL
   with the same count and area, and one byte of scratch less too. A
   failed check aborts (a crash for libFuzzer) after printing the case. */
#define GR_IMPLEMENTATION
#include "grooves.h"
#include "fuzz_check.h"
#include "test_even_odd.h"
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define FP_MAX_POINTS 24
#define FP_SAMPLES 64
/* Samples closer than FP_EPS grid units, or FP_EPS_ULPS roundings of the
   coordinates' magnitude M, to an edge or a slab height are skipped: the
   sweep's crossing heights and trapezoid corners are rounded there. */
#define FP_EPS 1e-6
#define FP_EPS_ULPS 1024.0
/* Area tolerance: FP_AREA_TOL of the grid's area (16 units square), plus
   FP_AREA_ULPS roundings of M per unit of a trapezoid's 36-unit perimeter
   bound for every slab the sweep may cut (vertex and crossing heights:
   at most ne + ne^2 for ne edges). */
#define FP_AREA_TOL 1e-11
#define FP_AREA_ULPS 8.0

typedef struct fp_set_t {
    double pts[2 * FP_MAX_POINTS];
    int sizes[FP_MAX_POINTS];
    int n, rings;
} fp_set_t;

static gr_polyset_t fp_polyset(const fp_set_t *s)
{
    gr_polyset_t p;
    memset(&p, 0, sizeof p);
    p.points = s->pts;
    p.point_count = s->n;
    p.ring_sizes = s->sizes;
    p.ring_count = s->rings;
    return p;
}

static int fp_in_set(const fp_set_t *s, double x, double y)
{
    int r, first = 0;
    for (r = 0; r < s->rings; r++) {
        if (teo_in_ring(s->pts + 2 * first, s->sizes[r], x, y)) return 1;
        first += s->sizes[r];
    }
    return 0;
}
static int fp_in_result(int op, int a, int b)
{
    return op == GR_POLY_INTERSECTION ? a && b : op == GR_POLY_DIFFERENCE ? a && !b : op == GR_POLY_UNION ? a || b : a != b;
}

/* The sets' edges (rings of 3 or more points), 4 doubles each. */
static int fp_edges(const fp_set_t *s, double *e, int ne)
{
    int r, i, first = 0;
    for (r = 0; r < s->rings; r++) {
        int n = s->sizes[r];
        for (i = 0; n >= 3 && i < n; i++) {
            const double *u = s->pts + 2 * (first + i), *v = s->pts + 2 * (first + (i + 1) % n);
            e[4 * ne] = u[0], e[4 * ne + 1] = u[1], e[4 * ne + 2] = v[0], e[4 * ne + 3] = v[1];
            ne++;
        }
        first += n;
    }
    return ne;
}

static double fp_seg_dist(const double *e, double x, double y)
{
    double dx = e[2] - e[0], dy = e[3] - e[1], l2 = dx * dx + dy * dy, t = 0;
    if (l2 > 0) t = fmax(0.0, fmin(1.0, ((x - e[0]) * dx + (y - e[1]) * dy) / l2));
    return hypot(x - (e[0] + t * dx), y - (e[1] + t * dy));
}

/* Is (x, y) at least eps from every edge, every vertex height and every
   height where two edges cross? Only there is the answer unambiguous. */
static int fp_clear(const double *e, int ne, double x, double y, double eps)
{
    int i, j;
    for (i = 0; i < ne; i++) {
        if (fp_seg_dist(e + 4 * i, x, y) < eps || fabs(e[4 * i + 1] - y) < eps) return 0;
        for (j = i + 1; j < ne; j++) {
            const double *p = e + 4 * i, *q = e + 4 * j;
            double d = (p[2] - p[0]) * (q[3] - q[1]) - (p[3] - p[1]) * (q[2] - q[0]), s;
            if (d == 0) continue;
            s = ((q[0] - p[0]) * (q[3] - q[1]) - (q[1] - p[1]) * (q[2] - q[0])) / d;
            if (s >= 0 && s <= 1 && fabs(p[1] + s * (p[3] - p[1]) - y) < eps) return 0;
        }
    }
    return 1;
}

/* Does trapezoid t hold (x, y)? Its corners run bottom-left, bottom-right,
   top-right, top-left (gr_poly_boolean's order), so it holds the points
   between its bottom and top heights and between its two sides there. (A
   test by the signs of the corners' cross products is not one: a bottom
   edge shrunk to a point by rounding may point anywhere.) */
static int fp_in_trap(const double *t, double x, double y)
{
    double f, xl, xr;
    if (!(y >= t[1] && y <= t[7])) return 0;
    f = t[7] > t[1] ? (y - t[1]) / (t[7] - t[1]) : 0;
    xl = t[0] + f * (t[6] - t[0]);
    xr = t[2] + f * (t[4] - t[2]);
    return x >= xl && x <= xr;
}

/* Is t a trapezoid as documented: bottom and top horizontal, the top not
   below the bottom, each side's left end not right of its right end by
   more than tol? */
static int fp_trap_shape(const double *t, double tol)
{
    return t[1] == t[3] && t[5] == t[7] && t[7] >= t[1] && t[0] <= t[2] + tol && t[6] <= t[4] + tol;
}

/* Reads a set: its point count from *cnt, its rings from the ring bytes. */
static void fp_read_set(fp_set_t *s, int n, int split, const uint8_t **rb, const uint8_t *end)
{
    s->n = n;
    s->rings = 0;
    if (!split) {
        s->sizes[s->rings++] = n;
        return;
    }
    while (n > 0) {
        int k = 1 + (*rb < end ? **rb : 0) % 8;
        if (*rb < end) (*rb)++;
        if (k > n) k = n;
        s->sizes[s->rings++] = k;
        n -= k;
    }
}

/* The sets and trapezoids in grid units, before a failed check. */
static void fp_print_case(const fp_set_t *A, const fp_set_t *B, const double *traps, int nt, double off, double unit)
{
    int i, k;
    const fp_set_t *s[2] = {A, B};
    for (k = 0; k < 2; k++) {
        fprintf(stderr, "%c (%d rings):", "ab"[k], s[k]->rings);
        for (i = 0; i < s[k]->n; i++) fprintf(stderr, " (%g %g)", (s[k]->pts[2 * i] - off) / unit, (s[k]->pts[2 * i + 1] - off) / unit);
        fprintf(stderr, "\n");
    }
    for (i = 0; i < nt; i++) {
        fprintf(stderr, "trapezoid %d:", i);
        for (k = 0; k < 4; k++) fprintf(stderr, " (%.9g %.9g)", (traps[8 * i + 2 * k] - off) / unit, (traps[8 * i + 2 * k + 1] - off) / unit);
        fprintf(stderr, "\n");
    }
}

static double fp_area(const gr_polyset_t *a, const gr_polyset_t *b, int op, void *scratch, size_t bytes)
{
    double area = -1;
    gr_result_t r = gr_poly_boolean(a, b, (gr_poly_op_t)op, scratch, bytes, NULL, 0, NULL, &area);
    FUZZ_CHECK(r == GR_OK, "op %d: %s", op, gr_result_string(r));
    return area;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static const int exps[8] = {-30, -10, 0, 10, 30, 0, 0, 0};
    static const double offs[4] = {0, 1e6, -3e5, 0};
    fp_set_t A, B;
    gr_polyset_t pa, pb, none;
    const uint8_t *rb, *end = data + size;
    double unit, off, mag, eps, area, sum = 0, ar[4], aa, ab, e[4 * 2 * FP_MAX_POINTS], *traps = NULL, again = -1, tol;
    int op, i, nt = -1, nt2 = -1, ne;
    size_t bytes;
    unsigned char *scratch;
    gr_result_t r;
    uint64_t h = 1469598103934665603ull;
    if (size < 3) return 0;
    op = data[0] & 3;
    unit = ldexp(1.0, exps[data[0] >> 3 & 7]);
    off = offs[data[0] >> 6 & 3];
    rb = data + 3;
    fp_read_set(&A, data[1] % 25, data[0] >> 2 & 1, &rb, end);
    fp_read_set(&B, data[2] % 25, data[0] >> 2 & 1, &rb, end);
    for (i = 0; i < A.n + B.n; i++) {
        int v = rb + i < end ? rb[i] : 0;
        double *p = i < A.n ? A.pts + 2 * i : B.pts + 2 * (i - A.n);
        p[0] = off + (v % 17 - 8) * unit;
        p[1] = off + (v / 17 % 17 - 8) * unit;
    }
    for (i = 0; i < (int)size; i++) h = (h ^ data[i]) * 1099511628211ull;
    pa = fp_polyset(&A), pb = fp_polyset(&B);
    memset(&none, 0, sizeof none);
    bytes = gr_poly_boolean_scratch_bytes(A.n + B.n);
    scratch = (unsigned char *)malloc(bytes);
    FUZZ_CHECK(scratch != NULL, "scratch of %zu bytes", bytes);
    ne = fp_edges(&B, e, fp_edges(&A, e, 0));
    mag = fabs(off) + 9 * unit;
    eps = FP_EPS * unit + FP_EPS_ULPS * DBL_EPSILON * mag;
    tol = FP_AREA_TOL * 256 * unit * unit + FP_AREA_ULPS * DBL_EPSILON * mag * 36 * unit * (double)(ne + ne * ne + 1);

    /* the set identities over the four operations */
    for (i = 0; i < 4; i++) ar[i] = fp_area(&pa, &pb, i, scratch, bytes);
    aa = fp_area(&pa, &none, GR_POLY_UNION, scratch, bytes);
    ab = fp_area(&pb, &none, GR_POLY_UNION, scratch, bytes);
    for (i = 0; i < 4; i++) FUZZ_CHECK(ar[i] >= -tol && ar[i] <= 256 * unit * unit + tol, "op %d area %.17g", i, ar[i]);
    FUZZ_CHECK(fabs(ar[GR_POLY_UNION] + ar[GR_POLY_INTERSECTION] - aa - ab) <= tol,
               "|A u B| %.17g + |A n B| %.17g != |A| %.17g + |B| %.17g", ar[GR_POLY_UNION], ar[GR_POLY_INTERSECTION], aa, ab);
    FUZZ_CHECK(fabs(ar[GR_POLY_DIFFERENCE] - (ar[GR_POLY_UNION] - ab)) <= tol, "|A \\ B| %.17g, |A u B| %.17g, |B| %.17g",
               ar[GR_POLY_DIFFERENCE], ar[GR_POLY_UNION], ab);
    FUZZ_CHECK(fabs(ar[GR_POLY_XOR] - (ar[GR_POLY_UNION] - ar[GR_POLY_INTERSECTION])) <= tol,
               "|A xor B| %.17g, |A u B| %.17g, |A n B| %.17g", ar[GR_POLY_XOR], ar[GR_POLY_UNION], ar[GR_POLY_INTERSECTION]);

    /* the trapezoids of the chosen operation */
    r = gr_poly_boolean(&pa, &pb, (gr_poly_op_t)op, scratch, bytes, NULL, 0, &nt, &area);
    FUZZ_CHECK(r == GR_OK && nt >= 0, "count: %s, %d", gr_result_string(r), nt);
    traps = (double *)malloc(sizeof(double) * 8 * (size_t)(nt + 1));
    FUZZ_CHECK(traps != NULL, "%d trapezoids", nt);
    r = gr_poly_boolean(&pa, &pb, (gr_poly_op_t)op, scratch, bytes, traps, nt, &nt2, &again);
    FUZZ_CHECK(r == GR_OK && nt2 == nt && again == area, "%s: %d trapezoids (%d), area %.17g (%.17g)", gr_result_string(r), nt2,
               nt, again, area);
    FUZZ_CHECK(area == ar[op], "op %d: area %.17g, with the trapezoids %.17g", op, ar[op], area);
    for (i = 0; i < nt; i++) {
        double ta = gr_poly_area(traps + 8 * i, 4);
        FUZZ_CHECK(ta >= -tol, "trapezoid %d of %d: area %.17g", i, nt, ta);
        if (!fp_trap_shape(traps + 8 * i, eps)) fp_print_case(&A, &B, traps, nt, off, unit);
        FUZZ_CHECK(fp_trap_shape(traps + 8 * i, eps), "trapezoid %d of %d is not one", i, nt);
        sum += ta;
    }
    FUZZ_CHECK(fabs(sum - area) <= tol, "%d trapezoids sum to %.17g, the area is %.17g", nt, sum, area);
    for (i = 0; i < FP_SAMPLES; i++) {
        double x, y;
        int want, held = 0, k;
        h = h * 6364136223846793005ull + 1442695040888963407ull;
        x = off + ((double)(h >> 40) / 16777216.0 * 18 - 9) * unit;
        y = off + ((double)(h >> 16 & 0xFFFFFF) / 16777216.0 * 18 - 9) * unit;
        if (!fp_clear(e, ne, x, y, eps)) continue;
        want = fp_in_result(op, fp_in_set(&A, x, y), fp_in_set(&B, x, y));
        for (k = 0; k < nt; k++) held += fp_in_trap(traps + 8 * k, x, y);
        if (held != want) fp_print_case(&A, &B, traps, nt, off, unit);
        FUZZ_CHECK(held == want, "op %d at (%.17g, %.17g): in a %d, in b %d, held by %d of %d trapezoids", op, x, y,
                   fp_in_set(&A, x, y), fp_in_set(&B, x, y), held, nt);
    }

    /* short buffers */
    if (nt > 0) {
        r = gr_poly_boolean(&pa, &pb, (gr_poly_op_t)op, scratch, bytes, traps, nt - 1, &nt2, &again);
        FUZZ_CHECK(r == GR_ERR_BUFFER_TOO_SMALL && nt2 == nt && again == area, "trap_cap %d: %s, count %d, area %.17g", nt - 1,
                   gr_result_string(r), nt2, again);
    }
    if (bytes > 0) {
        r = gr_poly_boolean(&pa, &pb, (gr_poly_op_t)op, scratch, bytes - 1, NULL, 0, NULL, NULL);
        FUZZ_CHECK(r == GR_ERR_BUFFER_TOO_SMALL, "scratch %zu of %zu bytes: %s", bytes - 1, bytes, gr_result_string(r));
    }
    free(traps);
    free(scratch);
    return 0;
}
