/* sim_machine_marlin.c - Marlin 2.x as a serial machine: the serial side (queue.cpp
 * get_serial_commands, gcode_line_error, flush_and_request_resend, ok_to_send), the main
 * loop (MarlinCore.cpp loop/idle/manage_inactivity), the planner's gate (planner.cpp) and
 * the host keepalive (gcode.cpp host_keepalive).
 * SPDX-License-Identifier: MIT
 *
 * Written from the behaviour of Marlin's source (facts, not code: Marlin is GPL).
 * Configuration: the stock Configuration.h / Configuration_adv.h (BUFSIZE 4, MAX_CMD_SIZE 96,
 * BLOCK_BUFFER_SIZE 16, no EMERGENCY_PARSER, no PAREN_COMMENTS, no GCODE_CASE_INSENSITIVE,
 * HOST_KEEPALIVE_FEATURE with DEFAULT_KEEPALIVE_INTERVAL 2, no SDSUPPORT), plus
 * SPINDLE_FEATURE unless opts.marlin_no_spindle, ADVANCED_OK when opts.advanced_ok.
 */
#include "sim_machine_marlin.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const double ml_steps[3] = {80.0, 80.0, 4000.0}; /* DEFAULT_AXIS_STEPS_PER_UNIT */
static const double ml_vmax[3] = {300.0, 300.0, 5.0};   /* DEFAULT_MAX_FEEDRATE, mm/s */

static int ml_time_model(const struct sim_machine *m)
{
    return m->o.ms_per_mm > 0.0 || m->o.time_scale > 0.0;
}

/* queue.cpp ok_to_send: "ok", with ADVANCED_OK " N<n>" (the line's own N, when the queued
 * text starts with N) " P<planner.moves_free()> B<BUFSIZE - length>" */
void ml_ok(struct sim_machine *m, int arg)
{
    struct sm_marlin *ml = m->ml;
    const char *p = ml->q[ml->qhead];
    char n[24] = "";
    size_t k = 0;
    (void)arg;
    if (!m->o.advanced_ok) {
        sm_out(m, "ok\n");
        return;
    }
    if (*p == 'N') {
        n[k++] = ' ';
        n[k++] = *p++;
        while (k < sizeof n - 1 && ((*p >= '0' && *p <= '9') || *p == '-')) {
            n[k++] = *p++;
        }
        n[k] = '\0';
    }
    sm_outf(m, "ok%s P%u B%d\n", n, SM_PLAN_SLOTS - m->plan_n, ML_BUFSIZE - ml->qlen);
}

/* parser.cpp unknown_command_warning */
void ml_unknown(struct sim_machine *m, const char *cmd)
{
    char esc[96];
    sm_step_text(m, "echo:Unknown command: \"%s\"\n", cmd);
    m->r.v.unknown++;
    sm_esc(esc, sizeof esc, cmd);
    sm_problem(m, m->ml->qline[m->ml->qhead], "line %lu: \"%s\" -> echo:Unknown command",
               m->ml->qline[m->ml->qhead], esc);
}

/* queue.cpp gcode_line_error: "Error:<msg><last_N>", the RX buffer read empty, then
 * flush_and_request_resend: "Resend: <last_N + 1>" and "ok" */
static void ml_line_error(struct sim_machine *m, const char *msg, const char *line)
{
    struct sm_marlin *ml = m->ml;
    char esc[64];
    sm_outf(m, "Error:%s%ld\n", msg, ml->last_n);
    sm_rx_clear(m);
    sm_outf(m, "Resend: %ld\nok\n", ml->last_n + 1);
    m->r.v.errors++;
    m->r.v.resends++;
    sm_esc(esc, sizeof esc, line);
    sm_problem(m, m->prog_line, "line %lu: \"%s\" -> Error:%s%ld", m->prog_line, esc, msg,
               ml->last_n);
}

/* M112 read from the serial line (queue.cpp, EMERGENCY_PARSER off): kill() */
static void ml_kill(struct sim_machine *m)
{
    m->ml->killed = 1;
    m->r.v.alarms++;
    sm_out(m, "Error:Printer halted. kill() called!\n");
    sm_problem(m, m->prog_line, "line %lu: M112: Printer halted", m->prog_line);
}

/* queue.cpp get_serial_commands: a complete, non-empty line: line number and checksum
 * (only when the line starts with N), critical M-codes, then into the queue */
