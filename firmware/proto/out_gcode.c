/* out_gcode.c - the G-code output format (out_gcode.h).
 * SPDX-License-Identifier: MIT
 */
#include "out_gcode.h"
#include "fmt.h"
#include "parse.h"

/* The longest line: "N<10 digits> " (12), "G1 X" and " Y", " Z", " F" each with an int32
 * count written with its sign and point (12 bytes), "*<3 digits>" (4), '\n': 75 bytes.
 * The appends below are bounded by pend[] anyway; the single bytes are stored directly. */
CP_STATIC_ASSERT(12 + 4 + 12 + 3 * (2 + 12) + 4 + 1 <= OUT_GCODE_LINE_MAX, gcode_line_fits);

/* Append "G1 X.. Y.. Z.." (4 decimals) and " F.." (1 decimal) unless the feed is 0. */
static void put_g1(char *out, size_t cap, size_t *pos, const struct raster_pt *pt,
                   cp_real feed)
{
    (void)fmt_str(out, cap, pos, "G1 X");
    (void)fmt_fixed(out, cap, pos, out_quantize(pt->p.x, CP_R(10000.0)), 4u);
    (void)fmt_str(out, cap, pos, " Y");
    (void)fmt_fixed(out, cap, pos, out_quantize(pt->p.y, CP_R(10000.0)), 4u);
    (void)fmt_str(out, cap, pos, " Z");
    (void)fmt_fixed(out, cap, pos, out_quantize(pt->p.z, CP_R(10000.0)), 4u);
    if (feed > CP_R(0.0)) {
        (void)fmt_str(out, cap, pos, " F");
        (void)fmt_fixed(out, cap, pos, out_quantize(feed, CP_R(10.0)), 1u);
    }
}

/* Build stream line idx into g->pend; returns its length, or < 0 (the point's error).
 * Lines 0..lead-1 are the header, then one G1 per point from run->start_k. */
static int build_line(struct out_gcode *g, const struct out_run *run, struct path *path,
                      const struct job *job, uint32_t idx)
{
    char *out = g->pend;
    const size_t cap = sizeof g->pend;
    size_t pos = 0;
    if (job->checksum) {
        out[pos++] = 'N';
        (void)fmt_u32(out, cap, &pos, idx);
        out[pos++] = ' ';
    }
    /* the header's lines are the last `lead` lines before the points: the modes line
     * last, the line-number reset (checksums only) before it */
    if (idx < run->lead && run->lead - idx == 2u) { /* checksums: number this run from N1 */
        (void)fmt_str(out, cap, &pos, "M110 N0");
    } else if (idx < run->lead) { /* the modes line, just before the first point */
        (void)fmt_str(out, cap, &pos, "G21 G90 G17");
    } else {
        struct raster_pt pt;
        int e = out_point(path, &run->place, run->start_k + (idx - run->lead), &pt);
        if (e != CP_OK) {
            return e;
        }
        put_g1(out, cap, &pos, &pt, job->feed);
    }
    if (job->checksum) {
        uint8_t cs = 0;
        size_t i;
        for (i = 0; i < pos; i++) {
            cs ^= (uint8_t)out[i];
        }
        out[pos++] = '*';
        (void)fmt_u32(out, cap, &pos, cs);
    }
    out[pos++] = '\n';
    return (int)pos;
}

size_t out_gcode_start(struct out_gcode *g, struct out_run *run, const struct job *job,
                       const struct path *path, uint8_t *out, size_t cap)
{
    char *s = (char *)out;
    size_t pos = 0;
    g->ring_head = 0;
    g->ring_n = 0;
    g->inflight = 0;
    g->resync = 0;
    g->pend_len = 0;
    g->pend_idx = 0;
    /* "M110 N0" first with checksums, so that a Marlin-style machine numbers this run's
     * lines from N1 whatever it saw before */
    run->lead = (uint8_t)(job->checksum ? 2u : 1u);
    run->end = path_count(path) - run->start_k + run->lead;
    /* what the stream will hold, for hosts and judges */
    (void)fmt_str(s, cap, &pos, "[RUN:points=");
    (void)fmt_u32(s, cap, &pos, path_count(path));
    (void)fmt_str(s, cap, &pos, ",first=");
    (void)fmt_u32(s, cap, &pos, run->start_k);
    (void)fmt_str(s, cap, &pos, path->info.mode == RASTER_LINES ? ",mode=LINES" : ",mode=CIRCLES");
    (void)fmt_str(s, cap, &pos, ",n=");
    (void)fmt_u32(s, cap, &pos, path->info.n);
    (void)fmt_str(s, cap, &pos, ",steps=");
    (void)fmt_u32(s, cap, &pos, path->info.steps);
    (void)fmt_str(s, cap, &pos, ",link=");
    (void)fmt_u32(s, cap, &pos, path->info.link);
    (void)fmt_str(s, cap, &pos, "]\n");
    return pos;
}

