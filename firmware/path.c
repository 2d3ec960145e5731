/* path.c - dispatch to the model iterators (path.h).
 * SPDX-License-Identifier: MIT
 */
#include "path.h"

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
    /* the model's init (on error its count is 0), then the stream header */
    switch (kind) {
    case PATH_CANAL:
        err = canal_path_init(&p->u.canal, &geom->canal, raster);
        if (err != CP_OK) {
            p->u.canal.head.count = 0;
            return err;
        }
        p->info.count = canal_path_count(&p->u.canal);
        p->info.n = p->u.canal.head.n;
        p->info.steps = p->u.canal.head.steps;
        p->info.link = p->u.canal.head.link;
        p->info.mode = p->u.canal.head.mode;
        return CP_OK;
#if PATH_HAVE_CHANNEL
    case PATH_CHANNEL:
        err = channel_path_init(&p->u.channel, &geom->channel, raster);
        if (err != CP_OK) {
            p->u.channel.head.count = 0;
            return err;
        }
        p->info.count = channel_path_count(&p->u.channel);
        p->info.n = p->u.channel.head.n;
        p->info.steps = p->u.channel.head.steps;
        p->info.link = p->u.channel.head.link;
        p->info.mode = p->u.channel.head.mode;
        return CP_OK;
#endif
#if PATH_HAVE_GSR
    case PATH_GSR:
        err = gsr_path_init(&p->u.gsr, &geom->gsr, raster);
        if (err != CP_OK) {
            return err; /* count is 0 */
        }
        p->info.count = gsr_path_count(&p->u.gsr);
        p->info.n = p->u.gsr.head.n;
        p->info.steps = p->u.gsr.head.steps;
        p->info.link = p->u.gsr.head.link;
        p->info.mode = p->u.gsr.head.mode;
        return CP_OK;
#endif
#if PATH_HAVE_DRC
    case PATH_DRC:
        err = drc_path_init(&p->u.drc, &geom->drc, raster);
        if (err != CP_OK) {
            return err; /* count is 0 */
        }
        p->info.count = drc_path_count(&p->u.drc);
        p->info.n = p->u.drc.head.n;
        p->info.steps = p->u.drc.head.steps;
        p->info.link = p->u.drc.head.link;
        p->info.mode = p->u.drc.head.mode;
        return CP_OK;
#endif
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
        return p->u.canal.head.k;
#if PATH_HAVE_CHANNEL
    case PATH_CHANNEL:
        return p->u.channel.head.k;
#endif
#if PATH_HAVE_GSR
    case PATH_GSR:
        return p->u.gsr.head.k;
#endif
#if PATH_HAVE_DRC
    case PATH_DRC:
        return p->u.drc.head.k;
#endif
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
    case PATH_CANAL:
        return canal_path_next(&p->u.canal, pt);
#if PATH_HAVE_CHANNEL
    case PATH_CHANNEL:
        return channel_path_next(&p->u.channel, pt);
#endif
#if PATH_HAVE_GSR
    case PATH_GSR:
        return gsr_path_next(&p->u.gsr, pt);
#endif
#if PATH_HAVE_DRC
    case PATH_DRC:
        return drc_path_next(&p->u.drc, pt);
#endif
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
        return canal_path_seek(&p->u.canal, k);
#if PATH_HAVE_CHANNEL
    case PATH_CHANNEL:
        return channel_path_seek(&p->u.channel, k);
#endif
#if PATH_HAVE_GSR
    case PATH_GSR:
        return gsr_path_seek(&p->u.gsr, k);
#endif
#if PATH_HAVE_DRC
    case PATH_DRC:
        return drc_path_seek(&p->u.drc, k);
#endif
    default:
        return CP_ERR_RANGE;
    }
}
