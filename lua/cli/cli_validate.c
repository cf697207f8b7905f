/* lamina validate MODEL [slice options] [--program FILE] [--json]: an
 * independent 3D check of every layer (SPEC 6, validate.h): each contour's
 * direction, ancestry, nesting and label against rays through the model,
 * and each layer's net area against the model's own section. Without
 * --program the layers are sliced here; with it they are read back from the
 * program file (program_read.h), as the machine would get them. Exit 0 when
 * everything checked agrees, 3 when anything disagrees. Contours too small
 * to place a test point in are reported as unchecked, not as failures.
 *
 * The model checked against is the repaired one (repair.h): with
 * --no-repair the layers come from the mesh as the file has it and the
 * rays and sections from a repaired copy of it (reference_model), so a
 * layer that lost area where an outline stayed open is compared with what
 * the part should have there. When even the repaired model stays open its
 * section means nothing: the areas are not compared, and the summary and a
 * warning say so (the exit status is then that of the other checks). */
#include "cli.h"
#include "cli_args.h"
#include "cli_check.h"
#include "fmt.h"
#include "model.h"
#include "program_read.h"
#include "repair.h"
#include "size_sense.h"
#include "validate.h"
#include "validate_run.h"

#include <float.h>
#include <math.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

static const char usage_text[] =
    "usage: lamina validate MODEL [-m MACHINE] [-a AXIS] [-w WIDTH | --widths ... | --planes ...]\n"
    "                             [--cut floor|middle|ceiling] [--gap TOL] [--allow-open]\n"
    "                             [--fill evenodd|nonzero] [--json] [-q | -v] [-j N]\n"
    "       lamina validate MODEL --program FILE [-m MACHINE] [-a AXIS] [-w WIDTH ...] [--cut ...]\n"
    "                             [--frame model|machine] [--beam-offset] [--fill ...] [--json]\n"
    "                             [-q | -v] [-j N]\n"
    "Slices like 'lamina slice' (or reads the program FILE back: sls-contours, cli-ascii,\n"
    "cli-binary or a run's JSON from 'slice --json', told apart by content) and checks every\n"
    "layer against the 3D model: each\n"
    "contour's direction against its label, its parents and depth against the contours\n"
    "around it, its label against the winding number of rays cast through the model\n"
    "(Embree) from test points beside its edges in the cut plane, and the layer's net\n"
    "area against the model's own section. Exit 3 when anything disagrees.\n"
    "The model checked against is the repaired one: with --no-repair the layers come from\n"
    "the mesh as the file has it and are checked against a repaired copy, so a layer whose\n"
    "outline stayed open and was dropped (--allow-open) is reported with the area it lost\n"
    "(layers with gaps closed are allowed gap/2 x the length bridged, and at least 0.1%).\n"
    "A model that stays open after repair has no section to compare: the summary and a\n"
    "warning say so, and the exit status is that of the other checks.\n"
    "With --program: -a, --frame (or the profile's) say how the program was written (a run's\n"
    "JSON says it itself), --cut which side of a flat face a height on it meant (middle and\n"
    "floor: above, ceiling: below). Give the options it was sliced with: it must hold each\n"
    "layer they give once, in the profile's units, its contour passes where -m, -s and\n"
    "--beam-offset put them (exit 3 otherwise).\n"
    "-q (--quiet): only the layers that disagree and the summary, no progress line;\n"
    "-v (--verbose): also the time each stage takes.\n"
    "  -j, --jobs       threads that slice (or make the layers read back) and check them\n"
    "                   (default: LAMINA_THREADS, else the processors); the report and\n"
    "                   the exit status are the same for every number\n";

static const char *kind_name(const lam_layer *L, size_t c)
{
    return L->contours[c].kind == LAM_SOLID ? "solid" : "hole";
}

/* "contour 3 (solid" and, read back, ", FILE:LINE:COL" */
static void contour_name(FILE *out, const lam_layer *L, size_t c, const vsource *src)
{
    fprintf(out, "contour %zu (%s", c + 1, kind_name(L, c));
    if (src) {
        const lam_program_contour *pc = &src->contours[c];
        if (pc->offset >= 0) fprintf(out, ", %s: byte %lld", src->path, pc->offset);
        else fprintf(out, ", %s:%ld:%ld", src->path, pc->line, pc->column);
    }
    fputc(')', out);
}

static const unsigned STRUCTURE[] = { LAM_VP_ANCESTRY, LAM_VP_DIRECTION, LAM_VP_NESTING };

static int bit_index(unsigned bit)
{
    int i = 0;
    while (bit > 1) bit >>= 1, i++;
    return i;
}

