/* One YAML document read as data: see yaml_doc.h. */
#include "yaml_doc.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

int lam_yaml_at(const lam_yaml_doc *d, yaml_mark_t m, int code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int rc = lam_error_vset(d->err, code, d->path, (long)m.line + 1, (long)m.column + 1, -1, fmt, ap);
    va_end(ap);
    return rc;
}

yaml_node_t *lam_yaml_node(const lam_yaml_doc *d, int id)
{
    return id ? yaml_document_get_node((yaml_document_t *)&d->doc, id) : NULL;
}

int lam_yaml_is_null(const yaml_node_t *n)
{
    if (n->type != YAML_SCALAR_NODE) return 0;
    if (strcmp((const char *)n->tag, YAML_NULL_TAG) == 0) return 1;
    if (n->data.scalar.style != YAML_PLAIN_SCALAR_STYLE) return 0;
    const char *v = (const char *)n->data.scalar.value;
    return !*v || !strcmp(v, "~") || !strcmp(v, "null") || !strcmp(v, "Null") || !strcmp(v, "NULL");
}

/* Only the core schema's tags: anything else could mean "construct an
 * object" to some loader, and the file is data. */
static int check_tags(const lam_yaml_doc *d)
{
    static const char *const ok_tags[] = { YAML_STR_TAG, YAML_INT_TAG, YAML_FLOAT_TAG, YAML_BOOL_TAG,
                                           YAML_NULL_TAG, YAML_MAP_TAG, YAML_SEQ_TAG, NULL };
    for (yaml_node_t *n = d->doc.nodes.start; n < d->doc.nodes.top; n++) {
        const char *tag = (const char *)n->tag;
        int good = 0;
        for (int i = 0; ok_tags[i] && tag; i++) good |= !strcmp(tag, ok_tags[i]);
        if (!good) {
            char shown[200];
            const char *prefix = "tag:yaml.org,2002:";
            if (tag && !strncmp(tag, prefix, strlen(prefix)))
                snprintf(shown, sizeof shown, "!!%s", tag + strlen(prefix));
            else
                snprintf(shown, sizeof shown, "%s", tag ? tag : "?");
            return lam_yaml_at(d, n->start_mark, LAM_EINVAL, "YAML tag '%s' is not allowed: %s is data only", shown,
                               d->what);
        }
    }
    return LAM_OK;
}

/* Refuse nesting deeper than LAM_YAML_MAX_NESTING from the event stream,
 * before the loader builds the document: libyaml's scanner and loader take
 * time quadratic in the depth (100,000 nested '[' took 31 s), the events
 * up to the limit take time linear in the file. A syntax error is left to
 * the loader, which meets it at the same place and says it with context. */
static int check_nesting(const lam_yaml_doc *d)
{
    yaml_parser_t parser;
    if (!yaml_parser_initialize(&parser)) return lam_error_nomem(d->err, NULL);
    yaml_parser_set_input_string(&parser, (const unsigned char *)d->text, d->len);
    int rc = LAM_OK, depth = 0, done = 0;
    while (!done && rc == LAM_OK) {
        yaml_event_t ev;
        if (!yaml_parser_parse(&parser, &ev)) break;
        if (ev.type == YAML_SEQUENCE_START_EVENT || ev.type == YAML_MAPPING_START_EVENT) {
            if (++depth > LAM_YAML_MAX_NESTING)
                rc = lam_yaml_at(d, ev.start_mark, LAM_EINVAL, "lists and mappings nested more than %d deep",
                                 LAM_YAML_MAX_NESTING);
        } else if (ev.type == YAML_SEQUENCE_END_EVENT || ev.type == YAML_MAPPING_END_EVENT) {
            depth--;
        }
        done = ev.type == YAML_STREAM_END_EVENT;
        yaml_event_delete(&ev);
    }
    yaml_parser_delete(&parser);
    return rc;
}

/* libyaml's complaint at its position. */
static int parse_error(const lam_yaml_doc *d, const yaml_parser_t *parser)
{
    if (parser->error == YAML_MEMORY_ERROR) return lam_error_nomem(d->err, NULL);
    if (parser->error == YAML_READER_ERROR) { /* invalid encoding: only a byte offset is known */
        size_t off = parser->problem_offset < d->len ? parser->problem_offset : d->len;
        long line = 1, ls = 0;
        for (size_t i = 0; i < off; i++)
            if (d->text[i] == '\n') line++, ls = (long)i + 1;
        long col = 1;
        for (long i = ls; i < (long)off; i++) col += ((unsigned char)d->text[i] & 0xC0) != 0x80;
        return lam_error_set(d->err, LAM_ESYNTAX, d->path, line, col, "malformed YAML: %s",
                             parser->problem ? parser->problem : "cannot read");
    }
    char ctx[200] = "";
    if (parser->context)
        snprintf(ctx, sizeof ctx, " (%s at line %lu, column %lu)", parser->context,
                 (unsigned long)parser->context_mark.line + 1, (unsigned long)parser->context_mark.column + 1);
    return lam_error_set(d->err, LAM_ESYNTAX, d->path, (long)parser->problem_mark.line + 1,
                         (long)parser->problem_mark.column + 1, "malformed YAML: %s%s",
                         parser->problem ? parser->problem : "cannot parse", ctx);
}

/* A second document after the first is refused. */
static int one_document(const lam_yaml_doc *d, yaml_parser_t *parser)
{
    yaml_document_t more;
    if (!yaml_parser_load(parser, &more)) return parse_error(d, parser);
    yaml_node_t *r = yaml_document_get_root_node(&more);
    yaml_mark_t m = more.start_mark;
    yaml_document_delete(&more);
    return r ? lam_yaml_at(d, m, LAM_EINVAL, "%s is one YAML document; a second one starts here", d->what) : LAM_OK;
}

int lam_yaml_doc_parse(lam_yaml_doc *d, const char *empty)
{
    int rc = check_nesting(d);
    if (rc) return rc;
    yaml_parser_t parser;
    if (!yaml_parser_initialize(&parser)) return lam_error_nomem(d->err, NULL);
    yaml_parser_set_input_string(&parser, (const unsigned char *)d->text, d->len);
    if (!yaml_parser_load(&parser, &d->doc)) {
        rc = parse_error(d, &parser);
    } else {
        d->have_doc = 1;
        if (!yaml_document_get_root_node(&d->doc))
            rc = lam_error_set(d->err, LAM_EINVAL, d->path, 1, 1, "%s", empty);
        if (!rc) rc = one_document(d, &parser);
        if (!rc) rc = check_tags(d);
    }
    yaml_parser_delete(&parser);
    return rc;
}

void lam_yaml_doc_free(lam_yaml_doc *d)
{
    if (d->have_doc) yaml_document_delete(&d->doc);
    d->have_doc = 0;
}
