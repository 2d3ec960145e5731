/* test_raster.c - the shared raster plumbing (raster.h): checks and their precedence,
 * the zigzag layout against an independent enumeration, seek, and the tolerance search
 * (driven with synthetic sagittas s = C / m^2, as the models' walks would measure).
 * SPDX-License-Identifier: MIT
 */
#include <string.h>

#include "raster.h"
#include "test.h"

static void base(struct raster_cfg *c)
{
    memset(c, 0, sizeof *c);
    c->mode = RASTER_LINES;
    c->n = 3;
    c->u0 = CP_R(-1.0);
    c->u1 = CP_R(1.0);
    c->link = RASTER_LINK_AUTO;
    c->tol = CP_R(0.001);
}

int test_raster_check(void)
{
    struct raster_cfg c;
    base(&c);
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_OK);
    CHECK_EQ_INT(raster_check(NULL, CP_PI), CP_ERR_INVAL);
    c.mode = 2;
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_INVAL);
    base(&c);
    c.output = RASTER_OUT_TIP + 1u;
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_INVAL);
    base(&c);
    c.tool_r = CP_R(1.0); /* a tool with OUT_SURFACE */
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_INVAL);
    c.output = RASTER_OUT_CENTRE;
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_OK);
    c.tool_r = CP_R(-1.0);
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_TOOL);
    base(&c);
    c.u1 = (cp_real)INFINITY;
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_NONFINITE);
    c.u1 = (cp_real)NAN;
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_NONFINITE);
    base(&c);
    c.tol = (cp_real)NAN;
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_NONFINITE);
    base(&c);
    c.u1 = CP_R(3.2);
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_RANGE);
    CHECK_EQ_INT(raster_check(&c, CP_R(4.0)), CP_OK); /* umax is the caller's */
    base(&c);
    c.u1 = c.u0;
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_RANGE);
    c.n = 1;
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_OK);
    c.n = 0;
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_RANGE);
    base(&c);
    c.tol = CP_R(0.0); /* steps == 0: nothing to derive them from */
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_RANGE);
    c.steps = 10;
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_OK);
    c.tol = CP_R(11.0);
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_RANGE);
    c.tol = CP_R(1e-6);
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_RANGE);
    base(&c);
    c.link = CP_MAX_LINK;
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_OK);
    c.link = CP_MAX_LINK + 1u;
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_RANGE);
    base(&c);
    c.n = CP_MAX_LINES + 1u;
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_TOO_MANY);
    c.n = 3;
    c.steps = CP_MAX_STEPS + 1u;
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_TOO_MANY);
    /* precedence: INVAL, NONFINITE, RANGE, TOO_MANY, TOOL */
    c.link = CP_MAX_LINK + 1u; /* RANGE and TOO_MANY */
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_RANGE);
    c.output = RASTER_OUT_CENTRE;
    c.tool_r = CP_R(-1.0); /* + TOOL */
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_RANGE);
    c.u0 = (cp_real)NAN; /* + NONFINITE */
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_NONFINITE);
    c.output = RASTER_OUT_SURFACE; /* + INVAL (a tool with OUT_SURFACE) */
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_INVAL);
    base(&c);
    c.steps = CP_MAX_STEPS + 1u;
    c.output = RASTER_OUT_TIP;
    c.tool_r = CP_R(-2.0);
    CHECK_EQ_INT(raster_check(&c, CP_PI), CP_ERR_TOO_MANY);
    return 0;
}

/* Layout: every point of rasters up to n = 4, steps = 5, link = 3 against a plain
 * enumeration (lines zigzag, links in travel order); count; seek. */
