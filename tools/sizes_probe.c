/* sizes_probe.c - one zero-initialised object per firmware context, compiled for the
 * target and never linked: `nm -S` on the object gives each sizeof exactly as the
 * target ABI lays it out (make sizes).
 * SPDX-License-Identifier: MIT
 */
#include "proto.h"

const struct canal_path sizeof_canal_path;
const struct canal sizeof_canal;
const struct job sizeof_job;
const struct frame_rx sizeof_frame_rx;
const struct proto sizeof_proto;
const struct path sizeof_path;
const union path_geom sizeof_path_geom;
const struct gsr_path sizeof_gsr_path;
const struct channel_path sizeof_channel_path;
const struct drc_path sizeof_drc_path;
