/* The tee sink: every operation to every sink in order, the first error
 * stops an operation, end reaches every sink, destroy destroys them all;
 * and the JSON sink through it, into a memory writer: a string that needs
 * escaping, '<' in script mode, no NaN. */
#include "json_sink.h"
#include "tap.h"
#include "tee.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct log {
    char s[256];
    int fail_layer; /* layer returns LAM_EIO */
    int fail_end;
} logsink;

static void add(logsink *l, const char *what) { strncat(l->s, what, sizeof l->s - strlen(l->s) - 1); }
static int l_begin(void *c, const lam_job_info *j) { (void)j; add(c, "b"); return 0; }
static int l_layer(void *c, const lam_layer_info *li)
{
    (void)li;
    add(c, "l");
    return ((logsink *)c)->fail_layer ? LAM_EIO : 0;
}
static int l_move(void *c, const lam_move_info *m) { add(c, m->deposit ? "D" : "T"); return 0; }
static int l_end(void *c)
{
    add(c, "e");
    return ((logsink *)c)->fail_end ? LAM_EINVAL : 0;
}
static void l_destroy(void *c) { add(c, "x"); }
static int l_fork(void *c, int moves, lam_sink_fork *out, lam_error *err)
{
    (void)err;
    add(c, moves ? "F" : "f");
    memset(out, 0, sizeof *out);
    out->main = c;
    return LAM_OK;
}

static lam_sink mk(logsink *l)
{
    lam_sink s;
    memset(&s, 0, sizeof s);
    s.ctx = l;
    s.begin = l_begin;
    s.layer = l_layer;
    s.move = l_move;
    s.end = l_end;
    s.destroy = l_destroy;
    return s;
}

int main(void)
{
    lam_error err;
    lam_error_clear(&err);
    logsink a = { "", 0, 0 }, b = { "", 0, 0 };
    lam_sink both[2] = { mk(&a), mk(&b) }, t;
    ok(lam_tee_sink(both, 2, &t, &err) == LAM_OK, "a tee of two sinks");
    ok(t.hatches == NULL, "no sink takes hatches: neither does the tee");
    lam_job_info job;
    memset(&job, 0, sizeof job);
    lam_layer_info li;
    memset(&li, 0, sizeof li);
    lam_move_info p = { .deposit = 1, .xyz = { 1, 2, 3 } };
    t.begin(t.ctx, &job);
    t.layer(t.ctx, &li);
    t.move(t.ctx, &p);
    t.feed(t.ctx, 1); /* neither has feed: skipped */
    ok(t.end(t.ctx) == LAM_OK, "end: both fine");
    is_str(a.s, "blDe", "the first sink got every operation");
    is_str(b.s, "blDe", "so did the second");
    a.s[0] = b.s[0] = '\0';
    a.fail_layer = 1;
    b.fail_end = 1;
    ok(t.layer(t.ctx, &li) == LAM_EIO, "a failing sink's error comes back");
    is_str(b.s, "", "... and the sinks after it do not get the operation");
    ok(t.end(t.ctx) == LAM_EINVAL, "end: the first error of any sink");
    is_str(a.s, "le", "... every sink was ended");
    t.destroy(t.ctx);
    ok(strchr(a.s, 'x') && strchr(b.s, 'x'), "destroy destroys every sink");
    ok(lam_tee_sink(both, 0, &t, &err) == LAM_EUSAGE, "a tee of no sinks: LAM_EUSAGE");

    /* fork (plan.h): a tee of one forwards its sink's, a tee of several has none */
    a.s[0] = b.s[0] = '\0';
    both[0].fork = both[1].fork = l_fork;
    lam_sink_fork fk;
    ok(lam_tee_sink(both, 2, &t, &err) == LAM_OK && t.fork == NULL, "a tee of two sinks cannot be forked");
    free(t.ctx); /* not destroyed: the sinks stay ours */
    ok(lam_tee_sink(both, 1, &t, &err) == LAM_OK && t.fork != NULL, "a tee of one sink that forks does too");
    ok(t.fork(t.ctx, 1, &fk, &err) == LAM_OK && fk.main == &a, "... with the sink's own fork");
    is_str(a.s, "F", "... which was told of the moves");
    free(t.ctx);
    both[0].fork = NULL;
    ok(lam_tee_sink(both, 1, &t, &err) == LAM_OK && t.fork == NULL, "a tee of one that does not fork does not");
    free(t.ctx);
    both[1].fork = NULL;

    /* the JSON into memory, behind a tee: the <script> text to w, the
     * plain JSON to w2, from one consumer of one vector stream */
    lam_writer *w, *w2;
    lam_writer_memory(&w, &err);
    lam_writer_memory(&w2, &err);
    lam_sink js, one[1];
    lam_vec_consumer jc;
    ok(lam_json_consumer(w2, w, &jc, &err) == LAM_OK && lam_vstream_sink(&jc, 1, &js, &err) == LAM_OK, "a JSON sink");
    one[0] = js;
    lam_tee_sink(one, 1, &t, &err);
    job.model = "a\"b\\</script>\xff.ug";
    job.name = "m";
    job.process = "ladrp";
    job.units = "mm";
    job.bead = 0.1;
    job.layers = 1;
    int rc = t.begin(t.ctx, &job);
    li.z = 0.1;
    li.width = 0.2;
    li.ceiling = 0.2;
    if (!rc) rc = t.layer(t.ctx, &li);
    lam_move_info q = { .attrs = lam_attrs_default(), .deposit = 1, .xyz = { 0.1, 0.2, 0.1 } };
    if (!rc) rc = t.move(t.ctx, &q);
    if (!rc) rc = t.layer_end(t.ctx, &li);
    if (!rc) rc = t.end(t.ctx);
    ok(rc == LAM_OK, "a one-layer run");
    char *text;
    size_t len;
    lam_writer_take(w, &text, &len, &err);
    ok(strstr(text, "\"model\": \"a\\\"b\\\\\\u003c/script>\\ufffd.ug\"") != NULL,
       "quotes and backslashes escaped, '<' as \\u003c, a byte that is not UTF-8 as U+FFFD");
    ok(strstr(text, "{\"kind\": \"deposit\", \"from\": [0, 0, 0], \"to\": [0.1, 0.2, 0.1], \"order\": 1}") != NULL,
       "a deposit from the job's origin, shortest numbers");
    ok(strstr(text, "\"stats\": {\"area\": 0, \"vectors\": 1, \"deposit_length\": 0.24494897427831783, "
                    "\"travel_length\": 0, \"time\": null}") != NULL,
       "the layer's figures: sqrt(0.06)");
    ok(len > 0 && text[len - 1] == '\n', "the document ends with a newline");
    char *plain;
    size_t plen;
    lam_writer_take(w2, &plain, &plen, &err);
    ok(strstr(plain, "\"model\": \"a\\\"b\\\\</script>\\ufffd.ug\"") != NULL && plen + 5 == len,
       "the plain JSON: the same text with its one '<' as it is");
    free(plain);
    free(text);
    t.destroy(t.ctx);

    /* a NaN is an error, not a document that no reader accepts */
    lam_writer_memory(&w, &err);
    lam_json_consumer(w, NULL, &jc, &err);
    lam_vstream_sink(&jc, 1, &js, &err);
    job.bead = NAN;
    ok(js.begin(js.ctx, &job) == LAM_EINVAL && strstr(err.msg, "not finite"), "NaN: LAM_EINVAL (%s)", err.msg);
    js.destroy(js.ctx);
    lam_writer_abort(w);
    return done_testing();
}