static void text_contour(FILE *out, const lam_layer *L, const lam_contour_check *c, const vsource *src)
{
    if (c->ok < 0) {
        fputs("  ", out);
        contour_name(out, L, c->contour, src);
        fprintf(out, " not checked: %s\n", c->why ? c->why : "no test point");
        return;
    }
    if (c->problems & LAM_VP_MATERIAL) {
        fputs("  ", out);
        contour_name(out, L, c->contour, src);
        fprintf(out, " disagrees at (%g, %g, %g): winding %d, the label says %s (%s)\n", c->xyz[0], c->xyz[1],
                c->xyz[2], c->winding_found, c->expected_material ? "material" : "void",
                c->whys[bit_index(LAM_VP_MATERIAL)]);
    }
    const lam_contour *k = &L->contours[c->contour];
    for (size_t i = 0; i < sizeof STRUCTURE / sizeof *STRUCTURE; i++) {
        unsigned b = STRUCTURE[i];
        if (!(c->problems & b)) continue;
        fputs("  ", out);
        contour_name(out, L, c->contour, src);
        fprintf(out, " %s: %s (", lam_validate_problem_name(b), c->whys[bit_index(b)]);
        if (b == LAM_VP_DIRECTION) fprintf(out, "signed area %g", c->area);
        else if (k->depth >= 0 && k->parent >= 0) fprintf(out, "depth %d, parent contour %ld", k->depth, k->parent + 1);
        else if (k->depth >= 0) fprintf(out, "depth %d, no parent", k->depth);
        if (b == LAM_VP_NESTING) {
            fputs(k->depth >= 0 ? "; " : "", out);
            if (c->depth_found > 0)
                fprintf(out, "%d contour%s around it, the smallest contour %ld", c->depth_found,
                        c->depth_found == 1 ? "" : "s", c->parent_found + 1);
            else fputs("no contour around it", out);
        }
        fputs(")\n", out);
    }
}

static void json_contour(FILE *out, const lam_layer *L, const lam_contour_check *c, const vsource *src)
{
    fprintf(out, "{\"contour\":%zu,\"label\":\"%s\"", c->contour, kind_name(L, c->contour));
    if (src) {
        const lam_program_contour *pc = &src->contours[c->contour];
        if (pc->offset >= 0) fprintf(out, ",\"offset\":%lld", pc->offset);
        else fprintf(out, ",\"line\":%ld,\"column\":%ld", pc->line, pc->column);
    }
    fputs(",\"position\":[", out);
    for (int k = 0; k < 3; k++) {
        if (k) fputc(',', out);
        cli_json_number(out, c->xyz[k]);
    }
    fprintf(out, "],\"winding\":%d,\"label_says\":\"%s\",\"area\":", c->winding_found,
            c->expected_material ? "material" : "void");
    cli_json_number(out, c->area);
    fprintf(out, ",\"depth_found\":%d,\"parent_found\":%ld,\"why\":", c->depth_found, c->parent_found);
    cli_json_string(out, c->why ? c->why : "");
    fputs(",\"problems\":[", out);
    int first = 1;
    for (unsigned b = 1; b <= LAM_VP_NESTING; b <<= 1) {
        if (!(c->problems & b)) continue;
        fprintf(out, "%s{\"check\":\"%s\",\"why\":", first ? "" : ",", lam_validate_problem_name(b));
        cli_json_string(out, c->whys[bit_index(b)]);
        fputc('}', out);
        first = 0;
    }
    fputs("]}", out);
}

int vreport_layer(vreport *r, lam_rays *v, const lam_layer *L, const lam_frame *f, const lam_validate_opts *o,
                  const vsource *src, lam_error *err)
{
    lam_layer_check chk;
    int rc = lam_validate_layer(v, L, f, o, &chk, err);
    if (rc) return rc;
    vreport_check(r, L, &chk, src);
    lam_layer_check_free(&chk);
    return LAM_OK;
}

/* "  net area 0 (solids minus holes) but the model's section has 314.1: off
 * by -314.1 (lost 314.1, 100% of the section), tolerance ... (why)" */
static void text_area(FILE *out, const lam_layer_check *c)
{
    fprintf(out, "  net area %.10g (solids minus holes) but the model's section has %.10g: off by %.3g (", c->net_area,
            c->section_area, -c->area_lost);
    fprintf(out, c->area_lost >= 0 ? "lost %.3g" : "%.3g more than the model has", fabs(c->area_lost));
    if (c->section_area > 0) fprintf(out, ", %.3g%% of the section", 100 * fabs(c->area_lost) / c->section_area);
    fprintf(out, "), tolerance %.3g (%s)\n", c->area_tolerance, c->area_why);
}

