/* libFuzzer target for frep.h's HyperFun-subset parser (make fuzz).
   Any input must give FR_OK or an error with a position, never a crash,
   a leak or undefined behaviour; accepted models are then evaluated by
   every evaluator and pruned, so the tape they produce is walked too. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#define IV_IMPLEMENTATION
#include "interval.h"
#define FR_IMPLEMENTATION
#include "frep.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fr_tape_t t;
    fr_diag_t d;
    fr_parse_desc_t desc;
    double params[2] = {0.5, -0.25};
    memset(&desc, 0, sizeof desc);
    desc.params = params;
    desc.n_params = 2;
    desc.max_nodes = 1u << 16;
    if (fr_parse((const char *)data, size, &desc, &t, &d) != FR_OK) {
        /* an error always names its place */
        if (d.line < 1 || d.column < 1 || d.message[0] == 0) abort();
        return 0;
    }
    {
        size_t n = fr_scratch_size(&t, FR_EVAL_PRUNE);
        size_t m;
        void *sc;
        fr_instr_t *buf;
        double p[3] = {0.25, -0.5, 0.75}, v, g[3], out[FR_MAX_OUTPUTS];
        iv_t box[3] = {{-1, 1}, {-0.5, 0.5}, {0, 2}}, o;
        iv_affine_t ap[3];
        fr_tape_t pr;
        m = fr_scratch_size(&t, FR_EVAL_AFFINE);
        if (fr_scratch_size(&t, FR_EVAL_GRAD) > m) m = fr_scratch_size(&t, FR_EVAL_GRAD);
        if (n > m) m = n;
        sc = malloc(m);
        buf = (fr_instr_t *)malloc(t.n_code * sizeof(fr_instr_t));
        if (sc && buf) {
            v = fr_eval(&t, p, sc);
            fr_eval_outputs(&t, p, sc, out);
            (void)fr_eval_grad(&t, p, sc, &v, g);
            (void)fr_eval_interval(&t, box, sc, &o);
            ap[0] = iv_affine_from_iv(box[0]);
            ap[1] = iv_affine_from_iv(box[1]);
            ap[2] = iv_affine_from_iv(box[2]);
            (void)fr_eval_affine(&t, ap, sc, ap);
            if (fr_prune(&t, box, sc, buf, t.n_code, &pr, &o) == FR_OK) v = fr_eval(&pr, p, sc);
            (void)v;
        }
        free(sc);
        free(buf);
    }
    fr_tape_free(&t);
    return 0;
}
