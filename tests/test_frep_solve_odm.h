/* tests/test_frep_solve_odm.h -- the quartics of Orellana & De Michele's
   accuracy test (ACM TOMS 46(2) art. 20, 2020, "Algorithm 1010", Table 1),
   shared by tests/test_frep_solve.c and bench/bench_frep_solve.c.

   Source: the authors' driver, cridemichel/quarticpp accuracytest.cpp and
   cridemichel/quartic_C Drivers/accuracytest.c ("caso" 1-24): cases 1-13 are
   Flocke's (2015), 14-18 Strobach's (2010), 19-24 the authors'. Cases 1-22
   are given by their roots, the coefficients being rounded once from the
   exact product (here in __float128, as the authors do in 200-digit
   arithmetic); cases 23 and 24 by their coefficients. The authors' user
   manual (quartic_C USER_MANUAL) names 26 cases, the last two "added in the
   previous and present remark" (De Michele, remarks on Algorithm 1010, about
   the d2 = 0 branch); their coefficients are in no published driver we could
   find, so they are not here (see odm_remark_family in the test for the
   family the authors' search driver draws them from). Case 15's small root
   is 2^-48 as in quarticpp (quartic_C used 1e-15). */
#ifndef FILIGREE_TEST_FREP_SOLVE_ODM_H
#define FILIGREE_TEST_FREP_SOLVE_ODM_H

#include "test_frep_solve_ref.h"

#define ODM_NCASES 24

/* Case k (1..ODM_NCASES): c[0..4] (increasing degree, leading 1). Returns 1
   when the doubles are exactly the coefficients of the listed roots (all
   real), which are then in exact[0..3]: a quadruple root like (x - 1000)^4
   is beyond the Aberth oracle, so such cases are checked against the exact
   roots. Returns 0 otherwise (use the oracle on c). */
static int odm_case(int k, double *c, __float128 *exact)
{
    /* roots (re, im) of cases 1-22 */
    static const double R[22][4][2] = {
        {{1e9, 0}, {1e6, 0}, {1e3, 0}, {1, 0}},
        {{2.003, 0}, {2.002, 0}, {2.001, 0}, {2, 0}},
        {{1e53, 0}, {1e50, 0}, {1e49, 0}, {1e47, 0}},
        {{1e14, 0}, {2, 0}, {1, 0}, {-1, 0}},
        {{-2e7, 0}, {1e7, 0}, {1, 0}, {-1, 0}},
        {{1e7, 0}, {-1e6, 0}, {1, 1}, {1, -1}},
        {{-7, 0}, {-4, 0}, {-1e6, 1e5}, {-1e6, -1e5}},
        {{1e8, 0}, {11, 0}, {1e3, 1}, {1e3, -1}},
        {{1e7, 1e6}, {1e7, -1e6}, {1, 2}, {1, -2}},
        {{1e4, 3}, {1e4, -3}, {-7, 1e3}, {-7, -1e3}},
        {{1.001, 4.998}, {1.001, -4.998}, {1.000, 5.001}, {1.000, -5.001}},
        {{1e3, 3}, {1e3, -3}, {1e3, 1}, {1e3, -1}},
        {{2, 1e4}, {2, -1e4}, {1, 1e3}, {1, -1e3}},
        {{1000, 0}, {1000, 0}, {1000, 0}, {1000, 0}},
        {{1000, 0}, {1000, 0}, {1000, 0}, {3.552713678800501e-15, 0}}, /* 2^-48 */
        {{1e16, 1e7}, {1e16, -1e7}, {1, 0.1}, {1, -0.1}},
        {{10000, 0}, {10001, 0}, {10010, 0}, {10100, 0}},
        {{4e5, 3e2}, {4e5, -3e2}, {3e4, 7e3}, {3e4, -7e3}},
        {{1e44, 0}, {1e30, 0}, {1e30, 0}, {1, 0}},
        {{1e14, 0}, {1e7, 0}, {1e7, 0}, {1, 0}},
        {{1e15, 0}, {1e7, 0}, {1e7, 0}, {1, 0}},
        {{1e154, 0}, {1e152, 0}, {10, 0}, {1, 0}},
    };
    if (k <= 22) {
        __float128 re[4], pairs[2][2], q[5] = {1, 0, 0, 0, 0};
        int nr = 0, np = 0, i, j, exact_ok = 1;
        for (i = 0; i < 4; i++) {
            if (R[k - 1][i][1] == 0) re[nr++] = R[k - 1][i][0];
            else if (R[k - 1][i][1] > 0) { pairs[np][0] = R[k - 1][i][0]; pairs[np][1] = R[k - 1][i][1]; np++; }
        }
        ref_coeffs_from_roots(re, nr, (const __float128(*)[2])pairs, np, 1, c);
        if (np > 0) return 0;
        for (i = 0; i < 4; i++) { /* the monic product in quad, compared with the doubles */
            __float128 z = R[k - 1][i][0];
            for (j = i + 1; j > 0; j--) q[j] = q[j - 1] - z * q[j];
            q[0] = -z * q[0];
        }
        for (i = 0; i < 5; i++) exact_ok = exact_ok && (__float128)c[i] == q[i];
        if (!exact_ok) return 0;
        for (i = 0; i < 4; i++) exact[i] = R[k - 1][i][0];
        return 1;
    } else if (k == 23) {
        c[4] = 1; c[3] = 1; c[2] = 1; c[1] = 0.375; c[0] = 0.001;
    } else {
        __float128 S = 1e30Q;
        c[4] = 1;
        c[3] = (double)(-(1 + 1 / S));
        c[2] = (double)(1 / S - S * S);
        c[1] = (double)(S * S + S);
        c[0] = (double)(-S);
    }
    return 0;
}

#endif
