/* sim_machine_grbl_gc.c - grbl 1.1h's G-code block: gcode.c gc_execute_line, in its order
 * of checks (STEP 2 words, STEP 3 checks, STEP 4 execution), with motion_control.c for
 * mc_line / mc_arc / mc_dwell / mc_probe_cycle and the synchronisations they imply.
 * SPDX-License-Identifier: MIT
 */
#include "sim_machine_grbl.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#define MM_PER_INCH 25.40f /* nuts_bolts.h */
#define G_PI 3.14159265358979f
#define AX_NONE 0
#define AX_NONMODAL 1
#define AX_MOTION 2
#define AX_TLO 3
#define BIT(n) (1u << (n))
/* gcode.h word bits */
#define W_F 0
#define W_I 1
#define W_L 4
#define W_N 5
#define W_P 6
#define W_R 7
#define W_S 8
#define W_T 9
#define W_X 10
/* modal groups */
#define GR_G0 0
#define GR_G1 1
#define GR_G3 3
#define GR_G6 6
#define GR_G12 9
#define GR_M4 11
#define GR_M7 12

struct g_blk {
    struct g_modal md;
    int nonmodal, axis_cmd, jog;
    unsigned cmds, vals, axes, ijks;
    float f, ijk[3], p, r, s, xyz[3];
    int l, t;
    long n;
    int ax0, ax1, axl, coord_sel, cw, has_ac, had_f;
    float bcs[3]; /* the block's coordinate system (gcode.c block_coord_system) */
};

/* gcode.c gc_init: parser defaults (G0 G54 G17 G21 G90 G94 M5 M9, F0 S0 T0), G54 loaded */
void g_gc_init(struct sim_machine *m)
{
    struct sm_grbl *g = m->g;
    memset(&g->md, 0, sizeof g->md);
    g->spindle_speed = g->feed = 0.0f;
    g->tool = 0;
    memset(g->g92, 0, sizeof g->g92);
    g->tlo = 0.0f;
    memcpy(g->wcs, g->coord[0], sizeof g->wcs);
}

/* STEP 2, 'G': gcode.c command word table */
static int gw_g(struct g_blk *b, int iv, int *mant, int *grp)
{
    switch (iv) {
    case 10: case 28: case 30: case 92:
        if (*mant == 0) { /* G28.1, G30.1, G92.1 are not axis commands */
            if (b->axis_cmd) {
                return G_ERR_AXIS_CONFLICT;
            }
            b->axis_cmd = AX_NONMODAL;
        }
        /* fall through */
    case 4: case 53:
        *grp = GR_G0;
        b->nonmodal = iv;
        if (iv == 28 || iv == 30 || iv == 92) {
            if (!(*mant == 0 || *mant == 10)) {
                return G_ERR_UNSUPPORTED;
            }
            b->nonmodal += *mant; /* 38 G28.1, 40 G30.1, 102 G92.1 */
            *mant = 0;
        }
        return 0;
    case 0: case 1: case 2: case 3: case 38:
        if (b->axis_cmd) {
            return G_ERR_AXIS_CONFLICT;
        }
        b->axis_cmd = AX_MOTION;
        /* fall through */
    case 80:
        *grp = GR_G1;
        b->md.motion = iv;
        if (iv == 38) {
            if (!(*mant == 20 || *mant == 30 || *mant == 40 || *mant == 50)) {
                return G_ERR_UNSUPPORTED;
            }
            b->md.motion += *mant / 10 + 100;
            *mant = 0;
        }
        return 0;
    case 17: case 18: case 19:
        *grp = 2;
        b->md.plane = iv - 17;
        return 0;
    case 90: case 91:
        if (*mant == 0) {
            *grp = GR_G3;
            b->md.incr = iv - 90;
            return 0;
        }
        *grp = 4;
        if (*mant != 10 || iv == 90) {
            return G_ERR_UNSUPPORTED; /* G90.1 */
        }
        *mant = 0; /* G91.1: arc IJK are incremental anyway */
        return 0;
    case 93: case 94:
        *grp = 5;
        b->md.inverse = 94 - iv;
        return 0;
    case 20: case 21:
        *grp = GR_G6;
        b->md.inch = 21 - iv;
        return 0;
    case 40:
        *grp = 7;
        return 0;
    case 43: case 49:
        *grp = 8;
        if (b->axis_cmd) {
            return G_ERR_AXIS_CONFLICT;
        }
        b->axis_cmd = AX_TLO;
        if (iv == 49) {
            b->md.tlo = 0;
        } else if (*mant == 10) {
            b->md.tlo = 1;
        } else {
            return G_ERR_UNSUPPORTED; /* G43 */
        }
        *mant = 0;
        return 0;
    case 54: case 55: case 56: case 57: case 58: case 59:
        *grp = GR_G12;
        b->md.coord = iv - 54;
        return 0;
    case 61:
        *grp = 10;
        return *mant != 0 ? G_ERR_UNSUPPORTED : 0; /* G61.1 */
    default:
        return G_ERR_UNSUPPORTED;
    }
}

