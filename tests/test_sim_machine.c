/* test_sim_machine.c - self-test of the grbl 1.1h and Marlin 2.x machine emulators
 * (host_sim/sim_machine*.c). Run by `make sim-machine`; prints "  PASS ..." / "  FAIL ..."
 * and ends with "machine: N passed, N failed" (exit status 1 on a failure).
 * SPDX-License-Identifier: MIT
 *
 * The expected replies are the real firmwares' (PROTOCOL-NOTES.md section 8 for grbl 1.1h
 * run against our stream; the sources named in sim_machine.h otherwise), never values read
 * back from the emulator. Every check compares against a fixed text or number, so a
 * machine that answered otherwise fails it.
 */
#include "sim_machine.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int n_pass, n_fail;

struct sess {
    struct sim_machine *m;
    double t;
    char out[1 << 16];
    size_t n, mark;
};

static void check(int ok, const char *name, const char *got)
{
    if (ok) {
        n_pass++;
        printf("  PASS %s\n", name);
        return;
    }
    n_fail++;
    printf("  FAIL %s", name);
    if (got != NULL) {
        char esc[400];
        size_t o = 0;
        for (; *got != '\0' && o + 5 < sizeof esc; got++) {
            unsigned char c = (unsigned char)*got;
            if (c >= 0x20 && c < 0x7f) {
                esc[o++] = (char)c;
            } else {
                o += (size_t)snprintf(esc + o, sizeof esc - o, "\\x%02X", c);
            }
        }
        esc[o] = '\0';
        printf(": got \"%s\"", esc);
    }
    printf("\n");
}

static struct sess *open_m(enum sim_machine_kind kind, int homing, int advok, double ms_per_mm)
{
    struct sim_machine_opts o;
    struct sess *s = calloc(1, sizeof *s);
    if (s == NULL) {
        exit(2);
    }
    memset(&o, 0, sizeof o);
    o.kind = kind;
    o.homing = homing;
    o.advanced_ok = advok;
    o.ms_per_mm = ms_per_mm;
    s->m = sim_machine_new(&o);
    if (s->m == NULL) {
        printf("  FAIL sim_machine_new\n");
        exit(2);
    }
    return s;
}

static void close_m(struct sess *s)
{
    sim_machine_free(s->m);
    free(s);
}

/* everything the machine sent since the last call */
static const char *drain(struct sess *s)
{
    size_t k;
    s->mark = s->n;
    do {
        k = sim_machine_tx(s->m, s->t, (uint8_t *)s->out + s->n, sizeof s->out - 1 - s->n);
        s->n += k;
    } while (k > 0 && s->n < sizeof s->out - 1);
    s->out[s->n] = '\0';
    return s->out + s->mark;
}

static void put(struct sess *s, const char *text)
{
    sim_machine_rx(s->m, (const uint8_t *)text, strlen(text), s->t);
}

/* send, then the reply */
static const char *say(struct sess *s, const char *text)
{
    put(s, text);
    return drain(s);
}

static int count_of(const char *hay, const char *needle)
{
    int n = 0;
    const char *p = hay;
    while ((p = strstr(p, needle)) != NULL) {
        n++;
        p += strlen(needle);
    }
    return n;
}

static unsigned xor_cs(const char *s)
{
    unsigned cs = 0;
    while (*s != '\0') {
        cs ^= (unsigned char)*s++;
    }
    return cs;
}

static struct sim_machine_verdict verdict(const struct sess *s)
{
    struct sim_machine_verdict v;
    sim_machine_verdict(s->m, &v);
    return v;
}

/* ---------------------------------------------------------------- grbl */

