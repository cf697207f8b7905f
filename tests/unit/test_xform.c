/* The transform on load (xform.h): the text forms and their errors, the
 * order of the steps, exact quarter turns, --place plate on a generated
 * mesh, coordinates pushed out of range, and the identity left bit for bit
 * alone. Every expected coordinate is worked out here by hand. */
#include "meshes.h"
#include "model.h"
#include "profile.h"
#include "xform.h"

#include <stdlib.h>

/* the mesh's bounding box into b (xmin, ymin, zmin, xmax, ymax, zmax) */
static void bbox(const lam_mesh *m, double b[6])
{
    for (int k = 0; k < 3; k++) b[k] = INFINITY, b[k + 3] = -INFINITY;
    for (size_t i = 0; i < m->nverts; i++)
        for (int k = 0; k < 3; k++) {
            double q = m->xyz[3 * i + k];
            if (q < b[k]) b[k] = q;
            if (q > b[k + 3]) b[k + 3] = q;
        }
}

static int bbox_is(const lam_mesh *m, double x0, double y0, double z0, double x1, double y1, double z1)
{
    double b[6], w[6] = { x0, y0, z0, x1, y1, z1 };
    bbox(m, b);
    for (int k = 0; k < 6; k++)
        if (b[k] != w[k]) {
            diag("bbox[%d] is %.17g, expected %.17g", k, b[k], w[k]);
            return 0;
        }
    return 1;
}

static int parse(int (*fn)(lam_xform *, const char *, lam_error *), lam_xform *x, const char *text, lam_error *err)
{
    lam_error_clear(err);
    return fn(x, text, err);
}

