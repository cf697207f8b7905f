/* Which shells enclose which; see enclose.h. */
#include "enclose.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "validate.h"

/* Samples per inner shell. */
#define SAMPLES 9

/* Past this many winding-number terms (samples times triangles of the
 * shells around them) the pairwise test gives way to rays: some tens of
 * milliseconds. */
#define PAIRWISE_WORK 4e6

static int oom(lam_error *err)
{
    return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "out of memory building the model");
}

static int bbox_inside(const double *in, const double *out)
{
    for (int j = 0; j < 3; j++)
        if (in[j] < out[j] || in[j + 3] > out[j + 3]) return 0;
    return 1;
}

/* ---- candidate pairs ------------------------------------------------------ */

/* Shells listed by grid cell (cells over more than `wide` cells of the
 * grid go on the list `bigs` instead). */
typedef struct grid {
    double lo[3], size[3];
    int n[3];
    uint32_t *first, *list, *bigs;
    size_t nbig;
} grid;

static int cell_of(const grid *g, int k, double x)
{
    double c = floor((x - g->lo[k]) / g->size[k]);
    return c < 0 ? 0 : c >= g->n[k] ? g->n[k] - 1 : (int)c;
}

static size_t cell_index(const grid *g, int i, int j, int k)
{
    return ((size_t)i * (size_t)g->n[1] + (size_t)j) * (size_t)g->n[2] + (size_t)k;
}

static void grid_free(grid *g)
{
    free(g->first);
    free(g->list);
    free(g->bigs);
}

static int grid_build(const lam_model *md, grid *g)
{
    memset(g, 0, sizeof *g);
    size_t ns = md->nshells;
    int per = (int)ceil(cbrt((double)ns));
    if (per < 1) per = 1;
    if (per > 64) per = 64;
    for (int k = 0; k < 3; k++) {
        double lo = INFINITY, hi = -INFINITY;
        for (size_t s = 0; s < ns; s++) {
            if (md->shells[s].bbox[k] < lo) lo = md->shells[s].bbox[k];
            if (md->shells[s].bbox[k + 3] > hi) hi = md->shells[s].bbox[k + 3];
        }
        g->lo[k] = lo;
        g->n[k] = hi > lo ? per : 1;
        g->size[k] = hi > lo ? (hi - lo) / per : 1;
    }
    size_t ncells = (size_t)g->n[0] * (size_t)g->n[1] * (size_t)g->n[2];
    /* a box over more cells than this goes on the list every shell checks */
    size_t wide = ncells / 8 > 8 ? ncells / 8 : 8;
    int *range = malloc(6 * ns * sizeof *range + 1);
    uint32_t *fill = NULL;
    g->first = calloc(ncells + 1, sizeof *g->first);
    if (!range || !g->first) goto fail;
    for (size_t s = 0; s < ns; s++) {
        int *r = range + 6 * s;
        size_t cells = 1;
        for (int k = 0; k < 3; k++) {
            r[k] = cell_of(g, k, md->shells[s].bbox[k]);
            r[k + 3] = cell_of(g, k, md->shells[s].bbox[k + 3]);
            cells *= (size_t)(r[k + 3] - r[k] + 1);
        }
        if (cells > wide) {
            r[0] = -1; /* big */
            g->nbig++;
            continue;
        }
        for (int i = r[0]; i <= r[3]; i++)
            for (int j = r[1]; j <= r[4]; j++)
                for (int k = r[2]; k <= r[5]; k++) g->first[cell_index(g, i, j, k) + 1]++;
    }
    for (size_t c = 0; c < ncells; c++) g->first[c + 1] += g->first[c];
    g->list = malloc(g->first[ncells] * sizeof *g->list + 1);
    g->bigs = malloc(g->nbig * sizeof *g->bigs + 1);
    fill = malloc((ncells + 1) * sizeof *fill);
    if (!g->list || !g->bigs || !fill) goto fail;
    memcpy(fill, g->first, (ncells + 1) * sizeof *fill);
    g->nbig = 0;
    for (size_t s = 0; s < ns; s++) {
        const int *r = range + 6 * s;
        if (r[0] < 0) {
            g->bigs[g->nbig++] = (uint32_t)s;
            continue;
        }
        for (int i = r[0]; i <= r[3]; i++)
            for (int j = r[1]; j <= r[4]; j++)
                for (int k = r[2]; k <= r[5]; k++) g->list[fill[cell_index(g, i, j, k)]++] = (uint32_t)s;
    }
    free(fill);
    free(range);
    return LAM_OK;
fail:
    free(fill);
    free(range);
    grid_free(g);
    return LAM_ENOMEM;
}

/* The candidates for shell s, in increasing order, one by one: *cursor
 * starts at 0; returns the next o whose box holds s's box, or -1. Both
 * lists hold shells in increasing order and are merged. */
static long next_candidate(const lam_model *md, const grid *g, size_t s, size_t cursor[2])
{
    const double *b = md->shells[s].bbox;
    int ci[3];
    for (int k = 0; k < 3; k++) ci[k] = cell_of(g, k, (b[k] + b[k + 3]) / 2);
    size_t c = cell_index(g, ci[0], ci[1], ci[2]);
    size_t az = g->first[c + 1] - g->first[c];
    const uint32_t *cl = g->list + g->first[c];
    while (cursor[0] < az || cursor[1] < g->nbig) {
        uint32_t o = cursor[1] >= g->nbig || (cursor[0] < az && cl[cursor[0]] < g->bigs[cursor[1]])
                         ? cl[cursor[0]++]
                         : g->bigs[cursor[1]++];
        if (o != s && bbox_inside(b, md->shells[o].bbox)) return (long)o;
    }
    return -1;
}

