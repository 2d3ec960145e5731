/* judge_canal.c - host_sim's judge of the canal (SURFACE CANAL, the default; judge.h):
 * every received point against an independent double-precision model (tests/ref_canal.c;
 * no firmware code, no closed form).
 * SPDX-License-Identifier: MIT
 *
 * Row 0 of models.def: the canal job is also the firmware's base job, so sim_check.c gives
 * this judge every job line whatever the SURFACE (the raster commands TOOL, LINES, CIRCLES,
 * STEPS, TOL stay in it); it judges only the runs of SURFACE CANAL.
 *
 * Model. The job commands are parsed here (same grammar and range checks as
 * firmware/job/job.c, in double, degrees -> radians) into a struct ref_canal. The
 * raster is rebuilt from the run header (mode, n, steps, link) exactly as
 * firmware/models/canal_path.h defines it, with DOUBLE t:
 *   LINES    block = steps + 1 + link, j = k / block, r = k % block.
 *            r <= steps: line j at i = (j odd ? steps - r : r), t_i = t0 + i (t1 - t0)/steps,
 *            u = the family-2 line through (t0, u0 + j (u1 - u0)/(n - 1)), integrated by
 *            ref_line (adaptive Dormand-Prince, 1e-12 rad), one state per line, advanced
 *            incrementally in either direction (odd lines: t0 -> t1 once, then back).
 *            r > steps: link point kk = r - steps at t = t1 (j even) / t0 (j odd), at the
 *            contact angle of the normalised linear interpolation (fraction kk/(link + 1))
 *            of the half-angle directions of u_j and u_{j+1} along the shorter half-angle
 *            route (the firmware's label_lerp; link_u).
 *   CIRCLES  gsteps = (n - 1)(link + 1) (1 if n == 1), node t = t0 + node (t1 - t0)/gsteps;
 *            circle c at node c (link + 1), points i = (c odd ? steps - r : r) uniform in
 *            contact angle from the bound u0 to the bound u1 (half-angle route); links at
 *            nodes c (link + 1) + kk along bound u1 (c even) / u0 (c odd). Bounds: fixed
 *            angles (span ANGLE, default) or the family-2 lines from u0, u1 (PATCH).
 *   Output: surface m, tool centre m - r n (TOOL BALL r CENTRE), tip centre - r z (TIP).
 *
 * Checks (max, RMS, limit; one pass/fail each):
 *   surface  | |c - rho(t)| - (R(t) - r_tool) |, c the tool centre recovered from the point;
 *            limit 1e-3 mm.
 *   line     |p - reference emitted point at (t, u_ref)|; limit 1e-3 mm.
 *   ortho    deviation from 90 deg between the streamed family-2 line and the circle at
 *            every point that lies on a family-2 line (LINES: line points; CIRCLES PATCH:
 *            the links and the circle end points). Method: the stencil direction
 *            D = (P_b - P_a) - [(M_b - M_a) - (t_b - t_a) M'(t_x)] with a, b the stream
 *            neighbours of the point x on the same line (central when both exist, one-sided
 *            at line ends), M the reference emitted positions and M' the reference line
 *            tangent (analytic m_t + u' m_u, with the offset term for tools). The bracket is
 *            the stencil's own truncation error, computed exactly from the reference, so D
 *            = (t_b - t_a) M' + (e_b - e_a) with e the stream's position errors: no O(h)
 *            chord bias, and what is measured is the stream's error growth ALONG the circle.
 *            dev = asin(|D . e_c| / |D|), e_c the unit circle tangent. Resolution: the 0.1 um
 *            quantization alone can tilt D by up to qb = 1e-4 mm * (|e_cx|+|e_cy|+|e_cz|)/|D|
 *            (both ends rounded by <= 0.05 um per axis), which at fine steps is larger than
 *            0.01 deg (0.2 mm chords: ~0.05 deg). The per-point limit is therefore
 *            0.01 deg + qb (the achievable bound); the row shows max dev, RMS, max qb and the
 *            max excess dev - qb.
 *   chord    for every consecutive pair of points of this run, the max distance of the
 *            reference curve between them (8 interior samples; family-2 lines by advancing
 *            the line's own ODE state through the samples, circles by angle, u = const
 *            links by t) from the received chord; limit the job's TOL (STEPS: info only,
 *            not counted).
 *   coverage every run: points k = first, first + 1, ... in order, complete runs up to
 *            points - 1; the header agrees with the job (mode, n, STEPS) and with
 *            points = n (steps + 1) + (n - 1) link; over the runs of one pass (a RUN and its
 *            RESUMEs), a complete run closes the pass and every point of [start, points) must
 *            have been received exactly once.
 *   normal   (FRAMES only, when normals were received) angle to the reference normal
 *            (m - rho)/R, limit 0.01 deg.
 */
#include "judge.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ref_canal.h"

#define SC_PI 3.14159265358979323846
#define SC_DEG (SC_PI / 180.0)
#define SC_MAX_LINES 256u
#define SC_MAX_STEPS 4096u
#define SC_MAX_LINK 64u
#define SC_MAX_POINTS (SC_MAX_LINES * (SC_MAX_STEPS + 1u) + (SC_MAX_LINES - 1u) * SC_MAX_LINK)
#define SC_QUANT 1e-4      /* wire quantization, mm */
#define SC_LIM_SURF 1e-3   /* mm */
#define SC_LIM_LINE 1e-3   /* mm */
#define SC_LIM_ORTHO 0.01  /* deg (+ quantization bound per point) */
#define SC_LIM_NORMAL 0.01 /* deg */
#define SC_CHORD_SAMPLES 8
#define SC_MAX_TOKENS 12

