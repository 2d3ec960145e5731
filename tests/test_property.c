/* test_property.c - property tests with a seeded PRNG (deterministic on every target).
 * SPDX-License-Identifier: MIT
 *
 * property_random_jobs: K random valid-looking jobs, written as protocol command
 *   lines (random curve kind and parameters, radius law, tool or none, LINES or
 *   CIRCLES [PATCH], n, u0..u1, STEPS or TOL) and applied with job_command, then
 *   canal_path_init. Either init rejects with a documented enum cp_err code
 *   (canal_path.h / canal.h: RANGE, RADIUS, DEGENERATE, EMPTY, TOO_MANY, TOOL, CUSP,
 *   TOL, NUMERIC, NONFINITE, INVAL), or every point is finite with a unit normal and
 *   every family-2 point is within 1 um of the independent reference (ref_canal.c:
 *   the orthogonal-trajectory ODE integrated adaptively, each line once,
 *   incrementally). Family-2 points: LINES mode, every point of a line; CIRCLES
 *   PATCH mode, the circle ends and the links (they run along the bounding lines).
 *   CIRCLES without PATCH: the circle ends and links lie at the fixed contact angles
 *   u0, u1 and are checked against the reference surface point (same 1 um). The
 *   interior points of the circles are measured against the evenly spaced angle and
 *   reported (note), not asserted. The distribution is deliberately not only easy
 *   cases: degenerate curves, empty sweeps, R <= 0, oversized tools, cusps, tight
 *   tolerances appear at their natural rates and are counted per code.
 * property_random_invalid: random invalid command lines (corrupted numbers, wrong
 *   arity, out of range, NaN/Inf, over-long, bad keywords, control bytes, unknown
 *   commands) through the protocol engine over the in-memory HAL: each gets exactly
 *   one "error:<code> <text>" with a code of cp_status.def (and its text), never
 *   "ok", and the engine answers "$I" afterwards. Counts per code are reported.
 */
#include <stdlib.h>
#include <string.h>

#include "hal_mem.h"
#include "job.h"
#include "proto.h"
#include "ref_canal.h"
#include "test.h"
#include "canal_path.h"

#ifdef __arm__
#define PROP_JOBS 16      /* QEMU: soft double reference, keep it short */
#define PROP_MAXN 3u
#define PROP_MAXSTEPS 24u
#define PROP_TOL_MIN 50.0 /* um */
#define PROP_INVALID 60
#else
#define PROP_JOBS 600
#define PROP_MAXN 8u
#define PROP_MAXSTEPS 200u
#define PROP_TOL_MIN 1.0
#define PROP_INVALID 2000
#endif
/* points per accepted job above which it is checked only on a prefix (runtime bound) */
#define PROP_MAX_POINTS 40000u
#define PROP_TOL_MM 1.0e-3 /* 1 um */

/* ------------------------------------------------------------ random helpers */

static double urand(unsigned *s)
{
    return (double)(test_prng(s) >> 8) * (1.0 / 16777216.0);
}

static double uni(unsigned *s, double a, double b)
{
    return a + (b - a) * urand(s);
}

static double logu(unsigned *s, double a, double b)
{
    return exp(log(a) + (log(b) - log(a)) * urand(s));
}

static unsigned irand(unsigned *s, unsigned n)
{
    return test_prng(s) % n;
}

/* Append a number in a random but valid spelling: fixed with 0..5 decimals, or an
 * exponent form. */
static void put_num(char *buf, size_t cap, unsigned *s, double v)
{
    size_t len = strlen(buf);
    if (irand(s, 8u) == 0u && v != 0.0) {
        snprintf(buf + len, cap - len, " %.6e", v);
    } else {
        snprintf(buf + len, cap - len, " %.*f", (int)irand(s, 6u) + (fabs(v) < 1.0 ? 3 : 0), v);
    }
}

/* ------------------------------------------------------------ statistics */

static unsigned st_err[20];     /* canal_path_init rejections by -enum cp_err */
static unsigned st_cmd[CP_ST_END_];     /* job command rejections by wire code */
static unsigned st_ok, st_points, st_fam2, st_trunc;
static double st_max2, st_max1, st_maxn;

/* ------------------------------------------------------------ random jobs */