void vreport_check(vreport *r, const lam_layer *L, const lam_layer_check *c, const vsource *src)
{
    r->layers++;
    r->checked += c->checked;
    r->confirmed += c->confirmed;
    r->disagreeing += c->disagreeing;
    r->unchecked += c->unchecked;
    r->areas_compared += c->area_checked;
    r->areas_differ += !c->area_ok;
    if (r->json) {
        fprintf(r->out, "%s{\"index\":%zu,\"z\":", r->first ? "" : ",", L->index);
        cli_json_number(r->out, L->cut);
        fprintf(r->out, ",\"contours\":%zu,\"checked\":%zu,\"confirmed\":%zu,\"disagreeing\":%zu,\"unchecked\":%zu,"
                        "\"net_area\":",
                L->ncontours, c->checked, c->confirmed, c->disagreeing, c->unchecked);
        cli_json_number(r->out, c->net_area);
        fputs(",\"section_area\":", r->out);
        cli_json_number(r->out, c->area_checked ? c->section_area : NAN);
        fputs(",\"area_tolerance\":", r->out);
        cli_json_number(r->out, c->area_checked ? c->area_tolerance : NAN);
        fputs(",\"area_lost\":", r->out);
        cli_json_number(r->out, c->area_checked ? c->area_lost : NAN);
        fprintf(r->out, ",\"area_loss_check\":%s,\"area_ok\":%s,\"area\":", c->area_loose ? "true" : "false",
                c->area_ok ? "true" : "false");
        cli_json_string(r->out, c->area_why ? c->area_why : "");
        fputs(",\"disagreements\":[", r->out);
        int firstd = 1;
        for (size_t i = 0; i < c->nitems; i++) {
            if (c->items[i].ok != 0) continue;
            if (!firstd) fputc(',', r->out);
            json_contour(r->out, L, &c->items[i], src);
            firstd = 0;
        }
        fputs("]}", r->out);
        r->first = 0;
    } else {
        if (r->verbose || c->disagreeing || c->unchecked || !c->area_ok) {
            cli_progress_hide(r->progress);
            fprintf(r->out, "layer %zu (h=%s): %zu contour%s, %zu confirmed, %zu disagreeing%s\n", L->index + 1,
                    LAM_NUM(L->cut), L->ncontours, L->ncontours == 1 ? "" : "s", c->confirmed, c->disagreeing,
                    c->unchecked ? ", some too small to check" : "");
        }
        for (size_t i = 0; i < c->nitems; i++)
            if (c->items[i].ok <= 0) text_contour(r->out, L, &c->items[i], src);
        if (!c->area_ok) text_area(r->out, c);
    }
}

/* What validate adds up over its layers beyond vreport's counts: the
 * area lost or added on the layers that differ, and the layers whose area
 * could not be compared because the model stays open. */
typedef struct vareas {
    const lam_model *ref;    /* the model checked against */
    size_t open;             /* layers not compared: its section does not close */
    size_t loss_checked;     /* layers compared by the loss check (validate.h) */
    size_t lost_layers, added_layers;  /* differing layers lacking area, holding more */
    double lost, lost_section;         /* over lost_layers: the area lacking, their sections */
    double added;                      /* over added_layers: the area beyond the section */
} vareas;

static void vareas_add(vareas *t, const lam_layer_check *c)
{
    t->open += c->area_open;
    t->loss_checked += c->area_checked && c->area_loose;
    if (c->area_ok) return;
    if (c->area_lost > 0) {
        t->lost_layers++;
        t->lost += c->area_lost;
        t->lost_section += c->section_area;
    } else {
        t->added_layers++;
        t->added -= c->area_lost;
    }
}

/* Why the areas were not compared, for the summary, the JSON and the
 * warning: "the model stays open (223 boundary edges after repair)". */
static void open_why(char *buf, size_t size, const lam_model *ref)
{
    const lam_model_stats *st = &ref->stats;
    int n = snprintf(buf, size, "the model stays open (%zu boundary edge%s", st->boundary_edges,
                     st->boundary_edges == 1 ? "" : "s");
    if (n > 0 && (size_t)n < size && st->orientation_conflicts)
        n += snprintf(buf + n, size - n, ", %zu edge%s that cannot be oriented", st->orientation_conflicts,
                      st->orientation_conflicts == 1 ? "" : "s");
    if (n > 0 && (size_t)n < size) snprintf(buf + n, size - n, "%s)", ref->repair.ran ? " after repair" : ", not repaired");
}

static void finish_json(vreport *r, const vareas *t)
{
    fprintf(r->out, "],\"checked\":%zu,\"confirmed\":%zu,\"disagreeing\":%zu,\"unchecked\":%zu,"
                    "\"areas_compared\":%zu,\"areas_differing\":%zu",
            r->checked, r->confirmed, r->disagreeing, r->unchecked, r->areas_compared, r->areas_differ);
    if (!t) return;
    fprintf(r->out, ",\"areas_loss_checked\":%zu,\"areas_lost\":%zu,\"area_lost\":", t->loss_checked,
            t->lost_layers);
    cli_json_number(r->out, t->lost);
    fprintf(r->out, ",\"areas_added\":%zu,\"area_added\":", t->added_layers);
    cli_json_number(r->out, t->added);
    fprintf(r->out, ",\"areas_not_compared\":%zu,\"areas_not_compared_why\":", t->open);
    if (t->open) {
        char why[200];
        open_why(why, sizeof why, t->ref);
        cli_json_string(r->out, why);
    } else {
        fputs("null", r->out);
    }
}

/* The text summary's area part: "; net area against the section in 40
 * layers (12 allowing for gap closing), 3 differ: 942 lost (100% of their
 * sections)", or that it was not compared. */
