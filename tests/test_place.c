/* test_place.c - placement on the part (firmware/proto/place.h): the matrix is a rotation
 * (orthonormal, det +1), known rotations (multiples of 90 exact, TILT's sense), the
 * identity is recognised (no transform: the stream stays byte-identical), the inverse
 * round trip, the float transform against a double one (um), and PLACE/TILT's checks.
 * SPDX-License-Identifier: MIT
 */
#include <string.h>

#include "job.h"
#include "place.h"
#include "test.h"

#define PL_FLOAT (sizeof(cp_real) == sizeof(float))

static void jp_set(struct job_place *jp, double x, double y, double z, double rz, double axis,
                   double tilt)
{
    jp->off[0] = (cp_real)x;
    jp->off[1] = (cp_real)y;
    jp->off[2] = (cp_real)z;
    jp->rz = (cp_real)rz;
    jp->axis = (cp_real)axis;
    jp->tilt = (cp_real)tilt;
}

/* R's entry (i, j) as double */
static double pl_r(const struct place *pl, int i, int j)
{
    const struct cp_vec3 *r = &pl->row[i];
    return (double)(j == 0 ? r->x : (j == 1 ? r->y : r->z));
}

/* The double reference: R = T(axis, tilt) Rz(rz), libm sin/cos (independent of place.c). */
static void ref_matrix(const struct job_place *jp, double R[3][3])
{
    const double d = 3.14159265358979323846 / 180.0;
    double z = (double)jp->rz * d, a = (double)jp->axis * d, t = (double)jp->tilt * d;
    double ca = cos(a), sa = sin(a), ct = cos(t), st = sin(t);
    double T[3][3] = {{ct + (1 - ct) * ca * ca, (1 - ct) * ca * sa, st * sa},
                      {(1 - ct) * ca * sa, ct + (1 - ct) * sa * sa, -st * ca},
                      {-st * sa, st * ca, ct}};
    double Z[3][3] = {{cos(z), -sin(z), 0}, {sin(z), cos(z), 0}, {0, 0, 1}};
    int i, j, k;
    for (i = 0; i < 3; i++) {
        for (j = 0; j < 3; j++) {
            R[i][j] = 0;
            for (k = 0; k < 3; k++) {
                R[i][j] += T[i][k] * Z[k][j];
            }
        }
    }
}

static const double angles[][3] = {
    {0, 0, 0},      {37, 45, 30},   {-123.4, 10, -90}, {360, -360, 90}, {271, 181, 1e-3},
    {0.5, -45, 45}, {-359.9, 300, -17}, {90, 90, 90},  {13.7, 0, 60},   {-200, -200, -60},
};

int test_place_matrix(void)
{
    const double lim = PL_FLOAT ? 3e-6 : 1e-14;
    double worst = 0, det;
    struct job_place jp;
    struct place pl;
    size_t c;
    int i, j, k;
    for (c = 0; c < sizeof angles / sizeof angles[0]; c++) {
        jp_set(&jp, 1, 2, 3, angles[c][0], angles[c][1], angles[c][2]);
        place_init(&pl, &jp);
        CHECK(pl.on == 1u);
        for (i = 0; i < 3; i++) { /* R^T R = I */
            for (j = 0; j < 3; j++) {
                double s = 0;
                for (k = 0; k < 3; k++) {
                    s += pl_r(&pl, k, i) * pl_r(&pl, k, j);
                }
                s -= i == j ? 1.0 : 0.0;
                worst = fabs(s) > worst ? fabs(s) : worst;
            }
        }
        det = pl_r(&pl, 0, 0) * (pl_r(&pl, 1, 1) * pl_r(&pl, 2, 2) - pl_r(&pl, 1, 2) * pl_r(&pl, 2, 1)) -
              pl_r(&pl, 0, 1) * (pl_r(&pl, 1, 0) * pl_r(&pl, 2, 2) - pl_r(&pl, 1, 2) * pl_r(&pl, 2, 0)) +
              pl_r(&pl, 0, 2) * (pl_r(&pl, 1, 0) * pl_r(&pl, 2, 1) - pl_r(&pl, 1, 1) * pl_r(&pl, 2, 0));
        CHECK_NEAR(det, 1.0, lim, 0);
    }
    CHECK(worst <= lim);
    printf("  note: place: |R^T R - I| <= %.2g over %u placements\n", worst,
           (unsigned)(sizeof angles / sizeof angles[0]));

    /* known rotations: PLACE 0 0 0 90 is exactly x -> y, y -> -x */
    jp_set(&jp, 0, 0, 0, 90, 0, 0);
    place_init(&pl, &jp);
    CHECK(pl.on == 1u);
    CHECK(pl_r(&pl, 0, 0) == 0 && pl_r(&pl, 0, 1) == -1 && pl_r(&pl, 1, 0) == 1 &&
          pl_r(&pl, 1, 1) == 0 && pl_r(&pl, 2, 2) == 1);
    /* TILT 0 90: about +X, +Y goes to +Z exactly */
    jp_set(&jp, 0, 0, 0, 0, 0, 90);
    place_init(&pl, &jp);
    CHECK(pl_r(&pl, 2, 1) == 1 && pl_r(&pl, 1, 1) == 0 && pl_r(&pl, 0, 0) == 1);
    /* "inclined 30 deg about the line at 45 deg": the line stays, its normal in XY rises */
    jp_set(&jp, 0, 0, 0, 0, 45, 30);
    place_init(&pl, &jp);
    {
        const double h = sqrt(0.5), t = 30.0 * 3.14159265358979323846 / 180.0;
        double ax[3] = {h, h, 0}, v[3] = {-h, h, 0}, o[3], w[3];
        for (i = 0; i < 3; i++) {
            o[i] = pl_r(&pl, i, 0) * ax[0] + pl_r(&pl, i, 1) * ax[1];
            w[i] = pl_r(&pl, i, 0) * v[0] + pl_r(&pl, i, 1) * v[1];
            CHECK_NEAR(o[i], ax[i], lim, 0);
        }
        CHECK_NEAR(w[0], -h * cos(t), lim, 0);
        CHECK_NEAR(w[1], h * cos(t), lim, 0);
        CHECK_NEAR(w[2], sin(t), lim, 0);
    }
    /* place_sincos_deg: exact on the quadrants */
    {
        static const double q[] = {-360, -270, -180, -90, 0, 90, 180, 270, 360};
        for (c = 0; c < sizeof q / sizeof q[0]; c++) {
            cp_real s, co;
            place_sincos_deg((cp_real)q[c], &s, &co);
            CHECK((double)s == floor(sin(q[c] * 3.14159265358979323846 / 180.0) + 0.5) &&
                  (double)co == floor(cos(q[c] * 3.14159265358979323846 / 180.0) + 0.5));
        }
    }
    return 0;
}

