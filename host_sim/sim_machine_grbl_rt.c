/* sim_machine_grbl_rt.c - grbl 1.1h's realtime side: the bytes serial.c picks out of the
 * RX stream, protocol.c protocol_exec_rt_system (hold, resume, reset, overrides), the
 * status report (report.c report_realtime_status), the boot and the soft reset (main.c).
 * SPDX-License-Identifier: MIT
 */
#include "sim_machine_grbl.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* spindle_control.c spindle_set_state + spindle_compute_pwm_value: the speed the machine
 * really runs (and reports in FS:) is clamped to $30 (1000 by default) and $31 */
void g_spindle_out(struct sim_machine *m, int arg)
{
    struct sm_grbl *g = m->g;
    float rpm = g->spindle_speed * (0.010f * (float)g->s_ovr);
    float max = g->set[G_SET_RPMMAX], min = g->set[G_SET_RPMMIN];
    g->sp_state = arg;
    if (arg == 0) {
        g->sp_rpm = 0.0f;
        return;
    }
    if (min >= max || rpm >= max) {
        rpm = max;
    } else if (rpm <= min && rpm != 0.0f) {
        rpm = min;
    }
    g->sp_rpm = rpm;
}

/* M0 (gcode.c): a feed hold while idle: Hold, and nothing runs until '~' */
void g_hold_now(struct sim_machine *m, int arg)
{
    (void)arg;
    if (!(m->g->state & (G_ST_ALARM | G_ST_CHECK))) {
        m->g->state = G_ST_HOLD;
        m->g->suspend = 1;
        m->g->hold_t = m->now;
    }
}

/* after a jog cancel or a reset: parser and planner positions = the machine position */
static void g_sync_position(struct sim_machine *m)
{
    struct sm_grbl *g = m->g;
    int i;
    for (i = 0; i < 3; i++) {
        long st = lround(m->mpos[i] * (double)g->set[G_SET_STEPS + i]);
        m->mpos[i] = (double)st / (double)g->set[G_SET_STEPS + i]; /* sys_position: steps */
        g->plan_steps[i] = st;
        g->pos[i] = (float)m->mpos[i];
    }
}

/* '!' (protocol.c EXEC_FEED_HOLD): no deceleration here, so the hold completes at once */
static void g_feed_hold(struct sim_machine *m)
{
    struct sm_grbl *g = m->g;
    if (g->state & (G_ST_ALARM | G_ST_CHECK | G_ST_SLEEP)) {
        return;
    }
    if (g->state & G_ST_JOG) { /* a hold cancels a jog: planner flushed, back to Idle */
        sm_plan_clear(m);
        g_sync_position(m);
        g->state = G_ST_IDLE;
        return;
    }
    if (g->state & G_ST_CYCLE) {
        sm_plan_hold(m);
    }
    if (g->state == G_ST_IDLE || (g->state & G_ST_CYCLE)) {
        g->state = G_ST_HOLD;
        g->suspend = 1;
        g->hold_t = m->now;
    }
}

/* '~' (protocol.c EXEC_CYCLE_START): start queued blocks, or resume a completed hold */
static void g_resume(struct sim_machine *m)
{
    struct sm_grbl *g = m->g;
    if (g->state == G_ST_IDLE) {
        g_cycle_start(m);
    } else if ((g->state & G_ST_HOLD) && g->suspend) {
        g->suspend = 0;
        if (m->cmd.active && m->cmd.t0_set) {
            m->cmd.t0 += m->now - g->hold_t; /* nuts_bolts.c delay_sec stood still */
        }
        if (m->plan_n > 0) {
            g->state = G_ST_CYCLE;
            sm_plan_run(m);
        } else {
            g->state = G_ST_IDLE;
        }
    }
}

/* 0x18 (serial.c -> motion_control.c mc_reset): kill spindle and coolant; in motion the
 * position is lost: ALARM:3, then report_alarm_message's 500 ms; then main.c resets */
void g_soft_reset(struct sim_machine *m)
{
    struct sm_grbl *g = m->g;
    int moving = (g->state & (G_ST_CYCLE | G_ST_HOMING | G_ST_JOG)) != 0;
    if (g->reset_pending) {
        return; /* mc_reset runs once */
    }
    g->sp_state = 0;
    g->sp_rpm = 0.0f;
    g->cl_state = 0;
    sm_plan_clear(m);
    g->reset_pending = 1;
    g->reset_at = m->now;
    if (moving) {
        g->state = G_ST_ALARM;
        m->r.v.alarms++;
        sm_out(m, "ALARM:3\r\n");
        sm_problem(m, m->prog_line, "line %lu: ALARM:3 (reset while in motion)", m->prog_line);
        g->reset_at = m->now + 500.0;
    }
}

