/* The transform on load (xform.h): units and scale, rotations, placement,
 * translation, each step skipped when it changes nothing. */
#include "xform.h"

#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "profile_keys.h"

void lam_xform_init(lam_xform *x)
{
    memset(x, 0, sizeof *x);
    x->scale[0] = x->scale[1] = x->scale[2] = 1;
}

/* x's scale on axis k: an all-zero scale (a zero-initialised lam_xform) is 1 */
static double scale_of(const lam_xform *x, int k)
{
    if (x->scale[0] == 0 && x->scale[1] == 0 && x->scale[2] == 0) return 1;
    return x->scale[k];
}

/* A rotation by a whole number of turns changes nothing */
static int rot_identity(double deg) { return fmod(deg, 360) == 0; }

int lam_xform_is_identity(const lam_xform *x)
{
    if (!x) return 1;
    for (int k = 0; k < 3; k++)
        if (scale_of(x, k) != 1 || x->translate[k] != 0) return 0;
    for (size_t i = 0; i < x->nrot && i < LAM_XFORM_MAX_ROT; i++)
        if (!rot_identity(x->rot[i].deg)) return 0;
    return x->place == LAM_PLACE_NONE;
}

/* The profile's `units` table (profile_keys.c) is the one table: a model's
 * unit and a machine's are the same names with the same factors. */
double lam_unit_mm(const char *unit) { return lam_key_unit_mm(unit); }

void lam_xform_scale_by(lam_xform *x, double factor)
{
    double f[3] = { scale_of(x, 0), scale_of(x, 1), scale_of(x, 2) }; /* before the first is written */
    for (int k = 0; k < 3; k++) x->scale[k] = f[k] * factor;
}

/* ---- parsing ------------------------------------------------------------- */

/* A finite number at *s (strtod's syntax, no leading space) ending at one
 * of `ends` (or the end of the text); *s moves past it. 0 on failure. */
static int number(const char **s, const char *ends, double *out)
{
    char *end;
    errno = 0;
    if (!**s || isspace((unsigned char)**s)) return 0;
    double v = strtod(*s, &end);
    if (end == *s || errno == ERANGE || !isfinite(v) || (*end && !strchr(ends, *end))) return 0;
    *s = end;
    *out = v;
    return 1;
}

/* "A,B,C" (or "A" when one is allowed) into v: the count read, 0 when malformed */
static int triple(const char *text, int one, double v[3])
{
    const char *p = text;
    int n = 0;
    while (n < 3) {
        if (!number(&p, ",", &v[n])) return 0;
        n++;
        if (!*p) break;
        p++; /* the comma */
        if (!*p) return 0;
    }
    if (*p) return 0;
    return n == 3 || (one && n == 1) ? n : 0;
}

int lam_xform_parse_scale(lam_xform *x, const char *text, lam_error *err)
{
    double v[3];
    int n = triple(text, 1, v);
    if (!n) return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "expected a factor F or three FX,FY,FZ (numbers)");
    if (n == 1) v[1] = v[2] = v[0];
    for (int k = 0; k < 3; k++)
        if (v[k] == 0) return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "a factor of 0 flattens the model");
    for (int k = 0; k < 3; k++) {
        double f = scale_of(x, k) * v[k];
        if (!isfinite(f) || f == 0)
            return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "the factors multiply to %g on %c", f, "xyz"[k]);
        v[k] = f;
    }
    memcpy(x->scale, v, sizeof v);
    return LAM_OK;
}

/* One "AXIS:DEG" at *p, ending at a comma or the end */
static int parse_one_rotation(lam_xform *x, const char **p, lam_error *err)
{
    const char *s = *p;
    const char *axes = "xyz";
    const char *a = *s ? strchr(axes, tolower((unsigned char)*s)) : NULL;
    if (!a || s[1] != ':') {
        if (*s && s[1] == ':') return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "the axis must be x, y or z");
        return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "expected AXIS:DEG (x:90, z:-45)");
    }
    s += 2;
    double deg;
    if (!number(&s, ",", &deg))
        return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "the angle must be a finite number of degrees");
    if (x->nrot >= LAM_XFORM_MAX_ROT)
        return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "more than %d rotations", LAM_XFORM_MAX_ROT);
    x->rot[x->nrot].axis = (int)(a - axes);
    x->rot[x->nrot].deg = deg;
    x->nrot++;
    *p = s;
    return LAM_OK;
}

int lam_xform_parse_rotate(lam_xform *x, const char *text, lam_error *err)
{
    lam_xform tmp = *x; /* all or nothing: a bad second rotation keeps none */
    const char *p = text;
    for (;;) {
        int rc = parse_one_rotation(&tmp, &p, err);
        if (rc) return rc;
        if (!*p) break;
        p++;
        if (!*p) return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "a rotation after the comma is missing");
    }
    *x = tmp;
    return LAM_OK;
}

int lam_xform_parse_translate(lam_xform *x, const char *text, lam_error *err)
{
    double v[3];
    if (!triple(text, 0, v)) return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "expected X,Y,Z (three numbers)");
    for (int k = 0; k < 3; k++) {
        double t = x->translate[k] + v[k];
        if (!isfinite(t)) return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "the offsets add to %g on %c", t, "xyz"[k]);
        v[k] = t;
    }
    memcpy(x->translate, v, sizeof v);
    return LAM_OK;
}

