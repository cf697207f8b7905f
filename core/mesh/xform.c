/* Placeholder: the transform on load (xform.h); the identity for now. */
#include "xform.h"

#include <string.h>

void lam_xform_init(lam_xform *x) { memset(x, 0, sizeof *x); }

int lam_xform_is_identity(const lam_xform *x) { (void)x; return 1; }

int lam_xform_apply(const lam_xform *x, lam_mesh *m, lam_error *err)
{
    (void)x;
    (void)m;
    (void)err;
    return LAM_OK;
}