/* PROTOCOL-NOTES.md section 8: what grbl 1.1h answered to canalpath's lines */
static void grbl_section8(void)
{
    struct sess *s = open_m(SIM_MACHINE_GRBL, 0, 0, 0.0);
    const char *r = drain(s);
    check(strcmp(r, "\r\nGrbl 1.1h ['$' for help]\r\n") == 0, "grbl banner at power-up", r);
    r = say(s, "[RUN:points=4117,first=0,mode=LINES,n=8,steps=511,link=3]\n");
    check(strcmp(r, "error:1\r\n") == 0, "grbl [RUN:...] -> error:1", r);
    r = say(s, "ok\n");
    check(strcmp(r, "error:2\r\n") == 0, "grbl 'ok' -> error:2", r);
    r = say(s, "N0 M110 N0*125\n");
    check(strcmp(r, "error:20\r\n") == 0, "grbl N0 M110 N0*125 -> error:20", r);
    r = say(s, "N2 G1 X1 Y2 Z3 F600.0*5\n");
    check(strcmp(r, "error:1\r\n") == 0, "grbl N2 G1 ... F600.0*5 -> error:1", r);
    r = say(s, "G1 X25.0000 Y0.0000 Z0.0000\n");
    check(strcmp(r, "error:22\r\n") == 0, "grbl G1 with no F ever -> error:22", r);
    check(verdict(s).g1_without_feed == 1, "grbl verdict counts the G1 without feed", NULL);
    r = say(s, "G21 G90 G17 G94 G54\n");
    check(strcmp(r, "ok\r\n") == 0, "grbl G21 G90 G17 G94 G54 -> ok", r);
    r = say(s, "; comment\n");
    check(strcmp(r, "ok\r\n") == 0, "grbl '; comment' -> ok", r);
    r = say(s, "(comment)\n");
    check(strcmp(r, "ok\r\n") == 0, "grbl '(comment)' -> ok", r);
    r = say(s, "G1 X9.7555 Y0.2550 Z1.4980 F600.0\n");
    check(strcmp(r, "ok\r\n") == 0, "grbl G1 X9.7555 Y0.2550 Z1.4980 F600.0 -> ok", r);
    r = say(s, "N7 G0 X1\n");
    check(strcmp(r, "ok\r\n") == 0, "grbl N line number alone -> ok", r);
    check(verdict(s).errors == 5, "grbl verdict counts 5 errors", NULL);
    close_m(s);
}

/* protocol.c: 80-character line buffer counting stored characters only; CR LF = 2 lines */
static void grbl_lines(void)
{
    struct sess *s = open_m(SIM_MACHINE_GRBL, 0, 0, 0.0);
    char line[200];
    const char *r;
    drain(s);
    strcpy(line, "G4P");
    memset(line + 3, '0', 76);
    strcpy(line + 79, "\n"); /* 79 stored characters: the most that fit */
    r = say(s, line);
    check(strcmp(r, "ok\r\n") == 0, "grbl 79-character line -> ok", r);
    strcpy(line, "G4P");
    memset(line + 3, '0', 77);
    strcpy(line + 80, "\n"); /* the 80th character overflows */
    r = say(s, line);
    check(strcmp(r, "error:11\r\n") == 0, "grbl 80-character line -> error:11", r);
    check(verdict(s).long_lines == 1, "grbl verdict counts the long line", NULL);
    r = say(s, "G0      X1      Y1      Z1      (a comment that is long enough to pass eighty) ;x\n");
    check(strcmp(r, "ok\r\n") == 0, "grbl spaces and comments do not count toward 80", r);
    r = say(s, "g0 x2\r\n");
    check(strcmp(r, "ok\r\nok\r\n") == 0, "grbl lower case accepted; CR LF answers twice", r);
    r = say(s, "G0 A5\n");
    check(strcmp(r, "error:20\r\n") == 0, "grbl A word -> error:20 (no A axis)", r);
    check(verdict(s).ignored_axes == 1, "grbl verdict counts the A word", NULL);
    r = say(s, "G17 G18\n");
    check(strcmp(r, "error:21\r\n") == 0, "grbl two plane words -> error:21 (modal group)", r);
    r = say(s, "G0 G1 X1\n");
    check(strcmp(r, "error:24\r\n") == 0, "grbl G0 G1 -> error:24 (axis command conflict)", r);
    r = say(s, "G1 X1 X2 F10\n");
    check(strcmp(r, "error:25\r\n") == 0, "grbl X twice -> error:25", r);
    r = say(s, "G2 X1 F10\n");
    check(strcmp(r, "error:35\r\n") == 0, "grbl G2 without I/J -> error:35", r);
    r = say(s, "G5 X1\n");
    check(strcmp(r, "error:20\r\n") == 0, "grbl G5 -> error:20", r);
    r = say(s, "$I\n");
    check(strcmp(r, "[VER:1.1h.20190830:]\r\n[OPT:V,15,128]\r\nok\r\n") == 0, "grbl $I", r);
    r = say(s, "$G\n");
    check(strcmp(r, "[GC:G0 G54 G17 G21 G90 G94 M5 M9 T0 F0 S0]\r\nok\r\n") == 0, "grbl $G", r);
    r = say(s, "$10\n");
    check(strcmp(r, "error:3\r\n") == 0, "grbl $10 without = -> error:3", r);
    r = say(s, "$Q\n");
    check(strcmp(r, "error:2\r\n") == 0, "grbl $Q -> error:2 (read_float of 'Q')", r);
    r = say(s, "$X\n");
    check(strcmp(r, "ok\r\n") == 0, "grbl $X when not in alarm -> ok", r);
    close_m(s);
}

