/* lam_model: a loaded solid ready for slicing.
 *
 * Built from a lam_mesh: vertices welded, an edge table, shells (connected
 * components through shared edges), orientation made consistent inside each
 * shell from adjacency (the file's winding is never trusted), each shell
 * turned outward by its signed volume, and shells enclosed by an odd number
 * of other shells turned inward (cavities). Volume is then the signed sum. */
#ifndef LAM_MODEL_H
#define LAM_MODEL_H

#include <stddef.h>
#include <stdint.h>

#include "error.h"
#include "mesh.h"

/* Every undirected edge with its incident triangles (CSR layout). */
typedef struct lam_edges {
    size_t n;
    uint32_t *v;         /* 2 per edge, v[2e] < v[2e+1] */
    uint32_t *first;     /* n + 1 offsets into tris */
    uint32_t *tris;      /* triangles of edge e: tris[first[e] .. first[e+1]) */
    uint32_t *tri_edge;  /* 3 per triangle: edges (t0,t1), (t1,t2), (t2,t0) */
} lam_edges;

typedef struct lam_shell {
    size_t ntris;
    double bbox[6];      /* xmin ymin zmin xmax ymax zmax */
    double volume;       /* signed: positive for a solid, negative for a cavity */
    double area;
    int enclosing;       /* how many other shells enclose this one */
    int cavity;          /* enclosing is odd */
    size_t flipped;      /* triangles the file wound against the shell's majority */
} lam_shell;

typedef struct lam_model_stats {
    size_t triangles, vertices, edges, shells, cavities, wires;
    size_t boundary_edges;     /* edges with one triangle */
    size_t nonmanifold_edges;  /* edges with more than two triangles */
    size_t degenerate_tris;    /* zero area: repeated or collinear vertices */
    size_t orientation_conflicts; /* manifold edges whose triangles could not
                                     be made consistent (non-orientable) */
    size_t flipped_tris;       /* triangles the file wound against their shell's majority,
                                  turned to agree (a shell wound inward throughout is
                                  turned outward as always, and not counted) */
    double bbox[6];
    double area, volume;
} lam_model_stats;

/* What repairing a mesh on load did (repair.h). All zero when the model
 * was loaded with no_repair or needed nothing. */
typedef struct lam_repair_report {
    int ran;                  /* 1 when repair was asked for (the default) */
    double weld_tolerance;    /* the distance within which open edges' vertices were merged (model units) */
    size_t welded;            /* vertices merged within that tolerance */
    size_t degenerate;        /* facets removed: repeated vertices or no area */
    size_t duplicates;        /* facets removed: the same three vertices as another */
    size_t flipped;           /* facets whose winding was turned to agree with their shell */
    size_t holes;             /* boundary loops filled with triangles */
    size_t hole_edges;        /* the boundary edges those loops had */
    size_t fill_triangles;    /* triangles added to fill them */
    double fill_area;         /* the area those triangles cover */
    double largest_hole;      /* the largest filled loop's fill area */
    size_t crossing_loops;    /* loops that cross themselves (filled, reported) */
    size_t holes_left;        /* loops not filled (see repair.h) */
    size_t boundary_edges;    /* open edges that remain */
    size_t nonmanifold_edges; /* edges with more than two facets that remain */
    size_t crossing_edges;    /* edges through a facet not their own, the edge or the facet a
                                 fill's: self-intersections the fills left */
    int crossings_unknown;    /* 1 when they could not all be counted (Embree could not be
                                 loaded, or overlapping facets by the thousand: a part) */
} lam_repair_report;

typedef struct lam_model {
    char *path;            /* as given to lam_model_load, owned */
    const char *format;    /* static: "unigrafix", "stl-ascii", "stl-binary", "obj", "mesh" */
    lam_mesh mesh;         /* welded, oriented */
    lam_edges edges;
    uint32_t *tri_shell;   /* per triangle */
    uint32_t *shell_first; /* nshells + 1 offsets into shell_tris */
    uint32_t *shell_tris;  /* triangles of shell s: shell_tris[shell_first[s] .. shell_first[s+1]) */
    lam_shell *shells;
    size_t nshells;
    lam_model_stats stats;
    lam_repair_report repair; /* what repair on load did (zero: not asked or nothing) */
} lam_model;

/* How a model is loaded (zero-initialise; a NULL pointer means all
 * defaults). */
struct lam_xform;
typedef struct lam_load_opts {
    const struct lam_xform *xform; /* units, scale, rotations, placement
                         applied to the vertices before the model is built
                         (xform.h); NULL: as the file has them */
    int no_repair;    /* 1: build the model from the file as it is (no
                         repair.h pass): today's open-mesh behaviour */
    unsigned threads; /* threads that read it (0 or 1: the calling thread
                         alone); the model is the same, bit for bit, for
                         every number. A binary STL of 524,288 facets
                         or more is decoded and welded in parallel. */
} lam_load_opts;

/* Load a model file. The format is chosen by extension (.ug, .stl, .obj)
 * and confirmed by content; an unknown extension is sniffed. The mesh is
 * transformed (o->xform) and repaired (repair.h) unless o->no_repair; the
 * model's `repair` says what was done. On success
 * *out is a new model the caller frees with lam_model_free. */
int lam_model_load(const char *path, lam_model **out, lam_error *err);

/* lam_model_load with options (o may be NULL). */
int lam_model_load_opts(const char *path, const lam_load_opts *o, lam_model **out, lam_error *err);

/* The same from standard input (lam_read_stdin: the model size limit),
 * the format told by content; the model and its messages are named
 * "<stdin>" (LAM_STDIN_NAME), a Unigrafix include is resolved against the
 * working directory. */
int lam_model_load_stdin(lam_model **out, lam_error *err);

/* lam_model_load_stdin with options (o may be NULL). */
int lam_model_load_stdin_opts(const lam_load_opts *o, lam_model **out, lam_error *err);

/* Build a model from a mesh the caller filled, as it is (no repair: see
 * lam_model_repair in repair.h). The mesh's contents move
 * into the model (mesh is left empty) whether or not this succeeds. */
int lam_model_from_mesh(lam_mesh *mesh, const char *path, const char *format,
                        lam_model **out, lam_error *err);

/* Free a model (NULL is fine). */
void lam_model_free(lam_model *model);

/* The bytes a model's arrays hold: parts[0] the mesh (vertices, triangles,
 * faces, wires, strings), parts[1] the edges, parts[2] the shells (parts
 * may be NULL); the sum is returned. What the elements take, not the
 * capacity reserved: room reserved and never written is never resident. */
size_t lam_model_bytes(const lam_model *model, size_t parts[3]);

/* The winding number of the closed shell s of the model around point p
 * (generalised winding number: sum of solid angles / 4 pi). Near 1 inside a
 * solid shell, 0 outside, 0.5 on its surface. O(triangles of s). */
double lam_model_shell_winding(const lam_model *model, size_t s, const double p[3]);

#endif
