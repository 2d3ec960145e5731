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
#include "frenet.h"
#include "hal_mem.h"
#include "proto.h"
#include "cp_math.h"
#include "canal_path.h"
#include "drc.h"
#include "channel.h"
#include "gsr.h"
#include "spine.h"

#ifdef BENCH_HOST
#include <stdio.h>
#include <valgrind/callgrind.h>
#else
#include "bench_print.h"
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
    struct proto_cfg cfg = {0};
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


/* ---- canal core on the paper's example: ARC r = 3, R = 5.5 cos 2t + 10.5 ---- */
static struct canal_path tp_bench;
static struct raster_pt tp_pt;
static struct canal_cfg tp_surf;

/* The paper's surface into tp_surf, a raster of n lines of `steps` steps into *c. */
static void paper_cfg(struct raster_cfg *c, uint16_t n, uint16_t steps)
{
    memset(&tp_surf, 0, sizeof tp_surf);
    memset(c, 0, sizeof *c);
    tp_surf.curve = CANAL_ARC;
    tp_surf.radius = CANAL_R_COS;
    tp_surf.cp[2] = CP_R(3.0);
    tp_surf.cp[4] = CP_TWO_PI;
    tp_surf.rp[0] = CP_R(5.5);
    tp_surf.rp[1] = CP_R(10.5);
    tp_surf.rp[2] = CP_R(2.0);
    c->mode = RASTER_LINES;
    c->n = n;
    c->u0 = CP_R(-0.3);
    c->u1 = CP_R(0.1);
    c->steps = steps;
    c->substeps = 1;
    c->link = 0;
}

/* One streamed point of a single family-2 line, mid-line, sequential: 2 jets
 * (ARC + COS law), Simpson + Kahan on Lambda, frame, label, point, checks. */
static void setup_tp_next(void)
{
    struct raster_cfg c;
    int i;
    paper_cfg(&c, 1, 256);
    bench_sink = canal_path_init(&tp_bench, &tp_surf, &c);
    for (i = 0; i < 101; i++) {
        bench_sink = canal_path_next(&tp_bench, &tp_pt);
    }
}

static void call_tp_next(void)
{
    bench_sink = canal_path_next(&tp_bench, &tp_pt);
}

/* The same circle given as an ELLIPSE (A = B = 3): the general path, Simpson + Kahan
 * on Lambda with 1 panel per step (2 jets per point). */
static void setup_tp_next_ellipse(void)
{
    struct raster_cfg c;
    int i;
    paper_cfg(&c, 1, 256);
    tp_surf.curve = CANAL_ELLIPSE;
    tp_surf.cp[3] = CP_R(3.0);
    tp_surf.cp[4] = CP_R(0.0);
    tp_surf.cp[5] = CP_TWO_PI;
    bench_sink = canal_path_init(&tp_bench, &tp_surf, &c);
    for (i = 0; i < 101; i++) {
        bench_sink = canal_path_next(&tp_bench, &tp_pt);
    }
}

/* Each additional line at the same t: h = alpha + Lambda b, then the point. */
static struct canal_frame frame_bench;
static struct canal_point cpt_bench;
static volatile cp_real lab_a = CP_R(0.97), lab_b = CP_R(0.15), lam_v = CP_R(-1.3);

static void setup_extra_line(void)
{
    struct canal_jet j;
    canal_jet(&tp_bench.surf, CP_R(1.1), &j);
    canal_frame(&j, &frame_bench);
}

static void call_extra_line(void)
{
    cp_real b = lab_b;
    canal_point(&frame_bench, lab_a + lam_v * b, b, CP_R(0.0), &cpt_bench);
    bench_sink = (int32_t)(cpt_bench.m.z * CP_R(1000.0));
}

static struct canal_jet jet_bench;

static void call_jet(void)
{
    canal_jet(&tp_bench.surf, CP_R(1.1), &jet_bench);
    bench_sink = (int32_t)jet_bench.r;
}

/* The paper's Frenet two-quadrature form (baseline), one step of one line. */
static struct frenet fr_bench;
static struct cp_vec3 fr_pt;

