/* maxpoint_m4f.c - worst-case (not only mean) instructions per generated point of the
 * toolpath iterator, every point of soak-sized jobs, on QEMU mps2-an386 -icount shift=7.
 * SPDX-License-Identifier: MIT
 *
 * Build and run: make maxpoint (mk/hardening.mk; docs/SOAK.md). Each job is built the
 * way the firmware builds it: job_init + job_command for every protocol line, then
 * canal_path_init on job.canal and job.cfg (proto.c does the same at RUN). Then every
 * canal_path_next() call of the whole job is timed with TIMER0, as bench/bench_m4f.c
 * does: with -icount shift=7 one instruction is 128 ns of virtual time and TIMER0
 * ticks every 40 ns, so a span of `ticks` is round(ticks * 40 / 128) instructions,
 * exact. The empty call (the two timer reads and an indirect call) is measured the
 * same way and subtracted, so a row is the instructions of canal_path_next itself.
 *
 * Per job: points, mean / max / min instructions per point, max/mean, where the max
 * occurs (k, line or circle j, index; line -1 = a link point), and the same figures by
 * point class:
 *   body   a point of a line (circle) that is not its first in travel order
 *   start  the first point of a line (circle) in travel order (k = 0 included)
 *   link   a link move point between two lines (circles)
 * and, outside the stream, the cost of canal_path_seek(k) + the next call (the path a
 * RESUME or a go-back-N retransmit takes) for a few k of the first job.
 * Check per job: max <= MAXPOINT_LIMIT_PCT % of the mean (default 125). The closing
 * line is "maxpoint: N passed, N failed"; the exit status is the failure count.
 */
#include <string.h>

#include "bench_print.h"
#include "fmt.h"
#include "job.h"
#include "mps2.h"
#include "semihost.h"
#include "canal_path.h"

#ifndef MAXPOINT_LIMIT_PCT
#define MAXPOINT_LIMIT_PCT 125u
#endif

struct mp_job {
    const char *name;
    const char *const *lines; /* protocol command lines, NULL-terminated */
};

/* The paper's canal (ARC r = 3, R = 5.5 cos 2t + 10.5): 24 family-2 lines, links of
 * derived length (TOL 1 um default), 1000 steps: ~24k points. Constant curvature: exact
 * Lambda, no quadrature state. */
static const char *const job_canal[] = {"CURVE ARC 0 0 3 0 360", "RADIUS COS 5.5 10.5 2",
                                        "LINES 24 -25 10", "STEPS 1000", NULL};
/* An ellipse: varying curvature, Lambda by Simpson + Kahan (2 jets per point). */
static const char *const job_ellipse[] = {"CURVE ELLIPSE 0 0 4 3 0 300", "RADIUS LINEAR 1 1.5",
                                          "LINES 10 -40 40", "STEPS 2000", NULL};
/* Characteristic circles of the paper's canal (span ANGLE) with links along u = const. */
static const char *const job_circles[] = {"CURVE ARC 0 0 3 0 360", "RADIUS COS 5.5 10.5 2",
                                          "CIRCLES 40 -25 10", "STEPS 500", NULL};
/* The same as a PATCH (circles between the family-2 lines that start at u0, u1). */
static const char *const job_patch[] = {"CURVE ARC 0 0 3 0 360", "RADIUS COS 5.5 10.5 2",
                                        "CIRCLES 30 -25 10 PATCH", "STEPS 600", NULL};
/* A Bezier with a cubic radius law and a ball-end tool (tip output). */
static const char *const job_bezier[] = {"CURVE BEZIER 0 0 10 20 30 -20 40 0",
                                         "RADIUS CUBIC 3 4 4 3", "TOOL BALL 1",
                                         "LINES 10 0 80", "STEPS 2000", NULL};

static const struct mp_job jobs[] = {
    {"canal_arc_cos_lines", job_canal},   {"ellipse_simpson_lines", job_ellipse},
    {"circles_arc_cos", job_circles},     {"circles_patch", job_patch},
    {"bezier_cubic_tool", job_bezier},
};
#define N_JOBS (sizeof jobs / sizeof jobs[0])

