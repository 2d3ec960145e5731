/* test_proto.c - fmt and the line protocol engine over the in-memory HAL.
 * SPDX-License-Identifier: MIT
 */
#include <string.h>

#include "fmt.h"
#include "hal_mem.h"
#include "proto.h"
#include "test.h"

int test_fmt_numbers(void)
{
    char b[64];
    size_t pos = 0;
    CHECK_EQ_INT(fmt_u32(b, sizeof b, &pos, 0u), CP_OK);
    CHECK_EQ_INT(fmt_str(b, sizeof b, &pos, " "), CP_OK);
    CHECK_EQ_INT(fmt_u32(b, sizeof b, &pos, 4294967295u), CP_OK);
    CHECK_EQ_INT(fmt_str(b, sizeof b, &pos, " "), CP_OK);
    CHECK_EQ_INT(fmt_i32(b, sizeof b, &pos, -2147483647 - 1), CP_OK);
    CHECK_EQ_INT(fmt_str(b, sizeof b, &pos, " "), CP_OK);
    CHECK_EQ_INT(fmt_fixed(b, sizeof b, &pos, -12345, 4), CP_OK);
    CHECK_EQ_INT(fmt_str(b, sizeof b, &pos, " "), CP_OK);
    CHECK_EQ_INT(fmt_fixed(b, sizeof b, &pos, 7, 4), CP_OK);
    CHECK_EQ_INT(fmt_str(b, sizeof b, &pos, " "), CP_OK);
    CHECK_EQ_INT(fmt_fixed(b, sizeof b, &pos, -7, 3), CP_OK);
    b[pos] = '\0';
    CHECK(strcmp(b, "0 4294967295 -2147483648 -1.2345 0.0007 -0.007") == 0);
    /* a full buffer is reported, never overrun */
    pos = 0;
    CHECK_EQ_INT(fmt_u32(b, 3, &pos, 12345u), CP_ERR_FULL);
    CHECK_EQ_INT(pos, 0);
    CHECK_EQ_INT(fmt_fixed(b, 64, &pos, 1, 10), CP_ERR_INVAL);
    return 0;
}

/* Run the engine until it is idle for a few polls (bounded). */
static void pump(struct proto *p)
{
    int idle = 0, i;
    for (i = 0; i < 100000 && idle < 4; i++) {
        idle = proto_poll(p) > 0 ? 0 : idle + 1;
    }
}

/* cp_status_of: the FROM column of cp_status.def, CP_ERR_INVAL as OUT_OF_RANGE and the
 * codes no row names as NUMERIC (the mapping job_status_of had, case by case). */
int test_status_of(void)
{
    static const struct {
        int err, st;
    } map[] = {
        {CP_OK, CP_ST_OK},
        {CP_ERR_INVAL, CP_ST_OUT_OF_RANGE},
        {CP_ERR_NONFINITE, CP_ST_NONFINITE},
        {CP_ERR_RANGE, CP_ST_OUT_OF_RANGE},
        {CP_ERR_RADIUS, CP_ST_RADIUS},
        {CP_ERR_DEGENERATE, CP_ST_DEGENERATE},
        {CP_ERR_EMPTY, CP_ST_EMPTY},
        {CP_ERR_TOO_MANY, CP_ST_TOO_MANY},
        {CP_ERR_TOOL, CP_ST_TOOL},
        {CP_ERR_CUSP, CP_ST_CUSP},
        {CP_ERR_NUMERIC, CP_ST_NUMERIC},
        {CP_ERR_TOL, CP_ST_TOL},
        {CP_ERR_IO, CP_ST_NUMERIC},
        {CP_ERR_FULL, CP_ST_NUMERIC},
        {CP_ERR_STATE, CP_ST_NUMERIC},
        {CP_ERR_DONE, CP_ST_NUMERIC},
        {CP_ERR_OFF_PLANE, CP_ST_OFF_PLANE},
        {CP_ERR_FRENET, CP_ST_FRENET},
        {CP_ERR_FRAME_REF, CP_ST_FRAME_REF},
        {CP_ERR_SECTION, CP_ST_SECTION},
        {CP_ERR_FT_RANGE, CP_ST_FT_RANGE},
        {CP_ERR_FOLD, CP_ST_FOLD},
        {CP_ERR_TOO_FEW, CP_ST_TOO_FEW},
        {CP_ERR_EXPONENT, CP_ST_EXPONENT},
        {CP_ERR_COINCIDENT, CP_ST_COINCIDENT},
        {CP_ERR_SECTION_PLANE, CP_ST_SECTION_PLANE},
        {CP_ERR_AREA_LAW, CP_ST_AREA_LAW},
        {CP_ERR_ISOTROPIC, CP_ST_ISOTROPIC},
        {CP_ERR_TURN, CP_ST_TURN},
        {CP_ERR_TWIST, CP_ST_TWIST},
        {CP_ERR_BUFFER, CP_ST_BUFFER},
        {-31, CP_ST_NUMERIC}, /* not (yet) an enum cp_err */
        {1, CP_ST_NUMERIC},   /* WIRE_ONLY's value is no cp_err */
    };
    unsigned i;
    for (i = 0; i < sizeof map / sizeof map[0]; i++) {
        CHECK_EQ_INT(cp_status_of(map[i].err), map[i].st);
    }
    return 0;
}

