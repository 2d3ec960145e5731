/* job_spine.c - protocol commands of SURFACE SPINE (docs/PROTOCOL.md, "Canal surfaces along a
 * 3D spine"); the geometry is struct spine_cfg in job->geom.spine (spine.h), its radius law
 * the canal's RADIUS (in the normalized spine parameter u; job_geom_fill copies it at RUN).
 * SPDX-License-Identifier: MIT
 *
 *   SPINE LINE x0 y0 z0 x1 y1 z1            straight spine P0 -> P1 (needs SPINEREF)
 *   SPINE ARC cx cy cz nx ny nz r span      circle about C in the plane normal to n, radius
 *                                           r, turning span degrees (> 0 ccw about n) from
 *                                           the SPINEDIR direction
 *   SPINE HELIX px py pz ax ay az r pitch turns   helix about the axis through P along a
 *                                           (pitch mm per turn, signed), from SPINEDIR
 *   SPINE P0|P1|P2|P3 x y z                 a control point of a cubic Bezier spine (all
 *                                           four needed; another kind starts afresh)
 *   SPINEDIR dx dy dz                       ARC/HELIX start direction (default 1 0 0)
 *   SPINEREF x y z                          N1 at u = 0 (default 0 0 0: the principal normal)
 * Arity error:3, numbers error:4/5, keyword error:9 (job.c, from commands.def); every
 * number |x| <= 1e4 (error:6; ARC |span| <= 360 deg). The rest (degenerate spine, R <= 0,
 * |dR/ds| >= 1, frame reference, tool, cusps) is spine_path_init's at RUN, the same codes.
 */
#include "job.h"

#if CP_WITH_SPINE /* its commands.def rows exist only then */

#define SET_BEZIER 0x0Fu /* SPINE P<i>: 1 << i */
#define SET_SPINE 0x10u  /* a complete spine */

void job_spine_defaults(union path_geom *g)
{
    struct spine_cfg *c = &g->spine;
    unsigned i;
    for (i = 0; i < 12u; i++) {
        c->sp[i] = CP_R(0.0);
    }
    for (i = 0; i < 4u; i++) {
        c->rp[i] = CP_R(0.0);
    }
    for (i = 0; i < 3u; i++) {
        c->ref[i] = CP_R(0.0);
        c->dir[i] = i == 0u ? CP_R(1.0) : CP_R(0.0);
    }
    c->kind = SPINE_LINE;
    c->law = SPINE_R_CONST;
    c->set = 0u;
}

int job_spine_ready(const struct job *j)
{
    return (j->geom.spine.set & SET_SPINE) != 0u && (j->have & JOB_HAVE_RADIUS) != 0u &&
           (j->have & JOB_HAVE_RASTER) != 0u;
}

/* Where the start direction goes in sp[] (ARC 7, HELIX 9; 12: none). */
static unsigned dir_slot(unsigned kind)
{
    return kind == SPINE_ARC ? 7u : kind == SPINE_HELIX ? 9u : 12u;
}

/* Copy SPINEDIR into the kind's sp[] slots (RUN and $J). */
void job_spine_fill(struct spine_cfg *c)
{
    unsigned s = dir_slot(c->kind), i;
    for (i = 0; s < 12u && i < 3u; i++) {
        c->sp[s + i] = c->dir[i];
    }
}

