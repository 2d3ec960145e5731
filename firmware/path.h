/* path.h - the toolpath source of a run, whatever the surface model.
 * SPDX-License-Identifier: MIT
 *
 * The stream (proto.c) pulls points from one `struct path`: a tagged union of the
 * models' iterators, each yielding exactly path_count() `struct raster_pt` with
 * the conventions of canal_path.h (zigzag lines, link points, fixed counts decided
 * at init, seek(k) reproducing point k bit for bit). The raster request (mode,
 * n, u0, u1, steps/tol, link, tool, output) is the job's `struct raster_cfg`
 * for every model (raster.h); the model's geometry is its member of `union path_geom`.
 * Every iterator starts with a `struct raster_head head` (mode, n, steps, link, count,
 * k), which the stream header and path_pos read.
 *
 * Models (SURFACE command, docs/PROTOCOL.md):
 *   PATH_CANAL    canal surface touching the floor along a plane curve (seed 000)
 *   PATH_GSR      generalized surface of revolution (seed 003)        [issue 7]
 *   PATH_CHANNEL  channel surface from cross-sections (seed 002)      [issue 5]
 *   PATH_DRC      discretely represented curve, thickened (seed 001)  [issue 6]
 * A kind whose model is not compiled in is refused by SURFACE (error:9).
 *
 * HOW TO ADD A MODEL <m> (kind PATH_<M>):
 *   1. firmware/<m>.h: struct <m>_cfg (geometry, plain data) and an iterator
 *      struct <m>_path with
 *        int      <m>_path_init(struct <m>_path *, const struct <m>_cfg *,
 *                               const struct raster_cfg *raster);
 *        uint32_t <m>_path_count(const struct <m>_path *);
 *        int      <m>_path_next(struct <m>_path *, struct raster_pt *);
 *        int      <m>_path_seek(struct <m>_path *, uint32_t k);
 *      whose first member is `struct raster_head head` (raster.h: mode, n, steps,
 *      link, count, k; <m>_path_seek via raster_seek).
 *   2. here: include <m>.h, add the cfg to union path_geom and the iterator to
 *      struct path's union, and set PATH_HAVE_<M> to 1.
 *   3. path.c: one case in each switch (init, count, next, seek, info).
 *   4. firmware/job_<m>.c: int job_<m>_command(struct job *, struct job_args *)
 *      (job.h) and a defaults function; in job.c its keywords, their words and
 *      number counts in the `words` table (and KW_<M>), one case each in
 *      job_command()'s hook switch and model_defaults(), and need[PATH_<M>] = the
 *      have bits RUN needs (job.h JOB_HAVE_<M>_MASK). Its cp_err codes map to wire
 *      codes (appended to cp_status.def) in job_status_of().
 *   5. docs/PROTOCOL.md: the commands; host_sim: a judge of the model's stream.
 */
#ifndef PATH_H
#define PATH_H

#include "raster.h"
#include "canal_path.h"
#include "channel.h"
#include "gsr.h"
#include "drc.h"

enum path_kind {
    PATH_CANAL = 0,
    PATH_GSR = 1,
    PATH_CHANNEL = 2,
    PATH_DRC = 3,
    PATH_KINDS = 4
};

/* 1 when the model is compiled in (SURFACE accepts it): cp_config.h CP_WITH_<M>.
 * The types stay declared either way (struct layouts do not depend on the choice);
 * only path.c and job.c stop referring to the model, so --gc-sections drops its code. */
#define PATH_HAVE_GSR CP_WITH_GSR
#define PATH_HAVE_CHANNEL CP_WITH_CHANNEL
#define PATH_HAVE_DRC CP_WITH_DRC

/* Geometry of the models (the one of the path's kind). */
union path_geom {
    struct canal_cfg canal;
    struct channel_cfg channel;
    struct gsr_cfg gsr;
    struct drc_cfg drc;
};

/* What the stream header tells the host (BEGIN frame, [RUN:...] line). */
struct path_info {
    uint32_t count; /* points of the whole path */
    uint16_t n;     /* lines or circles/rings */
    uint16_t steps; /* steps per line (points per line = steps + 1) */
    uint16_t link;  /* link points between consecutive lines */
    uint8_t mode;   /* enum raster_mode: 0 lines, 1 circles/rings */
};

struct path {
    /* the iterator first, at offset 0 (its hot fields stay at Thumb's short load/store
     * offsets when reached through the path), then the header */
    union {
        struct canal_path canal;
        struct channel_path channel;
        struct gsr_path gsr;
        struct drc_path drc;
    } u;
    uint8_t kind;          /* enum path_kind of the initialised iterator */
    struct path_info info; /* valid after a successful path_init */
};

/* Initialise the iterator of model `kind` on the raster in `raster` and the geometry
 * geom->(the model's member).
 * Errors: CP_ERR_INVAL for a kind that is not compiled in, else the model's init
 * codes (canal_path_init for the canal). On error p->info.count is 0. */
CP_MUST_CHECK int path_init(struct path *p, uint8_t kind, const struct raster_cfg *raster,
                            const union path_geom *geom);

/* Total number of points (0 before a successful init). */
uint32_t path_count(const struct path *p);

/* Points emitted so far (the k of the next path_next). */
uint32_t path_pos(const struct path *p);

/* The next point. Returns CP_OK, or CP_ERR_DONE after path_count() points. */
int path_next(struct path *p, struct raster_pt *pt);

/* Restart at point k (0 <= k <= count): the next path_next yields exactly what it
 * yielded the first time at k. Returns CP_OK or CP_ERR_RANGE. */
CP_MUST_CHECK int path_seek(struct path *p, uint32_t k);

#endif /* PATH_H */