/* STEP 2, 'M' (no ENABLE_M7, no parking override: M7 and M56 are unsupported) */
static int gw_m(struct g_blk *b, int iv, int *grp)
{
    switch (iv) {
    case 0: case 1: case 2: case 30:
        *grp = GR_M4;
        if (iv == 0) {
            b->md.flow = 3; /* PROGRAM_FLOW_PAUSED */
        } else if (iv != 1) {
            b->md.flow = iv; /* M1 optional stop: valid and ignored */
        }
        return 0;
    case 3: case 4: case 5:
        *grp = GR_M7;
        b->md.spindle = iv == 5 ? 0 : iv - 2;
        return 0;
    case 8: case 9:
        *grp = 13;
        b->md.coolant = iv == 8 ? (b->md.coolant | 1) : 0;
        return 0;
    default:
        return G_ERR_UNSUPPORTED;
    }
}

/* STEP 2, value words; A B C D E H O Q U V W are not supported (error:20) */
static int gw_value(struct g_blk *b, char letter, float v, int iv, int *bit)
{
    switch (letter) {
    case 'F': *bit = W_F; b->f = v; return 0;
    case 'I': case 'J': case 'K':
        *bit = W_I + (letter - 'I');
        b->ijk[letter - 'I'] = v;
        b->ijks |= BIT(letter - 'I');
        return 0;
    case 'L': *bit = W_L; b->l = iv; return 0;
    case 'N': *bit = W_N; b->n = (long)truncf(v); return 0;
    case 'P': *bit = W_P; b->p = v; return 0;
    case 'R': *bit = W_R; b->r = v; return 0;
    case 'S': *bit = W_S; b->s = v; return 0;
    case 'T':
        *bit = W_T;
        if (v > 255.0f) {
            return G_ERR_MAX_VALUE; /* MAX_TOOL_NUMBER */
        }
        b->t = iv;
        return 0;
    case 'X': case 'Y': case 'Z':
        *bit = W_X + (letter - 'X');
        b->xyz[letter - 'X'] = v;
        b->axes |= BIT(letter - 'X');
        return 0;
    default:
        b->has_ac |= letter == 'A' || letter == 'C';
        return G_ERR_UNSUPPORTED;
    }
}

/* STEP 2: import every word (letter + number), modal group and repeat checks */
static int g_words(struct sim_machine *m, struct g_blk *b)
{
    const char *line = m->g->line;
    int cc = b->jog ? 3 : 0;
    while (line[cc] != '\0') {
        char letter = line[cc];
        float v;
        int iv, mant, grp = 0, bit = 0, st;
        if (letter < 'A' || letter > 'Z') {
            return G_ERR_LETTER;
        }
        cc++;
        if (!g_read_float(line, &cc, &v)) {
            return G_ERR_NUMBER;
        }
        /* gcode.c: int_value is a uint8_t, mantissa round(100 * fraction) a uint16_t */
        iv = (int)(unsigned char)(long)truncf(v);
        mant = (int)(unsigned short)lroundf(100.0f * (v - (float)iv));
        if (letter == 'G' || letter == 'M') {
            if (letter == 'M' && mant > 0) {
                return G_ERR_NOT_INTEGER;
            }
            st = letter == 'G' ? gw_g(b, iv, &mant, &grp) : gw_m(b, iv, &grp);
            if (st) {
                return st;
            }
            if (mant > 0) {
                return G_ERR_NOT_INTEGER;
            }
            if (b->cmds & BIT(grp)) {
                return G_ERR_MODAL;
            }
            b->cmds |= BIT(grp);
            continue;
        }
        st = gw_value(b, letter, v, iv, &bit);
        if (st) {
            return st;
        }
        if (b->vals & BIT(bit)) {
            return G_ERR_REPEATED;
        }
        if ((BIT(bit) & (BIT(W_F) | BIT(W_N) | BIT(W_P) | BIT(W_T) | BIT(W_S))) && v < 0.0f) {
            return G_ERR_NEGATIVE;
        }
        b->vals |= BIT(bit);
    }
    return 0;
}

