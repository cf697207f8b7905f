/* Orders and output: a block's segments to vectors in the layer frame,
 * short ones dropped, meander or unidirectional along the lines, greedy
 * by nearest end (hatch.h). */
#include <string.h>

#include "hatch_internal.h"

int lam_hatch_emit(hatcher *h, const seg *segs, size_t n, const lam_scan *sc, int type, double angle, double c,
                   double s, double d, lam_hatches *out)
{
    int rc = lam_hatches_add_block(out, type, angle);
    if (rc) return rc;
    size_t first = out->nv;
    long line = 0, prev_k = 0;
    int have_prev = 0;
    /* meander: lines alternate (counting lines that have vectors); within a
     * reversed line its pieces run backwards too */
    for (size_t i = 0; i < n;) {
        size_t j = i;
        while (j < n && segs[j].k == segs[i].k) j++;
        size_t kept = 0;
        for (size_t q = i; q < j; q++) kept += segs[q].x1 - segs[q].x0 >= sc->min_vector;
        if (kept) {
            if (have_prev && segs[i].k != prev_k) line++;
            have_prev = 1;
            prev_k = segs[i].k;
            int back = sc->order == LAM_ORDER_MEANDER && (line & 1);
            for (size_t t = 0; t < j - i; t++) {
                const seg *p = &segs[back ? j - 1 - t : i + t];
                if (p->x1 - p->x0 < sc->min_vector) continue;
                double y = (p->k + 0.5) * d;
                double a = back ? p->x1 : p->x0, b = back ? p->x0 : p->x1;
                if (h->budget == 0) return LAM_EUSAGE;
                h->budget--;
                if ((rc = lam_hatches_add(out, a * c - y * s, a * s + y * c, b * c - y * s, b * s + y * c)))
                    return rc;
            }
        }
        i = j;
    }
    if (sc->order == LAM_ORDER_GREEDY && out->nv - first > 2) {
        /* nearest next end, from the first vector */
        double *v = out->v + 4 * first;
        size_t m = out->nv - first;
        for (size_t i = 1; i < m; i++) {
            double px = v[4 * (i - 1) + 2], py = v[4 * (i - 1) + 3];
            size_t best = i;
            int flip = 0;
            double bd = INFINITY;
            for (size_t j = i; j < m; j++) {
                double *q = v + 4 * j;
                double d0 = (q[0] - px) * (q[0] - px) + (q[1] - py) * (q[1] - py);
                double d1 = (q[2] - px) * (q[2] - px) + (q[3] - py) * (q[3] - py);
                if (d0 < bd) bd = d0, best = j, flip = 0;
                if (d1 < bd) bd = d1, best = j, flip = 1;
            }
            double t[4];
            memcpy(t, v + 4 * best, sizeof t);
            memmove(v + 4 * (i + 1), v + 4 * i, (best - i) * 4 * sizeof *v);
            if (flip) v[4 * i] = t[2], v[4 * i + 1] = t[3], v[4 * i + 2] = t[0], v[4 * i + 3] = t[1];
            else memcpy(v + 4 * i, t, sizeof t);
        }
    }
    if (out->blocks[out->nblocks - 1].n == 0) out->nblocks--; /* nothing left in it */
    return LAM_OK;
}
