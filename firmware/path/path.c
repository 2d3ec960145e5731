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

/* The raster head of the iterator of p->kind (NULL for a kind not compiled in): its
 * shape (the stream header) and its position. */
static const struct raster_head *head_of(const struct path *p)
{
    switch (p->kind) {
#define CP_MODEL(NAME, name, WITH, WORD) PATH_IF(WITH, case PATH_##NAME : return &p->u.name.head;)
#include "models.def"
#undef CP_MODEL
    default:
        return NULL;
    }
}

/* The whole init of a model without a sliced check (on error its count is 0). */
#define PATH_INIT_ROW(name)                                                                        \
    err = name##_path_init(&p->u.name, &geom->name, raster);                                       \
    if (err != CP_OK) {                                                                            \
        p->u.name.head.count = 0;                                                                  \
    }                                                                                              \
    break;

int path_check_begin(struct path *p, struct path_check *c, uint8_t kind,
                     const struct raster_cfg *raster, const union path_geom *geom)
{
    int err;
    p->kind = kind;
    p->info.count = 0;
    p->info.n = 0;
    p->info.steps = 0;
    p->info.link = 0;
    p->info.mode = 0;
    p->info.overlap = 0;
    if (raster == NULL || geom == NULL || !path_has(kind)) {
        return CP_ERR_INVAL;
    }
    if (kind != PATH_CANAL) {
        return PATH_CHECK_MORE; /* its whole init is the first step */
    }
    err = canal_path_check_begin(&p->u.canal, &geom->canal, raster, &c->u.canal);
    return err == CANAL_CHECK_MORE ? PATH_CHECK_MORE : err;
}

int path_check_step(struct path *p, struct path_check *c, const struct raster_cfg *raster,
                    const union path_geom *geom)
{
    const struct raster_head *h;
    int err = CP_ERR_INVAL;
    if (p->kind == PATH_CANAL) { /* the sliced check (canal_path.h) */
        err = canal_path_check_step(&p->u.canal, raster, &c->u.canal);
        if (err == CANAL_CHECK_MORE) {
            return PATH_CHECK_MORE;
        }
    } else { /* the others: the whole init (the canal's row is not taken here) */
        switch (p->kind) {
#define CP_MODEL(NAME, name, WITH, WORD) PATH_IF(WITH, case PATH_##NAME : PATH_INIT_ROW(name))
#include "models.def"
#undef CP_MODEL
        default:
            break;
        }
    }
    if (err != CP_OK) {
        return err;
    }
    h = head_of(p); /* the stream header: the model's raster head (not NULL: path_has) */
    p->info.count = h->count;
    p->info.n = h->n;
    p->info.steps = (uint16_t)h->steps;
    p->info.link = h->link;
    p->info.mode = h->mode;
    p->info.overlap = h->overlap;
    return CP_OK;
}

void path_check_progress(const struct path *p, const struct path_check *c, uint32_t *walk,
                         uint32_t *i, uint32_t *m)
{
    *walk = 0u;
    *i = 0u;
    *m = 0u;
    if (p->kind == PATH_CANAL) {
        *walk = c->u.canal.walk;
        *i = c->u.canal.i;
        *m = c->u.canal.m;
    }
}

int path_init(struct path *p, uint8_t kind, const struct raster_cfg *raster,
              const union path_geom *geom)
{
    struct path_check c;
    uint32_t s;
    int err = path_check_begin(p, &c, kind, raster, geom);
    for (s = 0; s < PATH_CHECK_STEPS_MAX && err == PATH_CHECK_MORE; s++) {
        err = path_check_step(p, &c, raster, geom);
    }
    return err == PATH_CHECK_MORE ? CP_ERR_NUMERIC : err; /* (cannot run out: STEPS_MAX) */
}

uint32_t path_count(const struct path *p)
{
    return p->info.count;
}

uint32_t path_pos(const struct path *p)
{
    const struct raster_head *h = head_of(p);
    return h != NULL ? h->k : 0u;
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
