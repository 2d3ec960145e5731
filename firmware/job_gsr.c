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
 * <= 1e4 mm, |w| <= 23040 deg, ref != 0). The geometry itself is checked by RUN.
 */
#include "job.h"

/* cfg.set bits: Bezier points 0..3 (CENTER P<i>: 1 << i), radii N and B */
#define SET_BEZIER 0x0Fu
#define SET_RADII_N 0x10u
#define SET_RADII_B 0x20u
#define SET_RADII (SET_RADII_N | SET_RADII_B)

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
    const uint16_t need =
        JOB_HAVE_GSR_CENTER | JOB_HAVE_GSR_RADII | JOB_HAVE_GSR_FRAME | JOB_HAVE_RASTER;
    return (j->have & need) == need;
}

/* CENTER X|Y|Z (a coordinate function) or P0..P3 (a control point of the Bezier form). */
static unsigned center_form(enum job_word w)
{
    return w == JOB_WORD_CENTER_P0 || w == JOB_WORD_CENTER_P1 || w == JOB_WORD_CENTER_P2 ||
                   w == JOB_WORD_CENTER_P3
               ? GSR_CENTRE_BEZIER
               : GSR_CENTRE_POLY;
}

int job_gsr_command(struct job *j, struct job_args *a)
{
    struct gsr_cfg *c;
    cp_real *v = a->v;
    unsigned k = a->value, na = a->na, i, form, bit, mask, have;
    for (i = 0; i < na; i++) { /* i = GSR_W only in a function (7 numbers) */
        if (!(cp_fabs(v[i]) <= (i == GSR_W ? CP_R(23040.0) : GSR_COEF_MAX))) {
            return CP_ST_OUT_OF_RANGE;
        }
    }
    if (na == GSR_FN) {
        v[GSR_W] *= CP_DEG2RAD;
    }
    c = &j->geom.gsr;
    bit = 0u;  /* c->set bit of this command */
    mask = 0u; /* c->set bits that complete the part */
    have = 0u; /* its j->have bit, once complete */
    switch (a->cmd) {
    case GSR_CMD_CENTER: /* k: the axis (X|Y|Z) or the control point (P<k>) */
        form = center_form(a->word);
        if (form != c->centre) { /* the other form: start afresh */
            zero3(c->c);
            c->centre = (uint8_t)form;
            c->set &= (uint8_t)~SET_BEZIER;
            j->have &= (uint16_t)~JOB_HAVE_GSR_CENTER;
        }
        for (i = 0; i < na; i++) {
            if (form == GSR_CENTRE_BEZIER) {
                c->c[i][k] = v[i]; /* coordinate i of point k */
            } else {
                c->c[k][i] = v[i]; /* number i of axis k */
            }
        }
        bit = form == GSR_CENTRE_BEZIER ? 1u << k : 0u; /* all four points needed */
        mask = form == GSR_CENTRE_BEZIER ? SET_BEZIER : 0u;
        have = JOB_HAVE_GSR_CENTER;
        break;
    case GSR_CMD_RADII: /* k: f_N, f_B, f_t */
        for (i = 0; i < GSR_FN; i++) {
            c->r[k][i] = v[i];
        }
        bit = a->word == JOB_WORD_RADII_N   ? SET_RADII_N
              : a->word == JOB_WORD_RADII_B ? SET_RADII_B
                                            : 0u; /* f_t has a default */
        mask = SET_RADII;
        have = JOB_HAVE_GSR_RADII;
        break;
    case GSR_CMD_FRAME: /* k: enum gsr_frame_kind; N0 and RMF with their reference */
        if (na != 0u) {
            if (!(v[0] * v[0] + v[1] * v[1] + v[2] * v[2] > CP_R(0.0))) {
                return CP_ST_OUT_OF_RANGE;
            }
            c->ref.x = v[0];
            c->ref.y = v[1];
            c->ref.z = v[2];
        }
        c->frame = (uint8_t)k;
        have = JOB_HAVE_GSR_FRAME;
        break;
    case GSR_CMD_FORM: /* k: enum gsr_section_kind */
        c->section = (uint8_t)k;
        break;
    default: /* not GSR's (unreachable: job.c calls the owner's hook) */
        return CP_ST_UNKNOWN_CMD;
    }
    c->set |= (uint8_t)bit;
    if ((c->set & mask) == mask) {
        j->have |= (uint16_t)have;
    }
    return CP_ST_OK;
}