/* STEP 3 [0-15]: feed rate, spindle speed, dwell, plane, units, tool length, WCS */
static int g_check_common(struct sim_machine *m, struct g_blk *b)
{
    struct sm_grbl *g = m->g;
    int i;
    if (b->axes && !b->axis_cmd) {
        b->axis_cmd = AX_MOTION; /* implicit motion: the modal motion mode */
    }
    if ((b->vals & BIT(W_N)) && b->n > 10000000L) {
        return G_ERR_LINE_NUMBER; /* MAX_LINE_NUMBER */
    }
    if (b->jog) {
        if (!(b->vals & BIT(W_F))) {
            return G_ERR_FEED;
        }
        if (b->md.inch) {
            b->f *= MM_PER_INCH;
        }
    } else if (b->md.inverse) {
        if (b->axis_cmd == AX_MOTION && b->md.motion != G_MO_NONE &&
            b->md.motion != G_MO_SEEK && !(b->vals & BIT(W_F))) {
            return G_ERR_FEED; /* G93: F on every feed block */
        }
    } else if (!g->md.inverse) { /* G94 after G94: F in mm/min, else the modal F */
        if (b->vals & BIT(W_F)) {
            b->f *= b->md.inch ? MM_PER_INCH : 1.0f;
        } else {
            b->f = g->feed;
        }
    }
    if (!(b->vals & BIT(W_S))) {
        b->s = g->spindle_speed;
    }
    if (b->nonmodal == 4) {
        if (!(b->vals & BIT(W_P))) {
            return G_ERR_VALUE_MISSING; /* G4 without P */
        }
        b->vals &= ~BIT(W_P);
    }
    b->ax0 = b->md.plane == 0 ? 0 : (b->md.plane == 1 ? 2 : 1);
    b->ax1 = b->md.plane == 0 ? 1 : (b->md.plane == 1 ? 0 : 2);
    b->axl = b->md.plane == 0 ? 2 : (b->md.plane == 1 ? 1 : 0);
    for (i = 0; i < 3 && b->md.inch; i++) {
        if (b->axes & BIT(i)) {
            b->xyz[i] *= MM_PER_INCH;
        }
    }
    if (b->axis_cmd == AX_TLO && b->md.tlo == 1 && (b->axes ^ BIT(2))) {
        return G_ERR_G43; /* G43.1 takes the Z word only */
    }
    memcpy(b->bcs, g->wcs, sizeof b->bcs);
    if ((b->cmds & BIT(GR_G12)) && g->md.coord != b->md.coord) {
        memcpy(b->bcs, g->coord[b->md.coord], sizeof b->bcs);
    }
    return 0;
}

/* STEP 3 [19]: G10 L2/L20 and G92 (their axis words are not a target) */
static int g_check_offsets(struct sim_machine *m, struct g_blk *b)
{
    struct sm_grbl *g = m->g;
    int i;
    if (!b->axes) {
        return G_ERR_NO_AXIS;
    }
    if (b->nonmodal == 92) {
        for (i = 0; i < 3; i++) {
            if (b->axes & BIT(i)) {
                b->xyz[i] = g->pos[i] - b->bcs[i] - b->xyz[i] - (i == 2 ? g->tlo : 0.0f);
            } else {
                b->xyz[i] = g->g92[i];
            }
        }
        return 0;
    }
    /* G10: an error only when both P and L are missing */
    if (!(b->vals & (BIT(W_P) | BIT(W_L)))) {
        return G_ERR_VALUE_MISSING;
    }
    b->coord_sel = (int)(unsigned char)(long)truncf(b->p);
    if (b->coord_sel > 6) {
        return G_ERR_COORD_SYS; /* N_COORDINATE_SYSTEM */
    }
    if (b->l != 20) {
        if (b->l != 2 || (b->vals & BIT(W_R))) {
            return G_ERR_UNSUPPORTED; /* L other than 2/20, or G10 L2 R */
        }
    }
    b->vals &= ~(BIT(W_L) | BIT(W_P));
    b->coord_sel = b->coord_sel > 0 ? b->coord_sel - 1 : b->md.coord; /* P0: the active one */
    memcpy(b->ijk, g->coord[b->coord_sel], sizeof b->ijk);
    for (i = 0; i < 3; i++) {
        if (b->axes & BIT(i)) {
            b->ijk[i] = b->l == 20 ? g->pos[i] - g->g92[i] - b->xyz[i] - (i == 2 ? g->tlo : 0.0f)
                                   : b->xyz[i];
        }
    }
    return 0;
}