static void test_parse(void)
{
    lam_xform x;
    lam_error err;
    lam_xform_init(&x);
    ok(lam_xform_is_identity(&x), "init: the identity");
    ok(lam_xform_is_identity(NULL), "NULL: the identity");
    lam_xform z;
    memset(&z, 0, sizeof z);
    ok(lam_xform_is_identity(&z), "a zero-initialised lam_xform: the identity (scale 0 means 1)");

    ok(parse(lam_xform_parse_scale, &x, "2", &err) == LAM_OK, "scale 2");
    ok(x.scale[0] == 2 && x.scale[1] == 2 && x.scale[2] == 2, "... on every axis");
    ok(parse(lam_xform_parse_scale, &x, "1,0.5,-3", &err) == LAM_OK, "scale 1,0.5,-3");
    ok(x.scale[0] == 2 && x.scale[1] == 1 && x.scale[2] == -6, "... multiplies into the first");
    ok(!lam_xform_is_identity(&x), "a scale is not the identity");
    static const char *const bad_scales[] = { "", "0", "1,0,1", "1,2", "1,2,3,4", "x", "2x", "1,,2", "1,2,", "inf",
                                              "nan", "1e999", " 2", NULL };
    for (int i = 0; bad_scales[i]; i++) {
        lam_xform y = x;
        int rc = parse(lam_xform_parse_scale, &y, bad_scales[i], &err);
        ok(rc == LAM_EUSAGE && err.code == LAM_EUSAGE && err.msg[0], "scale '%s' refused: %s", bad_scales[i], err.msg);
        ok(!memcmp(&y, &x, sizeof x), "... and x is as it was");
    }
    parse(lam_xform_parse_scale, &x, "0", &err);
    is_str(err.msg, "a factor of 0 flattens the model", "scale 0: says why");
    lam_xform big;
    lam_xform_init(&big);
    parse(lam_xform_parse_scale, &big, "1e300", &err);
    ok(parse(lam_xform_parse_scale, &big, "1e300", &err) == LAM_EUSAGE, "scale 1e300 twice overflows: refused");

    lam_xform_init(&x);
    ok(parse(lam_xform_parse_rotate, &x, "x:90", &err) == LAM_OK && x.nrot == 1 && x.rot[0].axis == 0 &&
           x.rot[0].deg == 90, "rotate x:90");
    ok(parse(lam_xform_parse_rotate, &x, "Z:-45.5,y:1e1", &err) == LAM_OK && x.nrot == 3 && x.rot[1].axis == 2 &&
           x.rot[1].deg == -45.5 && x.rot[2].axis == 1 && x.rot[2].deg == 10, "rotate Z:-45.5,y:1e1: two more, in order");
    parse(lam_xform_parse_rotate, &x, "q:90", &err);
    is_str(err.msg, "the axis must be x, y or z", "rotate q:90: the axis");
    static const char *const bad_rots[] = { "", "x", "x:", "x90", ":90", "xy:90", "x:abc", "x:inf", "x:90,", "x:90,q:1",
                                            "x:90;y:1", "x:90 ", NULL };
    for (int i = 0; bad_rots[i]; i++) {
        lam_xform y = x;
        int rc = parse(lam_xform_parse_rotate, &y, bad_rots[i], &err);
        ok(rc == LAM_EUSAGE && err.msg[0] && !memcmp(&y, &x, sizeof x), "rotate '%s' refused, nothing kept: %s",
           bad_rots[i], err.msg);
    }
    lam_xform_init(&x);
    int rc = 0;
    for (int i = 0; i < LAM_XFORM_MAX_ROT && !rc; i++) rc = parse(lam_xform_parse_rotate, &x, "z:1", &err);
    ok(rc == LAM_OK && x.nrot == LAM_XFORM_MAX_ROT, "%d rotations fit", LAM_XFORM_MAX_ROT);
    ok(parse(lam_xform_parse_rotate, &x, "z:1", &err) == LAM_EUSAGE, "one more is refused: %s", err.msg);
    lam_xform_init(&x);
    parse(lam_xform_parse_rotate, &x, "z:360", &err);
    parse(lam_xform_parse_rotate, &x, "x:-720", &err);
    ok(lam_xform_is_identity(&x), "whole turns only: the identity");

    lam_xform_init(&x);
    ok(parse(lam_xform_parse_translate, &x, "1,-2.5,3e2", &err) == LAM_OK && x.translate[0] == 1 &&
           x.translate[1] == -2.5 && x.translate[2] == 300, "translate 1,-2.5,3e2");
    ok(parse(lam_xform_parse_translate, &x, "1,1,1", &err) == LAM_OK && x.translate[0] == 2 && x.translate[2] == 301,
       "a second translate adds");
    static const char *const bad_tr[] = { "1", "1,2", "1,2,3,4", "a,b,c", "1,2,nan", "", NULL };
    for (int i = 0; bad_tr[i]; i++)
        ok(parse(lam_xform_parse_translate, &x, bad_tr[i], &err) == LAM_EUSAGE, "translate '%s' refused: %s", bad_tr[i],
           err.msg);

    ok(parse(lam_xform_parse_place, &x, "plate", &err) == LAM_OK && x.place == LAM_PLACE_PLATE, "place plate");
    ok(parse(lam_xform_parse_place, &x, "none", &err) == LAM_OK && x.place == LAM_PLACE_NONE, "place none");
    ok(parse(lam_xform_parse_place, &x, "Plate", &err) == LAM_EUSAGE && x.place == LAM_PLACE_NONE, "place Plate refused");
}