/* serial.c: 128-byte ring; beyond it bytes are dropped */
static void grbl_overflow(void)
{
    static const char *const ln = "G1 X1.000 F100\nG1 X0.000 F100\n"; /* 30 bytes */
    struct sess *s = open_m(SIM_MACHINE_GRBL, 0, 0, 1000.0);
    struct sim_machine_opts o;
    struct sim_machine *big;
    char buf[2048] = "";
    int i;
    for (i = 0; i < 16; i++) {
        strcat(buf, ln); /* 32 moves, 480 bytes, each move 1 s */
    }
    drain(s);
    put(s, buf);
    check(verdict(s).rx_overflows > 0, "grbl 480 bytes unread with a 128-byte ring overflow", NULL);
    check(count_of(drain(s), "ok") == 15, "grbl 15 planner blocks answered at once", s->out + s->mark);
    close_m(s);
    memset(&o, 0, sizeof o);
    o.rx_size = 1024;
    o.ms_per_mm = 1000.0;
    big = sim_machine_new(&o);
    sim_machine_rx(big, (const uint8_t *)buf, strlen(buf), 0.0);
    {
        struct sim_machine_verdict v;
        sim_machine_verdict(big, &v);
        check(v.rx_overflows == 0, "grbl the same bytes fit a 1024-byte ring (control)", NULL);
    }
    sim_machine_free(big);
}

/* serial.c: '?' is taken out on arrival; report.c status format and counters */
static void grbl_realtime(void)
{
    struct sess *s = open_m(SIM_MACHINE_GRBL, 0, 0, 0.0);
    const char *r;
    drain(s);
    r = say(s, "?");
    check(strcmp(r, "<Idle|MPos:0.000,0.000,0.000|FS:0,0|WCO:0.000,0.000,0.000>\r\n") == 0,
          "grbl first status report carries WCO", r);
    r = say(s, "?");
    check(strcmp(r, "<Idle|MPos:0.000,0.000,0.000|FS:0,0|Ov:100,100,100>\r\n") == 0,
          "grbl second status report carries Ov", r);
    r = say(s, "?");
    check(strcmp(r, "<Idle|MPos:0.000,0.000,0.000|FS:0,0>\r\n") == 0, "grbl third is bare", r);
    r = say(s, "G0 X1?");
    check(strncmp(r, "<Idle|MPos:0.000", 16) == 0, "grbl '?' mid-line is answered at once", r);
    r = say(s, "0\n?");
    check(strstr(r, "ok\r\n<Idle|MPos:10.000,0.000,0.000") == r,
          "grbl '?' was not part of the line (G0 X10 ran)", r);
    close_m(s);
}

/* planner: ok when planned; M2 after the planner empties; hold, resume, reset */
static void grbl_planner(void)
{
    struct sess *s = open_m(SIM_MACHINE_GRBL, 0, 0, 1000.0); /* 1 s per mm */
    const char *r;
    int i;
    drain(s);
    say(s, "G21 G90 F100\n");
    for (i = 1; i <= 16; i++) {
        char l[32];
        snprintf(l, sizeof l, "G1 X%d\n", i);
        put(s, l);
    }
    r = drain(s);
    check(count_of(r, "ok") == 15, "grbl 16 moves: 15 ok while the planner is full", r);
    s->t += 999.0;
    r = drain(s);
    check(count_of(r, "ok") == 0, "grbl no ok before the first block ends", r);
    s->t += 1.0;
    r = drain(s);
    check(count_of(r, "ok") == 1, "grbl the 16th ok when a block finished", r);
    r = say(s, "?");
    check(strncmp(r, "<Run|MPos:1.000,0.000,0.000|FS:100,0", 36) == 0, "grbl Run at X1", r);
    r = say(s, "!?");
    check(strncmp(r, "<Hold:0|MPos:1.000", 18) == 0, "grbl '!' holds", r);
    s->t += 5000.0;
    r = say(s, "?");
    check(strncmp(r, "<Hold:0|MPos:1.000", 18) == 0, "grbl no motion during the hold", r);
    say(s, "~");
    r = say(s, "M2\n");
    check(r[0] == '\0', "grbl M2 waits for the planner to empty", r);
    s->t += 15000.0;
    r = drain(s);
    check(strcmp(r, "[MSG:Pgm End]\r\nok\r\n") == 0, "grbl M2 answers after the last block", r);
    r = say(s, "G0 X20\n");
    s->t += 1000.0;
    r = say(s, "\x18");
    check(strcmp(r, "ALARM:3\r\n") == 0, "grbl reset in motion -> ALARM:3", r);
    s->t += 499.0;
    r = drain(s);
    check(r[0] == '\0', "grbl 500 ms of silence after ALARM:3", r);
    s->t += 1.0;
    r = drain(s);
    check(strcmp(r, "\r\nGrbl 1.1h ['$' for help]\r\n[MSG:'$H'|'$X' to unlock]\r\n") == 0,
          "grbl banner and unlock message after the reset", r);
    r = say(s, "G0 X0\n");
    check(strcmp(r, "error:9\r\n") == 0, "grbl after ALARM:3 blocks are refused", r);
    close_m(s);
}

