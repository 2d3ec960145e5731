/* proto.c - the protocol engine: the link, command lines, real-time bytes, replies, and
 * the run, dispatched to its output format (out_gcode.c, out_frames.c) at one switch per
 * seam: run_start, run_emit, run_finish, host_answer, feed; the machine link's lines
 * (machine_take, machine_line) and the pass-through.
 * SPDX-License-Identifier: MIT
 */
#include "proto.h"
#include "fmt.h"
#include "parse.h"

#define PROTO_LF_OVERFLOW 0x01u /* the line exceeded CP_LINE_MAX-1 bytes */
#define PROTO_LF_BADCHAR 0x02u  /* the line held a byte outside 0x20..0x7E */

#define RT_STATUS '?'
#define RT_HOLD '!'
#define RT_RESUME '~'
#define RT_ABORT 0x18

static const char *const status_texts[CP_ST_END_] = {
#define CP_STATUS(name, num, text, from) [num] = text,
#include "cp_status.def"
#undef CP_STATUS
};

const char *cp_status_text(int code)
{
    if (code < 0 || code >= CP_ST_END_ || status_texts[code] == NULL) {
        return "?";
    }
    return status_texts[code];
}

int proto_init(struct proto *p, const struct proto_cfg *cfg)
{
    if (p == NULL || cfg == NULL || cfg->uart == NULL || cfg->uart->write == NULL ||
        cfg->uart->read == NULL || cfg->uart->now_ms == NULL) {
        return CP_ERR_INVAL;
    }
    if (cfg->machine != NULL && (cfg->machine->write == NULL || cfg->machine->read == NULL ||
                                 cfg->machine->now_ms == NULL)) {
        return CP_ERR_INVAL;
    }
    {
        /* every counter, length, flag and buffer 0: line_len, rx/tx, err = CP_OK,
         * state = PROTO_IDLE, fmt = JOB_GCODE, the tail closed, ... (volatile stores,
         * as in job_init: no library memset in the image). The format state is set up
         * by its start call. */
        volatile unsigned char *b = (volatile unsigned char *)p;
        size_t i;
        for (i = 0; i < sizeof *p; i++) {
            b[i] = 0u;
        }
    }
    p->uart = cfg->uart;
    machine_link_init(&p->mach, cfg->machine);
    job_init(&p->job);
    return CP_OK;
}

/*---------------------------------------------------------------------------
 * Output staging. Callers check tx_room() >= PROTO_REPLY_MAX before a burst,
 * so the appends below cannot fail; a failure would truncate, never overrun.
 *-------------------------------------------------------------------------*/
static size_t tx_room(struct proto *p)
{
    return link_tx_room(p->tx, sizeof p->tx, &p->tx_len, &p->tx_pos);
}

static void tx_str(struct proto *p, const char *s)
{
    size_t pos = p->tx_len;
    (void)fmt_str((char *)p->tx, sizeof p->tx, &pos, s);
    p->tx_len = (uint16_t)pos;
}

static void tx_u32(struct proto *p, uint32_t v)
{
    size_t pos = p->tx_len;
    (void)fmt_u32((char *)p->tx, sizeof p->tx, &pos, v);
    p->tx_len = (uint16_t)pos;
}

/* A key and its number: "|P:" and 12 (a report's field, an option, an error code). */
static void tx_field(struct proto *p, const char *key, uint32_t v)
{
    tx_str(p, key);
    tx_u32(p, v);
}

/* "error:<code> <text>", the head of every error reply (a cause may follow). */
static void tx_error(struct proto *p, int code)
{
    tx_field(p, "error:", (uint32_t)code);
    tx_str(p, " ");
    tx_str(p, cp_status_text(code));
}

/* "ok" or the error reply of a status code. (Not inlined: one copy for its three
 * callers, -20 B on the all-features image.) */
static CP_NOINLINE void reply_status(struct proto *p, int code)
{
    if (code == CP_ST_OK) {
        tx_str(p, "ok\n");
        return;
    }
    tx_error(p, code);
    tx_str(p, "\n");
}

/* Append s[0..n) to the tx buffer (at most the room left). */
static void tx_mem(struct proto *p, const char *s, size_t n)
{
    link_tx_put(p->tx, sizeof p->tx, &p->tx_len, s, n);
}

