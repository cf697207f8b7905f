/* Tab completion (complete.h). */
#include "complete.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#include <lauxlib.h>

const char lam_complete_breaks[] = " \t\n\"\\'`@$><=;|&{}()[],+-*/%^~#!?";

static const char *const keywords[] = { "and", "break", "do", "else", "elseif", "end", "false", "for",
                                        "function", "goto", "if", "in", "local", "nil", "not", "or",
                                        "repeat", "return", "then", "true", "until", "while", NULL };

typedef struct cands {
    char **v;
    size_t n, cap;
    int failed;
} cands;

static void add(cands *c, const char *head, size_t hl, const char *name)
{
    if (c->failed) return;
    if (c->n + 2 > c->cap) {
        size_t cap = c->cap ? 2 * c->cap : 32;
        char **v = realloc(c->v, cap * sizeof *v);
        if (!v) {
            c->failed = 1;
            return;
        }
        c->v = v;
        c->cap = cap;
    }
    size_t nl = strlen(name);
    char *s = malloc(hl + nl + 1);
    if (!s) {
        c->failed = 1;
        return;
    }
    memcpy(s, head, hl);
    memcpy(s + hl, name, nl + 1);
    c->v[c->n++] = s;
}

static int is_name(const char *s)
{
    if (!(isalpha((unsigned char)*s) || *s == '_')) return 0;
    for (; *s; s++)
        if (!(isalnum((unsigned char)*s) || *s == '_')) return 0;
    return 1;
}

/* The string keys of table t (absolute index) that start with part: as
 * head .. key; only functions when `methods`. */
static void from_table(lua_State *L, int t, const char *part, const char *head, size_t hl, int methods, cands *c)
{
    size_t pl = strlen(part);
    lua_pushnil(L);
    while (lua_next(L, t)) {
        if (lua_type(L, -2) == LUA_TSTRING) {
            const char *k = lua_tostring(L, -2);
            if (strncmp(k, part, pl) == 0 && is_name(k) && (!methods || lua_isfunction(L, -1))) add(c, head, hl, k);
        }
        lua_pop(L, 1);
    }
}

/* What the metatable of the value at v offers: a lamina class's methods
 * (the first upvalue of its C __index), or an __index table. */
static void from_meta(lua_State *L, int v, const char *part, const char *head, size_t hl, int methods, cands *c)
{
    int top = lua_gettop(L);
    if (!lua_getmetatable(L, v)) return;
    lua_pushliteral(L, "__index");
    lua_rawget(L, -2);
    if (lua_istable(L, -1)) from_table(L, lua_gettop(L), part, head, hl, methods, c);
    else if (lua_iscfunction(L, -1) && lua_getupvalue(L, -1, 1) && lua_istable(L, -1))
        from_table(L, lua_gettop(L), part, head, hl, methods, c);
    lua_settop(L, top);
}

static int cmp(const void *a, const void *b)
{
    return strcmp(*(char *const *)a, *(char *const *)b);
}

typedef struct job {
    const char *word;
    cands c;
} job;

static int complete_in(lua_State *L)
{
    job *j = lua_touserdata(L, 1);
    const char *word = j->word;
    const char *sep = NULL;
    for (const char *p = word; *p; p++)
        if (*p == '.' || *p == ':') sep = p;
    lua_pushglobaltable(L);
    if (!sep) {
        from_table(L, lua_gettop(L), word, "", 0, 0, &j->c);
        for (int i = 0; keywords[i]; i++)
            if (strncmp(keywords[i], word, strlen(word)) == 0) add(&j->c, "", 0, keywords[i]);
        return 0;
    }
    /* walk the path before the last separator: names joined by '.' */
    const char *p = word;
    while (p < sep) {
        const char *q = p;
        while (q < sep && *q != '.' && *q != ':') q++;
        if (q == p || (*q == ':' && q != sep)) return 0;
        if (!lua_istable(L, -1)) return 0;
        lua_pushlstring(L, p, (size_t)(q - p));
        lua_rawget(L, -2);
        lua_remove(L, -2);
        p = q + 1;
    }
    int v = lua_gettop(L);
    const char *part = sep + 1;
    size_t hl = (size_t)(part - word);
    int methods = *sep == ':';
    if (lua_istable(L, v)) from_table(L, v, part, word, hl, methods, &j->c);
    if (lua_istable(L, v) || lua_isuserdata(L, v) || lua_type(L, v) == LUA_TSTRING)
        from_meta(L, v, part, word, hl, methods, &j->c);
    return 0;
}

char **lam_complete(lua_State *L, const char *word)
{
    job j;
    memset(&j, 0, sizeof j);
    j.word = word;
    int top = lua_gettop(L);
    /* protected: reading tables allocates (a memory error, a finalizer) */
    lua_pushcfunction(L, complete_in);
    lua_pushlightuserdata(L, &j);
    int rc = lua_pcall(L, 1, 0, 0);
    lua_settop(L, top);
    if (rc != LUA_OK || j.c.failed || j.c.n == 0) {
        for (size_t i = 0; i < j.c.n; i++) free(j.c.v[i]);
        free(j.c.v);
        return NULL;
    }
    qsort(j.c.v, j.c.n, sizeof *j.c.v, cmp);
    size_t n = 0;
    for (size_t i = 0; i < j.c.n; i++) {
        if (n && strcmp(j.c.v[n - 1], j.c.v[i]) == 0) free(j.c.v[i]);
        else j.c.v[n++] = j.c.v[i];
    }
    j.c.v[n] = NULL;
    return j.c.v;
}
