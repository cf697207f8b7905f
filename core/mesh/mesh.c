#include "mesh.h"

#include <stdio.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "grow.h"
#include "hugemem.h"
#include "prefetch.h"
#include "weld_hash.h"

void lam_mesh_init(lam_mesh *m)
{
    memset(m, 0, sizeof *m);
}

void lam_mesh_free(lam_mesh *m)
{
    if (!m) return;
    free(m->xyz);
    free(m->tris);
    free(m->tri_face);
    free(m->faces);
    free(m->wires);
    free(m->strings);
    lam_mesh_init(m);
}

static int grow_slow(void **p, size_t *cap, size_t need, size_t elem, lam_error *err)
{
    if (!lam_grow_cap(*cap, need, 16, elem)) return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "mesh too large");
    void *np = lam_grow(*p, cap, need, elem, 16);
    if (!np) return lam_error_nomem(err, NULL);
    *p = np;
    lam_huge_hint(np, *cap * elem); /* the mesh is read at random: huge pages */
    return LAM_OK;
}

/* Grow *p (elements of size elem) so it holds at least need elements: the
 * test inline (once per vertex and face), the growth out of line. */
static inline int grow(void **p, size_t *cap, size_t need, size_t elem, lam_error *err)
{
    return need <= *cap ? LAM_OK : grow_slow(p, cap, need, elem, err);
}

/* Triangles and their face ids grow together so they never disagree. */
static int grow_tris(lam_mesh *m, size_t need, lam_error *err)
{
    if (need <= m->cap_tris) return LAM_OK;
    size_t cap = m->cap_tris;
    int rc = grow((void **)&m->tris, &cap, need, 3 * sizeof *m->tris, err);
    if (rc) return rc;
    if (m->nfaces || m->tri_face) {
        void *np = lam_realloc_n(m->tri_face, cap, sizeof *m->tri_face);
        if (!np) return lam_error_nomem(err, NULL);
        m->tri_face = np;
    }
    m->cap_tris = cap;
    return LAM_OK;
}

int lam_mesh_reserve(lam_mesh *m, size_t nverts, size_t ntris, lam_error *err)
{
    if (nverts > UINT32_MAX - m->nverts || ntris > UINT32_MAX - m->ntris)
        return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "mesh too large (more than 2^32 elements)");
    int rc = grow((void **)&m->xyz, &m->cap_verts, m->nverts + nverts, 3 * sizeof *m->xyz, err);
    if (rc) return rc;
    return grow_tris(m, m->ntris + ntris, err);
}

const char *lam_coord_problem(double x)
{
    if (!isfinite(x)) return "is not a finite number";
    if (fabs(x) > LAM_COORD_MAX)
        return "is beyond 1e50 in magnitude: the model would span more than a double can measure";
    return NULL;
}

int lam_mesh_add_vertex(lam_mesh *m, double x, double y, double z,
                        uint32_t *idx, lam_error *err)
{
    const double in[3] = { x, y, z };
    for (int k = 0; k < 3; k++)
        if (lam_coord_problem(in[k]))
            return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "vertex %c coordinate %g %s", "xyz"[k], in[k],
                                 lam_coord_problem(in[k]));
    if (m->nverts >= UINT32_MAX - 1)
        return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "too many vertices");
    int rc = grow((void **)&m->xyz, &m->cap_verts, m->nverts + 1, 3 * sizeof *m->xyz, err);
    if (rc) return rc;
    double *p = m->xyz + 3 * m->nverts;
    p[0] = x;
    p[1] = y;
    p[2] = z;
    if (idx) *idx = (uint32_t)m->nverts;
    m->nverts++;
    return LAM_OK;
}

static int add_string(lam_mesh *m, const char *s, uint32_t *off, lam_error *err)
{
    if (!s) {
        *off = LAM_NO_NAME;
        return LAM_OK;
    }
    size_t n = strlen(s) + 1;
    if (m->strings_len + n >= UINT32_MAX)
        return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "too many names");
    int rc = grow((void **)&m->strings, &m->strings_cap, m->strings_len + n, 1, err);
    if (rc) return rc;
    memcpy(m->strings + m->strings_len, s, n);
    *off = (uint32_t)m->strings_len;
    m->strings_len += n;
    return LAM_OK;
}

