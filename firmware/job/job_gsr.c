/* job_gsr.c - protocol commands of SURFACE GSR (docs/PROTOCOL.md, "Generalized surfaces of
 * revolution"); the geometry is struct gsr_cfg in job->geom.gsr (gsr.h).
 * SPDX-License-Identifier: MIT
 *
 *   CENTER X|Y|Z a0 a1 a2 a3 b c w   a centre coordinate a0 + a1 t + a2 t^2 + a3 t^3
 *                                    + b sin(w t) + c cos(w t), w in degrees per unit t;
 *                                    coordinates not given are 0 (switches a Bezier off)
 *   CENTER P0|P1|P2|P3 x y z         a control point of a cubic Bezier centre (all four
 *                                    needed; switches the X|Y|Z form off)
 *   RADII N|B|T a0 a1 a2 a3 b c w    f_N(u), f_B(u) (both needed), f_t(u) (default u)
 *   FRAME FIXED|FRENET | FRAME N0|RMF x y z
 *   FORM RATIONAL|TRIG               section points (default RATIONAL)
 * Arity error:3, numbers error:4/5, keyword error:9 (job.c checks these: the keywords,
 * words and number counts are rows of commands.def), range error:6 (|a_i|, |b|, |c|, |x|, ref
 * <= 1e4 mm, |w| <= 23040 deg, ref != 0); RADII checks its function alone as gsr_init does
 * (gsr_fn_check at u = k/256: error:28 f_N or f_B <= 0, error:29 f_t outside [0, 1],
 * decreasing or f_t(1) <= f_t(0)). The rest of the geometry is checked by RUN.
 */
#include "job.h"

/* cfg.set bits (the protocol's bookkeeping, ignored by gsr_init): what RUN needs */
#define SET_BEZIER 0x0Fu  /* CENTER P<i>: 1 << i, all four make the Bezier centre */
#define SET_RADII_N 0x10u /* RADII N */
#define SET_RADII_B 0x20u /* RADII B */
#define SET_FRAME 0x40u   /* FRAME */
#define SET_CENTER 0x80u  /* a complete centre: CENTER X|Y|Z, or all four P<i> */
#define SET_ALL (SET_CENTER | SET_RADII_N | SET_RADII_B | SET_FRAME)

/* Zero the 3 functions m[0..2]. */
static void zero3(cp_real (*m)[GSR_FN])
{
    unsigned i;
    for (i = 0; i < 3u * GSR_FN; i++) {
        m[i / GSR_FN][i % GSR_FN] = CP_R(0.0);
    }
}

void job_gsr_defaults(union path_geom *g)
{
    struct gsr_cfg *c = &g->gsr;
    zero3(c->c);
    zero3(c->r);
    c->r[2][1] = CP_R(1.0); /* f_t(u) = u */
    c->ref.x = c->ref.y = c->ref.z = CP_R(0.0);
    c->centre = GSR_CENTRE_POLY;
    c->frame = GSR_FRAME_FIXED;
    c->section = GSR_SECTION_RATIONAL;
    c->set = 0;
}

int job_gsr_ready(const struct job *j)
{
    return (j->geom.gsr.set & SET_ALL) == SET_ALL && (j->have & JOB_HAVE_RASTER) != 0u;
}

/* CENTER X|Y|Z (a coordinate function) or P0..P3 (a control point of the Bezier form). */
static unsigned center_form(enum job_word w)
{
    return w == JOB_WORD_CENTER_P0 || w == JOB_WORD_CENTER_P1 || w == JOB_WORD_CENTER_P2 ||
                   w == JOB_WORD_CENTER_P3
               ? GSR_CENTRE_BEZIER
               : GSR_CENTRE_POLY;
}

/* CENTER X|Y|Z a0 .. w (k: the axis) or P0..P3 x y z (k: the point). */
static void gsr_center(struct gsr_cfg *c, enum job_word w, unsigned k, const cp_real *v,
                       unsigned na)
{
    unsigned form = center_form(w), i;
    if (form != c->centre) { /* the other form: start afresh */
        zero3(c->c);
        c->centre = (uint8_t)form;
        c->set &= (uint8_t) ~(SET_BEZIER | SET_CENTER);
    }
    for (i = 0; i < na; i++) {
        if (form == GSR_CENTRE_BEZIER) {
            c->c[i][k] = v[i]; /* coordinate i of point k */
        } else {
            c->c[k][i] = v[i]; /* number i of axis k */
        }
    }
    if (form == GSR_CENTRE_BEZIER) {
        c->set |= (uint8_t)(1u << k);
    }
    if (form == GSR_CENTRE_POLY || (c->set & SET_BEZIER) == SET_BEZIER) {
        c->set |= SET_CENTER;
    }
}