/* The reply to a command line: reply_status, and for an error whose cause job_line named
 * "error:<code> <text> (<keyword> <token>: <limit>)", the token as typed (its first
 * PROTO_CAUSE_TOKEN_MAX chars) and the limit it broke, each part only when known. The
 * line (trimmed: its keyword first) is still in p->line. */
#define PROTO_CAUSE_TOKEN_MAX 24u
static void reply_command(struct proto *p, int code)
{
    const struct job *j = &p->job;
    size_t kw = 0;
    if (code == CP_ST_OK ||
        (j->cause_len == 0u && j->cause_limit == NULL && j->cause_args_max == 0u)) {
        reply_status(p, code);
        return;
    }
    while (kw < p->line_len && kw < PARSE_KW_MAX && p->line[kw] != ' ') {
        kw++;
    }
    tx_error(p, code);
    tx_str(p, " (");
    tx_mem(p, p->line, kw);
    if (j->cause_len != 0u && (size_t)j->cause_st + j->cause_len <= p->line_len) {
        tx_str(p, " ");
        tx_mem(p, p->line + j->cause_st,
               j->cause_len < PROTO_CAUSE_TOKEN_MAX ? j->cause_len : PROTO_CAUSE_TOKEN_MAX);
    }
    if (j->cause_limit != NULL) {
        tx_str(p, ": ");
        tx_str(p, j->cause_limit);
    }
    if (j->cause_args_max != 0u) { /* "(LINES: 3..4 arguments)" */
        tx_field(p, ": ", j->cause_args_min);
        if (j->cause_args_max != j->cause_args_min) {
            tx_field(p, "..", j->cause_args_max);
        }
        tx_str(p, j->cause_args_max == 1u ? " argument" : " arguments");
    }
    tx_str(p, ")\n");
}

/* "[VER:canalpath <fw> proto <n>]" and "[OPT:real=..,line=..,...,models=..]" */
static void reply_info(struct proto *p)
{
    static const struct {
        const char *key;
        uint32_t value;
    } opt[] = {
        {",line=", CP_LINE_MAX},      {",tx=", CP_TX_BUF},          {",steps=", CP_MAX_STEPS},
        {",sub=", CP_MAX_SUBSTEPS},   {",lines=", CP_MAX_LINES},    {",link=", CP_MAX_LINK},
        {",window=", OUT_FRAMES_WINDOW},
    };
    size_t i;
    tx_field(p, "[VER:canalpath " CP_FW_VERSION " proto ", CP_PROTO_VERSION);
    tx_str(p, "]\n[OPT:real=" CP_REAL_NAME);
    for (i = 0; i < sizeof opt / sizeof opt[0]; i++) {
        tx_field(p, opt[i].key, opt[i].value);
    }
    tx_str(p, ",models=");
    tx_str(p, job_models());
    tx_str(p, "]\n");
}

/* 1 while a run streams (PROTO_RUN, PROTO_HOLD): its output format's state is set up. */
static int streaming(const struct proto *p)
{
    return p->state == PROTO_RUN || p->state == PROTO_HOLD;
}

/* "<Idle>", "<Check|W:w|S:i/m>" (RUN's check: walk w of the patch, its step i of m;
 * path_check_progress) or "<Run|L:j/n|P:k/m>" ("<Hold|...>"): the line (or circle) j of
 * n of the last point sent, and k points of the job's m sent (k counts from the job's
 * first point: RESUME); then "|Overlap:1" when the run's path reported far parts that
 * meet (path_info.overlap). */
