/* test_machine.c - two links and machine dialects over two in-memory HALs: the program
 * each dialect gets (complete, nothing the machine would reject), the machine's answers
 * parsed by dialect (ADVANCED_OK, busy, chatter with real-time bytes, errors with the
 * machine's code in the host's reply), pass-through while idle, the poll of a silent grbl.
 * Each test names the defect of issue 17 it guards against.
 * SPDX-License-Identifier: MIT
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hal_mem.h"
#include "proto.h"
#include "test.h"

#define TM_PI 3.14159265358979323846

struct link_end {
    struct hal_mem m;
    struct hal_uart u;
    size_t scan; /* bytes of m.out already taken as lines */
};

static struct {
    struct link_end host, mach;
    struct proto p;
} rg;

/* Start an engine: with a machine link (two) or without (one). */
static int rig(int two)
{
    struct proto_cfg cfg = {0};
    memset(&rg, 0, sizeof rg);
    hal_mem_init(&rg.host.m, &rg.host.u);
    hal_mem_init(&rg.mach.m, &rg.mach.u);
    rg.host.m.tick_ms = 1;
    cfg.uart = &rg.host.u;
    cfg.machine = two ? &rg.mach.u : NULL;
    return proto_init(&rg.p, &cfg) == CP_OK;
}

static void send_to(struct link_end *e, const char *s)
{
    if (e->m.in_pos == e->m.in_len) {
        e->m.in_pos = e->m.in_len = 0;
    }
    (void)hal_mem_feed_str(&e->m, s);
}

/* The next complete line e received (no '\n'), within `polls` polls; 0 if none. */
static int line_of(struct link_end *e, char *buf, size_t cap, int polls)
{
    int i;
    for (i = 0; i <= polls; i++) {
        size_t k;
        for (k = e->scan; k < e->m.out_len; k++) {
            if (e->m.out[k] == '\n') {
                size_t n = k - e->scan < cap - 1u ? k - e->scan : cap - 1u;
                memcpy(buf, e->m.out + e->scan, n);
                buf[n] = '\0';
                e->scan = k + 1u;
                return 1;
            }
        }
        (void)proto_poll(&rg.p);
    }
    return 0;
}

/* A command on the host link; 1 if its final reply is `want` ("ok" or an "error:N" prefix). */
static int cmd(const char *c, const char *want)
{
    char l[200];
    send_to(&rg.host, c);
    send_to(&rg.host, "\n");
    while (line_of(&rg.host, l, sizeof l, 2000)) {
        if (l[0] == '[' || l[0] == '<') {
            continue;
        }
        if (strncmp(l, want, strlen(want)) == 0) {
            return 1;
        }
        printf("  \"%s\" -> \"%s\", want \"%s\"\n", c, l, want);
        return 0;
    }
    printf("  \"%s\": no reply\n", c);
    return 0;
}

static const char *const paper[] = {"CURVE ARC 0 0 3 0 360", "RADIUS COS 5.5 10.5 2",
                                    "LINES 3 -25 10",        "STEPS 40",
                                    "SAFE 30",               NULL};

static int load(const char *const *c)
{
    for (; *c != NULL; c++) {
        if (!cmd(*c, "ok")) {
            return 0;
        }
    }
    return 1;
}

/* A two-link rig with the paper's job for MACHINE m on the machine link, FEED f. */
static int cell(const char *m, const char *feed)
{
    char c[40];
    snprintf(c, sizeof c, "MACHINE %s", m);
    return rig(1) && load(paper) && cmd(c, "ok") && cmd("LINK MACHINE", "ok") && cmd(feed, "ok");
}

/* Send RUN and poll until the run has started (its "[RUN:" header is on the host link). */
static int start_run(void)
{
    int i;
    send_to(&rg.host, "RUN\n");
    for (i = 0; i < 100 && rg.p.state == PROTO_IDLE; i++) {
        (void)proto_poll(&rg.p);
    }
    return rg.p.state != PROTO_IDLE;
}