static struct job job;
static struct canal_path tp;
static struct raster_pt pt;
static volatile int32_t sink;

static void print_pad(const char *s, size_t w)
{
    size_t n = strlen(s);
    print(s);
    while (n++ < w) {
        print(" ");
    }
}

static void print_u32_pad(uint32_t v, size_t w)
{
    char b[12];
    size_t pos = 0;
    (void)fmt_u32(b, sizeof b - 1u, &pos, v);
    b[pos] = '\0';
    while (pos++ < w) {
        print(" ");
    }
    print(b);
}

static int call_empty(struct canal_path *t, struct raster_pt *p)
{
    (void)t;
    (void)p;
    __asm volatile("" ::: "memory");
    return 0;
}

/* One timed call through a volatile pointer (the same shape for the baseline). */
static uint32_t timed(int (*volatile fn)(struct canal_path *, struct raster_pt *), int *rc)
{
    uint32_t t0, t1;
    t0 = MPS2_TIMER0_VALUE;
    *rc = fn(&tp, &pt);
    t1 = MPS2_TIMER0_VALUE;
    return ticks_to_insns(t0, t1);
}

struct stat {
    uint32_t n, max, min;
    uint64_t sum;
    uint32_t max_k;
    int16_t max_line;
    uint16_t max_index;
};

static void stat_reset(struct stat *s)
{
    memset(s, 0, sizeof *s);
    s->min = 0xFFFFFFFFu;
}

static void stat_add(struct stat *s, uint32_t v, uint32_t k)
{
    s->n++;
    s->sum += v;
    if (v > s->max) {
        s->max = v;
        s->max_k = k;
        s->max_line = pt.line;
        s->max_index = pt.index;
    }
    if (v < s->min) {
        s->min = v;
    }
}

static uint32_t stat_mean10(const struct stat *s) /* mean x 10, rounded */
{
    return s->n ? (uint32_t)((s->sum * 10u + s->n / 2u) / s->n) : 0u;
}

static void stat_row(const char *what, const struct stat *s)
{
    print("    ");
    print_pad(what, 7);
    print_u32_pad(s->n, 7);
    print("  mean ");
    print_fixed((int32_t)stat_mean10(s), 1);
    print("  max ");
    print_u32(s->max);
    print("  min ");
    print_u32(s->n ? s->min : 0u);
    if (s->n) {
        print("  (max at k ");
        print_u32(s->max_k);
        print(", line ");
        print_i32(s->max_line);
        print(", index ");
        print_u32(s->max_index);
        print(")");
    }
    print("\n");
}

static int load(const struct mp_job *mj)
{
    size_t i;
    job_init(&job);
    for (i = 0; mj->lines[i] != NULL; i++) {
        if (job_command(&job, mj->lines[i], strlen(mj->lines[i])) != CP_ST_OK) {
            print("  job line rejected: ");
            print(mj->lines[i]);
            print("\n");
            return -1;
        }
    }
    if (canal_path_init(&tp, &job.canal, &job.cfg) != CP_OK) {
        print("  canal_path_init failed\n");
        return -1;
    }
    return 0;
}

