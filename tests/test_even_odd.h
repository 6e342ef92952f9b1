/* tests/test_even_odd.h — the reference point-in-polygon test of the
   grooves tests: the even-odd rule by crossing number, independent of
   grooves.h. (x, y) is inside the ring of n points at p (x0 y0 x1 y1 ...,
   closed from the last point back to the first) when a ray from it toward
   +x crosses the ring's edges an odd number of times. An edge counts when
   it spans y half-open (one end above y, the other not), so a ray through
   a vertex counts it once, and horizontal edges never; points on the ring
   may fall either way, so callers sample away from edges. A ring of fewer
   than 3 points encloses nothing. */
#ifndef TEST_EVEN_ODD_H
#define TEST_EVEN_ODD_H

static int teo_in_ring(const double *p, int n, double x, double y)
{
    int i, c = 0;
    if (n < 3) return 0;
    for (i = 0; i < n; i++) {
        const double *u = p + 2 * i, *v = p + 2 * ((i + 1) % n);
        if ((u[1] > y) != (v[1] > y) && x < u[0] + (y - u[1]) * (v[0] - u[0]) / (v[1] - u[1])) c = !c;
    }
    return c;
}

#endif
