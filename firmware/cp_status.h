/* cp_status.h - wire status codes, generated from cp_status.def by the preprocessor.
 * SPDX-License-Identifier: MIT
 */
#ifndef CP_STATUS_H
#define CP_STATUS_H

enum cp_status {
#define CP_STATUS(name, code, text) CP_ST_##name = code,
#include "cp_status.def"
#undef CP_STATUS
    CP_ST_END_
};

/* Text of a status code ("ok", "unknown command", ...); "?" for an unknown code. */
const char *cp_status_text(int code);

#endif /* CP_STATUS_H */
