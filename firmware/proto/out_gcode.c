/* out_gcode.c - the G-code output format (out_gcode.h).
 * SPDX-License-Identifier: MIT
 */
#include "out_gcode.h"
#include "fmt.h"

/* The longest line: "N<10 digits> " (12), "G1" (2), " X", " Y", " Z" each with an int32
 * count written with its sign and point (2 + 12), TOOLAXIS IJK's " I", " J", " K" with
 * 4 decimals of a unit vector (2 + 7), " F" and a feed by fmt_real (at most 1 +
 * PARSE_MAX_DIGITS + 6 = 24 here), "*<3 digits>" (4), '\n': 113 bytes (TOOLAXIS AC's
 * " A<180.000>" and " C<-180.000>" are 19 < 27). The appends are bounded by pend[] anyway.
 * A grbl line (no N, '*' or 5-axis words) is at most 70: under grbl's 79, a Marlin line
 * (N and '*') 86: under its 95 (machines.def LINE_MAX). */
CP_STATIC_ASSERT(12 + 2 + 3 * (2 + 12) + 3 * (2 + 7) + 2 + 24 + 4 + 1 <= OUT_GCODE_LINE_MAX,
                 gcode_line_fits);
CP_STATIC_ASSERT(2 + 3 * (2 + 12) + 2 + 24 <= 79, gcode_line_fits_grbl);
CP_STATIC_ASSERT(12 + 2 + 3 * (2 + 12) + 2 + 24 + 4 <= 95, gcode_line_fits_marlin);

/* The stream line of each item (out_gcode_item), checksums and numbers aside. */
static const char *const item_text[] = {
    [OUT_GCODE_M110] = "M110 N0",      [OUT_GCODE_MODES] = "G21 G90 G17 G94 ",
    [OUT_GCODE_G21] = "G21",           [OUT_GCODE_G90] = "G90",
    [OUT_GCODE_WCS] = "",              [OUT_GCODE_SPINDLE_ON] = "M3 S",
    [OUT_GCODE_SAFE] = "G0",           [OUT_GCODE_ABOVE] = "G0",
    [OUT_GCODE_SPINDLE_OFF] = "M5",    [OUT_GCODE_END] = "",
};

/* G54 .. G59 */
static const char *const wcs_text[6] = {"G54", "G55", "G56", "G57", "G58", "G59"};

/* Append a word and its number v with 4 decimals (" X": a coordinate in mm, 0.1 um;
 * " I": a component of a unit vector) or 3 (" A": an angle in degrees). */
static void put_word(char *out, size_t cap, size_t *pos, const char *word, cp_real v,
                     unsigned decimals)
{
    (void)fmt_str(out, cap, pos, word);
    (void)fmt_fixed(out, cap, pos,
                    out_quantize(v, decimals == 3u ? CP_R(1000.0) : CP_R(10000.0)), decimals);
}

/* Append a field of the [RUN:...] line: its key (",n=") and value. */
static void put_field(char *out, size_t cap, size_t *pos, const char *key, uint32_t v)
{
    (void)fmt_str(out, cap, pos, key);
    (void)fmt_u32(out, cap, pos, v);
}

/* The feed of point k of a run that starts at start_k: the plunge's for the first, the
 * link feed on a link point, else the cut's. (Not inlined: put_point asks for k and for
 * k - 1, and LTO had written it out twice there.) */
static CP_NOINLINE cp_real feed_of(const struct job *job, const struct path *path, uint32_t start_k,
                       uint32_t k)
{
    struct raster_at at;
    if (k == start_k) {
        return job->feed[1];
    }
    raster_locate(k, path->info.steps, path->info.link, &at);
    return at.line < 0 ? job->feed[2] : job->feed[0];
}

/* The travel direction at point k (position p): the chord from point k - 1, or to point
 * 1 at the path's first point (both placed; the last point written is remembered, so a
 * neighbour is computed again only after a seek: a resend, RESUME, the run's first line).
 * The iterator is left anywhere: the caller's next out_point seeks. */
static int travel(struct out_gcode *g, const struct out_run *run, struct path *path, uint32_t k,
                  const struct cp_vec3 *p, struct cp_vec3 *d)
{
    struct raster_pt q;
    int e;
    if (k > 0u && g->prev_ok && g->prev_k == k - 1u) {
        cp_v3_sub(p, &g->prev_p, d);
        return CP_OK;
    }
    if (k == 0u && path_count(path) < 2u) {
        d->x = d->y = d->z = CP_R(0.0); /* one point: no travel, the axis is the normal */
        return CP_OK;
    }
    e = out_point(path, &run->place, k > 0u ? k - 1u : 1u, &q);
    if (e != CP_OK) {
        return e;
    }
    if (k > 0u) {
        cp_v3_sub(p, &q.p, d);
    } else {
        cp_v3_sub(&q.p, p, d);
    }
    return CP_OK;
}