static void test_units(void)
{
    is_num(lam_unit_mm("mm"), 1, 0, "mm");
    is_num(lam_unit_mm("cm"), 10, 0, "cm");
    is_num(lam_unit_mm("m"), 1000, 0, "m");
    is_num(lam_unit_mm("um"), 1e-3, 0, "um");
    is_num(lam_unit_mm("in"), 25.4, 0, "in");
    is_num(lam_unit_mm("ft"), 304.8, 0, "ft");
    is_num(lam_unit_mm("furlong"), 0, 0, "an unknown unit: 0");
    is_num(lam_unit_mm(NULL), 0, 0, "NULL: 0");
    /* the one table: a profile in inches says what lam_unit_mm says */
    lam_profile p;
    memset(&p, 0, sizeof p);
    p.units = "in";
    is_num(lam_profile_unit_mm(&p), lam_unit_mm("in"), 0, "lam_profile_unit_mm agrees (in)");
    p.units = "cm";
    is_num(lam_profile_unit_mm(&p), lam_unit_mm("cm"), 0, "lam_profile_unit_mm agrees (cm)");
    lam_xform x;
    lam_xform_init(&x);
    lam_xform_scale_by(&x, 25.4);
    ok(x.scale[0] == 25.4 && x.scale[2] == 25.4, "scale_by: the factor on every axis");
    lam_error err;
    parse(lam_xform_parse_scale, &x, "2,1,1", &err);
    ok(x.scale[0] == 50.8 && x.scale[1] == 25.4, "then --scale multiplies");
    lam_xform z;
    memset(&z, 0, sizeof z);
    lam_xform_scale_by(&z, 10);
    ok(z.scale[0] == 10 && z.scale[1] == 10 && z.scale[2] == 10, "scale_by on a zero-initialised transform");
}

/* a box with its own 8 vertices in a fresh mesh */
static void box(lam_mesh *m, double x0, double y0, double z0, double x1, double y1, double z1)
{
    lam_mesh_init(m);
    add_box(m, x0, y0, z0, x1, y1, z1, 0, -1);
}

static int apply_text(lam_mesh *m, const char *scale, const char *rot, const char *place, const char *tr,
                      lam_error *err)
{
    lam_xform x;
    lam_xform_init(&x);
    lam_error_clear(err);
    if (scale && lam_xform_parse_scale(&x, scale, err)) return -1;
    if (rot && lam_xform_parse_rotate(&x, rot, err)) return -1;
    if (place && lam_xform_parse_place(&x, place, err)) return -1;
    if (tr && lam_xform_parse_translate(&x, tr, err)) return -1;
    return lam_xform_apply(&x, m, err);
}

