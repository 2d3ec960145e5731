/* sim_machine_grbl_sys.c - grbl 1.1h's '$' lines: system.c system_execute_line, with the
 * reports of report.c and the settings of settings.c; nuts_bolts.c read_float.
 * SPDX-License-Identifier: MIT
 */
#include "sim_machine_grbl.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

/* nuts_bolts.c read_float: optional sign, at most 8 significant digits (MAX_INT_DIGITS; more
 * integer digits scale by 10), one '.', no exponent; float arithmetic as on the AVR */
int g_read_float(const char *line, int *cc, float *out)
{
    const char *p = line + *cc;
    unsigned char c = (unsigned char)*p++;
    unsigned long iv = 0;
    int neg = 0, exp = 0, nd = 0, dec = 0;
    float f;
    if (c == '-') {
        neg = 1;
        c = (unsigned char)*p++;
    } else if (c == '+') {
        c = (unsigned char)*p++;
    }
    for (;;) {
        if (c >= '0' && c <= '9') {
            nd++;
            if (nd <= 8) {
                exp -= dec;
                iv = iv * 10u + (unsigned long)(c - '0');
            } else if (!dec) {
                exp++; /* dropped integer digit */
            }
        } else if (c == '.' && !dec) {
            dec = 1;
        } else {
            break;
        }
        c = (unsigned char)*p++;
    }
    if (nd == 0) {
        return 0;
    }
    f = (float)iv;
    if (f != 0.0f) {
        while (exp <= -2) {
            f *= 0.01f;
            exp += 2;
        }
        if (exp < 0) {
            f *= 0.1f;
        } else if (exp > 0) {
            do {
                f *= 10.0f;
            } while (--exp > 0);
        }
    }
    *out = neg ? -f : f;
    *cc = (int)(p - line - 1);
    return 1;
}

/* report.c report_util_axis_values: 3 decimals in mm */
void g_fmt3(char *buf, size_t cap, const float v[3])
{
    char a[3][32];
    int i;
    for (i = 0; i < 3; i++) {
        sm_fixed(a[i], sizeof a[i], (double)v[i], 3);
    }
    snprintf(buf, cap, "%s,%s,%s", a[0], a[1], a[2]);
}

/* the setting numbers of the $$ report, in order */
static const unsigned char g_setnum[G_NSET] = {0,   1,   2,   3,   4,   5,   6,   10,  11,
                                               12,  13,  20,  21,  22,  23,  24,  25,  26,
                                               27,  30,  31,  32,  100, 101, 102, 110, 111,
                                               112, 120, 121, 122, 130, 131, 132};

/* integer settings (print_uint8_base10), the others print with 3 decimals, $30/$31 with 0 */
static int g_set_is_int(int n)
{
    return n <= 10 || n == 13 || (n >= 20 && n <= 23) || n == 26 || n == 32;
}

/* report.c report_grbl_settings */
static void g_settings_dump(struct sim_machine *m)
{
    struct sm_grbl *g = m->g;
    char v[32];
    int i;
    for (i = 0; i < G_NSET; i++) {
        int n = g_setnum[i];
        if (g_set_is_int(n)) {
            snprintf(v, sizeof v, "%u", (unsigned)(unsigned char)g->set[i]);
        } else {
            sm_fixed(v, sizeof v, (double)g->set[i], (n == 30 || n == 31) ? 0 : 3);
        }
        sm_step_text(m, "$%d=%s\r\n", n, v);
    }
}

/* settings.c settings_store_global_setting */
static int g_store_setting(struct sim_machine *m, float param, float value)
{
    struct sm_grbl *g = m->g;
    int n = (int)param, i;
    if (value < 0.0f) {
        return G_ERR_NEGATIVE;
    }
    for (i = 0; i < G_NSET && g_setnum[i] != n; i++) {
    }
    if (i == G_NSET) {
        return G_ERR_STATEMENT;
    }
    if (g_set_is_int(n)) {
        value = (float)(unsigned char)(long)truncf(value);
        if (n == 0 && value < 3.0f) {
            return G_ERR_PULSE;
        }
        value = (n >= 4 && n <= 6) || n == 13 || (n >= 20 && n <= 22) || n == 32
                    ? (value != 0.0f ? 1.0f : 0.0f)
                    : value;
    }
    if (n == 20 && value != 0.0f && g->set[G_SET_HOMING] == 0.0f) {
        return G_ERR_SOFT_LIMIT; /* soft limits need homing */
    }
    if (n == 22 && value == 0.0f) {
        g->set[G_SET_SOFT] = 0.0f; /* homing off forces soft limits off */
    }
    g->set[i] = value;
    if (n == 13) {
        g->wco_cnt = 0;
    }
    return 0;
}