/* Append TOOLAXIS's words of the point: " A.. C.." or " I.. J.. K..". */
static int put_axis(struct out_gcode *g, const struct out_run *run, struct path *path,
                    const struct job *job, uint32_t k, const struct raster_pt *pt, char *out,
                    size_t cap, size_t *pos)
{
    struct cp_vec3 d, a;
    cp_real A, C;
    int e = travel(g, run, path, k, &pt->p, &d);
    if (e != CP_OK) {
        return e;
    }
    toolaxis_of(&g->axis, &pt->n, &d, &a);
    if (job->toolaxis == JOB_TOOLAXIS_AC) {
        toolaxis_ac(&a, &A, &C);
        put_word(out, cap, pos, " A", A, 3u);
        put_word(out, cap, pos, " C", C, 3u);
        return CP_OK;
    }
    put_word(out, cap, pos, " I", a.x, 4u);
    put_word(out, cap, pos, " J", a.y, 4u);
    put_word(out, cap, pos, " K", a.z, 4u);
    return CP_OK;
}

/* Append point k's line: "G1 X.. Y.. Z..", the tool axis with TOOLAXIS, and " F<feed>"
 * where the feed changes (modal F: the machine keeps the previous line's). Returns CP_OK
 * or the point's error. */
static int put_point(struct out_gcode *g, char *out, size_t cap, size_t *pos,
                     const struct out_run *run, struct path *path, const struct job *job,
                     uint32_t k)
{
    struct raster_pt pt;
    cp_real f = feed_of(job, path, run->start_k, k);
    int e = out_point(path, &run->place, k, &pt);
    if (e != CP_OK) {
        return e;
    }
    if (!(pt.p.z < job->safe)) { /* the rapids at SAFE would cross the part: stop before */
        g->above_safe = 1u;
        return CP_ERR_RANGE;
    }
    put_word(out, cap, pos, "G1 X", pt.p.x, 4u);
    put_word(out, cap, pos, " Y", pt.p.y, 4u);
    put_word(out, cap, pos, " Z", pt.p.z, 4u);
    if (job->toolaxis != JOB_TOOLAXIS_OFF) {
        e = put_axis(g, run, path, job, k, &pt, out, cap, pos);
        if (e != CP_OK) {
            return e;
        }
        g->prev_ok = 1u;
        g->prev_k = k;
        g->prev_p = pt.p;
    }
    if (k == run->start_k || f != feed_of(job, path, run->start_k, k - 1u)) {
        (void)fmt_str(out, cap, pos, " F");
        (void)fmt_real(out, cap, pos, f, CP_R(1.0));
    }
    return CP_OK;
}

/* Append the item's line. ABOVE fetches the run's first point (for its X and Y). */
static int put_item(char *out, size_t cap, size_t *pos, const struct out_run *run,
                    struct path *path, const struct job *job, enum out_gcode_item it)
{
    struct raster_pt pt;
    int e;
    (void)fmt_str(out, cap, pos, item_text[it]);
    switch (it) {
    case OUT_GCODE_MODES:
    case OUT_GCODE_WCS:
        (void)fmt_str(out, cap, pos, wcs_text[job->wcs < 6u ? job->wcs : 0u]);
        break;
    case OUT_GCODE_SPINDLE_ON:
        (void)fmt_real(out, cap, pos, job->spindle, CP_R(1.0));
        break;
    case OUT_GCODE_SAFE:
        put_word(out, cap, pos, " Z", job->safe, 4u);
        break;
    case OUT_GCODE_ABOVE:
        e = out_point(path, &run->place, run->start_k, &pt);
        if (e != CP_OK) {
            return e;
        }
        put_word(out, cap, pos, " X", pt.p.x, 4u);
        put_word(out, cap, pos, " Y", pt.p.y, 4u);
        break;
    case OUT_GCODE_END:
        (void)fmt_str(out, cap, pos, machine_dialect(job->machine)->end);
        break;
    default: /* the text alone */
        break;
    }
    return CP_OK;
}

