/* sim_machine_grbl.c - grbl 1.1h (gnea/grbl bfb67f0, build 20190830) as a serial machine.
 * SPDX-License-Identifier: MIT
 *
 * Written from the behaviour of grbl's source (facts, not code: grbl is GPL). Each
 * behaviour names its source file. Default settings: defaults.h DEFAULTS_GENERIC; compile
 * options: config.h as shipped (VARIABLE_SPINDLE, HOMING_INIT_LOCK, no M7, no line
 * numbers, no parking, FORCE_BUFFER_SYNC_DURING_EEPROM_WRITE and _WCO_CHANGE on).
 * The parser's values are float like grbl's (AVR double is float); positions in steps.
 */
#include "sim_machine_int.h"
#include "sim_machine_grbl.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- state */

/* line assembly (protocol.c protocol_main_loop) */
static void g_line_char(struct sim_machine *m, int c)
{
    struct sm_grbl *g = m->g;
    if (g->lflags) {
        /* protocol.c: inside a comment or after an overflow, only ')' matters */
        if (c == ')' && (g->lflags & G_LF_PAREN)) {
            g->lflags &= ~G_LF_PAREN;
        }
        return;
    }
    if (c <= ' ' || c == '/') {
        return; /* whitespace, control characters, block delete: thrown away */
    }
    if (c == '(') {
        g->lflags |= G_LF_PAREN;
    } else if (c == ';') {
        g->lflags |= G_LF_SEMI;
    } else if (g->count >= G_LINE_SIZE - 1) {
        g->lflags |= G_LF_OVERFLOW; /* LINE_BUFFER_SIZE 80: the 80th character overflows */
    } else if (c >= 'a' && c <= 'z') {
        g->line[g->count++] = (char)(c - 'a' + 'A');
    } else {
        g->line[g->count++] = (char)c;
    }
}

/* a line ended at '\n' or '\r' (protocol.c): answer it exactly once */
static void g_line_end(struct sim_machine *m, int c)
{
    struct sm_grbl *g = m->g;
    if (!(c == '\n' && m->last_cr)) {
        m->prog_line++;
    }
    m->last_cr = c == '\r';
    g->line[g->count] = '\0';
    m->r.v.lines++;
    if (g->lflags & G_LF_OVERFLOW) {
        m->r.v.long_lines++;
        g_status(m, G_ERR_OVERFLOW);
    } else if (g->count == 0) {
        g_status(m, 0); /* empty or comment line: "ok", for syncing */
    } else if (g->line[0] == '$') {
        g_system(m);
    } else if (g->state & (G_ST_ALARM | G_ST_JOG)) {
        g_status(m, G_ERR_GC_LOCK); /* error:9 */
    } else {
        g_gcode(m, 0);
    }
    g->count = 0;
    g->lflags = 0;
}

/* the reply of the current line: "ok" or "error:N" (report.c report_status_message) */
void g_status(struct sim_machine *m, int st)
{
    struct sm_grbl *g = m->g;
    char esc[80];
    if (st == 0) {
        if (g->startup) {
            sm_step_text(m, ">%s:ok\r\n", g->line);
        } else {
            sm_step_text(m, "ok\r\n");
        }
        return;
    }
    m->r.v.errors++;
    if (g->startup) {
        sm_step_text(m, ">%s:error:%d\r\n", g->line, st);
        return;
    }
    sm_step_text(m, "error:%d\r\n", st);
    sm_esc(esc, sizeof esc, g->line);
    sm_problem(m, m->prog_line, "line %lu: \"%s\" -> error:%d", m->prog_line, esc, st);
}

/* ---------------------------------------------------------------- main loop */

/* protocol.c protocol_auto_cycle_start + the EXEC_CYCLE_START handling of
 * protocol_exec_rt_system: blocks start moving when the machine is idle */
void g_cycle_start(struct sim_machine *m)
{
    struct sm_grbl *g = m->g;
    if (g->state == G_ST_IDLE && m->plan_n > 0) {
        g->state = G_ST_CYCLE;
        sm_plan_run(m);
    }
}

static void g_run(struct sim_machine *m)
{
    struct sm_grbl *g = m->g;
    int c;
    for (;;) {
        if (g->reset_pending) {
            if (m->now < g->reset_at) {
                return; /* report.c report_alarm_message: delay_ms(500) */
            }
            g_reset_finish(m);
            continue;
        }
        if (g->suspend || g->critical) {
            return; /* protocol.c protocol_exec_rt_suspend: nothing else runs */
        }
        if (m->cmd.active) {
            if (!sm_cmd_exec(m)) {
                return;
            }
            continue;
        }
        c = sm_rx_pop(m);
        if (c < 0) {
            g_cycle_start(m); /* protocol.c: RX empty -> auto cycle start */
            return;
        }
        if (c == '\n' || c == '\r') {
            g_line_end(m, c);
        } else {
            g_line_char(m, c);
        }
    }
}