/* Build one random job as command lines into lines[] (NULL-terminated). */
static int make_job(unsigned *s, char lines[8][160])
{
    double S = logu(s, 2.0, 200.0), c;
    unsigned kind = irand(s, 4u), law = irand(s, 4u), nl = 0, n, i;
    char *l;
    /* curve */
    l = lines[nl++];
    switch (kind) {
    case 0: {
        double x0 = uni(s, -S, S), y0 = uni(s, -S, S), L = logu(s, S / 10.0, 2.0 * S),
               ph = uni(s, 0.0, 6.283185307179586);
        strcpy(l, "CURVE LINE");
        put_num(l, 160, s, x0);
        put_num(l, 160, s, y0);
        if (irand(s, 25u) == 0u) { /* degenerate on purpose */
            put_num(l, 160, s, x0);
            put_num(l, 160, s, y0);
        } else {
            put_num(l, 160, s, x0 + L * cos(ph));
            put_num(l, 160, s, y0 + L * sin(ph));
        }
        break;
    }
    case 1:
    case 2: {
        double a0 = uni(s, -360.0, 360.0), span = uni(s, 2.0, 360.0);
        if (irand(s, 2u)) {
            span = -span;
        }
        if (irand(s, 30u) == 0u) {
            span = 0.0; /* empty sweep */
        }
        if (a0 + span > 720.0 || a0 + span < -720.0) {
            span = -span;
        }
        strcpy(l, kind == 1 ? "CURVE ARC" : "CURVE ELLIPSE");
        put_num(l, 160, s, uni(s, -S, S));
        put_num(l, 160, s, uni(s, -S, S));
        put_num(l, 160, s, logu(s, S / 20.0, S));
        if (kind == 2) {
            put_num(l, 160, s, logu(s, S / 20.0, S));
        }
        put_num(l, 160, s, a0);
        put_num(l, 160, s, a0 + span);
        break;
    }
    default:
        strcpy(l, "CURVE BEZIER");
        for (i = 0; i < 8u; i++) {
            put_num(l, 160, s, uni(s, -S, S));
        }
        break;
    }
    /* radius law around a typical radius c */
    c = logu(s, 0.3, S);
    l = lines[nl++];
    switch (law) {
    case 0:
        strcpy(l, "RADIUS CONST");
        put_num(l, 160, s, c);
        break;
    case 1:
        strcpy(l, "RADIUS LINEAR");
        put_num(l, 160, s, c * logu(s, 0.25, 2.0));
        put_num(l, 160, s, irand(s, 20u) == 0u ? -c : c * logu(s, 0.25, 2.0));
        break;
    case 2:
        strcpy(l, "RADIUS COS");
        put_num(l, 160, s, uni(s, -1.2 * c, 1.2 * c));
        put_num(l, 160, s, c);
        put_num(l, 160, s, irand(s, 2u) ? (double)(irand(s, 6u) + 1u) : uni(s, -8.0, 8.0));
        break;
    default:
        strcpy(l, "RADIUS CUBIC");
        for (i = 0; i < 4u; i++) {
            put_num(l, 160, s, c * uni(s, -0.2, 2.0));
        }
        break;
    }
    /* tool */
    if (irand(s, 2u)) {
        static const char *const how[3] = {"", " TIP", " CENTRE"};
        l = lines[nl++];
        strcpy(l, "TOOL BALL");
        put_num(l, 160, s, c * logu(s, 0.01, 1.5));
        strcat(l, how[irand(s, 3u)]);
    }
    /* raster */
    n = 1u + irand(s, PROP_MAXN);
    l = lines[nl++];
    {
        double u0 = uni(s, -180.0, 180.0), u1 = uni(s, -180.0, 180.0);
        if (irand(s, 2u)) { /* a narrower band around the contact curve, more often regular */
            u0 = uni(s, -60.0, 60.0);
            u1 = uni(s, -60.0, 60.0);
        }
        if (n == 1u && irand(s, 2u)) {
            u1 = u0;
        }
        strcpy(l, irand(s, 5u) < 3u ? "LINES" : "CIRCLES");
        snprintf(l + strlen(l), 40, " %u", n);
        put_num(l, 160, s, u0);
        put_num(l, 160, s, u1);
        if (l[0] == 'C' && irand(s, 2u)) {
            strcat(l, " PATCH");
        }
    }
    /* steps or tolerance */
    l = lines[nl++];
    if (irand(s, 2u)) {
        unsigned m = 1u + irand(s, PROP_MAXSTEPS);
#ifndef __arm__
        if (irand(s, 20u) == 0u) {
            m = 1000u + irand(s, 3097u); /* up to CP_MAX_STEPS */
        }
#endif
        snprintf(l, 160, "STEPS %u", m);
    } else {
        strcpy(l, "TOL");
        put_num(l, 160, s, logu(s, PROP_TOL_MIN, 1000.0));
    }
    lines[nl][0] = '\0';
    return (int)nl;
}

