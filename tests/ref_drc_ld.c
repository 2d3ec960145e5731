/* ref_drc_ld.c - tests/ref_drc.c's DRC-EXP compiled in long double (ref_drc.h: *_ld).
 * SPDX-License-Identifier: MIT
 */
#define REF_DRC_LD 1
#include "ref_drc.c"
