/* sim_machine.h - serial-machine emulators of grbl 1.1h and Marlin 2.x for host_sim:
 * "the machine on the other end of the firmware's machine UART".
 * SPDX-License-Identifier: MIT
 *
 * A pure state machine: no I/O, no threads, no wall clock. The caller passes the time
 * (milliseconds, any origin, never decreasing; a smaller value is taken as the last one)
 * with every call. Bytes from the firmware go in with sim_machine_rx(), the machine's
 * replies come out of sim_machine_tx(); both first advance the machine to the given time.
 *
 * Every behaviour follows the real firmware's source (facts only, no code copied; both
 * are GPL). The comments of sim_machine_grbl*.c and sim_machine_marlin*.c name the source
 * file of each behaviour. Sources read:
 *   grbl 1.1h   gnea/grbl bfb67f0 (build 20190830): grbl/serial.c, protocol.c, gcode.c,
 *               system.c, report.c, settings.c, motion_control.c, planner.c, config.h,
 *               defaults.h (DEFAULTS_GENERIC), nuts_bolts.c, spindle_control.c, print.c
 *   Marlin 2.x  MarlinFirmware/Marlin bugfix-2.1 files: src/gcode/queue.cpp (the
 *               2.1.x version with "Resend:" + "ok"), parser.cpp, gcode.cpp, M3-M5,
 *               M110, M114, G4, core/language.h, HAL/AVR/MarlinSerial.cpp,
 *               module/planner.h/.cpp, module/motion.cpp, MarlinCore.cpp; the default
 *               Configuration.h / Configuration_adv.h (2.0.5/2.1 stock; the defaults used
 *               here did not change between them).
 *
 * grbl 1.1h as emulated (defaults: $10=1 MPos, $22=0, 250 steps/mm, 500 mm/min max rate):
 *   - RX ring: 128 usable bytes (serial.c: RX_RING_BUFFER = RX_BUFFER_SIZE+1). A byte that
 *     finds it full is dropped (serial.c ISR) and counted in rx_overflows.
 *   - Realtime bytes are picked out on arrival and never stored: '?' status report,
 *     '!' feed hold, '~' cycle start/resume, 0x18 soft reset, 0x84 door (ignored: no door),
 *     0x85 jog cancel, 0x90..0xA1 overrides; every other byte >= 0x80 is thrown away.
 *   - Lines end at '\n' or '\r' (so "\r\n" is two lines: the second, empty, answers "ok").
 *     Bytes <= ' ' and '/' are dropped, "(...)" and ";..." comments stripped, a-z upcased;
 *     the 80th stored character sets the overflow flag and the line answers error:11.
 *   - Every line is answered exactly once: "ok" or "error:N" ("\r\n" line ends).
 *   - ok means planned, not executed. The planner holds 15 blocks (BLOCK_BUFFER_SIZE 16,
 *     one slot kept free); a motion line waits for a slot, and while it waits no byte is
 *     read from RX. Spindle/coolant changes, G4, G10/G28.1/G30.1 (EEPROM writes), G92,
 *     G43.1/G49, a WCS change and M0/M2/M30 wait for the planner to empty first.
 *   - With homing on ($22=1) it boots in Alarm; G-code blocks answer error:9 until $H or $X.
 *   - '!' stops motion at once (no deceleration: Hold:0 at once), and while held no line is
 *     read. 0x18 discards the planner; if a motion was running: "ALARM:3", 500 ms of
 *     silence, then the banner and "[MSG:'$H'|'$X' to unlock]" (state Alarm).
 * Marlin 2.x as emulated (default Configuration.h/_adv.h + SPINDLE_FEATURE by default):
 *   - RX ring RX_BUFFER_SIZE 128 = 127 usable (HAL/AVR/MarlinSerial.cpp); command queue
 *     BUFSIZE 4 of MAX_CMD_SIZE 96; bytes are read from RX only while the queue has a free
 *     slot (also while a command blocks: idle() -> manage_inactivity() reads serial).
 *   - ';' comments stripped; "(...)" is NOT a comment (PAREN_COMMENTS off): it is an
 *     unknown command. Empty or comment-only lines get no answer at all.
 *   - A line longer than 95 characters is cut at 95 (the rest skipped) and still run.
 *   - "N<n> ... *<cs>": N must be last+1 (else "Error:Line Number is not Last Line
 *     Number+1, Last Line: <last>"), then the checksum must be present ("Error:No Checksum
 *     with line number, Last Line: <last>") and right ("Error:checksum mismatch, Last
 *     Line: <last>"); each error empties the RX ring and sends "Resend: <last+1>" and
 *     "ok". A '*' without N is not checked (Marlin 2.x has no "No Line Number with
 *     checksum" error any more): the parser cuts the line at '*'. M110 N<v> sets last=v.
 *   - One command per line: the first G/M/T word; later G/M words are parameters and are
 *     ignored (counted in ignored_words). Unknown: echo:Unknown command: "<cmd>" + ok.
 *     Default config: G17-G19, G20, G53-G59, G93/G94, G40/G49/G80, M2, M30 (no SD),
 *     M7-M9 are unknown; G21 is accepted and does nothing. F is modal and shared by G0/G1
 *     (no G0_FEEDRATE), default feedrate 1500 mm/min; max 300/300/5 mm/s (X/Y/Z).
 *   - ok after the command ran; ADVANCED_OK: "ok N<n> P<planner free> B<queue free>".
 *   - M400, G4 (P ms / S s, after a planner sync), M3/M4/M5 (sync + 5000 ms spin-up or
 *     spin-down delay, SPINDLE_LASER_POWERUP/POWERDOWN_DELAY) and a G0/G1 that waits for a
 *     planner slot block; every busy_ms while one command blocks: "echo:busy: processing".
 *   - The first block waits up to 100 ms before it runs (BLOCK_DELAY_FOR_1ST_MOVE) unless
 *     3 blocks are queued; moves of fewer than 6 steps (MIN_STEPS_PER_SEGMENT) are joined
 *     to the next one (80/80/4000 steps/mm).
 *   - M112 (read as the line arrives): "Error:Printer halted. kill() called!" and the
 *     machine stops answering. M410 (likewise) discards the planner.
 *
 * Not emulated, or simplified (both): acceleration (a block runs at its nominal rate for
 * its whole length), TX back-pressure (replies are never lost or delayed: grbl's 104-byte
 * and Marlin's TX buffers would stall the main loop), limit switches, probe contact
 * (G38.x never touches: ALARM:5 for G38.2/.4), homing takes no time.
 * grbl: a hold completes at once (real grbl reports Hold:1 while decelerating); overrides
 * change only blocks planned after them; $13=1 (inch reports), laser mode ($32), the
 * safety door (0x84), parking and EEPROM-write RX masking are not modelled; "ALARM:2"
 * and its "[MSG:Reset to continue]" come out together (no 500 ms between them).
 * Marlin: M105 answers "ok T:25.00 /0.00 @:0" (invented temperatures); M17 M18 M31
 * M75-M77 M81-M85 M104 M106 M107 M111 M115 M117-M121 M140 M155 M201 M203-M206 M211 M220
 * M221 M500-M503 M999 and T<n> answer "ok" with no other effect; G28 homes the named
 * axes (none: all) to 0 at once, after which soft endstops clamp moves to [0, 200];
 * G2/G3 segment count follows 2.1's plan_arc (1 mm segments, >= 72 per turn) without its
 * rounding details; M114's "Count" is the planner position in steps (80/80/4000 per mm).
 */
