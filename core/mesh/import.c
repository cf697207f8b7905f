/* lam_model_load: read a file, pick the importer, build the model.
 *
 * The format is chosen by extension (.ug, .stl, .obj, any case); a file with
 * another extension is recognised by content: a binary STL by its size, an
 * ASCII STL by a leading "solid", an OBJ by `v`/`f` lines, Unigrafix by `;`
 * terminated statements. Standard input (lam_model_load_stdin) has no
 * extension: always by content. */
#include "file.h"
#include "import.h"
#include "model.h"
#include "repair.h"
#include "stl_weld.h"
#include "xform.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

enum fmt { FMT_UNKNOWN, FMT_UG, FMT_STL, FMT_OBJ };

static enum fmt by_extension(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *dot = strrchr(slash ? slash : path, '.');
    if (!dot) return FMT_UNKNOWN;
    if (strcasecmp(dot, ".ug") == 0) return FMT_UG;
    if (strcasecmp(dot, ".stl") == 0) return FMT_STL;
    if (strcasecmp(dot, ".obj") == 0) return FMT_OBJ;
    return FMT_UNKNOWN;
}

static enum fmt by_content(const char *d, size_t n)
{
    if (n >= 84) {
        unsigned long long count = (unsigned char)d[80] | (unsigned)(unsigned char)d[81] << 8 |
                                   (unsigned long)(unsigned char)d[82] << 16 |
                                   (unsigned long)(unsigned char)d[83] << 24;
        if (84 + 50 * count == n) return FMT_STL;
    }
    size_t i = 0;
    while (i < n && (d[i] == ' ' || d[i] == '\t' || d[i] == '\r' || d[i] == '\n')) i++;
    if (n - i >= 5 && strncasecmp(d + i, "solid", 5) == 0) return FMT_STL;
    /* OBJ: a line starting "v " and no statement terminators in the first
     * kilobytes; Unigrafix has ';' after every statement. */
    size_t look = n < 65536 ? n : 65536;
    int semis = 0, vlines = 0;
    for (size_t k = 0; k < look; k++) {
        if (d[k] == ';') semis++;
        if ((k == 0 || d[k - 1] == '\n') && k + 1 < look && d[k] == 'v' && (d[k + 1] == ' ' || d[k + 1] == '\t'))
            vlines++;
        if (d[k] == '\0') return FMT_UNKNOWN;
    }
    if (semis) return FMT_UG;
    if (vlines) return FMT_OBJ;
    return FMT_UNKNOWN;
}

/* The mesh in data (len bytes, NUL-terminated), named path: *mesh is
 * initialised here and freed on failure. The caller releases data before
 * building the model from the mesh: the file (as large as the mesh) need
 * not stay beside the model's arrays while they are made. */
static int parse_buf(const char *path, const char *data, size_t len, lam_mesh *mesh, const char **format,
                     unsigned threads, lam_error *err)
{
    lam_mesh_init(mesh);
    if (len == 0) return lam_error_set(err, LAM_EFORMAT, path, 0, 0, "empty file");
    enum fmt f = by_extension(path);
    if (f == FMT_UNKNOWN) f = by_content(data, len);
    int rc;
    switch (f) {
    case FMT_UG:
        rc = lam_import_ug_buf(path, data, len, mesh, err);
        *format = "unigrafix";
        break;
    case FMT_STL: {
        int binary = 0;
        rc = lam_import_stl_threads(path, (const unsigned char *)data, len, mesh, &binary, threads, err);
        *format = binary ? "stl-binary" : "stl-ascii";
        break;
    }
    case FMT_OBJ:
        rc = lam_import_obj_buf(path, data, len, mesh, err);
        *format = "obj";
        break;
    default:
        rc = lam_error_set(err, LAM_EFORMAT, path, 0, 0,
                           "unknown model format (lamina reads Unigrafix .ug, STL and OBJ)");
    }
    if (rc) lam_mesh_free(mesh);
    return rc;
}

static unsigned threads_of(const lam_load_opts *o) { return o && o->threads > 1 ? o->threads : 1; }

/* The mesh read, transformed, built and (unless told not to) repaired:
 * the one way from a parsed mesh to a loaded model. */
static int finish(lam_mesh *mesh, const char *path, const char *format, const lam_load_opts *o, lam_model **out,
                  lam_error *err)
{
    int rc = lam_xform_apply(o ? o->xform : NULL, mesh, err);
    if (rc) {
        if (err && !err->file[0]) snprintf(err->file, sizeof err->file, "%s", path);
        lam_mesh_free(mesh);
        return rc;
    }
    if ((rc = lam_model_from_mesh(mesh, path, format, out, err))) return rc;
    if (o && o->no_repair) return LAM_OK;
    if ((rc = lam_model_repair(out, NULL, err))) {
        lam_model_free(*out);
        *out = NULL;
    }
    return rc;
}

int lam_model_load_opts(const char *path, const lam_load_opts *o, lam_model **out, lam_error *err)
{
    *out = NULL;
    char *data;
    size_t len;
    int mapped;
    int rc = lam_map_file(path, lam_model_limit(), &data, &len, &mapped, err);
    if (rc) return rc;
    lam_mesh mesh;
    const char *format = NULL;
    rc = parse_buf(path, data, len, &mesh, &format, threads_of(o), err);
    lam_unmap_file(data, len, mapped);
    return rc ? rc : finish(&mesh, path, format, o, out, err);
}

int lam_model_load(const char *path, lam_model **out, lam_error *err)
{
    return lam_model_load_opts(path, NULL, out, err);
}

int lam_model_load_stdin_opts(const lam_load_opts *o, lam_model **out, lam_error *err)
{
    *out = NULL;
    char *data;
    size_t len;
    int rc = lam_read_stdin(lam_model_limit(), &data, &len, err);
    if (rc) return rc;
    lam_mesh mesh;
    const char *format = NULL;
    rc = parse_buf(LAM_STDIN_NAME, data, len, &mesh, &format, threads_of(o), err);
    free(data);
    return rc ? rc : finish(&mesh, LAM_STDIN_NAME, format, o, out, err);
}

int lam_model_load_stdin(lam_model **out, lam_error *err)
{
    return lam_model_load_stdin_opts(NULL, out, err);
}
