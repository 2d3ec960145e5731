/* job.c - the fillet job assembled from protocol commands.
 * SPDX-License-Identifier: MIT
 */
#include "job.h"
#include "parse.h"

/* The models other than the canal (path.h: how to add a model). Direct calls, no
 * function pointers, so the static stack analysis sees every path. */

/* have bits RUN needs, per enum path_kind (0: the model is not compiled in) */
static const uint16_t need[PATH_KINDS] = {
    JOB_HAVE_ALL, /* PATH_CANAL */
    0u,           /* PATH_GSR */
    0u,           /* PATH_CHANNEL */
    0u            /* PATH_DRC */
};

/* Model k's command hook (job_model_fn semantics), or JOB_NOT_MINE / 0 when the
 * model is not compiled in. */
static int model_command(unsigned k, struct job *j, const struct job_line *l)
{
    (void)j;
    (void)l;
    switch (k) {
    default:
        return j == NULL ? 0 : JOB_NOT_MINE;
    }
}

/* SURFACE <k>: model k's geometry starts afresh. */
static void model_defaults(unsigned k, union path_geom *g)
{
    switch (k) {
    default:
        g->none = 0;
        break;
    }
}

void job_init(struct job *j)
{
    unsigned i;
    j->cfg.surf.curve = CANAL_LINE;
    j->cfg.surf.radius = CANAL_R_CONST;
    for (i = 0; i < 8u; i++) {
        j->cfg.surf.cp[i] = CP_R(0.0);
    }
    for (i = 0; i < 4u; i++) {
        j->cfg.surf.rp[i] = CP_R(0.0);
    }
    j->cfg.mode = TOOLPATH_LINES;
    j->cfg.output = TOOLPATH_OUT_SURFACE;
    j->cfg.labels = TOOLPATH_LABEL_ANGLE;
    j->cfg.span = TOOLPATH_SPAN_LINES;
    j->cfg.n = 1;
    j->cfg.u0 = CP_R(0.0);
    j->cfg.u1 = CP_R(0.0);
    j->cfg.steps = 0;
    j->cfg.substeps = 0;
    j->cfg.link = TOOLPATH_LINK_AUTO;
    j->cfg.tol = CP_R(0.001);
    j->cfg.tool_r = CP_R(0.0);
    j->feed = CP_R(0.0);
    j->rxbuf = 128u;
    j->have = 0;
    j->kind = PATH_CANAL;
    j->geom.none = 0;
    j->format = JOB_GCODE;
    j->checksum = 0;
}

int job_ready(const struct job *j)
{
    uint16_t nd = j->kind < PATH_KINDS ? need[j->kind] : 0u;
    return nd != 0u && (j->have & nd) == nd ? CP_ST_OK : CP_ST_NO_JOB;
}

int job_is_command(const char *line, size_t len)
{
    static const char *const kw[14] = {"CURVE", "RADIUS",   "TOOL",    "LINES", "CIRCLES",
                                       "STEPS", "TOL",      "FEED",    "FORMAT", "RXBUF",
                                       "CHECKSUM", "SURFACE", "RUN",   "RESUME"};
    uint16_t st = 0, ln;
    struct job_line l;
    size_t n = 0;
    unsigned i;
    while (n < len && line[n] != ' ') {
        n++;
    }
    for (i = 0; i < 14u; i++) {
        if (parse_is(line, n, kw[i])) {
            return 1;
        }
    }
    ln = (uint16_t)(n < 0xFFFFu ? n : 0xFFFFu);
    l.s = line;
    l.st = &st;
    l.ln = &ln;
    l.nt = n > 0u ? 1u : 0u;
    for (i = 0; i < PATH_KINDS && l.nt > 0u; i++) {
        if (model_command(i, NULL, &l) == 1) {
            return 1;
        }
    }
    return 0;
}

int job_numbers(const struct job_line *l, unsigned first, unsigned n, cp_real *v)
{
    unsigned i;
    for (i = 0; i < n; i++) {
        int s = parse_real(l->s + l->st[first + i], l->ln[first + i], &v[i]);
        if (s != CP_ST_OK) {
            return s;
        }
    }
    return CP_ST_OK;
}

