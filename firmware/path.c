/* path.c - dispatch to the model iterators (path.h), one case per row of models.def.
 * SPDX-License-Identifier: MIT
 *
 * Direct calls, no function pointers: the static stack analysis (tools/stack.sh) sees
 * every edge. A model that is not compiled in has no case (PATH_IF): the default answers.
 */
#include "path.h"

/* ---- The canal row's adapters, until the raster rename (path.h) ----
 * toolpath_* under the models' names, the init with the models' signature (the canal's
 * surface is still raster->surf: its `surf` argument, the union's unused canal member,
 * is ignored). The rename (CANAL_PATH_H defined) switches them off; delete them then. */
#ifndef CANAL_PATH_H
static CP_ALWAYS_INLINE int canal_path_init(struct canal_path *it, const struct canal_cfg *surf,
                                            const struct raster_cfg *raster)
{
    (void)surf;
    return canal_path_init(it, raster);
}
static CP_ALWAYS_INLINE uint32_t canal_path_count(const struct canal_path *it)
{
    return canal_path_count(it);
}
static CP_ALWAYS_INLINE int canal_path_next(struct canal_path *it, struct raster_pt *pt)
{
    return canal_path_next(it, pt);
}
static CP_ALWAYS_INLINE int canal_path_seek(struct canal_path *it, uint32_t k)
{
    return canal_path_seek(it, k);
}
#endif

int path_has(unsigned kind)
{
    switch (kind) {
#define CP_MODEL(NAME, name, WITH, WORD)                                                           \
    case PATH_##NAME:                                                                              \
        return WITH;
#include "models.def"
#undef CP_MODEL
    default:
        return 0;
    }
}

/* The model's init (on error its count is 0), then the stream header. */
#define PATH_INIT_ROW(name)                                                                        \
    err = name##_path_init(&p->u.name, &geom->name, raster);                                       \
    if (err != CP_OK) {                                                                            \
        p->u.name.count = 0;                                                                       \
        return err;                                                                                \
    }                                                                                              \
    p->info.count = name##_path_count(&p->u.name);                                                 \
    p->info.n = p->u.name.n;                                                                       \
    p->info.steps = p->u.name.steps;                                                               \
    p->info.link = p->u.name.link;                                                                 \
    p->info.mode = p->u.name.mode;                                                                 \
    return CP_OK;

int path_init(struct path *p, uint8_t kind, const struct raster_cfg *raster,
              const union path_geom *geom)
{
    int err;
    p->kind = kind;
    p->info.count = 0;
    p->info.n = 0;
    p->info.steps = 0;
    p->info.link = 0;
    p->info.mode = 0;
    if (raster == NULL || geom == NULL) {
        return CP_ERR_INVAL;
    }
    switch (kind) {
#define CP_MODEL(NAME, name, WITH, WORD) PATH_IF(WITH, case PATH_##NAME : PATH_INIT_ROW(name))
#include "models.def"
#undef CP_MODEL
    default:
        return CP_ERR_INVAL;
    }
}

uint32_t path_count(const struct path *p)
{
    return p->info.count;
}

uint32_t path_pos(const struct path *p)
{
    switch (p->kind) {
#define CP_MODEL(NAME, name, WITH, WORD) PATH_IF(WITH, case PATH_##NAME : return p->u.name.k;)
#include "models.def"
#undef CP_MODEL
    default:
        return 0;
    }
}

int path_next(struct path *p, struct raster_pt *pt)
{
    if (p->info.count == 0u) {
        return CP_ERR_DONE;
    }
    switch (p->kind) {
#define CP_MODEL(NAME, name, WITH, WORD)                                                           \
    PATH_IF(WITH, case PATH_##NAME : return name##_path_next(&p->u.name, pt);)
#include "models.def"
#undef CP_MODEL
    default:
        return CP_ERR_DONE;
    }
}

int path_seek(struct path *p, uint32_t k)
{
    if (k > p->info.count) {
        return CP_ERR_RANGE;
    }
    switch (p->kind) {
#define CP_MODEL(NAME, name, WITH, WORD)                                                           \
    PATH_IF(WITH, case PATH_##NAME : return name##_path_seek(&p->u.name, k);)
#include "models.def"
#undef CP_MODEL
    default:
        return CP_ERR_RANGE;
    }
}
