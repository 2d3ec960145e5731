/* cp_config.h - every compile-time size and knob of canalpath, with unit and range.
 * SPDX-License-Identifier: MIT
 *
 * Override any knob with -DNAME=value. The #error block at the end rejects
 * combinations that would break a promise (grbl config.h style).
 */
#ifndef CP_CONFIG_H
#define CP_CONFIG_H

/* 0: cp_real is float (default, the M4F image). 1: double (host builds only). */
#ifndef CP_REAL_DOUBLE
#define CP_REAL_DOUBLE 0
#endif

/* Protocol version reported by $I. Integer, bumped on any wire-visible change. */
#define CP_PROTO_VERSION 1
#define CP_FW_VERSION "0.1.0"

/* Longest command line accepted, bytes including the terminator. Integer (16-250).
 * A longer line is discarded up to its newline and answered with error:line-too-long. */
#ifndef CP_LINE_MAX
#define CP_LINE_MAX 96
#endif

/* Transmit staging buffer in the protocol engine, bytes. Integer (64-1024).
 * One reply line must fit; larger values only reduce HAL write calls. */
#ifndef CP_TX_BUF
#define CP_TX_BUF 256
#endif

/* Maximum output steps per curvature line (points per line = steps + 1). Integer (2-65535). */
#ifndef CP_MAX_STEPS
#define CP_MAX_STEPS 4096
#endif

/* Maximum Simpson sub-steps per output step (quadrature of Lambda). Integer (1-64). */
#ifndef CP_MAX_SUBSTEPS
#define CP_MAX_SUBSTEPS 32
#endif

/* Maximum number of curvature lines (family 2) or circles (family 1) in one job. Integer (1-4096).
 */
#ifndef CP_MAX_LINES
#define CP_MAX_LINES 256
#endif

/* Points of one link move along a characteristic circle between two family-2 lines,
 * excluding both ends. Integer (0-64). */
#ifndef CP_MAX_LINK
#define CP_MAX_LINK 64
#endif

/* Byte budget of the complete canal iterator context (struct canal_path), float build
 * (the double build may use twice this). */
#ifndef CP_CANAL_PATH_BUDGET
#define CP_CANAL_PATH_BUDGET 256
#endif

/* DRC model (drc.h): most points of a sketched curve (POINT lines). Integer (3-16).
 * Each point costs 12 B in the job geometry and 12 B (its tangent) in the iterator. */
#ifndef CP_MAX_DRC_POINTS
#define CP_MAX_DRC_POINTS 12
#endif

/* DRC model: most thickening passes K (THICKEN K, or derived from TOL). Integer (1-10).
 * A line has 2^K (points - 1) steps (<= CP_MAX_STEPS); the iterator keeps a stack of K
 * nodes of 24 B (float). */
#ifndef CP_MAX_PASSES
#define CP_MAX_PASSES 7
#endif

/* Channel model (channel.h): most cross-sections (SECTION lines). Integer (2-4).
 * Each section costs 48 B in the job geometry and 80 B of node data in the iterator
 * (float); 4 keeps struct channel_path within its 400 B budget (the example has 3). */
#ifndef CP_MAX_SECTIONS
#define CP_MAX_SECTIONS 4
#endif

/* Surface models compiled into the protocol (SURFACE GSR | CHANNEL | DRC), 0 or 1
 * each; the canal is always in. A model left out costs no flash (its code is never
 * referenced) and SURFACE refuses it with error:9. Host builds take all three. The
 * Cortex-M4F images, one per model set, are the `image` rows of linker/budget.txt (the
 * canal product image, each model with the canal, all features); `make guard-images`
 * holds each to its flash budget with 10 % of it free. */
#ifndef CP_WITH_GSR
#define CP_WITH_GSR 1
#endif
#ifndef CP_WITH_CHANNEL
#define CP_WITH_CHANNEL 1
#endif
#ifndef CP_WITH_DRC
#define CP_WITH_DRC 1
#endif
/* The example model of docs/ARCHITECTURE.md (a flat strip): test builds only.
 * Every CP_WITH_<M> must be a literal 0 or 1 (not 1u): path.h's PATH_IF pastes it into a
 * macro name. */
#ifndef CP_WITH_SPINE
#define CP_WITH_SPINE 1
#endif
#ifndef CP_WITH_PLANE
#define CP_WITH_PLANE 0
#endif

#if CP_LINE_MAX < 16 || CP_LINE_MAX > 250
#error "CP_LINE_MAX must be in 16..250"
#endif
#if CP_TX_BUF < 64 || CP_TX_BUF > 1024
#error "CP_TX_BUF must be in 64..1024"
#endif
#if CP_MAX_STEPS < 2 || CP_MAX_STEPS > 65535
#error "CP_MAX_STEPS must be in 2..65535"
#endif
#if CP_MAX_SUBSTEPS < 1 || CP_MAX_SUBSTEPS > 64
#error "CP_MAX_SUBSTEPS must be in 1..64"
#endif
#if CP_MAX_LINES < 1 || CP_MAX_LINES > 4096
#error "CP_MAX_LINES must be in 1..4096"
#endif
#if CP_MAX_LINK < 0 || CP_MAX_LINK > 64
#error "CP_MAX_LINK must be in 0..64"
#endif
#if CP_MAX_DRC_POINTS < 3 || CP_MAX_DRC_POINTS > 16
#error "CP_MAX_DRC_POINTS must be in 3..16"
#endif
#if CP_MAX_PASSES < 1 || CP_MAX_PASSES > 10
#error "CP_MAX_PASSES must be in 1..10"
#endif
#if ((1 << CP_MAX_PASSES) * (CP_MAX_DRC_POINTS - 1)) > 65535
#error "2^CP_MAX_PASSES (CP_MAX_DRC_POINTS - 1) must fit a uint16_t step count"
#endif

#if (CP_WITH_GSR != 0 && CP_WITH_GSR != 1) || (CP_WITH_CHANNEL != 0 && CP_WITH_CHANNEL != 1) || \
    (CP_WITH_DRC != 0 && CP_WITH_DRC != 1) || (CP_WITH_PLANE != 0 && CP_WITH_PLANE != 1) || \
    (CP_WITH_SPINE != 0 && CP_WITH_SPINE != 1)
#error "CP_WITH_GSR, CP_WITH_CHANNEL, CP_WITH_DRC, CP_WITH_PLANE and CP_WITH_SPINE must be 0 or 1"
#endif
#if CP_MAX_SECTIONS < 2 || CP_MAX_SECTIONS > 4
#error "CP_MAX_SECTIONS must be in 2..4"
#endif

#endif /* CP_CONFIG_H */