/* Reference position of the emitted point at (t, u): surface, tool centre or tip. */
static double ref_dist(const struct ref_canal *rc, const struct canal_path *tp, double t, double u,
                       const struct raster_pt *pt)
{
    double m[3], nn[3], r = (double)tp->tool_r, d[3];
    ref_point(rc, t, u, m, nn);
    if (tp->output != RASTER_OUT_SURFACE) {
        int i;
        for (i = 0; i < 3; i++) {
            m[i] -= r * nn[i];
        }
        if (tp->output == RASTER_OUT_TIP) {
            m[2] -= r;
        }
    }
    d[0] = m[0] - (double)pt->p.x;
    d[1] = m[1] - (double)pt->p.y;
    d[2] = m[2] - (double)pt->p.z;
    return sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
}

static double start_u(const struct canal_path *tp, unsigned j)
{
    if (tp->head.n < 2u) {
        return (double)tp->u0;
    }
    return (double)tp->u0 + (double)j * ((double)tp->u1 - (double)tp->u0) / (double)(tp->head.n - 1u);
}

#define MAXL (PROP_MAXN > 2u ? PROP_MAXN : 2u)

/* Walk every point of an accepted job; returns 0 or the failing line. */
static int check_job(struct canal_path *tp, const char lines[8][160])
{
    struct ref_canal rc;
    static struct ref_line rl[MAXL];
    struct raster_pt pt;
    double cp[8], rp[4], worst = 0.0;
    uint32_t k, limit = canal_path_count(tp);
    int i, circ = tp->head.mode == RASTER_CIRCLES, patch = tp->span == RASTER_SPAN_LINES;
    int cur_circle = -1;
    for (i = 0; i < 8; i++) {
        cp[i] = (double)tp->surf.cp[i];
    }
    for (i = 0; i < 4; i++) {
        rp[i] = (double)tp->surf.rp[i];
    }
    ref_canal_set(&rc, tp->surf.curve, tp->surf.radius, cp, rp);
    CHECK((double)tp->surf.t0 == rc.t0 && (double)tp->surf.t1 == rc.t1);
    if (circ) {
        ref_line_start(&rl[0], &rc, rc.t0, (double)tp->u0);
        ref_line_start(&rl[1], &rc, rc.t0, (double)tp->u1);
    } else {
        CHECK(tp->head.n <= MAXL);
        for (i = 0; i < (int)tp->head.n; i++) {
            ref_line_start(&rl[i], &rc, rc.t0, start_u(tp, (unsigned)i));
        }
    }
    if (limit > PROP_MAX_POINTS) {
        limit = PROP_MAX_POINTS;
        st_trunc++;
    }
    for (k = 0; k < limit; k++) {
        double e = -1.0, t, nl;
        CHECK_EQ_INT(canal_path_next(tp, &pt), CP_OK);
        CHECK(cp_finite(pt.p.x) && cp_finite(pt.p.y) && cp_finite(pt.p.z));
        CHECK(cp_finite(pt.n.x) && cp_finite(pt.n.y) && cp_finite(pt.n.z));
        nl = sqrt((double)pt.n.x * pt.n.x + (double)pt.n.y * pt.n.y + (double)pt.n.z * pt.n.z);
        if (fabs(nl - 1.0) > st_maxn) {
            st_maxn = fabs(nl - 1.0);
        }
        CHECK(fabs(nl - 1.0) < 1e-3);
        t = (double)pt.t;
        st_points++;
        if (!circ) {
            if (pt.line >= 0) {
                CHECK(pt.line < (int)tp->head.n);
                CHECK_EQ_INT(ref_line_advance(&rl[pt.line], t), 0);
                e = ref_dist(&rc, tp, t, rl[pt.line].u, &pt);
            }
        } else {
            int side = -1; /* 0: on the u0 bound, 1: on the u1 bound */
            if (pt.line >= 0) {
                cur_circle = pt.line;
                if (pt.index == 0u) {
                    side = 0;
                } else if (pt.index == tp->head.steps) {
                    side = 1;
                }
            } else {
                side = (cur_circle & 1) ? 0 : 1; /* links leave where the circle ended */
            }
            if (patch) {
                CHECK_EQ_INT(ref_line_advance(&rl[0], t), 0);
                CHECK_EQ_INT(ref_line_advance(&rl[1], t), 0);
            }
            if (side >= 0) {
                e = ref_dist(&rc, tp, t, patch ? rl[side].u : (side ? (double)tp->u1 : (double)tp->u0),
                             &pt);
            } else {
                /* interior circle point: evenly spaced contact angle (measured only) */
                double ua = patch ? rl[0].u : (double)tp->u0, ub = patch ? rl[1].u : (double)tp->u1;
                double e1 = ref_dist(&rc, tp, t, ua + (ub - ua) * pt.index / tp->head.steps, &pt);
                if (e1 > st_max1) {
                    st_max1 = e1;
                }
            }
        }
        if (e >= 0.0) {
            st_fam2++;
            if (e > worst) {
                worst = e;
            }
            if (!(e <= PROP_TOL_MM)) {
                int q;
                printf("  point %u (line %d index %u t %.9g) off the reference by %.4g um; job:\n",
                       (unsigned)k, pt.line, pt.index, t, e * 1e3);
                for (q = 0; lines[q][0] != '\0'; q++) {
                    printf("    %s\n", lines[q]);
                }
                return __LINE__;
            }
        }
    }
    if (worst > st_max2) {
        st_max2 = worst;
    }
    return 0;
}