/* What the machine link carried during one run, as a real machine would judge it. */
struct program {
    unsigned lines, g1, g0, feeds, max_len, bad;
    int spindle_on_before_cut, ended_safe, retract_after_cut, modes_first;
    char first[200], last[200], first_bad[200];
    char fwords[8][24]; /* the first F words, in order */
};

static void note_bad(struct program *pr, const char *l)
{
    if (pr->bad++ == 0u) {
        snprintf(pr->first_bad, sizeof pr->first_bad, "%s", l);
    }
}

/* Play a machine on the machine link until the host gets its final reply: answer each
 * line with `ok_text` after `lag` lines; record the program. Returns the host's final
 * reply line in `final`. */
static int play_machine(struct program *pr, const char *ok_text, int lag, char *final, size_t cap)
{
    char l[200];
    int pending = 0, i;
    memset(pr, 0, sizeof *pr);
    for (i = 0; i < 400000; i++) {
        size_t n;
        while (line_of(&rg.mach, l, sizeof l, 0)) {
            n = strlen(l);
            pr->lines++;
            pending++;
            if (n > pr->max_len) {
                pr->max_len = (unsigned)n;
            }
            if (pr->lines == 1u) {
                snprintf(pr->first, sizeof pr->first, "%s", l);
            }
            snprintf(pr->last, sizeof pr->last, "%s", l);
            if (l[0] == '[' || l[0] == '<' || strncmp(l, "ok", 2) == 0 || strchr(l, '*') != NULL) {
                note_bad(pr, l); /* grbl: error:1 / error:2 (PROTOCOL-NOTES §8) */
            }
            if (l[0] == 'N' && strchr(l, ' ') != NULL) { /* N<n> <line>*<cs>: the line */
                memmove(l, strchr(l, ' ') + 1, strlen(strchr(l, ' ') + 1) + 1u);
            }
            if (strncmp(l, "G1 ", 3) == 0) {
                const char *f = strstr(l, " F");
                pr->g1++;
                if (f != NULL) {
                    if (pr->feeds < 8u) {
                        snprintf(pr->fwords[pr->feeds], sizeof pr->fwords[0], "%s", f + 1);
                    }
                    pr->feeds++;
                } else if (pr->g1 == 1u) {
                    note_bad(pr, l); /* grbl error:22: the first feed move has no F */
                }
            } else if (strncmp(l, "G0 ", 3) == 0) {
                pr->g0++;
            }
        }
        while (pending > lag) {
            send_to(&rg.mach, ok_text);
            pending--;
        }
        if (line_of(&rg.host, final, cap, 0) && final[0] != '[') {
            return 1;
        }
        (void)proto_poll(&rg.p);
        if (rg.p.run.next >= rg.p.run.end) {
            lag = 0; /* everything sent: answer what is left */
        }
    }
    return 0;
}

/* Issue 17: "[RUN:...]" and the firmware's own "ok" reached grbl (error:1, error:2), no F
 * (error:22), no preamble, safe moves or program end. Two links, MACHINE GRBL: the
 * machine link carries exactly a complete grbl program. */
int test_machine_grbl_program(void)
{
    struct program pr;
    char fin[200], hdr[200];
    CHECK(rig(1));
    CHECK(load(paper));
    CHECK(cmd("MACHINE GRBL", "ok"));
    CHECK(cmd("LINK MACHINE", "ok"));
    CHECK(cmd("SPINDLE 12000", "ok"));
    CHECK(cmd("WCS G55", "ok"));
    CHECK(cmd("FEED 600 100 300", "ok"));
    send_to(&rg.host, "RUN\n");
    CHECK(line_of(&rg.host, hdr, sizeof hdr, 100));
    CHECK(strncmp(hdr, "[RUN:points=", 12) == 0); /* the metadata: host link only */
    CHECK(play_machine(&pr, "ok\n", 3, fin, sizeof fin));
    CHECK(strcmp(fin, "ok") == 0);
    if (pr.bad) {
        printf("  grbl would reject \"%s\"\n", pr.first_bad);
    }
    CHECK_EQ_INT(pr.bad, 0);
    CHECK(strcmp(pr.first, "G21 G90 G17 G94 G55") == 0);
    CHECK(strcmp(pr.last, "M2") == 0);
    CHECK_EQ_INT(pr.g1, path_count(&rg.p.path)); /* one feed move per point */
    CHECK_EQ_INT(pr.g0, 3u); /* safe Z, above the first point, the retract */
    CHECK(pr.max_len <= 79u); /* grbl's LINE_BUFFER_SIZE */
    /* modal F: the plunge's, the cut's, then link feed and cut feed in turn, never repeated */
    CHECK(strcmp(pr.fwords[0], "F100") == 0 && strcmp(pr.fwords[1], "F600") == 0 &&
          strcmp(pr.fwords[2], "F300") == 0 && strcmp(pr.fwords[3], "F600") == 0);
    CHECK_EQ_INT(pr.feeds, 2u + 2u * (rg.p.path.info.n - 1u));
    printf("  note: grbl program: %u lines, %u feed moves, %u F words, longest %u chars\n",
           pr.lines, pr.g1, pr.feeds, pr.max_len);
    return 0;
}