enum { OUT_SURFACE = 0, OUT_CENTRE = 1, OUT_TIP = 2 };
enum { SEG_NONE = 0, SEG_LINE = 1, SEG_CIRCLE = 2, SEG_UCONST = 3 };
enum { CK_SURF = 0, CK_LINE, CK_ORTHO, CK_CHORD, CK_NORMAL, CK_N };

/* ---- the job as the judge models it ---------------------------------------------------- */

static struct {
    int curve, radius;
    double cp[8], rp[4];
    unsigned have; /* 1 curve, 2 radius, 4 raster */
    int mode, patch;
    unsigned n;
    double u0, u1;  /* radians */
    unsigned steps; /* STEPS m, or 0 */
    double tol;     /* mm; 0 with STEPS */
    int output;
    double tool_r;
    unsigned gen; /* bumped by every accepted job command */
} job;

/* ---- per-run state --------------------------------------------------------------------- */

static struct ref_canal rc;
static struct ref_line lines[SC_MAX_LINES];
static double line_start[SC_MAX_LINES];
static unsigned char line_live[SC_MAX_LINES];
static unsigned char seen[SC_MAX_POINTS];

static struct {
    int active, geom; /* a run is open; its geometry can be judged */
    uint32_t points, first, next;
    int mode;
    unsigned n, steps, link, gsteps;
    double tol; /* chord limit, mm (0: info only) */
} run;

static struct {
    int open;
    uint32_t points, start;
    unsigned gen;
} pass;

struct pt {
    int valid;
    uint32_t k;
    double P[3], M[3];
    double t, u;
    int on_line;  /* family-2 line id the point lies on, or -1 */
    int in_line;  /* the segment from the previous point runs along this line, or -1 */
    double Md[3]; /* dM/dt along the line (on_line >= 0) */
    double ec[3]; /* unit circle tangent */
};

static struct pt pp, pv; /* the points k - 2 and k - 1 of this run */

struct seg {
    int kind, line;
    double t, ua, ub; /* SEG_CIRCLE: at t, contact angle ua -> ub */
    double ta, tb, u; /* SEG_LINE (line), SEG_UCONST (u): t from ta to tb */
};

struct stat {
    double max, sum2, aux, aux2;
    unsigned long n, fails;
    uint32_t worst_k;
};

static struct stat st[CK_N];
static struct {
    unsigned long errors, out_of_order, out_of_range, dup, missing, header, unchecked;
    char first[160];
} cov;
static unsigned runs, runs_complete;
static unsigned long points_seen;
static double judge_seconds;
static int chord_info_only;
static double chord_tol; /* chord limit of the last modelled run, mm (0: info only) */

/* ---- small helpers --------------------------------------------------------------------- */

static char up(char c)
{
    return (c >= 'a' && c <= 'z') ? (char)(c - 'a' + 'A') : c;
}

static int kw(const char *s, const char *k)
{
    while (*s && *k) {
        if (up(*s) != *k) {
            return 0;
        }
        s++;
        k++;
    }
    return *s == '\0' && *k == '\0';
}

/* The firmware's number grammar (parse.c): [+-] digits [. digits] [e [+-] digits]. */
static int num(const char *s, double *v)
{
    const char *p = s;
    int digits = 0;
    char *end;
    if (*p == '+' || *p == '-') {
        p++;
    }
    while (*p >= '0' && *p <= '9') {
        p++;
        digits++;
    }
    if (*p == '.') {
        p++;
        while (*p >= '0' && *p <= '9') {
            p++;
            digits++;
        }
    }
    if (digits == 0) {
        return -1;
    }
    if (*p == 'e' || *p == 'E') {
        int ed = 0;
        p++;
        if (*p == '+' || *p == '-') {
            p++;
        }
        while (*p >= '0' && *p <= '9') {
            p++;
            ed++;
        }
        if (ed == 0) {
            return -1;
        }
    }
    if (*p != '\0') {
        return -1;
    }
    *v = strtod(s, &end);
    return isfinite(*v) ? 0 : -1;
}

static int uint_tok(const char *s, unsigned long *v)
{
    const char *p = s;
    unsigned long x = 0;
    if (*p == '+') {
        p++;
    }
    if (*p < '0' || *p > '9') {
        return -1;
    }
    while (*p >= '0' && *p <= '9') {
        if (x < 100000000ul) {
            x = x * 10ul + (unsigned long)(*p - '0');
        }
        p++;
    }
    if (*p != '\0') {
        return -1;
    }
    *v = x;
    return 0;
}

static double dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static double dist3(const double *a, const double *b)
{
    double d[3];
    d[0] = a[0] - b[0];
    d[1] = a[1] - b[1];
    d[2] = a[2] - b[2];
    return sqrt(dot3(d, d));
}

/* Distance of x from the segment [a, b]. */
static double seg_dist(const double *a, const double *b, const double *x)
{
    double ab[3], ax[3], L2, s, c[3];
    int i;
    for (i = 0; i < 3; i++) {
        ab[i] = b[i] - a[i];
        ax[i] = x[i] - a[i];
    }
    L2 = dot3(ab, ab);
    s = L2 > 0.0 ? dot3(ax, ab) / L2 : 0.0;
    s = s < 0.0 ? 0.0 : (s > 1.0 ? 1.0 : s);
    for (i = 0; i < 3; i++) {
        c[i] = a[i] + s * ab[i];
    }
    return dist3(c, x);
}