static void finish_text_areas(vreport *r, const vareas *t)
{
    char why[200] = "";
    if (t && t->open) open_why(why, sizeof why, t->ref);
    if (t && t->open && !r->areas_compared) {
        fprintf(r->out, "; net area not compared: %s\n", why);
    } else {
        fprintf(r->out, "; net area against the section in %zu layer%s", r->areas_compared,
                r->areas_compared == 1 ? "" : "s");
        if (t && t->loss_checked) fprintf(r->out, " (%zu allowing for gap closing)", t->loss_checked);
        fprintf(r->out, ", %zu differ%s", r->areas_differ, r->areas_differ == 1 ? "s" : "");
        if (t && t->lost_layers)
            fprintf(r->out, ": %.6g lost in %zu layer%s (%.3g%% of their sections)", t->lost, t->lost_layers,
                    t->lost_layers == 1 ? "" : "s", t->lost_section > 0 ? 100 * t->lost / t->lost_section : 100.0);
        if (t && t->added_layers)
            fprintf(r->out, "%s%.6g more than the model has in %zu layer%s", t->lost_layers ? ", " : ": ", t->added,
                    t->added_layers, t->added_layers == 1 ? "" : "s");
        if (t && t->open) fprintf(r->out, "; not compared in %zu layer%s: %s", t->open, t->open == 1 ? "" : "s", why);
        fputc('\n', r->out);
    }
}

/* The report's last line (text) or closing fields (JSON), and the exit
 * status; t (NULL for slice --validate) adds validate's area totals. */
static int report_finish(vreport *r, const char *what, const vareas *t)
{
    if (r->json) {
        finish_json(r, t);
    } else {
        fprintf(r->out, "%s: %zu layers, %zu contours checked, %zu confirmed, %zu disagreeing", what, r->layers,
                r->checked, r->confirmed, r->disagreeing);
        if (r->unchecked) fprintf(r->out, ", %zu too small to check", r->unchecked);
        finish_text_areas(r, t);
    }
    /* an area that could not be verified is no failure of the program, but
     * must not pass unseen: a warning on stderr too, whatever -q says */
    if (t && t->open) {
        char why[200];
        open_why(why, sizeof why, t->ref);
        fprintf(stderr, "lamina: warning: %s: net area not compared on %zu layer%s: %s; the program's area is not "
                        "verified\n", t->ref->path, t->open, t->open == 1 ? "" : "s", why);
    }
    return r->disagreeing || r->areas_differ ? EXIT_CHECK : EXIT_OK;
}

int vreport_finish(vreport *r, const char *what) { return report_finish(r, what, NULL); }

/* The model as loaded (the layers are made from it) and the one they are
 * checked against. */
typedef struct vmodels {
    lam_model *m;
    lam_model *ref;          /* m, or a repaired copy of it (owned) */
    vareas areas;
} vmodels;

/* A copy of m repaired (repair.h) into *out: its mesh as loaded (the load
 * options' transform applied), rebuilt and repaired, as loading it without
 * --no-repair would have made it. LAM_ENOMEM, or LAM_OK with *out NULL
 * when the repair failed otherwise (err says why). */
static int repaired_copy(const lam_model *m, lam_model **out, lam_error *err)
{
    *out = NULL;
    lam_mesh mesh;
    int rc = lam_mesh_copy(&m->mesh, &mesh, err);
    if (rc) return rc;
    if ((rc = lam_model_from_mesh(&mesh, m->path, m->format, out, err))) return rc;
    if ((rc = lam_model_repair(out, NULL, err))) {
        lam_model_free(*out);
        *out = NULL;
    }
    return rc == LAM_ENOMEM ? rc : LAM_OK;
}

/* vm->ref: the repaired model. Loaded with --no-repair, m is the mesh as
 * the file has it; when repair would change it (open or non-manifold
 * edges: repair.h leaves other models alone) the reference is a repaired
 * copy, so the rays and the sections say what the part should be where
 * m's outlines stay open. A repair that fails leaves m as the reference
 * (said on stderr; its areas are then not compared when it is open). */
static int reference_model(const args *a, vmodels *vm, lam_error *err)
{
    lam_model *m = vm->m;
    vm->ref = m;
    vm->areas.ref = m;
    if (!a->no_repair || (!m->stats.boundary_edges && !m->stats.nonmanifold_edges)) return LAM_OK;
    lam_error why;
    lam_error_clear(&why);
    lam_model *c;
    int rc = repaired_copy(m, &c, &why);
    if (rc) {
        *err = why;
        return rc;
    }
    if (!c) {
        char buf[1024];
        fprintf(stderr, "lamina: warning: %s: repairing a copy to check against failed (%s); checked against the "
                        "mesh as it is\n", m->path, lam_error_format(&why, buf, sizeof buf));
        return LAM_OK;
    }
    vm->ref = c;
    vm->areas.ref = c;
    if (a->talk >= 0) {
        char line[512];
        lam_repair_summary(&c->repair, line, sizeof line);
        fprintf(stderr, "lamina: %s: sliced as the file has it (--no-repair), checked against a repaired copy%s%s\n",
                m->path, line[0] ? ": " : "", line);
    }
    return LAM_OK;
}