/* STEP 3 [19]: the target of every other axis command; G28/G30, G53 checks */
static int g_check_target(struct sim_machine *m, struct g_blk *b)
{
    struct sm_grbl *g = m->g;
    int i;
    if (b->nonmodal == 10 || b->nonmodal == 92) {
        return g_check_offsets(m, b);
    }
    if (b->axis_cmd != AX_TLO && b->axes) {
        for (i = 0; i < 3; i++) {
            if (!(b->axes & BIT(i))) {
                b->xyz[i] = g->pos[i];
            } else if (b->nonmodal != 53) {
                if (!b->md.incr) {
                    b->xyz[i] += b->bcs[i] + g->g92[i] + (i == 2 ? g->tlo : 0.0f);
                } else {
                    b->xyz[i] += g->pos[i];
                }
            }
        }
    }
    if (b->nonmodal == 28 || b->nonmodal == 30) {
        memcpy(b->ijk, g->coord[b->nonmodal == 28 ? 6 : 7], sizeof b->ijk);
        if (b->axes) {
            for (i = 0; i < 3; i++) {
                if (!(b->axes & BIT(i))) {
                    b->ijk[i] = g->pos[i]; /* only the axes of the intermediate move */
                }
            }
        } else {
            b->axis_cmd = AX_NONE;
        }
    } else if (b->nonmodal == 53 && b->md.motion != G_MO_SEEK && b->md.motion != G_MO_LINEAR) {
        return G_ERR_G53;
    }
    return 0;
}

/* STEP 3 [20], arcs: radius or center format, checked against the current position */
static int g_check_arc(struct sim_machine *m, struct g_blk *b)
{
    struct sm_grbl *g = m->g;
    float x, y, h, tr;
    if (!b->axes) {
        return G_ERR_NO_AXIS;
    }
    if (!(b->axes & (BIT(b->ax0) | BIT(b->ax1)))) {
        return G_ERR_NO_AXIS_PLANE;
    }
    x = b->xyz[b->ax0] - g->pos[b->ax0];
    y = b->xyz[b->ax1] - g->pos[b->ax1];
    b->cw = b->md.motion == G_MO_CW;
    if (b->vals & BIT(W_R)) {
        b->vals &= ~BIT(W_R);
        if (memcmp(g->pos, b->xyz, sizeof g->pos) == 0) {
            return G_ERR_TARGET;
        }
        if (b->md.inch) {
            b->r *= MM_PER_INCH;
        }
        h = 4.0f * b->r * b->r - x * x - y * y;
        if (h < 0.0f) {
            return G_ERR_RADIUS;
        }
        h = -sqrtf(h) / hypotf(x, y);
        if (!b->cw) {
            h = -h;
        }
        if (b->r < 0.0f) { /* negative R: the arc of more than 180 degrees */
            h = -h;
            b->r = -b->r;
        }
        b->ijk[b->ax0] = 0.5f * (x - y * h);
        b->ijk[b->ax1] = 0.5f * (y + x * h);
        return 0;
    }
    if (!(b->ijks & (BIT(b->ax0) | BIT(b->ax1)))) {
        return G_ERR_NO_OFFSETS;
    }
    b->vals &= ~(BIT(W_I) | BIT(W_I + 1) | BIT(W_I + 2));
    if (b->md.inch) {
        int i;
        for (i = 0; i < 3; i++) {
            b->ijk[i] *= (b->ijks & BIT(i)) ? MM_PER_INCH : 1.0f;
        }
    }
    x -= b->ijk[b->ax0];
    y -= b->ijk[b->ax1];
    tr = hypotf(x, y);
    b->r = hypotf(b->ijk[b->ax0], b->ijk[b->ax1]);
    h = fabsf(tr - b->r);
    if (h > 0.005f && (h > 0.5f || h > 0.001f * b->r)) {
        return G_ERR_TARGET; /* the end point is not on the circle */
    }
    return 0;
}

