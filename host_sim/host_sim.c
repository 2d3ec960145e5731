/* host_sim.c - the host simulator: runs a firmware on a pty it creates, does the
 * $I handshake, plays a job file and checks the replies (docs/HOST_SIM.md).
 * SPDX-License-Identifier: MIT
 *
 * Usage: host_sim --target native|qemu --job FILE [--fw PATH] [--timeout-ms N]
 *                 [--log FILE] [--qemu PROGRAM] [--cmd PROGRAM [ARGS...]]
 * Exit status: 0 iff every check passed; 1 if a check failed; 2 on a usage or
 * set-up error; 130 after SIGINT (the firmware is always killed and reaped).
 * The last line of stdout is always "sim: N passed, N failed" (also on exit 2).
 */
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "sim_job.h"
#include "sim_link.h"
#include "sim_pty.h"

#define SIM_DEFAULT_NATIVE "build/host/fw_native"
#define SIM_DEFAULT_QEMU_FW "build/m4f/fw.elf"
#define SIM_HS_RETRY_MS 200u    /* $I is re-sent this often until answered */
#define SIM_HS_MAX_SENDS 50u    /* and at most this many times */
#define SIM_DRAIN_MS 500u       /* time allowed for answers to extra $I sends */
#define SIM_SHUTDOWN_MS 1000    /* the firmware must exit this soon after hang-up */
#define SIM_KILL_GRACE_MS 500   /* SIGTERM -> SIGKILL */

enum sim_target { SIM_NATIVE, SIM_QEMU, SIM_CMD };

static volatile sig_atomic_t sim_stop;

static struct {
    int passed, failed;
} checks;

static struct {
    unsigned long sent, ok, error, info, unknown, streamed;
    double rtt_min, rtt_max;
} stats;

static double *rtts; /* one per command, ms */

static void sim_on_signal(int sig)
{
    sim_stop = sig;
}

static void check(int ok, const char *what, const char *detail)
{
    if (ok) {
        checks.passed++;
        printf("  PASS %s\n", what);
    } else {
        checks.failed++;
        printf("  FAIL %s%s%s\n", what, detail[0] ? ": " : "", detail);
    }
}

static void finish_line(void)
{
    printf("sim: %d passed, %d failed\n", checks.passed, checks.failed);
    fflush(stdout);
}