/* The checks' options common to every layer: the fill rule, and what the
 * reference is against the mesh sliced (validate.h) with the gap its
 * outlines were closed with. */
static void base_opts(const args *a, const vmodels *vm, double gap, lam_validate_opts *o)
{
    lam_validate_opts_init(o);
    o->fill_nonzero = a->so.fill_nonzero;
    o->gap = gap;
    const lam_repair_report *rr = &vm->ref->repair;
    o->moved = vm->ref != vm->m && rr->welded ? rr->weld_tolerance : 0;
}

/* The gap-closing tolerance of the slicing the options give, resolved as
 * lam_slicer_new resolves the automatic one (the model's diagonal). */
static double run_gap(const args *a, const lam_model *m)
{
    if (a->so.gap >= 0) return a->so.gap;
    const double *b = m->stats.bbox;
    double d = sqrt((b[3] - b[0]) * (b[3] - b[0]) + (b[4] - b[1]) * (b[4] - b[1]) + (b[5] - b[2]) * (b[5] - b[2]));
    return lam_default_gap(isfinite(d) ? d : 0, a->so.gap_limit);
}

/* The layers of a program read back, each checked as it is written: the
 * program is read whole first (on this thread), then the workers make
 * each layer from it and check it (validate_run.h). */
typedef struct pjob {
    const args *a;
    const lam_program *p;
    const lam_frame *f;
    int frame_machine, below;
    lam_validate_opts vo;
    vreport *r;
    vareas *areas;
} pjob;

static int program_layer(void *ctx, unsigned worker, lam_rays *v, size_t i, lam_vlayer *out, lam_error *err)
{
    (void)worker;
    const pjob *j = ctx;
    const lam_program *p = j->p;
    lam_layer *L = calloc(1, sizeof *L);
    if (!L) return lam_error_nomem(err, "while validating");
    lam_section_index *sec; /* the worker's own (lam_rays_fork) */
    int rc = lam_rays_section(v, j->f, &sec, err);
    if (!rc) rc = lam_program_layer_make(p, i, j->f, j->frame_machine, j->a->program, L, err);
    if (rc) {
        free(L);
        return rc;
    }
    /* a height written on a flat face's plane (to its precision) means
     * that plane, and the side the cut says */
    double h = L->cut;
    rc = lam_section_snap(sec, h, p->quantum_z * (1 + 1e-9), &L->cut, err);
    double prev = i ? p->layers[i - 1].z : h - 1, next = i + 1 < p->nlayers ? p->layers[i + 1].z : h + 1;
    L->floor = j->below ? prev : L->cut;
    L->ceiling = j->below ? L->cut : next;
    L->width = L->ceiling - L->floor;
    if (rc) {
        lam_layer_free(L);
        return rc;
    }
    out->L = out->owned = L;
    out->f = j->f;
    out->o = j->vo;
    return LAM_OK;
}

static int program_report(void *ctx, size_t i, const lam_vlayer *l, lam_layer_check *chk, lam_error *err)
{
    (void)err;
    const pjob *j = ctx;
    cli_progress_step(j->r->progress, i + 1);
    const lam_program_layer *pl = &j->p->layers[i];
    vsource src = { j->a->program, pl->n ? j->p->contours + pl->first : NULL };
    vreport_check(j->r, l->L, chk, &src);
    vareas_add(j->areas, chk);
    return LAM_OK;
}

/* ---- does the program cover the model? ------------------------------------------- */