#ifndef SIM_MACHINE_H
#define SIM_MACHINE_H

#include <stddef.h>
#include <stdint.h>

enum sim_machine_kind { SIM_MACHINE_GRBL, SIM_MACHINE_MARLIN };

/* Options. A zeroed struct is the real default machine of the kind, with motion that
 * executes instantly. */
struct sim_machine_opts {
    enum sim_machine_kind kind;
    /* usable serial RX bytes, 1..65535; 0 = the real default (grbl 1.1h 128, Marlin
     * RX_BUFFER_SIZE 128 ring = 127) */
    unsigned rx_size;
    /* grbl: $22=1 (homing enabled, boots in Alarm). Marlin: ignored. */
    int homing;
    /* Marlin: ADVANCED_OK ("ok N<n> P<p> B<b>"). grbl: ignored. */
    int advanced_ok;
    /* Marlin: 1 = a build without SPINDLE_FEATURE/LASER_FEATURE (M3/M4/M5 are unknown
     * commands). 0 (default) = SPINDLE_FEATURE on. grbl: ignored. */
    int marlin_no_spindle;
    /* Time model of a motion block of length L mm at the machine's rate R mm/min (the
     * programmed feed, limited by the axes' maximum rates; rapids at the maximum rate):
     * duration = L * ms_per_mm + time_scale * 60000 * L / R  milliseconds.
     * Both 0 (default): motion executes instantly (and Marlin's first-block delay too).
     * ms_per_mm >= 0 (ms per mm, whatever the feed); time_scale >= 0 (1 = real time). */
    double ms_per_mm;
    double time_scale;
    /* Marlin host keepalive: "echo:busy: processing" every busy_ms while a command
     * blocks; 0 = the real default DEFAULT_KEEPALIVE_INTERVAL 2 s (2000); < 0 = off. */
    double busy_ms;
};

