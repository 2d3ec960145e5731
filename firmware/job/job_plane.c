/* job_plane.c - protocol commands of SURFACE PLANE, the example model (plane.h,
 * docs/ARCHITECTURE.md "Add a surface model").
 * SPDX-License-Identifier: MIT
 *
 *   STRIP len width   the strip, mm: (0, PLANE_SIZE_MAX] each (else error:6)
 * job.c checks the arity (error:3) and the numbers (4/5); RUN needs STRIP and LINES
 * (error:10) and checks the raster (plane_path_init: CIRCLES or a tool error:6).
 */
#include "job.h"

void job_plane_defaults(union path_geom *g)
{
    g->plane.len = CP_R(0.0); /* no STRIP yet */
    g->plane.width = CP_R(0.0);
}

int job_plane_ready(const struct job *j)
{
    return j->geom.plane.len > CP_R(0.0) && (j->have & JOB_HAVE_RASTER) != 0u;
}

int job_plane_command(struct job *j, struct job_args *a)
{
    switch (a->cmd) {
    case PLANE_CMD_STRIP:
        if (!(a->v[0] > CP_R(0.0)) || a->v[0] > PLANE_SIZE_MAX || !(a->v[1] > CP_R(0.0)) ||
            a->v[1] > PLANE_SIZE_MAX) {
            return CP_ST_OUT_OF_RANGE;
        }
        j->geom.plane.len = a->v[0];
        j->geom.plane.width = a->v[1];
        return CP_ST_OK;
    default: /* not the plane's (unreachable: job.c calls the owner's hook) */
        return CP_ST_UNKNOWN_CMD;
    }
}

/* $J: item 0 STRIP len width (when set). */
int job_plane_dump(const struct job *j, unsigned i, struct job_args *a)
{
    if (i > 0u) {
        return JOB_DUMP_END;
    }
    job_dump_args(a, PLANE_CMD_STRIP, JOB_NO_WORD);
    a->na = 2u;
    a->v[0] = j->geom.plane.len;
    a->v[1] = j->geom.plane.width;
    return j->geom.plane.len > CP_R(0.0) ? JOB_DUMP_LINE : JOB_DUMP_SKIP;
}