int lam_xform_parse_place(lam_xform *x, const char *text, lam_error *err)
{
    if (!strcmp(text, "plate")) x->place = LAM_PLACE_PLATE;
    else if (!strcmp(text, "none")) x->place = LAM_PLACE_NONE;
    else return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "expected plate or none");
    return LAM_OK;
}

/* ---- applying ------------------------------------------------------------ */

/* Every coordinate still one a model may have, else LAM_EGEOM naming step */
static int check(const lam_mesh *m, const char *step, lam_error *err)
{
    for (size_t i = 0; i < 3 * m->nverts; i++) {
        const char *why = lam_coord_problem(m->xyz[i]);
        if (why)
            return lam_error_set(err, LAM_EGEOM, NULL, 0, 0, "after %s, vertex %zu's %c coordinate (%g) %s", step,
                                 i / 3 + 1, "xyz"[i % 3], m->xyz[i], why);
    }
    return LAM_OK;
}

/* cos and sin of deg degrees, exact for multiples of 90 (cos(pi/2) is
 * 6e-17, which would leave a cube turned a quarter with coordinates off
 * the grid it was drawn on) */
static void cos_sin(double deg, double *c, double *s)
{
    double r = fmod(deg, 360);
    if (r < 0) r += 360;
    static const double qc[4] = { 1, 0, -1, 0 }, qs[4] = { 0, 1, 0, -1 };
    if (fmod(r, 90) == 0) {
        int q = (int)(r / 90) % 4;
        *c = qc[q];
        *s = qs[q];
        return;
    }
    double rad = r * (3.14159265358979323846 / 180);
    *c = cos(rad);
    *s = sin(rad);
}

/* Right-handed rotation about one axis: (u, v) are the two other axes in
 * cyclic order (about x: y, z; about y: z, x; about z: x, y). + 0.0 turns
 * the -0 an exact quarter turn makes of 0 into 0. */
static void rotate(lam_mesh *m, int axis, double deg)
{
    double c, s;
    cos_sin(deg, &c, &s);
    int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (size_t i = 0; i < m->nverts; i++) {
        double *p = m->xyz + 3 * i;
        double a = p[u], b = p[v];
        p[u] = c * a - s * b + 0.0;
        p[v] = s * a + c * b + 0.0;
    }
}

static void place_plate(lam_mesh *m, const double centre[2])
{
    double lo[3] = { INFINITY, INFINITY, INFINITY }, hi[3] = { -INFINITY, -INFINITY, -INFINITY };
    for (size_t i = 0; i < m->nverts; i++)
        for (int k = 0; k < 3; k++) {
            double q = m->xyz[3 * i + k];
            if (q < lo[k]) lo[k] = q;
            if (q > hi[k]) hi[k] = q;
        }
    /* the lowest point lands on exactly 0 (q - lo[2] for q == lo[2]) */
    double d[2];
    for (int k = 0; k < 2; k++) d[k] = centre[k] - (lo[k] / 2 + hi[k] / 2);
    for (size_t i = 0; i < m->nverts; i++) {
        double *p = m->xyz + 3 * i;
        if (d[0] != 0) p[0] += d[0];
        if (d[1] != 0) p[1] += d[1];
        p[2] -= lo[2];
        p[2] += 0.0;
    }
}

int lam_xform_apply(const lam_xform *x, lam_mesh *m, lam_error *err)
{
    if (!x || !m->nverts || lam_xform_is_identity(x)) return LAM_OK;
    int rc;
    double f[3] = { scale_of(x, 0), scale_of(x, 1), scale_of(x, 2) };
    if (f[0] != 1 || f[1] != 1 || f[2] != 1) {
        for (size_t i = 0; i < m->nverts; i++)
            for (int k = 0; k < 3; k++) m->xyz[3 * i + k] *= f[k];
        if ((rc = check(m, "scaling (units and --scale)", err))) return rc;
    }
    for (size_t i = 0; i < x->nrot && i < LAM_XFORM_MAX_ROT; i++)
        if (!rot_identity(x->rot[i].deg)) rotate(m, x->rot[i].axis, x->rot[i].deg);
    /* a rotation keeps the distance from the origin, and coordinates were
     * at most 1e50 in magnitude: within sqrt(3) of the bound, checked once */
    if (x->nrot && (rc = check(m, "rotating (--rotate)", err))) return rc;
    if (x->place == LAM_PLACE_PLATE) {
        place_plate(m, x->plate_centre);
        if ((rc = check(m, "placing on the plate (--place plate)", err))) return rc;
    }
    if (x->translate[0] != 0 || x->translate[1] != 0 || x->translate[2] != 0) {
        for (size_t i = 0; i < m->nverts; i++)
            for (int k = 0; k < 3; k++) m->xyz[3 * i + k] += x->translate[k];
        if ((rc = check(m, "translating (--translate)", err))) return rc;
    }
    return LAM_OK;
}
