/* The profile key table: its rows are consistent (unique names, flat names
 * and options, adjacent sections, one row per dialect command, defaults
 * that read and that a loaded profile holds), and every key set with
 * lam_profile_set (what --set does) survives the dump and a reload. The
 * Lua test tests/lua/keys.lua walks the same rows through YAML, --show,
 * --set and machine:override. */
#include "dialect.h"
#include "profile.h"
#include "profile_keys.h"
#include "util.h"
#include "writer.h"

#include <math.h>
#include <stdlib.h>

static const char base_yaml[] = "name: t\nprocess: ladrp\nbead_width: 0.5\ndialect: {}\n";
static const char sls_yaml[] = "name: t\nprocess: sls\nspot_width: 0.25\ndialect: {}\n";

static char *dump(const lam_profile *p)
{
    lam_writer *w;
    lam_error err;
    if (lam_writer_memory(&w, &err)) abort();
    lam_profile_dump(p, w);
    char *out;
    size_t n;
    if (lam_writer_take(w, &out, &n, &err)) abort();
    return out;
}

/* diag and clear the flag */
#define FAIL(flag, ...)       \
    do {                      \
        flag = 0;             \
        diag(__VA_ARGS__);    \
    } while (0)

static void test_rows(void)
{
    int names_unique = 1, flat_unique = 1, adjacent = 1, options_unique = 1, offsets = 1;
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *a = &lam_profile_keys[i];
        size_t as = lam_key_section_len(a);
        if (!(a->flags & LAM_KEY_LOADER) && a->offset >= sizeof(lam_profile)) FAIL(offsets, "%s: offset", a->name);
        if (as >= 32) FAIL(adjacent, "%s: section name too long", a->name);
        for (size_t j = i + 1; j < lam_profile_nkeys; j++) {
            const lam_key *b = &lam_profile_keys[j];
            if (!strcmp(a->name, b->name)) FAIL(names_unique, "two rows %s", a->name);
            if (!strcmp(lam_key_lua_name(a), lam_key_lua_name(b)))
                FAIL(flat_unique, "two rows known as %s", lam_key_lua_name(a));
            if ((a->option && b->option && !strcmp(a->option, b->option)) || (a->letter && a->letter == b->letter))
                FAIL(options_unique, "%s and %s have one option", a->name, b->name);
            if (!(a->flags & LAM_KEY_LOADER) && !(b->flags & LAM_KEY_LOADER) && a->offset == b->offset)
                FAIL(offsets, "%s and %s share a field", a->name, b->name);
            /* a later row of a's section must follow a row of the same section */
            const lam_key *prev = b - 1;
            if (as && lam_key_section_len(b) == as && !strncmp(a->name, b->name, as) &&
                (lam_key_section_len(prev) != as || strncmp(prev->name, a->name, as)))
                FAIL(adjacent, "%s is apart from its section", b->name);
        }
    }
    ok(names_unique, "every key name once");
    ok(flat_unique, "Lua names (flat rows by their own name) once");
    ok(options_unique, "every command-line option and letter once");
    ok(adjacent, "the rows of a section are adjacent (the dump writes a section once)");
    ok(offsets, "every row has its own field inside lam_profile");

    int tpl[LAM_CMD_COUNT] = { 0 }, tpl_ok = 1;
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *k = &lam_profile_keys[i];
        if (k->type != LAM_KEY_TEMPLATE) continue;
        tpl[k->cmd]++;
        if (strcmp(lam_key_short(k), lam_cmd_name((lam_cmd)k->cmd)) ||
            k->offset != offsetof(lam_profile, dialect.cmd) + (size_t)k->cmd * sizeof(lam_template))
            FAIL(tpl_ok, "template row %s", k->name);
    }
    for (int c = 0; c < LAM_CMD_COUNT; c++)
        if (tpl[c] != 1) FAIL(tpl_ok, "command %s has %d rows", lam_cmd_name((lam_cmd)c), tpl[c]);
    ok(tpl_ok, "one template row per dialect command, named as dialect.c names it");

    ok(lam_key_find("angle") == lam_key_find("raster.angle") && lam_key_find("angle"), "a flat row by its own name");
    ok(!lam_key_find("first") && !lam_key_find("raster"), "no row for a prefix or a section");
    const lam_key *travel = lam_key_find("travel_rate");
    ok(travel && travel->follows && lam_key_find(travel->follows), "travel_rate follows a row that exists");
}

/* Defaults read, are in range, and are what a profile without the key holds. */
static void test_defaults(void)
{
    lam_profile *p;
    lam_error err;
    if (lam_profile_load_buf("base.yaml", base_yaml, strlen(base_yaml), &p, &err)) {
        ok(0, "base profile loads: %s", err.msg);
        return;
    }
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *k = &lam_profile_keys[i];
        if (!k->def) continue;
        if (k->type == LAM_KEY_STRING) {
            is_str(*(char **)(void *)((char *)p + k->offset), k->def, "%s: default", k->name);
            continue;
        }
        double x = -1;
        int rc = lam_key_scan(k, NULL, k->def, strlen(k->def), &x, &err);
        ok(rc == LAM_OK, "%s: default '%s' reads (%s)", k->name, k->def, rc ? err.msg : "");
        is_num(lam_key_get(p, k), x, 0, "%s: a profile without it holds the default", k->name);
    }
    is_num(p->travel_rate, p->feed_rate, 0, "travel_rate follows feed_rate when not given");
    lam_profile_free(p);
}