/* STEP 3 [20] and the unused-word check */
static int g_check_motion(struct sim_machine *m, struct g_blk *b)
{
    int st;
    if (b->md.motion == G_MO_NONE) {
        if (b->axes) {
            return G_ERR_AXIS_EXIST; /* G80 with axis words */
        }
    } else if (b->axis_cmd == AX_MOTION) {
        if (b->md.motion == G_MO_SEEK) {
            if (!b->axes) {
                b->axis_cmd = AX_NONE;
            }
        } else {
            if (b->f == 0.0f) {
                return G_ERR_FEED; /* no feed rate ever given (or G93 without F) */
            }
            if (b->md.motion == G_MO_LINEAR) {
                if (!b->axes) {
                    b->axis_cmd = AX_NONE;
                }
            } else if (b->md.motion == G_MO_CW || b->md.motion == G_MO_CCW) {
                st = g_check_arc(m, b);
                if (st) {
                    return st;
                }
            } else {
                if (!b->axes) {
                    return G_ERR_NO_AXIS; /* G38.x */
                }
                if (memcmp(m->g->pos, b->xyz, sizeof b->xyz) == 0) {
                    return G_ERR_TARGET;
                }
            }
        }
    }
    b->vals &= ~(BIT(W_N) | BIT(W_F) | (b->jog ? 0u : (BIT(W_S) | BIT(W_T))));
    if (b->axis_cmd) {
        b->vals &= ~(BIT(W_X) | BIT(W_X + 1) | BIT(W_X + 2));
    }
    return b->vals ? G_ERR_UNUSED : 0;
}

/* ---------------------------------------------------------------- STEP 4 */

/* limits.c limits_soft_check ($20=1): a target outside the machine space [-$13x, 0] stops
 * motion (hold, then reset), "ALARM:2", "[MSG:Reset to continue]" (report.c), and nothing
 * but a reset is served (protocol.c critical event); checked in $C mode too */
static void g_soft_limit(struct sim_machine *m, int arg)
{
    struct sm_grbl *g = m->g;
    (void)arg;
    sm_plan_clear(m);
    g->state = G_ST_ALARM;
    g->critical = 1;
    g->sp_state = 0;
    g->sp_rpm = 0.0f;
    g->cl_state = 0;
    m->r.v.alarms++;
    sm_out(m, "ALARM:2\r\n[MSG:Reset to continue]\r\n");
    sm_problem(m, m->prog_line, "line %lu: ALARM:2 (soft limit)", m->prog_line);
}

/* a motion accepted by the parser: the judge's record, then (outside $C) a planner block */
static void g_move(struct sim_machine *m, const struct g_blk *b, const float from[3],
                   const float to[3], int rapid, float feed, int inv)
{
    struct sm_grbl *g = m->g;
    struct sm_motion mo;
    struct sm_block blk;
    int i;
    memset(&mo, 0, sizeof mo);
    memset(&blk, 0, sizeof blk);
    for (i = 0; i < 3; i++) {
        float w = g->wcs[i] + g->g92[i] + (i == 2 ? g->tlo : 0.0f);
        mo.w0[i] = (double)(from[i] - w);
        mo.w1[i] = (double)(to[i] - w);
        blk.p1[i] = (double)to[i];
    }
    mo.rapid = rapid;
    mo.feed = rapid ? (double)g->feed : (double)feed;
    if (!b->jog) {
        sm_motion(m, &mo);
        if (g->set[G_SET_SOFT] != 0.0f) {
            for (i = 0; i < 3; i++) {
                if (to[i] > 0.0f || to[i] < -g->set[G_SET_TRAVEL + i]) {
                    sm_step_call(m, g_soft_limit, 0);
                    return;
                }
            }
        }
    }
    if (g->state == G_ST_CHECK) {
        return; /* motion_control.c mc_line: check mode blocks the planner */
    }
    blk.rapid = rapid;
    blk.rate = inv && !rapid ? -(double)feed : (double)feed;
    sm_step_block(m, &blk);
}

/* motion_control.c mc_arc: floor(0.5 * angle * r / sqrt(tol * (2r - tol))) segments,
 * the small-angle rotation with an exact correction every N_ARC_CORRECTION (12) */