int job_status_of(int err)
{
    switch (err) {
    case CP_OK:
        return CP_ST_OK;
    case CP_ERR_NONFINITE:
        return CP_ST_NONFINITE;
    case CP_ERR_RANGE:
    case CP_ERR_INVAL:
        return CP_ST_OUT_OF_RANGE;
    case CP_ERR_RADIUS:
        return CP_ST_RADIUS;
    case CP_ERR_DEGENERATE:
        return CP_ST_DEGENERATE;
    case CP_ERR_EMPTY:
        return CP_ST_EMPTY;
    case CP_ERR_TOO_MANY:
        return CP_ST_TOO_MANY;
    case CP_ERR_TOOL:
        return CP_ST_TOOL;
    case CP_ERR_CUSP:
        return CP_ST_CUSP;
    case CP_ERR_TOL:
        return CP_ST_TOL;
    case CP_ERR_OFF_PLANE:
        return CP_ST_OFF_PLANE;
    case CP_ERR_FRENET:
        return CP_ST_FRENET;
    case CP_ERR_FRAME_REF:
        return CP_ST_FRAME_REF;
    case CP_ERR_SECTION:
        return CP_ST_SECTION;
    case CP_ERR_FT_RANGE:
        return CP_ST_FT_RANGE;
    case CP_ERR_FOLD:
        return CP_ST_FOLD;
    case CP_ERR_TOO_FEW:
        return CP_ST_TOO_FEW;
    case CP_ERR_EXPONENT:
        return CP_ST_EXPONENT;
    case CP_ERR_COINCIDENT:
        return CP_ST_COINCIDENT;
    case CP_ERR_SECTION_PLANE:
        return CP_ST_SECTION_PLANE;
    case CP_ERR_AREA_LAW:
        return CP_ST_AREA_LAW;
    case CP_ERR_ISOTROPIC:
        return CP_ST_ISOTROPIC;
    case CP_ERR_TURN:
        return CP_ST_TURN;
    case CP_ERR_TWIST:
        return CP_ST_TWIST;
    case CP_ERR_BUFFER:
        return CP_ST_BUFFER;
    default:
        return CP_ST_NUMERIC;
    }
}

/* Parse tokens first..first+n-1 as numbers into v[]. */
static int numbers(const char *line, const uint16_t *st, const uint16_t *ln, unsigned first,
                   unsigned n, cp_real *v)
{
    unsigned i;
    for (i = 0; i < n; i++) {
        int s = parse_real(line + st[first + i], ln[first + i], &v[i]);
        if (s != CP_ST_OK) {
            return s;
        }
    }
    return CP_ST_OK;
}

/* "<CMD> <KIND> n1 .. nk": find KIND among names[0..3] (arity[] numbers each) and
 * parse its numbers into v. Returns a wire status; *kind is the index. */
static int kind_args(const char *line, const uint16_t *st, const uint16_t *ln, unsigned nt,
                     const char *const *names, const uint8_t *arity, cp_real *v, unsigned *kind)
{
    unsigned k;
    if (nt < 2u) {
        return CP_ST_BAD_ARITY;
    }
    for (k = 0; k < 4u; k++) {
        if (parse_is(line + st[1], ln[1], names[k])) {
            break;
        }
    }
    if (k == 4u) {
        return CP_ST_BAD_KEYWORD;
    }
    if (nt != 2u + arity[k]) {
        return CP_ST_BAD_ARITY;
    }
    *kind = k;
    return numbers(line, st, ln, 2u, arity[k], v);
}

static int cmd_curve(struct job *j, const char *line, const uint16_t *st, const uint16_t *ln,
                     unsigned nt)
{
    static const char *const names[4] = {"LINE", "ARC", "ELLIPSE", "BEZIER"};
    static const uint8_t arity[4] = {4u, 5u, 6u, 8u};
    cp_real v[8];
    unsigned k = 0, i;
    int s = kind_args(line, st, ln, nt, names, arity, v, &k);
    if (s != CP_ST_OK) {
        return s;
    }
    if (k == CANAL_ARC || k == CANAL_ELLIPSE) { /* the two angles come last */
        v[arity[k] - 2u] *= CP_DEG2RAD;
        v[arity[k] - 1u] *= CP_DEG2RAD;
    }
    j->cfg.surf.curve = (uint8_t)k;
    for (i = 0; i < 8u; i++) {
        j->cfg.surf.cp[i] = i < arity[k] ? v[i] : CP_R(0.0);
    }
    j->have |= JOB_HAVE_CURVE;
    return CP_ST_OK;
}

static int cmd_radius(struct job *j, const char *line, const uint16_t *st, const uint16_t *ln,
                      unsigned nt)
{
    static const char *const names[4] = {"CONST", "LINEAR", "COS", "CUBIC"};
    static const uint8_t arity[4] = {1u, 2u, 3u, 4u};
    cp_real v[4];
    unsigned k = 0, i;
    int s = kind_args(line, st, ln, nt, names, arity, v, &k);
    if (s != CP_ST_OK) {
        return s;
    }
    j->cfg.surf.radius = (uint8_t)k;
    for (i = 0; i < 4u; i++) {
        j->cfg.surf.rp[i] = i < arity[k] ? v[i] : CP_R(0.0);
    }
    j->have |= JOB_HAVE_RADIUS;
    return CP_ST_OK;
}