struct sim_machine;

/* A new machine, powered up at time 0 (grbl prints its banner, readable at once).
 * NULL on a bad option (rx_size > 65535, negative ms_per_mm or time_scale) or no memory. */
struct sim_machine *sim_machine_new(const struct sim_machine_opts *o);
void sim_machine_free(struct sim_machine *m);

/* n bytes from the firmware (the machine's RX) arriving at now_ms. */
void sim_machine_rx(struct sim_machine *m, const uint8_t *b, size_t n, double now_ms);

/* Advance to now_ms; copy up to cap reply bytes (the machine's TX) to out; returns the
 * count. Bytes not copied stay for the next call. */
size_t sim_machine_tx(struct sim_machine *m, double now_ms, uint8_t *out, size_t cap);

/* Every motion the machine accepted, in order (grbl: planned, or checked in $C mode;
 * Marlin: executed by G0/G1/G2/G3/G28). Arcs appear as their line segments. */
struct sim_machine_move {
    int rapid;            /* 1: G0 (and G28/G30 moves); 0: a feed move (G1/G2/G3/G38) */
    double x, y, z;       /* end point, work coordinates in mm (what the program commanded,
                             converted from inches under G20) */
    int has_a, has_c;     /* the block carried an A / C word (ignored by both machines) */
    double a, c;          /* its value (0 when absent) */
    double feed;          /* programmed feed in mm/min (0: none ever given) */
    unsigned long line;   /* 1-based program line: lines the machine read, "\r\n" counts
                             once; bytes lost to an RX overflow or a Marlin resend flush
                             are not counted */
};
/* The moves so far; *v stays valid until the next call of any other function. */
size_t sim_machine_moves(const struct sim_machine *m, const struct sim_machine_move **v);

/* The verdict on the whole conversation and program so far. */
struct sim_machine_verdict {
    unsigned long lines;        /* lines read (grbl: each one answered; Marlin: non-empty) */
    unsigned long errors;       /* grbl "error:N"; Marlin "Error:..." (line number/checksum) */
    unsigned long unknown;      /* Marlin: "echo:Unknown command" (grbl: in errors, 20) */
    unsigned long alarms;       /* grbl "ALARM:N"; Marlin kill (M112) */
    unsigned long rx_overflows; /* bytes dropped because the RX ring was full */
    unsigned long resends;      /* Marlin "Resend:" */
    unsigned long long_lines;   /* grbl error:11; Marlin lines cut at 95 characters */
    unsigned long ignored_words;/* Marlin: lines with a second G/M word (ignored) */
    unsigned long ignored_axes; /* motion blocks with an A or C word the machine ignored
                                   (grbl refuses them: error:20, also in errors) */
    unsigned long g1_without_feed;  /* feed moves (G1/G2/G3) before any F was given; grbl
                                       refuses them (error:22), Marlin runs them at 1500 */
    unsigned long feed_before_safe; /* feed moves before the first rapid set a safe height */
    unsigned long rapid_below_safe; /* rapids with an XY change starting or ending below it */
    unsigned long feed_above_safe;  /* feed moves ending above the safe height */
    unsigned long feed_spindle_off; /* feed moves while the spindle was off, in a program
                                       that turns the spindle on somewhere */
    int started_safe;  /* G21 and G90 in effect before the first motion, the first motion
                          is a rapid, and no feed move ends above its Z (the safe height) */
    int ended_safe;    /* program_end and, if there was a feed move: after the last one a
                          rapid to Z >= the safe height, then (if the spindle was ever on) M5,
                          then the program end */
    int units_mm;      /* G21 in effect (explicitly) before the first motion, never G20 */
    int absolute;      /* G90 in effect (explicitly) before the first motion, never G91 */
    int spindle_off_at_end; /* the spindle was never on, or the last spindle command was an
                               explicit M5 (grbl's implicit stop at M2 does not count) */
    int program_end;   /* grbl: M2 or M30 accepted. Marlin (which has neither): the last
                          command processed was M400, or (end of stream) nothing is queued,
                          running or waiting and the planner is empty */
    double safe_z;     /* the safe height (work Z of the first rapid), when set */
    /* The first rejected line and the machine's answer, or the first rule broken, whichever
     * came first in the program; "" when none. */
    char first_problem[160];
};
void sim_machine_verdict(const struct sim_machine *m, struct sim_machine_verdict *v);

#endif /* SIM_MACHINE_H */