static void reply_report(struct proto *p)
{
    static const char *const names[4] = {[PROTO_IDLE] = "<Idle",
                                         [PROTO_RUN] = "<Run",
                                         [PROTO_HOLD] = "<Hold",
                                         [PROTO_CHECK] = "<Check"};
    uint32_t m = path_count(&p->path), k, block;
    tx_str(p, names[p->state]);
    if (p->state == PROTO_CHECK) {
        path_check_progress(&p->path, &p->out.check, &block, &k, &m);
        tx_field(p, "|W:", block);
        tx_field(p, "|S:", k);
        tx_field(p, "/", m);
    } else if (p->state != PROTO_IDLE) {
        /* the items sent after the lead items (header lines, BEGIN) are points from
         * start_k on, up to the last one (then END) */
        k = p->run.start_k + (p->run.next > p->run.lead ? p->run.next - p->run.lead : 0u);
        if (k > m) { /* start_k + next <= m + 2 (the end of a run): no wrap above */
            k = m;
        }
        block = (uint32_t)p->path.info.steps + 1u + p->path.info.link;
        tx_field(p, "|L:", k > 0u ? (k - 1u) / block : 0u);
        tx_field(p, "/", p->path.info.n);
        tx_field(p, "|P:", k);
        tx_field(p, "/", m);
        /* an overlap the model's init reported (the tool inside: harmless) stays in
         * every report of the run */
        if (p->path.info.overlap) {
            tx_str(p, "|Overlap:1");
        }
    }
    tx_str(p, ">\n");
}

/*---------------------------------------------------------------------------
 * The run: one switch on the output format per seam
 *-------------------------------------------------------------------------*/
static void run_finish(struct proto *p, int status)
{
    size_t n = 0;
    switch ((enum job_format)p->fmt) {
    case JOB_GCODE:
        p->tail.open = 0;
        break;
    case JOB_FRAMES:
        /* tell a binary host why the stream stopped, then the text reply; late frames
         * of the host may still come */
        n = out_frames_finish(&p->run, status, p->tx + p->tx_len, sizeof p->tx - p->tx_len);
        p->tail.open = 1;
        break;
    }
    p->tx_len = (uint16_t)(p->tx_len + n);
    if (p->fault_len > 0u && (status == CP_ST_PEER_ERROR || status == CP_ST_MACHINE_RESET)) {
        /* "error:19 machine reported an error (machine ALARM:9)" */
        tx_error(p, status);
        tx_str(p, " (machine ");
        tx_mem(p, p->fault, p->fault_len);
        tx_str(p, ")\n");
    } else {
        reply_status(p, status);
    }
    p->state = PROTO_IDLE;
}

/* RUN (first = 0) or RESUME first: begin the job's check (PROTO_CHECK; proto_poll runs it
 * in slices, run_check). Returns CP_ST_OK (the reply comes at the end of the run) or the
 * status to reply now. */
static int run_start(struct proto *p, uint32_t first)
{
    int err;
    if (job_ready(&p->job) != CP_ST_OK) {
        return CP_ST_NO_JOB;
    }
    job_geom_fill(&p->job);
    err = path_check_begin(&p->path, &p->out.check, p->job.kind, &p->job.cfg, &p->job.geom);
    if (err != PATH_CHECK_MORE) {
        return cp_status_of(err);
    }
    p->run.start_k = first;
    p->state = PROTO_CHECK;
    return CP_ST_OK;
}

/* The check passed: what the program needs, the RESUME point, then the stream starts.
 * Returns CP_ST_OK or the status to reply. */
static int run_checked(struct proto *p)
{
    uint32_t first = p->run.start_k;
    size_t n = 0;
    int err;
    if (p->job.format == JOB_GCODE) { /* the geometry first, then what the program needs */
        err = out_gcode_check(&p->job);
        if (err != CP_ST_OK) {
            return err;
        }
        if (p->job.link == JOB_LINK_MACHINE && p->mach.uart == NULL) {
            return CP_ST_NO_MACHINE_LINK;
        }
    }
    if (first >= path_count(&p->path)) {
        return CP_ST_RESUME_RANGE;
    }
    if (first > 0u && path_seek(&p->path, first) != CP_OK) {
        return CP_ST_RESUME_RANGE;
    }
    p->fmt = p->job.format;
    p->prog_link = p->job.format == JOB_GCODE ? p->job.link : (uint8_t)JOB_LINK_HOST;
    p->fault_len = 0u;
    p->run.start_k = first;
    p->run.next = 0;
    p->run.acked = 0;
    p->run.t_last = hal_uart_now_ms(p->uart);
    place_init(&p->run.place, &p->job.place); /* the matrix once per RUN */
    p->state = PROTO_RUN;
    switch ((enum job_format)p->fmt) { /* (the check's state in p->out is over) */
    case JOB_GCODE:
        n = out_gcode_start(&p->out.gcode, &p->run, &p->job, &p->path, p->tx + p->tx_len,
                            sizeof p->tx - p->tx_len);
        break;
    case JOB_FRAMES:
        out_frames_start(&p->out.frames, &p->run, &p->path);
        break;
    }
    p->tx_len = (uint16_t)(p->tx_len + n);
    return CP_ST_OK;
}

