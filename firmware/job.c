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
#if PATH_HAVE_GSR
    JOB_HAVE_GSR_CENTER | JOB_HAVE_GSR_RADII | JOB_HAVE_GSR_FRAME | JOB_HAVE_RASTER, /* PATH_GSR */
#else
    0u,
#endif
#if PATH_HAVE_CHANNEL
    JOB_HAVE_CHANNEL_SECTION | JOB_HAVE_RASTER, /* PATH_CHANNEL */
#else
    0u,
#endif
#if PATH_HAVE_DRC
    JOB_HAVE_DRC_POINTS /* PATH_DRC */
#else
    0u
#endif
};

/* Model k's command hook (job_model_fn semantics), or JOB_NOT_MINE / 0 when the
 * model is not compiled in (its keywords are then unknown commands, error:1). */
static int model_command(unsigned k, struct job *j, const struct job_line *l)
{
    (void)j;
    (void)l;
    switch (k) {
#if PATH_HAVE_GSR
    case PATH_GSR:
        return job_gsr_command(j, l);
#endif
#if PATH_HAVE_CHANNEL
    case PATH_CHANNEL:
        return job_channel_command(j, l);
#endif
#if PATH_HAVE_DRC
    case PATH_DRC:
        return job_drc_command(j, l);
#endif
    default:
        return j == NULL ? 0 : JOB_NOT_MINE;
    }
}

/* SURFACE <k>: model k's geometry starts afresh. */
static void model_defaults(unsigned k, union path_geom *g)
{
    switch (k) {
#if PATH_HAVE_GSR
    case PATH_GSR:
        job_gsr_defaults(g);
        break;
#endif
#if PATH_HAVE_CHANNEL
    case PATH_CHANNEL:
        job_channel_defaults(g);
        break;
#endif
#if PATH_HAVE_DRC
    case PATH_DRC:
        job_drc_defaults(g);
        break;
#endif
    default:
        g->none = 0;
        break;
    }
}

const char *job_models(void)
{
    return "CANAL"
#if PATH_HAVE_GSR
           "+GSR"
#endif
#if PATH_HAVE_CHANNEL
           "+CHANNEL"
#endif
#if PATH_HAVE_DRC
           "+DRC"
#endif
        ;
}

void job_init(struct job *j)
{
    /* everything 0 first: LINE, CONST, all parameters, LINES, OUT_SURFACE, ANGLE labels,
     * span LINES, u0 = u1 = 0, steps and substeps derived, no tool, no feed, nothing
     * set, SURFACE CANAL (geometry 0), GCODE, no checksums */
    unsigned char *b = (unsigned char *)j;
    size_t i;
    for (i = 0; i < sizeof *j; i++) {
        b[i] = 0u;
    }
    j->cfg.n = 1;
    j->cfg.link = TOOLPATH_LINK_AUTO;
    j->cfg.tol = CP_R(0.001);
    j->rxbuf = 128u;
}

int job_ready(const struct job *j)
{
    uint16_t nd = j->kind < PATH_KINDS ? need[j->kind] : 0u;
#if PATH_HAVE_DRC
    /* need[] is per kind: SURFACE DRC with EDGE ON also needs RADIUS (a fillet without
     * a radius law is an incomplete job, error:10; LINES may default: one line, u = 0) */
    if (j->kind == PATH_DRC && j->geom.drc.edge != 0u) {
        nd |= JOB_HAVE_RADIUS;
    }
#endif
    return nd != 0u && (j->have & nd) == nd ? CP_ST_OK : CP_ST_NO_JOB;
}

/* Keyword lists: upper case, packed one after the other, each ended by its NUL (no
 * pointer table, no padding; parse_kw), each shorter than PARSE_KW_MAX. The canal's job
 * commands first (enum order), then the protocol's: job_is_command knows them all. */
static const char kw_cmd[] = "CURVE\0RADIUS\0TOOL\0LINES\0CIRCLES\0STEPS\0TOL\0FEED\0RXBUF\0"
                             "FORMAT\0CHECKSUM\0SURFACE\0RUN\0RESUME";
enum { KW_CURVE, KW_RADIUS, KW_TOOL, KW_LINES, KW_CIRCLES, KW_STEPS, KW_TOL, KW_FEED, KW_RXBUF,
       KW_FORMAT, KW_CHECKSUM, KW_JOB, KW_ALL = 14 };