/* Marlin: one command per line ("G21 G90" would leave G90 unset), N and * with M110 first,
 * M400 as the end, ADVANCED_OK's "ok N.. P.. B.." understood (it once timed out). */
int test_machine_marlin_program(void)
{
    struct program pr;
    char fin[200], hdr[200];
    CHECK(rig(1));
    CHECK(load(paper));
    CHECK(cmd("MACHINE MARLIN", "ok"));
    CHECK(cmd("LINK MACHINE", "ok"));
    CHECK(cmd("CHECKSUM ON", "ok"));
    CHECK(cmd("FEED 0.05", "ok"));
    send_to(&rg.host, "RUN\n");
    CHECK(line_of(&rg.host, hdr, sizeof hdr, 100));
    CHECK(play_machine(&pr, "ok N2 P15 B3\n", 2, fin, sizeof fin));
    CHECK(strcmp(fin, "ok") == 0);
    CHECK(strncmp(pr.first, "N0 M110 N0*", 11) == 0);
    CHECK(strstr(pr.last, " M400*") != NULL);
    CHECK(pr.max_len <= 95u); /* Marlin's MAX_CMD_SIZE */
    CHECK(strncmp(pr.fwords[0], "F0.05*", 6) == 0);
    CHECK_EQ_INT(pr.feeds, 1u); /* plunge, cut and links at 0.05: one F, exact */
    CHECK_EQ_INT(pr.g1, path_count(&rg.p.path));
    return 0;
}

/* Marlin's "echo:busy: processing" every 2 s keeps a long M400 alive past the 10 s
 * answer timeout (it once held the run, then timed out); a silent one times out. */
int test_machine_busy_keepalive(void)
{
    char l[200];
    int i, busy = 0, lines = 0;
    CHECK(cell("MARLIN", "FEED 600"));
    CHECK(cmd("STEPS 1", "ok"));
    CHECK(cmd("LINES 1 0 0", "ok"));
    rg.host.m.tick_ms = 5;
    CHECK(start_run());
    for (i = 0; i < 200000 && rg.p.state != PROTO_IDLE; i++) {
        while (line_of(&rg.mach, l, sizeof l, 0)) {
            lines++;
            if (strcmp(l, "M400") != 0) {
                send_to(&rg.mach, "ok\n");
            }
        }
        if (rg.host.m.now / 2000u > (uint32_t)busy) { /* the keep-alive, every 2 s */
            busy++;
            send_to(&rg.mach, "echo:busy: processing\n");
        }
        if (busy == 15) { /* 30 s of M400: the moves end, its ok */
            send_to(&rg.mach, "ok\n");
            busy++;
        }
        (void)proto_poll(&rg.p);
    }
    CHECK(rg.host.m.now > 30000u);
    while (line_of(&rg.host, l, sizeof l, 10) && l[0] == '[') {
    }
    CHECK(strcmp(l, "ok") == 0);
    return 0;
}