int test_property_random_jobs(void)
{
    static struct job jb;
    static struct canal_path tp;
    static char lines[8][160];
    unsigned seed = 0x5eed2024u, i;
    int c;
    memset(st_err, 0, sizeof st_err);
    memset(st_cmd, 0, sizeof st_cmd);
    st_ok = st_points = st_fam2 = st_trunc = 0;
    st_max2 = st_max1 = st_maxn = 0.0;
    for (i = 0; i < PROP_JOBS; i++) {
        int st = CP_ST_OK, err, r;
        make_job(&seed, lines);
        job_init(&jb);
        for (c = 0; lines[c][0] != '\0'; c++) {
            st = job_command(&jb, lines[c], strlen(lines[c]));
            if (st != CP_ST_OK) {
                break;
            }
        }
        if (st != CP_ST_OK) {
            /* generated within the protocol ranges: a command may still be refused
             * (e.g. a radius written as 0.000) - counted, must be a documented code */
            CHECK(st > 0 && st < CP_ST_END_);
            st_cmd[st]++;
            continue;
        }
        CHECK((jb.have & JOB_HAVE_ALL) == JOB_HAVE_ALL);
        err = canal_path_init(&tp, &jb.canal, &jb.cfg);
        if (err != CP_OK) {
            CHECK(err == CP_ERR_RANGE || err == CP_ERR_RADIUS || err == CP_ERR_DEGENERATE ||
                  err == CP_ERR_EMPTY || err == CP_ERR_TOO_MANY || err == CP_ERR_TOOL ||
                  err == CP_ERR_CUSP || err == CP_ERR_TOL || err == CP_ERR_NUMERIC ||
                  err == CP_ERR_NONFINITE || err == CP_ERR_INVAL);
            st_err[-err]++;
            continue;
        }
        st_ok++;
        r = check_job(&tp, (const char(*)[160])lines);
        if (r != 0) {
            return r;
        }
    }
    TEST_NOTE("property jobs (%s): %u random jobs, %u accepted, %u points, %u family-2/bound "
              "points checked, max error %.4f um (limit 1 um); circle interiors %.4f um; "
              "max |n|-1 %.2g; %u truncated to %u points\n",
              CP_REAL_NAME, (unsigned)PROP_JOBS, st_ok, st_points, st_fam2, st_max2 * 1e3,
              st_max1 * 1e3, st_maxn, st_trunc, (unsigned)PROP_MAX_POINTS);
    TEST_NOTE("rejected by canal_path_init: RANGE %u RADIUS %u DEGENERATE %u EMPTY %u TOO_MANY %u "
              "TOOL %u CUSP %u NUMERIC %u TOL %u NONFINITE %u INVAL %u\n",
              st_err[3], st_err[4], st_err[5], st_err[6], st_err[7], st_err[8], st_err[9],
              st_err[10], st_err[11], st_err[2], st_err[1]);
    {
        unsigned q, any = 0;
        for (q = 1; q < (unsigned)CP_ST_END_; q++) {
            if (st_cmd[q]) {
                TEST_NOTE("rejected by a job command: error:%u (%s) x%u\n", q, cp_status_text((int)q),
                          st_cmd[q]);
                any = 1;
            }
        }
        if (!any) {
            TEST_NOTE("rejected by a job command: none\n");
        }
    }
    CHECK(st_ok > 0u);
    return 0;
}