/* Contact angle of a LINES link point at fraction sig of the way from ua to ua + d:
 * the firmware interpolates the unit half-angle directions linearly and renormalises
 * (label_lerp), so the half angle moves by atan2(sig sin phi, 1 - sig + sig cos phi),
 * phi = d/2 - not uniformly. */
static double link_u(double ua, double d, double sig)
{
    double phi = 0.5 * d;
    return ua + 2.0 * atan2(sig * sin(phi), 1.0 - sig + sig * cos(phi));
}

/* Contact-angle difference along the shorter half-angle route (firmware label_between). */
static double route(double d)
{
    double h = 0.5 * d;
    while (h > SC_PI) {
        h -= 2.0 * SC_PI;
    }
    while (h <= -SC_PI) {
        h += 2.0 * SC_PI;
    }
    return 2.0 * h;
}

static void stat_add(int ck, double v, int fail, uint32_t k)
{
    struct stat *s = &st[ck];
    if (s->n == 0 || v > s->max) {
        s->max = v;
        s->worst_k = k;
    }
    s->sum2 += v * v;
    s->n++;
    if (fail) {
        s->fails++;
    }
}

static void cov_err(const char *what, uint32_t k)
{
    cov.errors++;
    if (cov.first[0] == '\0') {
        snprintf(cov.first, sizeof cov.first, "%s (k=%lu)", what, (unsigned long)k);
    }
}

/* ---- the reference surface ------------------------------------------------------------- */

/* Emitted reference position (surface point, tool centre or tip) and unit normal. */
static void emit(double t, double u, double M[3], double nrm[3])
{
    double m[3], nn[3];
    ref_point(&rc, t, u, m, nn);
    if (job.output != OUT_SURFACE) {
        m[0] -= job.tool_r * nn[0];
        m[1] -= job.tool_r * nn[1];
        m[2] -= job.tool_r * nn[2];
        if (job.output == OUT_TIP) {
            m[2] -= job.tool_r;
        }
    }
    M[0] = m[0];
    M[1] = m[1];
    M[2] = m[2];
    if (nrm) {
        nrm[0] = nn[0];
        nrm[1] = nn[1];
        nrm[2] = nn[2];
    }
}

/* Tangent dM/dt of the emitted position along the family-2 line through (t, u), and the
 * unit tangent of the circle there. */
static void line_tangent(double t, double u, double Md[3], double ec[3])
{
    double m[3], mt[3], mu[3], ms[3], l;
    double up_ = ref_uprime(&rc, t, u);
    int i;
    ref_partials(&rc, t, u, m, mt, mu);
    for (i = 0; i < 3; i++) {
        ms[i] = mt[i] + up_ * mu[i];
        Md[i] = ms[i];
    }
    if (job.output != OUT_SURFACE) {
        struct ref_jet jt;
        double rho[3], drho[3];
        ref_jet(&rc, t, &jt);
        rho[0] = jt.x;
        rho[1] = jt.y;
        rho[2] = jt.r;
        drho[0] = jt.dx;
        drho[1] = jt.dy;
        drho[2] = jt.dr;
        for (i = 0; i < 3; i++) {
            /* n = (m - rho)/R: dn/dt = (m' - rho')/R - (m - rho) R'/R^2 */
            double dn = (ms[i] - drho[i]) / jt.r - (m[i] - rho[i]) * jt.dr / (jt.r * jt.r);
            Md[i] = ms[i] - job.tool_r * dn;
        }
    }
    l = sqrt(dot3(mu, mu));
    for (i = 0; i < 3; i++) {
        ec[i] = mu[i] / l;
    }
}

/* u of family-2 line id at t (advances the line's own ODE state). */
static int line_u(unsigned id, double t, double *u)
{
    if (!line_live[id]) {
        ref_line_start(&lines[id], &rc, rc.t0, line_start[id]);
        line_live[id] = 1;
    }
    if (ref_line_advance(&lines[id], t) != 0) {
        return -1;
    }
    *u = lines[id].u;
    return 0;
}

static double t_line(unsigned i)
{
    return rc.t0 + (double)i * (rc.t1 - rc.t0) / (double)run.steps;
}

static double t_node(unsigned node)
{
    if (run.gsteps == 0u) {
        return rc.t0;
    }
    return rc.t0 + (double)node * (rc.t1 - rc.t0) / (double)run.gsteps;
}

/* CIRCLES bound (0: u0, 1: u1) at t. */
static int bound_u(unsigned side, double t, double *u)
{
    if (job.patch) {
        return line_u(side, t, u);
    }
    *u = side ? job.u1 : job.u0;
    return 0;
}

/* ---- the stream model: point k -> (t, u, line), and the segment (k - 1, k) ------------ */

