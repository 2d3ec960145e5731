/* out.h - what the output formats share: the state of a run that the protocol engine
 * keeps for every format, the result convention of their steps, and the point fetch
 * and quantisation of the stream.
 * SPDX-License-Identifier: MIT
 *
 * An output format is one module firmware/proto/out_<name>.[ch] (prefix out_<name>_): its
 * state during a run (struct out_<name>, a member of the union `out` in struct proto),
 * and the calls proto.c makes directly at its seams - start a run, emit the next
 * stream item, take what the peer sends, finish the run (see out_gcode.h, out_frames.h).
 *
 * Adding an output format (a machine dialect, a 5-axis form):
 *   1. firmware/proto/out_<name>.[ch]: struct out_<name> and its calls, in the shape of
 *      out_gcode.h (text answers from a machine) or out_frames.h (bytes from a host),
 *      and its include in proto.h;
 *   2. one row in firmware/job/outputs.def: enum job_format's JOB_<NAME>, its FORMAT
 *      word and its member of proto.h's union `out` follow from it;
 *   3. one case in each switch on (enum job_format) in proto.c - run_start, run_emit,
 *      run_finish, host_answer, feed; -Wswitch (-Wall -Werror) names every switch
 *      that still lacks it.
 * The modules never read the clock or touch the UART: the engine reads the time where
 * a module needs it (exactly where it always did: the in-memory HAL's clock of the
 * tests advances on every read) and passes it in ms, with a buffer to append stream
 * bytes to.
 */
#ifndef OUT_H
#define OUT_H

#include "cp_status.h"
#include "cp_types.h"
#include "path.h"
#include "place.h"

/* The result of an output module's step while the run goes on; any other result is
 * the CP_ST_* status the engine ends the run with (CP_ST_OK: the stream is complete). */
#define OUT_GOING (-1)

/* A run as both sides count it. A stream is `end` items numbered from 0: `lead` items
 * before the first point (G-code header lines, the BEGIN frame), one per point from
 * start_k to the last point of the path, then the trailing items (the END frame). */
struct out_run {
    uint32_t start_k; /* first point of the run (RESUME k), 0..path_count - 1 */
    uint32_t next;    /* next stream item to send, 0..end */
    uint32_t acked;   /* FRAMES: every item below is acknowledged; GCODE: lines answered ok */
    uint32_t end;     /* stream items of the run */
    uint32_t t_last;  /* ms of the last progress from the peer (ACK, machine answer) */
    uint8_t lead;     /* stream items before the first point: 1 or 2 (G-code), 1 (frames) */
    struct place place; /* PLACE/TILT of the run (place_init at RUN; all 0: none) */
};

/* Position the iterator on point k (seek only if it is elsewhere), fetch it and place it
 * on the part (pl->on: place_apply to p and n; the one place every model's point of every
 * format goes through). Returns CP_OK, CP_ERR_RANGE when k is not a point of the path,
 * or path_next's error. */
int out_point(struct path *path, const struct place *pl, uint32_t k, struct raster_pt *pt);

/* v counted in units of 1/scale, rounded half up: floor(v * scale + 0.5), exact and the
 * same on every target (G-code and frame positions: scale 1e4, 0.1 um; frame normals:
 * 32767; G-code feed: 10). v * scale must lie within int32: not checked here. */
int32_t out_quantize(cp_real v, cp_real scale);

#endif /* OUT_H */