/* A machine error stops the job with the machine's own code in the host's reply. */
int test_machine_error_code(void)
{
    char l[200];
    int i, n = 0;
    CHECK(cell("GRBL", "FEED 600"));
    CHECK(start_run());
    for (i = 0; i < 20000 && rg.p.state != PROTO_IDLE; i++) {
        while (line_of(&rg.mach, l, sizeof l, 0)) {
            send_to(&rg.mach, ++n == 5 ? "ALARM:1\n" : "ok\n");
        }
        (void)proto_poll(&rg.p);
    }
    while (line_of(&rg.host, l, sizeof l, 10) && l[0] == '[') {
    }
    CHECK(strcmp(l, "error:19 machine reported an error (machine ALARM:1)") == 0);
    return 0;
}

/* One link (the host takes the G-code): a '?' inside the machine's chatter is text, not
 * a status request (echo:Unknown command: "M999?" once produced a report in the stream). */
int test_machine_chatter_realtime(void)
{
    char l[200];
    int i, reports = 0, done = 0;
    CHECK(rig(0));
    CHECK(load(paper));
    CHECK(cmd("FEED 600", "ok"));
    send_to(&rg.host, "RUN\n");
    for (i = 0; i < 400000 && !done; i++) {
        while (line_of(&rg.host, l, sizeof l, 0)) {
            if (l[0] == '<') {
                reports++;
            } else if (strcmp(l, "ok") == 0 || strncmp(l, "error:", 6) == 0) {
                done = 1;
                break;
            } else if (l[0] == 'G' || l[0] == 'M') {
                send_to(&rg.host, "echo:Unknown command: \"M999?\"\nok\n");
            }
        }
        (void)proto_poll(&rg.p);
    }
    CHECK(done && strcmp(l, "ok") == 0);
    CHECK_EQ_INT(reports, 0);
    return 0;
}

/* Idle pass-through: "$H" reaches the machine, its answer comes back as it is; an
 * unasked machine line comes up wrapped; host bytes wait while the machine answers. */
int test_machine_pass_through(void)
{
    char l[200];
    CHECK(rig(1));
    CHECK(cmd("$H", "error:1 ")); /* the cell is not wired yet: not a command */
    CHECK(cmd("LINK MACHINE", "ok"));
    send_to(&rg.host, "$H\n");
    CHECK(line_of(&rg.mach, l, sizeof l, 100));
    CHECK(strcmp(l, "$H") == 0);
    send_to(&rg.host, "$X\n"); /* waits: the machine has not answered $H */
    CHECK(!line_of(&rg.mach, l, sizeof l, 50));
    send_to(&rg.mach, "[MSG:Homed]\nok\n");
    CHECK(line_of(&rg.host, l, sizeof l, 100) && strcmp(l, "[MSG:Homed]") == 0);
    CHECK(line_of(&rg.host, l, sizeof l, 100) && strcmp(l, "ok") == 0);
    CHECK(line_of(&rg.mach, l, sizeof l, 100) && strcmp(l, "$X") == 0);
    send_to(&rg.mach, "error:9\n");
    CHECK(line_of(&rg.host, l, sizeof l, 100) && strcmp(l, "error:9") == 0);
    send_to(&rg.mach, "Grbl 1.1h ['$' for help]\n");
    CHECK(line_of(&rg.host, l, sizeof l, 100) &&
          strcmp(l, "[MACHINE:Grbl 1.1h ['$' for help]]") == 0);
    CHECK(cmd("$I", "ok")); /* the firmware's own commands stay its own */
    /* a machine that never answers: the host gets error:22, then the link is free */
    rg.host.m.tick_ms = 50;
    send_to(&rg.host, "G0 X1\n");
    CHECK(line_of(&rg.mach, l, sizeof l, 100) && strcmp(l, "G0 X1") == 0);
    CHECK(line_of(&rg.host, l, sizeof l, 2000) && strncmp(l, "error:22 ", 9) == 0);
    CHECK(cmd("$I", "ok"));
    CHECK(cmd("JOB CLEAR", "ok")); /* the wiring outlives the job */
    send_to(&rg.host, "$X\n");
    CHECK(line_of(&rg.mach, l, sizeof l, 100) && strcmp(l, "$X") == 0);
    send_to(&rg.mach, "ok\n");
    CHECK(line_of(&rg.host, l, sizeof l, 100) && strcmp(l, "ok") == 0);
    /* one link: no pass-through, an unknown line is an error */
    CHECK(rig(0));
    CHECK(cmd("$H", "error:1 "));
    return 0;
}