static int locate(uint32_t k, struct pt *x, struct seg *sg, int want_seg)
{
    uint32_t block = run.steps + 1u + run.link;
    uint32_t j = k / block, r = k % block;
    int odd = (int)(j & 1u);
    x->on_line = -1;
    sg->kind = SEG_NONE;
    sg->line = -1;
    if (run.mode == 0) { /* LINES */
        if (r <= run.steps) {
            unsigned i = odd ? run.steps - r : r;
            x->t = t_line(i);
            x->on_line = (int)j;
            if (want_seg && r > 0u) {
                sg->kind = SEG_LINE;
                sg->line = (int)j;
                sg->ta = t_line(odd ? i + 1u : i - 1u);
                sg->tb = x->t;
            } else if (want_seg && j > 0u) { /* from the last point of link j - 1 */
                double te = (j - 1u) & 1u ? rc.t0 : rc.t1, ua, ub, d;
                if (line_u(j - 1u, te, &ua) || line_u(j, te, &ub)) {
                    return -1;
                }
                d = route(ub - ua);
                sg->kind = SEG_CIRCLE;
                sg->t = te;
                sg->ua = link_u(ua, d, (double)run.link / (double)(run.link + 1u));
                sg->ub = ua + d;
            }
            /* the line state ends at x->t after the chord sampling */
            return 0;
        } else {
            uint32_t kk = r - run.steps;
            double te = odd ? rc.t0 : rc.t1, ua, ub, d;
            if (j + 1u >= run.n) {
                return -1;
            }
            if (line_u(j, te, &ua) || line_u(j + 1u, te, &ub)) {
                return -1;
            }
            d = route(ub - ua);
            x->t = te;
            x->u = link_u(ua, d, (double)kk / (double)(run.link + 1u));
            if (want_seg) {
                sg->kind = SEG_CIRCLE;
                sg->t = te;
                sg->ua = link_u(ua, d, (double)(kk - 1u) / (double)(run.link + 1u));
                sg->ub = x->u;
            }
            return 0;
        }
    }
    /* CIRCLES */
    if (r <= run.steps) {
        unsigned i = odd ? run.steps - r : r;
        double lo, hi, d;
        x->t = t_node(j * (run.link + 1u));
        if (want_seg && r == 0u && j > 0u) {
            unsigned side = ((j - 1u) & 1u) ? 0u : 1u;
            sg->kind = job.patch ? SEG_LINE : SEG_UCONST;
            sg->line = job.patch ? (int)side : -1;
            sg->u = side ? job.u1 : job.u0;
            sg->ta = t_node(j * (run.link + 1u) - 1u);
            sg->tb = x->t;
        }
        if (sg->kind == SEG_LINE) {
            return 0; /* bounds evaluated after the chord sampling: see finish_circle */
        }
        if (bound_u(0u, x->t, &lo) || bound_u(1u, x->t, &hi)) {
            return -1;
        }
        d = route(hi - lo);
        x->u = lo + d * (double)i / (double)run.steps;
        if (job.patch && (i == 0u || i == run.steps)) {
            x->on_line = i == 0u ? 0 : 1;
        }
        if (want_seg && r > 0u) {
            unsigned ip = odd ? i + 1u : i - 1u;
            sg->kind = SEG_CIRCLE;
            sg->t = x->t;
            sg->ua = lo + d * (double)ip / (double)run.steps;
            sg->ub = x->u;
        }
        return 0;
    } else {
        uint32_t kk = r - run.steps;
        unsigned side = odd ? 0u : 1u;
        unsigned node = j * (run.link + 1u) + kk;
        x->t = t_node(node);
        if (job.patch) {
            x->on_line = (int)side;
        } else {
            x->u = side ? job.u1 : job.u0;
        }
        if (want_seg) {
            sg->kind = job.patch ? SEG_LINE : SEG_UCONST;
            sg->line = job.patch ? (int)side : -1;
            sg->u = side ? job.u1 : job.u0;
            sg->ta = t_node(node - 1u);
            sg->tb = x->t;
        }
        return 0;
    }
}

/* Max distance of the reference curve of segment sg from the chord [a, b]. For SEG_LINE
 * the line's ODE state is advanced through the samples (it is at sg->ta, or is brought
 * there). */
static int chord_of(const struct seg *sg, const double *a, const double *b, double *out)
{
    double mx = 0.0, M[3];
    int s;
    for (s = 1; s <= SC_CHORD_SAMPLES; s++) {
        double f = (double)s / (double)(SC_CHORD_SAMPLES + 1), d;
        if (sg->kind == SEG_CIRCLE) {
            emit(sg->t, sg->ua + f * (sg->ub - sg->ua), M, NULL);
        } else {
            double t = sg->ta + f * (sg->tb - sg->ta), u = sg->u;
            if (sg->kind == SEG_LINE) {
                if (s == 1 && line_u((unsigned)sg->line, sg->ta, &u)) {
                    return -1;
                }
                if (line_u((unsigned)sg->line, t, &u)) {
                    return -1;
                }
            }
            emit(t, u, M, NULL);
        }
        d = seg_dist(a, b, M);
        mx = d > mx ? d : mx;
    }
    *out = mx;
    return 0;
}

/* Ortho check of point x (on a family-2 line) with its line neighbours a, b (or NULL). */
static void ortho_eval(const struct pt *x, const struct pt *a, const struct pt *b)
{
    double D[3], ld, c, dev, qb;
    int i;
    if (a == NULL && b == NULL) {
        return;
    }
    if (a == NULL) {
        a = x;
    }
    if (b == NULL) {
        b = x;
    }
    for (i = 0; i < 3; i++) {
        D[i] = (b->P[i] - a->P[i]) - ((b->M[i] - a->M[i]) - (b->t - a->t) * x->Md[i]);
    }
    ld = sqrt(dot3(D, D));
    if (!(ld > 0.0)) {
        return;
    }
    c = fabs(dot3(D, x->ec)) / ld;
    c = c > 1.0 ? 1.0 : c;
    dev = asin(c) / SC_DEG;
    qb = SC_QUANT * (fabs(x->ec[0]) + fabs(x->ec[1]) + fabs(x->ec[2])) / ld;
    qb = (qb >= 1.0 ? SC_PI / 2.0 : asin(qb)) / SC_DEG;
    stat_add(CK_ORTHO, dev, !(dev <= SC_LIM_ORTHO + qb), x->k);
    if (qb > st[CK_ORTHO].aux) {
        st[CK_ORTHO].aux = qb;
    }
    if (dev - qb > st[CK_ORTHO].aux2) {
        st[CK_ORTHO].aux2 = dev - qb;
    }
}