/* Build stream line idx into g->pend; returns its length, or < 0 (the point's error). */
static int build_line(struct out_gcode *g, const struct out_run *run, struct path *path,
                      const struct job *job, uint32_t idx)
{
    char *out = g->pend;
    const size_t cap = sizeof g->pend - 6u; /* room for "*<cs>\n" */
    size_t pos = 0;
    int e;
    if (job->checksum) {
        (void)fmt_str(out, cap, &pos, "N");
        (void)fmt_u32(out, cap, &pos, idx);
        (void)fmt_str(out, cap, &pos, " ");
    }
    if (idx < run->lead) {
        e = put_item(out, cap, &pos, run, path, job, (enum out_gcode_item)g->lead[idx]);
    } else if (idx - run->lead < g->points) {
        e = put_point(g, out, cap, &pos, run, path, job, run->start_k + (idx - run->lead));
    } else {
        e = put_item(out, cap, &pos, run, path, job,
                     (enum out_gcode_item)g->trail[idx - run->lead - g->points]);
    }
    if (e != CP_OK) {
        return e;
    }
    if (job->checksum) {
        uint8_t cs = 0;
        size_t i;
        for (i = 0; i < pos; i++) {
            cs ^= (uint8_t)out[i];
        }
        out[pos++] = '*';
        (void)fmt_u32(out, sizeof g->pend, &pos, cs);
    }
    out[pos++] = '\n';
    return (int)pos;
}

int out_gcode_check(const struct job *job)
{
    const struct machine_dialect *d = machine_dialect(job->machine);
    if (!(job->feed[0] > CP_R(0.0))) {
        return CP_ST_NO_FEED;
    }
    if (!job->safe_set) {
        return CP_ST_NO_SAFE;
    }
    if ((job->checksum && !d->checksum) || (job->toolaxis == JOB_TOOLAXIS_AC && !d->ac) ||
        (job->toolaxis == JOB_TOOLAXIS_IJK && !d->ijk)) {
        return CP_ST_DIALECT;
    }
    return CP_ST_OK;
}

/* The lines around the points for the job's dialect (out_gcode.h). */
static void plan_program(struct out_gcode *g, struct out_run *run, const struct job *job)
{
    const struct machine_dialect *d = machine_dialect(job->machine);
    uint8_t n = 0;
    if (job->checksum) { /* a Marlin-style machine numbers this run's lines from N1 */
        g->lead[n++] = OUT_GCODE_M110;
    }
    if (d->split) {
        g->lead[n++] = OUT_GCODE_G21;
        g->lead[n++] = OUT_GCODE_G90;
        if (job->wcs != 0u) {
            g->lead[n++] = OUT_GCODE_WCS;
        }
    } else {
        g->lead[n++] = OUT_GCODE_MODES;
    }
    g->lead[n++] = OUT_GCODE_SAFE; /* up first, then the spindle starts */
    if (job->spindle > CP_R(0.0)) {
        g->lead[n++] = OUT_GCODE_SPINDLE_ON;
    }
    g->lead[n++] = OUT_GCODE_ABOVE; /* n <= 8 = OUT_GCODE_LEAD_MAX */
    run->lead = n;
    n = 0;
    g->trail[n++] = OUT_GCODE_SAFE;
    if (job->spindle > CP_R(0.0)) {
        g->trail[n++] = OUT_GCODE_SPINDLE_OFF;
    }
    g->trail[n++] = OUT_GCODE_END;
    g->ntrail = n;
}

size_t out_gcode_start(struct out_gcode *g, struct out_run *run, const struct job *job,
                       const struct path *path, uint8_t *out, size_t cap)
{
    const struct machine_dialect *d = machine_dialect(job->machine);
    char *s = (char *)out;
    size_t pos = 0;
    g->ring_head = 0;
    g->ring_n = 0;
    g->inflight = 0;
    g->resync = 0;
    g->pend_len = 0;
    g->pend_idx = 0;
    g->machine = job->machine;
    g->rxbuf = d->acks ? (job->rxbuf != 0u ? job->rxbuf : d->rxbuf) : 0u;
    g->points = path_count(path) - run->start_k;
    g->t_poll = run->t_last;
    g->prev_ok = 0u;
    g->above_safe = 0u;
    toolaxis_init(&g->axis, job->lead, job->side);
    plan_program(g, run, job);
    run->end = run->lead + g->points + g->ntrail;
    /* what the stream will hold, for hosts and judges */
    put_field(s, cap, &pos, "[RUN:points=", path_count(path));
    put_field(s, cap, &pos, ",first=", run->start_k);
    (void)fmt_str(s, cap, &pos, path->info.mode == RASTER_LINES ? ",mode=LINES" : ",mode=CIRCLES");
    put_field(s, cap, &pos, ",n=", path->info.n);
    put_field(s, cap, &pos, ",steps=", path->info.steps);
    put_field(s, cap, &pos, ",link=", path->info.link);
    if (path->info.overlap) { /* far parts meet, the tool inside: reported, harmless */
        (void)fmt_str(s, cap, &pos, ",overlap=1");
    }
    (void)fmt_str(s, cap, &pos, "]\n");
    return pos;
}

/* Send the line in pend[] if the machine's RX buffer has room for it. Returns its
 * length, or 0. */