/* report.c report_ngc_parameters */
static void g_ngc_report(struct sim_machine *m)
{
    struct sm_grbl *g = m->g;
    char a[128];
    int i;
    for (i = 0; i < 8; i++) {
        g_fmt3(a, sizeof a, g->coord[i]);
        sm_step_text(m, "[G%d:%s]\r\n", i < 6 ? 54 + i : (i == 6 ? 28 : 30), a);
    }
    g_fmt3(a, sizeof a, g->g92);
    sm_step_text(m, "[G92:%s]\r\n", a);
    sm_fixed(a, sizeof a, (double)g->tlo, 3);
    sm_step_text(m, "[TLO:%s]\r\n", a);
    g_fmt3(a, sizeof a, g->prb);
    sm_step_text(m, "[PRB:%s:0]\r\n", a);
}

/* report.c report_gcode_modes */
static void g_modes_report(struct sim_machine *m)
{
    struct sm_grbl *g = m->g;
    char mo[16], f[32], s[32];
    if (g->md.motion >= G_MO_PROBE) {
        snprintf(mo, sizeof mo, "38.%d", g->md.motion - (G_MO_PROBE - 2));
    } else {
        snprintf(mo, sizeof mo, "%d", g->md.motion);
    }
    sm_fixed(f, sizeof f, (double)g->feed, 0);
    sm_fixed(s, sizeof s, (double)g->spindle_speed, 0);
    sm_step_text(m, "[GC:G%s G%d G%d G%d G%d G%d M%d M%d T%d F%s S%s]\r\n", mo, g->md.coord + 54,
                 g->md.plane + 17, 21 - g->md.inch, g->md.incr + 90, 94 - g->md.inverse,
                 g->md.spindle == 0 ? 5 : g->md.spindle + 2, g->md.coolant ? 8 : 9, g->tool, f, s);
}

static void g_unlock_reset(struct sim_machine *m, int arg)
{
    (void)arg;
    g_soft_reset(m);
}

/* $H (limits.c limits_go_home, motion_control.c mc_homing_cycle): done at once here; the
 * homed position with $23=0 is -$27 (pull-off) on every axis, in machine coordinates */
static void g_home(struct sim_machine *m, int arg)
{
    struct sm_grbl *g = m->g;
    int i;
    (void)arg;
    for (i = 0; i < 3; i++) {
        long st = lroundf(-g->set[G_SET_PULLOFF] * g->set[G_SET_STEPS + i]);
        m->mpos[i] = (double)st / (double)g->set[G_SET_STEPS + i];
        g->plan_steps[i] = st;
        g->pos[i] = (float)m->mpos[i];
    }
    g->state = G_ST_IDLE;
}

/* $SLP: "ok", then protocol.c's suspend loop for Sleep prints the message; only a reset
 * leaves it */
static void g_sleep(struct sim_machine *m, int arg)
{
    (void)arg;
    sm_out(m, "[MSG:Sleeping]\r\n");
    m->g->sp_state = 0;
    m->g->sp_rpm = 0.0f;
    m->g->cl_state = 0;
    m->g->state = G_ST_SLEEP;
    m->g->suspend = 1;
}

/* $N, $Nx=line: startup lines; storing one runs it through the parser first */
static int g_startup_line(struct sim_machine *m)
{
    struct sm_grbl *g = m->g;
    int cc = 2;
    unsigned long before;
    float param;
    char keep[G_LINE_SIZE];
    if (g->line[2] == '\0') {
        sm_step_text(m, "$N0=%s\r\n$N1=%s\r\n", g->nline[0], g->nline[1]);
        return 0;
    }
    if (g->state != G_ST_IDLE) {
        return G_ERR_IDLE;
    }
    if (!g_read_float(g->line, &cc, &param)) {
        return G_ERR_NUMBER;
    }
    if (g->line[cc++] != '=') {
        return G_ERR_STATEMENT;
    }
    strcpy(keep, g->line);
    memmove(g->line, g->line + cc, strlen(g->line + cc) + 1);
    before = m->r.v.errors;
    g_gcode(m, 0); /* it runs; its ok/error is the reply of the $N line */
    if (m->r.v.errors == before && (int)param >= 0 && (int)param < 2) {
        strcpy(g->nline[(int)param], g->line);
    }
    strcpy(g->line, keep);
    return -1; /* the reply is already queued */
}