/* Send the line in pend[] if the machine's RX buffer has room for it. Returns its
 * length, or 0. */
static size_t send_pending(struct out_gcode *g, struct out_run *run, const struct job *job,
                           uint32_t now, uint8_t *out, size_t cap)
{
    size_t i, n = g->pend_len;
    if ((uint32_t)g->inflight + (uint32_t)n > job->rxbuf || n > cap) {
        return 0;
    }
    for (i = 0; i < n; i++) {
        out[i] = (uint8_t)g->pend[i];
    }
    g->pend_len = 0;
    g->ring[(g->ring_head + g->ring_n) % OUT_GCODE_RING] = (uint8_t)n;
    g->ring_n++;
    g->inflight = (uint16_t)(g->inflight + n);
    if (g->ring_n == 1u) {
        run->t_last = now; /* the answer clock starts with the first line in flight */
    }
    run->next++;
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
                return CP_ST_NUMERIC;
            }
            g->pend_len = (uint8_t)n;
            g->pend_idx = run->next;
        }
        *len = send_pending(g, run, job, now, out, cap);
        if (*len > 0u) {
            return OUT_GOING;
        }
    }
    if (g->ring_n > 0u && (uint32_t)(now - run->t_last) > OUT_GCODE_PEER_TIMEOUT_MS) {
        return CP_ST_TIMEOUT;
    }
    return OUT_GOING;
}

/* The prefixes of enum out_gcode_answer, tried in its order. */
static const char *const answer_prefix[OUT_GCODE_NOT_ANSWER] = {
    [OUT_GCODE_OK] = "ok",          [OUT_GCODE_ERROR] = "error:", [OUT_GCODE_ALARM] = "ALARM:",
    [OUT_GCODE_MARLIN_ERR] = "Error:", [OUT_GCODE_RS] = "rs ",    [OUT_GCODE_RESEND] = "Resend:",
};

enum out_gcode_answer out_gcode_answer_kind(const char *line, size_t len, size_t *arg)
{
    unsigned k;
    for (k = 0; k < OUT_GCODE_NOT_ANSWER; k++) {
        const char *w = answer_prefix[k];
        size_t a = 0;
        while (a < len && w[a] != '\0' && line[a] == w[a]) { /* a < len bounds it */
            a++;
        }
        if (w[a] == '\0' && (k != OUT_GCODE_OK || len == 2u)) { /* "ok" is the whole line */
            *arg = a;
            return (enum out_gcode_answer)k;
        }
    }
    *arg = 0;
    return OUT_GCODE_NOT_ANSWER;
}

/* "Resend: n": regenerate from line n once the machine has gone quiet (out_gcode_emit);
 * later requests for lines already in flight are ignored. */
static int take_resend(struct out_gcode *g, struct out_run *run, const char *arg,
                       size_t arg_len)
{
    uint32_t n;
    size_t a = 0;
    while (a < arg_len && arg[a] == ' ') {
        a++;
    }
    if (g->resync) {
        return OUT_GOING;
    }
    if (parse_uint(arg + a, arg_len - a, UINT32_MAX, &n) != CP_ST_OK || n >= run->next) {
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
                     enum out_gcode_answer kind, const char *arg, size_t arg_len, uint32_t now)
{
    run->t_last = now;
    switch (kind) {
    case OUT_GCODE_OK:
        if (!g->resync && g->ring_n > 0u) { /* the oldest line is answered */
            g->inflight = (uint16_t)(g->inflight - g->ring[g->ring_head]);
            g->ring_head = (uint8_t)((g->ring_head + 1u) % OUT_GCODE_RING);
            g->ring_n--;
            run->acked++;
        }
        return OUT_GOING;
    case OUT_GCODE_ERROR:
    case OUT_GCODE_MARLIN_ERR:
        /* with checksums a machine error precedes its Resend: request */
        return job->checksum ? OUT_GOING : CP_ST_PEER_ERROR;
    case OUT_GCODE_ALARM:
        return CP_ST_PEER_ERROR;
    case OUT_GCODE_RS:
    case OUT_GCODE_RESEND:
        return job->checksum ? take_resend(g, run, arg, arg_len) : OUT_GOING;
    default:
        return OUT_GOING;
    }
}
