/* sim_machine_grbl.h - internals of the grbl 1.1h emulator (sim_machine_grbl*.c).
 * SPDX-License-Identifier: MIT
 */
#ifndef SIM_MACHINE_GRBL_H
#define SIM_MACHINE_GRBL_H

#include "sim_machine_int.h"

#define G_LINE_SIZE 80 /* protocol.h LINE_BUFFER_SIZE */
#define G_LF_OVERFLOW 1
#define G_LF_PAREN 2
#define G_LF_SEMI 4

/* system.h sys.state bits */
#define G_ST_IDLE 0
#define G_ST_ALARM 1
#define G_ST_CHECK 2
#define G_ST_HOMING 4
#define G_ST_CYCLE 8
#define G_ST_HOLD 16
#define G_ST_JOG 32
#define G_ST_SLEEP 128

/* report.h status codes */
#define G_ERR_LETTER 1
#define G_ERR_NUMBER 2
#define G_ERR_STATEMENT 3
#define G_ERR_NEGATIVE 4
#define G_ERR_DISABLED 5
#define G_ERR_PULSE 6
#define G_ERR_IDLE 8
#define G_ERR_GC_LOCK 9
#define G_ERR_SOFT_LIMIT 10
#define G_ERR_OVERFLOW 11
#define G_ERR_TRAVEL 15
#define G_ERR_JOG 16
#define G_ERR_UNSUPPORTED 20
#define G_ERR_MODAL 21
#define G_ERR_FEED 22
#define G_ERR_NOT_INTEGER 23
#define G_ERR_AXIS_CONFLICT 24
#define G_ERR_REPEATED 25
#define G_ERR_NO_AXIS 26
#define G_ERR_LINE_NUMBER 27
#define G_ERR_VALUE_MISSING 28
#define G_ERR_COORD_SYS 29
#define G_ERR_G53 30
#define G_ERR_AXIS_EXIST 31
#define G_ERR_NO_AXIS_PLANE 32
#define G_ERR_TARGET 33
#define G_ERR_RADIUS 34
#define G_ERR_NO_OFFSETS 35
#define G_ERR_UNUSED 36
#define G_ERR_G43 37
#define G_ERR_MAX_VALUE 38

/* settings, in the order of the $$ report (report.c report_grbl_settings) */
#define G_NSET 34
#define G_SET_MASK 7     /* $10 */
#define G_SET_ARCTOL 9   /* $12 */
#define G_SET_SOFT 11    /* $20 */
#define G_SET_HOMING 13  /* $22 */
#define G_SET_PULLOFF 18 /* $27 */
#define G_SET_RPMMAX 19  /* $30 */
#define G_SET_RPMMIN 20  /* $31 */
#define G_SET_STEPS 22   /* $100..$102 */
#define G_SET_RATE 25    /* $110..$112 */
#define G_SET_ACCEL 28   /* $120..$122 */
#define G_SET_TRAVEL 31  /* $130..$132 */

/* gcode.h modal values */
#define G_MO_SEEK 0
#define G_MO_LINEAR 1
#define G_MO_CW 2
#define G_MO_CCW 3
#define G_MO_PROBE 140 /* 140..143: G38.2..G38.5 */
#define G_MO_NONE 80

struct g_modal {
    int motion, plane, inch, incr, inverse, coord, tlo, spindle, coolant, flow;
};

struct sm_grbl {
    float set[G_NSET];
    int state;
    int suspend;  /* a hold is complete: nothing runs until '~' */
    double hold_t; /* when it began (a dwell in progress resumes after it) */
    int critical; /* soft-limit alarm: nothing runs until a reset */
    int reset_pending;
    double reset_at;
    char line[G_LINE_SIZE];
    int count, lflags;
    int startup; /* executing a startup line: replies are ">line:ok" */
    /* the parser state (gcode.c gc_state) */
    struct g_modal md;
    float spindle_speed, feed;
    int tool;
    float pos[3]; /* machine coordinates, mm */
    float wcs[3], g92[3], tlo;
    float coord[8][3]; /* "EEPROM": G54..G59, G28, G30 */
    char nline[2][G_LINE_SIZE];
    char build_info[G_LINE_SIZE];
    long plan_steps[3]; /* planner.c pl.position */
    float prb[3];
    /* sys */
    int f_ovr, r_ovr, s_ovr;
    int wco_cnt, ovr_cnt;
    int sp_state; /* spindle output: 0 off, 1 cw, 2 ccw */
    float sp_rpm;
    int cl_state;
};

/* sim_machine_grbl.c */
void g_status(struct sim_machine *m, int st);
void g_cycle_start(struct sim_machine *m);
void g_defaults(struct sm_grbl *g);
/* sim_machine_grbl_rt.c */
void g_rx_byte(struct sim_machine *m, uint8_t c, int *store);
void g_reset_finish(struct sim_machine *m);
void g_power_on(struct sim_machine *m);
void g_soft_reset(struct sim_machine *m);
void g_spindle_out(struct sim_machine *m, int arg);
void g_hold_now(struct sim_machine *m, int arg);
/* sim_machine_grbl_sys.c */
void g_system(struct sim_machine *m);
int g_read_float(const char *line, int *cc, float *out);
void g_fmt3(char *buf, size_t cap, const float v[3]);
/* sim_machine_grbl_gc.c */
void g_gcode(struct sim_machine *m, int jog);
void g_gc_init(struct sim_machine *m);

#endif /* SIM_MACHINE_GRBL_H */