/* One slice of RUN's check (PROTO_CHECK; path_check_step); at its end the stream starts,
 * or the RUN command gets its error. Returns 1 (a slice is work done). */
static int run_check(struct proto *p)
{
    int st;
    if (tx_room(p) < PROTO_REPLY_MAX) {
        return 0; /* the stream's first item, or the reply, may need a whole burst */
    }
    st = path_check_step(&p->path, &p->out.check, &p->job.cfg, &p->job.geom);
    if (st == PATH_CHECK_MORE) {
        return 1;
    }
    p->state = PROTO_IDLE;
    st = st == CP_OK ? run_checked(p) : cp_status_of(st);
    if (st != CP_ST_OK) {
        reply_status(p, st);
    }
    return 1;
}

/*---------------------------------------------------------------------------
 * The machine link
 *-------------------------------------------------------------------------*/
/* With the program on the machine link: a dialect with a POLL byte (grbl '?') is asked
 * for a status report when it has been silent OUT_GCODE_POLL_MS while lines are in
 * flight or a passed-through line waits (its "<...>" proves it alive: a long move). */
static void machine_poll(struct proto *p, uint32_t now)
{
    uint8_t c = machine_dialect(p->job.machine)->poll;
    int due = 0;
    if (c == 0u || machine_link_room(&p->mach) == 0u) {
        return;
    }
    if (streaming(p) && p->fmt == JOB_GCODE && p->prog_link == JOB_LINK_MACHINE) {
        due = out_gcode_poll_due(&p->out.gcode, &p->run, now);
    } else if (p->pass && (uint32_t)(now - p->t_pass) >= OUT_GCODE_POLL_MS &&
               (uint32_t)(now - p->t_mpoll) >= OUT_GCODE_POLL_MS) {
        p->t_mpoll = now; /* (t_pass, the answer's clock, runs on) */
        due = 1;
    }
    if (due) {
        machine_link_put(&p->mach, (const char *)&c, 1u);
    }
}

/* Keep the machine's line that stopped a run, for the host's reply. (Not inlined: one copy
 * for the machine link's lines and the host link's.) */
static CP_NOINLINE void keep_fault(struct proto *p, const char *line, size_t len)
{
    size_t i;
    for (i = 0; i < len && i < PROTO_FAULT_MAX; i++) {
        p->fault[i] = line[i];
    }
    p->fault_len = (uint8_t)i;
}

/* "[MACHINE:<line>]": a machine line that is not an answer, relayed to the host. */
static void relay_wrapped(struct proto *p, const char *line, size_t len)
{
    tx_str(p, "[MACHINE:");
    tx_mem(p, line, len);
    tx_str(p, "]\n");
}

/* One complete line from the machine link (p->mach.line). Host tx room >= PROTO_REPLY_MAX. */
static void machine_line(struct proto *p)
{
    const char *line = p->mach.line;
    size_t len = p->mach.line_len;
    uint32_t num;
    enum machine_reply kind = machine_reply(p->job.machine, line, len, &num);
    uint32_t now = hal_uart_now_ms(p->uart);
    if (streaming(p) && p->fmt == JOB_GCODE && p->prog_link == JOB_LINK_MACHINE) {
        int st = out_gcode_answer(&p->out.gcode, &p->run, &p->job, kind, num, now);
        if (kind == MACHINE_OTHER && len > 0u) {
            relay_wrapped(p, line, len);
        }
        if (st != OUT_GOING) {
            keep_fault(p, line, len);
            run_finish(p, st);
        }
        return;
    }
    if (p->pass) { /* a passed-through host line: its conversation goes up as it is */
        if (kind != MACHINE_ALIVE) {
            p->t_pass = now; /* a status report to the poll is life, not an answer */
        }
        tx_mem(p, line, len);
        tx_str(p, "\n");
        if (kind == MACHINE_OK || kind == MACHINE_ERROR) {
            p->pass = 0u;
        }
        return;
    }
    if (len > 0u && p->lines_seen > 0u) {
        /* unasked: a banner, an alarm, late answers (nothing before the host has spoken) */
        relay_wrapped(p, line, len);
    }
}