static size_t send_pending(struct out_gcode *g, struct out_run *run, uint32_t now, uint8_t *out,
                           size_t cap)
{
    size_t i, n = g->pend_len;
    if ((g->rxbuf != 0u && (uint32_t)g->inflight + (uint32_t)n > g->rxbuf) || n > cap) {
        return 0;
    }
    for (i = 0; i < n; i++) {
        out[i] = (uint8_t)g->pend[i];
    }
    g->pend_len = 0;
    run->next++;
    if (g->rxbuf == 0u) {
        return n; /* no acknowledgements: nothing in flight */
    }
    g->ring[(g->ring_head + g->ring_n) % OUT_GCODE_RING] = (uint8_t)n;
    g->ring_n++;
    g->inflight = (uint16_t)(g->inflight + n);
    if (g->ring_n == 1u) {
        run->t_last = now; /* the answer clock starts with the first line in flight */
        g->t_poll = now;
    }
    return n;
}

int out_gcode_emit(struct out_gcode *g, struct out_run *run, struct path *path,
                   const struct job *job, uint32_t now, int sending, uint8_t *out, size_t cap,
                   size_t *len)
{
    *len = 0;
    if (run->next >= run->end) {
        if (g->ring_n == 0u) {
            return CP_ST_OK; /* every line answered */
        }
    } else if (g->resync) {
        /* after a Resend: the line must be quiet, then start afresh from next */
        if ((uint32_t)(now - run->t_last) >= OUT_GCODE_RESYNC_MS) {
            g->resync = 0;
            g->ring_n = 0;
            g->inflight = 0;
            run->t_last = now;
        }
        return OUT_GOING;
    } else if (sending && g->ring_n < OUT_GCODE_RING) {
        /* the line is built once into pend[] and waits there until the machine's RX
         * buffer has room for it (text replies meanwhile do not disturb it) */
        if (g->pend_len == 0u || g->pend_idx != run->next) {
            int n = build_line(g, run, path, job, run->next);
            if (n < 0) {
                return g->above_safe ? CP_ST_ABOVE_SAFE : CP_ST_NUMERIC;
            }
            g->pend_len = (uint8_t)n;
            g->pend_idx = run->next;
        }
        *len = send_pending(g, run, now, out, cap);
        if (*len > 0u) {
            return OUT_GOING;
        }
    }
    if (g->ring_n > 0u && (uint32_t)(now - run->t_last) > OUT_GCODE_PEER_TIMEOUT_MS) {
        return CP_ST_TIMEOUT;
    }
    return OUT_GOING;
}

int out_gcode_poll_due(struct out_gcode *g, const struct out_run *run, uint32_t now)
{
    if (g->ring_n == 0u || (uint32_t)(now - run->t_last) < OUT_GCODE_POLL_MS ||
        (uint32_t)(now - g->t_poll) < OUT_GCODE_POLL_MS) {
        return 0;
    }
    g->t_poll = now;
    return 1;
}

/* "Resend: n": regenerate from line n once the machine has gone quiet (out_gcode_emit);
 * later requests for lines already in flight are ignored. */
static int take_resend(struct out_gcode *g, struct out_run *run, uint32_t n)
{
    if (g->resync) {
        return OUT_GOING;
    }
    if (n >= run->next) {
        /* a line we never sent: the machine counts differently (no M110, or a garbled
         * request); its oks cannot be trusted - stop */
        return CP_ST_PEER_ERROR;
    }
    run->next = n;
    g->resync = 1;
    g->pend_len = 0;
    return OUT_GOING;
}

int out_gcode_answer(struct out_gcode *g, struct out_run *run, const struct job *job,
                     enum machine_reply kind, uint32_t num, uint32_t now)
{
    switch (kind) {
    case MACHINE_OK:
        run->t_last = now;
        if (!g->resync && g->ring_n > 0u) { /* the oldest line is answered */
            g->inflight = (uint16_t)(g->inflight - g->ring[g->ring_head]);
            g->ring_head = (uint8_t)((g->ring_head + 1u) % OUT_GCODE_RING);
            g->ring_n--;
            run->acked++;
        }
        return OUT_GOING;
    case MACHINE_ALIVE:
        run->t_last = now;
        return OUT_GOING;
    case MACHINE_ERROR:
    case MACHINE_ALARM:
        return CP_ST_PEER_ERROR;
    case MACHINE_RETRY: /* the Resend that follows says from where */
        run->t_last = now;
        return job->checksum ? OUT_GOING : CP_ST_PEER_ERROR;
    case MACHINE_RESEND:
        run->t_last = now;
        return job->checksum ? take_resend(g, run, num) : OUT_GOING;
    case MACHINE_RESET:
        return CP_ST_MACHINE_RESET;
    default: /* MACHINE_OTHER: chatter */
        return OUT_GOING;
    }
}