/* ---- the judge (judge.h) --------------------------------------------------------------- */

/* session: everything afresh; SURFACE CANAL: nothing (the firmware keeps the canal's
 * CURVE and RADIUS across SURFACE commands). */
void judge_canal_reset(int session)
{
    if (!session) {
        return;
    }
    memset(&job, 0, sizeof job);
    job.n = 1;
    job.tol = 1e-3; /* firmware default TOL 1 um */
    memset(&run, 0, sizeof run);
    memset(&pass, 0, sizeof pass);
    memset(st, 0, sizeof st);
    memset(&cov, 0, sizeof cov);
    memset(&pp, 0, sizeof pp);
    memset(&pv, 0, sizeof pv);
    runs = runs_complete = 0;
    points_seen = 0;
    judge_seconds = 0.0;
    chord_info_only = 0;
    chord_tol = 0.0;
}

/* ---- the canal's job commands: each returns 0 (modelled), 1 (bad arguments) ------------ */

/* CURVE LINE|ARC|ELLIPSE|BEZIER p... (angles in degrees) */
static int cmd_curve(char **tok, unsigned nt)
{
    static const char *const names[4] = {"LINE", "ARC", "ELLIPSE", "BEZIER"};
    static const unsigned ar[4] = {4u, 5u, 6u, 8u};
    double v[8];
    unsigned k, i;
    if (nt < 2u) {
        return 1;
    }
    for (k = 0; k < 4u && !kw(tok[1], names[k]); k++) {
    }
    if (k == 4u || nt != 2u + ar[k]) {
        return 1;
    }
    for (i = 0; i < ar[k]; i++) {
        if (num(tok[2u + i], &v[i])) {
            return 1;
        }
    }
    if (k == 1u) {
        v[3] *= SC_DEG;
        v[4] *= SC_DEG;
    } else if (k == 2u) {
        v[4] *= SC_DEG;
        v[5] *= SC_DEG;
    }
    job.curve = (int)k;
    for (i = 0; i < 8u; i++) {
        job.cp[i] = i < ar[k] ? v[i] : 0.0;
    }
    job.have |= 1u;
    job.gen++;
    return 0;
}

/* RADIUS CONST|LINEAR|COS|CUBIC p... */
static int cmd_radius(char **tok, unsigned nt)
{
    static const char *const names[4] = {"CONST", "LINEAR", "COS", "CUBIC"};
    double v[4];
    unsigned k, i;
    if (nt < 2u) {
        return 1;
    }
    for (k = 0; k < 4u && !kw(tok[1], names[k]); k++) {
    }
    if (k == 4u || nt != 3u + k) {
        return 1;
    }
    for (i = 0; i <= k; i++) {
        if (num(tok[2u + i], &v[i])) {
            return 1;
        }
    }
    job.radius = (int)k;
    for (i = 0; i < 4u; i++) {
        job.rp[i] = i <= k ? v[i] : 0.0;
    }
    job.have |= 2u;
    job.gen++;
    return 0;
}

/* TOOL NONE | TOOL BALL r [TIP|CENTRE|CENTER] */
static int cmd_tool(char **tok, unsigned nt)
{
    double r;
    if (nt == 2u && kw(tok[1], "NONE")) {
        job.output = OUT_SURFACE;
        job.tool_r = 0.0;
        job.gen++;
        return 0;
    }
    if (nt < 3u || nt > 4u || !kw(tok[1], "BALL") || num(tok[2], &r) || !(r > 0.0) || r > 1e4) {
        return 1;
    }
    if (nt == 4u && !kw(tok[3], "TIP") && !kw(tok[3], "CENTRE") && !kw(tok[3], "CENTER")) {
        return 1;
    }
    job.output = (nt == 4u && !kw(tok[3], "TIP")) ? OUT_CENTRE : OUT_TIP;
    job.tool_r = r;
    job.gen++;
    return 0;
}

/* LINES n u0 u1 | CIRCLES n u0 u1 [PATCH] (degrees) */
static int cmd_raster(char **tok, unsigned nt)
{
    int circles = kw(tok[0], "CIRCLES"), patch = 0;
    unsigned long uv;
    double v[2];
    if (circles && nt == 5u) {
        if (!kw(tok[4], "PATCH")) {
            return 1;
        }
        patch = 1;
    } else if (nt != 4u) {
        return 1;
    }
    if (uint_tok(tok[1], &uv) || num(tok[2], &v[0]) || num(tok[3], &v[1])) {
        return 1;
    }
    if (uv == 0ul || uv > SC_MAX_LINES || fabs(v[0]) > 180.0 || fabs(v[1]) > 180.0 ||
        (v[0] == v[1] && uv > 1ul)) {
        return 1;
    }
    job.mode = circles;
    job.patch = circles ? patch : 0;
    job.n = (unsigned)uv;
    job.u0 = v[0] * SC_DEG;
    job.u1 = v[1] * SC_DEG;
    job.have |= 4u;
    job.gen++;
    return 0;
}

