#include "sls.h"

#include <math.h>
#include <string.h>

#include "fmt.h"

/* Six decimals without "-0.000000". */
static double tidy(double x)
{
    return fabs(x) < 5e-7 ? 0.0 : x;
}

int lam_sls_write_layer(lam_writer *w, const lam_layer *L, const lam_frame *f, size_t *blocks)
{
    int rc = LAM_OK;
    for (size_t i = 0; i < L->ncontours && !rc; i++) {
        const lam_contour *c = &L->contours[i];
        if ((*blocks)++) lam_writer_write(w, "\n", 1);
        lam_writer_printf(w, "contour %.6f\nloop %zu\n", tidy(L->cut), c->n);
        for (size_t k = 0; k < c->n; k++) {
            double p[3];
            lam_frame_to_model(f, L->uv[2 * (c->first + k)], L->uv[2 * (c->first + k) + 1], L->cut, p);
            char line[3 * LAM_FMT_MAX + 4];
            size_t len = 0;
            for (int j = 0; j < 3; j++) {
                len += lam_fmt_fixed(line + len, tidy(p[j]), 6);
                line[len++] = j < 2 ? ' ' : '\n';
            }
            lam_writer_write(w, line, len);
        }
        rc = lam_writer_printf(w, "endloop\nendcontour\n");
    }
    return rc;
}