static void setup_frenet(void)
{
    int i;
    bench_sink = frenet_init(&fr_bench, CP_R(0.0), CP_R(0.0), CP_R(3.0), CP_R(5.5), CP_R(10.5),
                             CP_R(2.0), CP_R(0.0), CP_TWO_PI, 256u, CP_R(-0.3));
    for (i = 0; i < 101; i++) {
        frenet_next(&fr_bench, &fr_pt);
    }
}

static void call_frenet(void)
{
    frenet_next(&fr_bench, &fr_pt);
    bench_sink = (int32_t)fr_pt.z;
}

static volatile cp_real sc_arg = CP_R(1.234);
static cp_real sc_s, sc_c;

static void call_sincos(void)
{
    cp_sincos(sc_arg, &sc_s, &sc_c);
    bench_sink = (int32_t)(sc_s * CP_R(100.0));
}

static void call_frame(void)
{
    canal_frame(&jet_bench, &frame_bench);
    bench_sink = (int32_t)frame_bench.p;
}

static void setup_frame(void)
{
    canal_jet(&tp_bench.surf, CP_R(1.1), &jet_bench);
}

/* Chord-tolerance init of a whole job (5 lines, tol 2 um): the walk that fixes the
 * step counts and proves regularity before the first point. */
static void call_tp_init(void)
{
    struct raster_cfg c;
    paper_cfg(&c, 5, 0);
    c.substeps = 0;
    c.tol = CP_R(0.002);
    c.link = RASTER_LINK_AUTO;
    bench_sink = canal_path_init(&tp_bench, &tp_surf, &c);
}

/* ---- DRC (seed 001): thickening and its streams ---- */
static struct drc_pt drc_a, drc_b, drc_m;
static struct drc_cfg drc_g;
static struct drc_path drc_it;
static struct raster_pt drc_pt;
static struct cp_vec3 drc_tan[12];

/* a 7-point spiral (the unit tests' spiral_nonuniform, scaled x10), 3D variant lifted */
static const float drc_xy[7][2] = {{0.0f, 0.0f},      {4.98f, 0.3f},   {9.7f, 1.49f},
                                   {14.16f, 3.6f},    {17.47f, 6.77f}, {19.32f, 10.7f},
                                   {19.95f, 15.05f}};

static void drc_geom(int edge, int lift, uint8_t k)
{
    int i;
    memset(&drc_g, 0, sizeof drc_g);
    for (i = 0; i < 7; i++) {
        drc_g.p[i].x = drc_xy[i][0];
        drc_g.p[i].y = drc_xy[i][1];
        drc_g.p[i].z = lift ? 0.4f * (float)i : 0.0f;
    }
    drc_g.n = 7;
    drc_g.passes = k;
    drc_g.edge = (uint8_t)edge;
}

static void setup_drc_insert(void)
{
    drc_a.p.x = 0.0f;
    drc_a.p.y = 0.0f;
    drc_a.p.z = 0.0f;
    drc_a.t.x = 0.995f;
    drc_a.t.y = -0.0998f;
    drc_a.t.z = 0.0f;
    drc_b.p.x = 1.0f;
    drc_b.p.y = 0.0f;
    drc_b.p.z = 0.0f;
    drc_b.t.x = 0.98f;
    drc_b.t.y = 0.199f;
    drc_b.t.z = 0.0f;
}

/* one inserted point, planar closed form (r^-1 by bisection + 2 E evaluations) */
static void call_drc_insert_planar(void)
{
    drc_insert(&drc_a, &drc_b, 1, &drc_m);
    bench_sink = (int32_t)(drc_m.p.y * 1000.0f);
}

/* one inserted point, 3D twisted model (30 complex Newton steps) */
static void setup_drc_insert_3d(void)
{
    setup_drc_insert();
    drc_b.p.z = 0.05f;
    drc_b.t.z = 0.08f;
}

static void call_drc_insert_3d(void)
{
    drc_insert(&drc_a, &drc_b, 0, &drc_m);
    bench_sink = (int32_t)(drc_m.p.y * 1000.0f);
}