/* STEPS m */
static int cmd_steps(char **tok, unsigned nt)
{
    unsigned long uv;
    if (nt != 2u || uint_tok(tok[1], &uv) || uv == 0ul || uv > SC_MAX_STEPS) {
        return 1;
    }
    job.steps = (unsigned)uv;
    job.tol = 0.0;
    job.gen++;
    return 0;
}

/* TOL um */
static int cmd_tol(char **tok, unsigned nt)
{
    double v;
    if (nt != 2u || num(tok[1], &v) || v < 0.01 || v > 10000.0) {
        return 1;
    }
    job.tol = v * 1e-3;
    job.steps = 0;
    job.gen++;
    return 0;
}

/* FEED, FORMAT, RXBUF, CHECKSUM: no geometry */
static int cmd_none(char **tok, unsigned nt)
{
    (void)tok;
    (void)nt;
    return 0;
}

static const struct {
    const char *word;
    int (*parse)(char **tok, unsigned nt);
} canal_cmds[] = {
    {"CURVE", cmd_curve},    {"RADIUS", cmd_radius}, {"TOOL", cmd_tool},     {"LINES", cmd_raster},
    {"CIRCLES", cmd_raster}, {"STEPS", cmd_steps},   {"TOL", cmd_tol},       {"FEED", cmd_none},
    {"FORMAT", cmd_none},    {"RXBUF", cmd_none},    {"CHECKSUM", cmd_none},
};

int judge_canal_job_line(const char *line)
{
    char buf[128], *tok[SC_MAX_TOKENS + 1];
    unsigned nt, c;
    size_t L = strlen(line);
    if (L >= sizeof buf) {
        return 0; /* longer than any command the firmware accepts (error:2) */
    }
    memcpy(buf, line, L + 1u);
    nt = judge_words(buf, tok, SC_MAX_TOKENS);
    if (nt == 0u) {
        return 0;
    }
    for (c = 0; c < sizeof canal_cmds / sizeof canal_cmds[0]; c++) {
        if (kw(tok[0], canal_cmds[c].word)) {
            /* more tokens than any of these commands takes: bad arguments */
            return nt > SC_MAX_TOKENS ? 1 : canal_cmds[c].parse(tok, nt);
        }
    }
    return 0; /* not a job command (RUN, RESUME, $I, ...) */
}

void judge_canal_run_begin(uint32_t points, uint32_t first, int mode, unsigned n, unsigned steps,
                           unsigned link)
{
    unsigned i;
    uint64_t want;
    runs++;
    if (run.active) {
        cov_err("run began before the previous one ended", first);
    }
    memset(&run, 0, sizeof run);
    memset(&pp, 0, sizeof pp);
    memset(&pv, 0, sizeof pv);
    run.active = 1;
    run.points = points;
    run.first = first;
    run.next = first;
    run.mode = mode;
    run.n = n;
    run.steps = steps;
    run.link = link;
    if ((job.have & 7u) != 7u) {
        cov.unchecked++;
        cov_err("run of a job the judge cannot model (CURVE/RADIUS/raster missing)", first);
        return;
    }
    if (mode != job.mode || n != job.n || (job.steps != 0u && steps != job.steps)) {
        cov.header++;
        cov_err("run header disagrees with the job (mode, n or STEPS)", first);
    }
    want = (uint64_t)n * (steps + 1u) + (uint64_t)(n > 0u ? n - 1u : 0u) * link;
    if (n == 0u || n > SC_MAX_LINES || steps == 0u || steps > SC_MAX_STEPS || link > SC_MAX_LINK ||
        (mode != 0 && mode != 1)) {
        cov.unchecked++;
        cov_err("run header outside the firmware limits", first);
        return;
    }
    if (want != points) {
        cov.header++;
        cov_err("header points != n (steps + 1) + (n - 1) link", first);
    }
    if (first >= points && points > 0u) {
        cov.header++;
        cov_err("first point beyond the job", first);
    }
    ref_canal_set(&rc, job.curve, job.radius, job.cp, job.rp);
    run.gsteps = mode == 0 ? 0u : (n > 1u ? (n - 1u) * (link + 1u) : 0u);
    run.tol = job.steps ? 0.0 : job.tol;
    chord_tol = run.tol;
    if (job.steps) {
        chord_info_only = 1;
    }
    for (i = 0; i < SC_MAX_LINES; i++) {
        line_live[i] = 0;
    }
    if (mode == 0) {
        for (i = 0; i < n; i++) {
            line_start[i] =
                n > 1u ? job.u0 + (job.u1 - job.u0) * (double)i / (double)(n - 1u) : job.u0;
        }
    } else {
        line_start[0] = job.u0;
        line_start[1] = job.u1;
    }
    run.geom = 1;
    /* coverage pass: a RUN from 0, a new job, a different size or a closed pass starts one */
    if (!pass.open || first == 0u || pass.gen != job.gen || pass.points != points) {
        pass.open = 1;
        pass.points = points;
        pass.start = first;
        pass.gen = job.gen;
        if (points <= SC_MAX_POINTS) {
            memset(seen, 0, points);
        }
    }
}

