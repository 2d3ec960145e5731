/* sim_machine_marlin.h - internals of the Marlin 2.x emulator (sim_machine_marlin*.c).
 * SPDX-License-Identifier: MIT
 */
#ifndef SIM_MACHINE_MARLIN_H
#define SIM_MACHINE_MARLIN_H

#include "sim_machine_int.h"

#define ML_MAX_CMD 96 /* Configuration_adv.h MAX_CMD_SIZE */
#define ML_BUFSIZE 4  /* Configuration_adv.h BUFSIZE */
#define ML_BED 200.0  /* Configuration.h X/Y_BED_SIZE, Z_MAX_POS; MIN_POS 0 */

struct sm_marlin {
    /* queue.cpp SerialState: the line being received */
    char buf[ML_MAX_CMD];
    int count;
    int sis;     /* PS_NORMAL 0, PS_EOL 1, >= PS_ESC 4: escaped character */
    int full;    /* PS_EOL came from the length limit */
    int cut;     /* characters were skipped because of it */
    long last_n; /* serial.last_N */
    /* the command queue (queue.cpp RingBuffer) */
    char q[ML_BUFSIZE][ML_MAX_CMD];
    unsigned long qline[ML_BUFSIZE];
    int qhead, qlen;
    /* motion (module/motion.cpp) */
    double cur[3];   /* current_position, native mm */
    double shift[3]; /* workspace offset: logical = native + shift (G92) */
    int relative;    /* G91 */
    double feed_mms; /* feedrate_mm_s */
    long psteps[3];  /* planner.position, steps */
    int homed[3];
    double deliver_at; /* BLOCK_DELAY_FOR_1ST_MOVE */
    /* spindle (SPINDLE_FEATURE) */
    int sp_on;
    double sp_power;
    /* host keepalive (gcode.cpp host_keepalive) */
    double busy_next;
    int killed;
    int last_m400; /* the last command processed was M400 */
};

/* sim_machine_marlin.c */
void ml_ok(struct sim_machine *m, int arg);
void ml_unknown(struct sim_machine *m, const char *cmd);
/* sim_machine_marlin_cmd.c */
void ml_process(struct sim_machine *m, char *line);
void ml_quickstop(struct sim_machine *m, int arg);

#endif /* SIM_MACHINE_MARLIN_H */