static int usage(const char *msg)
{
    fprintf(stderr,
            "host_sim: %s\n"
            "usage: host_sim --target native|qemu --job FILE [--fw PATH] [--timeout-ms N]\n"
            "                [--log FILE] [--qemu PROGRAM] [--cmd PROGRAM [ARGS...]]\n",
            msg);
    checks.failed++;
    finish_line();
    return 2;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Print the [OPT:k=v,...] line as "k=v k=v ..." */
static void print_limits(const char *opt)
{
    size_t n = strlen(opt), i;
    printf("sim: firmware limits ");
    for (i = 5; i + 1 < n; i++) {
        putchar(opt[i] == ',' ? ' ' : opt[i]);
    }
    putchar('\n');
}

struct hs_result {
    int ok;
    unsigned sends;
    char ver[128], opt[256];
    char why[200];
};

/* Send $I every SIM_HS_RETRY_MS until "[VER:" and "ok" arrive or timeout_ms pass. */
static int handshake(struct sim_link *l, unsigned timeout_ms, struct hs_result *h)
{
    uint64_t end = sim_link_now_ms() + timeout_ms;
    struct sim_reply r;
    int rc = SIM_LINK_TIMEOUT;
    unsigned unknown = 0;
    memset(h, 0, sizeof *h);
    while (h->sends < SIM_HS_MAX_SENDS) {
        uint64_t now = sim_link_now_ms(), d = now + SIM_HS_RETRY_MS;
        if (now >= end) {
            break;
        }
        rc = sim_link_send(l, "$I\n", 3, end);
        if (rc < 0) {
            break;
        }
        h->sends++;
        rc = sim_link_await(l, d < end ? d : end, &r, NULL, NULL);
        if (r.ver[0]) {
            memcpy(h->ver, r.ver, sizeof h->ver);
        }
        if (r.opt[0]) {
            memcpy(h->opt, r.opt, sizeof h->opt);
        }
        unknown += r.unknown;
        if (r.unknown) {
            printf("  handshake: unknown reply line \"%s\"\n", r.first_unknown);
        }
        if (rc != SIM_LINK_TIMEOUT) {
            break;
        }
    }
    if (rc == SIM_LINK_REPLY && r.error) {
        snprintf(h->why, sizeof h->why, "$I answered error:%d", r.code);
    } else if (rc == SIM_LINK_REPLY && !h->ver[0]) {
        snprintf(h->why, sizeof h->why, "no [VER:...] line before ok");
    } else if (rc == SIM_LINK_REPLY && unknown) {
        snprintf(h->why, sizeof h->why, "%u unknown line(s)", unknown);
    } else if (rc == SIM_LINK_REPLY) {
        h->ok = 1;
    } else {
        snprintf(h->why, sizeof h->why, "%s", sim_link_strerror(rc));
    }
    if (h->ok && h->sends > 1) {
        /* answers to the extra $I sends may still be on their way */
        unsigned k;
        uint64_t dend = sim_link_now_ms() + SIM_DRAIN_MS;
        for (k = 1; k < h->sends; k++) {
            if (sim_link_await(l, dend, &r, NULL, NULL) != SIM_LINK_REPLY) {
                break;
            }
        }
    }
    return rc;
}

int main(int argc, char **argv)
{
    static char err[512], detail[512], what[256];
    enum sim_target target = SIM_NATIVE;
    const char *job_path = NULL, *fw = NULL, *log_path = NULL, *qemu = "qemu-system-arm";
    const char *target_name = NULL;
    char **cmd = NULL;
    unsigned timeout_ms = 2000;
    struct sim_job job;
    struct sim_pty pty;
    struct sim_link link;
    struct hs_result hs;
    struct sigaction sa;
    FILE *log = NULL;
    uint64_t t_start, t_hs = 0;
    size_t i;
    int rc, fatal = 0, interrupted = 0;
    char *qargv[20];
    char st[32];

    setvbuf(stdout, NULL, _IOLBF, 0);
    for (i = 1; i < (size_t)argc; i += 2) { /* every option takes one value */
        const char *a = argv[i];
        const char *v = i + 1 < (size_t)argc ? argv[i + 1] : NULL;
        if (strcmp(a, "--cmd") == 0) {
            if (v == NULL) {
                return usage("--cmd needs a program");
            }
            cmd = argv + i + 1;
            target = SIM_CMD;
            break;
        }
        if (v == NULL) {
            return usage("missing value after an option");
        }
        if (strcmp(a, "--target") == 0) {
            target_name = v;
        } else if (strcmp(a, "--job") == 0) {
            job_path = v;
        } else if (strcmp(a, "--fw") == 0) {
            fw = v;
        } else if (strcmp(a, "--log") == 0) {
            log_path = v;
        } else if (strcmp(a, "--qemu") == 0) {
            qemu = v;
        } else if (strcmp(a, "--timeout-ms") == 0) {
            char *e;
            unsigned long t = strtoul(v, &e, 10);
            if (*e != '\0' || t < 50 || t > 600000) {
                return usage("--timeout-ms must be 50..600000");
            }
            timeout_ms = (unsigned)t;
        } else {
            return usage("unknown option");
        }
    }
    if (target != SIM_CMD) {
        if (target_name == NULL || strcmp(target_name, "native") == 0) {
            target = SIM_NATIVE;
        } else if (strcmp(target_name, "qemu") == 0) {
            target = SIM_QEMU;
        } else {
            return usage("--target must be native or qemu");
        }
    } else if (target_name != NULL && strcmp(target_name, "native") != 0) {
        return usage("--cmd runs the program like --target native");
    }
    if (job_path == NULL) {
        return usage("--job FILE is required");
    }
    if (fw == NULL) {
        fw = target == SIM_QEMU ? SIM_DEFAULT_QEMU_FW : SIM_DEFAULT_NATIVE;
    }
    if (sim_job_load(&job, job_path, err, sizeof err) != 0) {
        fprintf(stderr, "host_sim: %s\n", err);
        checks.failed++;
        finish_line();
        return 2;
    }
    if (target != SIM_CMD && access(fw, R_OK) != 0) {
        fprintf(stderr, "host_sim: firmware %s: %s%s\n", fw, strerror(errno),
                target == SIM_QEMU ? " (build it with make m4f-fw)" : " (make fw-native)");
        goto setup_fail;
    }
    rtts = calloc(job.n + 1u, sizeof *rtts);
    if (rtts == NULL) {
        fprintf(stderr, "host_sim: out of memory\n");
        goto setup_fail;
    }
    if (log_path != NULL) {
        log = fopen(log_path, "w");
        if (log == NULL) {
            fprintf(stderr, "host_sim: %s: %s\n", log_path, strerror(errno));
            goto setup_fail;
        }
        setvbuf(log, NULL, _IOLBF, 0);
    }

    memset(&sa, 0, sizeof sa);
    sa.sa_handler = sim_on_signal;
    sigemptyset(&sa.sa_mask);
    (void)sigaction(SIGINT, &sa, NULL);
    (void)sigaction(SIGTERM, &sa, NULL);
    (void)sigaction(SIGHUP, &sa, NULL);
    sa.sa_handler = SIG_IGN;
    (void)sigaction(SIGPIPE, &sa, NULL);

    t_start = sim_link_now_us();
    if (sim_pty_open(&pty, err, sizeof err) != 0) {
        fprintf(stderr, "host_sim: %s\n", err);
        goto setup_fail;
    }
    if (target == SIM_QEMU) {
        size_t k = 0;
        qargv[k++] = (char *)qemu;
        qargv[k++] = "-M";
        qargv[k++] = "mps2-an386";
        qargv[k++] = "-display";
        qargv[k++] = "none";
        qargv[k++] = "-monitor";
        qargv[k++] = "none";
        qargv[k++] = "-serial";
        qargv[k++] = pty.path;
        qargv[k++] = "-semihosting-config";
        qargv[k++] = "enable=on,target=native";
        qargv[k++] = "-icount";
        qargv[k++] = "shift=7";
        qargv[k++] = "-kernel";
        qargv[k++] = (char *)fw;
        qargv[k] = NULL;
        cmd = qargv;
    } else if (target == SIM_NATIVE) {
        qargv[0] = (char *)fw;
        qargv[1] = NULL;
        cmd = qargv;
    }
    printf("sim: target %s, %s on %s, job %s (%lu commands), timeout %u ms\n",
           target == SIM_QEMU ? "qemu" : target == SIM_NATIVE ? "native" : "cmd",
           target == SIM_QEMU ? fw : cmd[0], pty.path, job_path, (unsigned long)job.n,
           timeout_ms);
    if (sim_pty_spawn(&pty, cmd, target != SIM_QEMU, err, sizeof err) != 0) {
        fprintf(stderr, "host_sim: %s%s\n", err,
                target == SIM_QEMU && strstr(err, qemu) != NULL
                    ? " (install qemu-system-arm: apt-get install qemu-system-arm)"
                    : "");
        sim_pty_hangup(&pty);
        goto setup_fail;
    }
    sim_link_init(&link, &pty, &sim_stop, log);

    /* 1. handshake */
    rc = handshake(&link, timeout_ms, &hs);
    t_hs = sim_link_now_us();
    snprintf(what, sizeof what, "handshake ($I x%u, %.2f ms)", hs.sends,
             (double)(t_hs - t_start) / 1000.0);
    check(hs.ok, what, hs.why);
    if (hs.ok) {
        printf("sim: firmware %s\n", hs.ver);
        if (hs.opt[0]) {
            print_limits(hs.opt);
        }
        sim_pty_release(&pty); /* the firmware has the slave: a death now gives EIO */
    } else {
        fatal = 1;
        interrupted = rc == SIM_LINK_INTR;
    }

    /* 2. the job */
    if (!fatal) {
        printf("  %4s  %-30s %-26s %-10s %9s  %s\n", "line", "command", "reply", "expect",
               "rtt ms", "check");
    }
    for (i = 0; !fatal && i < job.n; i++) {
        const struct sim_job_cmd *c = &job.cmd[i];
        static char out[SIM_JOB_LINE_MAX + 2], reply[64], expect[24], esc[31];
        struct sim_reply r;
        uint64_t t0;
        double ms;
        int pass = 1;
        memcpy(out, c->text, c->len);
        out[c->len] = '\n';
        t0 = sim_link_now_us();
        rc = sim_link_send(&link, out, c->len + 1u, sim_link_now_ms() + timeout_ms);
        if (rc == SIM_LINK_REPLY) {
            stats.sent++;
            rc = sim_link_await(&link, sim_link_now_ms() + timeout_ms, &r, NULL, NULL);
        }
        ms = (double)(sim_link_now_us() - t0) / 1000.0;
        sim_link_escape(c->text, c->len, esc, sizeof esc);
        if (rc != SIM_LINK_REPLY) {
            snprintf(detail, sizeof detail, "%s after %.1f ms", sim_link_strerror(rc), ms);
            snprintf(what, sizeof what, "line %d \"%s\"", c->lineno, esc);
            check(0, what, detail);
            fatal = 1;
            interrupted = rc == SIM_LINK_INTR;
            break;
        }
        rtts[stats.ok + stats.error] = ms;
        if (r.error) {
            stats.error++;
            snprintf(reply, sizeof reply, "error:%d", r.code);
        } else {
            stats.ok++;
            snprintf(reply, sizeof reply, "ok");
        }
        if (r.info) {
            size_t L = strlen(reply);
            snprintf(reply + L, sizeof reply - L, " +%u info", r.info);
        }
        stats.info += r.info;
        stats.unknown += r.unknown;
        stats.streamed += r.streamed;
        if (c->expect == SIM_JOB_EXPECT_OK) {
            snprintf(expect, sizeof expect, "ok");
            pass = !r.error;
        } else if (c->expect == SIM_JOB_EXPECT_ERROR) {
            snprintf(expect, sizeof expect, "error:%d", c->code);
            pass = r.error && r.code == c->code;
        } else {
            snprintf(expect, sizeof expect, "-");
        }
        printf("  %4d  %-30s %-26s %-10s %9.3f  %s\n", c->lineno, esc, reply, expect, ms,
               c->expect == SIM_JOB_EXPECT_NONE ? "-" : pass ? "pass" : "FAIL");
        if (c->expect != SIM_JOB_EXPECT_NONE && pass) {
            checks.passed++;
        } else if (c->expect != SIM_JOB_EXPECT_NONE) {
            checks.failed++;
        }
        if (r.unknown) {
            snprintf(what, sizeof what, "line %d: %u unknown reply line(s), first \"%s\"",
                     c->lineno, r.unknown, r.first_unknown);
            check(0, what, "");
        }
        if (r.error && !r.text_ok) {
            snprintf(what, sizeof what, "line %d: error:%d text does not match cp_status.def",
                     c->lineno, r.code);
            check(0, what, "");
        }
    }

    /* 3. shutdown: every path ends here, the child is always reaped */
    if (interrupted || sim_stop) {
        (void)sim_pty_stop(&pty, SIM_KILL_GRACE_MS);
        sim_pty_hangup(&pty);
        check(0, "interrupted", "firmware stopped and reaped");
    } else if (target == SIM_QEMU) {
        int alive = !sim_pty_exited(&pty), how;
        how = sim_pty_stop(&pty, SIM_KILL_GRACE_MS); /* QEMU never exits on a hang-up */
        sim_pty_hangup(&pty);
        if (!alive) {
            snprintf(detail, sizeof detail, "QEMU exited during the session (%s)",
                     sim_pty_describe(pty.status, st, sizeof st));
        } else {
            snprintf(detail, sizeof detail, "QEMU needed SIGKILL");
        }
        check(alive && how == 1, "clean shutdown (QEMU alive, ends on SIGTERM)", detail);
    } else {
        int early = sim_pty_exited(&pty), exited, how = 0;
        sim_pty_hangup(&pty);
        exited = early || sim_pty_wait(&pty, SIM_SHUTDOWN_MS);
        if (!exited) {
            how = sim_pty_stop(&pty, SIM_KILL_GRACE_MS);
        }
        if (early) {
            snprintf(detail, sizeof detail, "firmware exited before the hang-up (%s)",
                     sim_pty_describe(pty.status, st, sizeof st));
        } else if (!exited) {
            snprintf(detail, sizeof detail, "no exit within %d ms of the hang-up; %s", SIM_SHUTDOWN_MS,
                     how == 2 ? "needed SIGKILL" : "ended by SIGTERM");
        } else {
            snprintf(detail, sizeof detail, "%s", sim_pty_describe(pty.status, st, sizeof st));
        }
        check(!early && exited && WIFEXITED(pty.status) && WEXITSTATUS(pty.status) == 0,
              "clean shutdown (exit 0 on hang-up)", detail);
    }

    /* 4. summary */
    {
        unsigned long n = stats.ok + stats.error;
        double med = 0.0;
        if (n > 0) {
            qsort(rtts, n, sizeof *rtts, cmp_double);
            med = n % 2u ? rtts[n / 2u] : (rtts[n / 2u - 1u] + rtts[n / 2u]) / 2.0;
        }
        printf("sim: summary\n");
        printf("  %-18s %lu of %lu\n", "commands sent", stats.sent, (unsigned long)job.n);
        printf("  %-18s ok %lu, error %lu, info lines %lu, unknown %lu\n", "replies", stats.ok,
               stats.error, stats.info, stats.unknown);
        printf("  %-18s out %llu, in %llu\n", "bytes", link.bytes_out, link.bytes_in);
        if (n > 0) {
            printf("  %-18s min %.3f, median %.3f, max %.3f\n", "round trip ms", rtts[0], med,
                   rtts[n - 1u]);
        }
        printf("  %-18s %.2f\n", "handshake ms", (double)(t_hs - t_start) / 1000.0);
        printf("  %-18s %.2f\n", "elapsed ms", (double)(sim_link_now_us() - t_start) / 1000.0);
    }
    if (log != NULL) {
        fclose(log);
    }
    sim_job_free(&job);
    free(rtts);
    finish_line();
    if (interrupted || sim_stop) {
        return 130;
    }
    return checks.failed == 0 ? 0 : 1;

setup_fail: /* nothing was spawned, or the child is already gone */
    if (log != NULL) {
        fclose(log);
    }
    sim_job_free(&job);
    free(rtts);
    checks.failed++;
    finish_line();
    return 2;
}