/* steps 0-1 on 7 points: validation and the tangent assignment (once per RUN) */
static void call_drc_tangents(void)
{
    bench_sink = drc_tangents(drc_g.p, 1u, drc_tan, 1u, 7u);
}

static void setup_drc_tangents(void)
{
    drc_geom(0, 0, 5);
}

/* 32 streamed points = one original segment at K = 5 (32 inserted points): EDGE OFF */
static void setup_drc_curve32(void)
{
    static struct raster_cfg c; /* drc_path keeps a pointer to its raster */
    int i;
    drc_geom(0, 0, 5);
    memset(&c, 0, sizeof c);
    c.n = 1;
    c.tol = CP_R(0.001);
    bench_sink = drc_path_init(&drc_it, &drc_g, &c);
    for (i = 0; i < 64; i++) {
        bench_sink = drc_path_next(&drc_it, &drc_pt);
    }
}

static void call_drc_next32(void)
{
    int i;
    for (i = 0; i < 32; i++) {
        bench_sink = drc_path_next(&drc_it, &drc_pt);
    }
}

/* the same on a fillet (EDGE ON, 1 line, LINEAR radius law): + Lambda, frame, point */
static void setup_drc_edge32(void)
{
    static struct raster_cfg c; /* drc_path keeps a pointer to its raster */
    int i;
    drc_geom(1, 0, 5);
    memset(&c, 0, sizeof c);
    c.n = 1;
    c.u0 = CP_R(0.5);
    c.u1 = CP_R(0.5);
    c.tol = CP_R(0.001);
    c.link = RASTER_LINK_AUTO;
    drc_g.radius = CANAL_R_LINEAR;
    drc_g.rp[0] = CP_R(3.0);
    drc_g.rp[1] = CP_R(5.0);
    bench_sink = drc_path_init(&drc_it, &drc_g, &c);
    for (i = 0; i < 64; i++) {
        bench_sink = drc_path_next(&drc_it, &drc_pt);
    }
}

/* ---- CHANNEL (seed 002): the B.3 example (R = T(psi)T(theta)T(phi)) ---- */
static struct channel_cfg ch_g;
static struct channel_path ch_it;
static struct channel_row ch_row;
static struct raster_pt ch_pt;
static volatile cp_real ch_u = CP_R(0.731);

static void ch_geom(void)
{
    static const float abn[3][3] = {{5.0f, 3.5f, 2.0f}, {4.0f, 3.0f, 3.0f}, {3.5f, 2.5f, 6.0f}};
    static const float ang[3][3] = {{240.0f, 10.5882353f, 30.0f},
                                    {225.0f, 22.5f, 15.0f},
                                    {210.0f, 25.7142857f, 10.0f}};
    static const float cen[3][3] = {{3.0f, 4.5f, 1.0f}, {6.0f, 3.5f, 7.0f}, {7.0f, 1.0f, 14.0f}};
    int i;
    memset(&ch_g, 0, sizeof ch_g);
    ch_g.count = 3;
    for (i = 0; i < 3; i++) {
        ch_g.s[i].a = abn[i][0];
        ch_g.s[i].b = abn[i][1];
        ch_g.s[i].n = abn[i][2];
        ch_g.s[i].c.x = cen[i][0];
        ch_g.s[i].c.y = cen[i][1];
        ch_g.s[i].c.z = cen[i][2];
        channel_euler(&ch_g.s[i], ang[i][0] * CP_DEG2RAD, ang[i][1] * CP_DEG2RAD,
                      ang[i][2] * CP_DEG2RAD, CHANNEL_ORDER_SPIN_FIRST);
    }
}

static void ch_raster(struct raster_cfg *c, uint8_t mode)
{
    memset(c, 0, sizeof *c);
    c->mode = mode;
    c->n = 3;
    c->u0 = CP_R(-1.5);
    c->u1 = CP_R(1.5);
    c->steps = 200;
    c->link = 8;
}

/* one point of a LINES raster: every point is a new u (row: guide, laws, Beta constants,
 * section, frame; then the point and its normal; the angle's logs are cached per line) */
