/* Loading the command's model with its load options (cli_args.h). */
#include "cli_args.h"
#include "model.h"
#include "pool.h"
#include "size_sense.h"
#include "profile.h"
#include "xform.h"

#include <string.h>

int cli_load_model(const args *a, const lam_profile *machine, lam_model **m, lam_error *err)
{
    const char *path = a->path;
    /* the units are a scale known once the machine is: the model's unit
     * over the machine's (no machine: mm), before --scale's factors */
    lam_xform x = a->xform;
    double machine_mm = machine ? lam_profile_unit_mm(machine) : 1;
    if (a->units && !(machine_mm > 0))
        return lam_error_set(err, LAM_EUSAGE, NULL, 0, 0, "--units %s: the machine's units (%s) are unknown",
                             a->units ? a->units : "", machine && machine->units ? machine->units : "");
    if (a->units) lam_xform_scale_by(&x, lam_unit_mm(a->units) / machine_mm);
    /* --place plate centres the footprint on the machine's plate */
    lam_profile_plate_centre(machine, x.plate_centre);
    cli_size_sense_loaded(a->units ? lam_unit_mm(a->units) : 0);
    lam_load_opts o = { .threads = a->threads ? a->threads : lam_default_threads(NULL),
                        .no_repair = a->no_repair,
                        .xform = &x };
    *m = NULL;
    return strcmp(path, "-") ? lam_model_load_opts(path, &o, m, err) : lam_model_load_stdin_opts(&o, m, err);
}