static void g_arc(struct sim_machine *m, const struct g_blk *b)
{
    struct sm_grbl *g = m->g;
    float pos[3], prev[3], c0, c1, r0, r1, rt0, rt1, ang, tol = g->set[G_SET_ARCTOL];
    float th, lin, cos_t, sin_t, feed = b->f;
    unsigned seg, i, count = 0;
    memcpy(pos, g->pos, sizeof pos);
    c0 = pos[b->ax0] + b->ijk[b->ax0];
    c1 = pos[b->ax1] + b->ijk[b->ax1];
    r0 = -b->ijk[b->ax0];
    r1 = -b->ijk[b->ax1];
    rt0 = b->xyz[b->ax0] - c0;
    rt1 = b->xyz[b->ax1] - c1;
    ang = atan2f(r0 * rt1 - r1 * rt0, r0 * rt0 + r1 * rt1);
    if (b->cw && ang >= -5e-7f) {
        ang -= 2.0f * G_PI;
    } else if (!b->cw && ang <= 5e-7f) {
        ang += 2.0f * G_PI;
    }
    seg = (unsigned)(unsigned short)floorf(fabsf(0.5f * ang * b->r) / sqrtf(tol * (2.0f * b->r - tol)));
    if (seg) {
        if (b->md.inverse) {
            feed *= (float)seg; /* inverse time over the whole arc: F per segment */
        }
        th = ang / (float)seg;
        lin = (b->xyz[b->axl] - pos[b->axl]) / (float)seg;
        cos_t = 2.0f - th * th;
        sin_t = th * 0.16666667f * (cos_t + 4.0f);
        cos_t *= 0.5f;
        for (i = 1; i < seg; i++) {
            if (count < 12) {
                float ri = r0 * sin_t + r1 * cos_t;
                r0 = r0 * cos_t - r1 * sin_t;
                r1 = ri;
                count++;
            } else {
                float ci = cosf((float)i * th), si = sinf((float)i * th);
                r0 = -b->ijk[b->ax0] * ci + b->ijk[b->ax1] * si;
                r1 = -b->ijk[b->ax0] * si - b->ijk[b->ax1] * ci;
                count = 0;
            }
            memcpy(prev, pos, sizeof prev);
            pos[b->ax0] = c0 + r0;
            pos[b->ax1] = c1 + r1;
            pos[b->axl] += lin;
            g_move(m, b, prev, pos, 0, feed, 0);
        }
    }
    /* with segments, the arc runs in units per minute (mc_arc clears the inverse flag) */
    g_move(m, b, pos, b->xyz, 0, feed, b->md.inverse && seg == 0);
}

/* coolant_control.c coolant_set_state */
static void g_coolant_out(struct sim_machine *m, int arg)
{
    m->g->cl_state = arg;
}

/* gcode.c STEP 4 [1-17]: modes; spindle and coolant changes wait for the planner to empty
 * (spindle_control.c spindle_sync, coolant_control.c coolant_sync; not in $C mode) */
static void g_exec_modes(struct sim_machine *m, const struct g_blk *b)
{
    struct sm_grbl *g = m->g;
    int chk = g->state == G_ST_CHECK;
    float old_s = g->spindle_speed;
    g->md.inverse = b->md.inverse;
    g->feed = b->f; /* always copied: G93 blocks leave it 0 */
    if (b->had_f) {
        sm_rule_feed_given(m);
    }
    if (g->spindle_speed != b->s) {
        g->spindle_speed = b->s;
        if (g->md.spindle != 0 && !chk) {
            sm_step_sync(m);
            sm_step_call(m, g_spindle_out, g->md.spindle);
        }
    }
    g->tool = b->t; /* values.t is 0 when no T word: $G shows T0 again */
    if (g->md.spindle != b->md.spindle) {
        if (!chk) {
            sm_step_sync(m);
            sm_step_call(m, g_spindle_out, b->md.spindle);
        }
        g->md.spindle = b->md.spindle;
    }
    if ((b->cmds & BIT(GR_M7)) || old_s != g->spindle_speed) {
        sm_rule_spindle(m, g->md.spindle != 0 && g->spindle_speed > 0.0f,
                        (b->cmds & BIT(GR_M7)) && b->md.spindle == 0);
    }
    if (g->md.coolant != b->md.coolant) {
        if (!chk) {
            sm_step_sync(m);
            sm_step_call(m, g_coolant_out, b->md.coolant);
        }
        g->md.coolant = b->md.coolant;
    }
    if (b->nonmodal == 4 && !chk) {
        /* motion_control.c mc_dwell: sync, then nuts_bolts.c delay_sec: ceil(20 * P)
         * steps of DWELL_TIME_STEP 50 ms (P in seconds) */
        sm_step_sync(m);
        sm_step_delay(m, 50.0 * (double)(unsigned short)ceilf(20.0f * b->p));
    }
    g->md.plane = b->md.plane;
    g->md.inch = b->md.inch;
    if (b->cmds & BIT(GR_G6)) {
        sm_rule_units(m, !b->md.inch);
    }
    if (b->axis_cmd == AX_TLO) {
        float z = b->md.tlo ? b->xyz[2] : 0.0f;
        g->md.tlo = b->md.tlo;
        if (g->tlo != z) {
            g->tlo = z;
            sm_step_sync(m); /* FORCE_BUFFER_SYNC_DURING_WCO_CHANGE */
            g->wco_cnt = 0;
        }
    }
    if (g->md.coord != b->md.coord) {
        g->md.coord = b->md.coord;
        memcpy(g->wcs, b->bcs, sizeof g->wcs);
        sm_step_sync(m);
        g->wco_cnt = 0;
    }
    g->md.incr = b->md.incr;
    if (b->cmds & BIT(GR_G3)) {
        sm_rule_distance(m, !b->md.incr);
    }
}

