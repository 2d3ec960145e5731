/* cp_types.h - project-wide types: cp_real, vectors, error codes, static asserts.
 * SPDX-License-Identifier: MIT
 *
 * Every firmware module includes this first. It pulls in nothing but <stdint.h>,
 * <stddef.h> and <math.h> (the only library the firmware links is the C maths).
 */
#ifndef CP_TYPES_H
#define CP_TYPES_H

#include <stddef.h>
#include <stdint.h>
#include <math.h>

#include "cp_config.h"

/* cp_real: the scalar of every geometric computation.
 * float (default; the Cortex-M4F image links no double helpers) or double
 * (host build option -DCP_REAL_DOUBLE=1, used for the 1e-9 mm accuracy tests). */
#if CP_REAL_DOUBLE
typedef double cp_real;
#define CP_R(x) (x)
#define cp_sqrt(x) sqrt(x)
#define cp_fabs(x) fabs(x)
#define cp_floor(x) floor(x)
#define cp_ceil(x) ceil(x)
#define CP_REAL_EPS 2.220446049250313e-16
#define CP_REAL_NAME "double"
#else
typedef float cp_real;
#define CP_R(x) (x##f)
#define cp_sqrt(x) sqrtf(x)
#define cp_fabs(x) fabsf(x)
/* floor and ceil of the float build: cp_floorf (cp_math.c), exact for every float;
 * ceil(x) = -floor(-x). The firmware's own: newlib-nano's floorf + ceilf cost 288 B
 * of flash, this one pair 40 B. */
cp_real cp_floorf(cp_real x);
#define cp_floor(x) cp_floorf(x)
#define cp_ceil(x) (-cp_floorf(-(x)))
#define CP_REAL_EPS 1.1920929e-07f
#define CP_REAL_NAME "float"
#endif

#define CP_PI CP_R(3.14159265358979323846)
#define CP_TWO_PI CP_R(6.28318530717958647692)
#define CP_DEG2RAD CP_R(0.01745329251994329577)

/* A point or direction in machine coordinates, mm (or unitless for directions). */
struct cp_vec3 {
    cp_real x, y, z;
};

/* Error codes returned by firmware functions as int: < 0 an error, >= 0 success
 * or a count (littlefs style). Values are stable; new codes are appended.
 * Wire-visible status codes are a separate frozen table: cp_status.def. */
enum cp_err {
    CP_OK = 0,
    CP_ERR_INVAL = -1,      /* bad argument: kind out of range, NULL, malformed */
    CP_ERR_NONFINITE = -2,  /* a parameter is NaN or Inf */
    CP_ERR_RANGE = -3,      /* a parameter outside its documented range */
    CP_ERR_RADIUS = -4,     /* R(t) <= 0 somewhere on the interval */
    CP_ERR_DEGENERATE = -5, /* C'(t) = 0 somewhere (degenerate curve) */
    CP_ERR_EMPTY = -6,      /* empty parameter interval (t0 == t1) */
    CP_ERR_TOO_MANY = -7,   /* step, line or point count above the compile-time maximum */
    CP_ERR_TOOL = -8,       /* ball tool radius >= min R on the interval */
    CP_ERR_CUSP = -9,       /* a requested line crosses a cuspidal edge (D <= 0) */
    CP_ERR_NUMERIC = -10,   /* a non-finite value was produced (never emitted) */
    CP_ERR_TOL = -11,       /* chord tolerance cannot be met within CP_MAX_STEPS */
    CP_ERR_IO = -12,        /* the HAL reported a failure (e.g. hang-up) */
    CP_ERR_FULL = -13,      /* back-pressure: try again later (not fatal) */
    CP_ERR_STATE = -14,     /* call not allowed in the current state */
    CP_ERR_DONE = -15,      /* iterator exhausted */
    /* models of seeds 001-003 (gsr, channel, drc); wire codes 25.. in cp_status.def */
    CP_ERR_OFF_PLANE = -16,     /* fixed-B frame: the centre curve leaves the Oxz plane */
    CP_ERR_FRENET = -17,        /* Frenet frame undefined: |C' x C''| <= 1e-9 |C'||C''| */
    CP_ERR_FRAME_REF = -18,     /* tangent parallel to the frame's reference vector */
    CP_ERR_SECTION = -19,       /* section size not positive (f_N, f_B, a or b <= 0) */
    CP_ERR_FT_RANGE = -20,      /* the section parameter law f_t leaves [0, 1] */
    CP_ERR_FOLD = -21,          /* the sweep folds: 1 - k.(P - C) <= 0 somewhere */
    CP_ERR_TOO_FEW = -22,       /* fewer sections or points than the model needs */
    CP_ERR_EXPONENT = -23,      /* superellipse exponent n < 1 */
    CP_ERR_COINCIDENT = -24,    /* coincident consecutive points or section centres */
    CP_ERR_SECTION_PLANE = -25, /* a section plane contains the chord to its neighbour */
    CP_ERR_AREA_LAW = -26,      /* interpolated area S <= 0 or exponent n < 1 */
    CP_ERR_ISOTROPIC = -27,     /* a = b with n != 2: section orientation undefined */
    CP_ERR_TURN = -28,          /* a turning angle >= 90 degrees (data too sparse, cusp) */
    CP_ERR_TWIST = -29,         /* adjoining planes twist >= 45 degrees (3D data too sparse) */
    CP_ERR_BUFFER = -30,        /* caller buffer too small (the function reports the size) */
    /* closed curves (issue 22); wire code 46 */
    CP_ERR_SEAM = -31,          /* closed curve: a law's value or slope jumps at the seam
                                   (raster_seam_check, raster.h) */
    /* global overlap (issue 22); wire code 47 */
    CP_ERR_OVERLAP = -32        /* parts of the sweep far apart along its curve meet, where
                                   the tool is outside (raster_overlap_check, raster.h) */
};

/* C99 compile-time assertion (no _Static_assert in C99). File scope only, unique tag. */
#define CP_STATIC_ASSERT(cond, tag) typedef char cp_static_assert_##tag[(cond) ? 1 : -1]

#if defined(__GNUC__)
#define CP_MUST_CHECK __attribute__((warn_unused_result))
#define CP_NOINLINE __attribute__((noinline))
#define CP_ALWAYS_INLINE inline __attribute__((always_inline))
#else
#define CP_ALWAYS_INLINE inline
#define CP_MUST_CHECK
#define CP_NOINLINE
#endif

#endif /* CP_TYPES_H */