/* main.c HOMING_INIT_LOCK: with $22=1 the machine starts in Alarm */
static void grbl_homing(void)
{
    struct sess *s = open_m(SIM_MACHINE_GRBL, 1, 0, 0.0);
    const char *r = drain(s);
    check(strcmp(r, "\r\nGrbl 1.1h ['$' for help]\r\n[MSG:'$H'|'$X' to unlock]\r\n") == 0,
          "grbl homing on: boots in Alarm", r);
    r = say(s, "G0 Z5\n");
    check(strcmp(r, "error:9\r\n") == 0, "grbl homing on: G0 Z5 -> error:9", r);
    r = say(s, "$X\n");
    check(strcmp(r, "[MSG:Caution: Unlocked]\r\nok\r\n") == 0, "grbl $X unlocks", r);
    r = say(s, "G0 Z5\n");
    check(strcmp(r, "ok\r\n") == 0, "grbl G0 Z5 accepted after $X", r);
    check(sim_machine_moves(s->m, NULL) == 1, "grbl the motion was recorded", NULL);
    r = say(s, "$H\n");
    check(strcmp(r, "ok\r\n") == 0, "grbl $H -> ok", r);
    r = say(s, "??");
    check(strstr(r, "<Idle|MPos:-1.000,-1.000,-1.000") == r, "grbl homed at -pull-off ($27)", r);
    r = say(s, "$20=1\n");
    check(strcmp(r, "ok\r\n") == 0, "grbl $20=1 (soft limits) with homing on", r);
    r = say(s, "G0 X5\n");
    check(strcmp(r, "ALARM:2\r\n[MSG:Reset to continue]\r\n") == 0,
          "grbl soft limit: X5 is outside [-200, 0] -> ALARM:2", r);
    r = say(s, "?G0 X-5\n");
    check(r[0] == '\0', "grbl after ALARM:2 only a reset is served", r);
    r = say(s, "\x18");
    check(strcmp(r, "ok\r\n\r\nGrbl 1.1h ['$' for help]\r\n[MSG:'$H'|'$X' to unlock]\r\n") == 0,
          "grbl reset: the line's ok, banner, Alarm", r);
    close_m(s);
    s = open_m(SIM_MACHINE_GRBL, 0, 0, 0.0);
    drain(s);
    r = say(s, "$20=1\n");
    check(strcmp(r, "error:10\r\n") == 0, "grbl $20=1 without homing -> error:10", r);
    close_m(s);
}

/* serial.c RX_RING_BUFFER = RX_BUFFER_SIZE + 1: all 128 bytes usable (0.9 had 127); held
 * by '!', the machine reads nothing, so 4 lines of 32 bytes sit in the ring */
static void grbl_ring_exact(void)
{
    static const char ln[] = "G1 X1.0000 Y2.0000 Z0.0000 F100\n"; /* 32 bytes */
    struct sess *s = open_m(SIM_MACHINE_GRBL, 0, 0, 0.0);
    struct sim_machine_opts o;
    struct sim_machine *m127;
    struct sim_machine_verdict v;
    const char *r;
    int i;
    check(sizeof ln - 1 == 32, "grbl test line is 32 bytes", NULL);
    drain(s);
    put(s, "!");
    for (i = 0; i < 4; i++) {
        put(s, ln);
    }
    r = drain(s);
    check(r[0] == '\0' && verdict(s).rx_overflows == 0, "grbl held: 128 bytes wait in the ring",
          r);
    r = say(s, "~");
    check(count_of(r, "ok") == 4, "grbl '~': the 4 lines run, none lost", r);
    close_m(s);
    memset(&o, 0, sizeof o);
    o.rx_size = 127; /* grbl 0.9's ring: the same sender overflows it */
    m127 = sim_machine_new(&o);
    sim_machine_rx(m127, (const uint8_t *)"!", 1, 0.0);
    for (i = 0; i < 4; i++) {
        sim_machine_rx(m127, (const uint8_t *)ln, 32, 0.0);
    }
    sim_machine_verdict(m127, &v);
    check(v.rx_overflows == 1, "grbl a 127-byte ring drops the 128th byte (control)", NULL);
    sim_machine_free(m127);
    s = open_m(SIM_MACHINE_GRBL, 0, 0, 0.0);
    put(s, "!");
    for (i = 0; i < 6; i++) {
        put(s, ln); /* 192 bytes */
    }
    put(s, "G0 X1.0\n"); /* 8 more: 200 */
    check(verdict(s).rx_overflows == 72, "grbl 200 bytes while it reads nothing: 72 dropped",
          NULL);
    close_m(s);
}