int test_raster_layout(void)
{
    uint32_t n, st, lk;
    for (n = 1; n <= 4u; n++) {
        for (st = 1; st <= 5u; st++) {
            for (lk = 0; lk <= 3u; lk++) {
                uint32_t k = 0, j, r, cnt = raster_count(n, st, lk);
                struct raster_head h = {0};
                struct raster_at at;
                for (j = 0; j < n; j++) {
                    for (r = 0; r <= st; r++, k++) {
                        raster_locate(k, st, lk, &at);
                        CHECK_EQ_INT(at.j, j);
                        CHECK_EQ_INT(at.a, 0);
                        CHECK_EQ_INT(at.line, (int32_t)j);
                        CHECK_EQ_INT(at.i, (j & 1u) ? st - r : r);
                        CHECK_EQ_INT(at.index, at.i);
                    }
                    for (r = 1; j + 1u < n && r <= lk; r++, k++) {
                        raster_locate(k, st, lk, &at);
                        CHECK_EQ_INT(at.j, j);
                        CHECK_EQ_INT(at.a, r);
                        CHECK_EQ_INT(at.line, -1);
                        CHECK_EQ_INT(at.index, r);
                        CHECK_EQ_INT(at.i, (j & 1u) ? 0u : st); /* where line j stopped */
                    }
                }
                CHECK_EQ_INT(cnt, k);
                h.count = cnt;
                h.k = 7u;
                CHECK_EQ_INT(raster_seek(&h, cnt), CP_OK);
                CHECK_EQ_INT(h.k, cnt);
                CHECK_EQ_INT(raster_seek(&h, cnt + 1u), CP_ERR_RANGE);
                CHECK_EQ_INT(h.k, cnt);
            }
        }
    }
    /* the largest raster (and the doubled walk rasters) do not overflow */
    CHECK_EQ_INT(raster_count(CP_MAX_LINES, 2u * CP_MAX_STEPS, 2u * CP_MAX_LINK + 1u),
                 (uint32_t)CP_MAX_LINES * (2u * CP_MAX_STEPS + 1u) +
                     (uint32_t)(CP_MAX_LINES - 1u) * (2u * CP_MAX_LINK + 1u));
    return 0;
}

/* Drive a search with sagittas C[q] / m^2 (mm); returns the update result, rounds in *r. */
static int drive(struct raster_fit *f, const double *cq, int *r)
{
    int round, err = RASTER_FIT_MORE;
    for (round = 0; round <= RASTER_FIT_ROUNDS && err == RASTER_FIT_MORE; round++) {
        cp_real sag[2];
        sag[0] = (cp_real)(cq[0] / ((double)f->m[0] * (double)f->m[0]));
        sag[1] = (cp_real)(cq[1] / ((double)f->m[1] * (double)f->m[1]));
        err = raster_fit_update(f, sag);
    }
    *r = round;
    return err;
}

