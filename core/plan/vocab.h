/* The plan's vocabulary: one enum and one name table for what a planned
 * vector is (its kind) and the regions a layer's area is exposed as (the
 * first kinds), and one table of the attributes every operation of a plan
 * carries (plan.h's infos), read by every consumer from that table: the
 * recording and part files (plan_record.h), the vector stream (vstream.h),
 * the JSON (json_sink.h, so the viewer's data too) and Lua's plan data.
 *
 * Adding an attribute is one row of LAM_ATTRS and the planner that sets it:
 * the recording, part files, JSON and Lua carry it without another edit. A
 * value equal to the row's default is left out of the JSON and of Lua's
 * vectors (so `part` shows only when a build has several parts). */
#ifndef LAM_VOCAB_H
#define LAM_VOCAB_H

#include <stddef.h>

/* Kinds. The regions come first, with the values the profile's sections
 * and lam_scan_cfg.type use: each region has its own exposure (and, but
 * the contour, its own hatching). */
typedef enum lam_vec_kind {
    LAM_KIND_CONTOUR,        /* SLS contour passes (each edge a vector) */
    LAM_KIND_CORE,           /* hatch vectors of the core */
    LAM_KIND_UPSKIN,         /* hatch vectors under the part's top surfaces */
    LAM_KIND_DOWNSKIN,       /* hatch vectors over its overhangs */
    LAM_KIND_SUPPORT,        /* support walls under overhangs (support.h): lines, no contour */
    LAM_REGIONS,             /* the number of regions */
    LAM_KIND_DEPOSIT = LAM_REGIONS, /* LADRP: a stage move with the laser on */
    LAM_KIND_TRAVEL,         /* LADRP: a stage move with the laser off */
    LAM_KIND_JUMP,           /* SLS: the scanner between paths, beam off */
    LAM_KINDS
} lam_vec_kind;

/* The kind's name: "contour", "core", "upskin", "downskin", "support",
 * "deposit", "travel", "jump"; "?" for a value outside the enum. */
const char *lam_kind_name(int kind);

/* The kind named by the first len bytes of name, or -1. */
int lam_kind_find(const char *name, size_t len);

/* Whether vectors of the kind are exposed (beam or laser on). */
int lam_kind_exposed(int kind);

/* The attributes: X(field, key, default, meaning). Whole numbers. */
/* A build's rows (core/build): 0 outside a build, so they are left out of
 * the JSON of a single part's run. */
#define LAM_ATTRS_BUILD(X)                                                                                   \
    X(style, "style", 0, "the build style it is exposed with (a build's style number; 0: not a build)")     \
    X(laser, "laser", 0, "the laser that exposes it (a build's laser number; 0: not a build)")              \
    X(label, "label", 0, "its CLI $$LABEL id: the build's (part, style, laser) number; 0: the part's")
#define LAM_ATTRS(X) X(part, "part", 1, "the part the operation belongs to (CLI's $$LABEL id)") LAM_ATTRS_BUILD(X)

typedef struct lam_attrs {
#define LAM_ATTR_FIELD(field, key, def, doc) long long field;
    LAM_ATTRS(LAM_ATTR_FIELD)
#undef LAM_ATTR_FIELD
} lam_attrs;

/* The number of attributes (rows of LAM_ATTRS). */
#define LAM_NATTRS (sizeof(lam_attrs) / sizeof(long long))

/* The CLI $$LABEL id of an operation: a->label when set (a build), else
 * a->part. */
long long lam_attrs_id(const lam_attrs *a);

/* Every attribute at its default. */
lam_attrs lam_attrs_default(void);

/* Attribute i's key, default and value in a (i < LAM_NATTRS). */
const char *lam_attr_key(size_t i);
long long lam_attr_default(size_t i);
long long lam_attr_get(const lam_attrs *a, size_t i);
void lam_attr_set(lam_attrs *a, size_t i, long long v);

#endif
