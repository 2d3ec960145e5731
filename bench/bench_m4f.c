/* bench_m4f.c - exact instructions per call of firmware routines (QEMU M4F and host callgrind).
 * SPDX-License-Identifier: MIT
 *
 * TO ADD A ROUTINE: write a setup function (prepares state; not measured) and a
 * call function (exactly the work to measure), both `static void f(void)`, keep
 * their state in file-scope statics below, and add one line to `cases[]`.
 * Nothing else changes: `make bench` (QEMU) and `make bench-host` (callgrind)
 * pick it up. Use volatile sinks (bench_sink) so -Os cannot drop the work.
 *
 * Target (make bench, build/m4f/bench.elf on mps2-an386 with -icount shift=7):
 * every guest instruction advances the virtual clock by 2^7 ns and TIMER0 ticks
 * every 40 ns, so a span of `ticks` is round(ticks * 40 / 128) instructions,
 * exact for any count (one tick = 0.3125 instruction, so the +-1 tick phase
 * jitter never changes the rounded value; QEMU.md §4). Each call is measured
 * BENCH_REPS times (setup before each) and the empty call's count is
 * subtracted, leaving the instructions of the call itself (call + return of the
 * routine under test included, the timer reads excluded).
 * Host (make bench-host, -DBENCH_HOST): the same table under valgrind
 * --tool=callgrind --collect-atstart=no; collection is toggled around each call
 * and one dump per call is written; tools/bench_host.sh prints the table.
 */
#include <string.h>

#include "fmt.h"
#include "hal_mem.h"
#include "proto.h"

#ifdef BENCH_HOST
#include <stdio.h>
#include <valgrind/callgrind.h>
#else
#include "mps2.h"
#include "semihost.h"
#include "startup.h"
#endif

#define BENCH_REPS 4

struct bench_case {
    const char *name;    /* printed; no spaces */
    void (*setup)(void); /* prepares the state for one call; not measured */
    void (*call)(void);  /* the measured work */
};

static volatile int32_t bench_sink; /* keeps results alive */

/* ---- empty call: the baseline subtracted from every row ---- */
static void setup_none(void)
{
}

static void call_empty(void)
{
    __asm volatile("" ::: "memory");
}

/* ---- fmt_fixed: one 7-digit value with 4 decimals ---- */
static char fmt_buf[32];
static size_t fmt_pos;

static void setup_fmt_fixed(void)
{
    fmt_pos = 0;
}

static void call_fmt_fixed(void)
{
    bench_sink = fmt_fixed(fmt_buf, sizeof fmt_buf, &fmt_pos, -1234567, 4);
}

/* ---- proto_poll: the engine over the in-memory HAL ---- */
static struct hal_mem mem;
static struct hal_uart mem_uart;
static struct proto engine;

static void proto_fresh(const char *input)
{
    struct proto_cfg cfg;
    hal_mem_init(&mem, &mem_uart);
    cfg.uart = &mem_uart;
    bench_sink = proto_init(&engine, &cfg);
    (void)hal_mem_feed_str(&mem, input);
}

static void setup_proto_idle(void)
{
    proto_fresh("");
}

/* One proto_poll with nothing to read or send (the main-loop idle cost). */
static void call_proto_idle(void)
{
    bench_sink = proto_poll(&engine);
}

static void setup_proto_info(void)
{
    proto_fresh("$I\n");
}

/* One "$I" line in, its whole reply out: proto_poll until it reports idle. */
static void call_proto_info(void)
{
    int i;
    for (i = 0; i < 16 && proto_poll(&engine) > 0; i++) {
    }
    bench_sink = (int32_t)mem.out_len;
}

/* ---- the table: add routines here ---- */
static const struct bench_case cases[] = {
    {"empty", setup_none, call_empty}, /* must stay first: the baseline */
    {"fmt_fixed", setup_fmt_fixed, call_fmt_fixed},
    {"proto_poll_idle", setup_proto_idle, call_proto_idle},
    {"proto_poll_$I_line", setup_proto_info, call_proto_info},
};

#define N_CASES (sizeof cases / sizeof cases[0])

#ifdef BENCH_HOST

int main(void)
{
    size_t i;
    int r;
    for (i = 0; i < N_CASES; i++) {
        for (r = 0; r < BENCH_REPS; r++) {
            void (*volatile call)(void) = cases[i].call;
            cases[i].setup();
            CALLGRIND_ZERO_STATS;
            CALLGRIND_TOGGLE_COLLECT;
            call();
            CALLGRIND_TOGGLE_COLLECT;
            CALLGRIND_DUMP_STATS_AT(cases[i].name);
        }
    }
    printf("bench-host: %u routines x %d calls dumped\n", (unsigned)N_CASES, BENCH_REPS);
    return 0;
}

#else /* QEMU mps2-an386 */

static void print(const char *s)
{
    semihost_write0(s);
}

static void print_u32(uint32_t v)
{
    char b[12];
    size_t pos = 0;
    (void)fmt_u32(b, sizeof b - 1u, &pos, v);
    b[pos] = '\0';
    print(b);
}

static void print_padded(const char *s, size_t width)
{
    size_t n = strlen(s);
    print(s);
    while (n++ < width) {
        print(" ");
    }
}

/* Instructions of one call of c (setup excluded), rounded from TIMER0 ticks. */
static uint32_t measure(const struct bench_case *c)
{
    void (*volatile call)(void) = c->call;
    uint32_t t0, t1;
    c->setup();
    t0 = MPS2_TIMER0_VALUE;
    call();
    t1 = MPS2_TIMER0_VALUE;
    return ((t0 - t1) * 40u + 64u) / 128u; /* down-counter; 25 MHz vs 2^7 ns/insn */
}

int main(void)
{
    uint32_t base = 0;
    size_t i;
    int fail = 0;
    MPS2_TIMER0_CTRL = 0u;
    MPS2_TIMER0_RELOAD = 0xFFFFFFFFu;
    MPS2_TIMER0_VALUE = 0xFFFFFFFFu;
    MPS2_TIMER0_CTRL = MPS2_TIMER_CTRL_EN;

    print("routine                 insns/call\n");
    for (i = 0; i < N_CASES; i++) {
        uint32_t first = measure(&cases[i]), v;
        int r, same = 1;
        for (r = 1; r < BENCH_REPS; r++) {
            v = measure(&cases[i]);
            same &= (v == first);
        }
        if (i == 0) {
            base = first;
            print_padded("(empty-call baseline)", 24);
            print_u32(base);
            print(" raw\n");
            continue;
        }
        print_padded(cases[i].name, 24);
        print_u32(first - base);
        print(same ? "\n" : "  (VARIES between calls)\n");
        fail |= !same;
    }
    print("stack peak (painted)    ");
    print_u32((uint32_t)startup_stack_peak());
    print(" bytes (bench image, includes the bench driver)\n");
    semihost_exit(fail);
}

#endif
