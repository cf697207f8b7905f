/* lamina machines [--show NAME|PATH]: list the machine profiles found in the
 * machine directories, or print one resolved profile as YAML. */
#include "cli.h"
#include "profile.h"
#include "writer.h"

#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define MAX_DIRS 16

static const char usage_text[] =
    "usage: lamina machines [--show NAME|PATH]\n"
    "List the machine profiles (name, process, description), or with --show\n"
    "print one profile as YAML with inheritance resolved and defaults filled in.\n"
    "Profiles are NAME.yaml files in $LAMINA_MACHINES (colon-separated), then\n"
    "<lamina>/../machines and <lamina>/../share/lamina/machines; when two\n"
    "directories have the same name, the first one wins.\n";

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
                cap = cap ? 2 * cap : 16;
                entry *ne = realloc(e, cap * sizeof *ne);
                if (!ne) {
                    free(name);
                    free(path);
                    rc = 1;
                    break;
                }
                e = ne;
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

static int show(const char *which)
{
    lam_error err;
    lam_error_clear(&err);
    lam_profile *p;
    if (lam_profile_find(which, &p, &err)) return cli_fail(&err);
    lam_writer *w;
    int rc = lam_writer_stream(stdout, "(stdout)", &w, &err);
    if (!rc) {
        lam_profile_dump(p, w);
        rc = lam_writer_commit(w, &err);
    }
    lam_profile_free(p);
    return rc ? cli_fail(&err) : EXIT_OK;
}

int cmd_machines(int argc, char **argv)
{
    const char *which = NULL;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) {
            fputs(usage_text, stdout);
            return EXIT_OK;
        } else if (strcmp(argv[i], "--show") == 0) {
            if (i + 1 >= argc) return cli_usage("machines", "option --show needs a profile name or path");
            if (which) return cli_usage("machines", "--show given twice");
            which = argv[++i];
        } else if (strncmp(argv[i], "--show=", 7) == 0) {
            if (which) return cli_usage("machines", "--show given twice");
            which = argv[i] + 7;
        } else if (argv[i][0] == '-' && argv[i][1]) {
            return cli_usage("machines", "unknown option '%s'", argv[i]);
        } else {
            return cli_usage("machines", "unexpected argument '%s' (to print a profile: --show %s)", argv[i], argv[i]);
        }
    }
    if (which && !*which) return cli_usage("machines", "--show needs a profile name or path");
    return which ? show(which) : list();
}