/* Coverage of point k (order, range, twice). 1 if its geometry is to be judged. */
static int point_coverage(uint32_t k)
{
    if (!run.active) {
        cov_err("point outside a run", k);
        return 0;
    }
    if (k != run.next) {
        cov.out_of_order++;
        cov_err("point out of order", k);
    }
    run.next = k + 1u;
    if (k >= run.points) {
        cov.out_of_range++;
        cov_err("point beyond the job", k);
        return 0;
    }
    if (pass.open && k < SC_MAX_POINTS) {
        if (seen[k]) {
            cov.dup++;
            cov_err("point received twice", k);
        } else {
            seen[k] = 1;
        }
    }
    return run.geom;
}

/* The contact angle of point k where it depends on integrated lines (after the chord
 * sampling, which moved the line states on). -1 if the reference integration failed. */
static int point_angle(uint32_t k, struct pt *cur, const struct seg *sg)
{
    if (run.mode == 0 && cur->on_line >= 0) {
        return line_u((unsigned)cur->on_line, cur->t, &cur->u);
    }
    if (run.mode == 1) {
        uint32_t block = run.steps + 1u + run.link, r = k % block;
        if (r <= run.steps && sg->kind == SEG_LINE) { /* circle start after a PATCH link */
            unsigned i = (k / block) & 1u ? run.steps - r : r;
            double lo, hi;
            if (bound_u(0u, cur->t, &lo) || bound_u(1u, cur->t, &hi)) {
                return -1;
            }
            cur->u = lo + route(hi - lo) * (double)i / (double)run.steps;
            cur->on_line = (i == 0u) ? 0 : (i == run.steps ? 1 : -1);
        } else if (r > run.steps && job.patch) {
            return line_u((unsigned)cur->on_line, cur->t, &cur->u);
        }
    }
    return 0;
}

/* surface, line and normal of the located point cur (n: received normal or NULL); its line
 * tangent for the ortho check. */
static void point_checks(struct pt *cur, const double *n)
{
    double nref[3], rho[3], c[3], e;
    struct ref_jet jt;
    uint32_t k = cur->k;
    emit(cur->t, cur->u, cur->M, nref);
    /* surface: the tool centre recovered from the point */
    ref_jet(&rc, cur->t, &jt);
    rho[0] = jt.x;
    rho[1] = jt.y;
    rho[2] = jt.r;
    c[0] = cur->P[0];
    c[1] = cur->P[1];
    c[2] = cur->P[2] + (job.output == OUT_TIP ? job.tool_r : 0.0);
    e = fabs(dist3(c, rho) - (jt.r - job.tool_r));
    stat_add(CK_SURF, e, !(e <= SC_LIM_SURF), k);
    e = dist3(cur->P, cur->M);
    stat_add(CK_LINE, e, !(e <= SC_LIM_LINE), k);
    if (n != NULL) {
        double cr[3], a;
        cr[0] = n[1] * nref[2] - n[2] * nref[1];
        cr[1] = n[2] * nref[0] - n[0] * nref[2];
        cr[2] = n[0] * nref[1] - n[1] * nref[0];
        a = atan2(sqrt(dot3(cr, cr)), dot3(n, nref)) / SC_DEG;
        stat_add(CK_NORMAL, a, !(a <= SC_LIM_NORMAL), k);
    }
    if (cur->on_line >= 0) {
        line_tangent(cur->t, cur->u, cur->Md, cur->ec);
    }
}

/* The geometry of point k: locate, chord of (k - 1, k), angle, checks, and the ortho of
 * point k - 1 now that its right neighbour is known. */
static void point_geometry(uint32_t k, double x, double y, double z, const double *n)
{
    struct pt cur;
    struct seg sg;
    int have_prev;
    memset(&cur, 0, sizeof cur);
    memset(&sg, 0, sizeof sg);
    cur.valid = 1;
    cur.k = k;
    cur.P[0] = x;
    cur.P[1] = y;
    cur.P[2] = z;
    have_prev = pv.valid && pv.k + 1u == k;
    if (locate(k, &cur, &sg, have_prev)) {
        cov.unchecked++;
        cov_err("reference integration failed", k);
        run.geom = 0;
        return;
    }
    /* chord of the segment (k - 1, k): before the point, which moves the line state on */
    if (have_prev && sg.kind != SEG_NONE) {
        double c;
        if (chord_of(&sg, pv.P, cur.P, &c)) {
            cov.unchecked++;
            cov_err("reference integration failed", k);
            run.geom = 0;
            return;
        }
        stat_add(CK_CHORD, c, run.tol > 0.0 && c > run.tol, k);
    }
    cur.in_line = sg.kind == SEG_LINE ? sg.line : -1;
    if (point_angle(k, &cur, &sg)) {
        run.geom = 0;
        return;
    }
    point_checks(&cur, n);
    if (pv.valid && pv.on_line >= 0) {
        int left = pp.valid && pp.k + 1u == pv.k && pv.in_line == pv.on_line;
        int right = have_prev && cur.in_line == pv.on_line;
        ortho_eval(&pv, left ? &pp : NULL, right ? &cur : NULL);
    }
    pp = pv;
    pv = cur;
}

void judge_canal_point(uint32_t k, double x, double y, double z, const double *n)
{
    struct timespec t_a, t_b;
    clock_gettime(CLOCK_MONOTONIC, &t_a);
    points_seen++;
    if (point_coverage(k)) {
        point_geometry(k, x, y, z, n);
    }
    clock_gettime(CLOCK_MONOTONIC, &t_b);
    judge_seconds += (double)(t_b.tv_sec - t_a.tv_sec) + 1e-9 * (double)(t_b.tv_nsec - t_a.tv_nsec);
}