static void ml_line_done(struct sim_machine *m)
{
    struct sm_marlin *ml = m->ml;
    char *cmd = ml->buf;
    int slot;
    while (*cmd == ' ') {
        cmd++;
    }
    if (*cmd == 'N') {
        int m110 = strstr(cmd, "M110") != NULL;
        const char *npos = cmd, *star;
        long n;
        if (m110 && strchr(cmd + 4, 'N') != NULL) {
            npos = strchr(cmd + 4, 'N'); /* M110 N<v>: the second N */
        }
        n = strtol(npos + 1, NULL, 10);
        if (n != ml->last_n + 1 && !m110) {
            ml_line_error(m, "Line Number is not Last Line Number+1, Last Line: ", cmd);
            return;
        }
        star = strrchr(cmd, '*');
        if (star == NULL) {
            ml_line_error(m, "No Checksum with line number, Last Line: ", cmd);
            return;
        } else {
            unsigned char cs = 0;
            const char *p;
            for (p = cmd; p < star; p++) {
                cs ^= (unsigned char)*p;
            }
            if (strtol(star + 1, NULL, 10) != (long)cs) {
                ml_line_error(m, "checksum mismatch, Last Line: ", cmd);
                return;
            }
        }
        ml->last_n = n;
    }
    if (cmd[0] == 'M' && cmd[3] == '2' && cmd[2] == '1' && cmd[1] == '1') {
        ml_kill(m); /* M112 */
        return;
    }
    if (cmd[0] == 'M' && cmd[3] == '0' && cmd[1] == '4' && cmd[2] == '1') {
        ml_quickstop(m, 0); /* M410 */
    }
    slot = (ml->qhead + ml->qlen) % ML_BUFSIZE;
    strcpy(ml->q[slot], ml->buf);
    ml->qline[slot] = m->prog_line;
    ml->qlen++;
}

/* queue.cpp process_stream_char: ';' starts a comment to the end of the line, '\\' takes
 * the next character as it is, backspace erases one; the 95th character ends the line
 * (the rest of it is skipped). PAREN_COMMENTS and GCODE_QUOTED_STRINGS are off. */
static void ml_stream_char(struct sim_machine *m, char c)
{
    struct sm_marlin *ml = m->ml;
    if (ml->sis == 1) {
        ml->cut |= ml->full;
        return;
    }
    if (ml->sis >= 4) {
        ml->sis -= 4; /* the escaped character is stored */
    } else if (c == '\\') {
        ml->sis += 4;
        return;
    } else if (c == ';') {
        ml->sis = 1;
        return;
    }
    if (c == 0x08) {
        if (ml->count) {
            ml->buf[--ml->count] = '\0';
        }
        return;
    }
    ml->buf[ml->count++] = c;
    if (ml->count >= ML_MAX_CMD - 1) {
        ml->sis = 1;
        ml->full = 1;
    }
}

/* queue.cpp get_serial_commands: read RX while the queue has a free slot */
static void ml_read_serial(struct sim_machine *m)
{
    struct sm_marlin *ml = m->ml;
    while (ml->qlen < ML_BUFSIZE && !ml->killed) {
        int c = sm_rx_pop(m);
        if (c < 0) {
            return;
        }
        if (c != '\n' && c != '\r') {
            ml_stream_char(m, (char)c);
            continue;
        }
        if (!(c == '\n' && m->last_cr)) {
            m->prog_line++;
        }
        m->last_cr = c == '\r';
        ml->buf[ml->count] = '\0';
        ml->sis = 0; /* process_line_done */
        if (ml->count == 0) {
            ml->full = ml->cut = 0;
            continue; /* an empty (or comment-only) line: no answer at all */
        }
        m->r.v.lines++;
        if (ml->cut) {
            char esc[48];
            m->r.v.long_lines++;
            sm_esc(esc, sizeof esc, ml->buf);
            sm_problem(m, m->prog_line, "line %lu: longer than %d characters, cut to \"%s\"",
                       m->prog_line, ML_MAX_CMD - 1, esc);
        }
        ml->count = 0;
        ml->full = ml->cut = 0;
        ml_line_done(m);
    }
}

/* planner.cpp: a block put into an empty planner waits BLOCK_DELAY_FOR_1ST_MOVE (100 ms)
 * unless 3 blocks are queued (planner.h get_current_block) */
static void ml_gate(struct sim_machine *m)
{
    if (!m->exec_on && m->plan_n > 0 &&
        (m->plan_n >= 3 || m->now >= m->ml->deliver_at || !ml_time_model(m))) {
        sm_plan_run(m);
    }
}

/* MarlinCore.cpp loop(): idle() (which reads serial through manage_inactivity), then
 * queue.advance() runs the next command; a blocking command keeps calling idle() */
static void ml_run(struct sim_machine *m)
{
    struct sm_marlin *ml = m->ml;
    for (;;) {
        if (ml->killed) {
            sm_rx_clear(m);
            return;
        }
        ml_gate(m);
        ml_read_serial(m);
        if (m->cmd.active) {
            if (!sm_cmd_exec(m)) {
                return;
            }
            ml->qhead = (ml->qhead + 1) % ML_BUFSIZE; /* advance_pos(index_r) */
            ml->qlen--;
            continue;
        }
        if (ml->qlen == 0) {
            return;
        }
        ml->last_m400 = 0;
        ml->busy_next = m->now + (m->o.busy_ms > 0.0 ? m->o.busy_ms : 2000.0);
        ml_process(m, ml->q[ml->qhead]);
        if (!m->cmd.active) { /* nothing to do and no ok: cannot happen, but never hang */
            sm_step_call(m, ml_ok, 0);
        }
    }
}

