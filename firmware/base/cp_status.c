/* cp_status.c - the enum cp_err -> wire status mapping, the FROM column of cp_status.def.
 * SPDX-License-Identifier: MIT
 */
#include "cp_types.h"
#include "cp_status.h"

/* FROM of a row that no enum cp_err maps to: the protocol's own codes (a positive value,
 * so never an enum cp_err, which are all <= 0; cp_types.h) */
#define WIRE_ONLY 1
CP_STATIC_ASSERT(CP_OK == 0, cp_ok_is_zero_and_errors_negative);

/* The FROM column, indexed by wire code (designated: a row's place in the file does not
 * matter; a code without a row stays 0 = CP_OK and is never returned for an error). */
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