/* G4 P is in seconds (mc_dwell, delay_sec in 50 ms steps); M0 holds until '~'; $C; $J */
static void grbl_modes(void)
{
    struct sess *s = open_m(SIM_MACHINE_GRBL, 0, 0, 0.0);
    const char *r;
    drain(s);
    r = say(s, "G4 P0.5\n");
    check(r[0] == '\0', "grbl G4 P0.5 dwells", r);
    s->t += 499.0;
    check(drain(s)[0] == '\0', "grbl no ok before 500 ms", s->out + s->mark);
    s->t += 1.0;
    r = drain(s);
    check(strcmp(r, "ok\r\n") == 0, "grbl G4 P0.5 ok at 500 ms (P in seconds)", r);
    r = say(s, "G4 P1\n");
    s->t += 400.0;
    r = say(s, "!");
    s->t += 5000.0;
    r = say(s, "~");
    check(r[0] == '\0', "grbl a hold pauses a dwell", r);
    s->t += 599.0;
    check(drain(s)[0] == '\0', "grbl the dwell goes on after '~'", s->out + s->mark);
    s->t += 1.0;
    r = drain(s);
    check(strcmp(r, "ok\r\n") == 0, "grbl G4 P1 ok after 1 s of dwelling", r);
    r = say(s, "M0\n?");
    check(strncmp(r, "<Hold:0|", 8) == 0, "grbl M0 is a hold; no ok yet", r);
    r = say(s, "~");
    check(strcmp(r, "ok\r\n") == 0, "grbl M0 answers after '~'", r);
    r = say(s, "$C\n");
    check(strcmp(r, "[MSG:Enabled]\r\nok\r\n") == 0, "grbl $C enables check mode", r);
    r = say(s, "G0 X5\n?");
    check(strstr(r, "ok\r\n<Check|MPos:0.000,0.000,0.000") == r, "grbl check mode: no motion", r);
    r = say(s, "$C\n");
    check(strcmp(r, "[MSG:Disabled]\r\nok\r\n\r\nGrbl 1.1h ['$' for help]\r\n") == 0,
          "grbl $C off is a soft reset", r);
    r = say(s, "$J=G91 X1 F100\n?");
    check(strstr(r, "ok\r\n<Idle|MPos:1.000") == r || strstr(r, "ok\r\n<Jog|") == r,
          "grbl $J= jogs", r);
    r = say(s, "$J=X1\n");
    check(strcmp(r, "error:22\r\n") == 0, "grbl $J= without F -> error:22", r);
    check(sim_machine_moves(s->m, NULL) == 1, "grbl moves: the $C one recorded, the jog not",
          NULL);
    close_m(s);
}

static const char *const good_grbl[] = {"G21 G90 G17 G94 G54\n", "M3 S10000\n", "G0 Z10\n",
                                        "G0 X1 Y1\n", "G1 X1 Y1 Z0 F100\n", "G1 X2 Y1 Z0 F600\n",
                                        "G0 Z10\n", "M5\n", "M2\n"};

/* run good_grbl with line `drop` left out (-1: none) and `extra` inserted before line 2 */
static struct sim_machine_verdict run_program(enum sim_machine_kind kind, int drop,
                                              const char *extra, const char *end)
{
    struct sess *s = open_m(kind, 0, 0, 0.0);
    struct sim_machine_verdict v;
    size_t i;
    for (i = 0; i < sizeof good_grbl / sizeof good_grbl[0]; i++) {
        if (i == 2 && extra != NULL) {
            put(s, extra);
        }
        if ((int)i == drop) {
            continue;
        }
        if (end != NULL && i == 8) {
            put(s, end);
            continue;
        }
        if (kind == SIM_MACHINE_MARLIN && i == 0) {
            put(s, "G21\nG90\n"); /* Marlin runs only the first command of a line */
            continue;
        }
        put(s, good_grbl[i]);
        s->t += 6000.0; /* Marlin's spindle delays */
        drain(s);
    }
    s->t += 20000.0;
    drain(s);
    v = verdict(s);
    close_m(s);
    return v;
}