/* The machine link is gone (hang-up): a run on it ends, and the port has one link now. */
static void machine_gone(struct proto *p)
{
    p->mach.uart = NULL;
    p->pass = 0u;
    if (streaming(p) && p->prog_link == JOB_LINK_MACHINE) {
        run_finish(p, CP_ST_NO_MACHINE_LINK);
    }
}

/* Take the machine's lines (at most MACHINE_RX_CHUNK per call, while a relayed line fits
 * the host's tx), time out a passed-through line, poll a silent machine. Returns 1 if
 * anything moved. */
static int machine_take(struct proto *p)
{
    unsigned i;
    int moved = 0;
    uint32_t now;
    if (p->mach.uart == NULL) {
        return 0;
    }
    for (i = 0; i < MACHINE_RX_CHUNK && tx_room(p) >= PROTO_REPLY_MAX; i++) {
        int r = machine_link_line(&p->mach);
        if (r < 0) {
            machine_gone(p);
            return 1;
        }
        if (r == 0) {
            break;
        }
        machine_line(p);
        moved = 1;
    }
    now = hal_uart_now_ms(p->uart);
    if (p->pass && (uint32_t)(now - p->t_pass) > PROTO_PASS_TIMEOUT_MS &&
        tx_room(p) >= PROTO_REPLY_MAX) {
        p->pass = 0u;
        reply_status(p, CP_ST_TIMEOUT);
        moved = 1;
    }
    if (p->state == PROTO_IDLE) {
        machine_poll(p, now);
    }
    return moved;
}

/* Emit at most one stream item if flow control allows. Returns 1 if one was sent or
 * the run ended. */
static int run_emit(struct proto *p)
{
    uint32_t now = hal_uart_now_ms(p->uart);
    int sending = p->state == PROTO_RUN;
    int st = OUT_GOING;
    size_t n = 0, cap;
    uint8_t *out;
    if (tx_room(p) < PROTO_REPLY_MAX) {
        return 0; /* an item, or the end of the run with its reply, may need a whole burst */
    }
    out = p->tx + p->tx_len;
    cap = sizeof p->tx - p->tx_len;
    switch ((enum job_format)p->fmt) {
    case JOB_GCODE:
        if (p->prog_link == JOB_LINK_MACHINE) { /* the program goes down the machine link */
            size_t room = machine_link_room(&p->mach); /* a line waits until it fits */
            st = out_gcode_emit(&p->out.gcode, &p->run, &p->path, &p->job, now, sending,
                                p->mach.tx + p->mach.tx_len, room, &n);
            p->mach.tx_len = (uint16_t)(p->mach.tx_len + n);
            machine_poll(p, now);
            if (st != OUT_GOING) {
                run_finish(p, st);
                return 1;
            }
            return n > 0u;
        }
        st = out_gcode_emit(&p->out.gcode, &p->run, &p->path, &p->job, now, sending, out, cap,
                            &n);
        break;
    case JOB_FRAMES:
        st = out_frames_emit(&p->out.frames, &p->run, &p->path, now, sending, out, cap, &n);
        break;
    }
    p->tx_len = (uint16_t)(p->tx_len + n);
    if (st != OUT_GOING) {
        run_finish(p, st);
        return 1;
    }
    return n > 0u;
}

/* A host-link line that is a machine's answer (ok, error:, ALARM:, Error:, Resend:, rs,
 * busy:, a banner; machine.h): taken by a G-code run whose program goes up the host link,
 * swallowed without a reply otherwise (late answers after an aborted run must not start a
 * ping-pong; a host never sends them to a machine). Returns 1 if the line was one. */
static int host_answer(struct proto *p)
{
    uint32_t num;
    enum machine_reply kind = machine_reply(p->job.machine, p->line, p->line_len, &num);
    int st = OUT_GOING;
    if (kind == MACHINE_OTHER) {
        return 0;
    }
    if (streaming(p) && p->prog_link == JOB_LINK_HOST) {
        switch ((enum job_format)p->fmt) {
        case JOB_GCODE:
            st = out_gcode_answer(&p->out.gcode, &p->run, &p->job, kind, num,
                                  hal_uart_now_ms(p->uart));
            break;
        case JOB_FRAMES:
            break; /* no text reaches the line assembly during a FRAMES run */
        }
    }
    if (st != OUT_GOING) {
        keep_fault(p, p->line, p->line_len);
        run_finish(p, st);
    }
    return 1;
}

