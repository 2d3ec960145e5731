/* sim_machine_int.h - internals shared by sim_machine_core.c, sim_machine_grbl.c and
 * sim_machine_marlin.c (not for other users: the API is sim_machine.h).
 * SPDX-License-Identifier: MIT
 *
 * Model: one RX ring, one unbounded TX buffer, a planner ring of motion blocks executed one
 * after the other against the caller's clock, and one "current command": the list of steps
 * the line being executed still has to do (wait for the planner to empty, wait some time,
 * put a block into the planner, print a text, call a function). The main loop of each
 * dialect reads RX bytes and builds commands; a step that cannot complete yet blocks the
 * main loop, exactly where the real firmware's main loop blocks.
 */
#ifndef SIM_MACHINE_INT_H
#define SIM_MACHINE_INT_H

#include "sim_machine.h"

#include <stdarg.h>

/* planner: BLOCK_BUFFER_SIZE 16 ring with one slot kept free in both firmwares
 * (grbl planner.c plan_check_full_buffer, Marlin planner.h is_full/moves_free) */
#define SM_PLAN_RING 16
#define SM_PLAN_SLOTS 15

struct sim_machine;

struct sm_block {
    double p0[3], p1[3]; /* machine position, mm */
    double dur;          /* ms */
    double rate;         /* nominal rate, mm/min */
    int rapid;
};

enum sm_step_kind { SM_SYNC, SM_DELAY, SM_BLOCK, SM_TEXT, SM_CALL };

typedef void (*sm_fn)(struct sim_machine *m, int arg);

struct sm_step {
    int kind;
    double ms;           /* SM_DELAY */
    struct sm_block blk; /* SM_BLOCK */
    char *text;          /* SM_TEXT, malloc'd */
    sm_fn fn;            /* SM_CALL */
    int arg;
};

/* the command being executed: its remaining steps */
struct sm_cmd {
    struct sm_step *v;
    size_t n, cap, i;
    int active;
    double t0;    /* when the current SM_DELAY step began */
    int t0_set;
};

/* the program judge (the verdict under construction) */
struct sm_rules {
    struct sim_machine_verdict v;
    unsigned long problem_line; /* line of v.first_problem (0: none yet) */
    int motions;                /* motions recorded */
    int safe_set;
    int g21_seen, g90_seen, g20_seen, g91_seen; /* G20/G21/G90/G91 in effect at some time */
    int first_motion_ok_units, first_motion_ok_abs;
    int feed_ever;        /* an F word was accepted */
    int spindle_on, spindle_ever, last_spindle_m5;
    int first_rapid;      /* the first motion was a rapid */
    unsigned long feeds;  /* feed moves recorded */
    unsigned long spindle_off_line; /* first feed move with the spindle off */
    /* end of program, relative to the last feed move */
    int retract_after, m5_after, end_after;
    unsigned long last_feed_line;
};

/* dialect operations */
struct sm_ops {
    void (*rx_byte)(struct sim_machine *m, uint8_t c, int *store); /* on arrival */
    void (*run)(struct sim_machine *m);                 /* main loop at m->now */
    double (*next_event)(const struct sim_machine *m);  /* dialect events, or a huge value */
    void (*event)(struct sim_machine *m);               /* dialect events due at m->now */
    void (*planner_empty)(struct sim_machine *m);       /* the last block just finished */
    int (*push)(struct sim_machine *m, const struct sm_block *b); /* 0: the planner is full */
    int (*synced)(struct sim_machine *m);               /* 1: SM_SYNC may complete */
    int (*halted)(const struct sim_machine *m);         /* 1: no step may run now */
    void (*destroy)(struct sim_machine *m);
    void (*verdict)(const struct sim_machine *m, struct sim_machine_verdict *v);
};

struct sm_grbl;
struct sm_marlin;

struct sim_machine {
    struct sim_machine_opts o;
    const struct sm_ops *ops;
    double now;
    /* RX ring */
    uint8_t *rx;
    unsigned rx_cap, rx_head, rx_len;
    /* TX */
    char *tx;
    size_t tx_len, tx_cap, tx_pos;
    int tx_fail;
    /* planner */
    struct sm_block plan[SM_PLAN_RING];
    unsigned plan_tail, plan_n;
    int exec_on;      /* the head block is moving */
    double run_since; /* when it (re)started moving */
    double done_ms;   /* time it moved before the last hold */
    double mpos[3];   /* machine position at the start of the head block, mm */
    struct sm_cmd cmd;
    /* program lines: '\n', or '\r' not followed by '\n' */
    unsigned long prog_line;
    int last_cr;
    /* moves */
    struct sim_machine_move *mv;
    size_t mv_n, mv_cap;
    struct sm_rules r;
    struct sm_grbl *g;
    struct sm_marlin *ml;
};

/* dialects */
int sm_grbl_init(struct sim_machine *m);
int sm_marlin_init(struct sim_machine *m);

/* TX */
void sm_out(struct sim_machine *m, const char *s);
void sm_outf(struct sim_machine *m, const char *fmt, ...);
/* RX ring */
int sm_rx_pop(struct sim_machine *m);
void sm_rx_clear(struct sim_machine *m);

/* command steps */
void sm_cmd_clear(struct sim_machine *m);
void sm_step_sync(struct sim_machine *m);
void sm_step_delay(struct sim_machine *m, double ms);
void sm_step_block(struct sim_machine *m, const struct sm_block *b);
void sm_step_text(struct sim_machine *m, const char *fmt, ...);
void sm_step_call(struct sim_machine *m, sm_fn fn, int arg);
int sm_cmd_exec(struct sim_machine *m); /* 1: done (or none), 0: blocked */

/* planner */
int sm_plan_full(const struct sim_machine *m);
void sm_plan_add(struct sim_machine *m, const struct sm_block *b);
void sm_plan_pos(const struct sim_machine *m, double out[3]); /* where the tool is now */
void sm_plan_clear(struct sim_machine *m);  /* stop at once, discard every block */
void sm_plan_run(struct sim_machine *m);    /* (re)start moving the head block */
void sm_plan_hold(struct sim_machine *m);   /* stop moving, keep the blocks */
double sm_block_ms(const struct sim_machine *m, double len_mm, double rate);

/* moves and the judge */
struct sm_motion {
    int rapid;
    double w0[3], w1[3]; /* work coordinates, mm: start, end */
    int has_a, has_c;
    double a, c;
    double feed; /* mm/min, 0: none */
};
void sm_motion(struct sim_machine *m, const struct sm_motion *mo);
void sm_rule_units(struct sim_machine *m, int mm);
void sm_rule_distance(struct sim_machine *m, int absolute);
void sm_rule_feed_given(struct sim_machine *m);
void sm_rule_spindle(struct sim_machine *m, int on, int explicit_m5);
void sm_rule_program_end(struct sim_machine *m);
void sm_problem(struct sim_machine *m, unsigned long line, const char *fmt, ...);
/* program_end and end_ok: whether the program ended, and whether it ended after the
 * retract (and M5) that follow the last feed move (sm_end_ok) */
void sm_rules_final(const struct sim_machine *m, struct sim_machine_verdict *v, int program_end,
                    int end_ok);
int sm_end_ok(const struct sm_rules *r);

/* numbers */
void sm_fixed(char *buf, size_t cap, double v, int decimals); /* half-up, like print.c */
void sm_esc(char *buf, size_t cap, const char *s);            /* printable copy of s */

#endif /* SIM_MACHINE_INT_H */