/* ------------------------------------------------------------ random invalid lines */

static struct hal_mem pm;
static struct hal_uart pu;
static struct proto pp;

/* Send one line, collect every reply line until the engine is quiet. Returns the
 * number of reply lines; the first is copied to first[]. */
static int exchange(const char *line, size_t len, char *first, size_t cap, int *ver)
{
    int i, nlines = 0;
    size_t start = 0, k;
    pm.in_pos = pm.in_len = 0;
    pm.out_len = 0;
    (void)hal_mem_feed(&pm, line, len);
    (void)hal_mem_feed(&pm, "\n", 1);
    for (i = 0; i < 64; i++) {
        (void)proto_poll(&pp);
    }
    *ver = 0;
    for (k = 0; k < pm.out_len; k++) {
        if (pm.out[k] == '\n') {
            size_t n = k - start;
            if (nlines == 0) {
                if (n >= cap) {
                    n = cap - 1;
                }
                memcpy(first, pm.out + start, n);
                first[n] = '\0';
            }
            if (k - start >= 5 && memcmp(pm.out + start, "[VER:", 5) == 0) {
                *ver = 1;
            }
            nlines++;
            start = k + 1;
        }
    }
    return nlines;
}

static const char *const valid_cmds[] = {
    "CURVE LINE 0 0 10 5",          "CURVE ARC 0 0 3 0 360",   "CURVE ELLIPSE 1 -2 20 12 20 140",
    "CURVE BEZIER 0 0 10 15 20 -15 30 0", "RADIUS CONST 2",    "RADIUS LINEAR 2 6",
    "RADIUS COS 5.5 10.5 2",        "RADIUS CUBIC 3 5 2 4",    "TOOL BALL 1 TIP",
    "LINES 3 -25 10",               "CIRCLES 4 -20 30 PATCH",  "STEPS 40",
    "TOL 5",                        "SAFE 25",                 "RXBUF 128",
};
#define NVALID (sizeof valid_cmds / sizeof valid_cmds[0])

static const char *const bad_numbers[] = {"x", "1.2.3", "1e", "--1", "0x10", "1,5", "+", ".", "e5",
                                          "1e+", "5..", "1-2", "12a", "#", "1e5e5"};
static const char *const nonfinite[] = {"nan", "NaN", "inf", "-inf", "+Infinity", "INF"};