/* A silent grbl (a long move) is asked '?' after OUT_GCODE_POLL_MS; its status report
 * keeps the run alive past the answer timeout. */
int test_machine_grbl_poll(void)
{
    char l[200];
    int i, polls = 0, lines = 0, held = 1;
    CHECK(cell("GRBL", "FEED 600"));
    rg.host.m.tick_ms = 5;
    CHECK(start_run());
    for (i = 0; i < 100000 && rg.p.state != PROTO_IDLE; i++) {
        size_t k;
        for (k = rg.mach.scan; k < rg.mach.m.out_len; k++) {
            if (rg.mach.m.out[k] == '?') { /* a real-time byte: not part of a line */
                polls++;
                memmove(rg.mach.m.out + k, rg.mach.m.out + k + 1, rg.mach.m.out_len - k - 1u);
                rg.mach.m.out_len--;
                send_to(&rg.mach, "<Run|MPos:1.000,2.000,3.000|FS:600,0>\n");
                k--;
            }
        }
        while (line_of(&rg.mach, l, sizeof l, 0)) {
            if (++lines > 3 && held && rg.host.m.now < 25000u) {
                continue; /* a long move: no ok for 20 s */
            }
            send_to(&rg.mach, "ok\n");
        }
        if (held && rg.host.m.now >= 25000u) {
            held = 0;
            for (k = 3; k < (size_t)lines; k++) {
                send_to(&rg.mach, "ok\n");
            }
        }
        (void)proto_poll(&rg.p);
    }
    while (line_of(&rg.host, l, sizeof l, 10) && l[0] == '[') {
    }
    CHECK(strcmp(l, "ok") == 0);
    CHECK(polls >= 5);
    printf("  note: grbl polled %d times during a 20 s move\n", polls);
    return 0;
}

/* LinuxCNC takes a program file: no acknowledgements, the link alone paces it. */
int test_machine_linuxcnc(void)
{
    char l[200], fin[200];
    unsigned g1 = 0;
    int i;
    CHECK(cell("LINUXCNC", "FEED 600"));
    send_to(&rg.host, "RUN\n");
    CHECK(line_of(&rg.host, fin, sizeof fin, 100) && fin[0] == '[');
    fin[0] = '\0';
    for (i = 0; i < 200000 && fin[0] == '\0'; i++) {
        while (line_of(&rg.mach, l, sizeof l, 0)) {
            g1 += strncmp(l, "G1 ", 3) == 0;
        }
        if (!line_of(&rg.host, fin, sizeof fin, 0)) {
            fin[0] = '\0';
        }
    }
    while (line_of(&rg.mach, l, sizeof l, 0)) {
        g1 += strncmp(l, "G1 ", 3) == 0;
    }
    CHECK(strcmp(fin, "ok") == 0);
    CHECK_EQ_INT(g1, path_count(&rg.p.path));
    CHECK(strcmp(l, "M2") == 0);
    return 0;
}

/* TOOLAXIS: the words recovered (A/C, or I J K) against the streamed normal and the travel
 * (in double, from the program's own points): the angle to the normal is
 * acos(cos lead cos side), the lead leans along the travel, the side to its left; machines
 * that cannot take the words refuse the job at RUN (grbl would answer A/C with error:20,
 * Marlin ignore them). */