/* lam_profile_set for every key: the value is stored, the dump shows it,
 * and the dump reloads to the same dump. */
static void test_set_round_trip(void)
{
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *k = &lam_profile_keys[i];
        lam_profile *p, *q;
        lam_error err;
        /* a key of one planner on a profile of its process (the other refuses it) */
        const char *base = k->planner == LAM_READ_SLS ? sls_yaml : base_yaml;
        if (lam_profile_load_buf("base.yaml", base, strlen(base), &p, &err)) abort();
        char text[64];
        switch (k->type) {
        case LAM_KEY_NUMBER:
            snprintf(text, sizeof text, "%.17g",
                     k->lo == -HUGE_VAL                    ? 12.5
                     : k->hi == HUGE_VAL && k->lo < 0.375 ? 0.375 /* in range, and exact in decimal */
                     : k->hi == HUGE_VAL                  ? k->lo + 0.375
                                                          : (k->lo + k->hi) / 2 + 0.25);
            break;
        case LAM_KEY_INTEGER: snprintf(text, sizeof text, "%d", (int)k->lo + 7); break;
        case LAM_KEY_BOOLEAN: snprintf(text, sizeof text, "%s", k->def && !strcmp(k->def, "true") ? "false" : "true"); break;
        case LAM_KEY_CHOICE: {
            int n = 0;
            while (k->choices[n + 1]) n++;
            snprintf(text, sizeof text, "%s", k->choices[n]); /* the last: never the base's (first) value here */
            break;
        }
        case LAM_KEY_NUMBERS: {
            /* [12.5, 12.5, ...]: the dump's flow style */
            size_t n = 0;
            n += (size_t)snprintf(text, sizeof text, "[");
            for (size_t j = 0; j < k->count && n < sizeof text - 8; j++)
                n += (size_t)snprintf(text + n, sizeof text - n, "%s12.5", j ? ", " : "");
            snprintf(text + n, sizeof text - n, "]");
            break;
        }
        case LAM_KEY_LASERS: snprintf(text, sizeof text, "[{field: [0, 0, 12.5, 12.5]}]"); break;
        default:
            if (k->choices) snprintf(text, sizeof text, "%s", k->choices[1]); /* units: not the default */
            else snprintf(text, sizeof text, "v-%s", lam_key_short(k));
            break;
        }
        int rc = lam_profile_set(p, k->name, text, &err);
        /* process: sls needs its width given too */
        if (!rc && k->offset == offsetof(lam_profile, process)) rc = lam_profile_set(p, "spot_width", "0.25", &err);
        /* a plate's width and depth go together */
        if (!rc && k->offset == offsetof(lam_profile, plate_width)) rc = lam_profile_set(p, "plate.depth", "1", &err);
        if (!rc && k->offset == offsetof(lam_profile, plate_depth)) rc = lam_profile_set(p, "plate.width", "1", &err);
        if (k->flags & LAM_KEY_LOADER) {
            ok(rc == LAM_EINVAL && strstr(err.msg, "only read while a profile loads"), "%s: refused by set", k->name);
            lam_profile_free(p);
            continue;
        }
        ok(rc == LAM_OK, "%s=%s: set (%s)", k->name, text, rc ? err.msg : "");
        char *d = dump(p);
        char line[160];
        snprintf(line, sizeof line, "%s: %s%s%s\n", lam_key_short(k),
                 k->type == LAM_KEY_STRING || k->type == LAM_KEY_TEMPLATE ? "\"" : "", text,
                 k->type == LAM_KEY_STRING || k->type == LAM_KEY_TEMPLATE ? "\"" : "");
        ok(strstr(d, line) != NULL, "%s: the dump writes %.*s", k->name, (int)strlen(line) - 1, line);
        rc = lam_profile_load_buf("dump.yaml", d, strlen(d), &q, &err);
        ok(rc == LAM_OK, "%s: the dump loads (%s)", k->name, rc ? err.msg : "");
        if (!rc) {
            char *d2 = dump(q);
            const char *a = strstr(d, "\nname:"), *b = strstr(d2, "\nname:"); /* past the comments */
            is_str(b ? b : d2, a ? a : d, "%s: dump -> load -> dump is the same", k->name);
            free(d2);
            lam_profile_free(q);
        }
        free(d);
        lam_profile_free(p);
    }
}

/* Who reads a key: the planner column agrees with the key's text (the
 * reference says "ladrp:" or "sls" first), every `instead` is a key of the
 * other planner and its value reads, and the message names it. */
