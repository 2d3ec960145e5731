/* sim_machine_core.c - the part of the machine emulators both dialects share: the API,
 * the clock, RX ring, TX buffer, planner execution, command steps and the program judge.
 * SPDX-License-Identifier: MIT
 */
#include "sim_machine_int.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SM_FAR 1e300 /* "no event" */

/* ---------------------------------------------------------------- API */

struct sim_machine *sim_machine_new(const struct sim_machine_opts *o)
{
    struct sim_machine *m;
    int rc;
    if (o == NULL || o->rx_size > 65535u || !(o->ms_per_mm >= 0.0) || !(o->time_scale >= 0.0) ||
        (o->kind != SIM_MACHINE_GRBL && o->kind != SIM_MACHINE_MARLIN)) {
        return NULL;
    }
    m = calloc(1, sizeof *m);
    if (m == NULL) {
        return NULL;
    }
    m->o = *o;
    /* grbl serial.c: RX_RING_BUFFER = RX_BUFFER_SIZE(128)+1, all 128 usable;
     * Marlin HAL/AVR/MarlinSerial.cpp store_rxd_char: full when head+1 == tail, 127 */
    m->rx_cap = o->rx_size ? o->rx_size : (o->kind == SIM_MACHINE_GRBL ? 128u : 127u);
    m->rx = malloc(m->rx_cap);
    if (m->rx == NULL) {
        free(m);
        return NULL;
    }
    rc = o->kind == SIM_MACHINE_GRBL ? sm_grbl_init(m) : sm_marlin_init(m);
    if (rc != 0 || m->tx_fail) {
        sim_machine_free(m);
        return NULL;
    }
    return m;
}

void sim_machine_free(struct sim_machine *m)
{
    if (m == NULL) {
        return;
    }
    sm_cmd_clear(m);
    free(m->cmd.v);
    if (m->ops != NULL && m->ops->destroy != NULL) {
        m->ops->destroy(m);
    }
    free(m->rx);
    free(m->tx);
    free(m->mv);
    free(m);
}

/* the head block's end time, or SM_FAR */
static double sm_plan_next(const struct sim_machine *m)
{
    const struct sm_block *b;
    if (!m->exec_on || m->plan_n == 0) {
        return SM_FAR;
    }
    b = &m->plan[m->plan_tail];
    return m->run_since + (b->dur - m->done_ms);
}

/* finish every block whose end time has come */
static void sm_plan_events(struct sim_machine *m)
{
    while (m->exec_on && m->plan_n > 0) {
        const struct sm_block *b = &m->plan[m->plan_tail];
        double end = m->run_since + (b->dur - m->done_ms);
        if (end > m->now) {
            break;
        }
        memcpy(m->mpos, b->p1, sizeof m->mpos);
        m->plan_tail = (m->plan_tail + 1u) % SM_PLAN_RING;
        m->plan_n--;
        m->run_since = end;
        m->done_ms = 0.0;
        if (m->plan_n == 0) {
            m->exec_on = 0;
            m->ops->planner_empty(m);
        }
    }
}

static double sm_delay_next(const struct sim_machine *m)
{
    const struct sm_cmd *c = &m->cmd;
    if (c->active && c->i < c->n && c->v[c->i].kind == SM_DELAY && c->t0_set &&
        !m->ops->halted(m)) {
        return c->t0 + c->v[c->i].ms;
    }
    return SM_FAR;
}

/* run the machine from m->now to t, event by event */
static void sm_advance(struct sim_machine *m, double t)
{
    long guard;
    if (!(t >= m->now)) {
        t = m->now; /* time never goes back (and NaN is "now") */
    }
    for (guard = 0; guard < 100000000L; guard++) {
        double te, e;
        m->ops->run(m);
        te = sm_plan_next(m);
        e = sm_delay_next(m);
        te = e < te ? e : te;
        e = m->ops->next_event(m);
        te = e < te ? e : te;
        if (te > t) {
            break;
        }
        if (te > m->now) {
            m->now = te;
        }
        sm_plan_events(m);
        m->ops->event(m);
    }
    m->now = t;
    m->ops->run(m);
}