int test_place_identity(void)
{
    struct job_place jp;
    struct place pl;
    struct job j;
    struct raster_pt pt, p0;
    job_init(&j);
    place_init(&pl, &j.place); /* no PLACE/TILT: none */
    CHECK(pl.on == 0u);
    jp_set(&jp, 0, 0, 0, 360, 123, 0); /* a full turn, a tilt axis without a tilt */
    place_init(&pl, &jp);
    CHECK(pl.on == 0u);
    jp_set(&jp, 0, 0, 0, -360, 0, 0);
    place_init(&pl, &jp);
    CHECK(pl.on == 0u);
    jp_set(&jp, 0, 0, 1e-3, 0, 0, 0); /* an offset alone: on, R exactly I */
    place_init(&pl, &jp);
    CHECK(pl.on == 1u);
    memset(&pt, 0, sizeof pt);
    pt.p.x = CP_R(1.25);
    pt.p.y = CP_R(-3.5);
    pt.p.z = CP_R(7.0);
    pt.n.z = CP_R(1.0);
    p0 = pt;
    place_apply(&pl, &pt);
    CHECK(pt.p.x == p0.p.x && pt.p.y == p0.p.y && pt.p.z == p0.p.z + (cp_real)1e-3);
    CHECK(pt.n.x == 0 && pt.n.y == 0 && pt.n.z == 1);
    return 0;
}

