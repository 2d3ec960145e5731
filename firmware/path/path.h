/* path.h - the toolpath source of a run, whatever the surface model.
 * SPDX-License-Identifier: MIT
 *
 * The stream (proto.c) pulls points from one `struct path`: a tagged union of the
 * models' iterators, each yielding exactly path_count() `struct raster_pt` with the
 * conventions of raster.h (zigzag lines, link points, fixed counts decided at init,
 * seek(k) reproducing point k bit for bit). The raster request (mode, n, u0, u1,
 * steps/tol, link, tool, output) is the job's `struct raster_cfg` for every model; each
 * model's geometry is its member of `union path_geom` (the canal's too: job_geom_fill
 * puts it there at RUN).
 *
 * Models: firmware/models/models.def, one row each (the SURFACE word, the module prefix,
 * the compile-time switch). From it come enum path_kind, the iterator union of struct
 * path, the dispatch of path.c, the job's per-model hooks (job.c) and the $I model list:
 *   PATH_CANAL    canal surface touching the floor along a plane curve (seed 000)
 *   PATH_GSR      generalized surface of revolution (seed 003)
 *   PATH_CHANNEL  channel surface from cross-sections (seed 002)
 *   PATH_DRC      discretely represented curve, thickened (seed 001)
 *   PATH_PLANE    the example model, a flat strip (test builds only)
 * A kind whose model is not compiled in is refused by SURFACE (error:9).
 * Adding a model: docs/ARCHITECTURE.md (its header's #include goes below).
 */
#ifndef PATH_H
#define PATH_H

#include "canal_path.h"
#include "channel.h"
#include "gsr.h"
#include "drc.h"
#include "plane.h"
#include "spine.h"

/* PATH_IF(WITH, tokens): the tokens when WITH (models.def's column: the literal 0 or 1,
 * cp_config.h checks) is 1, nothing when it is 0. The rows of a model that is not
 * compiled in thus vanish: no call, no stack edge, its code dropped by --gc-sections. */
#define PATH_IF(with, ...) PATH_IF_(with, __VA_ARGS__)
#define PATH_IF_(with, ...) PATH_IF_##with(__VA_ARGS__)
#define PATH_IF_0(...)
#define PATH_IF_1(...) __VA_ARGS__

enum path_kind {
#define CP_MODEL(NAME, name, WITH, WORD) PATH_##NAME,
#include "models.def"
#undef CP_MODEL
    PATH_KINDS
};

/* The geometry of the model of `kind` (the job's SURFACE): member <name> of models.def. */
union path_geom {
#define CP_MODEL(NAME, name, WITH, WORD) struct name##_cfg name;
#include "models.def"
#undef CP_MODEL
};

/* What the stream header tells the host (BEGIN frame, [RUN:...] line). */
struct path_info {
    uint32_t count; /* points of the whole path */
    uint16_t n;     /* lines or circles/rings */
    uint16_t steps; /* steps per line (points per line = steps + 1) */
    uint16_t link;  /* link points between consecutive lines */
    uint8_t mode;   /* enum raster_mode: 0 lines, 1 circles/rings */
    uint8_t overlap; /* raster_head.overlap: 1 = far parts of the sweep meet, the tool inside
                        (reported, harmless: raster.h raster_overlap_report) */
};

struct path {
    /* the model's iterator (the one of `kind`), then the stream header */
    union {
#define CP_MODEL(NAME, name, WITH, WORD) struct name##_path name;
#include "models.def"
#undef CP_MODEL
    } u;
    uint8_t kind;          /* enum path_kind of the initialised iterator */
    struct path_info info; /* valid after a successful path_init */
};

/* Initialise the iterator of model `kind` on the raster `raster` and the model's
 * geometry, member <name> of `geom` (the job's union): the whole check at once.
 * Errors: CP_ERR_INVAL for a kind that is not compiled in, or raster or geom NULL, else
 * the model's init codes (canal_path_init for the canal). On error p->info.count is 0. */
CP_MUST_CHECK int path_init(struct path *p, uint8_t kind, const struct raster_cfg *raster,
                            const union path_geom *geom);

/* ---- the check in slices (issue 22: a controller that always answers) ----
 *
 * path_init is path_check_begin, then path_check_step until it stops answering
 * PATH_CHECK_MORE (at most PATH_CHECK_STEPS_MAX steps): RUN's validation of the job, cut
 * into slices so that proto.c reads its link between them ('?' answers "<Check|...>",
 * Ctrl-X cancels). The canal's check runs in slices of at most CANAL_CHECK_WORK units
 * (canal_path.h; the worst slice on the M4F: `make pollgap`). The other models have no
 * sliced check yet: their whole init is one step (they answer nothing while it runs). */
#define PATH_CHECK_MORE 1
#define PATH_CHECK_STEPS_MAX CANAL_CHECK_STEPS_MAX

struct path_check {
    union {
        struct canal_check canal; /* PATH_CANAL */
    } u;
};

/* Begin the check of model `kind` on raster and geom (path_init's arguments; both must stay
 * unchanged until the check ends). Returns PATH_CHECK_MORE or path_init's codes. */
CP_MUST_CHECK int path_check_begin(struct path *p, struct path_check *c, uint8_t kind,
                                   const struct raster_cfg *raster, const union path_geom *geom);

/* One slice of the check. Returns PATH_CHECK_MORE, CP_OK (p streams: path_count() points,
 * the stream header in p->info) or path_init's codes (p->info.count is 0). */
CP_MUST_CHECK int path_check_step(struct path *p, struct path_check *c,
                                  const struct raster_cfg *raster, const union path_geom *geom);

/* The check's progress for a status report: walks of the patch begun (1, 2, ...; 0 for a
 * model checked in one step), the next unit of the current walk or phase and its units. */
void path_check_progress(const struct path *p, const struct path_check *c, uint32_t *walk,
                         uint32_t *i, uint32_t *m);

/* 1 when model `kind` (enum path_kind) is compiled in (models.def WITH), else 0. */
int path_has(unsigned kind);

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