/* gcode.c STEP 4 [19]: G10, G28/G30, G28.1/G30.1, G92, G92.1 (EEPROM writes and WCO
 * changes wait for the planner to empty: config.h FORCE_BUFFER_SYNC_*) */
static void g_exec_nonmodal(struct sim_machine *m, const struct g_blk *b)
{
    struct sm_grbl *g = m->g;
    switch (b->nonmodal) {
    case 10:
        sm_step_sync(m);
        memcpy(g->coord[b->coord_sel], b->ijk, sizeof b->ijk);
        if (g->md.coord == b->coord_sel) {
            memcpy(g->wcs, b->ijk, sizeof g->wcs);
            g->wco_cnt = 0;
        }
        break;
    case 28: case 30:
        if (b->axis_cmd) {
            g_move(m, b, g->pos, b->xyz, 1, 0.0f, 0);
        }
        g_move(m, b, b->axis_cmd ? b->xyz : g->pos, b->ijk, 1, 0.0f, 0);
        memcpy(g->pos, b->ijk, sizeof g->pos);
        break;
    case 38: case 40:
        sm_step_sync(m);
        memcpy(g->coord[b->nonmodal == 38 ? 6 : 7], g->pos, sizeof g->pos);
        break;
    case 92: case 102:
        if (b->nonmodal == 92) {
            memcpy(g->g92, b->xyz, sizeof g->g92);
        } else {
            memset(g->g92, 0, sizeof g->g92);
        }
        sm_step_sync(m);
        g->wco_cnt = 0;
        break;
    default:
        break;
    }
}

static void g_probe_alarm(struct sim_machine *m, int arg)
{
    m->g->state = G_ST_ALARM;
    m->r.v.alarms++;
    sm_outf(m, "ALARM:%d\r\n", arg);
    sm_problem(m, m->prog_line, "line %lu: ALARM:%d (probe fail: no contact)", m->prog_line, arg);
}

/* report.c report_probe_parameters */
static void g_probe_report(struct sim_machine *m, int noerr)
{
    struct sm_grbl *g = m->g;
    char p[128];
    int i;
    if (noerr) {
        for (i = 0; i < 3; i++) {
            g->prb[i] = (float)m->mpos[i];
        }
    }
    g_fmt3(p, sizeof p, g->prb);
    sm_outf(m, "[PRB:%s:0]\r\n", p);
}

/* motion_control.c mc_probe_cycle: no probe input here, so the probe never touches: the
 * move runs to its end; G38.2/G38.4 then raise ALARM:5 (probe fail contact) */
static void g_probe(struct sim_machine *m, const struct g_blk *b)
{
    struct sm_grbl *g = m->g;
    int noerr = b->md.motion == G_MO_PROBE + 1 || b->md.motion == G_MO_PROBE + 3;
    if (g->state == G_ST_CHECK) {
        g_move(m, b, g->pos, b->xyz, 0, b->f, b->md.inverse);
        return;
    }
    sm_step_sync(m);
    g_move(m, b, g->pos, b->xyz, 0, b->f, b->md.inverse);
    sm_step_sync(m);
    if (!noerr) {
        sm_step_call(m, g_probe_alarm, 5);
        sm_step_delay(m, 500.0); /* report.c report_alarm_message */
    }
    sm_step_call(m, g_probe_report, noerr);
}