static int cmd_raster(struct job *j, int circles, const char *line, const uint16_t *st,
                      const uint16_t *ln, unsigned nt)
{
    uint32_t n;
    cp_real v[2];
    int s, patch = 0;
    if (circles && nt == 5u) {
        if (!parse_is(line + st[4], ln[4], "PATCH")) {
            return CP_ST_BAD_KEYWORD;
        }
        patch = 1;
    } else if (nt != 4u) {
        return CP_ST_BAD_ARITY;
    }
    s = parse_uint(line + st[1], ln[1], 0xFFFFFFFFu, &n);
    if (s != CP_ST_OK) {
        return s;
    }
    s = numbers(line, st, ln, 2u, 2u, v);
    if (s != CP_ST_OK) {
        return s;
    }
    if (n > CP_MAX_LINES) {
        return CP_ST_TOO_MANY;
    }
    if (n == 0u || cp_fabs(v[0]) > CP_R(180.0) || cp_fabs(v[1]) > CP_R(180.0) ||
        (v[0] == v[1] && n > 1u)) {
        return CP_ST_OUT_OF_RANGE;
    }
    j->cfg.mode = circles ? TOOLPATH_CIRCLES : TOOLPATH_LINES;
    j->cfg.span = (circles && !patch) ? TOOLPATH_SPAN_ANGLE : TOOLPATH_SPAN_LINES;
    j->cfg.n = (uint16_t)n;
    j->cfg.u0 = v[0] * CP_DEG2RAD;
    j->cfg.u1 = v[1] * CP_DEG2RAD;
    j->have |= JOB_HAVE_RASTER;
    return CP_ST_OK;
}

