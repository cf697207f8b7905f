/* The plan's encoding: the one serialised form of a plan's operations
 * (plan.h's lam_sink calls), written by one encoder and read by one
 * decoder. Worker threads record a layer's operations in it, to be
 * replayed in layer order onto the one real sink (a text dialect, a plugin
 * writer, ...), so what that sink writes is the same, byte for byte,
 * whatever the number of threads; a part file (part.h) is a header and
 * then these records, replayed by `lamina join` through the same decoder.
 *
 * A record is a tag byte and its fields: integers 64-bit little-endian
 * (u64, or i64 where signed), reals IEEE 754 binary64 little-endian, each
 * attribute block LAM_NATTRS i64 in vocab.h's row order:
 *
 *   'L' layer        u64 index, z, width, floor, ceiling
 *   'E' layer end    the same, then the layer's build-time estimate
 *                    (lam_scan_time: 4 u64 counts, 6 reals)
 *   'F' feed         rate
 *   'A' laser        u8 on
 *   'M' move         attrs, u8 deposit, xyz (3 reals), uv (2)
 *   'C' contour      attrs, u8 solid, i64 depth, z, u64 n, power, speed,
 *                    point_distance, exposure_time, u8 has_uv, 3n reals
 *                    (xyz), 2n reals (uv) when has_uv
 *   'H' hatches      attrs, i64 kind (lam_vec_kind), z, u64 n, angle,
 *                    power, speed, point_distance, exposure_time, u8
 *                    has_uv, 6n reals, 4n when has_uv
 *
 * The decoder reads a record's structure (its counts against the bytes
 * left); what the values may be is the reader's to check (part.c checks
 * every value of a part file, which may come from anywhere). */
#ifndef LAM_PLAN_RECORD_H
#define LAM_PLAN_RECORD_H

#include <stddef.h>
#include <stdint.h>

#include "hatch.h"
#include "plan.h"

/* The decoder's scratch (zero it first; free with lam_rec_scratch_free). */
typedef struct lam_rec_scratch {
    double *d;
    size_t cap;
} lam_rec_scratch;

/* Encoded records in memory. */
typedef struct lam_record {
    unsigned char *buf;
    size_t len, cap;
    int failed;              /* out of memory while recording */
    lam_rec_scratch sc;      /* the replay's points, kept for the next layer */
} lam_record;

/* A sink recording into r (not owned; r starts empty or cleared). It has
 * exactly the callbacks `like` has among feed, laser, move, contour and
 * hatches, so a planner decides what to compute as it would for `like`;
 * begin, layer, layer_end and end are NULL (the caller sends them, or
 * records them with lam_record_layer). A callback returns LAM_ENOMEM when
 * memory runs out. */
lam_sink lam_record_sink(lam_record *r, const lam_sink *like);

/* Record a layer's start ('L'), or its end with its estimate t ('E'). */
int lam_record_layer(lam_record *r, const lam_layer_info *li);
int lam_record_layer_end(lam_record *r, const lam_layer_info *li, const lam_scan_time *t);

/* Append n raw bytes (a file's header around the records). Out of memory
 * marks r failed. */
void lam_record_bytes(lam_record *r, const void *p, size_t n);

/* Forget the records, keeping the memory for the next layer. */
void lam_record_clear(lam_record *r);

/* Send r's operations to sink in the order they came (layers too, when
 * recorded: the layer's info then has neither section nor estimate).
 * Returns the first error a callback returns. */
int lam_record_replay(lam_record *r, const lam_sink *sink);

/* Release r's memory. */
void lam_record_free(lam_record *r);

/* ---- decoding ------------------------------------------------------------- */

/* Where records are read from. get reads exactly n bytes into dst or
 * fails (LAM_EFORMAT when the bytes end: a truncated record); left is the
 * number of bytes not read yet; corrupt makes the error of a malformed
 * record (what: "an unknown record", "a count larger than the file", ...)
 * at the current position. */
typedef struct lam_rec_source {
    void *ctx;
    int (*get)(void *ctx, void *dst, size_t n, lam_error *err);
    unsigned long long (*left)(void *ctx);
    int (*corrupt)(void *ctx, const char *what, lam_error *err);
} lam_rec_source;

/* One decoded record. The point arrays of move, contour and hatches point
 * into the decoder's scratch: valid until the next lam_rec_read. */
typedef struct lam_rec_op {
    int tag;                 /* 'L', 'E', 'F', 'A', 'M', 'C', 'H'; 'Z': not a record (the tag only) */
    uint64_t index;          /* 'L', 'E': the layer's index as written */
    lam_layer_info layer;    /* 'L', 'E' (index, heights; no section, no time: a sink
                                replayed onto sees the layers as join always gave them) */
    uint64_t counts[4];      /* 'E': the estimate's counts as written */
    lam_scan_time time;      /* 'E' */
    double rate;             /* 'F' */
    int flag;                /* 'A': on; 'M': deposit; 'C', 'H': has_uv (as written) */
    int64_t kind;            /* 'H': as written */
    lam_move_info move;      /* 'M' */
    lam_contour_info contour;/* 'C' */
    lam_hatch_info hatches;  /* 'H' */
} lam_rec_op;

void lam_rec_scratch_free(lam_rec_scratch *sc);

/* Read the next record from src into op. A tag 'Z' is returned without
 * reading anything after it. Errors: src's, src->corrupt's (an unknown
 * tag, counts larger than what is left), LAM_ENOMEM. */
int lam_rec_read(const lam_rec_source *src, lam_rec_scratch *sc, lam_rec_op *op, lam_error *err);

/* Send op ('F', 'A', 'M', 'C', 'H', 'L', 'E') to sink (a callback sink
 * leaves NULL is skipped). */
int lam_rec_send(const lam_rec_op *op, const lam_sink *sink);

#endif