void judge_canal_run_end(int complete)
{
    uint32_t k;
    if (!run.active) {
        cov_err("run end without a run", 0u);
        return;
    }
    if (run.geom && pv.valid && pv.on_line >= 0) {
        int left = pp.valid && pp.k + 1u == pv.k && pv.in_line == pv.on_line;
        ortho_eval(&pv, left ? &pp : NULL, NULL);
    }
    if (complete) {
        runs_complete++;
        if (run.next != run.points) {
            cov.missing++;
            cov_err("complete run did not reach the last point", run.next);
        }
        if (pass.open && run.points <= SC_MAX_POINTS) {
            for (k = pass.start; k < run.points; k++) {
                if (!seen[k]) {
                    cov.missing++;
                    cov_err("point never received in this RUN/RESUME pass", k);
                    break;
                }
            }
        }
        pass.open = 0;
    }
    run.active = 0;
    memset(&pp, 0, sizeof pp);
    memset(&pv, 0, sizeof pv);
}

static void row(FILE *f, int *passed, int *failed, const char *name, int counted, int ok,
                const char *detail)
{
    if (!counted) {
        fprintf(f, "  INFO judge %-8s %s\n", name, detail);
        return;
    }
    if (ok) {
        (*passed)++;
    } else {
        (*failed)++;
    }
    fprintf(f, "  %s judge %-8s %s\n", ok ? "PASS" : "FAIL", name, detail);
}

void judge_canal_report(FILE *f, int *passed, int *failed)
{
    static const char *const names[CK_N] = {"surface", "line", "ortho", "chord", "normal"};
    char d[320];
    int c;
    if (runs == 0u) {
        return; /* "no run" is sim_check.c's line */
    }
    fprintf(f,
            "  judge: %u run(s), %u complete, %lu points, %.3f s in the judge (%.0f points/s), "
            "%ld reference RK steps\n",
            runs, runs_complete, points_seen, judge_seconds,
            judge_seconds > 0.0 ? (double)points_seen / judge_seconds : 0.0, ref_total_steps());
    for (c = 0; c < CK_N; c++) {
        const struct stat *s = &st[c];
        double rms = s->n ? sqrt(s->sum2 / (double)s->n) : 0.0;
        int mm = c == CK_SURF || c == CK_LINE || c == CK_CHORD;
        const char *unit = mm ? "mm" : "deg";
        if (c == CK_NORMAL && s->n == 0ul) {
            continue; /* G-code: no normals */
        }
        if (s->n == 0ul) {
            /* nothing to measure (e.g. CIRCLES span ANGLE has no family-2 line for ortho,
             * or every run stopped before its second point): shown, not counted */
            row(f, passed, failed, names[c], 0, 1, "no samples in the judged runs");
            continue;
        }
        if (c == CK_CHORD) {
            if (chord_info_only || chord_tol <= 0.0) {
                snprintf(d, sizeof d, "max %.3e mm rms %.3e mm (STEPS: no limit) n=%lu worst k=%lu",
                         s->max, rms, s->n, (unsigned long)s->worst_k);
                row(f, passed, failed, names[c], 0, 1, d);
                continue;
            }
            snprintf(d, sizeof d, "max %.3e mm rms %.3e mm limit %.3e mm (TOL) n=%lu worst k=%lu",
                     s->max, rms, chord_tol, s->n, (unsigned long)s->worst_k);
        } else if (c == CK_ORTHO) {
            snprintf(
                d, sizeof d,
                "max %.4f deg rms %.4f deg limit %.2f deg + quantization bound (max %.4f deg); "
                "max excess %.4f deg n=%lu worst k=%lu",
                s->max, rms, SC_LIM_ORTHO, s->aux, s->aux2, s->n, (unsigned long)s->worst_k);
        } else {
            double lim = c == CK_SURF ? SC_LIM_SURF : (c == CK_LINE ? SC_LIM_LINE : SC_LIM_NORMAL);
            snprintf(d, sizeof d, "max %.3e %s rms %.3e %s limit %.0e %s n=%lu worst k=%lu", s->max,
                     unit, rms, unit, lim, unit, s->n, (unsigned long)s->worst_k);
        }
        if (s->fails) {
            size_t L = strlen(d);
            snprintf(d + L, sizeof d - L, ", %lu over the limit", s->fails);
        }
        row(f, passed, failed, names[c], 1, s->fails == 0ul && s->n > 0ul, d);
    }
    snprintf(d, sizeof d,
             "%lu point(s) in %u run(s): %lu out of order, %lu beyond, %lu twice, %lu missing, "
             "%lu header, %lu unchecked%s%s",
             points_seen, runs, cov.out_of_order, cov.out_of_range, cov.dup, cov.missing,
             cov.header, cov.unchecked, cov.first[0] ? "; first: " : "", cov.first);
    row(f, passed, failed, "coverage", 1, cov.errors == 0ul, d);
}

int judge_canal_surface(double tf, double u, double p[3])
{
    struct ref_canal s;
    double n[3];
    if ((job.have & 3u) != 3u) {
        return 0;
    }
    ref_canal_set(&s, job.curve, job.radius, job.cp, job.rp);
    ref_point(&s, s.t0 + tf * (s.t1 - s.t0), u, p, n);
    return 1;
}

int judge_canal_urange(double *u0, double *u1)
{
    if ((job.have & 4u) == 0u) {
        return 0;
    }
    *u0 = job.u0 < job.u1 ? job.u0 : job.u1;
    *u1 = job.u0 < job.u1 ? job.u1 : job.u0;
    return 1;
}