int job_command(struct job *j, const char *line, size_t len)
{
    uint16_t st[JOB_MAX_TOKENS], ln[JOB_MAX_TOKENS];
    unsigned nt = parse_split(line, len, st, ln, JOB_MAX_TOKENS);
    const char *w0 = line + (nt > 0u ? st[0] : 0u);
    size_t l0 = nt > 0u ? ln[0] : 0u;
    cp_real v;
    uint32_t u;
    int s;
    if (nt == 0u) {
        return JOB_NOT_MINE;
    }
    if (parse_is(w0, l0, "SURFACE")) {
        static const char *const names[PATH_KINDS] = {"CANAL", "GSR", "CHANNEL", "DRC"};
        unsigned k;
        if (nt != 2u) {
            return CP_ST_BAD_ARITY;
        }
        for (k = 0; k < PATH_KINDS; k++) {
            if (parse_is(line + st[1], ln[1], names[k]) && need[k] != 0u) {
                break;
            }
        }
        if (k == PATH_KINDS) {
            return CP_ST_BAD_KEYWORD;
        }
        if (k != PATH_CANAL) {
            /* that model's geometry starts afresh (the union holds one model) */
            j->have &= (uint16_t)(JOB_HAVE_ALL);
            model_defaults(k, &j->geom);
        }
        j->kind = (uint8_t)k;
        return CP_ST_OK;
    }
    {
        struct job_line l;
        unsigned k;
        l.s = line;
        l.st = st;
        l.ln = ln;
        l.nt = nt > JOB_MAX_TOKENS ? JOB_MAX_TOKENS : nt;
        for (k = 0; k < PATH_KINDS; k++) {
            if (model_command(k, NULL, &l) == 1) {
                if (nt > JOB_MAX_TOKENS) {
                    return CP_ST_BAD_ARITY;
                }
                return j->kind == k ? model_command(k, j, &l) : CP_ST_WRONG_SURFACE;
            }
        }
    }
    if (parse_is(w0, l0, "CURVE")) {
        return nt > JOB_MAX_TOKENS ? CP_ST_BAD_ARITY : cmd_curve(j, line, st, ln, nt);
    }
    if (parse_is(w0, l0, "RADIUS")) {
        return nt > JOB_MAX_TOKENS ? CP_ST_BAD_ARITY : cmd_radius(j, line, st, ln, nt);
    }
    if (nt > JOB_MAX_TOKENS) {
        return parse_is(w0, l0, "TOOL") || parse_is(w0, l0, "LINES") ||
                       parse_is(w0, l0, "CIRCLES") || parse_is(w0, l0, "STEPS") ||
                       parse_is(w0, l0, "TOL") || parse_is(w0, l0, "FEED") ||
                       parse_is(w0, l0, "FORMAT") || parse_is(w0, l0, "RXBUF") ||
                       parse_is(w0, l0, "CHECKSUM")
                   ? CP_ST_BAD_ARITY
                   : JOB_NOT_MINE;
    }
    if (parse_is(w0, l0, "TOOL")) {
        if (nt == 2u && parse_is(line + st[1], ln[1], "NONE")) {
            j->cfg.output = TOOLPATH_OUT_SURFACE;
            j->cfg.tool_r = CP_R(0.0);
            return CP_ST_OK;
        }
        if (nt < 2u) {
            return CP_ST_BAD_ARITY;
        }
        if (!parse_is(line + st[1], ln[1], "BALL")) {
            return CP_ST_BAD_KEYWORD;
        }
        if (nt != 3u && nt != 4u) {
            return CP_ST_BAD_ARITY;
        }
        s = parse_real(line + st[2], ln[2], &v);
        if (s != CP_ST_OK) {
            return s;
        }
        if (!(v > CP_R(0.0)) || v > CANAL_COORD_MAX) {
            return CP_ST_OUT_OF_RANGE;
        }
        if (nt == 4u && !parse_is(line + st[3], ln[3], "TIP") &&
            !parse_is(line + st[3], ln[3], "CENTRE") && !parse_is(line + st[3], ln[3], "CENTER")) {
            return CP_ST_BAD_KEYWORD;
        }
        j->cfg.output = (nt == 4u && !parse_is(line + st[3], ln[3], "TIP")) ? TOOLPATH_OUT_CENTRE
                                                                            : TOOLPATH_OUT_TIP;
        j->cfg.tool_r = v;
        return CP_ST_OK;
    }
    if (parse_is(w0, l0, "LINES")) {
        return cmd_raster(j, 0, line, st, ln, nt);
    }
    if (parse_is(w0, l0, "CIRCLES")) {
        return cmd_raster(j, 1, line, st, ln, nt);
    }
    if (parse_is(w0, l0, "STEPS")) {
        if (nt != 2u) {
            return CP_ST_BAD_ARITY;
        }
        s = parse_uint(line + st[1], ln[1], 0xFFFFFFFFu, &u);
        if (s != CP_ST_OK) {
            return s;
        }
        if (u > CP_MAX_STEPS) {
            return CP_ST_TOO_MANY;
        }
        if (u == 0u) {
            return CP_ST_OUT_OF_RANGE;
        }
        j->cfg.steps = (uint16_t)u;
        j->cfg.tol = CP_R(0.0);
        return CP_ST_OK;
    }
    if (parse_is(w0, l0, "TOL")) {
        if (nt != 2u) {
            return CP_ST_BAD_ARITY;
        }
        s = parse_real(line + st[1], ln[1], &v);
        if (s != CP_ST_OK) {
            return s;
        }
        if (v < CP_R(0.01) || v > CP_R(10000.0)) {
            return CP_ST_OUT_OF_RANGE;
        }
        j->cfg.tol = v * CP_R(0.001);
        j->cfg.steps = 0;
        return CP_ST_OK;
    }
    if (parse_is(w0, l0, "FEED")) {
        if (nt != 2u) {
            return CP_ST_BAD_ARITY;
        }
        s = parse_real(line + st[1], ln[1], &v);
        if (s != CP_ST_OK) {
            return s;
        }
        if (v < CP_R(0.0) || v > JOB_FEED_MAX || (v > CP_R(0.0) && v < JOB_FEED_MIN)) {
            return CP_ST_OUT_OF_RANGE;
        }
        j->feed = v;
        return CP_ST_OK;
    }
    if (parse_is(w0, l0, "FORMAT")) {
        if (nt != 2u) {
            return CP_ST_BAD_ARITY;
        }
        if (parse_is(line + st[1], ln[1], "GCODE")) {
            j->format = JOB_GCODE;
        } else if (parse_is(line + st[1], ln[1], "FRAMES")) {
            j->format = JOB_FRAMES;
        } else {
            return CP_ST_BAD_KEYWORD;
        }
        return CP_ST_OK;
    }
    if (parse_is(w0, l0, "RXBUF")) {
        if (nt != 2u) {
            return CP_ST_BAD_ARITY;
        }
        s = parse_uint(line + st[1], ln[1], 0xFFFFFFFFu, &u);
        if (s != CP_ST_OK) {
            return s;
        }
        if (u < JOB_RXBUF_MIN || u > JOB_RXBUF_MAX) {
            return CP_ST_OUT_OF_RANGE;
        }
        j->rxbuf = (uint16_t)u;
        return CP_ST_OK;
    }
    if (parse_is(w0, l0, "CHECKSUM")) {
        if (nt != 2u) {
            return CP_ST_BAD_ARITY;
        }
        if (parse_is(line + st[1], ln[1], "ON")) {
            j->checksum = 1;
        } else if (parse_is(line + st[1], ln[1], "OFF")) {
            j->checksum = 0;
        } else {
            return CP_ST_BAD_KEYWORD;
        }
        return CP_ST_OK;
    }
    return JOB_NOT_MINE;
}