static int layer_error(lam_error *err, const char *path, const lam_program_layer *pl, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static int layer_error(lam_error *err, const char *path, const lam_program_layer *pl, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = lam_error_vset(err, LAM_EINVAL, path, pl && pl->offset < 0 ? pl->line : 0,
                            pl && pl->offset < 0 ? pl->column : 0, pl ? pl->offset : -1, fmt, ap);
    va_end(ap);
    return rc;
}

/* Whether a layer of the slicing at h must be in the program: the model
 * has material there, more than a first pass inset by `inset` can lose
 * whole (a region within inset of its outline has at most about perimeter
 * x inset of area; twice that is allowed). */
static int has_material(lam_section_index *sec, double h, int below, double inset)
{
    lam_section_measure sm;
    lam_section_measure_at(sec, h, below, &sm);
    if (!sm.segments) return 0;
    if (!sm.closed) return 1;
    return sm.area > fmax(2 * inset * sm.perimeter, 1e-9 * sm.perimeter * sm.perimeter);
}

/* What the program's heights are compared with, for messages. */
static void units_note(char *buf, size_t size, const lam_program *p, double scale)
{
    if (scale == 1) buf[0] = '\0';
    else snprintf(buf, size, " ($$UNITS/%g: one unit of the program is %g of the model's)", p->units_mm, scale);
}

/* The layers of a run's JSON against the model's extent: the slabs it
 * gives (floor, ceiling) follow each other from the model's bottom to its
 * top, each once. */
static int covers_slabs(const lam_model *m, const lam_frame *f, const char *path, const lam_program *p,
                        lam_error *err)
{
    double lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < m->mesh.nverts; i++) {
        const double *q = m->mesh.xyz + 3 * i;
        double h = q[0] * f->w[0] + q[1] * f->w[1] + q[2] * f->w[2];
        lo = fmin(lo, h);
        hi = fmax(hi, h);
    }
    double tol = 1e-9 * fmax(hi - lo, fmax(fabs(lo), fabs(hi)));
    if (!p->nlayers) return layer_error(err, path, NULL, "the run has no layers: the model spans %s to %s", LAM_NUM(lo), LAM_NUM(hi));
    for (size_t i = 0; i < p->nlayers; i++) {
        const lam_program_layer *pl = &p->layers[i];
        double below = i ? p->layers[i - 1].ceiling : lo;
        if (fabs(pl->floor - below) > tol)
            return layer_error(err, path, pl,
                               "layer %zu starts at %s, not where %s ends (%s): layers missing, repeated or out of order",
                               i + 1, LAM_NUM(pl->floor), i ? "the layer before it" : "the model", LAM_NUM(below));
        if (!(pl->ceiling > pl->floor) || pl->z < pl->floor - tol || pl->z > pl->ceiling + tol)
            return layer_error(err, path, pl, "layer %zu: its height %s is not in its slab %s to %s", i + 1,
                               LAM_NUM(pl->z), LAM_NUM(pl->floor), LAM_NUM(pl->ceiling));
    }
    if (p->layers[p->nlayers - 1].ceiling < hi - tol)
        return layer_error(err, path, &p->layers[p->nlayers - 1], "the last layer ends at %s, below the model's top (%s)",
                           LAM_NUM(p->layers[p->nlayers - 1].ceiling), LAM_NUM(hi));
    return LAM_OK;
}

/* The program's layers against the slicing the options give (-w,
 * --widths, --planes, --cut, -a and the profile's layer_width): each at the
 * height of one of its layers, once, in order; a layer of the slicing may
 * be missing only where the model has no material (has_material). */
static int covers_slicing(const args *a, const lam_model *m, const lam_frame *f, lam_section_index *sec, int below,
                          double inset, double scale, const lam_program *p, lam_error *err)
{
    lam_slice_opts so = a->so;
    so.frame = *f;
    lam_slicer *s;
    int rc = lam_slicer_new(m, &so, &s, err);
    if (rc) return rc;
    size_t S = lam_slicer_count(s), j = 0;
    char note[160];
    units_note(note, sizeof note, p, scale);
    const char *path = a->program;
    for (size_t i = 0; i < p->nlayers && !rc; i++) {
        const lam_program_layer *pl = &p->layers[i];
        double z = pl->z;
        for (; !rc && j < S && lam_slicer_cut(s, j) < z - p->quantum_z * (1 + 1e-6) - 4 * DBL_EPSILON * fabs(z); j++)
            if (has_material(sec, lam_slicer_cut(s, j), below, inset))
                rc = layer_error(err, path, pl,
                                 "layer %zu of the slicing (h=%s) is not in the program, which goes on at h=%s%s: "
                                 "the model has material there",
                                 j + 1, LAM_NUM(lam_slicer_cut(s, j)), LAM_NUM(z), note);
        if (rc) break;
        double c = j < S ? lam_slicer_cut(s, j) : NAN;
        if (j < S && fabs(c - z) <= p->quantum_z * (1 + 1e-6) + 4 * DBL_EPSILON * fabs(z)) {
            j++;
            continue;
        }
        if (i && z <= p->layers[i - 1].z)
            rc = layer_error(err, path, pl, "layer %zu (h=%s) is not above the layer before it (h=%s): every layer "
                                            "of the model must be written once, in order", i + 1, LAM_NUM(z),
                             LAM_NUM(p->layers[i - 1].z));
        else
            rc = layer_error(err, path, pl, "layer %zu (h=%s) is not at a height of the slicing the options give "
                                            "(%zu layers from h=%s to %s)%s: give validate the options the program "
                                            "was sliced with", i + 1, LAM_NUM(z), S,
                             LAM_NUM(S ? lam_slicer_cut(s, 0) : 0), LAM_NUM(S ? lam_slicer_cut(s, S - 1) : 0), note);
    }
    for (; !rc && j < S; j++)
        if (has_material(sec, lam_slicer_cut(s, j), below, inset))
            rc = layer_error(err, path, p->nlayers ? &p->layers[p->nlayers - 1] : NULL,
                             "layer %zu of the slicing (h=%s) is not in the program, which %s%s: the model has material "
                             "there", j + 1, LAM_NUM(lam_slicer_cut(s, j)), p->nlayers ? "ends before it" : "has no layers",
                             note);
    lam_slicer_free(s);
    return rc;
}

/* The program's coordinates in the model's units: a CLI program says in
 * $$UNITS how many millimetres one of its units is, the profile's `units`
 * what one model unit is. */