int lam_mesh_add_face(lam_mesh *m, const char *name, const char *file,
                      long line, long column, uint32_t *face, lam_error *err)
{
    if (m->nfaces == 0 && m->ntris > 0 && !m->tri_face)
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0,
                             "face records added to a mesh built without them");
    if (m->nfaces >= UINT32_MAX - 1)
        return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "too many faces");
    int rc = grow((void **)&m->faces, &m->cap_faces, m->nfaces + 1, sizeof *m->faces, err);
    if (rc) return rc;
    if (!m->tri_face && m->cap_tris) {
        m->tri_face = malloc(m->cap_tris * sizeof *m->tri_face);
        if (!m->tri_face) return lam_error_nomem(err, NULL);
    }
    lam_face_src *f = &m->faces[m->nfaces];
    /* The file name repeats for every face: share it with the previous face. */
    if (file && m->nfaces > 0 && m->faces[m->nfaces - 1].file != LAM_NO_NAME &&
        strcmp(m->strings + m->faces[m->nfaces - 1].file, file) == 0) {
        f->file = m->faces[m->nfaces - 1].file;
    } else if ((rc = add_string(m, file, &f->file, err))) {
        return rc;
    }
    if ((rc = add_string(m, name, &f->name, err))) return rc;
    f->line = line > 0 && line < (long)UINT32_MAX ? (uint32_t)line : 0;
    f->column = column > 0 && column < (long)UINT32_MAX ? (uint32_t)column : 0;
    if (face) *face = (uint32_t)m->nfaces;
    m->nfaces++;
    return LAM_OK;
}

int lam_mesh_add_tri(lam_mesh *m, uint32_t a, uint32_t b, uint32_t c,
                     uint32_t face, lam_error *err)
{
    if (a >= m->nverts || b >= m->nverts || c >= m->nverts)
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "triangle names a vertex that does not exist");
    if (m->nfaces ? face >= m->nfaces : face != LAM_NO_NAME)
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "triangle names a face that does not exist");
    if (m->ntris >= UINT32_MAX - 1)
        return lam_error_set(err, LAM_ENOMEM, NULL, 0, 0, "too many triangles");
    int rc = grow_tris(m, m->ntris + 1, err);
    if (rc) return rc;
    uint32_t *t = m->tris + 3 * m->ntris;
    t[0] = a;
    t[1] = b;
    t[2] = c;
    if (m->tri_face) m->tri_face[m->ntris] = face;
    m->ntris++;
    return LAM_OK;
}

int lam_mesh_add_wire_seg(lam_mesh *m, uint32_t a, uint32_t b, lam_error *err)
{
    if (a >= m->nverts || b >= m->nverts)
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "wire names a vertex that does not exist");
    int rc = grow((void **)&m->wires, &m->cap_wire_segs, m->nwire_segs + 1, 2 * sizeof *m->wires, err);
    if (rc) return rc;
    m->wires[2 * m->nwire_segs] = a;
    m->wires[2 * m->nwire_segs + 1] = b;
    m->nwire_segs++;
    return LAM_OK;
}

/* ---- welding ---------------------------------------------------------- */