/* ---- pairwise ---------------------------------------------------------------- */

/* The sample triangles of shell s: up to SAMPLES, spread evenly over its
 * triangles. Returns how many. */
static int samples(const lam_model *md, size_t s, uint32_t tri[SAMPLES])
{
    size_t n = md->shell_first[s + 1] - md->shell_first[s], want = n < SAMPLES ? n : SAMPLES;
    size_t step = want ? n / want : 1;
    for (size_t k = 0; k < want; k++) tri[k] = md->shell_tris[md->shell_first[s] + k * step];
    return (int)want;
}

/* Does shell `outer` enclose shell `inner`? (See enclose.h.) */
static int shell_encloses(const lam_model *md, size_t outer, size_t inner)
{
    const lam_mesh *m = &md->mesh;
    uint32_t tri[SAMPLES];
    int ns = samples(md, inner, tri), in = 0, out = 0;
    for (int k = 0; k < ns; k++) {
        const uint32_t *tv = m->tris + 3 * (size_t)tri[k];
        double c[3];
        for (int j = 0; j < 3; j++)
            c[j] = (m->xyz[3 * (size_t)tv[0] + j] + m->xyz[3 * (size_t)tv[1] + j] + m->xyz[3 * (size_t)tv[2] + j]) / 3.0;
        double w = fabs(lam_model_shell_winding(md, outer, c));
        if (w > 0.75) in++;
        else if (w < 0.25) out++;
    }
    return in > out;
}

/* ---- by rays ------------------------------------------------------------------- */

/* Set enclosing for every shell marked in cand; 1 when all were decided,
 * else 0 with nothing changed, -LAM_ENOMEM when out of memory. */
static int by_rays(lam_model *md, const unsigned char *cand, lam_error *err)
{
    const lam_mesh *m = &md->mesh;
    int *found = malloc((md->nshells + 1) * sizeof *found);
    if (!found) return -oom(err);
    lam_validator *v = NULL;
    lam_error verr;
    lam_error_clear(&verr);
    if (lam_validator_new(md, &v, &verr)) {
        free(found);
        return 0; /* no Embree here: the pairwise test decides */
    }
    /* the offset: the validator's own inset for its test points, well clear
     * of its float32 tolerance and tiny against the model */
    double delta = lam_validator_min_inset(v);
    int good = 1;
    for (size_t s = 0; s < md->nshells && good; s++) {
        if (!cand[s]) continue;
        uint32_t tri[SAMPLES];
        int ns = samples(md, s, tri), w[SAMPLES], nw = 0;
        for (int k = 0; k < ns; k++) {
            const uint32_t *t = m->tris + 3 * (size_t)tri[k];
            const double *a = m->xyz + 3 * (size_t)t[0], *b = m->xyz + 3 * (size_t)t[1], *c = m->xyz + 3 * (size_t)t[2];
            double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] }, q[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
            double nrm[3] = { u[1] * q[2] - u[2] * q[1], u[2] * q[0] - u[0] * q[2], u[0] * q[1] - u[1] * q[0] };
            double len = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
            if (!(len > 0)) continue;
            double pt[3];
            for (int j = 0; j < 3; j++) pt[j] = (a[j] + b[j] + c[j]) / 3 + delta * nrm[j] / len;
            int wind;
            lam_error_clear(&verr);
            if (lam_validator_winding(v, pt, &wind, &verr) == LAM_OK) w[nw++] = wind;
        }
        /* the most frequent answer, with a strict majority of the decisive
         * samples (a sample on another shell's surface says nothing) */
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
    if (good)
        for (size_t s = 0; s < md->nshells; s++)
            if (cand[s]) md->shells[s].enclosing = found[s];
    free(found);
    return good;
}

int lam_count_enclosing(lam_model *md, lam_error *err)
{
    size_t ns = md->nshells;
    for (size_t s = 0; s < ns; s++) md->shells[s].enclosing = 0;
    if (ns < 2) return LAM_OK;
    grid g;
    unsigned char *cand = calloc(ns, 1);
    if (!cand || grid_build(md, &g)) {
        free(cand);
        return oom(err);
    }
    /* the work the pairwise test would do, and who has a candidate at all */
    double work = 0;
    for (size_t s = 0; s < ns; s++) {
        size_t cur[2] = { 0, 0 }, n = md->shells[s].ntris;
        for (long o; (o = next_candidate(md, &g, s, cur)) >= 0;) {
            cand[s] = 1;
            work += (double)(n < SAMPLES ? n : SAMPLES) * (double)md->shells[o].ntris;
        }
    }
    int done = 0;
    if (work > PAIRWISE_WORK) done = by_rays(md, cand, err);
    for (size_t s = 0; s < ns && done == 0; s++) {
        if (!cand[s]) continue;
        size_t cur[2] = { 0, 0 };
        for (long o; (o = next_candidate(md, &g, s, cur)) >= 0;)
            if (shell_encloses(md, (size_t)o, s)) md->shells[s].enclosing++;
    }
    grid_free(&g);
    free(cand);
    return done < 0 ? LAM_ENOMEM : LAM_OK;
}
