/* Writing a model's mesh (mesh_write.h): binary STL and Wavefront OBJ.
 *
 * Both stream: facets and lines are put together in a small buffer of
 * this file and handed to the writer a buffer at a time, so a mesh of
 * any size takes no more memory than that buffer (and, for OBJ, one index
 * per vertex). Numbers are written byte by byte, little-endian, never by
 * copying a struct: the file is the same on every host. */
#include "mesh_write.h"
#include "dialect_template.h"
#include "fmt.h"
#include "version.h"

#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

int lam_mesh_format_for(const char *path)
{
    size_t n = strlen(path);
    return n >= 4 && strcasecmp(path + n - 4, ".obj") == 0 ? LAM_MESH_OBJ : LAM_MESH_STL;
}

/* ---- a chunk buffer in front of the writer -------------------------------- */

#define CHUNK 32768

typedef struct chunk {
    lam_writer *w;
    unsigned char b[CHUNK];
    size_t n;
} chunk;

/* Hand what is buffered to the writer; LAM_OK or the writer's sticky code. */
static int flush(chunk *c)
{
    int rc = lam_writer_write(c->w, c->b, c->n);
    c->n = 0;
    return rc;
}

/* Room for `need` more bytes (need <= CHUNK), flushing first when short. */
static int room(chunk *c, size_t need)
{
    return c->n + need > CHUNK ? flush(c) : LAM_OK;
}

static void put_u16(chunk *c, unsigned v)
{
    c->b[c->n++] = (unsigned char)(v & 0xff);
    c->b[c->n++] = (unsigned char)(v >> 8 & 0xff);
}

static void put_u32(chunk *c, uint32_t v)
{
    for (int i = 0; i < 4; i++) c->b[c->n++] = (unsigned char)(v >> (8 * i) & 0xff);
}

/* IEEE 754 single as its bits (float is binary32 on every platform lamina
 * builds on: static_assert below), little-endian. */
_Static_assert(sizeof(float) == 4 && FLT_MANT_DIG == 24, "float must be IEEE 754 binary32");
static void put_f32(chunk *c, float f)
{
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    put_u32(c, u);
}

/* The source's name for a header or comment: the path as given, control
 * characters (a newline would end an OBJ comment) shown as '?'. */
static void source_name(const lam_model *md, char *buf, size_t size)
{
    const char *p = md->path ? md->path : "";
    size_t k = 0;
    for (; *p && k + 1 < size; p++) buf[k++] = (unsigned char)*p < 0x20 || *p == 0x7f ? '?' : *p;
    buf[k] = '\0';
}

/* ---- binary STL ------------------------------------------------------------ */

/* A triangle's unit normal from its vertices (in double: the float
 * corners would lose the direction of a thin facet), or 0 for no area. */
static void unit_normal(const double *a, const double *b, const double *c, float n[3])
{
    double u[3] = { b[0] - a[0], b[1] - a[1], b[2] - a[2] };
    double v[3] = { c[0] - a[0], c[1] - a[1], c[2] - a[2] };
    double x[3] = { u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0] };
    /* scaled by the largest component first: |x|^2 of a tiny or huge
     * facet would underflow or overflow */
    double m = fmax(fabs(x[0]), fmax(fabs(x[1]), fabs(x[2])));
    if (!(m > 0) || !isfinite(m)) {
        n[0] = n[1] = n[2] = 0.0f;
        return;
    }
    for (int i = 0; i < 3; i++) x[i] /= m;
    double len = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
    for (int i = 0; i < 3; i++) n[i] = (float)(x[i] / len);
}

/* Every corner fits a float32 (|x| <= FLT_MAX; converting a larger double
 * to float is undefined): else LAM_EINVAL, before a byte is written. */
static int check_float_range(const lam_mesh *m, lam_error *err)
{
    for (size_t t = 0; t < 3 * m->ntris; t++) {
        const double *p = m->xyz + 3 * (size_t)m->tris[t];
        for (int j = 0; j < 3; j++)
            if (!(fabs(p[j]) <= FLT_MAX))
                return lam_error_set(err, LAM_EINVAL, NULL, 0, 0,
                                     "vertex coordinate %s does not fit the float32 numbers of binary STL "
                                     "(at most %g): write OBJ (a name ending in .obj) instead",
                                     LAM_NUM(p[j]), (double)FLT_MAX);
    }
    return LAM_OK;
}