static void test_apply(void)
{
    lam_mesh m;
    lam_error err;

    /* the identity: every bit as it was, -0 included */
    box(&m, -0.0, 0.1, -3.3, 1e-300, 0.7, 2.2);
    size_t n = 3 * m.nverts;
    double *before = malloc(n * sizeof *before);
    memcpy(before, m.xyz, n * sizeof *before);
    lam_xform x;
    lam_xform_init(&x);
    lam_error_clear(&err);
    ok(lam_xform_apply(&x, &m, &err) == LAM_OK && !memcmp(before, m.xyz, n * sizeof *before),
       "the identity leaves every coordinate bit for bit");
    ok(lam_xform_apply(NULL, &m, &err) == LAM_OK && !memcmp(before, m.xyz, n * sizeof *before), "so does NULL");
    apply_text(&m, NULL, "z:360,x:-360", "none", "0,0,0", &err);
    ok(!memcmp(before, m.xyz, n * sizeof *before), "whole turns, place none and 0,0,0: skipped");
    free(before);
    lam_mesh_free(&m);

    /* box [0,1]x[0,2]x[0,3]; about x by 90: (x, y, z) -> (x, -z, y) */
    box(&m, 0, 0, 0, 1, 2, 3);
    ok(apply_text(&m, NULL, "x:90", NULL, NULL, &err) == LAM_OK, "rotate x:90");
    ok(bbox_is(&m, 0, -3, 0, 1, 0, 2), "x:90: y becomes -z, z becomes y, exactly");
    int integer = 1, negzero = 0;
    for (size_t i = 0; i < 3 * m.nverts; i++) {
        integer &= m.xyz[i] == floor(m.xyz[i]);
        negzero |= m.xyz[i] == 0 && signbit(m.xyz[i]);
    }
    ok(integer, "a quarter turn keeps integer coordinates integers");
    ok(!negzero, "and makes no -0");
    lam_mesh_free(&m);

    /* about y by 90: (x, y, z) -> (z, y, -x); about z by 90: (x, y) -> (-y, x) */
    box(&m, 0, 0, 0, 1, 2, 3);
    apply_text(&m, NULL, "y:90", NULL, NULL, &err);
    ok(bbox_is(&m, 0, 0, -1, 3, 2, 0), "y:90: x becomes z, z becomes -x");
    lam_mesh_free(&m);
    box(&m, 0, 0, 0, 1, 2, 3);
    apply_text(&m, NULL, "z:-90", NULL, NULL, &err);
    ok(bbox_is(&m, 0, -1, 0, 2, 0, 3), "z:-90: x becomes y, y becomes -x");
    lam_mesh_free(&m);
    box(&m, 0, 0, 0, 1, 2, 3);
    apply_text(&m, NULL, "z:180", NULL, NULL, &err);
    ok(bbox_is(&m, -1, -2, 0, 0, 0, 3), "z:180: exact");
    lam_mesh_free(&m);
    box(&m, 0, 0, 0, 1, 2, 3);
    apply_text(&m, NULL, "z:450", NULL, NULL, &err);
    ok(bbox_is(&m, -2, 0, 0, 0, 1, 3), "z:450 is z:90");
    lam_mesh_free(&m);

    /* the order of the rotations: x:90 then z:90 against the reverse.
     * box [0,1]x[0,2]x[0,3]: x:90 -> [0,1]x[-3,0]x[0,2]; z:90 -> [0,3]x[0,1]x[0,2].
     * z:90 -> [-2,0]x[0,1]x[0,3]; x:90 -> [-2,0]x[-3,0]x[0,1]. */
    box(&m, 0, 0, 0, 1, 2, 3);
    apply_text(&m, NULL, "x:90,z:90", NULL, NULL, &err);
    ok(bbox_is(&m, 0, 0, 0, 3, 1, 2), "x:90 then z:90");
    lam_mesh_free(&m);
    box(&m, 0, 0, 0, 1, 2, 3);
    apply_text(&m, NULL, "z:90,x:90", NULL, NULL, &err);
    ok(bbox_is(&m, -2, -3, 0, 0, 0, 1), "z:90 then x:90: another box");
    lam_mesh_free(&m);

    /* 45 degrees about z: the corner (1, 0) goes to (c, c), c = sqrt(1/2) */
    box(&m, 0, 0, 0, 1, 1, 1);
    apply_text(&m, NULL, "z:45", NULL, NULL, &err);
    double b[6];
    bbox(&m, b);
    double c = sqrt(0.5);
    is_num(b[0], -c, 1e-15, "z:45: xmin -sqrt(1/2)");
    is_num(b[3], c, 1e-15, "z:45: xmax sqrt(1/2)");
    is_num(b[4], 2 * c, 1e-15, "z:45: ymax sqrt(2)");
    is_num(b[1], 0, 1e-15, "z:45: ymin 0");
    lam_mesh_free(&m);

    /* scale before rotation: scale 2,1,1 then z:90 stretches what becomes y */
    box(&m, 0, 0, 0, 1, 1, 1);
    apply_text(&m, "2,1,1", "z:90", NULL, NULL, &err);
    ok(bbox_is(&m, -1, 0, 0, 0, 2, 1), "scale comes before the rotation");
    lam_mesh_free(&m);

    /* placement, then translation: box [3,5]x[-4,-2]x[-7,-6] */
    box(&m, 3, -4, -7, 5, -2, -6);
    apply_text(&m, NULL, NULL, "plate", NULL, &err);
    ok(bbox_is(&m, -1, -1, 0, 1, 1, 1), "place plate: lowest point on z = 0, footprint centred on the origin");
    lam_mesh_free(&m);
    box(&m, 3, -4, -7, 5, -2, -6);
    apply_text(&m, NULL, NULL, "plate", "10,20,30", &err);
    ok(bbox_is(&m, 9, 19, 30, 11, 21, 31), "place plate then translate 10,20,30");
    lam_mesh_free(&m);
    box(&m, 3, -4, -7, 5, -2, -6);
    lam_xform_init(&x);
    x.place = LAM_PLACE_PLATE;
    x.plate_centre[0] = 100;
    x.plate_centre[1] = -50;
    lam_xform_apply(&x, &m, &err);
    ok(bbox_is(&m, 99, -51, 0, 101, -49, 1), "plate_centre: the footprint's centre goes there");
    lam_mesh_free(&m);
    /* placement after the rotation: x:90 of [0,1]x[0,2]x[0,3] is [0,1]x[-3,0]x[0,2] */
    box(&m, 0, 0, 0, 1, 2, 3);
    apply_text(&m, NULL, "x:90", "plate", NULL, &err);
    ok(bbox_is(&m, -0.5, -1.5, 0, 0.5, 1.5, 2), "the plate sees the rotated part");
    lam_mesh_free(&m);

    /* a generated sphere, off-centre and turned by 30 degrees: on the plate */
    lam_mesh_init(&m);
    add_uv_sphere(&m, 7, 24, 12, 0);
    lam_xform_init(&x);
    lam_error_clear(&err);
    lam_xform_parse_translate(&x, "3,4,-50", &err);
    lam_xform_apply(&x, &m, &err);
    apply_text(&m, NULL, "y:30", "plate", NULL, &err);
    bbox(&m, b);
    ok(b[2] == 0, "the sphere's lowest point is exactly on z = 0 (got %.17g)", b[2]);
    is_num(b[0] + b[3], 0, 1e-12, "its footprint is centred on x = 0");
    is_num(b[1] + b[4], 0, 1e-12, "and on y = 0");
    lam_model *md = build_model_quiet(&m, "sphere");
    ok(md && md->stats.boundary_edges == 0 && md->stats.volume > 0, "and it still builds as a closed, outward solid");
    lam_model_free(md);

    /* a mirror (negative factor): the model is rebuilt outward */
    box(&m, 0, 0, 0, 1, 2, 3);
    apply_text(&m, "-1,1,1", NULL, NULL, NULL, &err);
    ok(bbox_is(&m, -1, 0, 0, 0, 2, 3), "scale -1,1,1 mirrors x");
    md = build_model_quiet(&m, "mirror");
    ok(md && md->stats.volume == 6, "the mirrored box builds with volume +6");
    lam_model_free(md);

    /* out of range after a step: LAM_EGEOM naming it */
    box(&m, 0, 0, 0, 1e40, 1, 1);
    ok(apply_text(&m, "1e20", NULL, NULL, NULL, &err) == LAM_EGEOM, "1e40 scaled by 1e20: LAM_EGEOM");
    ok(strstr(err.msg, "scaling") != NULL, "... naming the step: %s", err.msg);
    lam_mesh_free(&m);
    box(&m, 0, 0, 0, 1e50, 1, 1);
    ok(apply_text(&m, NULL, NULL, NULL, "1e50,0,0", &err) == LAM_EGEOM && strstr(err.msg, "translat"),
       "1e50 moved by 1e50: LAM_EGEOM naming the translation: %s", err.msg);
    lam_mesh_free(&m);
    box(&m, -1e50, 0, 0, 1e50, 1, 1);
    ok(apply_text(&m, NULL, NULL, "plate", NULL, &err) == LAM_OK, "a model 2e50 wide on the plate: still in range");
    lam_mesh_free(&m);
    box(&m, 1e50, 0, -1e50, 1e50, 1, 1e50);
    ok(apply_text(&m, NULL, NULL, "plate", NULL, &err) == LAM_EGEOM && strstr(err.msg, "plate"),
       "z from -1e50 to 1e50 on the plate reaches 2e50: LAM_EGEOM naming the placement: %s", err.msg);
    lam_mesh_free(&m);

    /* an empty mesh: nothing to do */
    lam_mesh_init(&m);
    ok(apply_text(&m, "2", "x:30", "plate", "1,2,3", &err) == LAM_OK && m.nverts == 0, "an empty mesh: nothing");
    lam_mesh_free(&m);
}

int main(void)
{
    test_parse();
    test_units();
    test_apply();
    return done_testing();
}