void sim_machine_rx(struct sim_machine *m, const uint8_t *b, size_t n, double now_ms)
{
    size_t i;
    if (m == NULL) {
        return;
    }
    sm_advance(m, now_ms);
    for (i = 0; i < n; i++) {
        int store = 1;
        m->ops->rx_byte(m, b[i], &store);
        if (!store) {
            sm_advance(m, m->now);
            continue;
        }
        if (m->rx_len < m->rx_cap) {
            m->rx[(m->rx_head + m->rx_len) % m->rx_cap] = b[i];
            m->rx_len++;
        } else {
            m->r.v.rx_overflows++;
            sm_problem(m, m->prog_line + 1u,
                       "RX overflow: byte dropped in line %lu (the %u-byte ring was full: the "
                       "sender's character counting is broken)",
                       m->prog_line + 1u, m->rx_cap);
        }
        sm_advance(m, m->now); /* the main loop, and what it finishes in no time */
    }
}

size_t sim_machine_tx(struct sim_machine *m, double now_ms, uint8_t *out, size_t cap)
{
    size_t n;
    if (m == NULL) {
        return 0;
    }
    sm_advance(m, now_ms);
    n = m->tx_len - m->tx_pos;
    if (n > cap) {
        n = cap;
    }
    if (n > 0 && out != NULL) {
        memcpy(out, m->tx + m->tx_pos, n);
        m->tx_pos += n;
    }
    if (m->tx_pos == m->tx_len) {
        m->tx_pos = m->tx_len = 0;
    }
    return out != NULL ? n : 0;
}

size_t sim_machine_moves(const struct sim_machine *m, const struct sim_machine_move **v)
{
    if (v != NULL) {
        *v = m != NULL ? m->mv : NULL;
    }
    return m != NULL ? m->mv_n : 0;
}

void sim_machine_verdict(const struct sim_machine *m, struct sim_machine_verdict *v)
{
    if (m == NULL || v == NULL) {
        return;
    }
    m->ops->verdict(m, v);
}

/* ---------------------------------------------------------------- TX, RX */

void sm_out(struct sim_machine *m, const char *s)
{
    size_t n = strlen(s);
    if (m->tx_len + n + 1 > m->tx_cap) {
        size_t cap = m->tx_cap ? m->tx_cap : 256;
        char *p;
        while (cap < m->tx_len + n + 1) {
            cap *= 2;
        }
        p = realloc(m->tx, cap);
        if (p == NULL) {
            m->tx_fail = 1;
            return;
        }
        m->tx = p;
        m->tx_cap = cap;
    }
    memcpy(m->tx + m->tx_len, s, n);
    m->tx_len += n;
}

