/* cp_status.h - wire status codes, generated from cp_status.def by the preprocessor.
 * SPDX-License-Identifier: MIT
 */
#ifndef CP_STATUS_H
#define CP_STATUS_H

enum cp_status {
#define CP_STATUS(name, code, text, from) CP_ST_##name = code,
#include "cp_status.def"
#undef CP_STATUS
    CP_ST_END_
};

/* Text of a status code ("ok", "unknown command", ...); "?" for an unknown code. */
const char *cp_status_text(int code);

/* The wire status of an enum cp_err (cp_types.h) returned by a firmware call: the row
 * of cp_status.def whose FROM column names it (CP_OK: CP_ST_OK); CP_ERR_INVAL gives
 * CP_ST_OUT_OF_RANGE, a code no row names CP_ST_NUMERIC (cp_status.def). */
int cp_status_of(int err);

#endif /* CP_STATUS_H */
