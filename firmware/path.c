/* path.c - dispatch to the model iterators (path.h).
 * SPDX-License-Identifier: MIT
 */
#include "path.h"

int path_init(struct path *p, uint8_t kind, const struct toolpath_cfg *raster,
              const union path_geom *geom)
{
    int err;
    (void)geom;
    p->kind = kind;
    p->info.count = 0;
    p->info.n = 0;
    p->info.steps = 0;
    p->info.link = 0;
    p->info.mode = 0;
    if (raster == NULL) {
        return CP_ERR_INVAL;
    }
    switch (kind) {
    case PATH_CANAL:
        err = toolpath_init(&p->u.canal, raster);
        if (err != CP_OK) {
            p->u.canal.count = 0;
            return err;
        }
        p->info.count = toolpath_count(&p->u.canal);
        p->info.n = p->u.canal.n;
        p->info.steps = p->u.canal.steps;
        p->info.link = p->u.canal.link;
        p->info.mode = p->u.canal.mode;
        return CP_OK;
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
    case PATH_CANAL:
        return p->u.canal.k;
    default:
        return 0;
    }
}

int path_next(struct path *p, struct toolpath_pt *pt)
{
    if (p->info.count == 0u) {
        return CP_ERR_DONE;
    }
    switch (p->kind) {
    case PATH_CANAL:
        return toolpath_next(&p->u.canal, pt);
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
    case PATH_CANAL:
        return toolpath_seek(&p->u.canal, k);
    default:
        return CP_ERR_RANGE;
    }
}