/*---------------------------------------------------------------------------
 * Lines
 *-------------------------------------------------------------------------*/
/* $J: the next item of job_dump as "[JOB:<command line>]", or at the end "ok". One item
 * per call (a line fits PROTO_REPLY_MAX: keyword, word, 9 numbers of at most 16 chars,
 * option); the numbers by fmt_real, so the line reads back to the same job. */
static void dump_step(struct proto *p)
{
    struct job_args a;
    char line[PROTO_REPLY_MAX];
    size_t pos = 0, cap = sizeof line - 3u; /* room for "]\n" and the NUL */
    unsigned k, shape;
    int r = job_dump(&p->job, (unsigned)p->dump - 1u, &a);
    if (r == JOB_DUMP_END) {
        p->dump = 0u;
        reply_status(p, CP_ST_OK);
        return;
    }
    p->dump++;
    if (r != JOB_DUMP_LINE) {
        return;
    }
    shape = job_shape_of(a.cmd);
    (void)fmt_str(line, cap, &pos, "[JOB:");
    (void)fmt_str(line, cap, &pos, job_keyword(a.cmd));
    if (a.word != JOB_NO_WORD) {
        (void)fmt_str(line, cap, &pos, " ");
        (void)fmt_str(line, cap, &pos, job_word_text(a.word));
    } else if (shape == JOB_ARGS_UINT_NUMBERS_OPTION || shape == JOB_ARGS_UINT_OR_WORD) {
        (void)fmt_str(line, cap, &pos, " ");
        (void)fmt_u32(line, cap, &pos, a.u);
    }
    for (k = 0; k < a.na && k < JOB_MAX_NUMBERS; k++) {
        (void)fmt_str(line, cap, &pos, " ");
        (void)fmt_real(line, cap, &pos, a.v[k], JOB_SCALE_FACTOR(a.scale[k]));
    }
    if (a.option != JOB_NO_WORD) {
        (void)fmt_str(line, cap, &pos, " ");
        (void)fmt_str(line, cap, &pos, job_word_text(a.option));
    }
    (void)fmt_str(line, sizeof line, &pos, "]\n");
    line[pos] = '\0';
    tx_str(p, line);
}

/* The commands that answer the version and limits line. */
static const char *const info_words[2] = {"$I", "HELLO"};

static void exec_line(struct proto *p)
{
    uint32_t k = 0;
    int st;
    p->lines_seen++;
    if (p->line_flags != 0u) { /* PROTO_LF_OVERFLOW and/or PROTO_LF_BADCHAR */
        if (p->state == PROTO_IDLE) { /* (machine chatter during a run: no reply into the stream) */
            reply_status(p, (p->line_flags & PROTO_LF_OVERFLOW) ? CP_ST_LINE_TOO_LONG
                                                                : CP_ST_BAD_CHAR);
        }
        return;
    }
    p->line_len = parse_trim(p->line, p->line_len);
    if (host_answer(p)) {
        return;
    }
    if (p->line_len == 0u) {
        if (p->state == PROTO_IDLE) {
            reply_status(p, CP_ST_OK); /* sync, as grbl */
        }
        return;
    }
    if (parse_is_any(p->line, p->line_len, info_words, 2u)) {
        reply_info(p);
        reply_status(p, CP_ST_OK);
        return;
    }
    if (p->state != PROTO_IDLE) {
        /* a G-code run up the host link: the peer is the machine, a job command gets
         * error:7, any other line (echo:, [MSG:...]) is chatter with no reply in the
         * stream; otherwise the host link carries no chatter: every line gets error:7 */
        if (p->prog_link == JOB_LINK_MACHINE || job_is_command(p->line, p->line_len)) {
            reply_status(p, CP_ST_BUSY);
        }
        return;
    }
    p->tail.open = 0; /* a text command: late frames of the last run are over */
    st = job_line(&p->job, p->line, p->line_len, &k);
    if (st == JOB_DUMP) { /* $J: the lines, then ok (proto_poll: dump_step) */
        p->dump = 1u;
        return;
    }
    if (st == JOB_RUN) { /* RUN or RESUME k: a run from point 0 or k ("ok" at its end) */
        st = run_start(p, k);
        if (st == CP_ST_OK) {
            return;
        }
    }
    if (st == JOB_NOT_MINE && p->mach.uart != NULL && p->job.link == JOB_LINK_MACHINE) {
        /* pass-through (proto.h): the cell is wired (LINK MACHINE) */
        machine_link_put(&p->mach, p->line, p->line_len);
        machine_link_put(&p->mach, "\n", 1u);
        p->pass = 1u;
        p->t_pass = p->t_mpoll = hal_uart_now_ms(p->uart);
        return;
    }
    reply_command(p, st == JOB_NOT_MINE ? CP_ST_UNKNOWN_CMD : st);
}