static struct sim_machine_verdict run_lines(enum sim_machine_kind kind, const char *const *l,
                                            size_t n)
{
    struct sess *s = open_m(kind, 0, 0, 0.0);
    struct sim_machine_verdict v;
    size_t i;
    for (i = 0; i < n; i++) {
        put(s, l[i]);
        s->t += 6000.0;
        drain(s);
    }
    v = verdict(s);
    close_m(s);
    return v;
}

static void grbl_program(void)
{
    static const char *const low_retract[] = {"G21 G90 G17 G94 G54\n", "M3 S10000\n", "G0 Z10\n",
                                              "G0 X1 Y1\n", "G1 X1 Y1 Z0 F100\n", "G0 Z5\n",
                                              "M5\n", "M2\n"};
    static const char *const low_rapid[] = {"G21 G90\n", "G0 Z10\n", "G0 X5 Y5 Z2\n", "M2\n"};
    struct sim_machine_verdict v = run_program(SIM_MACHINE_GRBL, -1, NULL, NULL);
    check(v.started_safe && v.ended_safe && v.units_mm && v.absolute && v.spindle_off_at_end &&
              v.program_end && v.first_problem[0] == '\0' && v.errors == 0,
          "grbl good program: clean verdict", v.first_problem);
    v = run_program(SIM_MACHINE_GRBL, 6, NULL, NULL);
    check(!v.ended_safe && strstr(v.first_problem, "retract") != NULL,
          "grbl no final retract breaks ended_safe", v.first_problem);
    v = run_program(SIM_MACHINE_GRBL, -1, "G1 X0 Y0 Z-1 F100\n", NULL);
    check(!v.started_safe && v.feed_before_safe == 1 &&
              strstr(v.first_problem, "before the first rapid") != NULL,
          "grbl G1 before G0 Z breaks started_safe", v.first_problem);
    v = run_program(SIM_MACHINE_GRBL, 7, NULL, NULL);
    check(!v.spindle_off_at_end && !v.ended_safe && strstr(v.first_problem, "M5") != NULL,
          "grbl no M5 breaks spindle_off_at_end", v.first_problem);
    v = run_lines(SIM_MACHINE_GRBL, low_retract, 8);
    check(!v.ended_safe && v.program_end && strstr(v.first_problem, "retract") != NULL,
          "grbl a retract below the safe height is no retract", v.first_problem);
    v = run_lines(SIM_MACHINE_GRBL, low_rapid, 4);
    check(v.rapid_below_safe == 1 && strstr(v.first_problem, "line 3: rapid move in XY") != NULL,
          "grbl a rapid in XY below the safe height", v.first_problem);
    v = run_program(SIM_MACHINE_GRBL, 8, NULL, NULL);
    check(!v.program_end && strstr(v.first_problem, "M2") != NULL, "grbl no M2: no program end",
          v.first_problem);
}

/* ---------------------------------------------------------------- Marlin */

static void ml_line(char *buf, size_t cap, const char *body)
{
    snprintf(buf, cap, "%s*%u\n", body, xor_cs(body));
}

/* queue.cpp: line numbers, checksums, Resend, comments */
static void marlin_protocol(void)
{
    struct sess *s = open_m(SIM_MACHINE_MARLIN, 0, 0, 0.0);
    char l[128];
    const char *r = drain(s);
    check(r[0] == '\0', "marlin says nothing at power-up here", r);
    check(xor_cs("N0 M110 N0") == 125, "marlin checksum of N0 M110 N0 is 125", NULL);
    r = say(s, "N0 M110 N0*125\n");
    check(strcmp(r, "ok\n") == 0, "marlin N0 M110 N0*125 -> ok", r);
    ml_line(l, sizeof l, "N1 G1 X1");
    r = say(s, l);
    check(strcmp(r, "ok\n") == 0, "marlin N1 G1 X1*<good> -> ok", r);
    r = say(s, "N2 G1 X2*0\n");
    check(strcmp(r, "Error:checksum mismatch, Last Line: 1\nResend: 2\nok\n") == 0,
          "marlin bad checksum -> Error + Resend + ok", r);
    r = say(s, "N2 G1 X2\n");
    check(strcmp(r, "Error:No Checksum with line number, Last Line: 1\nResend: 2\nok\n") == 0,
          "marlin N without checksum -> Error + Resend + ok", r);
    ml_line(l, sizeof l, "N5 G1 X2");
    r = say(s, l);
    check(strcmp(r, "Error:Line Number is not Last Line Number+1, Last Line: 1\nResend: 2\nok\n") ==
              0,
          "marlin wrong line number -> Error + Resend + ok", r);
    check(verdict(s).resends == 3 && verdict(s).errors == 3, "marlin verdict counts 3 resends",
          NULL);
    r = say(s, "; only a comment\n\n");
    check(r[0] == '\0', "marlin comment-only/empty lines get no answer", r);
    r = say(s, "   \n");
    check(strcmp(r, "echo:Unknown command: \"\"\nok\n") == 0,
          "marlin a line of spaces is not empty: Unknown command \"\"", r);
    r = say(s, "M2\n");
    check(strcmp(r, "echo:Unknown command: \"M2\"\nok\n") == 0, "marlin M2 -> Unknown command", r);
    r = say(s, "(comment)\n");
    check(strcmp(r, "echo:Unknown command: \"(comment)\"\nok\n") == 0,
          "marlin (comment) is no comment (PAREN_COMMENTS off)", r);
    r = say(s, "G1 X3*99\n");
    check(strcmp(r, "ok\n") == 0, "marlin '*' without N is not checked", r);
    r = say(s, "G17\n");
    check(strcmp(r, "echo:Unknown command: \"G17\"\nok\n") == 0, "marlin G17 unknown (stock)", r);
    r = say(s, "M114\n");
    check(strcmp(r, "X:3.00 Y:0.00 Z:0.00 E:0.00 Count X:240 Y:0 Z:0\nok\n") == 0, "marlin M114",
          r);
    close_m(s);
}