/* float vs double transform, and the inverse round trip (R^T (p' - off) = p) */
int test_place_accuracy(void)
{
    const double lim_um = PL_FLOAT ? 0.5 : 1e-6;
    double worst = 0, worst_rt = 0, worst_n = 0;
    struct job_place jp;
    struct place pl;
    unsigned s = 12345u;
    size_t c;
    int m, i, k;
    for (c = 0; c < sizeof angles / sizeof angles[0]; c++) {
        double R[3][3];
        jp_set(&jp, 1000.0 * (c % 3 == 0 ? 1 : -0.37), -987.6, 111.1 * (double)c, angles[c][0],
               angles[c][1], angles[c][2]);
        place_init(&pl, &jp);
        ref_matrix(&jp, R);
        for (m = 0; m < 200; m++) {
            struct raster_pt pt;
            double p[3], n[3], q[3], e = 0, rt = 0, en = 0;
            for (i = 0; i < 3; i++) { /* |p_i| <= 100 mm, a unit normal */
                s = s * 1103515245u + 12345u;
                p[i] = (double)(cp_real)(((double)(s >> 8) / 16777216.0 - 0.5) * 200.0);
                n[i] = ((double)(s & 255u) - 127.5) / 127.5;
            }
            {
                double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
                for (i = 0; i < 3; i++) {
                    n[i] = (double)(cp_real)(n[i] / l);
                }
            }
            memset(&pt, 0, sizeof pt);
            pt.p.x = (cp_real)p[0], pt.p.y = (cp_real)p[1], pt.p.z = (cp_real)p[2];
            pt.n.x = (cp_real)n[0], pt.n.y = (cp_real)n[1], pt.n.z = (cp_real)n[2];
            place_apply(&pl, &pt);
            q[0] = (double)pt.p.x - (double)jp.off[0];
            q[1] = (double)pt.p.y - (double)jp.off[1];
            q[2] = (double)pt.p.z - (double)jp.off[2];
            for (i = 0; i < 3; i++) {
                double want = (double)jp.off[i], wn = 0, back = 0;
                double got = i == 0 ? (double)pt.p.x : (i == 1 ? (double)pt.p.y : (double)pt.p.z);
                double gn = i == 0 ? (double)pt.n.x : (i == 1 ? (double)pt.n.y : (double)pt.n.z);
                for (k = 0; k < 3; k++) {
                    want += R[i][k] * p[k];
                    wn += R[i][k] * n[k];
                    back += R[k][i] * q[k]; /* the inverse: R^T (p' - off) */
                }
                e += (got - want) * (got - want);
                en += (gn - wn) * (gn - wn);
                rt += (back - p[i]) * (back - p[i]);
            }
            worst = sqrt(e) > worst ? sqrt(e) : worst;
            worst_n = sqrt(en) > worst_n ? sqrt(en) : worst_n;
            worst_rt = sqrt(rt) > worst_rt ? sqrt(rt) : worst_rt;
        }
    }
    worst *= 1000.0;
    worst_rt *= 1000.0;
    printf("  note: place vs double: |p' - p'_ref| <= %.3g um (|p_i| <= 100 mm, |off_i| <= 1000 mm), "
           "normals %.2g; inverse round trip %.3g um\n", worst, worst_n, worst_rt);
    CHECK(worst <= lim_um);
    CHECK(worst_rt <= lim_um);
    CHECK(worst_n <= (PL_FLOAT ? 3e-6 : 1e-14));
    return 0;
}

int test_place_commands(void)
{
    static const struct {
        const char *line;
        int st;
    } cases[] = {
        {"PLACE 10 -20 5", CP_ST_OK},        {"PLACE 10 -20 5 30", CP_ST_OK},
        {"PLACE 1000 -1000 1000 -360", CP_ST_OK}, {"TILT 45 30", CP_ST_OK},
        {"TILT -360 -90", CP_ST_OK},         {"PLACE 10 20", CP_ST_BAD_ARITY},
        {"PLACE 1 2 3 4 5", CP_ST_BAD_ARITY}, {"TILT 45", CP_ST_BAD_ARITY},
        {"PLACE 1000.1 0 0", CP_ST_OUT_OF_RANGE}, {"PLACE 0 0 -1001", CP_ST_OUT_OF_RANGE},
        {"PLACE 0 0 0 360.5", CP_ST_OUT_OF_RANGE}, {"TILT 0 90.01", CP_ST_OUT_OF_RANGE},
        {"TILT 361 0", CP_ST_OUT_OF_RANGE},  {"PLACE nan 0 0", CP_ST_NONFINITE},
        {"TILT 0 inf", CP_ST_NONFINITE},     {"PLACE x 0 0", CP_ST_BAD_NUMBER},
    };
    struct job j;
    size_t i;
    job_init(&j);
    for (i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        struct job before = j;
        int st = job_command(&j, cases[i].line, strlen(cases[i].line));
        /* the cause of a refusal is for the error reply, not a setting */
        before.cause_st = j.cause_st;
        before.cause_len = j.cause_len;
        before.cause_limit = j.cause_limit;
        before.cause_args_min = j.cause_args_min;
        before.cause_args_max = j.cause_args_max;
        if (st != cases[i].st) {
            printf("  %s -> %d, want %d\n", cases[i].line, st, cases[i].st);
        }
        CHECK_EQ_INT(st, cases[i].st);
        if (st != CP_ST_OK) {
            CHECK(memcmp(&before, &j, sizeof j) == 0); /* unchanged on error */
        }
    }
    /* the last good ones stand; PLACE without rz turns back to 0 */
    CHECK(j.place.off[0] == CP_R(1000.0) && j.place.rz == CP_R(-360.0));
    CHECK(j.place.axis == CP_R(-360.0) && j.place.tilt == CP_R(-90.0));
    CHECK_EQ_INT(job_command(&j, "place 1 2 3", 11u), CP_ST_OK);
    CHECK(j.place.rz == CP_R(0.0) && j.place.off[2] == CP_R(3.0));
    return 0;
}