static double ml_next_event(const struct sim_machine *m)
{
    const struct sm_marlin *ml = m->ml;
    double t = 1e300;
    if (!m->exec_on && m->plan_n > 0 && ml_time_model(m)) {
        t = ml->deliver_at;
    }
    if (m->cmd.active && m->o.busy_ms >= 0.0 && ml->busy_next < t && !ml->killed) {
        t = ml->busy_next;
    }
    return t;
}

/* gcode.cpp host_keepalive: while a command blocks (busy_state IN_HANDLER), one
 * "echo:busy: processing" every host_keepalive_interval */
static void ml_event(struct sim_machine *m)
{
    struct sm_marlin *ml = m->ml;
    ml_gate(m);
    if (m->cmd.active && m->o.busy_ms >= 0.0 && m->now >= ml->busy_next && !ml->killed) {
        sm_out(m, "echo:busy: processing\n");
        ml->busy_next = m->now + (m->o.busy_ms > 0.0 ? m->o.busy_ms : 2000.0);
    }
}

static void ml_planner_empty(struct sim_machine *m)
{
    (void)m;
}

static int ml_synced(struct sim_machine *m)
{
    return m->plan_n == 0; /* planner.synchronize: while (has_blocks_queued()) idle(); */
}

/* planner.cpp buffer_line/_buffer_steps: wait for a free slot (get_next_free_block); a
 * move of fewer than MIN_STEPS_PER_SEGMENT (6) steps is dropped and its distance joins the
 * next one (planner.position is not updated); the rate is limited per axis
 * (DEFAULT_MAX_FEEDRATE) */
static int ml_push(struct sim_machine *m, const struct sm_block *b)
{
    struct sm_marlin *ml = m->ml;
    struct sm_block nb;
    long st[3], most = 0;
    double len = 0.0, rate = b->rate;
    int i;
    for (i = 0; i < 3; i++) {
        long d;
        st[i] = lround(b->p1[i] * ml_steps[i]);
        d = labs(st[i] - ml->psteps[i]);
        most = d > most ? d : most;
    }
    if (most < 6) {
        return 1;
    }
    if (sm_plan_full(m)) {
        return 0;
    }
    for (i = 0; i < 3; i++) {
        nb.p0[i] = (double)ml->psteps[i] / ml_steps[i];
        nb.p1[i] = (double)st[i] / ml_steps[i];
        len += (nb.p1[i] - nb.p0[i]) * (nb.p1[i] - nb.p0[i]);
    }
    len = sqrt(len);
    for (i = 0; i < 3; i++) {
        double d = fabs(nb.p1[i] - nb.p0[i]);
        if (d > 0.0 && rate * d / len > ml_vmax[i] * 60.0) {
            rate = ml_vmax[i] * 60.0 * len / d;
        }
        ml->psteps[i] = st[i];
    }
    nb.rate = rate;
    nb.rapid = b->rapid;
    nb.dur = sm_block_ms(m, len, rate);
    if (m->plan_n == 0) {
        ml->deliver_at = m->now + 100.0;
    }
    sm_plan_add(m, &nb);
    ml_gate(m);
    return 1;
}

static int ml_halted(const struct sim_machine *m)
{
    return m->ml->killed;
}

static void ml_destroy(struct sim_machine *m)
{
    free(m->ml);
    m->ml = NULL;
}

/* Marlin has no M2/M30: the program ends with M400, or with the stream (nothing queued,
 * waiting or moving) */
static void ml_verdict(const struct sim_machine *m, struct sim_machine_verdict *v)
{
    const struct sm_marlin *ml = m->ml;
    int idle = ml->qlen == 0 && !m->cmd.active && m->plan_n == 0 && m->rx_len == 0 &&
               ml->count == 0 && !ml->killed;
    sm_rules_final(m, v, ml->last_m400 || idle, sm_end_ok(&m->r));
}

static void ml_rx_byte(struct sim_machine *m, uint8_t c, int *store)
{
    (void)m;
    (void)c;
    *store = 1; /* no realtime bytes (EMERGENCY_PARSER off) */
}

static const struct sm_ops ml_ops = {ml_rx_byte, ml_run,    ml_next_event, ml_event,   ml_planner_empty,
                                     ml_push,    ml_synced, ml_halted,     ml_destroy, ml_verdict};

int sm_marlin_init(struct sim_machine *m)
{
    struct sm_marlin *ml = calloc(1, sizeof *ml);
    if (ml == NULL) {
        return -1;
    }
    m->ml = ml;
    m->ops = &ml_ops;
    ml->feed_mms = 1500.0 / 60.0; /* motion.cpp feedrate_mm_s = MMM_TO_MMS(1500) */
    return 0;
}
