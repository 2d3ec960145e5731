/* job_channel.c - protocol commands of SURFACE CHANNEL (docs/PROTOCOL.md, "Channel").
 * SPDX-License-Identifier: MIT
 *
 *   SECTION a b n cx cy cz psi theta phi   append a superellipse section: semi-axes a, b
 *                             (mm), exponent n, centre (mm), orientation R = T(psi) T(theta)
 *                             T(phi) (degrees, |angle| <= 360; B5 reading)
 *   AXES x1 x2 x3 z1 z2 z3    replace the last section's orientation by explicit rows: local x
 *                             axis (the a axis) and section normal (unit, orthogonal, 1e-4)
 *   SECTIONS CLEAR            forget the sections
 * job.c checks the arity (error:3), numbers (4/5) and words (9) (commands.def). Each command checks
 * its section at once (channel_section_check: error:6 range, 28 a or b <= 0, 32 n < 1, 36 a = b
 * with n != 2); SECTION beyond CP_MAX_SECTIONS sections answers error:14 (too many), AXES before
 * any SECTION error:31 (too few: nothing to apply to); RUN checks the geometry (channel_path_init).
 */
#include "job.h"

void job_channel_defaults(union path_geom *g)
{
    g->channel.count = 0u;
}

int job_channel_ready(const struct job *j)
{
    return j->geom.channel.count > 0u && (j->have & JOB_HAVE_RASTER) != 0u;
}

/* Store section s (checked: channel_section_check) as section i (the next one or the
 * last). Returns a wire status. (Not inlined: LTO had copied it into SECTION and AXES.) */
static CP_NOINLINE int channel_store(struct job *j, const struct channel_section *s, unsigned i)
{
    struct channel_cfg *g = &j->geom.channel;
    int st = channel_section_check(s);
    if (st != CP_OK) {
        return cp_status_of(st);
    }
    g->s[i] = *s;
    g->count = (uint8_t)(i + 1u);
    return CP_ST_OK;
}

/* SECTION a b n cx cy cz psi theta phi: a new section. */
static int channel_section(struct job *j, struct job_args *a)
{
    const cp_real *v = a->v;
    struct channel_section s;
    if (j->geom.channel.count >= CP_MAX_SECTIONS) {
        a->limit = "SECTIONS CLEAR";
        return CP_ST_TOO_MANY;
    }
    if (job_limit_abs(a, 6u, 9u, CP_R(360.0), "|angle| <= 360") != CP_ST_OK) { /* the angles */
        return CP_ST_OUT_OF_RANGE;
    }
    s.a = v[0];
    s.b = v[1];
    s.n = v[2];
    s.c.x = v[3];
    s.c.y = v[4];
    s.c.z = v[5];
    channel_euler(&s, v[6] * CP_DEG2RAD, v[7] * CP_DEG2RAD, v[8] * CP_DEG2RAD,
                  CHANNEL_ORDER_SPIN_FIRST); /* the rows x and z */
    return channel_store(j, &s, j->geom.channel.count);
}

/* AXES x1 x2 x3 z1 z2 z3: the last section's rows x and z. */
static int channel_axes(struct job *j, struct job_args *a)
{
    const cp_real *v = a->v;
    const struct channel_cfg *g = &j->geom.channel;
    struct channel_section s;
    if (g->count == 0u) {
        a->limit = "SECTION first";
        return CP_ST_TOO_FEW; /* AXES needs a SECTION to apply to */
    }
    s = g->s[g->count - 1u];
    s.x.x = v[0];
    s.x.y = v[1];
    s.x.z = v[2];
    s.z.x = v[3];
    s.z.y = v[4];
    s.z.z = v[5];
    return channel_store(j, &s, g->count - 1u);
}

int job_channel_command(struct job *j, struct job_args *a)
{
    switch (a->cmd) {
    case CHANNEL_CMD_SECTION:
        return channel_section(j, a);
    case CHANNEL_CMD_AXES:
        return channel_axes(j, a);
    case CHANNEL_CMD_SECTIONS_CLEAR:
        j->geom.channel.count = 0u;
        return CP_ST_OK;
    default: /* not CHANNEL's (unreachable: job.c calls the owner's hook) */
        return CP_ST_UNKNOWN_CMD;
    }
}

/* $J: per section s (items 2 s, 2 s + 1): SECTION a b n cx cy cz 0 0 0, then AXES with the
 * rows the job holds (SECTION's angles only make rows; AXES sets them exactly). */
int job_channel_dump(const struct job *j, unsigned i, struct job_args *a)
{
    const struct channel_cfg *g = &j->geom.channel;
    const struct channel_section *s = &g->s[i / 2u];
    if (i >= 2u * CP_MAX_SECTIONS) {
        return JOB_DUMP_END;
    }
    if (i / 2u >= g->count) {
        return JOB_DUMP_SKIP;
    }
    if (i % 2u == 0u) {
        job_dump_args(a, CHANNEL_CMD_SECTION, JOB_NO_WORD);
        a->na = 9u;
        a->v[0] = s->a;
        a->v[1] = s->b;
        a->v[2] = s->n;
        job_dump_vec3(a, 3u, &s->c); /* the angles 0 */
        return JOB_DUMP_LINE;
    }
    job_dump_args(a, CHANNEL_CMD_AXES, JOB_NO_WORD);
    a->na = 6u;
    job_dump_vec3(a, 0u, &s->x);
    job_dump_vec3(a, 3u, &s->z);
    return JOB_DUMP_LINE;
}