int test_proto_info(void)
{
    static struct hal_mem m;
    struct hal_uart u;
    struct proto p;
    struct proto_cfg cfg;
    static char want[512];
    char line[CP_LINE_MAX + 40];
    size_t i;

    hal_mem_init(&m, &u);
    cfg.uart = &u;
    CHECK_EQ_INT(proto_init(&p, &cfg), CP_OK);
    cfg.uart = NULL;
    CHECK_EQ_INT(proto_init(&p, &cfg), CP_ERR_INVAL);
    cfg.uart = &u;
    CHECK_EQ_INT(proto_init(&p, &cfg), CP_OK);

    /* nothing is streamed before the host has spoken */
    pump(&p);
    CHECK_EQ_INT(m.out_len, 0);

    m.write_chunk = 3; /* partial writes are normal */
    hal_mem_feed_str(&m, "$I\r\nhello\n\nFOO\n");
    pump(&p);
    snprintf(want, sizeof want,
             "[VER:canalpath %s proto %d]\n[OPT:real=%s,line=%d,tx=%d,steps=%d,sub=%d,lines=%d,"
             "link=%d,window=%d,models=CANAL%s%s%s]\nok\n",
             CP_FW_VERSION, CP_PROTO_VERSION, CP_REAL_NAME, CP_LINE_MAX, CP_TX_BUF, CP_MAX_STEPS,
             CP_MAX_SUBSTEPS, CP_MAX_LINES, CP_MAX_LINK, (int)PROTO_WINDOW,
             PATH_HAVE_GSR ? "+GSR" : "", PATH_HAVE_CHANNEL ? "+CHANNEL" : "",
             PATH_HAVE_DRC ? "+DRC" : "");
    i = strlen(want);
    CHECK(m.out_len == 2 * i + strlen("ok\nerror:1 unknown command\n"));
    CHECK(memcmp(m.out, want, i) == 0);
    CHECK(memcmp(m.out + i, want, i) == 0);
    CHECK(memcmp(m.out + 2 * i, "ok\nerror:1 unknown command\n", 27) == 0);

    /* an over-long line and a line with a control byte get their codes, and the
     * engine is ready for the next line */
    hal_mem_clear_out(&m);
    memset(line, 'A', sizeof line);
    line[sizeof line - 1] = '\n';
    hal_mem_feed(&m, line, sizeof line);
    hal_mem_feed(&m, "$\x01I\n$i\n", 7);
    pump(&p);
    CHECK(m.out_len > 40);
    CHECK(memcmp(m.out, "error:2 line too long\nerror:8 invalid character in line\n[VER:", 60) ==
          0);

    /* hang-up is reported and sticky */
    hal_mem_hangup(&m);
    hal_mem_feed_str(&m, "$I\n");
    CHECK_EQ_INT(proto_poll(&p), CP_ERR_IO);
    CHECK_EQ_INT(proto_poll(&p), CP_ERR_IO);
    return 0;
}