/* the banner and, when idle, the startup lines (main.c loop, protocol.c) */
static void g_boot(struct sim_machine *m)
{
    struct sm_grbl *g = m->g;
    int i;
    g->f_ovr = g->r_ovr = g->s_ovr = 100;
    g->wco_cnt = g->ovr_cnt = 0;
    g->suspend = g->critical = 0;
    memset(g->prb, 0, sizeof g->prb);
    g_gc_init(m);
    g_sync_position(m);
    sm_out(m, "\r\nGrbl 1.1h ['$' for help]\r\n"); /* report.c report_init_message */
    if (g->state & (G_ST_ALARM | G_ST_SLEEP)) {
        g->state = G_ST_ALARM;
        sm_out(m, "[MSG:'$H'|'$X' to unlock]\r\n");
        return;
    }
    g->state = G_ST_IDLE;
    for (i = 0; i < 2; i++) { /* system.c system_execute_startup */
        if (g->nline[i][0] != '\0') {
            strcpy(g->line, g->nline[i]);
            g->startup = 1;
            g_gcode(m, 0);
            g->startup = 0;
        }
    }
}

void g_power_on(struct sim_machine *m)
{
    g_boot(m);
}

/* the reset completes: the line being executed still prints what it prints after its
 * blocking calls return on sys.abort (its "ok"), the RX ring is emptied (main.c
 * serial_reset_read_buffer), planner and parser start again */
void g_reset_finish(struct sim_machine *m)
{
    struct sm_grbl *g = m->g;
    struct sm_cmd *c = &m->cmd;
    size_t i;
    for (i = c->i; c->active && i < c->n; i++) {
        if (c->v[i].kind == SM_TEXT) {
            sm_out(m, c->v[i].text);
        }
    }
    sm_cmd_clear(m);
    g->reset_pending = 0;
    sm_rx_clear(m);
    g->count = 0;
    g->lflags = 0;
    sm_plan_clear(m);
    sm_rule_spindle(m, 0, 0);
    g_boot(m);
}

/* report.c report_realtime_status, with $10 (status_report_mask) and the WCO/Ov counters */
static void g_report(struct sim_machine *m)
{
    struct sm_grbl *g = m->g;
    char out[400], a[128];
    float p[3], wco[3];
    double pos[3];
    int i, busy = (g->state & (G_ST_HOMING | G_ST_CYCLE | G_ST_HOLD | G_ST_JOG)) != 0;
    int mask = (int)g->set[G_SET_MASK];
    static const char *const names[] = {"Idle", "Alarm", "Check", "Home", "Run", "Jog", "Sleep"};
    const char *nm = names[0];
    sm_plan_pos(m, pos);
    for (i = 0; i < 3; i++) {
        p[i] = (float)(lround(pos[i] * (double)g->set[G_SET_STEPS + i]) /
                       (double)g->set[G_SET_STEPS + i]);
        wco[i] = g->wcs[i] + g->g92[i] + (i == 2 ? g->tlo : 0.0f);
        if (!(mask & 1)) {
            p[i] -= wco[i];
        }
    }
    nm = g->state & G_ST_ALARM ? names[1] : g->state & G_ST_CHECK ? names[2]
         : g->state & G_ST_HOMING ? names[3] : g->state & G_ST_CYCLE ? names[4]
         : g->state & G_ST_JOG ? names[5] : g->state & G_ST_SLEEP ? names[6] : nm;
    if (g->state & G_ST_HOLD) {
        nm = g->suspend ? "Hold:0" : "Hold:1";
    }
    g_fmt3(a, sizeof a, p);
    snprintf(out, sizeof out, "<%s|%s:%s", nm, (mask & 1) ? "MPos" : "WPos", a);
    if (mask & 2) {
        sprintf(out + strlen(out), "|Bf:%u,%u", SM_PLAN_SLOTS - m->plan_n, m->rx_cap - m->rx_len);
    }
    sm_fixed(a, sizeof a, (busy && m->exec_on) ? m->plan[m->plan_tail].rate : 0.0, 0);
    sprintf(out + strlen(out), "|FS:%s,", a); /* stepper.c st_get_realtime_rate */
    sm_fixed(a, sizeof a, (double)g->sp_rpm, 0);
    strcat(out, a);
    if (g->wco_cnt > 0) {
        g->wco_cnt--;
    } else {
        g->wco_cnt = busy ? 29 : 9; /* REPORT_WCO_REFRESH_BUSY/IDLE_COUNT - 1 */
        if (g->ovr_cnt == 0) {
            g->ovr_cnt = 1;
        }
        g_fmt3(a, sizeof a, wco);
        sprintf(out + strlen(out), "|WCO:%s", a);
    }
    if (g->ovr_cnt > 0) {
        g->ovr_cnt--;
    } else {
        g->ovr_cnt = busy ? 19 : 9; /* REPORT_OVR_REFRESH_BUSY/IDLE_COUNT - 1 */
        sprintf(out + strlen(out), "|Ov:%d,%d,%d", g->f_ovr, g->r_ovr, g->s_ovr);
        if (g->sp_state || g->cl_state) {
            sprintf(out + strlen(out), "|A:%s%s", g->sp_state == 1 ? "S" : g->sp_state ? "C" : "",
                    g->cl_state ? "F" : "");
        }
    }
    strcat(out, ">\r\n");
    sm_out(m, out);
}

