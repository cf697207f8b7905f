/* Placeholder: writing a model's mesh (mesh_write.h). */
#include "mesh_write.h"

#include <string.h>
#include <strings.h>

int lam_mesh_format_for(const char *path)
{
    size_t n = strlen(path);
    return n >= 4 && strcasecmp(path + n - 4, ".obj") == 0 ? LAM_MESH_OBJ : LAM_MESH_STL;
}

int lam_model_write_mesh(const lam_model *md, int fmt, lam_writer *w, lam_error *err)
{
    (void)md;
    (void)fmt;
    (void)w;
    return lam_error_set(err, LAM_EINVAL, NULL, 0, 0, "not written yet");
}