/* gcode.c STEP 4 [20] motion and [21] program flow */
static void g_exec_motion(struct sim_machine *m, const struct g_blk *b)
{
    struct sm_grbl *g = m->g;
    g->md.motion = b->md.motion;
    if (g->md.motion != G_MO_NONE && b->axis_cmd == AX_MOTION) {
        if (g->md.motion == G_MO_LINEAR || g->md.motion == G_MO_SEEK) {
            g_move(m, b, g->pos, b->xyz, g->md.motion == G_MO_SEEK, b->f, b->md.inverse);
        } else if (g->md.motion == G_MO_CW || g->md.motion == G_MO_CCW) {
            g_arc(m, b);
        } else {
            g_probe(m, b);
        }
        memcpy(g->pos, b->xyz, sizeof g->pos);
    }
    if (b->md.flow == 0) {
        return;
    }
    sm_step_sync(m); /* protocol_buffer_synchronize */
    if (b->md.flow == 3) {
        if (g->state != G_ST_CHECK) {
            sm_step_call(m, g_hold_now, 0); /* M0: a feed hold; "ok" after '~' */
        }
        return;
    }
    /* M2/M30: groups G1 G2 G3 G5 G12 M7 M8 reset to G1 G17 G90 G94 G54 M5 M9; overrides
     * restored (RESTORE_OVERRIDES_AFTER_PROGRAM_END) */
    g->md.motion = G_MO_LINEAR;
    g->md.plane = g->md.incr = g->md.inverse = g->md.coord = 0;
    g->md.spindle = g->md.coolant = 0;
    g->f_ovr = g->r_ovr = g->s_ovr = 100;
    if (g->state != G_ST_CHECK) {
        memcpy(g->wcs, g->coord[0], sizeof g->wcs);
        g->wco_cnt = 0;
        sm_step_call(m, g_spindle_out, 0);
        sm_step_call(m, g_coolant_out, 0);
    }
    sm_step_text(m, "[MSG:Pgm End]\r\n");
    sm_rule_spindle(m, 0, 0);
    sm_rule_program_end(m);
}

static void g_jog_start(struct sim_machine *m, int arg)
{
    (void)arg;
    if (m->g->state == G_ST_IDLE && m->plan_n > 0) {
        m->g->state = G_ST_JOG; /* jog.c jog_execute: runs at once, no cycle start */
        sm_plan_run(m);
    }
}

/* gcode.c STEP 4 for $J= (jog.c): only G20/G21, G90/G91 and G53 are allowed; the parser
 * modes are not changed, only its position */
static int g_exec_jog(struct sim_machine *m, const struct g_blk *b)
{
    struct sm_grbl *g = m->g;
    int i;
    if (b->cmds & ~(BIT(GR_G3) | BIT(GR_G6) | BIT(GR_G0))) {
        return G_ERR_JOG;
    }
    if (!(b->nonmodal == 53 || b->nonmodal == 0)) {
        return G_ERR_JOG;
    }
    if (g->set[G_SET_SOFT] != 0.0f) {
        for (i = 0; i < 3; i++) { /* system.c system_check_travel_limits */
            if (b->xyz[i] > 0.0f || b->xyz[i] < -g->set[G_SET_TRAVEL + i]) {
                return G_ERR_TRAVEL;
            }
        }
    }
    g_move(m, b, g->pos, b->xyz, 0, b->f, 0);
    sm_step_call(m, g_jog_start, 0);
    memcpy(g->pos, b->xyz, sizeof g->pos);
    return 0;
}

/* gcode.c gc_execute_line for the line in m->g->line ("$J=..." when jog) */
void g_gcode(struct sim_machine *m, int jog)
{
    struct g_blk b;
    int st;
    memset(&b, 0, sizeof b);
    b.md = m->g->md;
    b.md.flow = 0;
    if (jog) {
        b.jog = 1;
        b.md.motion = G_MO_LINEAR;
        b.md.inverse = 0;
    }
    st = g_words(m, &b);
    b.had_f = (b.vals & BIT(W_F)) != 0;
    if (!st) {
        st = g_check_common(m, &b);
    }
    if (!st) {
        st = g_check_target(m, &b);
    }
    if (!st) {
        st = g_check_motion(m, &b);
    }
    if (!st && jog) {
        st = g_exec_jog(m, &b);
    }
    if (st) {
        m->r.v.ignored_axes += b.has_ac ? 1u : 0u;
        if (st == G_ERR_FEED && !jog && !m->r.feed_ever && b.md.motion >= G_MO_LINEAR &&
            b.md.motion <= G_MO_CCW) {
            m->r.v.g1_without_feed++;
        }
        g_status(m, st);
        return;
    }
    if (!jog) {
        g_exec_modes(m, &b);
        g_exec_nonmodal(m, &b);
        g_exec_motion(m, &b);
    }
    g_status(m, 0);
}