static int program_units(const lam_profile *prof, const char *path, lam_program *p, double *scale, lam_error *err)
{
    *scale = 1;
    if (!(p->units_mm > 0)) return LAM_OK;
    double mm = lam_profile_unit_mm(prof);
    if (!(mm > 0))
        return lam_error_set(err, LAM_EINVAL, path, p->units_line, p->units_column,
                             "$$UNITS gives millimetres, but the profile's units are not a length lamina knows "
                             "(mm, cm, m, um, in, inch, ft)");
    *scale = p->units_mm / mm;
    if (*scale != 1) lam_program_scale(p, *scale);
    return LAM_OK;
}

/* The contour passes the options say the program holds (validate.h); a
 * run's JSON holds the layers' contours themselves. */
static int program_passes(const lam_plan_opts *po, const lam_program *p, lam_validate_opts *vo, lam_error *err)
{
    if (po->kind != LAM_PLAN_SLS || p->format == LAM_PROGRAM_JSON) return LAM_OK;
    if (po->scan.contour_count == 0)
        return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0,
                             "contour_count is 0: a program of no contour passes has no contours to check");
    vo->passes = po->scan.contour_count;
    vo->inset = po->beam_offset ? po->bead / 2 : 0;
    vo->pass_distance = po->scan.contour_distance;
    return LAM_OK;
}

static int validate_program(const args *a, const lam_profile *prof, const lam_plan_opts *po, vmodels *vm,
                            lam_rays *v, vreport *r, int *uncovered, lam_error *err)
{
    const lam_model *m = vm->m;
    lam_program *p = NULL;
    int rc = lam_program_read(a->program, &p, err);
    /* the report sent to the program (> or >>) is said first: the
     * program is read (or found empty) only to be destroyed */
    int out = cli_stdout_check(err);
    if (out && p) lam_program_free(p);
    if (out || rc) return out ? out : rc;
    double scale = 1;
    if ((rc = program_units(prof, a->program, p, &scale, err))) {
        lam_program_free(p);
        return rc;
    }
    pjob j;
    memset(&j, 0, sizeof j);
    j.a = a;
    j.p = p;
    j.r = r;
    j.areas = &vm->areas;
    /* a run's JSON says its own axis and frame (-a and --frame are for
     * programs that do not) */
    j.f = p->has_frame ? &p->frame : &a->so.frame;
    j.frame_machine = po->frame_machine; /* (a JSON's points are read in the layer frame) */
    j.below = a->so.cut == LAM_CUT_CEILING;
    /* the model's sections, and its sorted heights made now (a snap that
     * moves nothing), so the workers' indexes share them */
    lam_section_index *sec = NULL;
    double unused;
    if ((rc = lam_rays_section(v, j.f, &sec, err)) || (rc = lam_section_snap(sec, 0, 0, &unused, err))) {
        lam_program_free(p);
        return rc;
    }
    base_opts(a, vm, run_gap(a, m), &j.vo);
    /* sliced from the mesh before repair, any layer may have had gaps
     * bridged or outlines dropped: the program does not say which */
    j.vo.gaps_unknown = vm->ref != vm->m;
    j.vo.quantum_uv = p->quantum_xy;
    j.vo.quantum_h = p->quantum_z;
    if ((rc = program_passes(po, p, &j.vo, err))) {
        lam_program_free(p);
        return rc;
    }
    /* every layer of the model, once (a run's JSON gives its own slabs) */
    int slabs = p->format == LAM_PROGRAM_JSON && p->nlayers && isfinite(p->layers[0].floor);
    rc = slabs ? covers_slabs(m, j.f, a->program, p, err)
               : covers_slicing(a, m, j.f, sec, j.below, j.vo.passes ? j.vo.inset : 0, scale, p, err);
    if (rc) {
        *uncovered = rc == LAM_EINVAL;
        lam_program_free(p);
        return rc;
    }
    if (r->json) {
        fputs("{\"model\":", r->out);
        cli_json_string(r->out, a->path);
        fputs(",\"program\":", r->out);
        cli_json_string(r->out, a->program);
        fprintf(r->out, ",\"format\":\"%s\",\"fill\":\"%s\",\"layers\":[", lam_program_format_name(p->format),
                a->so.fill_nonzero ? "nonzero" : "evenodd");
    }
    cli_progress_begin(r->progress, "validating", a->program, p->nlayers);
    rc = lam_validate_layers(v, p->nlayers, a->threads, j.f, program_layer, program_report, &j, err);
    cli_progress_end(r->progress);
    if (!rc && !r->json)
        fprintf(r->out, "%s: %s program, %zu layers, %zu contours, read back\n", a->program,
                lam_program_format_name(p->format), p->nlayers, p->ncontours);
    lam_program_free(p);
    return rc;
}

/* The layers sliced here: the workers slice and check them
 * (validate_run.h), this thread reports them in order. */
typedef struct sjob {
    vreport *r;
    vareas *areas;
    size_t open;             /* outlines left open, over the layers reported */
} sjob;

