/* mesh_write.h: binary STL and OBJ written to a memory writer and read
 * back by this test's own readers (not lamina's importers): the STL's
 * count, size, header, every facet's normal (unit length, the direction of
 * its float corners' cross product, away from the solid), its corners
 * equal as float32 to the model's; the OBJ's vertices equal to the model's
 * doubles bit for bit and its faces the model's triangles. */
#include "meshes.h"
#include "mesh_write.h"
#include "writer.h"

#include <float.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

/* ---- an independent reader of binary STL --------------------------------- */

static uint32_t le32(const unsigned char *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static float lef(const unsigned char *p)
{
    uint32_t u = le32(p);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

/* Write md as fmt into memory; the bytes (caller frees) or NULL. */
static char *write_mem(const lam_model *md, int fmt, size_t *len, int *rc, lam_error *err)
{
    lam_writer *w = NULL;
    char *data = NULL;
    lam_error_clear(err);
    if (lam_writer_memory(&w, err)) return NULL;
    *rc = lam_model_write_mesh(md, fmt, w, err);
    lam_error e2;
    if (*rc) {
        lam_writer_abort(w);
        return NULL;
    }
    if (lam_writer_take(w, &data, len, &e2)) return NULL;
    return data;
}

/* Check the STL bytes of md: facet t's corners are model triangle t's as
 * float32, its normal unit length and along the float corners' cross
 * product; `inside` a point inside every solid shell of a convex model
 * whose cavity (if any) contains `void_c`: each normal points away from
 * the material (outward on the outer shell, into the void on a cavity). */
static void check_stl(const char *what, const lam_model *md, const unsigned char *b, size_t len,
                      const double inside[3], const double *void_c, const double void_box[6])
{
    const lam_mesh *m = &md->mesh;
    is_int(len, 84 + 50 * m->ntris, "%s: 84 + 50 bytes per facet", what);
    if (len != 84 + 50 * m->ntris) return;
    ok(memcmp(b, "lamina ", 7) == 0 && memcmp(b, "solid", 5) != 0, "%s: header names lamina, not 'solid'", what);
    char head[81], want[81];
    memcpy(head, b, 80);
    head[80] = '\0';
    size_t wn = 0;
    for (const char *p = md->path; *p && wn < 40; p++) want[wn++] = (unsigned char)*p < 0x20 ? '?' : *p;
    want[wn] = '\0';
    ok(strstr(head, want) != NULL, "%s: header names the source ('%s' in '%s')", what, want, head);
    is_int(le32(b + 80), m->ntris, "%s: facet count", what);
    size_t bad_corner = 0, bad_len = 0, bad_dir = 0, bad_out = 0, bad_attr = 0;
    double vol = 0;
    for (size_t t = 0; t < m->ntris; t++) {
        const unsigned char *f = b + 84 + 50 * t;
        float n[3], c[3][3];
        for (int j = 0; j < 3; j++) n[j] = lef(f + 4 * j);
        for (int k = 0; k < 3; k++)
            for (int j = 0; j < 3; j++) {
                c[k][j] = lef(f + 12 + 12 * k + 4 * j);
                if (c[k][j] != (float)m->xyz[3 * (size_t)m->tris[3 * t + k] + j]) bad_corner++;
            }
        if (f[48] || f[49]) bad_attr++;
        double nl = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
        if (fabs(nl - 1) > 1e-6) bad_len++;
        double u[3], v[3], x[3], cen[3];
        for (int j = 0; j < 3; j++) {
            u[j] = (double)c[1][j] - c[0][j];
            v[j] = (double)c[2][j] - c[0][j];
            cen[j] = ((double)c[0][j] + c[1][j] + c[2][j]) / 3;
        }
        x[0] = u[1] * v[2] - u[2] * v[1], x[1] = u[2] * v[0] - u[0] * v[2], x[2] = u[0] * v[1] - u[1] * v[0];
        double xl = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
        if (!(xl > 0) || (n[0] * x[0] + n[1] * x[1] + n[2] * x[2]) / xl < 0.999) bad_dir++;
        /* a facet of the cavity lies in void_box; its material is outside it */
        int in_void = void_c && cen[0] >= void_box[0] && cen[0] <= void_box[3] && cen[1] >= void_box[1] &&
                      cen[1] <= void_box[4] && cen[2] >= void_box[2] && cen[2] <= void_box[5];
        const double *ref = in_void ? void_c : inside;
        double d = n[0] * (cen[0] - ref[0]) + n[1] * (cen[1] - ref[1]) + n[2] * (cen[2] - ref[2]);
        if (in_void ? d >= 0 : d <= 0) bad_out++;
        /* signed volume of the float facets (divergence theorem) */
        vol += ((double)c[0][0] * (c[1][1] * (double)c[2][2] - (double)c[1][2] * c[2][1]) -
                (double)c[0][1] * (c[1][0] * (double)c[2][2] - (double)c[1][2] * c[2][0]) +
                (double)c[0][2] * (c[1][0] * (double)c[2][1] - (double)c[1][1] * c[2][0])) / 6;
    }
    is_int(bad_corner, 0, "%s: every corner equals the model's as float32", what);
    is_int(bad_attr, 0, "%s: attribute bytes 0", what);
    is_int(bad_len, 0, "%s: every normal of unit length", what);
    is_int(bad_dir, 0, "%s: every normal along its corners' right-hand cross product", what);
    is_int(bad_out, 0, "%s: every normal away from the material", what);
    is_num(vol, md->stats.volume, 1e-5 * fabs(md->stats.volume), "%s: the facets enclose the model's volume", what);
}

/* ---- an independent reader of the OBJ written ---------------------------- */

/* Check the OBJ text against md: `v` lines are the triangles' vertices in
 * the model's order, bit for bit; `f` lines the triangles, 1-based. */
static void check_obj(const char *what, const lam_model *md, char *text)
{
    const lam_mesh *m = &md->mesh;
    size_t nv = 0, nf = 0, bad_v = 0, bad_f = 0, other = 0;
    uint32_t *map = calloc(m->nverts + 1, sizeof *map); /* OBJ index -> model vertex */
    /* the model's vertices the triangles use, in order */
    char *used = calloc(m->nverts + 1, 1);
    for (size_t t = 0; t < 3 * m->ntris; t++) used[m->tris[t]] = 1;
    size_t next = 0;
    for (char *line = strtok(text, "\n"); line; line = strtok(NULL, "\n")) {
        if (line[0] == '#') continue;
        if (line[0] == 'v' && line[1] == ' ') {
            while (next < m->nverts && !used[next]) next++;
            char *p = line + 2, *end;
            for (int j = 0; j < 3; j++, p = end) {
                double x = strtod(p, &end);
                if (end == p || next >= m->nverts || x != m->xyz[3 * next + j]) bad_v++;
            }
            if (*p) bad_v++;
            if (next < m->nverts) map[++nv] = (uint32_t)next++;
        } else if (line[0] == 'f' && line[1] == ' ') {
            char *p = line + 2, *end;
            for (int j = 0; j < 3; j++, p = end) {
                unsigned long k = strtoul(p, &end, 10);
                if (end == p || k < 1 || k > nv || nf >= m->ntris || map[k] != m->tris[3 * nf + j]) bad_f++;
            }
            if (*p) bad_f++;
            nf++;
        } else {
            other++;
        }
    }
    size_t want_v = 0;
    for (size_t v = 0; v < m->nverts; v++) want_v += used[v] != 0;
    is_int(nv, want_v, "%s: one v line per vertex of a triangle", what);
    is_int(nf, m->ntris, "%s: one f line per triangle", what);
    is_int(bad_v, 0, "%s: every vertex reads back as the model's double", what);
    is_int(bad_f, 0, "%s: every face the model's triangle (1-based)", what);
    is_int(other, 0, "%s: nothing else but comments", what);
    free(map);
    free(used);
}

static void round_trip(const char *what, lam_model *md, const double inside[3], const double *void_c,
                       const double void_box[6])
{
    lam_error err;
    size_t len = 0;
    int rc = -1;
    char label[128];
    char *stl = write_mem(md, LAM_MESH_STL, &len, &rc, &err);
    ok(stl && rc == LAM_OK, "%s: STL written (%s)", what, rc ? err.msg : "ok");
    snprintf(label, sizeof label, "%s STL", what);
    if (stl) check_stl(label, md, (const unsigned char *)stl, len, inside, void_c, void_box);
    free(stl);
    char *obj = write_mem(md, LAM_MESH_OBJ, &len, &rc, &err);
    ok(obj && rc == LAM_OK, "%s: OBJ written (%s)", what, rc ? err.msg : "ok");
    snprintf(label, sizeof label, "%s OBJ", what);
    if (obj) check_obj(label, md, obj);
    free(obj);
}

int main(void)
{
    is_int(lam_mesh_format_for("a.obj"), LAM_MESH_OBJ, ".obj: OBJ");
    is_int(lam_mesh_format_for("dir.obj/A.OBJ"), LAM_MESH_OBJ, ".OBJ: OBJ (any case)");
    is_int(lam_mesh_format_for("a.stl"), LAM_MESH_STL, ".stl: STL");
    is_int(lam_mesh_format_for("a.obj.stl"), LAM_MESH_STL, ".obj.stl: STL");
    is_int(lam_mesh_format_for("obj"), LAM_MESH_STL, "'obj' alone: STL");
    is_int(lam_mesh_format_for("-"), LAM_MESH_STL, "-: STL");

    /* a box of awkward numbers, every other input triangle flipped: the
     * files hold the model's outward winding, not the input's */
    lam_mesh m;
    lam_mesh_init(&m);
    double x0 = 0.1, y0 = 1.0 / 3, z0 = -2.5e-5, x1 = 1e3 + 0.3, y1 = 2 * acos(-1.0) / 3, z1 = 7.000000000000001;
    add_box(&m, x0, y0, z0, x1, y1, z1, 0x555, -1);
    lam_model *box = build_model(&m, "box.stl");
    double c1[3] = { (x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2 };
    if (box) round_trip("box", box, c1, NULL, NULL);

    /* a box with a cavity (its shell turned inward by the model) */
    lam_mesh_init(&m);
    add_box(&m, -10, -10, -10, 10, 10, 10, 0, -1);
    add_box(&m, -3, -2, -1, 3, 2, 1, 0, -1);
    lam_model *hollow = build_model(&m, "hollow \"box\"\t.ug");
    double c2[3] = { 0, 0, 0 }, vb[6] = { -3, -2, -1, 3, 2, 1 };
    if (hollow) {
        is_int(hollow->stats.cavities, 1, "hollow box: one cavity");
        is_num(hollow->stats.volume, 8000 - 48, 1e-9, "hollow box: volume without the cavity");
        /* the normals of the outer shell point away from the centre: any
         * point of the cavity is inside the outer box */
        round_trip("hollow box", hollow, c2, c2, vb);
    }

    /* a sphere of 40,000 facets: many buffers of the writer */
    lam_model *ball = uv_sphere(25.5, 200, 101, 7, "ball.stl");
    double c3[3] = { 0, 0, 0 };
    if (ball) round_trip("sphere", ball, c3, NULL, NULL);

    /* out of float32 range: STL refused before a byte, OBJ exact */
    lam_mesh_init(&m);
    add_box(&m, 0, 0, 0, 1e39, 1, 1, 0, -1);
    lam_model *big = build_model(&m, "big.stl");
    if (big) {
        lam_error err;
        lam_writer *w = NULL;
        lam_writer_memory(&w, &err);
        int rc = lam_model_write_mesh(big, LAM_MESH_STL, w, &err);
        ok(rc == LAM_EINVAL && strstr(err.msg, "float32") && strstr(err.msg, "OBJ"), "1e39: STL refused (%s)",
           err.msg);
        is_int(lam_writer_bytes(w), 0, "1e39: nothing written");
        lam_writer_abort(w);
        size_t len;
        char *obj = write_mem(big, LAM_MESH_OBJ, &len, &rc, &err);
        ok(obj && rc == LAM_OK, "1e39: OBJ written");
        if (obj) check_obj("1e39 OBJ", big, obj);
        free(obj);
    }

    /* a writer that fails: its error, with the reason */
    if (ball) {
        for (int fmt = 0; fmt < 2; fmt++) {
            lam_error err;
            lam_error_clear(&err);
            lam_writer *w = NULL;
            lam_writer_memory(&w, &err);
            lam_writer_set_limit(w, 100000);
            int rc = lam_model_write_mesh(ball, fmt, w, &err);
            ok(rc != LAM_OK && strstr(err.msg, "limit"), "%s past the writer's limit: its error (%s)",
               fmt ? "OBJ" : "STL", err.msg);
            ok(lam_writer_bytes(w) <= 100000, "and no byte past it");
            lam_writer_abort(w);
        }
    }

    lam_model_free(box);
    lam_model_free(hollow);
    lam_model_free(ball);
    lam_model_free(big);
    return done_testing();
}
