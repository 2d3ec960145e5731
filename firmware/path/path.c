/* path.c - dispatch to the model iterators (path.h), one case per row of models.def.
 * SPDX-License-Identifier: MIT
 *
 * Direct calls, no function pointers: the static stack analysis (tools/stack.sh) sees
 * every edge. A model that is not compiled in has no case (PATH_IF): the default answers.
 */
#include "path.h"

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
        p->u.name.head.count = 0;                                                                  \
        return err;                                                                                \
    }                                                                                              \
    p->info.count = name##_path_count(&p->u.name);                                                 \
    p->info.n = p->u.name.head.n;                                                                  \
    p->info.steps = p->u.name.head.steps;                                                          \
    p->info.link = p->u.name.head.link;                                                            \
    p->info.mode = p->u.name.head.mode;                                                            \
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
#define CP_MODEL(NAME, name, WITH, WORD) PATH_IF(WITH, case PATH_##NAME : return p->u.name.head.k;)
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
