/* job_canal.c - protocol commands of the canal's geometry (docs/PROTOCOL.md); the surface
 * is struct canal_cfg in job->canal (canal.h), kept by SURFACE: every model may use it (DRC
 * EDGE ON fillets with its RADIUS law); job_geom_fill hands it to the path at RUN.
 * SPDX-License-Identifier: MIT
 *
 *   CURVE LINE x0 y0 x1 y1 | ARC cx cy r a0 a1 | ELLIPSE cx cy A B a0 a1
 *         | BEZIER x0 y0 x1 y1 x2 y2 x3 y3     (mm; angles a0, a1 in degrees)
 *   RADIUS CONST c | LINEAR r0 r1 | COS b c k | CUBIC r0 r1 r2 r3
 * Arity error:3, numbers error:4/5, keyword error:9 (job.c, from commands.def). CURVE
 * then applies canal_init's checks of the curve alone (canal_curve_check: error:6 range,
 * 12 degenerate, 13 empty interval), RADIUS those of the law alone (canal_radius_check:
 * error:6 range), the same code for the same fault as at RUN; RUN checks the rest
 * (canal_init: error:11 R <= 0 on the interval; the raster, tool and cusps).
 */
#include "job.h"

void job_canal_defaults(union path_geom *g)
{
    (void)g; /* SURFACE CANAL: the canal's geometry is job->canal, which SURFACE keeps */
}

int job_canal_ready(const struct job *j)
{
    return (j->have & JOB_HAVE_ALL) == JOB_HAVE_ALL; /* CURVE, RADIUS, LINES or CIRCLES */
}

/* The command's numbers into dst[0..cnt), the rest 0 (CURVE, RADIUS; not inlined: one copy). */
static CP_NOINLINE void take_numbers(cp_real *dst, unsigned cnt, const struct job_args *a)
{
    unsigned i;
    for (i = 0; i < cnt; i++) {
        dst[i] = i < a->na ? a->v[i] : CP_R(0.0);
    }
}

/* (not inlined: its copy of the canal's geometry stays out of the line handler's frame) */
CP_NOINLINE int job_canal_command(struct job *j, struct job_args *a)
{
    struct canal_cfg t = j->canal; /* the job unchanged on error */
    int err;
    switch (a->cmd) {
    case CANAL_CMD_CURVE: /* the word's numbers, the rest 0 */
        take_numbers(t.cp, sizeof t.cp / sizeof t.cp[0], a);
        if (a->word == JOB_WORD_CURVE_ARC || a->word == JOB_WORD_CURVE_ELLIPSE) {
            t.cp[a->na - 2u] *= CP_DEG2RAD; /* the two angles come last */
            t.cp[a->na - 1u] *= CP_DEG2RAD;
        }
        t.curve = (uint8_t)a->value; /* enum canal_curve_kind */
        err = canal_curve_check(&t); /* canal_init's checks of the curve alone */
        break;
    case CANAL_CMD_RADIUS:
        take_numbers(t.rp, sizeof t.rp / sizeof t.rp[0], a);
        t.radius = (uint8_t)a->value; /* enum canal_radius_kind */
        err = canal_radius_check(&t); /* canal_init's checks of the law alone */
        break;
    default: /* not the canal's (unreachable: job.c calls the owner's hook) */
        return CP_ST_UNKNOWN_CMD;
    }
    if (err != CP_OK) {
        return cp_status_of(err);
    }
    j->canal = t;
    j->have |= a->cmd == CANAL_CMD_CURVE ? JOB_HAVE_CURVE : JOB_HAVE_RADIUS;
    return CP_ST_OK;
}

/* $J: item 0 CURVE, item 1 RADIUS (when set), the numbers as the job holds them (ARC and
 * ELLIPSE angles in radians: JOB_SCALE_DEG). */
int job_canal_dump(const struct job *j, unsigned i, struct job_args *a)
{
    const struct canal_cfg *surf = &j->canal;
    if (i >= JOB_CANAL_ITEMS) {
        return JOB_DUMP_END;
    }
    if (i == 0u) {
        job_dump_word(a, CANAL_CMD_CURVE, surf->curve);
        job_dump_numbers(a, surf->cp);
        if (surf->curve == CANAL_ARC || surf->curve == CANAL_ELLIPSE) {
            a->scale[a->na - 2u] = JOB_SCALE_DEG;
            a->scale[a->na - 1u] = JOB_SCALE_DEG;
        }
        return (j->have & JOB_HAVE_CURVE) != 0u ? JOB_DUMP_LINE : JOB_DUMP_SKIP;
    }
    job_dump_word(a, CANAL_CMD_RADIUS, surf->radius);
    job_dump_numbers(a, surf->rp);
    return (j->have & JOB_HAVE_RADIUS) != 0u ? JOB_DUMP_LINE : JOB_DUMP_SKIP;
}