static void setup_ch_lines(void)
{
    struct raster_cfg c;
    ch_geom();
    ch_raster(&c, RASTER_LINES);
    bench_sink = channel_path_init(&ch_it, &ch_g, &c);
    bench_sink = channel_path_seek(&ch_it, 50u);
    bench_sink = channel_path_next(&ch_it, &ch_pt);
}

static void call_ch_next(void)
{
    bench_sink = channel_path_next(&ch_it, &ch_pt);
}

/* one point of a CIRCLES raster: the row is cached for the ring (sincos, 2 logs, 2 exps) */
static void setup_ch_circles(void)
{
    struct raster_cfg c;
    ch_geom();
    ch_raster(&c, RASTER_CIRCLES);
    bench_sink = channel_path_init(&ch_it, &ch_g, &c);
    bench_sink = channel_path_seek(&ch_it, 50u);
    bench_sink = channel_path_next(&ch_it, &ch_pt);
}

static void setup_ch_model(void)
{
    ch_geom();
    bench_sink = channel_init(&ch_it.ch, &ch_g);
}

static void call_ch_row(void)
{
    channel_row(&ch_it.ch, ch_u, &ch_row);
    bench_sink = (int32_t)(ch_row.ab[0] * 1000.0f);
}

/* RUN's validation: model, evaluation grid, step/link derivation and walks (LINES 3, 10 um) */
static void call_ch_init(void)
{
    struct raster_cfg c;
    ch_raster(&c, RASTER_LINES);
    c.steps = 0;
    c.tol = CP_R(0.01);
    c.link = RASTER_LINK_AUTO;
    bench_sink = channel_path_init(&ch_it, &ch_g, &c);
}

/* ---- the table: add routines here ---- */
/* ---- GSR (seed 003): one streamed point, rational vs trigonometric section ---- */
static struct gsr_cfg gsr_g;
static struct gsr_path gsr_it;
static struct raster_pt gsr_pt;

/* Bezier centre, polynomial radii, RMF: no trigonometry outside the section form. */
static void gsr_setup(uint8_t mode, uint8_t form, int g1)
{
    struct raster_cfg c;
    int i;
    memset(&gsr_g, 0, sizeof gsr_g);
    if (g1) { /* C.4 G1: two sinusoids (centre z and f_N): 2 sincos per new section */
        gsr_g.c[0][1] = 8.0f;
        gsr_g.c[2][GSR_B] = 2.0f;
        gsr_g.c[2][GSR_W] = CP_PI;
        gsr_g.r[0][0] = 1.2f;
        gsr_g.r[0][GSR_B] = 0.5f;
        gsr_g.r[0][GSR_W] = CP_PI;
        gsr_g.frame = GSR_FRAME_FIXED;
    } else {
        static const float bz[4][3] = {{0, 0, 0}, {4, 0, 2}, {8, 3, 2}, {12, 3, 0}};
        for (i = 0; i < 12; i++) {
            gsr_g.c[i % 3][i / 3] = bz[i / 3][i % 3];
        }
        gsr_g.centre = GSR_CENTRE_BEZIER;
        gsr_g.r[0][0] = 0.8f;
        gsr_g.frame = GSR_FRAME_RMF;
        gsr_g.ref.z = 1.0f;
    }
    gsr_g.r[1][0] = 0.8f;
    gsr_g.r[1][1] = 0.3f;
    gsr_g.r[2][1] = 1.0f;
    gsr_g.section = form;
    memset(&c, 0, sizeof c);
    c.mode = mode;
    c.n = 3;
    c.u0 = -CP_PI;
    c.u1 = CP_PI;
    c.steps = 64;
    c.link = 0;
    bench_sink = gsr_path_init(&gsr_it, &gsr_g, &c);
    for (i = 0; i < 20; i++) {
        bench_sink = gsr_path_next(&gsr_it, &gsr_pt);
    }
}

static void setup_gsr_ring_rational(void)
{
    gsr_setup(RASTER_CIRCLES, GSR_SECTION_RATIONAL, 0);
}