int main(void)
{
    uint32_t base = 0xFFFFFFFFu;
    size_t i;
    int r, passed = 0, failed = 0;
    MPS2_TIMER0_CTRL = 0u;
    MPS2_TIMER0_RELOAD = 0xFFFFFFFFu;
    MPS2_TIMER0_VALUE = 0xFFFFFFFFu;
    MPS2_TIMER0_CTRL = MPS2_TIMER_CTRL_EN;

    for (i = 0; i < 8u; i++) { /* the baseline must not vary; keep the smallest */
        uint32_t v = timed(call_empty, &r);
        base = v < base ? v : base;
    }
    print("maxpoint: instructions per canal_path_next() call, every point of the job, QEMU -icount "
          "shift=7 (empty-call baseline ");
    print_u32(base);
    print(" subtracted); limit max <= ");
    print_u32(MAXPOINT_LIMIT_PCT);
    print("% of the mean\n");
    for (i = 0; i < N_JOBS; i++) {
        struct stat all, body, start, link;
        uint32_t k = 0, ratio;
        int ok;
        print("job ");
        print(jobs[i].name);
        print(":");
        {
            size_t l;
            for (l = 0; jobs[i].lines[l] != NULL; l++) {
                print(l ? " | " : " ");
                print(jobs[i].lines[l]);
            }
        }
        print("\n");
        if (load(&jobs[i]) != 0) {
            failed++;
            continue;
        }
        stat_reset(&all);
        stat_reset(&body);
        stat_reset(&start);
        stat_reset(&link);
        {
            int16_t prev_line = -2;
            for (;;) {
                uint32_t v = timed(canal_path_next, &r);
                if (r != CP_OK) {
                    break;
                }
                v -= base;
                stat_add(&all, v, k);
                if (pt.line < 0) {
                    stat_add(&link, v, k);
                } else if (pt.line != prev_line) {
                    stat_add(&start, v, k);
                } else {
                    stat_add(&body, v, k);
                }
                prev_line = pt.line;
                k++;
            }
        }
        ok = r == CP_ERR_DONE && k == canal_path_count(&tp) && all.n > 0u;
        ratio = all.n /* max/mean x 1000 */ ? (uint32_t)(((uint64_t)all.max * 1000u * all.n + all.sum / 2u) / all.sum) : 0u;
        ok = ok && (uint64_t)all.max * 100u * all.n <= (uint64_t)MAXPOINT_LIMIT_PCT * all.sum;
        print("  points ");
        print_u32(all.n);
        print(" of ");
        print_u32(canal_path_count(&tp));
        print(" (n ");
        print_u32(tp.head.n);
        print(", steps ");
        print_u32(tp.head.steps);
        print(", link ");
        print_u32(tp.head.link);
        print(", substeps ");
        print_u32(tp.substeps);
        print(")\n  all    mean ");
        print_fixed((int32_t)stat_mean10(&all), 1);
        print("  max ");
        print_u32(all.max);
        print("  min ");
        print_u32(all.min);
        print("  max/mean ");
        print_fixed((int32_t)ratio, 3);
        print("  max at k ");
        print_u32(all.max_k);
        print(" (line ");
        print_i32(all.max_line);
        print(", index ");
        print_u32(all.max_index);
        print(all.max_line < 0 ? ": a link point)\n" : ")\n");
        stat_row("body", &body);
        stat_row("start", &start);
        stat_row("link", &link);
        print(ok ? "  PASS " : "  FAIL ");
        print(jobs[i].name);
        print(": max/mean ");
        print_fixed((int32_t)ratio, 3);
        print(ok ? " <= " : " > ");
        print_fixed((int32_t)(MAXPOINT_LIMIT_PCT * 10u), 3);
        print("\n");
        passed += ok;
        failed += !ok;

        if (i <= 1u) { /* resume / retransmit path: seek + next, not part of the stream */
            static const uint32_t at[] = {1u, 250u, 500u, 750u, 999u}; /* per mille of count */
            size_t s;
            print("  seek+next (RESUME / go-back-N path, outside the stream):");
            for (s = 0; s < sizeof at / sizeof at[0]; s++) {
                uint32_t t0, t1, kk = (uint32_t)((uint64_t)canal_path_count(&tp) * at[s] / 1000u);
                t0 = MPS2_TIMER0_VALUE;
                r = canal_path_seek(&tp, kk);
                r |= canal_path_next(&tp, &pt);
                t1 = MPS2_TIMER0_VALUE;
                print(" k ");
                print_u32(kk);
                print(" -> ");
                print_u32(ticks_to_insns(t0, t1) - base);
                print(r == CP_OK ? "" : " (error)");
            }
            print("\n");
        }
    }
    print("maxpoint: ");
    print_u32((uint32_t)passed);
    print(" passed, ");
    print_u32((uint32_t)failed);
    print(" failed\n");
    sink = failed;
    semihost_exit(failed);
}
