/* lamina machines [--show NAME|PATH]: list the machine profiles found in the
 * machine directories, or print one resolved profile as YAML. */
#include "cli.h"
#include "cli_args.h"
#include "dialect.h"
#include "profile.h"
#include "writer.h"

#include <dirent.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define MAX_DIRS 16

static const char usage_text[] =
    "usage: lamina machines [--show NAME|PATH [-s KEY=VALUE ...]] [--keys]\n"
    "List the machine profiles (name, process, description), or with --show\n"
    "print one profile as YAML with inheritance resolved and defaults filled in\n"
    "(and the values of -s/--set KEY=VALUE applied, as 'lamina slice' would);\n"
    "--keys lists every key a profile may have: type, default, meaning.\n"
    "Profiles are NAME.yaml files in $LAMINA_MACHINES (colon-separated), then\n"
    "<lamina>/../machines and <lamina>/../share/lamina/machines (for the Lua\n"
    "module: beside lamina.so, see lua/API.md); when two directories have the\n"
    "same name, the first one wins.\n";

typedef struct entry {
    char *name, *path;
} entry;

static int by_name(const void *a, const void *b)
{
    return strcmp(((const entry *)a)->name, ((const entry *)b)->name);
}

static int has_name(const entry *e, size_t n, const char *name)
{
    for (size_t i = 0; i < n; i++)
        if (strcmp(e[i].name, name) == 0) return 1;
    return 0;
}

/* Every NAME.yaml of the machine directories, first directory wins. */
static int collect(entry **out, size_t *count)
{
    char *dirs[MAX_DIRS];
    size_t nd = lam_machine_dirs(dirs, MAX_DIRS);
    entry *e = NULL;
    size_t n = 0, cap = 0;
    int rc = 0;
    for (size_t d = 0; d < nd; d++) {
        DIR *dir = opendir(dirs[d]);
        size_t first = n; /* names of this directory start here */
        struct dirent *de;
        while (!rc && dir && (de = readdir(dir))) {
            size_t len = strlen(de->d_name);
            if (len <= 5 || de->d_name[0] == '.' || strcmp(de->d_name + len - 5, ".yaml") != 0) continue;
            char *name = strndup(de->d_name, len - 5);
            size_t plen = strlen(dirs[d]) + len + 2;
            char *path = malloc(plen);
            if (!name || !path) {
                free(name);
                free(path);
                rc = 1;
                break;
            }
            snprintf(path, plen, "%s/%s", dirs[d], de->d_name);
            struct stat st;
            if (stat(path, &st) != 0 || !S_ISREG(st.st_mode) || has_name(e, first, name)) {
                free(name);
                free(path);
                continue;
            }
            if (n == cap) {
                /* a directory's worth of names: no count near SIZE_MAX */
                entry *ne = realloc(e, (cap ? 2 * cap : 16) * sizeof *ne);
                if (!ne) {
                    free(name);
                    free(path);
                    rc = 1;
                    break;
                }
                e = ne;
                cap = cap ? 2 * cap : 16;
            }
            e[n].name = name;
            e[n].path = path;
            n++;
        }
        if (dir) closedir(dir);
        free(dirs[d]);
    }
    if (e) qsort(e, n, sizeof *e, by_name);
    *out = e;
    *count = n;
    return rc;
}

static int list(void)
{
    entry *e;
    size_t n;
    if (collect(&e, &n)) {
        fprintf(stderr, "lamina machines: out of memory\n");
        return EXIT_INPUT;
    }
    int status = EXIT_OK;
    lam_profile **p = calloc(n ? n : 1, sizeof *p);
    size_t wname = 4;
    for (size_t i = 0; p && i < n; i++) {
        lam_error err;
        lam_error_clear(&err);
        if (lam_profile_load(e[i].path, &p[i], &err)) status = cli_fail(&err);
        size_t len = strlen(e[i].name);
        if (len > wname) wname = len;
    }
    if (!p) {
        fprintf(stderr, "lamina machines: out of memory\n");
        status = EXIT_INPUT;
    }
    if (n == 0) fprintf(stderr, "lamina machines: no profiles found (set LAMINA_MACHINES to a directory of *.yaml)\n");
    for (size_t i = 0; p && i < n; i++) {
        if (p[i])
            printf("%-*s  %-5s  %s\n", (int)wname, e[i].name, p[i]->process == LAM_PROCESS_SLS ? "sls" : "ladrp",
                   p[i]->description ? p[i]->description : "");
        lam_profile_free(p[i]);
    }
    for (size_t i = 0; i < n; i++) {
        free(e[i].name);
        free(e[i].path);
    }
    free(p);
    free(e);
    return status;
}

static int show(const args *a)
{
    lam_error err;
    lam_error_clear(&err);
    lam_profile *p;
    if (lam_profile_find(a->show, &p, &err)) return cli_fail(&err);
    int rc = cli_apply_sets("machines", a, p);
    if (rc) {
        lam_profile_free(p);
        return rc;
    }
    lam_writer *w;
    rc = lam_writer_stream(stdout, "(stdout)", &w, &err);
    if (!rc) {
        lam_profile_dump(p, w);
        rc = lam_writer_commit(w, &err);
    }
    lam_profile_free(p);
    return rc ? cli_fail(&err) : EXIT_OK;
}