/* Make an invalid variant of a random valid command. Returns the category. */
static int make_invalid(unsigned *s, char *out, size_t cap, size_t *len)
{
    char tok[16][40];
    unsigned nt = 0, i, cat = irand(s, 8u), pick;
    const char *src = valid_cmds[irand(s, NVALID)];
    const char *p = src;
    /* split */
    while (*p != '\0' && nt < 16u) {
        size_t n = 0;
        while (*p == ' ') {
            p++;
        }
        while (*p != '\0' && *p != ' ' && n < 39u) {
            tok[nt][n++] = *p++;
        }
        tok[nt][n] = '\0';
        nt++;
    }
    /* first numeric token */
    for (pick = 1; pick < nt; pick++) {
        if ((tok[pick][0] >= '0' && tok[pick][0] <= '9') || tok[pick][0] == '-') {
            break;
        }
    }
    switch (cat) {
    case 0: /* corrupted number: a listed non-number, or a stray character inside */
        if (pick < nt) {
            unsigned which = pick + irand(s, nt - pick);
            if (irand(s, 2u)) {
                strcpy(tok[which], bad_numbers[irand(s, sizeof bad_numbers / sizeof bad_numbers[0])]);
            } else {
                static const char stray[] = "xX,;#@_/:=&";
                size_t n = strlen(tok[which]), at = irand(s, (unsigned)n + 1u);
                memmove(tok[which] + at + 1, tok[which] + at, n - at + 1);
                tok[which][at] = stray[irand(s, sizeof stray - 1u)];
            }
        }
        break;
    case 1: /* wrong arity: drop a token or add one */
        if (irand(s, 2u) && pick < nt) { /* a number (dropping TIP/PATCH stays valid) */
            unsigned which = pick + irand(s, nt - pick);
            while (which > pick && !((tok[which][0] >= '0' && tok[which][0] <= '9') ||
                                     tok[which][0] == '-')) {
                which--;
            }
            for (i = which; i + 1u < nt; i++) {
                strcpy(tok[i], tok[i + 1u]);
            }
            nt--;
        } else if (nt < 16u) {
            strcpy(tok[nt++], "7");
        }
        break;
    case 2: /* out of range */
        if (pick < nt) {
            static const char *const big[] = {"1e12", "-2e9", "1e10", "99999999999", "1e41"};
            unsigned which = pick + irand(s, nt - pick); /* sequenced: same on every compiler */
            strcpy(tok[which], big[irand(s, 5u)]);
        }
        break;
    case 3: /* NaN / Inf */
        if (pick < nt) {
            unsigned which = pick + irand(s, nt - pick);
            strcpy(tok[which], nonfinite[irand(s, sizeof nonfinite / sizeof nonfinite[0])]);
        }
        break;
    case 4: /* bad keyword (second word) or unknown command (first) */
    {
        unsigned which = nt > 1u && irand(s, 2u) ? 1u : 0u;
        strcpy(tok[which], irand(s, 2u) ? "WAVY" : "SPIRALX");
    }
        break;
    default:
        break;
    }
    out[0] = '\0';
    for (i = 0; i < nt; i++) {
        if (i) {
            strcat(out, " ");
        }
        strcat(out, tok[i]);
    }
    *len = strlen(out);
    if (cat == 5) { /* over-long: pad with spaces and junk to >= 96 bytes */
        size_t target = 96u + irand(s, 200u);
        while (*len < target && *len < cap - 1u) {
            static const char junk[] = " 0123456789abcXYZ.-+e";
            out[(*len)++] = junk[irand(s, sizeof junk - 1u)];
        }
        out[*len] = '\0';
    } else if (cat == 6) { /* a control byte inside (not \n \r \t or 0x18) */
        static const char ctl[] = {1, 2, 3, 4, 7, 8, 11, 12, 14, 27, 31, 127};
        size_t at = irand(s, (unsigned)*len + 1u);
        memmove(out + at + 1, out + at, *len - at + 1);
        out[at] = ctl[irand(s, sizeof ctl)];
        (*len)++;
    } else if (cat == 7) { /* out of range of the command itself */
        static const char *const oor[] = {"LINES 0 -10 10", "LINES 3 -10 200", "LINES 3 5 5",
                                          "STEPS 0", "TOL 0", "TOL 20000", "FEED -5",
                                          "RXBUF 8", "RXBUF 5000", "TOOL BALL -1", "TOOL BALL 0",
                                          "LINES 99999 -10 10", "STEPS 999999", "CIRCLES 3 1 1",
                                          "FEED 2e6", "TOOL BALL 20000", "SAFE 2000",
                                          "SPINDLE 1e6", "FEED 600 0"};
        strcpy(out, oor[irand(s, sizeof oor / sizeof oor[0])]);
        *len = strlen(out);
    }
    return (int)cat;
}

