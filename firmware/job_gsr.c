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
 * words and number counts are in its table), range error:6 (|a_i|, |b|, |c|, |x|, ref
 * <= 1e4 mm, |w| <= 23040 deg, ref != 0). The geometry itself is checked by RUN.
 */
#include "job.h"

/* cfg.set bits: Bezier points 0..3, radii N and B */
#define SET_BEZIER 0x0Fu
#define SET_RADII 0x30u

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

int job_gsr_command(struct job *j, struct job_args *a)
{
    struct gsr_cfg *c;
    cp_real *v = a->v;
    unsigned cmd = a->cmd, k = a->sub, na = a->na, i, bz, bit, mask, have;
    for (i = 0; i < na; i++) { /* i = GSR_W only in a function (7 numbers) */
        if (!(cp_fabs(v[i]) <= (i == GSR_W ? CP_R(23040.0) : GSR_COEF_MAX))) {
            return CP_ST_OUT_OF_RANGE;
        }
    }
    if (na == GSR_FN) {
        v[GSR_W] *= CP_DEG2RAD;
    }
    c = &j->geom.gsr;
    bz = k >= 3u;
    bit = 0u;  /* c->set bit of this command */
    mask = 0u; /* c->set bits that complete the part */
    have = 0u; /* its j->have bit, once complete */
    switch (cmd) {
    case 0u:                  /* CENTER */
        if (bz != c->centre) { /* the other form: start afresh */
            zero3(c->c);
            c->centre = (uint8_t)bz;
            c->set &= (uint8_t)~SET_BEZIER;
            j->have &= (uint16_t)~JOB_HAVE_GSR_CENTER;
        }
        for (i = 0; i < na; i++) {
            c->c[bz ? i : k][bz ? k - 3u : i] = v[i];
        }
        bit = bz << (k & 3u); /* P0..P3 (k = 3..6): one bit each, all four needed */
        mask = bz ? SET_BEZIER : 0u;
        have = JOB_HAVE_GSR_CENTER;
        break;
    case 1u: /* RADII */
        for (i = 0; i < GSR_FN; i++) {
            c->r[k][i] = v[i];
        }
        bit = (0x10u << k) & SET_RADII; /* N and B needed */
        mask = SET_RADII;
        have = JOB_HAVE_GSR_RADII;
        break;
    case 2u: /* FRAME */
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
    default: /* FORM */
        c->section = (uint8_t)k;
        break;
    }
    c->set |= (uint8_t)bit;
    if ((c->set & mask) == mask) {
        j->have |= (uint16_t)have;
    }
    return CP_ST_OK;
}