static void setup_gsr_ring_trig(void)
{
    gsr_setup(RASTER_CIRCLES, GSR_SECTION_TRIG, 0);
}

static void setup_gsr_line_rational(void)
{
    gsr_setup(RASTER_LINES, GSR_SECTION_RATIONAL, 0);
}

static void setup_gsr_line_g1(void)
{
    gsr_setup(RASTER_LINES, GSR_SECTION_RATIONAL, 1);
}

static void call_gsr_next(void)
{
    bench_sink = gsr_path_next(&gsr_it, &gsr_pt);
}

static volatile cp_real gsr_psi_arg = CP_R(0.37);

static void call_gsr_rational(void)
{
    cp_real x, y;
    gsr_unit_rational(gsr_psi_arg, &x, &y);
    bench_sink = (int32_t)(x * 1000.0f + y);
}

static void call_gsr_init(void)
{
    struct raster_cfg c;
    memset(&c, 0, sizeof c);
    c.mode = RASTER_LINES;
    c.n = 5;
    c.u0 = -0.5f * CP_PI;
    c.u1 = 0.5f * CP_PI;
    c.tol = 0.002f;
    c.link = RASTER_LINK_AUTO;
    bench_sink = gsr_path_init(&gsr_it, &gsr_g, &c);
}

/* even arc length on the G1 section 1.7 x 0.95 (library; not in the streamed path) */
static struct gsr_arclen gsr_arc;
static volatile cp_real gsr_arc_f = CP_R(0.3712);

static void setup_gsr_arclen(void)
{
    bench_sink = gsr_arclen_init(&gsr_arc, CP_R(1.7), CP_R(0.95));
}

static void call_gsr_arclen_angle(void)
{
    bench_sink = (int32_t)(gsr_arclen_angle(&gsr_arc, gsr_arc_f) * 1000.0f);
}

static void call_gsr_arclen_init(void)
{
    bench_sink = gsr_arclen_init(&gsr_arc, CP_R(1.7), CP_R(0.95));
}

/* placement on the part (proto/place.h): the per-point transform of p and n, and the
 * once-per-RUN matrix (PLACE 120 -45 30 35, TILT 45 30) */
static struct place bench_pl;
static struct raster_pt bench_ppt;
static const struct job_place bench_jp = {{CP_R(120.0), CP_R(-45.0), CP_R(30.0)}, CP_R(35.0),
                                          CP_R(45.0), CP_R(30.0)};

static void setup_place(void)
{
    place_init(&bench_pl, &bench_jp);
    memset(&bench_ppt, 0, sizeof bench_ppt);
    bench_ppt.p.x = CP_R(12.5);
    bench_ppt.p.y = CP_R(-3.25);
    bench_ppt.p.z = CP_R(4.0);
    bench_ppt.n.z = CP_R(1.0);
}

static void call_place_apply(void)
{
    place_apply(&bench_pl, &bench_ppt);
    bench_sink = (int32_t)(bench_ppt.p.x + bench_ppt.n.y);
}

static void call_place_init(void)
{
    place_init(&bench_pl, &bench_jp);
    bench_sink = (int32_t)bench_pl.on;
}

/* ---- SPINE (issue 18): one streamed point of one line, and one more line at the same node ---- */
static struct spine_path sp_it;
static struct raster_pt sp_pt;
static struct spine_state sp_st;
static struct spine_label sp_lab;
static struct spine_cfg sp_g;

/* helix tube (axis z, r 15, pitch 10, 2 turns) with R = 1.5 cos(8 pi u) + 4 (COS law), or the
 * Bezier blend with a CUBIC radius (tests/test_spine.c shapes); LINES 4 x 257 points: one
 * march step per 256 / N points (N by step doubling). `skip` points first: 100 lands on line 0 (forward), 400 on line 1
 * (the backward pass). */