static void marlin_rules(void)
{
    struct sess *s = open_m(SIM_MACHINE_MARLIN, 0, 1, 0.0);
    struct sim_machine_verdict v;
    char l[160];
    unsigned p = 0, b = 0;
    const char *r;
    drain(s);
    ml_line(l, sizeof l, "N1 G1 X1");
    r = say(s, l);
    check(strcmp(r, "ok N1 P14 B3\n") == 0, "marlin ADVANCED_OK: ok N1 P14 B3 (block planned)", r);
    r = say(s, "G0 X0\n");
    check(sscanf(r, "ok P%u B%u\n", &p, &b) == 2 && p == 14 && b == 3,
          "marlin ADVANCED_OK without N: ok P14 B3", r);
    r = say(s, "G21 G90 G17\n");
    v = verdict(s);
    check(strncmp(r, "ok P", 4) == 0 && v.ignored_words == 1 && !v.absolute,
          "marlin G21 G90 G17: G21 only (G90 never ran)", r);
    check(strstr(v.first_problem, "line 1: first motion before G21 and G90") != NULL,
          "marlin first_problem: the first rule broken (motion before G21/G90)", v.first_problem);
    close_m(s);
    s = open_m(SIM_MACHINE_MARLIN, 0, 0, 0.0);
    say(s, "G21 G90 G17\n");
    v = verdict(s);
    check(strstr(v.first_problem, "words after the command ignored") != NULL,
          "marlin first_problem: words after the command ignored", v.first_problem);
    say(s, "G1 X1 Y1\n");
    check(verdict(s).g1_without_feed == 1, "marlin G1 without F runs but is a defect", NULL);
    memset(l, 0, sizeof l);
    strcpy(l, "G1 X1 Y2 Z3");
    memset(l + strlen(l), ' ', 90);
    strcat(l, "X9\n"); /* 103 characters: X9 lies beyond the 95th */
    r = say(s, l);
    check(strcmp(r, "ok\n") == 0 && verdict(s).long_lines == 1,
          "marlin a 103-character line is cut at 95 and still run", r);
    r = say(s, "M114\n");
    check(strncmp(r, "X:1.00 Y:2.00 Z:3.00", 20) == 0, "marlin the cut X9 never arrived", r);
    close_m(s);
}