static int write_stl(const lam_model *md, chunk *c, lam_error *err)
{
    const lam_mesh *m = &md->mesh;
    if (m->ntris > UINT32_MAX)
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0,
                             "%zu facets do not fit binary STL (at most 4294967295): write OBJ instead", m->ntris);
    int rc = check_float_range(m, err);
    if (rc) return rc;
    /* the header: lamina and the source, padded with NULs; never "solid"
     * first, which readers take for ASCII STL */
    static const char lead[] = "lamina " LAMINA_VERSION " binary STL of ";
    char name[80];
    source_name(md, name, sizeof name);
    memset(c->b, 0, 80);
    memcpy(c->b, lead, sizeof lead - 1);
    size_t len = strlen(name), fit = 80 - (sizeof lead - 1);
    memcpy(c->b + sizeof lead - 1, name, len < fit ? len : fit);
    c->n = 80;
    put_u32(c, (uint32_t)m->ntris);
    for (size_t t = 0; t < m->ntris; t++) {
        if ((rc = room(c, 50))) return rc;
        const double *p[3];
        for (int j = 0; j < 3; j++) p[j] = m->xyz + 3 * (size_t)m->tris[3 * t + j];
        float n[3];
        unit_normal(p[0], p[1], p[2], n);
        for (int j = 0; j < 3; j++) put_f32(c, n[j]);
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 3; j++) put_f32(c, (float)p[k][j]);
        put_u16(c, 0);
    }
    return flush(c);
}

/* ---- Wavefront OBJ ---------------------------------------------------------- */

static void put_text(chunk *c, const char *s, size_t n)
{
    memcpy(c->b + c->n, s, n);
    c->n += n;
}

/* "v X Y Z\n" with the shortest numbers that read back as the doubles
 * (lam_dialect_number: lamina's one such printer, as the programs and
 * the JSON have them). */
static int put_vertex(chunk *c, const double *p)
{
    int rc = room(c, 3 * LAM_FMT_MAX + 8);
    if (rc) return rc;
    put_text(c, "v", 1);
    for (int j = 0; j < 3; j++) {
        char num[LAM_FMT_MAX];
        size_t n = lam_dialect_number(num, p[j]);
        put_text(c, " ", 1);
        put_text(c, num, n);
    }
    put_text(c, "\n", 1);
    return LAM_OK;
}

/* Decimal digits of v into s (no NUL); returns the count. */
static size_t put_index(char *s, uint32_t v)
{
    char tmp[16];
    size_t n = 0;
    do tmp[n++] = (char)('0' + v % 10), v /= 10;
    while (v);
    for (size_t i = 0; i < n; i++) s[i] = tmp[n - 1 - i];
    return n;
}

/* The vertices the triangles use, numbered from 1 in the mesh's order
 * into map (0: unused; a wire's own vertex has no place in a file of
 * facets). Returns how many. */
static uint32_t number_vertices(const lam_mesh *m, uint32_t *map)
{
    for (size_t t = 0; t < 3 * m->ntris; t++) map[m->tris[t]] = 1;
    uint32_t k = 0;
    for (size_t v = 0; v < m->nverts; v++)
        if (map[v]) map[v] = ++k;
    return k;
}

static int write_obj(const lam_model *md, chunk *c, lam_error *err)
{
    const lam_mesh *m = &md->mesh;
    uint32_t *map = calloc(m->nverts ? m->nverts : 1, sizeof *map);
    if (!map) return lam_error_nomem(err, "while writing the mesh");
    uint32_t used = number_vertices(m, map);
    char name[600];
    source_name(md, name, sizeof name);
    int k = snprintf((char *)c->b, CHUNK, "# lamina " LAMINA_VERSION ": %zu vertices, %zu triangles of %s\n",
                     (size_t)used, m->ntris, name);
    c->n = k > 0 && k < CHUNK ? (size_t)k : 0;
    int rc = LAM_OK;
    for (size_t v = 0; v < m->nverts && !rc; v++)
        if (map[v]) rc = put_vertex(c, m->xyz + 3 * v);
    for (size_t t = 0; t < m->ntris && !rc; t++) {
        if ((rc = room(c, 3 * 11 + 3))) break;
        char line[48] = "f";
        size_t n = 1;
        for (int j = 0; j < 3; j++) {
            line[n++] = ' ';
            n += put_index(line + n, map[m->tris[3 * t + j]]);
        }
        line[n++] = '\n';
        put_text(c, line, n);
    }
    free(map);
    return rc ? rc : flush(c);
}

int lam_model_write_mesh(const lam_model *md, int fmt, lam_writer *w, lam_error *err)
{
    if (fmt != LAM_MESH_STL && fmt != LAM_MESH_OBJ)
        return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "unknown mesh format %d", fmt);
    chunk *c = malloc(sizeof *c);
    if (!c) return lam_error_nomem(err, "while writing the mesh");
    c->w = w;
    c->n = 0;
    int rc = fmt == LAM_MESH_OBJ ? write_obj(md, c, err) : write_stl(md, c, err);
    free(c);
    /* a failed write: the writer's own words (path and reason) */
    return rc && lam_writer_error(w, NULL) ? lam_writer_error(w, err) : rc;
}