static void spine_setup(int bezier, uint32_t skip)
{
    static const cp_real helix[12] = {0, 0, 0, 0, 0, 1, 15, 10, 2, 1, 0, 0};
    static const cp_real bez[12] = {0, 0, 0, 25, 35, 15, 60, -25, 35, 90, 10, 5};
    struct spine_cfg *g = &sp_g;
    struct raster_cfg c;
    uint32_t i;
    memset(g, 0, sizeof *g);
    memset(&c, 0, sizeof c);
    g->kind = bezier ? SPINE_BEZIER : SPINE_HELIX;
    g->law = bezier ? SPINE_R_CUBIC : SPINE_R_COS;
    memcpy(g->sp, bezier ? bez : helix, sizeof g->sp);
    g->rp[0] = bezier ? CP_R(3.0) : CP_R(1.5);
    g->rp[1] = bezier ? CP_R(6.0) : CP_R(4.0);
    g->rp[2] = bezier ? CP_R(2.0) : CP_R(4.0);
    g->rp[3] = bezier ? CP_R(5.0) : CP_R(0.0);
    c.mode = RASTER_LINES;
    c.n = 4;
    c.u0 = CP_R(-2.5);
    c.u1 = CP_R(2.5);
    c.steps = 256;
    c.link = 0;
    c.output = RASTER_OUT_CENTRE;
    c.tool_r = CP_R(1.0);
    bench_sink = spine_path_init(&sp_it, g, &c);
    for (i = 0; i < skip; i++) {
        bench_sink = spine_path_next(&sp_it, &sp_pt);
    }
}

static void setup_spine_helix_fwd(void)
{
    spine_setup(0, 100u);
}

static void setup_spine_helix_back(void)
{
    spine_setup(0, 400u);
}

static void setup_spine_bezier_fwd(void)
{
    spine_setup(1, 100u);
}

static void call_spine_next(void)
{
    bench_sink = spine_path_next(&sp_it, &sp_pt);
}

/* a whole line (256 points after its first, from point 1 of line 0 or 259 of line 1):
 * the march's steps are amortized as in a stream, so raw / 256 is the mean per point */
static void setup_spine_helix_line(void)
{
    spine_setup(0, 1u);
}

static void setup_spine_helix_line_back(void)
{
    spine_setup(0, 259u);
}

static void setup_spine_bezier_line(void)
{
    spine_setup(1, 1u);
}

static void call_spine_line(void)
{
    uint32_t i;
    for (i = 0; i < 256u; i++) {
        bench_sink = spine_path_next(&sp_it, &sp_pt);
    }
}

/* the node state of the helix at u = 100/256, the label made once: what a second line at
 * the same node costs (spine_point_label; the label's cp_sincos is per line, once) */
static void setup_spine_extra(void)
{
    spine_setup(0, 0u);
    bench_sink = spine_node(&sp_it.s, 100u, &sp_st);
    spine_label(CP_R(0.7), &sp_lab);
}

static void call_spine_extra(void)
{
    spine_point_label(&sp_st, &sp_lab, CP_R(-1.0), &sp_pt);
    bench_sink = (int32_t)(sp_pt.p.z * CP_R(1000.0));
}

/* The parts of a point (MATH-spine 9.7): the full jet, and the point state at u = 101/256
 * (between two march nodes) with the march already there: what a point costs without a
 * march step (the streamed rows add the amortized step and the label and point). */
static struct spine_jet sp_j;

static void call_spine_jet(void)
{
    spine_jet(&sp_it.s, CP_R(0.37), &sp_j);
    bench_sink = (int32_t)(sp_j.c.x);
}

static void setup_spine_eval(int bezier)
{
    spine_setup(bezier, 0u);
    bench_sink = spine_eval(&sp_it.s, 101u, 256u, 0u, 0u, &sp_st);
}

static void setup_spine_eval_bezier(void)
{
    setup_spine_eval(1);
}

static void setup_spine_eval_helix(void)
{
    setup_spine_eval(0);
}