/* gcode.cpp host_keepalive, queue.cpp: RX fills while the queue is full */
static void marlin_timing(void)
{
    struct sess *s = open_m(SIM_MACHINE_MARLIN, 0, 0, 1000.0); /* 1 s per mm */
    char buf[2048] = "";
    const char *r;
    int i;
    drain(s);
    r = say(s, "G1 X10 F100\n");
    check(strcmp(r, "ok\n") == 0, "marlin G1 answered when planned", r);
    r = say(s, "M400\n");
    check(r[0] == '\0', "marlin M400 waits", r);
    s->t += 1999.0;
    r = drain(s);
    check(r[0] == '\0', "marlin no busy before 2000 ms", r);
    s->t += 1.0;
    r = drain(s);
    check(strcmp(r, "echo:busy: processing\n") == 0, "marlin echo:busy: processing at 2000 ms", r);
    s->t += 2000.0;
    r = drain(s);
    check(strcmp(r, "echo:busy: processing\n") == 0, "marlin busy again at 4000 ms", r);
    s->t += 6099.0;
    r = drain(s);
    check(strcmp(r, "echo:busy: processing\necho:busy: processing\necho:busy: processing\n") == 0,
          "marlin busy at 6, 8, 10 s; no ok at 10.099 s", r);
    s->t += 1.0;
    r = drain(s);
    check(strcmp(r, "ok\n") == 0,
          "marlin M400 ok at 10.1 s: the 10 s move after the 100 ms first-block delay", r);
    close_m(s);
    s = open_m(SIM_MACHINE_MARLIN, 0, 0, 1000.0);
    drain(s);
    for (i = 0; i < 30; i++) {
        strcat(buf, "G1 X1 F100\nG1 X0 F100\n");
    }
    put(s, buf);
    check(verdict(s).rx_overflows > 0, "marlin 660 bytes at once overflow the 127-byte ring",
          NULL);
    close_m(s);
}

/* M3-M5.cpp: sync, then SPINDLE_LASER_POWERUP_DELAY 5000 ms; G4 P in ms; M112 kill */
static void marlin_spindle(void)
{
    struct sess *s = open_m(SIM_MACHINE_MARLIN, 0, 0, 0.0);
    const char *r;
    drain(s);
    r = say(s, "M3 S1000\n");
    check(r[0] == '\0', "marlin M3 waits for the spindle", r);
    s->t += 4999.0;
    r = drain(s);
    check(strcmp(r, "echo:busy: processing\necho:busy: processing\n") == 0,
          "marlin busy twice during the 5 s spin-up", r);
    s->t += 1.0;
    r = drain(s);
    check(strcmp(r, "ok\n") == 0, "marlin M3 ok after SPINDLE_LASER_POWERUP_DELAY", r);
    r = say(s, "G4 P300\n");
    s->t += 299.0;
    r = drain(s);
    check(r[0] == '\0', "marlin G4 P300 dwells", r);
    s->t += 1.0;
    r = drain(s);
    check(strcmp(r, "ok\n") == 0, "marlin G4 P300 ok at 300 ms (P in ms)", r);
    r = say(s, "M112\nM114\n");
    check(strcmp(r, "Error:Printer halted. kill() called!\n") == 0, "marlin M112 kills", r);
    s->t += 10000.0;
    r = say(s, "M114\n");
    check(r[0] == '\0', "marlin killed: no more answers", r);
    close_m(s);
    {
        struct sim_machine_opts o;
        struct sim_machine *m;
        uint8_t out[128];
        size_t n;
        memset(&o, 0, sizeof o);
        o.kind = SIM_MACHINE_MARLIN;
        o.marlin_no_spindle = 1;
        m = sim_machine_new(&o);
        sim_machine_rx(m, (const uint8_t *)"M3 S1\n", 6, 0.0);
        n = sim_machine_tx(m, 0.0, out, sizeof out - 1);
        out[n] = 0;
        check(strcmp((char *)out, "echo:Unknown command: \"M3 S1\"\nok\n") == 0,
              "marlin without SPINDLE_FEATURE: M3 unknown", (char *)out);
        sim_machine_free(m);
    }
}

static void marlin_program(void)
{
    struct sim_machine_verdict v = run_program(SIM_MACHINE_MARLIN, -1, NULL, "M400\n");
    check(v.started_safe && v.ended_safe && v.units_mm && v.absolute && v.spindle_off_at_end &&
              v.program_end && v.first_problem[0] == '\0',
          "marlin good program (M400 end): clean verdict", v.first_problem);
    v = run_program(SIM_MACHINE_MARLIN, -1, NULL, NULL);
    check(v.unknown == 1 && strstr(v.first_problem, "M2") != NULL,
          "marlin M2 at the end is an unknown command", v.first_problem);
    v = run_program(SIM_MACHINE_MARLIN, 6, NULL, "M400\n");
    check(!v.ended_safe && strstr(v.first_problem, "retract") != NULL,
          "marlin no final retract breaks ended_safe", v.first_problem);
}

int main(void)
{
    grbl_section8();
    grbl_lines();
    grbl_overflow();
    grbl_realtime();
    grbl_planner();
    grbl_homing();
    grbl_ring_exact();
    grbl_modes();
    grbl_program();
    marlin_protocol();
    marlin_rules();
    marlin_timing();
    marlin_spindle();
    marlin_program();
    printf("machine: %d passed, %d failed\n", n_pass, n_fail);
    return n_fail ? 1 : 0;
}