/* '!', '~', 0x18 also go to a machine that has real-time bytes (a dialect with a POLL
 * byte: grbl) when the job's program goes down the machine link. */
static void realtime_to_machine(struct proto *p, uint8_t c)
{
    if (p->mach.uart != NULL && p->job.link == JOB_LINK_MACHINE &&
        machine_dialect(p->job.machine)->poll != 0u && machine_link_room(&p->mach) > 0u) {
        machine_link_put(&p->mach, (const char *)&c, 1u);
    }
}

/* 1 for the host link's real-time bytes. */
static int is_realtime(uint8_t c)
{
    return c == RT_STATUS || c == RT_HOLD || c == RT_RESUME || c == RT_ABORT;
}

/* Real-time bytes act at once, outside the line assembly (grbl). During a G-code run up
 * the host link, whose peer is the machine, only between lines: a '?' inside a line of
 * its chatter (echo:Unknown command: "M999?") is text. */
static int realtime(struct proto *p, uint8_t c)
{
    if (streaming(p) && p->fmt == JOB_GCODE && p->prog_link == JOB_LINK_HOST &&
        p->line_len > 0u) {
        return 0;
    }
    if (c == RT_HOLD || c == RT_RESUME || c == RT_ABORT) {
        realtime_to_machine(p, c);
    }
    switch (c) {
    case RT_STATUS:
        reply_report(p);
        return 1;
    case RT_HOLD:
        if (p->state == PROTO_RUN) {
            p->state = PROTO_HOLD;
        }
        return 1;
    case RT_RESUME:
        if (p->state == PROTO_HOLD) {
            p->state = PROTO_RUN;
            p->run.t_last = hal_uart_now_ms(p->uart);
        }
        return 1;
    case RT_ABORT:
        p->line_len = 0;
        p->line_flags = 0;
        if (p->state == PROTO_CHECK) { /* RUN's check is cancelled: its reply */
            p->state = PROTO_IDLE;
            reply_status(p, CP_ST_ABORTED);
        } else if (p->state != PROTO_IDLE) {
            run_finish(p, CP_ST_ABORTED);
        }
        if (p->pass) { /* the passed-through line gets its terminal reply here */
            p->pass = 0u;
            reply_status(p, CP_ST_ABORTED);
        }
        return 1;
    default:
        return 0;
    }
}

/* Text path: real-time bytes, then line assembly. */
static void feed_text(struct proto *p, uint8_t c)
{
    if (realtime(p, c)) {
        return;
    }
    if (c == '\n' || c == '\r') {
        int skip = (c == '\n' && p->last_cr);
        p->last_cr = (uint8_t)(c == '\r');
        if (skip) {
            return;
        }
        exec_line(p);
        p->line_len = 0;
        p->line_flags = 0;
        return;
    }
    p->last_cr = 0;
    if (c == '\t') {
        c = ' ';
    }
    if (c < 0x20u || c > 0x7Eu) {
        p->line_flags |= PROTO_LF_BADCHAR;
        return;
    }
    if (p->line_len >= CP_LINE_MAX - 1) {
        p->line_flags |= PROTO_LF_OVERFLOW;
        return;
    }
    p->line[p->line_len++] = (char)c;
}