int job_gsr_command(struct job *j, struct job_args *a)
{
    struct gsr_cfg *c = &j->geom.gsr;
    cp_real *v = a->v;
    unsigned k = a->value, na = a->na, i;
    int err;
    /* w (GSR_W, the last number) only in a function (GSR_FN numbers) */
    if (job_limit_abs(a, 0u, na == GSR_FN ? GSR_W : na, GSR_COEF_MAX, "|x| <= 1e4") != CP_ST_OK ||
        job_limit_abs(a, GSR_W, na, CP_R(23040.0), "|w| <= 23040") != CP_ST_OK) {
        return CP_ST_OUT_OF_RANGE;
    }
    if (na == GSR_FN) {
        v[GSR_W] *= CP_DEG2RAD;
    }
    switch (a->cmd) {
    case GSR_CMD_CENTER:
        gsr_center(c, a->word, k, v, na);
        return CP_ST_OK;
    case GSR_CMD_RADII: /* k: f_N, f_B, f_t (which has a default) */
        err = gsr_fn_check(v, k); /* gsr_init's checks of the function alone */
        if (err != CP_OK) {
            a->limit = err == CP_ERR_SECTION    ? "f > 0 at u = k/256"
                       : err == CP_ERR_FT_RANGE ? "0 <= f_t <= 1, increasing"
                                                : NULL;
            return cp_status_of(err);
        }
        for (i = 0; i < GSR_FN; i++) {
            c->r[k][i] = v[i];
        }
        if (a->word == JOB_WORD_RADII_N) {
            c->set |= SET_RADII_N;
        } else if (a->word == JOB_WORD_RADII_B) {
            c->set |= SET_RADII_B;
        }
        return CP_ST_OK;
    case GSR_CMD_FRAME: /* k: enum gsr_frame_kind; N0 and RMF with their reference */
        if (na != 0u) {
            if (!(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] > CP_R(0.0))) {
                a->limit = "x y z != 0 0 0";
                return CP_ST_OUT_OF_RANGE;
            }
            c->ref.x = v[0];
            c->ref.y = v[1];
            c->ref.z = v[2];
        }
        c->frame = (uint8_t)k;
        c->set |= SET_FRAME;
        return CP_ST_OK;
    case GSR_CMD_FORM: /* k: enum gsr_section_kind */
        c->section = (uint8_t)k;
        return CP_ST_OK;
    default: /* not GSR's (unreachable: job.c calls the owner's hook) */
        return CP_ST_UNKNOWN_CMD;
    }
}

/* One function fn (GSR_FN numbers, w in radians) as the numbers of a CENTER X|Y|Z or RADII
 * command. */
static void dump_fn(struct job_args *a, const cp_real *fn)
{
    a->na = GSR_FN;
    job_dump_numbers(a, fn);
    a->scale[GSR_W] = JOB_SCALE_DEG;
}

/* $J items: 0..3 CENTER P<i> (a Bezier centre's points given), 4..6 CENTER X|Y|Z (a
 * complete polynomial centre), 7, 8 RADII N, B (given), 9 RADII T (not f_t(u) = u),
 * 10 FRAME N0 ref (a reference kept under FIXED or FRENET), 11 FRAME, 12 FORM TRIG. */
static int gsr_dump_item(const struct gsr_cfg *c, unsigned i, struct job_args *a)
{
    static const uint8_t set_of[3] = {SET_RADII_N, SET_RADII_B, 0u};
    unsigned k;
    int ref = c->ref.x != CP_R(0.0) || c->ref.y != CP_R(0.0) || c->ref.z != CP_R(0.0);
    if (i < 4u) { /* CENTER P<i> x y z */
        job_dump_args(a, GSR_CMD_CENTER, (enum job_word)(JOB_WORD_CENTER_P0 + i));
        for (k = 0; k < 3u; k++) {
            a->v[k] = c->c[k][i];
        }
        return c->centre == GSR_CENTRE_BEZIER && (c->set & (1u << i)) != 0u;
    }
    if (i < 7u) { /* CENTER X|Y|Z */
        job_dump_word(a, GSR_CMD_CENTER, i - 4u);
        dump_fn(a, c->c[i - 4u]);
        return c->centre == GSR_CENTRE_POLY && (c->set & SET_CENTER) != 0u;
    }
    if (i < 10u) { /* RADII N|B|T */
        job_dump_word(a, GSR_CMD_RADII, i - 7u);
        dump_fn(a, c->r[i - 7u]);
        if (i == 9u) { /* f_t(u) = u is the default */
            k = 0;
            while (k < GSR_FN && c->r[2][k] == (k == 1u ? CP_R(1.0) : CP_R(0.0))) {
                k++;
            }
            return k < GSR_FN;
        }
        return (c->set & set_of[i - 7u]) != 0u;
    }
    if (i < 12u) { /* FRAME [N0 ref], FRAME */
        unsigned f = i == 10u ? GSR_FRAME_N0 : c->frame;
        job_dump_word(a, GSR_CMD_FRAME, f);
        job_dump_vec3(a, 0u, &c->ref);
        return (c->set & SET_FRAME) != 0u &&
               (i == 11u || (ref && c->frame != GSR_FRAME_N0 && c->frame != GSR_FRAME_RMF));
    }
    job_dump_word(a, GSR_CMD_FORM, c->section);
    return c->section != GSR_SECTION_RATIONAL;
}

int job_gsr_dump(const struct job *j, unsigned i, struct job_args *a)
{
    if (i > 12u) {
        return JOB_DUMP_END;
    }
    return gsr_dump_item(&j->geom.gsr, i, a) ? JOB_DUMP_LINE : JOB_DUMP_SKIP;
}
