/* Setting up a build's plate: models loaded and placed, parts arranged and
 * sliced on the plate's planes, styles and labels numbered (build_plan.h). */
#include "build_run.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"

static char *dup(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

/* The machine's plate, spacing and lasers. */
static int machine_plate(lam_build_run *r, lam_error *err)
{
    const lam_profile *p = r->b->profile;
    lam_plate *pl = &r->plate;
    memset(pl, 0, sizeof *pl);
    if (p->plate_diameter > 0) {
        pl->round = 1;
        pl->diameter = p->plate_diameter;
    } else if (p->plate_width > 0 && p->plate_depth > 0) {
        pl->width = p->plate_width;
        pl->depth = p->plate_depth;
    } else {
        return lam_error_set(err, LAM_EINVAL, r->b->path, 0, 0,
                             "machine %s has no plate: give plate: {width: W, depth: D} or plate: {diameter: D}",
                             p->name);
    }
    pl->margin = p->plate_margin;
    r->spacing = p->spacing;
    lam_laser_set *ls = &r->lasers;
    memset(ls, 0, sizeof *ls);
    ls->n = p->nlasers ? p->nlasers : 1;
    if (ls->n > LAM_LASERS_MAX) ls->n = LAM_LASERS_MAX;
    for (size_t k = 0; k < p->nlasers && k < LAM_LASERS_MAX; k++) memcpy(ls->field[k], p->laser_field[k], sizeof ls->field[k]);
    if (!p->nlasers) { /* one laser that reaches the whole plate */
        double h = pl->round ? pl->diameter / 2 : 0;
        double f[4] = { pl->round ? -h : 0, pl->round ? -h : 0, pl->round ? h : pl->width, pl->round ? h : pl->depth };
        memcpy(ls->field[0], f, sizeof f);
    }
    ls->gas_flow[0] = p->gas_flow[0];
    ls->gas_flow[1] = p->gas_flow[1];
    return LAM_OK;
}

/* The part's model loaded, dropped on the plate at z, its footprint box
 * centred on the origin. */
static int load_part(const lam_build_part *spec, const lam_load_opts *load, lam_model **m, lam_error *err)
{
    lam_xform x = spec->xform;
    x.place = LAM_PLACE_PLATE;
    x.plate_centre[0] = x.plate_centre[1] = 0;
    lam_load_opts o = { .xform = &x, .no_repair = load ? load->no_repair : 0, .threads = load ? load->threads : 0 };
    return lam_model_load_opts(spec->model, &o, m, err);
}

/* A copy of model m moved by (dx, dy, dz), as its own model. */
static int moved_copy(const lam_model *m, const double d[3], lam_model **out, lam_error *err)
{
    lam_mesh mesh;
    lam_mesh_init(&mesh);
    int rc = lam_mesh_copy(&m->mesh, &mesh, err);
    if (rc) return rc;
    for (size_t i = 0; i < mesh.nverts; i++)
        for (int a = 0; a < 3; a++) mesh.xyz[3 * i + a] += d[a];
    return lam_model_from_mesh(&mesh, m->path, m->format, out, err);
}

static void part_name(const lam_build_part *spec, size_t copy, char *buf, size_t size)
{
    char stem[128];
    if (spec->name) snprintf(stem, sizeof stem, "%s", spec->name);
    else lam_job_label(spec->model, stem, sizeof stem);
    if (spec->copies > 1) snprintf(buf, size, "%s_%zu", stem, copy + 1);
    else snprintf(buf, size, "%s", stem);
}

/* A model that does not open is said where the job names it; an error
 * inside the model keeps the model's own position. */
static int load_error(const lam_build_run *r, const lam_build_part *spec, const lam_error *e, lam_error *err)
{
    if (e->code != LAM_EIO || !spec->line) {
        if (err) *err = *e;
        return e->code;
    }
    return lam_error_set(err, e->code, r->b->path, spec->line, spec->column, "model %s: %s", spec->model, e->msg);
}

/* The parts' models, one per job part, and the arrangement's items, one
 * per copy. */
static int load_all(lam_build_run *r, const lam_load_opts *load, lam_model **models, lam_arrange_item *items,
                    lam_error *err)
{
    size_t n = 0;
    for (size_t i = 0; i < r->b->nparts; i++) {
        const lam_build_part *spec = &r->b->parts[i];
        lam_error e;
        lam_error_clear(&e);
        int rc = load_part(spec, load, &models[i], &e);
        if (rc) return load_error(r, spec, &e, err);
        const double *bb = models[i]->stats.bbox;
        for (size_t c = 0; c < spec->copies; c++, n++) {
            lam_run_part *p = &r->parts[n];
            p->spec = i;
            part_name(spec, c, p->name, sizeof p->name);
            lam_arrange_item *it = &items[n];
            double box[4] = { bb[0], bb[1], bb[3], bb[4] };
            memcpy(it->box, box, sizeof box);
            it->fixed = spec->has_at;
            it->at[0] = spec->at[0];
            it->at[1] = spec->at[1];
            it->name = p->name;
        }
    }
    return LAM_OK;
}

/* Whether the build's machine makes supports. */
static int supported(const lam_build_run *r)
{
    return r->b->profile->process == LAM_PROCESS_SLS && r->b->profile->scan.support.type != LAM_SUPPORT_NONE;
}

/* The part's supports (support.h) over its run, from the plate up. */
static int support_part(lam_run_part *p, lam_error *err)
{
    if (p->po.scan.support.type == LAM_SUPPORT_NONE) return LAM_OK;
    lam_layer **L = NULL;
    size_t n = 0;
    int rc = lam_slicer_all(p->slicer, &L, &n, err);
    if (!rc) rc = lam_supports_make((const lam_layer *const *)L, n, &p->po.scan.support, &p->supports, err);
    lam_layers_free(L, n);
    if (rc && err) {
        char msg[sizeof err->msg];
        snprintf(msg, sizeof msg, "%s", err->msg);
        lam_error_set(err, rc, NULL, 0, 0, "part %s: %s", p->name, msg);
    }
    p->po.supports = p->supports;
    return rc;
}

/* Planes k w for the plate layers the part reaches. */
static int slice_part(lam_build_run *r, lam_run_part *p, lam_error *err)
{
    const double *bb = p->model->stats.bbox;
    double w = r->width;
    /* with supports a part's run starts at the plate: they stand on it */
    size_t first = supported(r) ? 0 : (size_t)floor(bb[2] / w + 1e-9);
    size_t end = (size_t)ceil(bb[5] / w - 1e-9);
    if (end <= first) end = first + 1;
    if (end - first > LAM_DEFAULT_MAX_LAYERS)
        return lam_error_set(err, LAM_ELIMIT, NULL, 0, 0, "part %s: %zu layers, more than %d", p->name, end - first,
                             LAM_DEFAULT_MAX_LAYERS);
    double *planes = malloc((end - first + 1) * sizeof *planes);
    if (!planes) return lam_error_nomem(err, "slicing a part");
    for (size_t k = first; k <= end; k++) planes[k - first] = (double)k * w;
    lam_slice_opts so;
    lam_slice_opts_init(&so);
    so.cut = r->cut;
    so.gap = r->b->profile->gap;
    so.gap_limit = lam_profile_gap_limit(r->b->profile);
    so.planes = planes;
    so.nplanes = end - first + 1;
    int rc = lam_slicer_new(p->model, &so, &p->slicer, err);
    free(planes);
    p->first = first;
    p->count = end - first;
    p->zmax = bb[5];
    return rc;
}

/* ---- styles ---------------------------------------------------------------- */

/* Style numbers: the part regions' own first (contour, core, upskin,
 * downskin: 1 to 4), then the job's other styles, then the support's when
 * the machine makes supports (last, so a build without supports numbers
 * its styles as before supports existed). */
static int number_styles(lam_build_run *r, lam_error *err)
{
    const lam_build *b = r->b;
    r->styles = calloc(LAM_REGIONS + b->nstyles, sizeof *r->styles);
    if (!r->styles) return lam_error_nomem(err, "numbering build styles");
    for (int k = 0; k < LAM_KIND_SUPPORT; k++)
        if (!(r->styles[r->nstyles++] = dup(lam_kind_name(k)))) return lam_error_nomem(err, "numbering build styles");
    for (size_t i = 0; i < b->nstyles; i++)
        if (lam_region_find(b->styles[i].name) < 0 && !(r->styles[r->nstyles++] = dup(b->styles[i].name)))
            return lam_error_nomem(err, "numbering build styles");
    if (supported(r) && !(r->styles[r->nstyles++] = dup(lam_kind_name(LAM_KIND_SUPPORT))))
        return lam_error_nomem(err, "numbering build styles");
    return LAM_OK;
}

static int style_number(const lam_build_run *r, const char *name)
{
    for (size_t s = 0; s < r->nstyles; s++)
        if (!strcmp(r->styles[s], name)) return (int)s + 1;
    return 0;
}

/* The part's styled profile and planning options, and its regions' style
 * numbers: the job's styles named after a region first (every part's
 * default), then the part's own. */
static int style_part(lam_build_run *r, lam_run_part *p, lam_error *err)
{
    const lam_build *b = r->b;
    const lam_build_part *spec = &b->parts[p->spec];
    const lam_build_style *defaults[LAM_REGIONS] = { 0 }, *own[LAM_REGIONS] = { 0 };
    for (int k = 0; k < LAM_REGIONS; k++) {
        int d = lam_build_style_find(b, lam_kind_name(k));
        if (spec->style[k] < 0 && d >= 0) defaults[k] = &b->styles[d];
        if (spec->style[k] >= 0) own[k] = &b->styles[spec->style[k]];
        p->style_id[k] = style_number(r, own[k] ? own[k]->name : lam_kind_name(k));
        if (own[k] && lam_region_find(own[k]->name) >= 0)
            p->style_id[k] = style_number(r, lam_kind_name(lam_region_find(own[k]->name)));
        if (k == LAM_KIND_SUPPORT && !supported(r)) p->style_id[k] = 0; /* no supports: no style */
    }
    lam_profile tmp;
    int rc = lam_build_styled_profile(b->profile, defaults, 0, b->path, &tmp, err);
    if (!rc) rc = lam_build_styled_profile(&tmp, own, spec->style_whole, b->path, &p->styled, err);
    if (rc) return rc;
    lam_plan_opts_from_profile(&p->po, &p->styled);
    p->po.threads = 1;
    return LAM_OK;
}

/* ---- labels ---------------------------------------------------------------- */

long long lam_build_run_label(const lam_build_run *r, long long part, long long style, long long laser)
{
    if (part < 1 || (size_t)part > r->nparts || style < 1 || (size_t)style > r->nstyles || laser < 1 ||
        (size_t)laser > r->lasers.n)
        return 0;
    size_t i = ((size_t)(part - 1) * r->nstyles + (size_t)(style - 1)) * r->lasers.n + (size_t)(laser - 1);
    return r->label_of[i];
}

static int boxes_meet(const double a[4], const double b[4])
{
    return a[0] <= b[2] && b[0] <= a[2] && a[1] <= b[3] && b[1] <= a[3];
}

static int add_label(lam_build_run *r, size_t i, const lam_run_part *p, int s, size_t l, lam_error *err)
{
    if (r->label_of[i]) return LAM_OK;
    char text[256];
    snprintf(text, sizeof text, "%s:%s:%zu", p->name, r->styles[s - 1], l + 1);
    if (!(r->labels[r->nlabels] = dup(text))) return lam_error_nomem(err, "naming the build's labels");
    r->label_of[i] = (long long)++r->nlabels;
    return LAM_OK;
}

/* An id for every (part, style, laser) the plate can use, in that order. */
static int number_labels(lam_build_run *r, lam_error *err)
{
    size_t n = r->nparts * r->nstyles * r->lasers.n;
    r->label_of = calloc(n ? n : 1, sizeof *r->label_of);
    r->labels = calloc(n ? n : 1, sizeof *r->labels);
    if (!r->label_of || !r->labels) return lam_error_nomem(err, "naming the build's labels");
    for (size_t pi = 0; pi < r->nparts; pi++) {
        const lam_run_part *p = &r->parts[pi];
        for (int k = 0; k < LAM_REGIONS; k++) {
            if (!lam_scan_region_used(&p->po.scan, k)) continue;
            int s = p->style_id[k];
            for (size_t l = 0; l < r->lasers.n; l++) {
                if (!boxes_meet(p->box, r->lasers.field[l])) continue;
                int rc = add_label(r, (pi * r->nstyles + (size_t)(s - 1)) * r->lasers.n + l, p, s, l, err);
                if (rc) return rc;
            }
        }
    }
    return LAM_OK;
}

/* ---- the lasers' reach ----------------------------------------------------------- */

/* Whether the union of the fields covers box (every cell of the grid the
 * fields' edges cut the box into lies in some field). */
static int covered(const lam_laser_set *ls, const double box[4])
{
    double xs[2 * LAM_LASERS_MAX + 2], ys[2 * LAM_LASERS_MAX + 2];
    size_t nx = 0, ny = 0;
    xs[nx++] = box[0], xs[nx++] = box[2], ys[ny++] = box[1], ys[ny++] = box[3];
    for (size_t l = 0; l < ls->n; l++) {
        for (int k = 0; k < 4; k += 2)
            if (ls->field[l][k] > box[0] && ls->field[l][k] < box[2]) xs[nx++] = ls->field[l][k];
        for (int k = 1; k < 4; k += 2)
            if (ls->field[l][k] > box[1] && ls->field[l][k] < box[3]) ys[ny++] = ls->field[l][k];
    }
    for (size_t i = 0; i < nx; i++)
        for (size_t j = 0; j < ny; j++) {
            /* a cell's centre: a point between this cut and the nearest one above */
            double x1 = box[2], y1 = box[3];
            for (size_t k = 0; k < nx; k++) if (xs[k] > xs[i] && xs[k] < x1) x1 = xs[k];
            for (size_t k = 0; k < ny; k++) if (ys[k] > ys[j] && ys[k] < y1) y1 = ys[k];
            if (xs[i] >= box[2] || ys[j] >= box[3]) continue;
            double cx = (xs[i] + x1) / 2, cy = (ys[j] + y1) / 2;
            int in = 0;
            for (size_t l = 0; l < ls->n && !in; l++)
                in = cx >= ls->field[l][0] && cx <= ls->field[l][2] && cy >= ls->field[l][1] && cy <= ls->field[l][3];
            if (!in) return 0;
        }
    return 1;
}

/* Every part within the lasers' reach, said before anything is planned. */
static int check_reach(const lam_build_run *r, lam_error *err)
{
    for (size_t i = 0; i < r->nparts; i++) {
        const lam_run_part *p = &r->parts[i];
        if (covered(&r->lasers, p->box)) continue;
        const lam_build_part *spec = &r->b->parts[p->spec];
        return lam_error_set(err, LAM_EINVAL, r->b->path, spec->line, spec->column,
                             "part %s (%g .. %g x %g .. %g on the plate) is not within the lasers' fields "
                             "(%zu laser%s): give the machine lasers: [{field: [x0, y0, x1, y1]}, ...] that "
                             "reach it", p->name, p->box[0], p->box[2], p->box[1], p->box[3], r->lasers.n,
                             r->lasers.n == 1 ? "" : "s");
    }
    return LAM_OK;
}

/* ---- the run ----------------------------------------------------------------- */

/* Every copy moved to its place, sliced and styled. */
static int place_parts(lam_build_run *r, lam_model **models, const lam_arrange_item *items, lam_error *err)
{
    for (size_t i = 0; i < r->nparts; i++) {
        lam_run_part *p = &r->parts[i];
        const lam_arrange_item *it = &items[i];
        const lam_build_part *spec = &r->b->parts[p->spec];
        /* the same arithmetic for a fixed part and an arranged one, so a
         * part planned alone at the place it got here is the same part */
        double c[2] = { (it->box[0] + it->box[2]) / 2, (it->box[1] + it->box[3]) / 2 };
        double raise = supported(r) ? r->b->profile->scan.support.height : 0; /* support_height */
        double d[3] = { it->at[0] - c[0], it->at[1] - c[1], spec->z + raise };
        int rc = moved_copy(models[p->spec], d, &p->model, err);
        if (!rc) rc = slice_part(r, p, err);
        if (!rc) rc = style_part(r, p, err);
        if (!rc) rc = support_part(p, err);
        if (rc) return rc;
        const double *bb = p->model->stats.bbox;
        double box[4] = { bb[0], bb[1], bb[3], bb[4] };
        memcpy(p->box, box, sizeof box);
        p->at[0] = it->at[0];
        p->at[1] = it->at[1];
        r->centres[2 * i] = (box[0] + box[2]) / 2;
        r->centres[2 * i + 1] = (box[1] + box[3]) / 2;
        if (p->first + p->count > r->layers) r->layers = p->first + p->count;
    }
    return LAM_OK;
}

/* The job the program begins with: the plate's parts' box, its layers. */
static void make_job(lam_build_run *r)
{
    double bb[6] = { INFINITY, INFINITY, 0, -INFINITY, -INFINITY, 0 };
    for (size_t i = 0; i < r->nparts; i++) {
        const double *m = r->parts[i].model->stats.bbox;
        for (int a = 0; a < 2; a++) {
            if (m[a] < bb[a]) bb[a] = m[a];
            if (m[3 + a] > bb[3 + a]) bb[3 + a] = m[3 + a];
        }
        if (m[5] > bb[5]) bb[5] = m[5];
    }
    lam_plan_opts po;
    lam_plan_opts_from_profile(&po, r->b->profile);
    lam_job_label(r->b->path ? r->b->path : "build", r->job_label, sizeof r->job_label);
    double cut0 = r->nparts ? lam_slicer_cut(r->parts[0].slicer, 0) : 0;
    lam_job_init(&r->job, &po, r->layers, bb, cut0, &r->frame, r->job_label, r->b->path);
    r->job.labels = (const char *const *)r->labels;
    r->job.nlabels = r->nlabels;
}

/* The job's exposures: each (style, region) some part's plan can have
 * vectors of, by style number then region, with the values of the first
 * part that has it (a style and a region give every part the same: the
 * profile, the job's style named after the region or the part's own). */
static int make_exposure(lam_build_run *r, lam_error *err)
{
    r->exposure = calloc(r->nstyles * LAM_REGIONS + 1, sizeof *r->exposure);
    if (!r->exposure) return lam_error_nomem(err, "describing the build's exposures");
    size_t n = 0;
    for (size_t s = 1; s <= r->nstyles; s++)
        for (int k = 0; k < LAM_REGIONS; k++)
            for (size_t i = 0; i < r->nparts; i++) {
                const lam_run_part *p = &r->parts[i];
                if (p->style_id[k] != (int)s || !lam_scan_region_used(&p->po.scan, k)) continue;
                const lam_scan_cfg *c = &p->po.scan;
                const lam_exposure *e = &c->type[k].exposure;
                r->exposure[n++] = (lam_job_exposure){
                    .style = (long long)s, .region = k, .power = e->power, .speed = e->speed,
                    .distance = lam_scan_region_distance(c, p->po.bead, k),
                    .point_distance = e->point_distance, .exposure_time = e->exposure_time };
                break;
            }
    r->job.exposure = r->exposure;
    r->job.nexposure = n;
    return LAM_OK;
}

static int setup(lam_build_run *r, const lam_load_opts *load, lam_model **models, lam_arrange_item *items,
                 lam_error *err)
{
    int rc = machine_plate(r, err);
    if (!rc) rc = number_styles(r, err);
    if (!rc) rc = load_all(r, load, models, items, err);
    if (!rc) rc = lam_arrange(&r->plate, r->spacing, items, r->nparts, r->b->profile->units, err);
    if (!rc) rc = place_parts(r, models, items, err);
    if (!rc) rc = check_reach(r, err);
    if (!rc) rc = number_labels(r, err);
    if (!rc) make_job(r);
    if (!rc) rc = make_exposure(r, err);
    if (!rc) rc = lam_build_run_json(r, err);
    r->lasers.part_centre = r->centres;
    r->lasers.nparts = r->nparts;
    return rc;
}

static size_t count_parts(const lam_build *b)
{
    size_t n = 0;
    for (size_t i = 0; i < b->nparts; i++) n += b->parts[i].copies;
    return n;
}

int lam_build_run_new(const lam_build *b, const lam_load_opts *load, lam_build_run **out, lam_error *err)
{
    *out = NULL;
    if (!b->nparts) return lam_error_set(err, LAM_EINVAL, b->path, 0, 0, "the build has no parts");
    if (!(b->profile->layer_width > 0))
        return lam_error_set(err, LAM_EINVAL, b->path, 0, 0,
                             "machine %s gives no layer_width: set layer_width in the job", b->profile->name);
    lam_build_run *r = calloc(1, sizeof *r);
    size_t n = count_parts(b);
    lam_model **models = calloc(b->nparts, sizeof *models);
    lam_arrange_item *items = calloc(n, sizeof *items);
    if (r) {
        r->b = b;
        r->nparts = n;
        r->width = b->profile->layer_width;
        r->cut = b->profile->cut;
        lam_frame_axis('z', &r->frame, NULL);
        r->parts = calloc(n, sizeof *r->parts);
        r->centres = calloc(2 * n, sizeof *r->centres);
    }
    int rc = r && models && items && r->parts && r->centres ? setup(r, load, models, items, err)
                                                              : lam_error_nomem(err, "setting up a build");
    for (size_t i = 0; models && i < b->nparts; i++) lam_model_free(models[i]);
    free(models);
    free(items);
    if (rc) lam_build_run_free(r);
    else *out = r;
    return rc;
}

void lam_build_run_free(lam_build_run *r)
{
    if (!r) return;
    for (size_t i = 0; r->parts && i < r->nparts; i++) {
        lam_supports_free(r->parts[i].supports);
        lam_slicer_free(r->parts[i].slicer);
        lam_model_free(r->parts[i].model);
    }
    for (size_t s = 0; r->styles && s < r->nstyles; s++) free(r->styles[s]);
    for (size_t l = 0; r->labels && l < r->nlabels; l++) free(r->labels[l]);
    free(r->styles);
    free(r->labels);
    free(r->label_of);
    free(r->parts);
    free(r->centres);
    free(r->exposure);
    free(r->json);
    free(r);
}

const lam_run_part *lam_build_run_parts(const lam_build_run *r, size_t *n)
{
    *n = r->nparts;
    return r->parts;
}

size_t lam_build_run_layers(const lam_build_run *r) { return r->layers; }
double lam_build_run_width(const lam_build_run *r) { return r->width; }
const lam_plate *lam_build_run_plate(const lam_build_run *r) { return &r->plate; }
const lam_laser_set *lam_build_run_lasers(const lam_build_run *r) { return &r->lasers; }
const lam_job_info *lam_build_run_job(const lam_build_run *r) { return &r->job; }
const lam_frame *lam_build_run_frame(const lam_build_run *r) { return &r->frame; }

const char *const *lam_build_run_styles(const lam_build_run *r, size_t *n)
{
    *n = r->nstyles;
    return (const char *const *)r->styles;
}

/* ---- identity (part files) ------------------------------------------------------ */

static uint64_t hash_part(uint64_t h, const lam_build_part *spec, const lam_run_part *p)
{
    h = lam_part_hash(h, p->at, sizeof p->at);
    h = lam_part_hash(h, &spec->z, sizeof spec->z);
    h = lam_part_hash(h, spec->xform.scale, sizeof spec->xform.scale);
    for (size_t k = 0; k < spec->xform.nrot; k++) {
        h = lam_part_hash(h, &spec->xform.rot[k].axis, sizeof spec->xform.rot[k].axis);
        h = lam_part_hash(h, &spec->xform.rot[k].deg, sizeof spec->xform.rot[k].deg);
    }
    return lam_part_hash(h, p->style_id, sizeof p->style_id);
}

int lam_build_run_identity(const lam_build_run *r, const char *profile, size_t len, uint64_t *out, lam_error *err)
{
    uint64_t h = lam_part_hash(0, profile, len);
    for (size_t s = 0; s < r->b->nstyles; s++) {
        const lam_build_style *st = &r->b->styles[s];
        h = lam_part_hash(h, st->name, strlen(st->name) + 1);
        for (size_t k = 0; k < st->nkeys; k++) {
            h = lam_part_hash(h, st->keys[k].key, strlen(st->keys[k].key) + 1);
            h = lam_part_hash(h, st->keys[k].text, strlen(st->keys[k].text) + 1);
        }
    }
    for (size_t i = 0; i < r->nparts; i++) {
        const lam_run_part *p = &r->parts[i];
        const lam_build_part *spec = &r->b->parts[p->spec];
        uint64_t id;
        int rc = lam_part_identity(spec->model, "", 0, p->slicer, &id, err);
        if (rc) return rc;
        h = hash_part(lam_part_hash(h, &id, sizeof id), spec, p);
    }
    *out = h;
    return LAM_OK;
}