/* system.c: $$ $G $C $X (nothing may follow them) */
static int g_sys_short(struct sim_machine *m)
{
    struct sm_grbl *g = m->g;
    if (g->line[2] != '\0') {
        return G_ERR_STATEMENT;
    }
    switch (g->line[1]) {
    case '$':
        if (g->state & (G_ST_CYCLE | G_ST_HOLD)) {
            return G_ERR_IDLE; /* takes too long to print during a cycle */
        }
        g_settings_dump(m);
        return 0;
    case 'G':
        g_modes_report(m);
        return 0;
    case 'C':
        if (g->state == G_ST_CHECK) { /* leaving check mode is a soft reset */
            sm_step_text(m, "[MSG:Disabled]\r\n");
            g_status(m, 0);
            sm_step_call(m, g_unlock_reset, 0);
            return -1;
        }
        if (g->state) {
            return G_ERR_IDLE;
        }
        g->state = G_ST_CHECK;
        sm_step_text(m, "[MSG:Enabled]\r\n");
        return 0;
    default: /* 'X' */
        if (g->state == G_ST_ALARM) {
            sm_step_text(m, "[MSG:Caution: Unlocked]\r\n");
            g->state = G_ST_IDLE; /* no startup lines after an unlock */
        }
        return 0;
    }
}

/* system.c: $H $SLP $I $RST= $# $N and $x=value: only when Idle or in Alarm */
static int g_sys_long(struct sim_machine *m)
{
    struct sm_grbl *g = m->g;
    const char *l = g->line;
    int cc = 1;
    float param, value;
    if (!(g->state == G_ST_IDLE || g->state == G_ST_ALARM)) {
        return G_ERR_IDLE;
    }
    switch (l[1]) {
    case '#':
        if (l[2] != '\0') {
            return G_ERR_STATEMENT;
        }
        g_ngc_report(m);
        return 0;
    case 'H':
        if (g->set[G_SET_HOMING] == 0.0f) {
            return G_ERR_DISABLED; /* $22=0 */
        }
        if (l[2] != '\0') {
            return G_ERR_STATEMENT; /* no HOMING_SINGLE_AXIS_COMMANDS */
        }
        g->state = G_ST_HOMING;
        sm_step_call(m, g_home, 0);
        return 0;
    case 'S':
        if (l[2] != 'L' || l[3] != 'P' || l[4] != '\0') {
            return G_ERR_STATEMENT;
        }
        g_status(m, 0);
        sm_step_call(m, g_sleep, 0);
        return -1;
    case 'I':
        if (l[2] == '\0') {
            sm_step_text(m, "[VER:1.1h.20190830:%s]\r\n[OPT:V,15,128]\r\n", g->build_info);
        } else if (l[2] != '=') {
            return G_ERR_STATEMENT;
        } else {
            strcpy(g->build_info, l + 3);
        }
        return 0;
    case 'R':
        if (l[2] != 'S' || l[3] != 'T' || l[4] != '=' || l[6] != '\0' ||
            (l[5] != '$' && l[5] != '#' && l[5] != '*')) {
            return G_ERR_STATEMENT;
        }
        if (l[5] != '#') { /* settings.c settings_restore: defaults ($22=0 too) */
            g_defaults(g);
        }
        if (l[5] != '$') { /* G54..G59, G28, G30 cleared */
            memset(g->coord, 0, sizeof g->coord);
        }
        if (l[5] == '*') { /* startup lines and build info too */
            memset(g->nline, 0, sizeof g->nline);
            g->build_info[0] = '\0';
        }
        sm_step_text(m, "[MSG:Restoring defaults]\r\n");
        g_status(m, 0);
        sm_step_call(m, g_unlock_reset, 0); /* settings restore forces a reset */
        return -1;
    case 'N':
        return g_startup_line(m);
    default:
        break;
    }
    if (!g_read_float(l, &cc, &param)) {
        return G_ERR_NUMBER; /* "$Q": not a number */
    }
    if (l[cc++] != '=') {
        return G_ERR_STATEMENT;
    }
    if (!g_read_float(l, &cc, &value)) {
        return G_ERR_NUMBER;
    }
    if (l[cc] != '\0' || param > 255.0f) {
        return G_ERR_STATEMENT;
    }
    return g_store_setting(m, param, value);
}

/* system.c system_execute_line */
void g_system(struct sim_machine *m)
{
    struct sm_grbl *g = m->g;
    int st;
    switch (g->line[1]) {
    case '\0':
        sm_step_text(m, "[HLP:$$ $# $G $I $N $x=val $Nx=line $J=line $SLP $C $X $H ~ ! ? ctrl-x]\r\n");
        st = 0;
        break;
    case 'J':
        if (g->state != G_ST_IDLE && g->state != G_ST_JOG) {
            st = G_ERR_IDLE;
        } else if (g->line[2] != '=') {
            st = G_ERR_STATEMENT;
        } else {
            g_gcode(m, 1);
            st = -1;
        }
        break;
    case '$': case 'G': case 'C': case 'X':
        st = g_sys_short(m);
        break;
    default:
        st = g_sys_long(m);
        break;
    }
    if (st >= 0) {
        g_status(m, st);
    }
}
