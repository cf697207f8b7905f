/* Layer frames (frame.h). */
#include "frame.h"

#include <math.h>
#include <string.h>

static void set3(double *d, double x, double y, double z)
{
    d[0] = x;
    d[1] = y;
    d[2] = z;
}

int lam_frame_axis(char axis, lam_frame *f, lam_error *err)
{
    memset(f, 0, sizeof *f);
    switch (axis) {
    case 'x': case 'X':
        set3(f->u, 0, 1, 0); set3(f->v, 0, 0, 1); set3(f->w, 1, 0, 0);
        return LAM_OK;
    case 'y': case 'Y':
        set3(f->u, 0, 0, 1); set3(f->v, 1, 0, 0); set3(f->w, 0, 1, 0);
        return LAM_OK;
    case 'z': case 'Z':
        set3(f->u, 1, 0, 0); set3(f->v, 0, 1, 0); set3(f->w, 0, 0, 1);
        return LAM_OK;
    }
    return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "unknown axis '%c' (x, y, z or a direction DX,DY,DZ)", axis);
}

int lam_frame_direction(const double d[3], lam_frame *f, lam_error *err)
{
    double len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (!(len > 0) || !isfinite(len))
        return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "slice direction must be a finite non-zero vector");
    /* exact positive axes keep their exact thesis frames */
    if (d[1] == 0 && d[2] == 0 && d[0] > 0) return lam_frame_axis('x', f, err);
    if (d[0] == 0 && d[2] == 0 && d[1] > 0) return lam_frame_axis('y', f, err);
    if (d[0] == 0 && d[1] == 0 && d[2] > 0) return lam_frame_axis('z', f, err);
    for (int k = 0; k < 3; k++) f->w[k] = d[k] / len;
    int least = 0;
    for (int k = 1; k < 3; k++)
        if (fabs(f->w[k]) < fabs(f->w[least])) least = k;
    double a[3] = { 0, 0, 0 };
    a[least] = 1;
    double dot = f->w[least];
    for (int k = 0; k < 3; k++) f->u[k] = a[k] - dot * f->w[k];
    double ul = sqrt(f->u[0] * f->u[0] + f->u[1] * f->u[1] + f->u[2] * f->u[2]);
    for (int k = 0; k < 3; k++) f->u[k] /= ul;
    f->v[0] = f->w[1] * f->u[2] - f->w[2] * f->u[1];
    f->v[1] = f->w[2] * f->u[0] - f->w[0] * f->u[2];
    f->v[2] = f->w[0] * f->u[1] - f->w[1] * f->u[0];
    return LAM_OK;
}

void lam_frame_to_model(const lam_frame *f, double u, double v, double w, double xyz[3])
{
    for (int k = 0; k < 3; k++) {
        /* skip zero terms so axis frames map coordinates exactly */
        double s = 0;
        if (f->u[k] != 0) s += u * f->u[k];
        if (f->v[k] != 0) s += v * f->v[k];
        if (f->w[k] != 0) s += w * f->w[k];
        xyz[k] = s;
    }
}