int test_machine_toolaxis(void)
{
    static const struct {
        const char *machine, *axis;
        double lead, side;
    } cases[] = {{"LINUXCNC", "AC", 0.0, 0.0}, {"LINUXCNC", "AC", 10.0, 0.0},
                 {"GENERIC", "IJK", 0.0, 12.5}, {"GENERIC", "IJK", -7.0, 5.0}};
    char l[200], c[64];
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        double prev[3] = {0, 0, 0}, worst = 0.0, want;
        unsigned n = 0, j;
        int have_prev = 0, k;
        CHECK(rig(1));
        CHECK(load(paper));
        snprintf(c, sizeof c, "MACHINE %s", cases[i].machine);
        CHECK(cmd(c, "ok"));
        CHECK(cmd("LINK MACHINE", "ok"));
        CHECK(cmd("FEED 600", "ok"));
        snprintf(c, sizeof c, "TOOLAXIS %s %g %g", cases[i].axis, cases[i].lead, cases[i].side);
        CHECK(cmd(c, "ok"));
        CHECK(start_run());
        want = acos(cos(cases[i].lead * TM_PI / 180.0) * cos(cases[i].side * TM_PI / 180.0));
        for (k = 0; k < 200000 && rg.p.state != PROTO_IDLE; k++) {
            while (line_of(&rg.mach, l, sizeof l, 0)) {
                struct raster_pt pt;
                double a[3], p[3], d[3], nn[3], t[3], s[3], dn, tl, ang, al, sd;
                if (strncmp(l, "G1 ", 3) != 0) {
                    if (machine_dialect(rg.p.job.machine)->acks) {
                        send_to(&rg.mach, "ok\n");
                    }
                    continue;
                }
                p[0] = strtod(strstr(l, " X") + 2, NULL);
                p[1] = strtod(strstr(l, " Y") + 2, NULL);
                p[2] = strtod(strstr(l, " Z") + 2, NULL);
                if (strstr(l, " A") != NULL) {
                    double A = strtod(strstr(l, " A") + 2, NULL) * TM_PI / 180.0;
                    double C = strtod(strstr(l, " C") + 2, NULL) * TM_PI / 180.0;
                    a[0] = sin(A) * sin(C);
                    a[1] = -sin(A) * cos(C);
                    a[2] = cos(A);
                } else {
                    a[0] = strtod(strstr(l, " I") + 2, NULL);
                    a[1] = strtod(strstr(l, " J") + 2, NULL);
                    a[2] = strtod(strstr(l, " K") + 2, NULL);
                }
                /* the streamed normal of this point (the iterator's, exact as streamed) */
                CHECK(path_seek(&rg.p.path, n) == CP_OK && path_next(&rg.p.path, &pt) == CP_OK);
                tl = sqrt((double)pt.n.x * pt.n.x + (double)pt.n.y * pt.n.y + (double)pt.n.z * pt.n.z);
                nn[0] = pt.n.x / tl;
                nn[1] = pt.n.y / tl;
                nn[2] = pt.n.z / tl;
                s[0] = a[1] * nn[2] - a[2] * nn[1]; /* the angle, well conditioned near 0 */
                s[1] = a[2] * nn[0] - a[0] * nn[2];
                s[2] = a[0] * nn[1] - a[1] * nn[0];
                ang = atan2(sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]),
                            a[0] * nn[0] + a[1] * nn[1] + a[2] * nn[2]);
                worst = fmax(worst, fabs(ang - want));
                if (have_prev && (cases[i].lead != 0.0 || cases[i].side != 0.0)) {
                    for (j = 0; j < 3; j++) {
                        d[j] = p[j] - prev[j];
                    }
                    dn = d[0] * nn[0] + d[1] * nn[1] + d[2] * nn[2];
                    for (j = 0; j < 3; j++) {
                        t[j] = d[j] - dn * nn[j];
                    }
                    tl = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
                    for (j = 0; j < 3; j++) {
                        t[j] /= tl;
                    }
                    s[0] = nn[1] * t[2] - nn[2] * t[1];
                    s[1] = nn[2] * t[0] - nn[0] * t[2];
                    s[2] = nn[0] * t[1] - nn[1] * t[0];
                    al = a[0] * t[0] + a[1] * t[1] + a[2] * t[2];
                    sd = a[0] * s[0] + a[1] * s[1] + a[2] * s[2];
                    /* a = cos(side)(cos(lead) n + sin(lead) t) + sin(side) s */
                    worst = fmax(worst, fabs(sd - sin(cases[i].side * TM_PI / 180.0)));
                    worst = fmax(worst, fabs(al - cos(cases[i].side * TM_PI / 180.0) *
                                                       sin(cases[i].lead * TM_PI / 180.0)));
                }
                memcpy(prev, p, sizeof prev);
                have_prev = 1;
                n++;
                if (machine_dialect(rg.p.job.machine)->acks) {
                    send_to(&rg.mach, "ok\n");
                }
            }
            (void)proto_poll(&rg.p);
        }
        CHECK_EQ_INT(n, path_count(&rg.p.path));
        /* 4 decimals of a unit vector (5e-5), 3 of a degree (1e-5 rad); the travel from
         * points of 4 decimals over ~0.2 mm chords: the lead/side components ~5e-4 */
        if (worst > (cases[i].lead != 0.0 || cases[i].side != 0.0 ? 1e-3 : 3e-5)) {
            printf("  %s %s %g %g: worst %.3g\n", cases[i].machine, cases[i].axis, cases[i].lead,
                   cases[i].side, worst);
        }
        CHECK(worst <= (cases[i].lead != 0.0 || cases[i].side != 0.0 ? 1e-3 : 3e-5));
        printf("  note: TOOLAXIS %s %g %g on %s: %u points, worst angle/component error %.2g\n",
               cases[i].axis, cases[i].lead, cases[i].side, cases[i].machine, n, worst);
    }
    /* the machines that cannot take the words: refused at RUN */
    CHECK(rig(1));
    CHECK(load(paper));
    CHECK(cmd("FEED 600", "ok"));
    CHECK(cmd("TOOLAXIS AC 0 0", "ok"));
    CHECK(cmd("MACHINE GRBL", "ok"));
    CHECK(cmd("RUN", "error:43 "));
    CHECK(cmd("MACHINE MARLIN", "ok"));
    CHECK(cmd("RUN", "error:43 "));
    CHECK(cmd("MACHINE LINUXCNC", "ok"));
    CHECK(cmd("TOOLAXIS IJK 0 0", "ok"));
    CHECK(cmd("RUN", "error:43 "));
    CHECK(cmd("TOOLAXIS AC 61 0", "error:6 "));
    CHECK(cmd("TOOLAXIS OFF 1", "error:3 "));
    return 0;
}

