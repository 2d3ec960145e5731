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
     * set, SURFACE CANAL (geometry 0), GCODE, no checksums (volatile stores: the loop
     * stays a loop, a memset call would link the library's memset into the image) */
    volatile unsigned char *b = (volatile unsigned char *)j;
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

/* Every keyword of the job commands, packed: each entry is a lead character, the
 * keyword (upper case, shorter than PARSE_KW_MAX) and its NUL; a "|" ends a list (no
 * pointer table, no padding). List 0 holds the commands (enum order below: the
 * canal's, the protocol's RUN and RESUME, then each model's in its hook's order), list
 * 1 + c the words that may follow command c (the enum values in their order). The
 * lead character of a command says how its arguments are checked (job_command):
 *   K  a word from its list, then that word's numbers (the word's lead digit)
 *   T  TOOL: as K, but NONE takes nothing more (else error:9) and BALL r an optional
 *      TIP|CENTRE|CENTER
 *   W  exactly one word from its list (arity checked first)
 *   U  exactly one token: a word from its list, or an unsigned number
 *   ;  n u0 u1: an unsigned number, then two numbers (CIRCLES: an optional PATCH)
 *   :  POINT: two or three numbers
 *   0-9  that many numbers
 *   -  RUN: nothing more (job_line; with anything after it, not a command)
 * RESUME k is a U with an empty list: its k is the unsigned number (job_line). */
/* clang-format off */
static const char words[] =
    "KCURVE\0" "KRADIUS\0" "TTOOL\0" ";LINES\0" ";CIRCLES\0" "USTEPS\0" "1TOL\0" "1FEED\0"
    "URXBUF\0" "WFORMAT\0" "WCHECKSUM\0" "WSURFACE\0" "-RUN\0" "URESUME\0"
    "KCENTER\0" "KRADII\0" "KFRAME\0" "KFORM\0"   /* SURFACE GSR (job_gsr.c) */
    "9SECTION\0" "6AXES\0" "WSECTIONS\0"         /* SURFACE CHANNEL (job_channel.c) */
    ":POINT\0" "WPOINTS\0" "UTHICKEN\0" "WEDGE\0" /* SURFACE DRC (job_drc.c) */
    "|"
    /* CURVE, RADIUS: enum canal_curve_kind, enum canal_radius_kind and their numbers (the
     * canal's own counts, curve_nparams/radius_nparams in canal.c); TOOL */
    "4LINE\0" "5ARC\0" "6ELLIPSE\0" "8BEZIER\0" "|"
    "1CONST\0" "2LINEAR\0" "3COS\0" "4CUBIC\0" "|"
    "0NONE\0" "1BALL\0" "|"
    "|" "|" "|" "|" "|" "|" /* LINES .. RXBUF */
    "0GCODE\0" "0FRAMES\0" "|"        /* enum job_format */
    "0OFF\0" "0ON\0" "|"
    "0CANAL\0" "0GSR\0" "0CHANNEL\0" "0DRC\0" "|" /* enum path_kind */
    "|" "|"                                     /* RUN, RESUME */
    /* CENTER X|Y|Z a0 a1 a2 a3 b c w, P0..P3 x y z; RADII N|B|T ...; FRAME; FORM */
    "7X\0" "7Y\0" "7Z\0" "3P0\0" "3P1\0" "3P2\0" "3P3\0" "|"
    "7N\0" "7B\0" "7T\0" "|"
    "0FIXED\0" "0FRENET\0" "3N0\0" "3RMF\0" "|"
    "0RATIONAL\0" "0TRIG\0" "|"
    "|" "|" "0CLEAR\0" "|"                     /* SECTION, AXES, SECTIONS */
    "|" "0CLEAR\0" "|" "0AUTO\0" "|" "0OFF\0" "0ON"; /* POINT, POINTS, THICKEN, EDGE */
/* clang-format on */
enum { KW_CURVE, KW_RADIUS, KW_TOOL, KW_LINES, KW_CIRCLES, KW_STEPS, KW_TOL, KW_FEED, KW_RXBUF,
       KW_FORMAT, KW_CHECKSUM, KW_JOB, KW_RUN, KW_RESUME, KW_GSR, KW_CHANNEL = KW_GSR + 4,
       KW_DRC = KW_CHANNEL + 3 };

/* Index of s[0..n) (parse_is) in list `list` of words, *lead = its lead character, or
 * '\0' if it is none of them. */
static unsigned job_word(const char *s, size_t n, unsigned list, char *lead)
{
    unsigned i, k = 0;
    *lead = '\0';
    for (i = 0; i < sizeof words; i++) {
        const char *w = words + i;
        if (i > 0u && w[-1] != '\0' && w[-1] != '|') {
            continue; /* not the start of an entry */
        }
        if (*w == '|') {
            if (list-- == 0u) {
                break;
            }
            k = 0;
        } else if (list == 0u && parse_is(s, n, w + 1)) {
            *lead = *w;
            break;
        } else {
            k++;
        }
    }
    return k;
}

/* The model of command c (0 for the canal's and the protocol's). */
static unsigned model_of(unsigned c)
{
    return (unsigned)(c >= KW_GSR) + (unsigned)(c >= KW_CHANNEL) + (unsigned)(c >= KW_DRC);
}

int job_is_command(const char *line, size_t len)
{
    size_t n = 0;
    char lead;
    unsigned c;
    while (n < len && line[n] != ' ') {
        n++;
    }
    c = job_word(line, n, 0u, &lead);
    return lead != '\0' && need[model_of(c)] != 0u;
}

/* Parse tokens first..first+n-1 of line as numbers into v[]. Returns a wire status. */
static int job_numbers(const char *line, const uint16_t *st, const uint16_t *ln, unsigned first,
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

/* The canal's commands and SURFACE, their arguments checked (job_command). */
static int canal_command(struct job *j, unsigned c, const struct job_args *a)
{
    const cp_real *v = a->v;
    unsigned i, k = a->sub;
    uint32_t u = a->u;
    switch (c) {
    case KW_CURVE:
    case KW_RADIUS: {
        cp_real *dst = c == KW_RADIUS ? j->cfg.surf.rp : j->cfg.surf.cp;
        unsigned cap = c == KW_RADIUS ? 4u : 8u;
        for (i = 0; i < cap; i++) {
            dst[i] = i < a->na ? v[i] : CP_R(0.0);
        }
        if (c == KW_RADIUS) {
            j->cfg.surf.radius = (uint8_t)k;
            j->have |= JOB_HAVE_RADIUS;
        } else {
            if (k == CANAL_ARC || k == CANAL_ELLIPSE) { /* the two angles come last */
                dst[a->na - 2u] *= CP_DEG2RAD;
                dst[a->na - 1u] *= CP_DEG2RAD;
            }
            j->cfg.surf.curve = (uint8_t)k;
            j->have |= JOB_HAVE_CURVE;
        }
        return CP_ST_OK;
    }
    case KW_TOOL: /* NONE | BALL r [TIP|CENTRE|CENTER] (u: 0 none, 1 + the option's index) */
        if (k == 0u) {
            j->cfg.output = TOOLPATH_OUT_SURFACE;
            j->cfg.tool_r = CP_R(0.0);
            return CP_ST_OK;
        }
        if (!(v[0] > CP_R(0.0)) || v[0] > CANAL_COORD_MAX) {
            return CP_ST_OUT_OF_RANGE;
        }
        if (u == 4u) { /* not one of the three */
            return CP_ST_BAD_KEYWORD;
        }
        j->cfg.output = u > 1u ? TOOLPATH_OUT_CENTRE : TOOLPATH_OUT_TIP;
        j->cfg.tool_r = v[0];
        return CP_ST_OK;
    case KW_LINES:
    case KW_CIRCLES: /* n u0 u1 (k: PATCH) */
        if (u > CP_MAX_LINES) {
            return CP_ST_TOO_MANY;
        }
        if (u == 0u || cp_fabs(v[0]) > CP_R(180.0) || cp_fabs(v[1]) > CP_R(180.0) ||
            (v[0] == v[1] && u > 1u)) {
            return CP_ST_OUT_OF_RANGE;
        }
        j->cfg.mode = c == KW_CIRCLES ? TOOLPATH_CIRCLES : TOOLPATH_LINES;
        j->cfg.span = (c == KW_CIRCLES && k == 0u) ? TOOLPATH_SPAN_ANGLE : TOOLPATH_SPAN_LINES;
        j->cfg.n = (uint16_t)u;
        j->cfg.u0 = v[0] * CP_DEG2RAD;
        j->cfg.u1 = v[1] * CP_DEG2RAD;
        j->have |= JOB_HAVE_RASTER;
        return CP_ST_OK;
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
        if (v[0] < CP_R(0.01) || v[0] > CP_R(10000.0)) {
            return CP_ST_OUT_OF_RANGE;
        }
        j->cfg.tol = v[0] * CP_R(0.001);
        j->cfg.steps = 0;
        return CP_ST_OK;
    case KW_FEED:
        if (v[0] < CP_R(0.0) || v[0] > JOB_FEED_MAX || (v[0] > CP_R(0.0) && v[0] < JOB_FEED_MIN)) {
            return CP_ST_OUT_OF_RANGE;
        }
        j->feed = v[0];
        return CP_ST_OK;
    case KW_RXBUF:
        if (u < JOB_RXBUF_MIN || u > JOB_RXBUF_MAX) {
            return CP_ST_OUT_OF_RANGE;
        }
        j->rxbuf = (uint16_t)u;
        return CP_ST_OK;
    case KW_FORMAT:
        j->format = (uint8_t)k; /* JOB_GCODE, JOB_FRAMES */
        return CP_ST_OK;
    case KW_CHECKSUM:
        j->checksum = (uint8_t)k;
        return CP_ST_OK;
    default: /* KW_JOB: SURFACE <k> */
        if (need[k] == 0u) {
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
}

int job_command(struct job *j, const char *line, size_t len)
{
    /* RUN and RESUME are the protocol's, whatever follows them (job_line checks
     * RESUME's argument; proto.c calls job_line, so this costs the image nothing) */
    uint16_t st, ln;
    uint32_t first;
    char lead;
    unsigned c = parse_split(line, len, &st, &ln, 1u) > 0u ? job_word(line + st, ln, 0u, &lead)
                                                            : 0u;
    if (c == KW_RUN || c == KW_RESUME) {
        return JOB_NOT_MINE;
    }
    return job_line(j, line, len, &first);
}

int job_line(struct job *j, const char *line, size_t len, uint32_t *first_k)
{
    uint16_t st[JOB_MAX_TOKENS], ln[JOB_MAX_TOKENS];
    unsigned nt = parse_split(line, len, st, ln, JOB_MAX_TOKENS);
    struct job_args a;
    unsigned c, m, first = 1u, na, uint = 0u, ntv = nt;
    char lead, d;
    int s;
    if (nt == 0u) {
        return JOB_NOT_MINE;
    }
    /* (parse_split stored at most JOB_MAX_TOKENS tokens: nt beyond that is error:3) */
    c = job_word(line + st[0], ln[0], 0u, &lead);
    m = model_of(c);
    if (lead == '\0' || need[m] == 0u) { /* no job command */
        return JOB_NOT_MINE;
    }
    if (lead == '-') { /* RUN: alone on its line (the line is trimmed) */
        *first_k = 0u;
        return nt == 1u ? JOB_RUN : JOB_NOT_MINE;
    }
    if (nt > JOB_MAX_TOKENS) {
        return CP_ST_BAD_ARITY;
    }
    if (m != PATH_CANAL && j->kind != m) {
        return CP_ST_WRONG_SURFACE;
    }
    a.sub = 0;
    a.u = 0;
    na = (unsigned)(lead - '0'); /* 0-9: that many numbers */
    if (lead == ':') {            /* POINT x y [z] */
        if (nt != 3u && nt != 4u) {
            return CP_ST_BAD_ARITY;
        }
        na = nt - 1u;
    } else if (lead == ';') { /* LINES|CIRCLES n u0 u1 [PATCH] */
        if (c == KW_CIRCLES && nt == 5u) {
            if (!parse_is(line + st[4], ln[4], "PATCH")) {
                return CP_ST_BAD_KEYWORD;
            }
            a.sub = 1u;
            ntv = 4u;
        }
        na = 3u;
        uint = 1u;
    } else if (lead >= 'K') { /* K, T, U, W: a word from list 1 + c first */
        if (nt < 2u || (lead >= 'U' && nt != 2u)) {
            return CP_ST_BAD_ARITY;
        }
        a.sub = job_word(line + st[1], ln[1], 1u + c, &d);
        na = (unsigned)(d - '0');
        first = 2u;
        if (d == '\0') { /* none of them: U takes an unsigned number instead */
            if (lead != 'U') {
                return CP_ST_BAD_KEYWORD;
            }
            na = 1u;
            first = 1u;
            uint = 1u;
        } else if (lead == 'T') { /* TOOL NONE alone; TOOL BALL r [option] */
            if (a.sub == 0u && nt > 2u) {
                return CP_ST_BAD_KEYWORD;
            }
            if (nt == 4u) { /* the option: 1 + its index among the three, else 4 */
                ntv = 3u;
                a.u = 1u + parse_kw(line + st[3], ln[3], "TIP\0CENTRE\0CENTER", 3u);
            }
        }
    }
    if (ntv != first + na) {
        return CP_ST_BAD_ARITY;
    }
    if (uint) { /* the first argument is an unsigned number */
        s = parse_uint(line + st[first], ln[first], 0xFFFFFFFFu, &a.u);
        if (s != CP_ST_OK) {
            return c == KW_RESUME && s == CP_ST_OUT_OF_RANGE ? CP_ST_RESUME_RANGE : s;
        }
        if (c == KW_RESUME) {
            *first_k = a.u;
            return JOB_RUN;
        }
        first++;
        na--;
    }
    s = job_numbers(line, st, ln, first, na, a.v);
    if (s != CP_ST_OK) {
        return s;
    }
    a.na = na;
    switch (m) {
#if PATH_HAVE_GSR
    case PATH_GSR:
        a.cmd = c - KW_GSR;
        return job_gsr_command(j, &a);
#endif
#if PATH_HAVE_CHANNEL
    case PATH_CHANNEL:
        a.cmd = c - KW_CHANNEL;
        return job_channel_command(j, &a);
#endif
#if PATH_HAVE_DRC
    case PATH_DRC:
        a.cmd = c - KW_DRC;
        return job_drc_command(j, &a);
#endif
    default:
        return canal_command(j, c, &a);
    }
}