int lam_mesh_weld(lam_mesh *m, lam_error *err)
{
    size_t n = m->nverts;
    if (n == 0 || m->welded) return LAM_OK;
    /* used[v]: referenced by a triangle or wire; only those are kept. */
    uint32_t *remap = malloc(n * sizeof *remap);
    size_t cap = 16;
    while (cap < 2 * n) cap *= 2;
    uint32_t *table = malloc(cap * sizeof *table);
    if (!remap || !table) {
        free(remap);
        free(table);
        return lam_error_nomem(err, "welding vertices");
    }
    const uint32_t unused = UINT32_MAX;
    for (size_t v = 0; v < n; v++) remap[v] = unused;
    for (size_t i = 0; i < 3 * m->ntris; i++) remap[m->tris[i]] = 0;
    for (size_t i = 0; i < 2 * m->nwire_segs; i++) remap[m->wires[i]] = 0;
    memset(table, 0xff, cap * sizeof *table);

    /* Compact in first-use order of the original numbering, so the result
     * does not depend on hashing. */
    size_t out = 0;
    for (size_t v = 0; v < n; v++) {
        if (remap[v] == unused) continue;
        const double *p = m->xyz + 3 * v;
        size_t h = (size_t)lam_weld_hash(p) & (cap - 1);
        for (;;) {
            uint32_t slot = table[h];
            if (slot == unused) {
                table[h] = (uint32_t)out;
                double *q = m->xyz + 3 * out;
                q[0] = p[0] + 0.0;
                q[1] = p[1] + 0.0;
                q[2] = p[2] + 0.0;
                remap[v] = (uint32_t)out++;
                break;
            }
            if (lam_weld_same(m->xyz + 3 * (size_t)slot, p)) {
                remap[v] = slot;
                break;
            }
            h = (h + 1) & (cap - 1);
        }
    }
    for (size_t i = 0; i < 3 * m->ntris; i++) m->tris[i] = remap[m->tris[i]];
    for (size_t i = 0; i < 2 * m->nwire_segs; i++) m->wires[i] = remap[m->wires[i]];
    m->nverts = out;
    free(remap);
    free(table);
    return LAM_OK;
}

void lam_welder_init(lam_welder *w)
{
    memset(w, 0, sizeof *w);
}

void lam_welder_free(lam_welder *w)
{
    free(w->table);
    free(w->recent);
    lam_welder_init(w);
}

/* Slots hold the hash's high half beside the vertex index, so a probe
 * touches the vertex's coordinates only when the hashes agree. */
#define SLOT_EMPTY UINT64_MAX

static void welder_put(lam_welder *w, uint64_t h, uint32_t v)
{
    size_t i = (size_t)h & (w->cap - 1);
    while (w->table[i] != SLOT_EMPTY) i = (i + 1) & (w->cap - 1);
    w->table[i] = (h & 0xffffffff00000000ull) | v;
}

int lam_welder_reserve(lam_welder *w, const lam_mesh *m, size_t n, lam_error *err)
{
    size_t cap = w->cap ? w->cap : 1024;
    while (cap < 2 * n) cap *= 2;
    if (cap == w->cap) return LAM_OK;
    uint64_t *nt = lam_big_malloc(cap * sizeof *nt);
    if (!nt) return lam_error_nomem(err, "welding vertices");
    memset(nt, 0xff, cap * sizeof *nt);
    uint64_t *old = w->table;
    size_t oldcap = w->cap;
    w->table = nt;
    w->cap = cap;
    for (size_t i = 0; i < oldcap; i++)
        if (old[i] != SLOT_EMPTY) {
            uint32_t v = (uint32_t)old[i];
            welder_put(w, lam_weld_hash(m->xyz + 3 * (size_t)v), v);
        }
    free(old);
    return LAM_OK;
}

void lam_welder_prefetch(const lam_welder *w, double x, double y, double z)
{
    if (!w->cap) return;
    double p[3] = { x + 0.0, y + 0.0, z + 0.0 };
    uint64_t h = lam_weld_hash(p);
    LAM_PREFETCH(w->table + ((size_t)h & (w->cap - 1)));
}

int lam_mesh_add_vertex_welded(lam_mesh *m, lam_welder *w, double x, double y, double z,
                               uint32_t *idx, lam_error *err)
{
    if (2 * (w->count + 1) > w->cap) {
        int rc = lam_welder_reserve(w, m, w->count + 1 > 512 ? 2 * w->count : 512, err);
        if (rc) return rc;
    }
    if (!w->recent) {
        w->recent = malloc(LAM_WELDER_RECENT * sizeof *w->recent);
        if (!w->recent) return lam_error_nomem(err, "welding vertices");
        for (size_t k = 0; k < LAM_WELDER_RECENT; k++) w->recent[k].v = UINT32_MAX;
    }
    double p[3] = { x + 0.0, y + 0.0, z + 0.0 };
    uint64_t h = lam_weld_hash(p), tag = h & 0xffffffff00000000ull;
    size_t r = (size_t)(h >> 20) & (LAM_WELDER_RECENT - 1);
    if (w->recent[r].v != UINT32_MAX && w->recent[r].h == h && lam_weld_same(m->xyz + 3 * (size_t)w->recent[r].v, p)) {
        *idx = w->recent[r].v;
        return LAM_OK;
    }
    size_t i = (size_t)h & (w->cap - 1);
    for (;;) {
        uint64_t slot = w->table[i];
        if (slot == SLOT_EMPTY) break;
        if ((slot & 0xffffffff00000000ull) == tag && lam_weld_same(m->xyz + 3 * (size_t)(uint32_t)slot, p)) {
            *idx = (uint32_t)slot;
            w->recent[r].h = h;
            w->recent[r].v = *idx;
            return LAM_OK;
        }
        i = (i + 1) & (w->cap - 1);
    }
    int rc = lam_mesh_add_vertex(m, p[0], p[1], p[2], idx, err);
    if (rc) return rc;
    w->table[i] = tag | *idx;
    w->count++;
    w->recent[r].h = h;
    w->recent[r].v = *idx;
    return LAM_OK;
}

