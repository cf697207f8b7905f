/* Importers: one per format, all filling a lam_mesh.
 *
 * Each importer appends to an initialised (normally empty) mesh and returns
 * LAM_OK, or an error code with err holding file:line:column (text formats)
 * or a byte offset (binary STL). On failure the mesh may hold a partial
 * result; the caller frees it. Vertices are not welded here: lam_model
 * does that once for every format. Importers are linear in the input size. */
#ifndef LAM_IMPORT_H
#define LAM_IMPORT_H

#include <stddef.h>

#include "error.h"
#include "file.h"
#include "mesh.h"

/* Unigrafix (.ug), SPEC 2.1. `path` names the file for messages and for
 * resolving `include` (relative to the including file's directory). */
int lam_import_ug(const char *path, lam_mesh *mesh, lam_error *err);

/* Unigrafix from a buffer already in memory; `path` is used for messages and
 * include resolution only. */
int lam_import_ug_buf(const char *path, const char *data, size_t len,
                      lam_mesh *mesh, lam_error *err);

/* STL, ASCII or binary, chosen by content (a binary file whose header begins
 * with "solid" is still binary when its size matches its triangle count).
 * *binary (may be NULL) is set to 1 for binary, 0 for ASCII. */
int lam_import_stl_buf(const char *path, const unsigned char *data, size_t len,
                       lam_mesh *mesh, int *binary, lam_error *err);

/* Wavefront OBJ: v, f (v, v/vt, v//vn, v/vt/vn, negative indices); polygons
 * triangulated; other statements ignored. */
int lam_import_obj_buf(const char *path, const char *data, size_t len,
                       lam_mesh *mesh, lam_error *err);

#endif