/* "`a` \\| `b`": a row's choices, for the reference */
static void choice_names(const lam_key *k, char *out, size_t size)
{
    size_t n = 0;
    out[0] = '\0';
    for (int i = 0; k->choices[i] && n + 1 < size; i++) {
        int w = snprintf(out + n, size - n, "%s`%s`", i ? " \\| " : "", k->choices[i]);
        if (w < 0) break;
        n += (size_t)w;
    }
}

/* What a row takes, for the reference: "number > 0", "`a` \\| `b`", ... */
static void key_type(const lam_key *k, char *out, size_t size)
{
    char lo[64], hi[64];
    snprintf(lo, sizeof lo, "%g", k->lo);
    snprintf(hi, sizeof hi, "%g", k->hi);
    switch (k->type) {
    case LAM_KEY_NUMBER:
        if (k->lo == -HUGE_VAL && k->hi == HUGE_VAL) snprintf(out, size, "number");
        else if (k->hi == HUGE_VAL) snprintf(out, size, "number %s %s", k->flags & LAM_KEY_ABOVE ? ">" : ">=", lo);
        else snprintf(out, size, "number %s..%s", lo, hi);
        if (k->flags & LAM_KEY_AUTO) strncat(out, " or `auto`", size - strlen(out) - 1);
        break;
    case LAM_KEY_INTEGER: snprintf(out, size, "whole number %s..%s", lo, hi); break;
    case LAM_KEY_BOOLEAN: snprintf(out, size, "boolean"); break;
    case LAM_KEY_STRING:
        if (!k->choices) snprintf(out, size, "text");
        else choice_names(k, out, size); /* text that is one of the names */
        break;
    case LAM_KEY_TEMPLATE: snprintf(out, size, "template"); break;
    case LAM_KEY_CHOICE: choice_names(k, out, size); break;
    case LAM_KEY_NUMBERS: snprintf(out, size, "list of %zu numbers", k->count); break;
    case LAM_KEY_LASERS: snprintf(out, size, "list of 1..%d lasers", LAM_PROFILE_LASERS_MAX); break;
    }
}

/* The key reference of machines/README.md (a test keeps the two equal):
 * every key but the dialect's commands, then the commands with their
 * fields. */
static int keys(void)
{
    printf("| key | type | default | meaning |\n|-----|------|---------|---------|\n");
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *k = &lam_profile_keys[i];
        if (k->type == LAM_KEY_TEMPLATE) continue;
        char type[200], def[200];
        key_type(k, type, sizeof type);
        if (k->def) snprintf(def, sizeof def, "`%s`", k->def);
        else if (k->follows) snprintf(def, sizeof def, "`%s`", k->follows);
        else snprintf(def, sizeof def, "%s", k->flags & (LAM_KEY_NEED | LAM_KEY_NEED_LADRP | LAM_KEY_NEED_SLS) ? "required" : "none");
        if (k->flags & LAM_KEY_NEED_LADRP) snprintf(def, sizeof def, "required (ladrp)");
        if (k->flags & LAM_KEY_NEED_SLS) snprintf(def, sizeof def, "required (sls)");
        char opt[80] = "", alias[80] = "", other[120] = "";
        if (k->option && k->letter) snprintf(opt, sizeof opt, " Option: `-%c`, `--%s`.", k->letter, k->option);
        else if (k->option) snprintf(opt, sizeof opt, " Option: `--%s`.", k->option);
        if (k->alias) snprintf(alias, sizeof alias, " Also `%s`.", k->alias);
        if (k->instead)
            snprintf(other, sizeof other, " The %s planner's: `%s`.", k->planner == LAM_READ_SLS ? "ladrp" : "sls",
                     k->instead);
        printf("| `%s` | %s | %s | %s.%s%s%s |\n", k->name, type, def, k->doc, alias, opt, other);
    }
    printf("\n| command | when | fields |\n|---------|------|--------|\n");
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *k = &lam_profile_keys[i];
        if (k->type != LAM_KEY_TEMPLATE) continue;
        const char *f = lam_cmd_fields((lam_cmd)k->cmd);
        printf("| `%s` | %s | %s%s%s |\n", lam_key_short(k), k->doc, *f ? "`" : "", *f ? f : "none", *f ? "`" : "");
    }
    return EXIT_OK;
}

int cmd_machines(int argc, char **argv)
{
    args a;
    int rc = cli_parse_args("machines", usage_text, OPT_SHOW | OPT_SET, argc, argv, &a);
    if (!rc && a.nsets && !a.show) rc = cli_usage("machines", "-s/--set applies to a profile: give --show NAME too");
    if (!rc && a.keys && a.show) rc = cli_usage("machines", "give --show or --keys, not both");
    if (!rc) rc = a.keys ? keys() : a.show ? show(&a) : list();
    cli_args_free(&a);
    return rc < 0 ? EXIT_OK : rc;
}
