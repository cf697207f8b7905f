/* Part files: one layer range of a slicing run, to be joined with the
 * other parts into exactly the program the whole run writes (`lamina slice
 * --layers A:B` writes one, `lamina join` assembles them).
 *
 * What a part holds. Not the program's text: the operations the planner
 * gave the sink for its layers (lam_sink calls with their numbers as
 * IEEE 754 bits), which join replays, in layer order, into the one sink
 * the machine profile names. A dialect's text for a layer can depend on
 * every layer before it (relative moves carry the stage position read back
 * from the text since the job began; the separator goes between blocks
 * across layers; a plugin writer counts layers against its header), so
 * text made in pieces could not be put together byte for byte; the same
 * sink fed the same calls in the same order writes the same bytes, for
 * every dialect and every plugin writer. Slicing, contour building,
 * planning and hatching run in the parts; join only formats.
 *
 * Format, version 3 (integers unsigned 64-bit little-endian unless said,
 * reals IEEE 754 binary64 little-endian, strings a length then the bytes):
 *
 *   magic "LAMPART\0", u32 version, u32 flags (0)
 *   u64 identity       the run's identity (lam_part_identity): parts of
 *                      different runs are never joined
 *   u64 first, last    the part's layers, 1-based, inclusive
 *   u64 layers         the whole run's layer count
 *   job                name process units label (strings), bbox[6], bead,
 *                      rate, travel_rate, origin[3] (reals): lam_job_info
 *   profile            the resolved machine profile (lam_profile_dump), the
 *                      one join writes through
 *   model              the model's path as given (for join's messages)
 *   attributes         u64 count, then each key (string): vocab.h's
 *                      attribute table the records carry; a part of a
 *                      lamina with another table is refused
 *   labels             u64 count, then each label (string): a build's CLI
 *                      labels (lam_job_info.labels; 0 for a single part)
 *   u64 FNV-1a hash of the header's bytes before it (read before anything
 *                      the header says is used)
 *   records            the plan's encoding (plan_record.h: 'L' layer, 'E'
 *                      layer end, 'F', 'A', 'M', 'C', 'H' operations), the
 *                      same records worker threads keep in memory
 *     'Z' end          u64 FNV-1a hash of every byte before this tag
 *   and nothing after it.
 *
 * A part with a wrong magic, version, hash, truncated or with bytes after
 * its end is refused with the byte offset where it went wrong; so is one
 * whose hashes match but whose values no slicing run writes (numbers that
 * are not finite; points outside the job's box, by more than two beads;
 * heights outside their layer; negative rates or exposures; flags other
 * than 0 and 1; hatch kinds other than the hatch regions; negative
 * attributes or larger than the file; operations outside a
 * layer; counts larger than the file), naming the layer. Contours and
 * hatches carry their layer-frame points (has_uv 1). */
#ifndef LAM_PART_H
#define LAM_PART_H

#include <stdint.h>

#include "error.h"
#include "hatch.h"
#include "plan.h"
#include "plan_record.h"
#include "slice.h"
#include "writer.h"

#define LAM_PART_VERSION 3

/* What a part says about itself (strings owned by the part or the caller). */
typedef struct lam_part_meta {
    uint64_t identity;
    size_t first, last;      /* 1-based, inclusive */
    size_t layers;           /* the whole run's */
    const char *profile;     /* resolved YAML */
    size_t profile_len;
    const char *model;       /* the model's path as the slicing run was given it */
} lam_part_meta;

/* The identity of a run: FNV-1a over the resolved profile text, the
 * model file's bytes (read from model_path) and the slicer's layers
 * (planes, cuts, frame, gap). Two runs with equal identities write the same
 * program. Errors: LAM_EIO reading the model. */
int lam_part_identity(const char *model_path, const char *profile, size_t profile_len, const lam_slicer *s,
                      uint64_t *out, lam_error *err);

/* FNV-1a of data[0 .. n) continuing from h (0: from the start), as the
 * identities and the part's checks hash: for a build's identity
 * (build_run.h), which mixes its parts'. */
uint64_t lam_part_hash(uint64_t h, const void *data, size_t n);

/* A sink that writes a part file to w (not owned; the caller commits or
 * aborts it). meta's strings are copied. time, when not NULL, is the
 * planner's o->time: the sink records it at each layer's end as that
 * layer's estimate and sets it back to zero (so after the run it holds
 * nothing; join adds the layers up in order, as the whole run does);
 * NULL: each layer's own estimate (lam_layer_info.time at layer_end, a
 * build's). */
int lam_part_sink(const lam_part_meta *meta, lam_scan_time *time, lam_writer *w, lam_sink *out, lam_error *err);

typedef struct lam_part lam_part;

/* Open a part file and read its header (the records are read by
 * lam_part_join). Errors: LAM_EIO, LAM_EFORMAT (not a part file, another
 * version, a corrupt header), LAM_ENOMEM. */
int lam_part_open(const char *path, lam_part **out, lam_error *err);

/* The same from len bytes at data (name for messages), which must stay
 * unchanged while the part is open; read within len. */
int lam_part_open_buf(const char *name, const void *data, size_t len, lam_part **out, lam_error *err);

/* The part's header; valid while the part is open. */
const lam_part_meta *lam_part_get_meta(const lam_part *p);

/* The whole run's job (begin's lam_job_info); valid while the part is open. */
const lam_job_info *lam_part_job(const lam_part *p);

/* Put parts[0..n) in layer order and check that they are one run's (same
 * identity) and hold every layer exactly once. Errors (LAM_EINVAL, naming
 * the files): a part of another run, two parts that overlap, layers no
 * part holds. */
int lam_part_order(lam_part **parts, size_t n, lam_error *err);

/* Replay ordered parts (lam_part_order) into sink: begin with the run's
 * job, every record, end; each call reads the parts from their first
 * record (a first call with an empty sink checks every part whole). time (may be NULL) gets the run's build-time
 * estimate added layer by layer; layer_time (may be NULL), room for every
 * layer of the run, each layer's total. Errors: a corrupt or truncated part
 * (LAM_EFORMAT, with the file and byte offset), what the sink returns. */
int lam_part_join(lam_part *const *parts, size_t n, const lam_sink *sink, lam_scan_time *time, double *layer_time,
                  lam_error *err);

void lam_part_close(lam_part *p);

#endif