int job_is_command(const char *line, size_t len)
{
    uint16_t st = 0, ln;
    struct job_line l;
    size_t n = 0;
    unsigned i;
    while (n < len && line[n] != ' ') {
        n++;
    }
    if (parse_kw(line, n, kw_cmd, KW_ALL) < KW_ALL) {
        return 1;
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

/* Token t of l against the cnt packed keywords of tab: index or cnt. */
static unsigned tok_kw(const struct job_line *l, unsigned t, const char *tab, unsigned cnt)
{
    return parse_kw(l->s + l->st[t], l->ln[t], tab, cnt);
}

/* CURVE and RADIUS kinds (enum canal_curve_kind, enum canal_radius_kind order) and
 * their numbers (the canal's own counts, curve_nparams/radius_nparams in canal.c). */
static const char kind_names[] = "LINE\0ARC\0ELLIPSE\0BEZIER\0" /* CURVE: 0..3 */
                                 "CONST\0LINEAR\0COS\0CUBIC";      /* RADIUS: 4..7 */
static const uint8_t kind_arity[2][4] = {{4u, 5u, 6u, 8u}, {1u, 2u, 3u, 4u}};

/* "CURVE <KIND> n1 .. nk" (radius = 0) or "RADIUS <KIND> n1 .. nk" (radius = 1). */
static int cmd_kind(struct job *j, const struct job_line *l, unsigned radius)
{
    cp_real v[8];
    cp_real *dst = radius ? j->cfg.surf.rp : j->cfg.surf.cp;
    unsigned k, i, na, cap = radius ? 4u : 8u;
    int s;
    if (l->nt < 2u) {
        return CP_ST_BAD_ARITY;
    }
    k = tok_kw(l, 1u, kind_names, 8u);
    if (k / 4u != radius) { /* unknown, or the other command's kind */
        return CP_ST_BAD_KEYWORD;
    }
    k %= 4u;
    na = kind_arity[radius][k];
    if (l->nt != 2u + na) {
        return CP_ST_BAD_ARITY;
    }
    s = job_numbers(l, 2u, na, v);
    if (s != CP_ST_OK) {
        return s;
    }
    if (!radius && (k == CANAL_ARC || k == CANAL_ELLIPSE)) { /* the two angles come last */
        v[na - 2u] *= CP_DEG2RAD;
        v[na - 1u] *= CP_DEG2RAD;
    }
    for (i = 0; i < cap; i++) {
        dst[i] = i < na ? v[i] : CP_R(0.0);
    }
    if (radius) {
        j->cfg.surf.radius = (uint8_t)k;
        j->have |= JOB_HAVE_RADIUS;
    } else {
        j->cfg.surf.curve = (uint8_t)k;
        j->have |= JOB_HAVE_CURVE;
    }
    return CP_ST_OK;
}

static int cmd_raster(struct job *j, int circles, const struct job_line *l)
{
    uint32_t n;
    cp_real v[2];
    int s, patch = 0;
    if (circles && l->nt == 5u) {
        if (!parse_is(l->s + l->st[4], l->ln[4], "PATCH")) {
            return CP_ST_BAD_KEYWORD;
        }
        patch = 1;
    } else if (l->nt != 4u) {
        return CP_ST_BAD_ARITY;
    }
    s = parse_uint(l->s + l->st[1], l->ln[1], 0xFFFFFFFFu, &n);
    if (s != CP_ST_OK) {
        return s;
    }
    s = job_numbers(l, 2u, 2u, v);
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

/* TOOL NONE | TOOL BALL r [TIP|CENTRE|CENTER] */
static int cmd_tool(struct job *j, const struct job_line *l)
{
    static const char opt[] = "TIP\0CENTRE\0CENTER";
    cp_real v;
    unsigned o = 0, k;
    int s;
    if (l->nt < 2u) {
        return CP_ST_BAD_ARITY;
    }
    k = tok_kw(l, 1u, "NONE\0BALL", 2u);
    if (k == 0u && l->nt == 2u) { /* NONE */
        j->cfg.output = TOOLPATH_OUT_SURFACE;
        j->cfg.tool_r = CP_R(0.0);
        return CP_ST_OK;
    }
    if (k != 1u) { /* not BALL (or NONE with arguments) */
        return CP_ST_BAD_KEYWORD;
    }
    if (l->nt != 3u && l->nt != 4u) {
        return CP_ST_BAD_ARITY;
    }
    s = job_numbers(l, 2u, 1u, &v);
    if (s != CP_ST_OK) {
        return s;
    }
    if (!(v > CP_R(0.0)) || v > CANAL_COORD_MAX) {
        return CP_ST_OUT_OF_RANGE;
    }
    if (l->nt == 4u) {
        o = tok_kw(l, 3u, opt, 3u);
        if (o == 3u) {
            return CP_ST_BAD_KEYWORD;
        }
    }
    j->cfg.output = o != 0u ? TOOLPATH_OUT_CENTRE : TOOLPATH_OUT_TIP;
    j->cfg.tool_r = v;
    return CP_ST_OK;
}

/* The one-argument commands STEPS, TOL, FEED, RXBUF, FORMAT, CHECKSUM (k = KW_*). */
static int cmd_one(struct job *j, unsigned k, const struct job_line *l)
{
    static const char word[] = "GCODE\0FRAMES\0OFF\0ON"; /* value = index & 1 */
    cp_real v = CP_R(0.0);
    uint32_t u = 0;
    int s;
    if (l->nt != 2u) {
        return CP_ST_BAD_ARITY;
    }
    if (k >= KW_FORMAT) { /* FORMAT GCODE|FRAMES, CHECKSUM OFF|ON */
        unsigned w = k == KW_FORMAT ? 0u : 2u;
        unsigned i = tok_kw(l, 1u, word, 4u);
        if ((i & ~1u) != w) { /* unknown, or the other command's word */
            return CP_ST_BAD_KEYWORD;
        }
        i &= 1u;
        if (k == KW_FORMAT) {
            j->format = (uint8_t)i; /* JOB_GCODE, JOB_FRAMES */
        } else {
            j->checksum = (uint8_t)i;
        }
        return CP_ST_OK;
    }
    if (k == KW_STEPS || k == KW_RXBUF) {
        s = parse_uint(l->s + l->st[1], l->ln[1], 0xFFFFFFFFu, &u);
    } else {
        s = job_numbers(l, 1u, 1u, &v);
    }
    if (s != CP_ST_OK) {
        return s;
    }
    switch (k) {
    case KW_STEPS:
        if (u > CP_MAX_STEPS) {
            return CP_ST_TOO_MANY;
        }
        if (u == 0u) {
            return CP_ST_OUT_OF_RANGE;
        }
        j->cfg.steps = (uint16_t)u;
        j->cfg.tol = CP_R(0.0);
        return CP_ST_OK;
    case KW_TOL:
        if (v < CP_R(0.01) || v > CP_R(10000.0)) {
            return CP_ST_OUT_OF_RANGE;
        }
        j->cfg.tol = v * CP_R(0.001);
        j->cfg.steps = 0;
        return CP_ST_OK;
    case KW_FEED:
        if (v < CP_R(0.0) || v > JOB_FEED_MAX || (v > CP_R(0.0) && v < JOB_FEED_MIN)) {
            return CP_ST_OUT_OF_RANGE;
        }
        j->feed = v;
        return CP_ST_OK;
    default: /* KW_RXBUF */
        if (u < JOB_RXBUF_MIN || u > JOB_RXBUF_MAX) {
            return CP_ST_OUT_OF_RANGE;
        }
        j->rxbuf = (uint16_t)u;
        return CP_ST_OK;
    }
}

int job_command(struct job *j, const char *line, size_t len)
{
    static const char names[] = "CANAL\0GSR\0CHANNEL\0DRC"; /* enum path_kind */
    uint16_t st[JOB_MAX_TOKENS], ln[JOB_MAX_TOKENS];
    unsigned nt = parse_split(line, len, st, ln, JOB_MAX_TOKENS);
    struct job_line l;
    unsigned k, kw;
    if (nt == 0u) {
        return JOB_NOT_MINE;
    }
    l.s = line;
    l.st = st;
    l.ln = ln;
    l.nt = nt > JOB_MAX_TOKENS ? JOB_MAX_TOKENS : nt;
    kw = tok_kw(&l, 0u, kw_cmd, KW_ALL); /* the keywords are distinct */
    if (kw == KW_JOB) { /* SURFACE */
        if (nt != 2u) {
            return CP_ST_BAD_ARITY;
        }
        k = tok_kw(&l, 1u, names, PATH_KINDS);
        if (k == PATH_KINDS || need[k] == 0u) {
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
    for (k = 0; k < PATH_KINDS; k++) {
        if (model_command(k, NULL, &l) == 1) {
            if (nt > JOB_MAX_TOKENS) {
                return CP_ST_BAD_ARITY;
            }
            return j->kind == k ? model_command(k, j, &l) : CP_ST_WRONG_SURFACE;
        }
    }
    k = kw;
    if (k >= KW_JOB) { /* RUN, RESUME (the protocol's) or no job command */
        return JOB_NOT_MINE;
    }
    if (nt > JOB_MAX_TOKENS) {
        return CP_ST_BAD_ARITY;
    }
    switch (k) {
    case KW_CURVE:
    case KW_RADIUS:
        return cmd_kind(j, &l, k);
    case KW_TOOL:
        return cmd_tool(j, &l);
    case KW_LINES:
    case KW_CIRCLES:
        return cmd_raster(j, k == KW_CIRCLES, &l);
    default:
        return cmd_one(j, k, &l);
    }
}