/* grbl_rt.c: serial.c ISR realtime bytes */
static double g_next_event(const struct sim_machine *m)
{
    return m->g->reset_pending ? m->g->reset_at : 1e300;
}

static void g_event(struct sim_machine *m)
{
    (void)m;
}

/* stepper.c/protocol.c EXEC_CYCLE_STOP: the last block finished */
static void g_planner_empty(struct sim_machine *m)
{
    struct sm_grbl *g = m->g;
    if (g->state & (G_ST_CYCLE | G_ST_JOG)) {
        g->state = G_ST_IDLE;
    }
}

/* protocol.c protocol_buffer_synchronize: auto cycle start, then wait while a block is
 * queued or the cycle runs */
static int g_synced(struct sim_machine *m)
{
    if (m->g->suspend) {
        return 0; /* protocol_execute_realtime sits in the suspend loop */
    }
    g_cycle_start(m);
    return m->plan_n == 0 && m->g->state != G_ST_CYCLE;
}

/* motion_control.c mc_line + planner.c plan_buffer_line: wait for a free slot (auto cycle
 * start when full), drop a block of zero steps, limit the rate by the axes' max rates */
static int g_push(struct sim_machine *m, const struct sm_block *b)
{
    struct sm_grbl *g = m->g;
    struct sm_block nb;
    long st[3];
    double d[3], len = 0.0, rate, lim = 1e300;
    int i, moved = 0;
    for (i = 0; i < 3; i++) {
        st[i] = lroundf((float)b->p1[i] * g->set[G_SET_STEPS + i]);
        moved |= st[i] != g->plan_steps[i];
    }
    if (!moved) {
        return 1; /* PLAN_EMPTY_BLOCK */
    }
    if (sm_plan_full(m)) {
        g_cycle_start(m);
        return 0;
    }
    for (i = 0; i < 3; i++) {
        nb.p0[i] = g->plan_steps[i] / (double)g->set[G_SET_STEPS + i];
        nb.p1[i] = st[i] / (double)g->set[G_SET_STEPS + i];
        d[i] = nb.p1[i] - nb.p0[i];
        len += d[i] * d[i];
        g->plan_steps[i] = st[i];
    }
    len = sqrt(len);
    for (i = 0; i < 3; i++) {
        if (d[i] != 0.0) { /* planner.c limit_value_by_axis_maximum */
            double r = (double)g->set[G_SET_RATE + i] * len / fabs(d[i]);
            lim = r < lim ? r : lim;
        }
    }
    rate = b->rapid ? lim * g->r_ovr / 100.0 : b->rate * g->f_ovr / 100.0;
    if (b->rate < 0.0) {
        rate = -b->rate * len * g->f_ovr / 100.0; /* G93: F is 1/min, rate = F * mm */
    }
    rate = rate > lim ? lim : rate;
    rate = rate < 1.0 ? 1.0 : rate; /* config.h MINIMUM_FEED_RATE */
    nb.rate = rate;
    nb.rapid = b->rapid;
    nb.dur = sm_block_ms(m, len, rate);
    sm_plan_add(m, &nb);
    return 1;
}

static int g_halted(const struct sim_machine *m)
{
    return m->g->suspend || m->g->critical || m->g->reset_pending;
}

static void g_destroy(struct sim_machine *m)
{
    free(m->g);
    m->g = NULL;
}

static void g_verdict(const struct sim_machine *m, struct sim_machine_verdict *v)
{
    sm_rules_final(m, v, m->r.v.program_end, m->r.end_after);
}

static const struct sm_ops g_ops = {g_rx_byte, g_run,    g_next_event, g_event,   g_planner_empty,
                                    g_push,    g_synced, g_halted,     g_destroy, g_verdict};

/* settings.c settings_restore defaults (defaults.h DEFAULTS_GENERIC) */
void g_defaults(struct sm_grbl *g)
{
    static const float def[G_NSET] = {
        /* $0..$6 */ 10, 25, 0, 0, 0, 0, 0,
        /* $10..$13 */ 1, 0.010f, 0.002f, 0,
        /* $20..$27 */ 0, 0, 0, 0, 25.0f, 500.0f, 250, 1.0f,
        /* $30..$32 */ 1000.0f, 0.0f, 0,
        /* $100.. */ 250.0f, 250.0f, 250.0f, 500.0f, 500.0f, 500.0f, 10.0f, 10.0f, 10.0f,
        200.0f, 200.0f, 200.0f};
    memcpy(g->set, def, sizeof def);
}

int sm_grbl_init(struct sim_machine *m)
{
    struct sm_grbl *g = calloc(1, sizeof *g);
    if (g == NULL) {
        return -1;
    }
    m->g = g;
    m->ops = &g_ops;
    g_defaults(g);
    g->set[G_SET_HOMING] = m->o.homing ? 1.0f : 0.0f;
    /* main.c: HOMING_INIT_LOCK: power-up in Alarm when homing is enabled */
    g->state = m->o.homing ? G_ST_ALARM : G_ST_IDLE;
    g_power_on(m);
    return 0;
}
