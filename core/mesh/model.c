/* The model object: its winding numbers, size and freeing. It is built in
 * model_build.c. See model.h. */
#include "model.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define PI 3.14159265358979323846

double lam_model_shell_winding(const lam_model *md, size_t s, const double p[3])
{
    const lam_mesh *m = &md->mesh;
    double sum = 0;
    for (uint32_t i = md->shell_first[s]; i < md->shell_first[s + 1]; i++) {
        size_t t = md->shell_tris[i];
        double a[3], b[3], c[3];
        const double *pa = m->xyz + 3 * (size_t)m->tris[3 * t];
        const double *pb = m->xyz + 3 * (size_t)m->tris[3 * t + 1];
        const double *pc = m->xyz + 3 * (size_t)m->tris[3 * t + 2];
        for (int j = 0; j < 3; j++) {
            a[j] = pa[j] - p[j];
            b[j] = pb[j] - p[j];
            c[j] = pc[j] - p[j];
        }
        double la = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
        double lb = sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
        double lc = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        double det = a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
                     a[2] * (b[0] * c[1] - b[1] * c[0]);
        double ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        double bc = b[0] * c[0] + b[1] * c[1] + b[2] * c[2];
        double ca = c[0] * a[0] + c[1] * a[1] + c[2] * a[2];
        double den = la * lb * lc + ab * lc + bc * la + ca * lb;
        /* Van Oosterom and Strackee's solid angle of a triangle. */
        sum += 2.0 * atan2(det, den);
    }
    return sum / (4.0 * PI);
}

void lam_model_free(lam_model *md)
{
    if (!md) return;
    lam_mesh_free(&md->mesh);
    free(md->edges.v);
    free(md->edges.first);
    free(md->edges.tris);
    free(md->edges.tri_edge);
    free(md->tri_shell);
    free(md->shell_first);
    free(md->shell_tris);
    free(md->shells);
    free(md->path);
    free(md);
}

size_t lam_model_bytes(const lam_model *m, size_t parts[3])
{
    const lam_mesh *h = &m->mesh;
    size_t p[3];
    p[0] = h->nverts * 3 * sizeof *h->xyz + h->ntris * 3 * sizeof *h->tris +
           (h->tri_face ? h->ntris * sizeof *h->tri_face : 0) + h->nfaces * sizeof *h->faces +
           h->nwire_segs * 2 * sizeof *h->wires + h->strings_len;
    const lam_edges *e = &m->edges;
    size_t t = h->ntris;
    p[1] = e->v ? e->n * 2 * sizeof *e->v + (e->n + 1) * sizeof *e->first + 3 * t * sizeof *e->tri_edge +
                      (e->first ? e->first[e->n] : 0) * sizeof *e->tris
                : 0;
    p[2] = (m->tri_shell ? t * sizeof *m->tri_shell : 0) + (m->shell_tris ? t * sizeof *m->shell_tris : 0) +
           (m->shell_first ? (m->nshells + 1) * sizeof *m->shell_first : 0) + m->nshells * sizeof *m->shells;
    if (parts) memcpy(parts, p, sizeof p);
    return p[0] + p[1] + p[2];
}
