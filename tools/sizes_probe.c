/* sizes_probe.c - one zero-initialised object per firmware context, compiled for the
 * target and never linked: `nm -S` on the object gives each sizeof exactly as the
 * target ABI lays it out (make sizes).
 * SPDX-License-Identifier: MIT
 */
#include "proto.h"

const struct toolpath sizeof_toolpath;
const struct canal sizeof_canal;
const struct job sizeof_job;
const struct frame_rx sizeof_frame_rx;
const struct proto sizeof_proto;