static int g_clamp(int v, int lo, int hi)
{
    return v < lo ? lo : (v > hi ? hi : v);
}

/* protocol.c: feed 10..200 % (steps 10 and 1), rapid 100/50/25 %, spindle 10..200 %,
 * flood coolant toggle; they take effect on blocks planned after the change */
static void g_override(struct sim_machine *m, uint8_t c)
{
    struct sm_grbl *g = m->g;
    int f = g->f_ovr, r = g->r_ovr, s = g->s_ovr;
    static const int fd[5] = {0, 10, -10, 1, -1}, sd[5] = {0, 10, -10, 1, -1};
    if (c >= 0x90 && c <= 0x94) {
        f = c == 0x90 ? 100 : g_clamp(f + fd[c - 0x90], 10, 200);
    } else if (c >= 0x95 && c <= 0x97) {
        r = c == 0x95 ? 100 : (c == 0x96 ? 50 : 25);
    } else if (c >= 0x99 && c <= 0x9D) {
        s = c == 0x99 ? 100 : g_clamp(s + sd[c - 0x99], 10, 200);
    } else if (c == 0xA0) { /* coolant override: flood toggle (no M7 build) */
        if (g->state == G_ST_IDLE || (g->state & (G_ST_CYCLE | G_ST_HOLD | G_ST_JOG))) {
            g->md.coolant ^= 1;
            g->cl_state = g->md.coolant;
        }
        return;
    } else if (c == 0x85) { /* jog cancel, in Jog only */
        if (g->state & G_ST_JOG) {
            sm_plan_clear(m);
            g_sync_position(m);
            g->state = G_ST_IDLE;
        }
        return;
    }
    if (f != g->f_ovr || r != g->r_ovr) {
        g->ovr_cnt = 0;
    }
    if (s != g->s_ovr) {
        g->ovr_cnt = 0;
        g->s_ovr = s;
        if (g->sp_state) {
            g_spindle_out(m, g->sp_state);
        }
    }
    g->f_ovr = f;
    g->r_ovr = r;
}

/* serial.c ISR: realtime bytes never reach the RX ring; bytes >= 0x80 without a meaning
 * are thrown away. During the reset window and a critical alarm only a reset counts. */
void g_rx_byte(struct sim_machine *m, uint8_t c, int *store)
{
    struct sm_grbl *g = m->g;
    int quiet = g->reset_pending || g->critical;
    *store = 0;
    switch (c) {
    case 0x18:
        g_soft_reset(m);
        break;
    case '?':
        if (!quiet) {
            g_report(m);
        }
        break;
    case '~':
        if (!quiet) {
            g_resume(m);
        }
        break;
    case '!':
        if (!quiet) {
            g_feed_hold(m);
        }
        break;
    default:
        if (c > 0x7f) {
            if (!quiet) {
                g_override(m, c); /* 0x84 safety door: no door here, ignored */
            }
        } else {
            *store = 1;
        }
        break;
    }
}