static void test_planners(void)
{
    int agree = 1, instead = 1;
    for (size_t i = 0; i < lam_profile_nkeys; i++) {
        const lam_key *k = &lam_profile_keys[i];
        int want = !strncmp(k->doc, "ladrp:", 6) ? LAM_READ_LADRP
                   : !strncmp(k->doc, "sls:", 4) || !strncmp(k->doc, "sls,", 4) ? LAM_READ_SLS
                                                                                : LAM_READ_BOTH;
        if (k->planner != want) FAIL(agree, "%s: planner %d, its text says %d", k->name, k->planner, want);
        if (!k->instead) continue;
        char key[64];
        snprintf(key, sizeof key, "%.*s", (int)strcspn(k->instead, "="), k->instead);
        const lam_key *o = lam_key_find(key);
        const char *eq = strchr(k->instead, '=');
        double x;
        if (!o || k->planner == LAM_READ_BOTH || o->planner == LAM_READ_BOTH || o->planner == k->planner ||
            (eq && lam_key_scan(o, NULL, eq + 1, strlen(eq + 1), &x, NULL)))
            FAIL(instead, "%s: instead '%s'", k->name, k->instead);
    }
    ok(agree, "every key's planner is the one its text names");
    ok(instead, "every 'instead' is a key of the other planner, with a value it reads");
    const lam_key *angle = lam_key_find("raster.angle");
    ok(angle && !lam_key_read_by(angle, LAM_PROCESS_SLS) && lam_key_read_by(angle, LAM_PROCESS_LADRP),
       "raster.angle: ladrp reads it, sls does not");
    lam_error err;
    is_int(lam_key_unread(angle, "--angle", LAM_PROCESS_SLS, "cli-ascii", &err), LAM_EINVAL, "unread: LAM_EINVAL");
    is_str(err.msg, "--angle is read by the ladrp planner only, and cli-ascii is an sls profile: set hatch_angle instead",
           "unread: names the key the sls planner reads");
    lam_key_unread(lam_key_find("hatch_angle"), NULL, LAM_PROCESS_LADRP, NULL, &err);
    is_str(err.msg, "hatch_angle is read by the sls planner only, and this is a ladrp profile: set raster.angle instead (--angle)",
           "unread: names the ladrp key and its option");
    is_num(lam_key_unit_mm("inch"), 25.4, 0, "unit_mm: inch");
    is_num(lam_key_unit_mm("\xc2\xb5m"), 1e-3, 0, "unit_mm: \xc2\xb5m");
    is_num(lam_key_unit_mm("furlong"), 0, 0, "unit_mm: an unknown name is 0");
    ok(lam_key_find("layer_thickness") == lam_key_find("layer_width") && lam_key_find("layer_width"),
       "layer_thickness: the layer_width row");
}

static void test_messages(void)
{
    lam_error err;
    lam_profile *p;
    if (lam_profile_load_buf("base.yaml", base_yaml, strlen(base_yaml), &p, &err)) abort();
    struct {
        const char *key, *value, *msg;
    } bad[] = {
        { "bead_width", "abc", "bead_width must be a number, got 'abc'" },
        { "bead_width", "0", "bead_width must be greater than 0, got '0'" },
        { "feed_rate", "-1", "feed_rate must be 0 or more, got '-1'" },
        { "max_overhang_deg", "91", "max_overhang_deg must be from 0 to 90, got '91'" },
        { "perimeters", "1.5", "raster.perimeters must be a whole number from 0 to 1000, got '1.5'" },
        { "alternate", "maybe", "raster.alternate must be true or false, got 'maybe'" },
        { "cut", "top", "cut must be floor, middle or ceiling, got 'top'" },
        { "gap", "1e999", "gap must be a finite number, got '1e999'" },
        { "units", "", "units must not be empty" },
        { "bead_wdth", "1", "unknown key 'bead_wdth' (did you mean 'bead_width'?)" },
        { "zzz", "1", "unknown key 'zzz'" },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        int rc = lam_profile_set(p, bad[i].key, bad[i].value, &err);
        ok(rc == LAM_EINVAL, "set %s=%s fails", bad[i].key, bad[i].value);
        is_str(err.msg, bad[i].msg, "set %s=%s: message", bad[i].key, bad[i].value);
    }
    is_num(p->bead_width, 0.5, 0, "a failed set leaves the value");
    ok(lam_profile_set(p, "process", "sls", &err) == LAM_OK && lam_profile_set(p, "spot_width", "0.3", &err) == LAM_OK &&
           lam_profile_check(p, &err) == LAM_OK && p->bead_width == 0.3,
       "sls: setting the spot sets the bead width");
    lam_profile_free(p);
    const char *no_spot = "name: t\nprocess: ladrp\nbead_width: 0.5\ndialect: {}\n";
    if (lam_profile_load_buf("b.yaml", no_spot, strlen(no_spot), &p, &err)) abort();
    ok(lam_profile_set(p, "process", "sls", &err) == LAM_OK && lam_profile_check(p, &err) == LAM_EINVAL &&
           strstr(err.msg, "spot_width must be given for process sls"),
       "a process without its width: check says which key (%s)", err.msg);
    lam_profile_free(p);
}

int main(void)
{
    test_rows();
    test_defaults();
    test_set_round_trip();
    test_planners();
    test_messages();
    return done_testing();
}
