/* cp_status.c - the enum cp_err -> wire status mapping, the FROM column of cp_status.def.
 * SPDX-License-Identifier: MIT
 */
#include "cp_types.h"
#include "cp_status.h"

/* FROM of a row that no enum cp_err maps to (never matched: every cp_err is <= 0) */
#define WIRE_ONLY 1

/* The FROM column, indexed by code (the codes are 0, 1, 2, ...: proto.c checks it). */
static const int8_t status_from[CP_ST_END_] = {
#define CP_STATUS(name, code, text, from) [code] = (from),
#include "cp_status.def"
#undef CP_STATUS
};

int cp_status_of(int err)
{
    unsigned code;
    if (err == CP_ERR_INVAL) { /* a malformed argument reads as one out of range */
        err = CP_ERR_RANGE;
    }
    for (code = 0; code < (unsigned)CP_ST_END_; code++) {
        if (status_from[code] != WIRE_ONLY && status_from[code] == err) {
            return (int)code;
        }
    }
    return CP_ST_NUMERIC; /* IO, FULL, STATE, DONE: never the result of an init */
}
