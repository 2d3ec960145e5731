/* test_parse.c - number and token parsing: table-driven valid and invalid vectors.
 * SPDX-License-Identifier: MIT
 */
#include <string.h>

#include "parse.h"
#include "test.h"

struct num_vec {
    const char *s;
    int status;
    double value;
};

static const struct num_vec nums[] = {
    {"0", CP_ST_OK, 0.0},          {"-0", CP_ST_OK, 0.0},
    {"3", CP_ST_OK, 3.0},          {"+3.25", CP_ST_OK, 3.25},
    {"-12.5", CP_ST_OK, -12.5},    {".5", CP_ST_OK, 0.5},
    {"5.", CP_ST_OK, 5.0},         {"1e3", CP_ST_OK, 1000.0},
    {"2.5E-3", CP_ST_OK, 0.0025},  {"360", CP_ST_OK, 360.0},
    {"0.0001", CP_ST_OK, 1e-4},    {"123456789012", CP_ST_OUT_OF_RANGE, 0.0},
    {"31.41592653589793", CP_ST_OK, 31.41592653589793},
    {"1e-60", CP_ST_OK, 0.0},      {"1e99", CP_ST_OUT_OF_RANGE, 0.0},
    {"", CP_ST_BAD_NUMBER, 0.0},   {"-", CP_ST_BAD_NUMBER, 0.0},
    {".", CP_ST_BAD_NUMBER, 0.0},  {"1e", CP_ST_BAD_NUMBER, 0.0},
    {"1e+", CP_ST_BAD_NUMBER, 0.0}, {"1.2.3", CP_ST_BAD_NUMBER, 0.0},
    {"12x", CP_ST_BAD_NUMBER, 0.0}, {"0x10", CP_ST_BAD_NUMBER, 0.0},
    {"--1", CP_ST_BAD_NUMBER, 0.0}, {"nan", CP_ST_NONFINITE, 0.0},
    {"-INF", CP_ST_NONFINITE, 0.0}, {"Infinity", CP_ST_NONFINITE, 0.0},
    {"nanx", CP_ST_BAD_NUMBER, 0.0},
};

int test_parse_numbers(void)
{
    size_t i;
    for (i = 0; i < sizeof nums / sizeof nums[0]; i++) {
        cp_real v = CP_R(-999.0);
        int st = parse_real(nums[i].s, strlen(nums[i].s), &v);
        if (st != nums[i].status) {
            printf("  vector %u \"%s\": status %d, want %d\n", (unsigned)i, nums[i].s, st,
                   nums[i].status);
            return __LINE__;
        }
        if (st == CP_ST_OK) {
            CHECK_NEAR(v, nums[i].value, 0.0, 2.0 * CP_REAL_EPS);
        }
    }
    {
        uint32_t u = 0;
        CHECK_EQ_INT(parse_uint("4096", 4, 4096u, &u), CP_ST_OK);
        CHECK_EQ_INT(u, 4096);
        CHECK_EQ_INT(parse_uint("4097", 4, 4096u, &u), CP_ST_OUT_OF_RANGE);
        CHECK_EQ_INT(parse_uint("7", 1, 5u, &u), CP_ST_OUT_OF_RANGE);
        CHECK_EQ_INT(parse_uint("99999999999", 11, 0xFFFFFFFFu, &u), CP_ST_OUT_OF_RANGE);
        CHECK_EQ_INT(parse_uint("1.5", 3, 10u, &u), CP_ST_BAD_NUMBER);
        CHECK_EQ_INT(parse_uint("", 0, 10u, &u), CP_ST_BAD_NUMBER);
        CHECK_EQ_INT(parse_uint("-1", 2, 10u, &u), CP_ST_BAD_NUMBER);
    }
    return 0;
}

int test_parse_tokens(void)
{
    const char *l = "  CURVE  arc 0 0   3 ";
    uint16_t st[4], ln[4];
    CHECK_EQ_INT(parse_split(l, strlen(l), st, ln, 4), 5); /* too many for 4 */
    CHECK_EQ_INT(parse_split(l, strlen(l), st, ln, 3), 4);
    l = "CURVE arc 0";
    CHECK_EQ_INT(parse_split(l, strlen(l), st, ln, 4), 3);
    CHECK(parse_is(l + st[1], ln[1], "ARC"));
    CHECK(!parse_is(l + st[1], ln[1], "AR"));
    CHECK(!parse_is(l + st[0], ln[0], "CURVES"));
    CHECK_EQ_INT(parse_split("", 0, st, ln, 4), 0);
    return 0;
}