static int slice_report(void *ctx, size_t i, const lam_vlayer *l, lam_layer_check *chk, lam_error *err)
{
    (void)i, (void)err;
    sjob *j = ctx;
    cli_progress_step(j->r->progress, l->L->index + 1);
    j->open += l->L->nopen;
    vreport_check(j->r, l->L, chk, NULL);
    vareas_add(j->areas, chk);
    return LAM_OK;
}

/* lamina validate without --program: the model sliced and every layer
 * checked (rays v), reported through r. Returns the exit code. */
static int validate_slices(args *a, const lam_profile *prof, vmodels *vm, lam_rays *v, vreport *r,
                           cli_progress *progress)
{
    lam_model *m = vm->m;
    lam_error err;
    lam_error_clear(&err);
    lam_slicer *s = NULL;
    int rc;
    if (lam_slicer_new(m, &a->so, &s, &err)) {
        rc = err.code == LAM_EUSAGE ? cli_usage("validate", "%s", err.msg) : cli_fail_limit(&err, 0, CLI_RAISE_LAYERS);
        goto out;
    }
    if (r->json) {
        fputs("{\"model\":", stdout);
        cli_json_string(stdout, a->path);
        fprintf(stdout, ",\"fill\":\"%s\",\"layers\":[", a->so.fill_nonzero ? "nonzero" : "evenodd");
    }
    cli_progress_stage(progress, "preparing the layers");
    cli_size_sense(a->path, a->machine ? prof : NULL, m, s, NULL);
    cli_progress_begin(progress, "validating", a->path, lam_slicer_count(s));
    lam_validate_opts vo;
    base_opts(a, vm, lam_slicer_gap(s), &vo);
    sjob sj = { r, &vm->areas, 0 };
    int vrc = lam_validate_slicer(s, v, &vo, a->threads, slice_report, &sj, &err);
    cli_progress_end(progress);
    if (vrc) {
        rc = cli_fail(&err);
        goto out;
    }
    size_t open = sj.open;
    rc = report_finish(r, a->path, &vm->areas);
    if (r->json) printf(",\"open_outlines\":%zu}\n", open);
    if (open && !a->allow_open) {
        fprintf(stderr, "lamina: %s: %zu outline%s stayed open (gap tolerance %g); use --gap or --allow-open\n", a->path,
                open, open == 1 ? "" : "s", lam_slicer_gap(s));
        rc = EXIT_INPUT;
    }
out:
    lam_slicer_free(s);
    return rc;
}

int cmd_validate(int argc, char **argv)
{
    args a;
    int rc = cli_parse_args("validate", usage_text, OPT_MODEL | OPT_SLICE | OPT_SET | OPT_JSON | OPT_PROGRAM | OPT_TALK | OPT_JOBS,
                            argc, argv, &a);
    if (rc) {
        cli_args_free(&a);
        return rc < 0 ? EXIT_OK : rc;
    }
    lam_error err;
    lam_error_clear(&err);
    lam_profile *prof = NULL;
    vmodels vm;
    memset(&vm, 0, sizeof vm);
    lam_rays *v = NULL;
    vreport r;
    memset(&r, 0, sizeof r);
    r.out = stdout;
    r.json = a.json;
    r.verbose = a.talk >= 0;
    r.first = 1;
    cli_progress progress;
    cli_progress_init(&progress, a.talk, a.json);
    r.progress = &progress;
    lam_plan_opts po;
    lam_plan_opts_init(&po);
    for (size_t i = 0; i < a.nsets && !a.program; i++)
        if (a.sets[i].key->offset == offsetof(lam_profile, frame_machine) ||
            a.sets[i].key->offset == offsetof(lam_profile, beam_offset)) {
            rc = cli_usage("validate", "%s applies to --program only", a.sets[i].shown);
            goto done;
        }
    if ((rc = cli_profile("validate", &a, &prof, &po))) goto done;
    if (cli_load_model(&a, prof, &vm.m, &err)) {
        rc = cli_fail(&err);
        goto done;
    }
    a.path = vm.m->path; /* "<stdin>" for "-" */
    if (reference_model(&a, &vm, &err) || lam_rays_new(vm.ref, &v, &err)) {
        rc = cli_fail(&err);
        goto done;
    }
    cli_progress_stage(&progress, "reading the model and preparing the rays");
    if (a.program) {
        int uncovered = 0;
        int vrc = validate_program(&a, prof, &po, &vm, v, &r, &uncovered, &err);
        cli_progress_end(&progress);
        if (vrc) {
            rc = err.code == LAM_EUSAGE ? cli_usage("validate", "%s", err.msg) : cli_fail(&err);
            /* a program that is not the whole part disagrees with it */
            if (uncovered) rc = EXIT_CHECK;
            goto done;
        }
        rc = report_finish(&r, a.program, &vm.areas);
        if (r.json) fputs("}\n", stdout);
        goto done;
    }
    rc = validate_slices(&a, prof, &vm, v, &r, &progress);
done:
    fflush(stdout);
    lam_rays_free(v);
    if (vm.ref != vm.m) lam_model_free(vm.ref);
    lam_model_free(vm.m);
    lam_profile_free(prof);
    cli_args_free(&a);
    return rc;
}
