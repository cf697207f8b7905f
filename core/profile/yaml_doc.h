/* One YAML document read as data (libyaml's document API), with the checks
 * and messages every lamina YAML file gets: machine profiles (profile.c)
 * and build jobs (core/build/build_job.c). Nesting deeper than
 * LAM_YAML_MAX_NESTING is refused from the event stream before the loader
 * builds the document (libyaml's loader is quadratic in the depth); only
 * the core schema's tags are allowed (a file is data, never "construct an
 * object"); one document per file; malformed YAML is said with libyaml's
 * problem and context at file:line:column. Internal (not installed). */
#ifndef LAM_YAML_DOC_H
#define LAM_YAML_DOC_H

#include <stddef.h>
#include <yaml.h>

#include "error.h"

#define LAM_YAML_MAX_NESTING 32

typedef struct lam_yaml_doc {
    const char *path;        /* as given, for messages */
    char *text;              /* the raw bytes */
    size_t len;
    yaml_document_t doc;
    int have_doc;
    const char *what;        /* "a machine profile", "a build job": for messages */
    lam_error *err;
} lam_yaml_doc;

/* Parse d->text[0 .. d->len) (path, what and err set by the caller) into
 * d->doc, checked as above. An empty document is LAM_EINVAL with message
 * `empty` at 1:1; a second document, a tag, nesting: LAM_EINVAL at its
 * position; malformed YAML: LAM_ESYNTAX. */
int lam_yaml_doc_parse(lam_yaml_doc *d, const char *empty);

/* Release the document (not the text). */
void lam_yaml_doc_free(lam_yaml_doc *d);

/* Record an error at mark m (0-based line and column) of the document's
 * file. Returns code. */
int lam_yaml_at(const lam_yaml_doc *d, yaml_mark_t m, int code, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));

/* The node with id `id` (0: NULL). */
yaml_node_t *lam_yaml_node(const lam_yaml_doc *d, int id);

/* A YAML node that is null (~, null, empty). */
int lam_yaml_is_null(const yaml_node_t *n);

#endif
