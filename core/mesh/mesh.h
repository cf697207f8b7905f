/* lam_mesh: the indexed triangle mesh every importer fills.
 *
 * Positions are doubles; triangles index them (uint32). Every triangle
 * remembers the source face it came from (a face record with the user's
 * name and position), so that later errors can point at the user's face.
 * Wires (Unigrafix `w`) are kept as vertex pairs and never sliced.
 *
 * Ownership: a lam_mesh owns all its arrays; lam_mesh_free releases them.
 * Every function that can fail returns LAM_OK or LAM_ENOMEM/LAM_EINVAL and
 * fills err. */
#ifndef LAM_MESH_H
#define LAM_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "error.h"

#define LAM_NO_NAME UINT32_MAX

/* Where a face came from. Strings are offsets into lam_mesh.strings. */
typedef struct lam_face_src {
    uint32_t name;    /* the user's face id, LAM_NO_NAME when anonymous */
    uint32_t file;    /* source file, LAM_NO_NAME when unknown */
    uint32_t line;    /* 1-based, 0 when unknown */
    uint32_t column;
} lam_face_src;

typedef struct lam_mesh {
    double *xyz;          /* 3 per vertex */
    size_t nverts, cap_verts;
    uint32_t *tris;       /* 3 per triangle, indices into xyz */
    uint32_t *tri_face;   /* per triangle: index into faces; NULL when the mesh
                             has no face records (triangle i is facet i+1) */
    size_t ntris, cap_tris;
    lam_face_src *faces;
    size_t nfaces, cap_faces;
    uint32_t *wires;      /* 2 per wire segment */
    size_t nwire_segs, cap_wire_segs;
    size_t nwires;        /* wire statements read */
    int welded;           /* set by an importer whose vertices are already
                             distinct and all used: lam_mesh_weld has nothing to do */
    char *strings;        /* NUL-terminated strings, referenced by offset */
    size_t strings_len, strings_cap;
} lam_mesh;

/* Initialise an empty mesh (no allocation). */
void lam_mesh_init(lam_mesh *m);

/* Release everything the mesh owns and leave it empty. */
void lam_mesh_free(lam_mesh *m);

/* Reserve room for nverts more vertices and ntris more triangles. */
int lam_mesh_reserve(lam_mesh *m, size_t nverts, size_t ntris, lam_error *err);

/* The largest coordinate magnitude a model may have. Derived quantities
 * are products of up to four differences of coordinates (squared cross
 * products for areas and normals, triple products for volumes and winding
 * numbers), which overflow a double from about 1e76; 1e50 leaves room for
 * six. */
#define LAM_COORD_MAX 1e50

/* NULL when x can be a vertex coordinate (finite, |x| <= LAM_COORD_MAX),
 * else what is wrong with it, in words every importer reports (static). */
const char *lam_coord_problem(double x);

/* Append a vertex; its index is stored in *idx. Coordinates must pass
 * lam_coord_problem (importers check and report with a position before
 * calling; LAM_EINVAL without one here). */
int lam_mesh_add_vertex(lam_mesh *m, double x, double y, double z,
                        uint32_t *idx, lam_error *err);

/* Append a face record (name and file may be NULL). *face receives its id. */
int lam_mesh_add_face(lam_mesh *m, const char *name, const char *file,
                      long line, long column, uint32_t *face, lam_error *err);

/* Append triangle (a, b, c) belonging to face (LAM_NO_NAME for none, only
 * allowed while the mesh has no face records at all). */
int lam_mesh_add_tri(lam_mesh *m, uint32_t a, uint32_t b, uint32_t c,
                     uint32_t face, lam_error *err);

/* Append a wire segment between two vertices. */
int lam_mesh_add_wire_seg(lam_mesh *m, uint32_t a, uint32_t b, lam_error *err);

/* Triangulate a planar polygon and append its triangles. idx holds the
 * rings' vertex indices back to back; ring_len[r] is the length of ring r;
 * ring 0 is the outer boundary, the others are holes. The triangles keep
 * the outer ring's winding. Rings need 3 or more vertices. Fails with
 * LAM_EGEOM when the polygon is degenerate beyond triangulation.
 * (Implemented in triangulate.c.) */
int lam_mesh_add_polygon(lam_mesh *m, const uint32_t *idx, const size_t *ring_len,
                         size_t nrings, uint32_t face, lam_error *err);

/* Welding while importing: formats that repeat every vertex per triangle
 * (STL) look each one up by exact position instead of storing it again,
 * which keeps the mesh small from the start. */
#define LAM_WELDER_RECENT 4096
typedef struct lam_welder {
    uint64_t *table;      /* open addressing: hash tag << 32 | vertex index */
    size_t cap, count;
    /* Direct-mapped cache of recent vertices (full hash, index): a mesh
     * file names each vertex again a few facets later, and this small
     * table answers those from cache instead of the big one. */
    struct { uint64_t h; uint32_t v; } *recent;
} lam_welder;

/* An empty welder (no allocation until the first vertex). */
void lam_welder_init(lam_welder *w);
void lam_welder_free(lam_welder *w);

/* Make room for n distinct vertices without rehashing (m: the mesh whose
 * vertices the welder indexes). */
int lam_welder_reserve(lam_welder *w, const lam_mesh *m, size_t n, lam_error *err);

/* A hint: the vertex at (x, y, z) will be added soon, so start fetching
 * its slot of the table. Changes nothing. */
void lam_welder_prefetch(const lam_welder *w, double x, double y, double z);

/* Like lam_mesh_add_vertex, but returns the index of an earlier vertex
 * added through the same welder at bitwise the same position (-0.0 counts
 * as 0.0). */
int lam_mesh_add_vertex_welded(lam_mesh *m, lam_welder *w, double x, double y, double z,
                               uint32_t *idx, lam_error *err);

/* Identify vertices with bitwise-equal coordinates (-0.0 counts as 0.0),
 * drop vertices no triangle or wire uses, and renumber. Triangle order and
 * face records are kept. Linear expected time (hashing). */
int lam_mesh_weld(lam_mesh *m, lam_error *err);

/* A copy of every array of m in out (initialised here; free it with
 * lam_mesh_free). Errors: LAM_ENOMEM (out is then empty). */
int lam_mesh_copy(const lam_mesh *m, lam_mesh *out, lam_error *err);

/* Twice the area of triangle abc, and (*degenerate) whether it is exactly
 * zero (every component of the cross product 0: repeated or collinear
 * corners). The test is the same for either winding: swapping b and c
 * negates each component exactly (ISO C mode: no fused multiply-add
 * contraction). The one measure the model build and repair use. */
double lam_tri_area2(const double *a, const double *b, const double *c, int *degenerate);

/* The squared distance between two points. */
static inline double lam_dist2(const double *a, const double *b)
{
    double d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
    return d0 * d0 + d1 * d1 + d2 * d2;
}

/* A string stored in the mesh (NULL for LAM_NO_NAME). */
const char *lam_mesh_string(const lam_mesh *m, uint32_t offset);

/* Describe the source of triangle t for messages, e.g.
 * "face 'base' (part.ug:31:1)" or "facet 12". Returns buf. */
const char *lam_mesh_describe_tri(const lam_mesh *m, size_t t, char *buf, size_t size);

#endif