static void call_spine_eval(void)
{
    bench_sink = spine_eval(&sp_it.s, 101u, 256u, 0u, 0u, &sp_st);
}
/* spine_path_init of the Bezier blend, LINES 4, TOL 2 um (steps and link derived) */
static void call_spine_init(void)
{
    struct raster_cfg c;
    memset(&c, 0, sizeof c);
    c.mode = RASTER_LINES;
    c.n = 4;
    c.u0 = CP_R(-2.5);
    c.u1 = CP_R(2.5);
    c.tol = CP_R(0.002);
    c.link = RASTER_LINK_AUTO;
    c.output = RASTER_OUT_CENTRE;
    c.tool_r = CP_R(1.0);
    bench_sink = spine_path_init(&sp_it, &sp_g, &c);
}

static const struct bench_case cases[] = {
    {"empty", setup_none, call_empty}, /* must stay first: the baseline */
    {"fmt_fixed", setup_fmt_fixed, call_fmt_fixed},
    {"proto_poll_idle", setup_proto_idle, call_proto_idle},
    {"proto_poll_$I_line", setup_proto_info, call_proto_info},
    {"canal_path_next_1line", setup_tp_next, call_tp_next},
    {"canal_path_next_ellipse", setup_tp_next_ellipse, call_tp_next},
    {"canal_point_extra_line", setup_extra_line, call_extra_line},
    {"canal_jet_arc_cos", setup_tp_next, call_jet},
    {"frenet_baseline_step", setup_frenet, call_frenet},
    {"cp_sincos", setup_none, call_sincos},
    {"canal_frame", setup_frame, call_frame},
    {"canal_path_init_tol2um", setup_none, call_tp_init},
    {"drc_insert_planar", setup_drc_insert, call_drc_insert_planar},
    {"drc_insert_3d", setup_drc_insert_3d, call_drc_insert_3d},
    {"drc_tangents_7pt", setup_drc_tangents, call_drc_tangents},
    {"drc_next_curve_x32", setup_drc_curve32, call_drc_next32},
    {"drc_next_edge_x32", setup_drc_edge32, call_drc_next32},
    {"channel_next_lines", setup_ch_lines, call_ch_next},
    {"channel_next_circles", setup_ch_circles, call_ch_next},
    {"channel_row", setup_ch_model, call_ch_row},
    {"channel_init_tol10um", setup_ch_model, call_ch_init},
    {"gsr_ring_pt_rational", setup_gsr_ring_rational, call_gsr_next},
    {"gsr_ring_pt_trig", setup_gsr_ring_trig, call_gsr_next},
    {"gsr_line_pt_bezier_rmf", setup_gsr_line_rational, call_gsr_next},
    {"gsr_line_pt_g1", setup_gsr_line_g1, call_gsr_next},
    {"gsr_unit_rational", setup_none, call_gsr_rational},
    {"gsr_init_g1_tol2um", setup_gsr_line_g1, call_gsr_init},
    {"gsr_arclen_angle", setup_gsr_arclen, call_gsr_arclen_angle},
    {"gsr_arclen_init", setup_none, call_gsr_arclen_init},
    {"place_apply_point", setup_place, call_place_apply},
    {"place_init_run", setup_place, call_place_init},
    {"spine_pt_helix_cos", setup_spine_helix_fwd, call_spine_next},
    {"spine_pt_helix_cos_back", setup_spine_helix_back, call_spine_next},
    {"spine_pt_bezier_cubic", setup_spine_bezier_fwd, call_spine_next},
    {"spine_point_extra_line", setup_spine_extra, call_spine_extra},
    {"spine_line_helix_cos_x256", setup_spine_helix_line, call_spine_line},
    {"spine_line_helix_back_x256", setup_spine_helix_line_back, call_spine_line},
    {"spine_line_bezier_x256", setup_spine_bezier_line, call_spine_line},
    {"spine_jet_bezier_cubic", setup_spine_eval_bezier, call_spine_jet},
    {"spine_jet_helix_cos", setup_spine_eval_helix, call_spine_jet},
    {"spine_eval_bezier_cubic", setup_spine_eval_bezier, call_spine_eval},
    {"spine_eval_helix_cos", setup_spine_eval_helix, call_spine_eval},
    {"spine_init_bezier_tol2um", setup_spine_bezier_fwd, call_spine_init},
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
    return ticks_to_insns(t0, t1);
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
