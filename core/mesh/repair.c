/* Placeholder: repair on load (repair.h). */
#include "repair.h"

#include <stdio.h>

int lam_model_repair(lam_model **md, const lam_repair_opts *o, lam_error *err)
{
    (void)o;
    (void)err;
    (*md)->repair.ran = 1;
    return LAM_OK;
}

const char *lam_repair_summary(const lam_repair_report *r, char *buf, size_t size)
{
    (void)r;
    if (size) buf[0] = 0;
    return buf;
}