const char *lam_mesh_string(const lam_mesh *m, uint32_t offset)
{
    if (offset == LAM_NO_NAME || offset >= m->strings_len) return NULL;
    return m->strings + offset;
}

const char *lam_mesh_describe_tri(const lam_mesh *m, size_t t, char *buf, size_t size)
{
    if (!m->tri_face || t >= m->ntris || m->tri_face[t] >= m->nfaces) {
        snprintf(buf, size, "facet %zu", t + 1);
        return buf;
    }
    const lam_face_src *f = &m->faces[m->tri_face[t]];
    const char *name = lam_mesh_string(m, f->name);
    const char *file = lam_mesh_string(m, f->file);
    char where[600] = "";
    if (file && f->line)
        snprintf(where, sizeof where, " (%s:%u:%u)", file, f->line, f->column ? f->column : 1);
    else if (file)
        snprintf(where, sizeof where, " (%s)", file);
    if (name)
        snprintf(buf, size, "face '%s'%s", name, where);
    else
        snprintf(buf, size, "face%s", where);
    return buf;
}

double lam_tri_area2(const double *a, const double *b, const double *c, int *degenerate)
{
    double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    double n[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0] };
    *degenerate = n[0] == 0 && n[1] == 0 && n[2] == 0;
    return sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

int lam_mesh_copy(const lam_mesh *m, lam_mesh *out, lam_error *err)
{
    lam_mesh_init(out);
    out->xyz = malloc(3 * m->nverts * sizeof *out->xyz + 1);
    out->tris = malloc(3 * m->ntris * sizeof *out->tris + 1);
    out->tri_face = m->tri_face ? malloc(m->ntris * sizeof *out->tri_face + 1) : NULL;
    out->faces = malloc(m->nfaces * sizeof *out->faces + 1);
    out->wires = malloc(2 * m->nwire_segs * sizeof *out->wires + 1);
    out->strings = malloc(m->strings_len + 1);
    if (!out->xyz || !out->tris || (m->tri_face && !out->tri_face) || !out->faces || !out->wires || !out->strings) {
        lam_mesh_free(out);
        return lam_error_nomem(err, "copying the mesh");
    }
    /* an empty array may be NULL, which memcpy may not be given */
    if (m->nverts) memcpy(out->xyz, m->xyz, 3 * m->nverts * sizeof *out->xyz);
    if (m->ntris) memcpy(out->tris, m->tris, 3 * m->ntris * sizeof *out->tris);
    if (m->tri_face && m->ntris) memcpy(out->tri_face, m->tri_face, m->ntris * sizeof *out->tri_face);
    if (m->nfaces) memcpy(out->faces, m->faces, m->nfaces * sizeof *out->faces);
    if (m->nwire_segs) memcpy(out->wires, m->wires, 2 * m->nwire_segs * sizeof *out->wires);
    if (m->strings_len) memcpy(out->strings, m->strings, m->strings_len);
    out->nverts = out->cap_verts = m->nverts;
    out->ntris = out->cap_tris = m->ntris;
    out->nfaces = out->cap_faces = m->nfaces;
    out->nwire_segs = out->cap_wire_segs = m->nwire_segs;
    out->nwires = m->nwires;
    out->strings_len = out->strings_cap = m->strings_len;
    out->welded = m->welded;
    return LAM_OK;
}