void sm_outf(struct sim_machine *m, const char *fmt, ...)
{
    char buf[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    sm_out(m, buf);
}

int sm_rx_pop(struct sim_machine *m)
{
    int c;
    if (m->rx_len == 0) {
        return -1;
    }
    c = m->rx[m->rx_head];
    m->rx_head = (m->rx_head + 1u) % m->rx_cap;
    m->rx_len--;
    return c;
}

void sm_rx_clear(struct sim_machine *m)
{
    m->rx_head = 0;
    m->rx_len = 0;
}

/* ---------------------------------------------------------------- command steps */

void sm_cmd_clear(struct sim_machine *m)
{
    size_t i;
    for (i = 0; i < m->cmd.n; i++) {
        free(m->cmd.v[i].text);
    }
    m->cmd.n = m->cmd.i = 0;
    m->cmd.active = 0;
    m->cmd.t0_set = 0;
}

static struct sm_step *sm_step_new(struct sim_machine *m, int kind)
{
    struct sm_step *s;
    if (m->cmd.n == m->cmd.cap) {
        size_t cap = m->cmd.cap ? 2 * m->cmd.cap : 8;
        struct sm_step *v = realloc(m->cmd.v, cap * sizeof *v);
        if (v == NULL) {
            m->tx_fail = 1;
            return NULL;
        }
        m->cmd.v = v;
        m->cmd.cap = cap;
    }
    m->cmd.active = 1;
    s = &m->cmd.v[m->cmd.n++];
    memset(s, 0, sizeof *s);
    s->kind = kind;
    return s;
}

void sm_step_sync(struct sim_machine *m)
{
    (void)sm_step_new(m, SM_SYNC);
}

void sm_step_delay(struct sim_machine *m, double ms)
{
    struct sm_step *s = sm_step_new(m, SM_DELAY);
    if (s != NULL) {
        s->ms = ms;
    }
}

void sm_step_block(struct sim_machine *m, const struct sm_block *b)
{
    struct sm_step *s = sm_step_new(m, SM_BLOCK);
    if (s != NULL) {
        s->blk = *b;
    }
}

void sm_step_text(struct sim_machine *m, const char *fmt, ...)
{
    char buf[1024];
    va_list ap;
    struct sm_step *s;
    va_start(ap, fmt);
    vsnprintf(buf, sizeof buf, fmt, ap);
    va_end(ap);
    s = sm_step_new(m, SM_TEXT);
    if (s != NULL) {
        s->text = malloc(strlen(buf) + 1);
        if (s->text == NULL) {
            m->tx_fail = 1;
            s->kind = SM_CALL; /* a call of nothing */
            return;
        }
        strcpy(s->text, buf);
    }
}

void sm_step_call(struct sim_machine *m, sm_fn fn, int arg)
{
    struct sm_step *s = sm_step_new(m, SM_CALL);
    if (s != NULL) {
        s->fn = fn;
        s->arg = arg;
    }
}

int sm_cmd_exec(struct sim_machine *m)
{
    struct sm_cmd *c = &m->cmd;
    while (c->active && c->i < c->n) {
        struct sm_step *s = &c->v[c->i];
        if (m->ops->halted(m)) {
            return 0; /* a hold, an alarm or a kill stopped the main loop mid-line */
        }
        switch (s->kind) {
        case SM_SYNC:
            if (!m->ops->synced(m)) {
                return 0;
            }
            break;
        case SM_DELAY:
            if (!c->t0_set) {
                c->t0 = m->now;
                c->t0_set = 1;
            }
            if (m->now < c->t0 + s->ms) {
                return 0;
            }
            c->t0_set = 0;
            break;
        case SM_BLOCK:
            if (!m->ops->push(m, &s->blk)) {
                return 0;
            }
            break;
        case SM_TEXT:
            sm_out(m, s->text);
            break;
        default:
            if (s->fn != NULL) {
                s->fn(m, s->arg);
                if (!c->active) {
                    return 1; /* the call ended the command (a reset) */
                }
            }
            break;
        }
        c->i++;
    }
    sm_cmd_clear(m);
    return 1;
}

/* ---------------------------------------------------------------- planner */

int sm_plan_full(const struct sim_machine *m)
{
    return m->plan_n >= SM_PLAN_SLOTS;
}

void sm_plan_add(struct sim_machine *m, const struct sm_block *b)
{
    m->plan[(m->plan_tail + m->plan_n) % SM_PLAN_RING] = *b;
    m->plan_n++;
}

void sm_plan_pos(const struct sim_machine *m, double out[3])
{
    const struct sm_block *b;
    double f;
    int i;
    memcpy(out, m->mpos, 3 * sizeof *out);
    if (m->plan_n == 0) {
        return;
    }
    b = &m->plan[m->plan_tail];
    f = m->done_ms + (m->exec_on ? m->now - m->run_since : 0.0);
    if (f <= 0.0) {
        return;
    }
    f = b->dur > 0.0 ? f / b->dur : 1.0;
    if (f > 1.0) {
        f = 1.0;
    }
    for (i = 0; i < 3; i++) {
        out[i] = b->p0[i] + (b->p1[i] - b->p0[i]) * f;
    }
}

void sm_plan_clear(struct sim_machine *m)
{
    sm_plan_pos(m, m->mpos);
    m->plan_n = 0;
    m->exec_on = 0;
    m->done_ms = 0.0;
}

void sm_plan_run(struct sim_machine *m)
{
    if (!m->exec_on && m->plan_n > 0) {
        m->exec_on = 1;
        m->run_since = m->now;
    }
}

void sm_plan_hold(struct sim_machine *m)
{
    if (m->exec_on) {
        m->done_ms += m->now - m->run_since;
        m->exec_on = 0;
    }
}

double sm_block_ms(const struct sim_machine *m, double len_mm, double rate)
{
    double ms = len_mm * m->o.ms_per_mm;
    if (m->o.time_scale > 0.0 && rate > 0.0) {
        ms += m->o.time_scale * 60000.0 * len_mm / rate;
    }
    return ms;
}

/* ---------------------------------------------------------------- numbers */

/* grbl print.c printFloat and Marlin's print(double, digits) both print '-' for any
 * negative value, then round the magnitude half up at the last digit */
void sm_fixed(char *buf, size_t cap, double v, int decimals)
{
    double scale = 1.0, a = fabs(v);
    unsigned long long n;
    char digits[32];
    size_t len, o = 0, i;
    if (cap == 0) {
        return;
    }
    decimals = decimals < 0 ? 0 : (decimals > 9 ? 9 : decimals);
    for (i = 0; i < (size_t)decimals; i++) {
        scale *= 10.0;
    }
    if (!(a < 1e15)) {
        a = 0.0; /* out of any machine's range: print 0 rather than garbage */
    }
    n = (unsigned long long)(a * scale + 0.5);
    snprintf(digits, sizeof digits, "%0*llu", decimals + 1, n);
    len = strlen(digits);
    if (v < 0.0 && o + 1 < cap) {
        buf[o++] = '-';
    }
    for (i = 0; i < len && o + 1 < cap; i++) {
        if (decimals > 0 && i == len - (size_t)decimals) {
            buf[o++] = '.';
            if (o + 1 >= cap) {
                break;
            }
        }
        buf[o++] = digits[i];
    }
    buf[o] = '\0';
}

void sm_esc(char *buf, size_t cap, const char *s)
{
    size_t o = 0;
    if (cap == 0) {
        return;
    }
    for (; *s != '\0' && o + 5 < cap; s++) {
        unsigned char c = (unsigned char)*s;
        if (c >= 0x20 && c < 0x7f && c != '"' && c != '\\') {
            buf[o++] = (char)c;
        } else {
            o += (size_t)snprintf(buf + o, cap - o, "\\x%02X", c);
        }
    }
    if (*s != '\0' && o + 4 < cap) {
        memcpy(buf + o, "...", 3);
        o += 3;
    }
    buf[o] = '\0';
}

/* ---------------------------------------------------------------- the judge */

void sm_problem(struct sim_machine *m, unsigned long line, const char *fmt, ...)
{
    va_list ap;
    if (m->r.v.first_problem[0] != '\0') {
        return;
    }
    va_start(ap, fmt);
    vsnprintf(m->r.v.first_problem, sizeof m->r.v.first_problem, fmt, ap);
    va_end(ap);
    m->r.problem_line = line ? line : 1u;
}

void sm_rule_units(struct sim_machine *m, int mm)
{
    m->r.g21_seen = mm ? 1 : 0;
    if (!mm) {
        m->r.g20_seen = 1;
    }
}

void sm_rule_distance(struct sim_machine *m, int absolute)
{
    m->r.g90_seen = absolute ? 1 : 0;
    if (!absolute) {
        m->r.g91_seen = 1;
    }
}

void sm_rule_feed_given(struct sim_machine *m)
{
    m->r.feed_ever = 1;
}

void sm_rule_spindle(struct sim_machine *m, int on, int explicit_m5)
{
    struct sm_rules *r = &m->r;
    if (!on && !explicit_m5 && !r->spindle_on) {
        return; /* an implicit stop of a stopped spindle (M2, reset) changes nothing */
    }
    r->spindle_on = on;
    if (on) {
        r->spindle_ever = 1;
        r->last_spindle_m5 = 0;
        r->m5_after = 0;
        return;
    }
    r->last_spindle_m5 = explicit_m5;
    if (explicit_m5 && r->retract_after) {
        r->m5_after = 1;
    }
}

int sm_end_ok(const struct sm_rules *r)
{
    return r->feeds == 0 || (r->retract_after && (!r->spindle_ever || r->m5_after));
}

void sm_rule_program_end(struct sim_machine *m)
{
    m->r.v.program_end = 1;
    m->r.end_after = sm_end_ok(&m->r);
}

static void sm_rule_rapid(struct sim_machine *m, const struct sm_motion *mo, unsigned long line)
{
    struct sm_rules *r = &m->r;
    const double eps = 1e-6;
    char z[32], s[32];
    if (!r->safe_set) {
        r->safe_set = 1;
        r->v.safe_z = mo->w1[2];
        return;
    }
    if (fabs(mo->w1[0] - mo->w0[0]) > eps || fabs(mo->w1[1] - mo->w0[1]) > eps) {
        if (mo->w0[2] < r->v.safe_z - eps || mo->w1[2] < r->v.safe_z - eps) {
            r->v.rapid_below_safe++;
            sm_fixed(z, sizeof z, mo->w0[2] < mo->w1[2] ? mo->w0[2] : mo->w1[2], 3);
            sm_fixed(s, sizeof s, r->v.safe_z, 3);
            sm_problem(m, line, "line %lu: rapid move in XY at Z %s, below the safe height %s",
                       line, z, s);
        }
    }
    if (r->feeds > 0 && mo->w1[2] >= r->v.safe_z - eps) {
        r->retract_after = 1;
    }
}

static void sm_rule_feed(struct sim_machine *m, const struct sm_motion *mo, unsigned long line)
{
    struct sm_rules *r = &m->r;
    char z[32], s[32];
    if (mo->feed <= 0.0) {
        r->v.g1_without_feed++;
        sm_problem(m, line, "line %lu: feed move with no feed rate ever given (F)", line);
    }
    if (!r->safe_set) {
        r->v.feed_before_safe++;
        sm_problem(m, line, "line %lu: feed move before the first rapid to a safe height", line);
    } else if (mo->w1[2] > r->v.safe_z + 1e-6) {
        r->v.feed_above_safe++;
        sm_fixed(z, sizeof z, mo->w1[2], 3);
        sm_fixed(s, sizeof s, r->v.safe_z, 3);
        sm_problem(m, line, "line %lu: feed move to Z %s, above the safe height %s", line, z, s);
    }
    if (!r->spindle_on) {
        r->v.feed_spindle_off++;
        if (r->spindle_off_line == 0) {
            r->spindle_off_line = line;
        }
    }
    r->feeds++;
    r->last_feed_line = line;
    r->retract_after = r->m5_after = r->end_after = 0;
}

/* record an accepted motion and judge it */
void sm_motion(struct sim_machine *m, const struct sm_motion *mo)
{
    struct sm_rules *r = &m->r;
    unsigned long line = m->prog_line ? m->prog_line : 1u;
    struct sim_machine_move *v;
    if (m->mv_n == m->mv_cap) {
        size_t cap = m->mv_cap ? 2 * m->mv_cap : 64;
        v = realloc(m->mv, cap * sizeof *v);
        if (v == NULL) {
            m->tx_fail = 1;
            return;
        }
        m->mv = v;
        m->mv_cap = cap;
    }
    v = &m->mv[m->mv_n++];
    v->rapid = mo->rapid;
    v->x = mo->w1[0];
    v->y = mo->w1[1];
    v->z = mo->w1[2];
    v->has_a = mo->has_a;
    v->has_c = mo->has_c;
    v->a = mo->a;
    v->c = mo->c;
    v->feed = mo->feed;
    v->line = line;
    if (r->motions++ == 0) {
        r->first_motion_ok_units = r->g21_seen;
        r->first_motion_ok_abs = r->g90_seen;
        r->first_rapid = mo->rapid;
        if (!r->g21_seen || !r->g90_seen) {
            sm_problem(m, line, "line %lu: first motion before %s", line,
                       !r->g21_seen && !r->g90_seen ? "G21 and G90"
                                                    : (!r->g21_seen ? "G21" : "G90"));
        }
    }
    if (mo->has_a || mo->has_c) {
        r->v.ignored_axes++;
        sm_problem(m, line, "line %lu: an A/C axis word the machine ignores", line);
    }
    if (mo->rapid) {
        sm_rule_rapid(m, mo, line);
    } else {
        sm_rule_feed(m, mo, line);
    }
    r->end_after = 0;
}

/* the verdict fields the judge can decide from what it saw */
void sm_rules_final(const struct sim_machine *m, struct sim_machine_verdict *v, int program_end,
                    int end_ok)
{
    const struct sm_rules *r = &m->r;
    char s[32];
    *v = r->v;
    v->program_end = program_end;
    v->started_safe = r->motions > 0 && r->first_motion_ok_units && r->first_motion_ok_abs &&
                      r->first_rapid && v->feed_before_safe == 0 && v->feed_above_safe == 0;
    v->units_mm = r->g21_seen && !r->g20_seen;
    v->absolute = r->g90_seen && !r->g91_seen;
    v->spindle_off_at_end = !r->spindle_ever || (r->last_spindle_m5 && !r->spindle_on);
    if (!r->spindle_ever) {
        v->feed_spindle_off = 0; /* counted only in a program that uses a spindle (header) */
    }
    v->ended_safe = program_end && end_ok;
    if (r->spindle_ever && r->spindle_off_line != 0 &&
        (r->problem_line == 0 || r->spindle_off_line < r->problem_line)) {
        snprintf(v->first_problem, sizeof v->first_problem,
                 "line %lu: feed move with the spindle off (the program turns it on elsewhere)",
                 r->spindle_off_line);
        return;
    }
    if (v->first_problem[0] != '\0') {
        return;
    }
    sm_fixed(s, sizeof s, v->safe_z, 3);
    if (r->feeds > 0 && !r->retract_after) {
        snprintf(v->first_problem, sizeof v->first_problem,
                 "no rapid retract to the safe height %s after the last feed move (line %lu)", s,
                 r->last_feed_line);
    } else if (r->spindle_ever && !v->spindle_off_at_end) {
        snprintf(v->first_problem, sizeof v->first_problem,
                 "the spindle is not stopped by an M5 at the end");
    } else if (r->spindle_ever && r->feeds > 0 && !r->m5_after) {
        snprintf(v->first_problem, sizeof v->first_problem,
                 "M5 came before the rapid retract after the last feed move (line %lu)",
                 r->last_feed_line);
    } else if (!v->program_end) {
        snprintf(v->first_problem, sizeof v->first_problem, "%s",
                 m->o.kind == SIM_MACHINE_GRBL ? "no program end (M2 or M30)"
                                               : "no program end (M400, or the stream did not "
                                                 "come to an end: commands still waiting)");
    } else if (!v->ended_safe) {
        snprintf(v->first_problem, sizeof v->first_problem,
                 "the program end came before the retract and M5 after the last feed move");
    }
}