/* Reconnecting (docs/PROTOCOL.md "Reconnecting"): a host that comes back during a run on
 * the machine link sends "\n" (ends a partial line it may have left: no reply while a run
 * is on) and "?"; the run went on without it; once "?" says <Idle> the firmware takes
 * commands again. No abort byte is needed. */
int test_machine_reconnect(void)
{
    char l[200];
    int i, run_report = 0;
    CHECK(cell("GRBL", "FEED 600"));
    CHECK(start_run());
    send_to(&rg.host, "CURVE LI"); /* the old host died mid-line */
    for (i = 0; i < 50; i++) {
        while (line_of(&rg.mach, l, sizeof l, 0)) {
            send_to(&rg.mach, "ok\n");
        }
        (void)proto_poll(&rg.p);
    }
    rg.host.scan = rg.host.m.out_len; /* what it would have read is lost */
    send_to(&rg.host, "\n?");         /* the new host: "CURVE LI" ends, error:7 (busy) */
    for (i = 0; i < 20 && !run_report; i++) {
        if (line_of(&rg.host, l, sizeof l, 5)) {
            run_report = strncmp(l, "<Run|", 5) == 0;
            CHECK(run_report || strncmp(l, "error:7 ", 8) == 0);
        }
    }
    CHECK(run_report);
    for (i = 0; i < 400000 && rg.p.state != PROTO_IDLE; i++) {
        while (line_of(&rg.mach, l, sizeof l, 0)) {
            send_to(&rg.mach, "ok\n");
        }
        (void)proto_poll(&rg.p);
    }
    CHECK(rg.p.state == PROTO_IDLE);
    rg.host.scan = rg.host.m.out_len;
    send_to(&rg.host, "?");
    CHECK(line_of(&rg.host, l, sizeof l, 20) && strcmp(l, "<Idle>") == 0);
    CHECK(cmd("$I", "ok"));
    return 0;
}