/* A host frame's run control during a FRAMES run (the binary real-time bytes). */
static void frames_control(struct proto *p, enum out_frames_control c)
{
    switch (c) {
    case OUT_FRAMES_ABORT:
        run_finish(p, CP_ST_ABORTED);
        break;
    case OUT_FRAMES_HOLD:
        p->state = PROTO_HOLD;
        break;
    case OUT_FRAMES_GO:
        p->state = PROTO_RUN;
        break;
    case OUT_FRAMES_NONE:
        break;
    }
}

/* One received byte: to the run's output format if it reads bytes (FRAMES), else to
 * the late-frame tail of the last FRAMES run (not for bytes it replays itself), else
 * to the text path. */
static void feed(struct proto *p, uint8_t c, int replayed)
{
    if (streaming(p)) {
        switch ((enum job_format)p->fmt) {
        case JOB_GCODE:
            break; /* the machine's answers are text lines */
        case JOB_FRAMES:
            if (out_frames_rx(&p->out.frames, c)) {
                frames_control(p, out_frames_take(&p->out.frames, &p->run,
                                                  hal_uart_now_ms(p->uart)));
            }
            return; /* text and real-time bytes are not recognised during a FRAMES run */
        }
    }
    if (!replayed && p->tail.open) {
        switch (out_frames_tail_take(&p->tail, c)) {
        case OUT_FRAMES_TAIL_TEXT:
            break;
        case OUT_FRAMES_TAIL_STARTED:
            out_frames_tail_started(&p->tail, hal_uart_now_ms(p->uart));
            return;
        case OUT_FRAMES_TAIL_HELD:
            return;
        }
    }
    feed_text(p, c);
}

int proto_poll(struct proto *p)
{
    int moved = 0;
    int n;
    if (p->err != CP_OK) {
        return p->err;
    }
    /* 1. flush (non-blocking, partial writes are normal) */
    n = link_tx_flush(p->uart, p->tx, &p->tx_len, &p->tx_pos);
    if (n < 0) {
        p->err = CP_ERR_IO;
        return p->err;
    }
    moved |= n;
    n = machine_link_flush(&p->mach);
    if (n < 0) {
        machine_gone(p);
    }
    moved |= (n > 0);
    /* 2. refill the receive chunk */
    if (p->rx_pos == p->rx_len) {
        n = hal_uart_read(p->uart, p->rx, sizeof p->rx);
        if (n < 0) {
            p->err = CP_ERR_IO;
            return p->err;
        }
        p->rx_len = (uint8_t)n;
        p->rx_pos = 0;
        moved |= (n > 0);
    }
    /* 3. consume bytes while a whole reply burst still fits (back-pressure:
     *    unread bytes stay in the HAL/kernel buffer, nothing is dropped); first the
     *    held bytes of a late-frame prefix that turned out to be text */
    if (p->rx_pos == p->rx_len && out_frames_tail_waiting(&p->tail)) {
        out_frames_tail_stalled(&p->tail, hal_uart_now_ms(p->uart));
    }
    while (p->dump != 0u && tx_room(p) >= PROTO_REPLY_MAX) { /* $J: its lines first */
        dump_step(p);
        moved = 1;
    }
    while (p->dump == 0u && p->tail.replay > 0u && p->state != PROTO_CHECK &&
           tx_room(p) >= PROTO_REPLY_MAX) { /* <= FRAME_MIN */
        feed(p, out_frames_tail_next(&p->tail), 1);
        moved = 1;
    }
    while (p->dump == 0u && p->tail.replay == 0u && p->rx_pos < p->rx_len &&
           tx_room(p) >= PROTO_REPLY_MAX &&
           ((!p->pass && p->state != PROTO_CHECK) || is_realtime(p->rx[p->rx_pos]))) {
        /* (<= sizeof rx) while a passed-through line waits or RUN's job is checked, only
         * real-time bytes at the head are taken ('?', '!', '~', 0x18: a status or an abort
         * must not wait for a long $H or check); the next lines wait, in order */
        feed(p, p->rx[p->rx_pos++], 0);
        moved = 1;
    }
    moved |= machine_take(p);
    /* 4. one slice of RUN's check, or one stream item */
    if (p->state == PROTO_CHECK) {
        moved |= run_check(p);
    } else if (p->state != PROTO_IDLE) {
        moved |= run_emit(p);
    }
    return moved;
}
