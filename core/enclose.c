/* Enclosing counts of shells by Embree rays; see enclose.h. */
#include "enclose.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "validate.h"

/* Samples per shell: spread over its triangles, as model.c samples. */
#define SAMPLES 9

int lam_enclosing_by_rays(lam_model *md, const unsigned char *candidates, int *done, lam_error *err)
{
    *done = 0;
    const lam_mesh *m = &md->mesh;
    /* the offset: well clear of Embree's float32 tolerance, tiny against
     * the model (the validator's inset for its test points) */
    double scale = 0, maxabs = 0;
    for (size_t s = 0; s < md->nshells; s++)
        for (int k = 0; k < 3; k++) {
            double lo = md->shells[s].bbox[k], hi = md->shells[s].bbox[k + 3];
            if (hi - lo > scale) scale = hi - lo;
            if (fabs(lo) > maxabs) maxabs = fabs(lo);
            if (fabs(hi) > maxabs) maxabs = fabs(hi);
        }
    double delta = fmax(1e-5 * scale, 1e3 * FLT_EPSILON * maxabs);
    int *found = malloc((md->nshells + 1) * sizeof *found);
    if (!found) return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory building the model");
    lam_validator *v = NULL;
    lam_error verr;
    lam_error_clear(&verr);
    if (lam_validator_new(md, &v, &verr)) {
        free(found);
        if (verr.code == LAM_ENOMEM) return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "%s", verr.msg);
        return LAM_OK; /* no Embree here: the pairwise test decides */
    }
    int good = 1;
    for (size_t s = 0; s < md->nshells && good; s++) {
        found[s] = 0;
        if (!candidates[s]) continue;
        size_t n = md->shell_first[s + 1] - md->shell_first[s], want = n < SAMPLES ? n : SAMPLES;
        size_t step = n / want, seen = 0;
        int w[SAMPLES], nw = 0;
        for (uint32_t i = md->shell_first[s]; i < md->shell_first[s + 1] && seen < want; i += (uint32_t)step) {
            seen++;
            const uint32_t *t = m->tris + 3 * (size_t)md->shell_tris[i];
            const double *a = m->xyz + 3 * (size_t)t[0], *b = m->xyz + 3 * (size_t)t[1], *c = m->xyz + 3 * (size_t)t[2];
            double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] }, q[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
            double nrm[3] = { u[1] * q[2] - u[2] * q[1], u[2] * q[0] - u[0] * q[2], u[0] * q[1] - u[1] * q[0] };
            double len = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
            if (!(len > 0)) continue;
            double p[3];
            for (int k = 0; k < 3; k++) p[k] = (a[k] + b[k] + c[k]) / 3 + delta * nrm[k] / len;
            int wind;
            lam_error_clear(&verr);
            if (lam_validator_winding(v, p, &wind, &verr) == LAM_OK) w[nw++] = wind;
            else if (verr.code == LAM_ENOMEM) good = 0;
        }
        /* the most frequent answer, if it has a strict majority of the
         * decisive samples (a sample on another shell's surface says
         * nothing) */
        int best = -1, best_count = 0;
        for (int i = 0; i < nw; i++) {
            int count = 0;
            for (int j = 0; j < nw; j++) count += w[j] == w[i];
            if (count > best_count) {
                best_count = count;
                best = w[i];
            }
        }
        if (best < 0 || 2 * best_count <= nw) good = 0;
        found[s] = best;
    }
    lam_validator_free(v);
    if (good) {
        for (size_t s = 0; s < md->nshells; s++)
            if (candidates[s]) md->shells[s].enclosing = found[s];
        *done = 1;
    }
    free(found);
    return LAM_OK;
}