int test_property_random_invalid(void)
{
    static char line[400];
    static unsigned by_code[CP_ST_END_], by_cat[8];
    unsigned seed = 0xbadc0deu, i;
    struct proto_cfg cfg = {0};
    char first[160];
    hal_mem_init(&pm, &pu);
    pm.tick_ms = 1;
    cfg.uart = &pu;
    CHECK_EQ_INT(proto_init(&pp, &cfg), CP_OK);
    memset(by_code, 0, sizeof by_code);
    memset(by_cat, 0, sizeof by_cat);
    for (i = 0; i < PROP_INVALID; i++) {
        size_t len;
        int cat = make_invalid(&seed, line, sizeof line, &len), n, ver;
        long code;
        char *end;
        n = exchange(line, len, first, sizeof first, &ver);
        if (n != 1 || strncmp(first, "error:", 6) != 0) {
            printf("  invalid line \"%s\" (category %d) -> %d lines, first \"%s\"\n", line, cat, n,
                   n > 0 ? first : "");
            return __LINE__;
        }
        code = strtol(first + 6, &end, 10);
        CHECK(code >= 1 && code < CP_ST_END_);
        /* "error:<code> <text>", then optionally " (<cause>)" (PROTOCOL.md) */
        {
            const char *text = cp_status_text((int)code);
            size_t tl = strlen(text), fl;
            CHECK(*end == ' ' && strncmp(end + 1, text, tl) == 0);
            fl = strlen(end + 1 + tl);
            CHECK(fl == 0 || (strncmp(end + 1 + tl, " (", 2) == 0 && end[tl + fl] == ')'));
        }
        by_code[code]++;
        by_cat[cat]++;
        /* the engine still answers */
        n = exchange("$I", 2, first, sizeof first, &ver);
        CHECK_EQ_INT(n, 3);
        CHECK(ver);
    }
    {
        char buf[400];
        size_t pos = 0;
        unsigned q;
        buf[0] = '\0';
        for (q = 1; q < (unsigned)CP_ST_END_; q++) {
            if (by_code[q]) {
                pos += (size_t)snprintf(buf + pos, sizeof buf - pos, " %u:%u", q, by_code[q]);
            }
        }
        TEST_NOTE("property invalid: %u lines (categories number %u arity %u range %u nonfinite %u "
                  "keyword %u long %u control %u cmd-range %u), codes (code:count)%s\n",
                  (unsigned)PROP_INVALID, by_cat[0], by_cat[1], by_cat[2], by_cat[3], by_cat[4],
                  by_cat[5], by_cat[6], by_cat[7], buf);
    }
    return 0;
}

/* ------------------------------------------------------------ open finding F3 */

/* Regression test of finding F3 (docs/HARDENING.md, fixed): a G-code line built while
 * the machine's buffer is full waits for room; a text reply (here a '?' report) sent
 * meanwhile must not corrupt it (it once went out as "<Run|P:1/153>\nG1 X9.7619 Y0"). */
int test_property_repro_f3(void);

int test_property_repro_f3(void)
{
    static const char *const job[] = {"CURVE ARC 0 0 3 0 360", "RADIUS COS 5.5 10.5 2",
                                      "LINES 3 -25 10", "STEPS 40", "RXBUF 120",
                                      "FEED 600",              "SAFE 20",
                                      "RUN"};
    struct proto_cfg cfg = {0};
    unsigned i;
    hal_mem_init(&pm, &pu);
    pm.tick_ms = 1;
    cfg.uart = &pu;
    CHECK_EQ_INT(proto_init(&pp, &cfg), CP_OK);
    for (i = 0; i < sizeof job / sizeof job[0]; i++) {
        (void)hal_mem_feed_str(&pm, job[i]);
        (void)hal_mem_feed_str(&pm, "\n");
    }
    for (i = 0; i < 20u; i++) {
        (void)proto_poll(&pp);
    }
    /* the program's first lines (the modes 20 bytes, G0 Z 12, G0 X Y 22, the plunge 36)
     * and the first cut line in flight: the next one does not fit RXBUF 120 and waits */
    pm.out_len = 0;
    (void)hal_mem_feed_str(&pm, "?");
    (void)proto_poll(&pp); /* report staged, the G1 line built behind it */
    (void)proto_poll(&pp); /* report flushed */
    CHECK(pm.out_len > 0 && pm.out[0] == '<');
    pm.out_len = 0;
    (void)hal_mem_feed_str(&pm, "ok\nok\n"); /* the machine frees preamble and a line */
    for (i = 0; i < 3u; i++) {
        (void)proto_poll(&pp);
    }
    CHECK(pm.out_len > 4 && memcmp(pm.out, "G1 X", 4) == 0 && pm.out[pm.out_len - 1] == '\n');
    return 0;
}
