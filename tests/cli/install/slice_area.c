/* A library user's program, built by tests/cli/install.t against the
 * installed lamina with nothing but `pkg-config --cflags --libs lamina`:
 * load a model, slice it, and print per layer the number of contours, the
 * net area by lamina's own measure and by this program's shoelace sum. */
#include <lamina/lamina.h>

#include <stdio.h>

static double shoelace(const double *uv, size_t n)
{
    double a = 0;
    for (size_t i = 0; i < n; i++) {
        const double *p = uv + 2 * i, *q = uv + 2 * ((i + 1) % n);
        a += p[0] * q[1] - q[0] * p[1];
    }
    return a / 2;
}

static void report(const lam_error *err)
{
    char buf[2048];
    fprintf(stderr, "slice_area: %s\n", lam_error_format(err, buf, sizeof buf));
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: slice_area MODEL WIDTH\n");
        return 2;
    }
    lam_error err;
    lam_error_clear(&err);
    lam_model *m = NULL;
    if (lam_model_load(argv[1], &m, &err) != LAM_OK) {
        report(&err);
        return 1;
    }
    lam_slice_opts o;
    lam_slice_opts_init(&o);
    sscanf(argv[2], "%lf", &o.width);
    lam_slicer *s = NULL;
    if (lam_slicer_new(m, &o, &s, &err) != LAM_OK) {
        report(&err);
        lam_model_free(m);
        return 1;
    }
    printf("lamina %s: %zu layers\n", LAMINA_VERSION, lam_slicer_count(s));
    lam_layer *L = NULL;
    int rc;
    while ((rc = lam_slicer_next(s, &L, &err)) == LAM_OK && L) {
        double net = 0, mine = 0;
        for (size_t c = 0; c < L->ncontours; c++) {
            net += L->contours[c].area;
            mine += shoelace(L->uv + 2 * L->contours[c].first, L->contours[c].n);
        }
        printf("layer %zu at %g: %zu contours, net area %.6f (shoelace %.6f)\n", L->index, L->cut, L->ncontours,
               net, mine);
        lam_layer_free(L);
    }
    if (rc != LAM_OK) report(&err);
    lam_slicer_free(s);
    lam_model_free(m);
    return rc == LAM_OK ? 0 : 1;
}
