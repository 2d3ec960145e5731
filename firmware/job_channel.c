/* job_channel.c - protocol commands of SURFACE CHANNEL (docs/PROTOCOL.md, "Channel").
 * SPDX-License-Identifier: MIT
 *
 *   SECTION a b n cx cy cz psi theta phi   append a superellipse section: semi-axes a, b
 *                             (mm), exponent n, centre (mm), orientation R = T(psi) T(theta)
 *                             T(phi) (degrees, |angle| <= 360; B5 reading)
 *   AXES x1 x2 x3 z1 z2 z3    replace the last section's orientation by explicit rows: local x
 *                             axis (the a axis) and section normal (unit, orthogonal, 1e-4)
 *   SECTIONS CLEAR            forget the sections
 * job.c checks the arity (error:3), numbers (4/5) and words (9). Each command checks its
 * section at once (channel_section_check: error:6 range, 28 a or
 * b <= 0, 32 n < 1, 36 a = b with n != 2); SECTION beyond CP_MAX_SECTIONS sections answers
 * error:14 (too many), AXES before any SECTION error:31 (too few: nothing to apply to); RUN
 * checks the geometry (channel_path_init).
 */
#include "job.h"

#define JOB_HAVE_SECTION JOB_HAVE_CHANNEL_SECTION

CP_STATIC_ASSERT((JOB_HAVE_SECTION & ~JOB_HAVE_CHANNEL_MASK) == 0u, channel_bit_in_mask);

void job_channel_defaults(union path_geom *g)
{
    g->channel.count = 0u;
}

int job_channel_command(struct job *j, struct job_args *a)
{
    struct channel_cfg *g = &j->geom.channel;
    struct channel_section s;
    cp_real *sv = (cp_real *)&s; /* 12 reals (static assert in channel.c) */
    unsigned c = a->cmd, i;
    int st;
    if (c == 2u) { /* SECTIONS CLEAR */
        g->count = 0u;
        j->have &= (uint16_t)~JOB_HAVE_SECTION;
        return CP_ST_OK;
    }
    if (c == 0u && g->count >= CP_MAX_SECTIONS) {
        return CP_ST_TOO_MANY;
    }
    /* SECTION a b n centre at 0..5 and the angles at 6..8 (the x row, which
     * channel_euler then writes; |angle| <= 360); AXES the rows x, z at 6..11 */
    for (i = 0; i < a->na; i++) {
        sv[6u * c + i] = a->v[i];
        if (c == 0u && i >= 6u && cp_fabs(a->v[i]) > CP_R(360.0)) {
            return CP_ST_OUT_OF_RANGE;
        }
    }
    if (c == 0u) { /* SECTION: a b n, centre, angles */
        channel_euler(&s, sv[6] * CP_DEG2RAD, sv[7] * CP_DEG2RAD, sv[8] * CP_DEG2RAD,
                      CHANNEL_ORDER_SPIN_FIRST);
    } else { /* AXES: rows x, z of the last section */
        if (g->count == 0u) {
            return CP_ST_TOO_FEW; /* AXES needs a SECTION to apply to */
        }
        for (i = 0; i < 6u; i++) {
            sv[i] = ((const cp_real *)&g->s[g->count - 1u])[i];
        }
    }
    st = channel_section_check(&s);
    if (st != CP_OK) {
        return cp_status_of(st);
    }
    if (c == 0u) {
        g->count++;
    }
    g->s[g->count - 1u] = s;
    j->have |= JOB_HAVE_SECTION;
    return CP_ST_OK;
}