int test_raster_fit(void)
{
    static const struct raster_rule grow = {CP_R(0.9), CP_R(0.9), 8u, 0u, 31u, 1u};
    static const struct raster_rule pilot = {CP_R(0.8), CP_R(1.0), 32u, 1u, 3u, 0u};
    struct raster_cfg c;
    struct raster_fit f;
    double cq[2];
    int rounds;
    base(&c);
    /* derived steps and link: the results meet the rule's acceptance */
    cq[0] = 10.0; /* steps >= sqrt(10 / 0.9e-3) = 105.4 */
    cq[1] = 0.5;  /* link segments >= sqrt(0.5 / 0.9e-3) = 23.6 */
    raster_fit_begin(&f, &c, &grow);
    CHECK_EQ_INT(f.m[0], 8);
    CHECK_EQ_INT(f.m[1], 1);
    CHECK_EQ_INT(drive(&f, cq, &rounds), CP_OK);
    CHECK(f.m[0] >= 106u && f.m[0] <= 120u);
    CHECK(f.m[1] >= 24u && f.m[1] <= 28u);
    TEST_NOTE("grow: steps %u link %u in %d walks\n", (unsigned)f.m[0], (unsigned)(f.m[1] - 1u),
              rounds);
    raster_fit_begin(&f, &c, &pilot);
    CHECK_EQ_INT(f.m[0], 32);
    CHECK_EQ_INT(drive(&f, cq, &rounds), CP_OK);
    CHECK(f.m[0] >= 112u && f.m[0] <= 125u); /* aimed at 0.8 tol: >= 111.8 */
    CHECK(f.m[1] >= 25u && f.m[1] <= 29u);
    /* the pilot re-estimates downwards, not below RASTER_MIN_STEPS */
    cq[0] = 1e-4;
    cq[1] = 1e-7;
    raster_fit_begin(&f, &c, &pilot);
    CHECK_EQ_INT(drive(&f, cq, &rounds), CP_OK);
    CHECK_EQ_INT(f.m[0], RASTER_MIN_STEPS);
    CHECK_EQ_INT(f.m[1], 1);
    CHECK_EQ_INT(rounds, 2); /* the pilot, then the verification */
    raster_fit_begin(&f, &c, &grow); /* without a pilot: verified at once, kept */
    CHECK_EQ_INT(drive(&f, cq, &rounds), CP_OK);
    CHECK_EQ_INT(f.m[0], 8);
    CHECK_EQ_INT(rounds, 1);
    /* given counts are never changed (and n == 1 has no link) */
    c.steps = 12;
    c.link = 2;
    cq[0] = cq[1] = 1e3;
    raster_fit_begin(&f, &c, &grow);
    CHECK_EQ_INT(f.derive, 0);
    CHECK_EQ_INT(drive(&f, cq, &rounds), CP_OK);
    CHECK_EQ_INT(f.m[0], 12);
    CHECK_EQ_INT(f.m[1], 3);
    c.n = 1;
    c.link = RASTER_LINK_AUTO;
    raster_fit_begin(&f, &c, &grow);
    CHECK_EQ_INT(f.derive, 0);
    CHECK_EQ_INT(f.m[1], 1);
    /* out of reach: clamp tries the maximum, then CP_ERR_TOL; no clamp: at once */
    base(&c);
    cq[0] = 1e6;
    cq[1] = 1e-9;
    raster_fit_begin(&f, &c, &grow);
    CHECK_EQ_INT(drive(&f, cq, &rounds), CP_ERR_TOL);
    CHECK_EQ_INT(f.m[0], CP_MAX_STEPS);
    CHECK_EQ_INT(rounds, 2);
    raster_fit_begin(&f, &c, &pilot);
    CHECK_EQ_INT(drive(&f, cq, &rounds), CP_ERR_TOL);
    CHECK_EQ_INT(rounds, 1);
    /* a link out of reach (tol == 0 with given steps: links at 1 um) */
    base(&c);
    c.tol = CP_R(0.0);
    c.steps = 8;
    cq[0] = 0.0;
    cq[1] = 1.0; /* needs sqrt(1 / 0.9e-3) = 33 segments: fine */
    raster_fit_begin(&f, &c, &grow);
    CHECK_EQ_INT(drive(&f, cq, &rounds), CP_OK);
    CHECK(f.m[1] >= 34u && f.m[1] <= CP_MAX_LINK + 1u);
    cq[1] = 100.0; /* 334 segments: more than CP_MAX_LINK + 1 */
    raster_fit_begin(&f, &c, &grow);
    CHECK_EQ_INT(drive(&f, cq, &rounds), CP_ERR_TOL);
    /* a sagitta that never converges (does not fall with m): CP_ERR_TOL after the last
     * round, never RASTER_FIT_MORE past it */
    base(&c);
    {
        int round, err = RASTER_FIT_MORE;
        cp_real sag[2] = {CP_R(0.01), CP_R(0.0)};
        raster_fit_begin(&f, &c, &grow);
        for (round = 0; round <= RASTER_FIT_ROUNDS && err == RASTER_FIT_MORE; round++) {
            err = raster_fit_update(&f, sag);
        }
        CHECK_EQ_INT(err, CP_ERR_TOL);
        CHECK_EQ_INT(round, RASTER_FIT_ROUNDS + 1);
    }
    return 0;
}