int job_spine_command(struct job *j, struct job_args *a)
{
    struct spine_cfg *c = &j->geom.spine;
    cp_real *v = a->v;
    unsigned na = a->na, i, kind;
    unsigned coords = a->word == JOB_WORD_SPINE_ARC ? 7u : na; /* ARC's 8th: the span */
    if (job_limit_abs(a, 0u, coords, SPINE_COORD_MAX, "|x| <= 1e4") != CP_ST_OK ||
        job_limit_abs(a, coords, na, CP_R(360.0), "|span| <= 360") != CP_ST_OK) {
        return CP_ST_OUT_OF_RANGE;
    }
    switch (a->cmd) {
    case SPINE_CMD_SPINE:
        kind = a->word == JOB_WORD_SPINE_LINE    ? SPINE_LINE
               : a->word == JOB_WORD_SPINE_ARC   ? SPINE_ARC
               : a->word == JOB_WORD_SPINE_HELIX ? SPINE_HELIX
                                                 : SPINE_BEZIER;
        if (kind != c->kind || kind != SPINE_BEZIER) { /* another spine: start afresh */
            for (i = 0; i < 12u; i++) {
                c->sp[i] = CP_R(0.0);
            }
            c->set = 0u;
            c->kind = (uint8_t)kind;
        }
        if (kind == SPINE_BEZIER) { /* point value: its 3 coordinates */
            for (i = 0; i < 3u; i++) {
                c->sp[3u * a->value + i] = v[i];
            }
            c->set |= (uint8_t)(1u << a->value);
            if ((c->set & SET_BEZIER) == SET_BEZIER) {
                c->set |= SET_SPINE;
            }
            return CP_ST_OK;
        }
        for (i = 0; i < 7u && i < na; i++) {
            c->sp[i] = v[i];
        }
        if (kind == SPINE_ARC) {
            c->sp[10] = v[7] * CP_DEG2RAD;
        } else if (kind == SPINE_HELIX) {
            c->sp[7] = v[7];
            c->sp[8] = v[8];
        }
        c->set |= SET_SPINE;
        return CP_ST_OK;
    case SPINE_CMD_SPINEDIR:
    case SPINE_CMD_SPINEREF:
        for (i = 0; i < 3u; i++) {
            if (a->cmd == SPINE_CMD_SPINEDIR) {
                c->dir[i] = v[i];
            } else {
                c->ref[i] = v[i];
            }
        }
        return CP_ST_OK;
    default: /* not the spine's (unreachable: job.c calls the owner's hook) */
        return CP_ST_UNKNOWN_CMD;
    }
}

/* $J items: 0..3 SPINE P<i> (Bezier), 4 SPINE LINE|ARC|HELIX, 5 SPINEDIR (not 1 0 0),
 * 6 SPINEREF (not 0 0 0). */
int job_spine_dump(const struct job *j, unsigned i, struct job_args *a)
{
    /* SPINEDIR's and SPINEREF's defaults (not dumped) */
    static const cp_real dflt[2][3] = {{CP_R(1.0), CP_R(0.0), CP_R(0.0)},
                                       {CP_R(0.0), CP_R(0.0), CP_R(0.0)}};
    const struct spine_cfg *c = &j->geom.spine;
    const cp_real *v, *d;
    if (i > 6u) {
        return JOB_DUMP_END;
    }
    if (i < 4u) {
        job_dump_args(a, SPINE_CMD_SPINE, (enum job_word)(JOB_WORD_SPINE_P0 + i));
        job_dump_numbers(a, &c->sp[3u * i]); /* P<i>: its 3 coordinates */
        return c->kind == SPINE_BEZIER && (c->set & (1u << i)) != 0u ? JOB_DUMP_LINE
                                                                     : JOB_DUMP_SKIP;
    }
    if (i == 4u) {
        if (c->kind == SPINE_BEZIER || (c->set & SET_SPINE) == 0u) {
            return JOB_DUMP_SKIP;
        }
        job_dump_word(a, SPINE_CMD_SPINE, c->kind);
        job_dump_numbers(a, c->sp);
        if (c->kind == SPINE_ARC) {
            a->v[7] = c->sp[10];
            a->scale[7] = JOB_SCALE_DEG;
        }
        return JOB_DUMP_LINE;
    }
    job_dump_args(a, i == 5u ? SPINE_CMD_SPINEDIR : SPINE_CMD_SPINEREF, JOB_NO_WORD);
    a->na = 3u;
    v = i == 5u ? c->dir : c->ref;
    d = dflt[i - 5u];
    job_dump_numbers(a, v);
    return v[0] == d[0] && v[1] == d[1] && v[2] == d[2] ? JOB_DUMP_SKIP : JOB_DUMP_LINE;
}

#else
/* SURFACE SPINE not compiled in: the hooks models.def declares, never called (PATH_IF). */
void job_spine_defaults(union path_geom *g)
{
    (void)g;
}
int job_spine_ready(const struct job *j)
{
    (void)j;
    return 0;
}
int job_spine_command(struct job *j, struct job_args *a)
{
    (void)j;
    (void)a;
    return CP_ST_UNKNOWN_CMD;
}
int job_spine_dump(const struct job *j, unsigned i, struct job_args *a)
{
    (void)j;
    (void)i;
    (void)a;
    return JOB_DUMP_END;
}
void job_spine_fill(struct spine_cfg *c)
{
    (void)c;
}
#endif /* CP_WITH_SPINE */
