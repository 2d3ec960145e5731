/* job.c - the fillet job assembled from protocol commands: the commands of commands.def,
 * the models of models.def.
 * SPDX-License-Identifier: MIT
 *
 * job_line finds the command of a line's keyword, checks its arguments as the command's
 * shape says (enum job_shape) and calls its owner's hook: job.c's own (raster, output,
 * SURFACE) or a model's (job_<m>_command, a direct call per row of models.def: no
 * function pointers, so the static stack analysis sees every edge).
 */
#include "job.h"
#include "parse.h"

/* Who applies a command (CP_CMD's OWNER): a model (enum path_kind) or one of these. */
enum job_owner {
#define CP_MODEL(NAME, name, WITH, WORD) JOB_OWNER_##NAME = PATH_##NAME,
#include "models.def"
#undef CP_MODEL
    JOB_OWNER_JOB = PATH_KINDS, /* job_own_command below */
    JOB_OWNER_PROTO             /* the protocol's: job_line answers JOB_RUN */
};

/* Under which SURFACE a command is accepted (CP_CMD's SURFACE). */
enum job_surface {
    JOB_SURFACE_ANY = 0, /* every one */
    JOB_SURFACE_OWN = 1  /* its owner's only (else error:24) */
};

/* A CP_CMD row. */
struct job_cmd_row {
    const char *keyword; /* upper case */
    uint8_t owner;       /* enum job_owner */
    uint8_t shape;       /* enum job_shape */
    uint8_t min, max;    /* numbers (JOB_ARGS_NUMBERS: MIN..MAX; UINT_NUMBERS_OPTION: MIN) */
    uint8_t surface;     /* enum job_surface */
};

/* A CP_CMD_WORD or CP_CMD_OPTION row. */
struct job_word_row {
    const char *text; /* upper case */
    uint8_t cmd;      /* enum job_cmd of its command */
    uint8_t option;   /* 1: an option word (CP_CMD_OPTION) */
    uint8_t numbers;  /* numbers after it (a word) */
    uint8_t value;    /* what the hook stores for it */
};

CP_STATIC_ASSERT(JOB_CMDS <= 255 && JOB_BAD_WORD <= 255, ids_fit_a_byte);
/* every keyword and word shorter than PARSE_KW_MAX, every VALUE a byte; a command's
 * numbers fit job_args.v (JOB_MAX_NUMBERS) and its tokens the line's JOB_MAX_TOKENS
 * (keyword, word or unsigned number, numbers, option); UINT_NUMBERS_OPTION rows take
 * exactly MIN = MAX numbers (the tests check that keywords and words are distinct:
 * commands_distinct) */
#define CP_CMD(OWNER, NAME, KEYWORD, SHAPE, MIN, MAX, SURFACE)                                     \
    CP_STATIC_ASSERT(sizeof(KEYWORD) <= PARSE_KW_MAX && (MIN) <= (MAX) &&                          \
                         (MAX) <= JOB_MAX_NUMBERS && 3 + (MAX) <= JOB_MAX_TOKENS &&                \
                         (JOB_ARGS_##SHAPE != JOB_ARGS_UINT_NUMBERS_OPTION || (MIN) == (MAX)),     \
                     kw_##OWNER##_##NAME);
#define CP_CMD_WORD(CMD, WORD, TEXT, NUMBERS, VALUE)                                               \
    CP_STATIC_ASSERT(sizeof(TEXT) <= PARSE_KW_MAX && (VALUE) <= 255 &&                             \
                         (NUMBERS) <= JOB_MAX_NUMBERS && 3 + (NUMBERS) <= JOB_MAX_TOKENS,          \
                     word_##WORD);
#define CP_CMD_OPTION(CMD, WORD, TEXT, VALUE)                                                      \
    CP_STATIC_ASSERT(sizeof(TEXT) <= PARSE_KW_MAX && (VALUE) <= 255, option_##WORD);
#include "commands.def"
#undef CP_CMD
#undef CP_CMD_WORD
#undef CP_CMD_OPTION

static const struct job_cmd_row cmds[JOB_CMDS] = {
#define CP_CMD(OWNER, NAME, KEYWORD, SHAPE, MIN, MAX, SURFACE)                                     \
    [OWNER##_CMD_##NAME] = {.keyword = KEYWORD,                                                    \
                            .owner = JOB_OWNER_##OWNER,                                            \
                            .shape = JOB_ARGS_##SHAPE,                                             \
                            .min = MIN,                                                            \
                            .max = MAX,                                                            \
                            .surface = JOB_SURFACE_##SURFACE},
#define CP_CMD_WORD(CMD, WORD, TEXT, NUMBERS, VALUE)
#define CP_CMD_OPTION(CMD, WORD, TEXT, VALUE)
#include "commands.def"
#undef CP_CMD
#undef CP_CMD_WORD
#undef CP_CMD_OPTION
};

/* clang-format off */
static const struct job_word_row words[JOB_WORDS] = {
#define CP_CMD(OWNER, NAME, KEYWORD, SHAPE, MIN, MAX, SURFACE)
#define CP_CMD_WORD(CMD, WORD, TEXT, NUMBERS, VALUE) \
    [JOB_WORD_##WORD] = {.text = TEXT, .cmd = CMD, .option = 0u, .numbers = NUMBERS, \
                         .value = VALUE},
#define CP_CMD_OPTION(CMD, WORD, TEXT, VALUE) \
    [JOB_WORD_##WORD] = {.text = TEXT, .cmd = CMD, .option = 1u, .numbers = 0u, .value = VALUE},
#include "commands.def"
#undef CP_CMD
#undef CP_CMD_WORD
#undef CP_CMD_OPTION
};
/* clang-format on */

/* The tokens of one command line. */
struct job_tokens {
    const char *line;
    unsigned n; /* tokens (JOB_MAX_TOKENS + 1: more) */
    uint16_t st[JOB_MAX_TOKENS], ln[JOB_MAX_TOKENS];
};

/* ---- the models of models.def: one case per row, the rows not compiled in left out ---- */

const char *job_models(void)
{
    /* "+WORD" of every compiled-in row; the list starts after the first '+' */
    static const char models[] =
#define CP_MODEL(NAME, name, WITH, WORD) PATH_IF(WITH, "+" WORD)
#include "models.def"
#undef CP_MODEL
        ;
    return models + 1;
}

/* SURFACE <k>: model k's geometry starts afresh. */
static void model_defaults(unsigned k, union path_geom *g)
{
    switch (k) {
#define CP_MODEL(NAME, name, WITH, WORD)                                                           \
    PATH_IF(WITH, case PATH_##NAME : job_##name##_defaults(g); break;)
#include "models.def"
#undef CP_MODEL
    default:
        break;
    }
}

int job_ready(const struct job *j)
{
    switch (j->kind) {
#define CP_MODEL(NAME, name, WITH, WORD)                                                           \
    PATH_IF(WITH, case PATH_##NAME : return job_##name##_ready(j) ? CP_ST_OK : CP_ST_NO_JOB;)
#include "models.def"
#undef CP_MODEL
    default:
        return CP_ST_NO_JOB;
    }
}

/* (not inlined: one copy for proto_init and JOB CLEAR) */
CP_NOINLINE void job_init(struct job *j)
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
    j->cfg.link = RASTER_LINK_AUTO;
    j->cfg.tol = CP_R(0.001);
    j->rxbuf = 0u; /* the dialect's (machines.def) */
}

/* ---- lookups in the tables of commands.def ---- */

void job_geom_fill(struct job *j)
{
    unsigned i;
    if (j->kind == PATH_CANAL) {
        j->geom.canal = j->canal;
    }
#if CP_WITH_DRC
    if (j->kind == PATH_DRC) { /* the EDGE fillet's radius law: the canal's RADIUS */
        j->geom.drc.radius = j->canal.radius;
        for (i = 0; i < 4u; i++) {
            j->geom.drc.rp[i] = j->canal.rp[i];
        }
    }
#endif
#if CP_WITH_SPINE
    if (j->kind == PATH_SPINE) { /* the radius law in u: the canal's RADIUS (same enum) */
        job_spine_fill(&j->geom.spine);
        j->geom.spine.law = j->canal.radius;
        for (i = 0; i < 4u; i++) {
            j->geom.spine.rp[i] = j->canal.rp[i];
        }
    }
#endif
    (void)i;
}

/* The command whose keyword s[0..n) is (parse_is), JOB_CMDS if none. */
static unsigned find_cmd(const char *s, size_t n)
{
    unsigned c;
    for (c = 0; c < (unsigned)JOB_CMDS; c++) {
        if (parse_is(s, n, cmds[c].keyword)) {
            break;
        }
    }
    return c;
}

/* The word (option 0) or option word (option 1) of command c that s[0..n) is,
 * JOB_NO_WORD if none. */
static enum job_word find_word(unsigned c, unsigned option, const char *s, size_t n)
{
    unsigned w;
    for (w = 0; w < (unsigned)JOB_WORDS; w++) {
        if (words[w].cmd == c && words[w].option == option && parse_is(s, n, words[w].text)) {
            return (enum job_word)w;
        }
    }
    return JOB_NO_WORD;
}

/* 1 if command c has option words. */
static int has_options(unsigned c)
{
    unsigned w;
    for (w = 0; w < (unsigned)JOB_WORDS; w++) {
        if (words[w].cmd == c && words[w].option != 0u) {
            return 1;
        }
    }
    return 0;
}

/* Token i of t as a word or option word of command c. */
static enum job_word token_word(const struct job_tokens *t, unsigned i, unsigned c, unsigned option)
{
    return find_word(c, option, t->line + t->st[i], t->ln[i]);
}

/* 1 if the commands of `owner` are compiled in. */
static int owner_built(unsigned owner)
{
    return owner >= PATH_KINDS || path_has(owner);
}

int job_is_command(const char *line, size_t len)
{
    size_t n = 0;
    unsigned c;
    while (n < len && line[n] != ' ') {
        n++;
    }
    c = find_cmd(line, n);
    return c < (unsigned)JOB_CMDS && owner_built(cmds[c].owner);
}

/* ---- the arguments ---- */

/* Parse tokens first..first+n-1 as numbers into a->v[] (a failing one: a->bad). Returns a
 * wire status. */
static int job_numbers(const struct job_tokens *t, unsigned first, unsigned n, struct job_args *a)
{
    unsigned i;
    for (i = 0; i < n; i++) {
        int s = parse_real(t->line + t->st[first + i], t->ln[first + i], &a->v[i]);
        if (s != CP_ST_OK) {
            a->bad = (uint8_t)(JOB_ARG_V + i);
            a->limit = s == CP_ST_OUT_OF_RANGE ? "|x| <= 1e9" : NULL;
            return s;
        }
    }
    return CP_ST_OK;
}

/* The word after the keyword (the word shapes, at least 2 tokens): a->word, its value and
 * the tokens it takes (*first, *na, the last word: *ntv), or an unsigned number instead
 * (*uint). Returns a wire status. */
static int word_args(const struct job_tokens *t, const struct job_cmd_row *r, struct job_args *a,
                     unsigned *first, unsigned *na, unsigned *ntv, unsigned *uint)
{
    a->word = token_word(t, 1u, a->cmd, 0u);
    if (a->word == JOB_NO_WORD) {
        if (r->shape != JOB_ARGS_UINT_OR_WORD) {
            a->bad = JOB_ARG_WORD;
            return CP_ST_BAD_KEYWORD;
        }
        *na = 1u; /* the unsigned number */
        *uint = 1u;
        return CP_ST_OK;
    }
    a->value = words[a->word].value;
    *na = words[a->word].numbers;
    *first = 2u;
    if (r->shape == JOB_ARGS_WORD_NUMBERS_OPTION) {
        if (*na == 0u && t->n > 2u) { /* a word without numbers takes nothing more */
            return CP_ST_BAD_KEYWORD;
        }
        if (t->n == 3u + *na) { /* the option word (its check is the hook's, after ranges) */
            a->option = token_word(t, t->n - 1u, a->cmd, 1u);
            if (a->option == JOB_NO_WORD) {
                a->option = JOB_BAD_WORD;
            } else {
                a->option_value = words[a->option].value;
            }
            (*ntv)--;
        }
    }
    return CP_ST_OK;
}

/* Check the arguments of command c as its shape says (enum job_shape: arity, words,
 * unsigned number, numbers, in that order) into *a. Returns a wire status. */
static int job_args_of(const struct job_tokens *t, enum job_cmd c, struct job_args *a)
{
    const struct job_cmd_row *r = &cmds[c];
    unsigned first = 1u, na = 0u, ntv = t->n, uint = 0u;
    int s = CP_ST_OK;
    a->cmd = c;
    a->word = JOB_NO_WORD;
    a->value = 0u;
    a->option = JOB_NO_WORD;
    a->option_value = 0u;
    a->u = 0u;
    a->bad = JOB_ARG_NONE;
    a->limit = NULL;
    a->tok_u = 0u;
    a->args_min = a->args_max = 0u; /* error:3's cause: the arguments it takes */
    switch (r->shape) {
    case JOB_ARGS_NUMBERS:
        if (t->n < 1u + r->min || t->n > 1u + r->max) {
            a->args_min = r->min;
            a->args_max = r->max;
            return CP_ST_BAD_ARITY;
        }
        na = t->n - 1u;
        break;
    case JOB_ARGS_UINT_NUMBERS_OPTION:
        if (t->n == 3u + r->min && has_options(c)) { /* the option word first */
            a->option = token_word(t, t->n - 1u, c, 1u);
            if (a->option == JOB_NO_WORD) {
                a->bad = JOB_ARG_OPTION;
                return CP_ST_BAD_KEYWORD;
            }
            a->option_value = words[a->option].value;
            ntv--;
        }
        na = 1u + r->min;
        uint = 1u;
        break;
    case JOB_ARGS_ALONE: /* nothing after the keyword (job_line answers RUN before) */
        break;
    default: /* a word after the keyword: exactly one token for WORD and UINT_OR_WORD */
        if (t->n < 2u ||
            (t->n != 2u && (r->shape == JOB_ARGS_WORD || r->shape == JOB_ARGS_UINT_OR_WORD))) {
            a->args_min = a->args_max = 1u; /* a word (numbers after it: the word's row) */
            return CP_ST_BAD_ARITY;
        }
        s = word_args(t, r, a, &first, &na, &ntv, &uint);
        break;
    }
    if (s != CP_ST_OK) {
        return s;
    }
    if (ntv != first + na) {
        a->args_min = (uint8_t)(first - 1u + na); /* a known word's numbers, or LINES' */
        a->args_max = (uint8_t)(a->args_min + (has_options(c) ? 1u : 0u));
        return CP_ST_BAD_ARITY;
    }
    if (uint) { /* the first argument is an unsigned number */
        a->tok_u = (uint8_t)first;
        s = parse_uint(t->line + t->st[first], t->ln[first], UINT32_MAX, &a->u);
        if (s != CP_ST_OK) {
            a->bad = JOB_ARG_U;
            return s;
        }
        first++;
        na--;
    }
    a->na = na;
    a->tok_v = (uint8_t)first;
    return job_numbers(t, first, na, a);
}

/* ---- job.c's own commands: the raster, the output, SURFACE ---- */

/* A hook's refusal: argument `bad` (JOB_ARG_*) broke `limit` (NULL: none given). Not
 * inlined: one call per refusal instead of its stores at each. */
static CP_NOINLINE int refuse(struct job_args *a, int st, unsigned bad, const char *limit)
{
    a->bad = (uint8_t)bad;
    a->limit = limit;
    return st;
}

int job_limit_abs(struct job_args *a, unsigned first, unsigned end, cp_real max,
                  const char *limit)
{
    unsigned i;
    for (i = first; i < end; i++) {
        if (!(cp_fabs(a->v[i]) <= max)) {
            return refuse(a, CP_ST_OUT_OF_RANGE, JOB_ARG_V + i, limit);
        }
    }
    return CP_ST_OK;
}

/* TOOL NONE | BALL r [TIP|CENTRE|CENTER] */
static int job_tool(struct job *j, struct job_args *a)
{
    if (a->word == JOB_WORD_TOOL_NONE) {
        j->cfg.output = (uint8_t)a->value; /* RASTER_OUT_SURFACE */
        j->cfg.tool_r = CP_R(0.0);
        return CP_ST_OK;
    }
    if (!(a->v[0] > CP_R(0.0)) || a->v[0] > CANAL_COORD_MAX) {
        return refuse(a, CP_ST_OUT_OF_RANGE, JOB_ARG_V, "0 < r <= 1e4");
    }
    if (a->option == JOB_BAD_WORD) {
        return refuse(a, CP_ST_BAD_KEYWORD, JOB_ARG_OPTION, NULL);
    }
    /* the option's output, else the word's (BALL: the tip) */
    j->cfg.output = (uint8_t)(a->option == JOB_NO_WORD ? a->value : a->option_value);
    j->cfg.tool_r = a->v[0];
    return CP_ST_OK;
}

/* LINES | CIRCLES n u0 u1 [PATCH] */
static int job_raster(struct job *j, struct job_args *a)
{
    const cp_real *v = a->v;
    uint32_t n = a->u;
    int circles = a->cmd == JOB_CMD_CIRCLES;
    if (n > CP_MAX_LINES) {
        return refuse(a, CP_ST_TOO_MANY, JOB_ARG_U, "$I lines=");
    }
    if (n == 0u) {
        return refuse(a, CP_ST_OUT_OF_RANGE, JOB_ARG_U, "n >= 1");
    }
    if (job_limit_abs(a, 0u, 2u, CP_R(180.0), "|u| <= 180") != CP_ST_OK) {
        return CP_ST_OUT_OF_RANGE;
    }
    if (v[0] == v[1] && n > 1u) {
        return refuse(a, CP_ST_OUT_OF_RANGE, JOB_ARG_V + 1u, "u0 != u1 for n > 1");
    }
    j->cfg.mode = circles ? RASTER_CIRCLES : RASTER_LINES;
    /* PATCH: between the lines that start at u0, u1; CIRCLES alone: the angles u0..u1 */
    j->cfg.span = a->option != JOB_NO_WORD ? (uint8_t)a->option_value
                  : circles                ? RASTER_SPAN_ANGLE
                                           : RASTER_SPAN_LINES;
    j->cfg.n = (uint16_t)n;
    j->cfg.u0 = v[0] * CP_DEG2RAD;
    j->cfg.u1 = v[1] * CP_DEG2RAD;
    j->have |= JOB_HAVE_RASTER;
    return CP_ST_OK;
}

/* SURFACE <model>: the model's geometry starts afresh (the union holds one model; the
 * canal's and the raster's settings and have bits stay) */
static int job_surface(struct job *j, struct job_args *a)
{
    if (!path_has(a->value)) { /* a model not in this build ($I models=) */
        return refuse(a, CP_ST_BAD_KEYWORD, JOB_ARG_WORD, "$I models=");
    }
    model_defaults(a->value, &j->geom);
    j->kind = (uint8_t)a->value;
    return CP_ST_OK;
}

/* PLACE x y z [rz] | TILT axis_deg angle_deg: every number finite and in range (error:6),
 * else the job unchanged */
static int job_place_cmd(struct job *j, struct job_args *a)
{
    struct job_place *pl = &j->place;
    const cp_real *v = a->v;
    unsigned i;
    if (a->cmd == JOB_CMD_TILT) {
        if (job_limit_abs(a, 0u, 1u, JOB_TILT_AXIS_MAX, "|axis| <= 360") != CP_ST_OK ||
            job_limit_abs(a, 1u, 2u, JOB_TILT_MAX, "|angle| <= 90") != CP_ST_OK) {
            return CP_ST_OUT_OF_RANGE;
        }
        pl->axis = v[0];
        pl->tilt = v[1];
        return CP_ST_OK;
    }
    if (job_limit_abs(a, 0u, 3u, JOB_PLACE_OFF_MAX, "|x|, |y|, |z| <= 1000") != CP_ST_OK ||
        job_limit_abs(a, 3u, a->na, JOB_PLACE_RZ_MAX, "|rz| <= 360") != CP_ST_OK) {
        return CP_ST_OUT_OF_RANGE; /* (rz: the 4th number, when given) */
    }
    for (i = 0; i < 3u; i++) {
        pl->off[i] = v[i];
    }
    pl->rz = a->na == 4u ? v[3] : CP_R(0.0);
    return CP_ST_OK;
}

/* The commands of owner JOB, their arguments checked (job_args_of). */
/* FEED f [plunge [link]]: f 0 (not set: alone) or JOB_FEED_MIN..JOB_FEED_MAX, plunge and
 * link in that range too; plunge and link default to f. */
static int job_feed(struct job *j, struct job_args *a)
{
    unsigned i;
    for (i = 0; i < a->na; i++) {
        cp_real f = a->v[i];
        if (!(f == CP_R(0.0) && a->na == 1u) && !(f >= JOB_FEED_MIN && f <= JOB_FEED_MAX)) {
            return refuse(a, CP_ST_OUT_OF_RANGE, JOB_ARG_V + i,
                          i == 0u ? "0 or 0.001..1e6" : "0.001..1e6");
        }
    }
    for (i = 0; i < 3u; i++) {
        j->feed[i] = a->v[i < a->na ? i : 0u];
    }
    return CP_ST_OK;
}

static int job_own_command(struct job *j, struct job_args *a)
{
    const cp_real *v = a->v;
    uint32_t u = a->u;
    switch (a->cmd) {
    case JOB_CMD_TOOL:
        return job_tool(j, a);
    case JOB_CMD_LINES:
    case JOB_CMD_CIRCLES:
        return job_raster(j, a);
    case JOB_CMD_STEPS:
        if (u > CP_MAX_STEPS) {
            return refuse(a, CP_ST_TOO_MANY, JOB_ARG_U, "$I steps=");
        }
        if (u == 0u) {
            return refuse(a, CP_ST_OUT_OF_RANGE, JOB_ARG_U, "m >= 1");
        }
        j->cfg.steps = (uint16_t)u;
        j->cfg.tol = CP_R(0.0);
        return CP_ST_OK;
    case JOB_CMD_TOL:
        if (v[0] < CP_R(0.01) || v[0] > CP_R(10000.0)) {
            return refuse(a, CP_ST_OUT_OF_RANGE, JOB_ARG_V, "0.01..10000");
        }
        j->cfg.tol = v[0] * CP_R(0.001);
        j->cfg.steps = 0;
        return CP_ST_OK;
    case JOB_CMD_FEED:
        return job_feed(j, a);
    case JOB_CMD_SAFE:
        if (job_limit_abs(a, 0u, 1u, JOB_SAFE_MAX, "|z| <= 1000") != CP_ST_OK) {
            return CP_ST_OUT_OF_RANGE;
        }
        j->safe = v[0];
        j->safe_set = 1u;
        return CP_ST_OK;
    case JOB_CMD_SPINDLE:
        if (!(v[0] == CP_R(0.0) || (v[0] >= CP_R(1.0) && v[0] <= JOB_SPINDLE_MAX))) {
            return refuse(a, CP_ST_OUT_OF_RANGE, JOB_ARG_V, "0 or 1..100000");
        }
        j->spindle = v[0];
        return CP_ST_OK;
    case JOB_CMD_WCS:
        j->wcs = (uint8_t)a->value;
        return CP_ST_OK;
    case JOB_CMD_MACHINE:
        j->machine = (uint8_t)a->value; /* enum job_machine */
        return CP_ST_OK;
    case JOB_CMD_LINK:
        j->link = (uint8_t)a->value; /* enum job_link */
        return CP_ST_OK;
    case JOB_CMD_TOOLAXIS:
        if (a->na == 2u &&
            (job_limit_abs(a, 0u, 1u, JOB_TOOLAXIS_ANGLE_MAX, "|lead| <= 60") != CP_ST_OK ||
             job_limit_abs(a, 1u, 2u, JOB_TOOLAXIS_ANGLE_MAX, "|side| <= 60") != CP_ST_OK)) {
            return CP_ST_OUT_OF_RANGE;
        }
        j->toolaxis = (uint8_t)a->value;
        j->lead = a->na == 2u ? v[0] : CP_R(0.0);
        j->side = a->na == 2u ? v[1] : CP_R(0.0);
        return CP_ST_OK;
    case JOB_CMD_RXBUF:
        if (u < JOB_RXBUF_MIN || u > JOB_RXBUF_MAX) {
            return refuse(a, CP_ST_OUT_OF_RANGE, JOB_ARG_U, "120..1024");
        }
        j->rxbuf = (uint16_t)u;
        return CP_ST_OK;
    case JOB_CMD_FORMAT:
        j->format = (uint8_t)a->value; /* enum job_format */
        return CP_ST_OK;
    case JOB_CMD_CHECKSUM:
        j->checksum = (uint8_t)a->value;
        return CP_ST_OK;
    case JOB_CMD_SURFACE:
        return job_surface(j, a);
    case JOB_CMD_PLACE:
    case JOB_CMD_TILT:
        return job_place_cmd(j, a);
    case JOB_CMD_CLEAR: { /* JOB CLEAR: the defaults, but the cell's wiring stays */
        uint8_t machine = j->machine, link = j->link;
        job_init(j);
        j->machine = machine;
        j->link = link;
        return CP_ST_OK;
    }
    default: /* not JOB's (unreachable: job_line calls the owner's hook) */
        return CP_ST_UNKNOWN_CMD;
    }
}

/* The hook of the command's owner. */
static int owner_command(struct job *j, unsigned owner, struct job_args *a)
{
    switch (owner) {
#define CP_MODEL(NAME, name, WITH, WORD)                                                           \
    PATH_IF(WITH, case JOB_OWNER_##NAME : return job_##name##_command(j, a);)
#include "models.def"
#undef CP_MODEL
    default: /* JOB_OWNER_JOB */
        return job_own_command(j, a);
    }
}

/* ---- the job as command lines ($J) ---- */

const char *job_keyword(enum job_cmd c)
{
    return (unsigned)c < (unsigned)JOB_CMDS ? cmds[c].keyword : "";
}

const char *job_word_text(enum job_word w)
{
    return (unsigned)w < (unsigned)JOB_WORDS ? words[w].text : "";
}

unsigned job_shape_of(enum job_cmd c)
{
    return (unsigned)c < (unsigned)JOB_CMDS ? cmds[c].shape : JOB_ARGS_ALONE;
}

enum job_word job_word_of(enum job_cmd c, unsigned value, unsigned option)
{
    unsigned w;
    for (w = 0; w < (unsigned)JOB_WORDS; w++) {
        if (words[w].cmd == c && words[w].option == option && words[w].value == value) {
            return (enum job_word)w;
        }
    }
    return JOB_NO_WORD;
}

void job_dump_args(struct job_args *a, enum job_cmd c, enum job_word w)
{
    unsigned i;
    a->cmd = c;
    a->word = w;
    a->value = 0u;
    a->option = JOB_NO_WORD;
    a->option_value = 0u;
    a->na = (unsigned)w < (unsigned)JOB_WORDS ? words[w].numbers : 0u;
    a->u = 0u;
    for (i = 0; i < JOB_MAX_NUMBERS; i++) {
        a->v[i] = CP_R(0.0);
        a->scale[i] = JOB_SCALE_ONE;
    }
}

void job_dump_word(struct job_args *a, enum job_cmd c, unsigned value)
{
    job_dump_args(a, c, job_word_of(c, value, 0u));
}

void job_dump_numbers(struct job_args *a, const cp_real *v)
{
    unsigned i;
    for (i = 0; i < a->na && i < JOB_MAX_NUMBERS; i++) {
        a->v[i] = v[i];
    }
}

CP_NOINLINE void job_dump_vec3(struct job_args *a, unsigned k, const struct cp_vec3 *p)
{
    a->v[k] = p->x;
    a->v[k + 1u] = p->y;
    a->v[k + 2u] = p->z;
}

/* The items of job.c's own commands (JOB_DUMP_ITEMS_OWN of them), in this order; SKIP at
 * the default. */
static const uint8_t dump_cmds[] = {
    JOB_CMD_TOOL,    JOB_CMD_LINES, JOB_CMD_STEPS,   JOB_CMD_FEED,    JOB_CMD_FORMAT,
    JOB_CMD_RXBUF,   JOB_CMD_CHECKSUM, JOB_CMD_SURFACE, JOB_CMD_PLACE, JOB_CMD_TILT,
    JOB_CMD_SAFE,    JOB_CMD_SPINDLE, JOB_CMD_WCS,    JOB_CMD_MACHINE, JOB_CMD_LINK,
    JOB_CMD_TOOLAXIS};
#define JOB_DUMP_ITEMS_OWN ((unsigned)(sizeof dump_cmds / sizeof dump_cmds[0]))

/* A command of one word (FORMAT, CHECKSUM, SURFACE, WCS, MACHINE, LINK): its word for the
 * value, SKIP at the default 0 (JOB_GCODE, off, PATH_CANAL, G54, GENERIC, HOST). */
static int dump_word(struct job_args *a, unsigned value)
{
    job_dump_word(a, a->cmd, value);
    return value == 0u ? JOB_DUMP_SKIP : JOB_DUMP_LINE;
}

/* One number v (scale 1): SKIP when skip is non-zero. */
static int dump_number(struct job_args *a, cp_real v, int skip)
{
    a->na = 1u;
    a->v[0] = v;
    return skip ? JOB_DUMP_SKIP : JOB_DUMP_LINE;
}

static int dump_own(const struct job *j, unsigned i, struct job_args *a)
{
    const struct raster_cfg *c = &j->cfg;
    enum job_cmd cmd = (enum job_cmd)dump_cmds[i];
    job_dump_args(a, cmd, JOB_NO_WORD);
    switch (cmd) {
    case JOB_CMD_TOOL: /* TOOL BALL r [CENTRE] (TIP is BALL's own); NONE is the default */
        if (c->output == RASTER_OUT_SURFACE) {
            return JOB_DUMP_SKIP;
        }
        job_dump_args(a, JOB_CMD_TOOL, JOB_WORD_TOOL_BALL);
        a->v[0] = c->tool_r;
        a->option = c->output == RASTER_OUT_CENTRE ? JOB_WORD_TOOL_CENTRE : JOB_NO_WORD;
        return JOB_DUMP_LINE;
    case JOB_CMD_LINES: /* LINES | CIRCLES n u0 u1 [PATCH] */
        if ((j->have & JOB_HAVE_RASTER) == 0u) {
            return JOB_DUMP_SKIP;
        }
        a->cmd = c->mode == RASTER_CIRCLES ? JOB_CMD_CIRCLES : JOB_CMD_LINES;
        a->option = c->mode == RASTER_CIRCLES && c->span == RASTER_SPAN_LINES
                        ? JOB_WORD_CIRCLES_PATCH
                        : JOB_NO_WORD;
        a->u = c->n;
        a->na = 2u;
        a->v[0] = c->u0;
        a->v[1] = c->u1;
        a->scale[0] = a->scale[1] = JOB_SCALE_DEG;
        return JOB_DUMP_LINE;
    case JOB_CMD_STEPS: /* STEPS m | TOL chord_um (TOL 1 is the default) */
        if (c->steps != 0u) {
            a->u = c->steps;
            return JOB_DUMP_LINE;
        }
        a->cmd = JOB_CMD_TOL;
        a->scale[0] = JOB_SCALE_MILLI;
        return dump_number(a, c->tol, c->tol == CP_R(0.001));
    case JOB_CMD_FEED: /* FEED f plunge link */
        a->na = 3u;
        job_dump_numbers(a, j->feed);
        return j->feed[0] == CP_R(0.0) ? JOB_DUMP_SKIP : JOB_DUMP_LINE;
    case JOB_CMD_RXBUF: /* RXBUF n (0: the dialect's) */
        a->u = j->rxbuf;
        return j->rxbuf == 0u ? JOB_DUMP_SKIP : JOB_DUMP_LINE;
    case JOB_CMD_PLACE: /* PLACE x y z rz (mm, degrees as given) */
        a->na = 4u;
        a->v[0] = j->place.off[0];
        a->v[1] = j->place.off[1];
        a->v[2] = j->place.off[2];
        a->v[3] = j->place.rz;
        return a->v[0] == CP_R(0.0) && a->v[1] == CP_R(0.0) && a->v[2] == CP_R(0.0) &&
                       a->v[3] == CP_R(0.0)
                   ? JOB_DUMP_SKIP
                   : JOB_DUMP_LINE;
    case JOB_CMD_TILT: /* TILT axis angle (degrees as given) */
        a->na = 2u;
        a->v[0] = j->place.axis;
        a->v[1] = j->place.tilt;
        return j->place.tilt == CP_R(0.0) ? JOB_DUMP_SKIP : JOB_DUMP_LINE;
    case JOB_CMD_SAFE:
        return dump_number(a, j->safe, !j->safe_set);
    case JOB_CMD_SPINDLE:
        return dump_number(a, j->spindle, j->spindle == CP_R(0.0));
    case JOB_CMD_FORMAT:
        return dump_word(a, j->format);
    case JOB_CMD_CHECKSUM:
        return dump_word(a, j->checksum);
    case JOB_CMD_SURFACE:
        return dump_word(a, j->kind);
    case JOB_CMD_WCS:
        return dump_word(a, j->wcs);
    case JOB_CMD_MACHINE:
        return dump_word(a, j->machine);
    case JOB_CMD_TOOLAXIS: /* TOOLAXIS AC|IJK lead side (OFF is the default) */
        job_dump_word(a, JOB_CMD_TOOLAXIS, j->toolaxis);
        a->v[0] = j->lead;
        a->v[1] = j->side;
        return j->toolaxis == JOB_TOOLAXIS_OFF ? JOB_DUMP_SKIP : JOB_DUMP_LINE;
    default: /* JOB_CMD_LINK */
        return dump_word(a, j->link);
    }
}

/* The model of the job's items. */
static int dump_model(const struct job *j, unsigned i, struct job_args *a)
{
    switch (j->kind) {
#define CP_MODEL(NAME, name, WITH, WORD)                                                           \
    PATH_IF(WITH, case PATH_##NAME : return job_##name##_dump(j, i, a);)
#include "models.def"
#undef CP_MODEL
    default:
        return JOB_DUMP_END;
    }
}

int job_dump(const struct job *j, unsigned i, struct job_args *a)
{
    int r;
    if (i < JOB_DUMP_ITEMS_OWN) {
        return dump_own(j, i, a);
    }
    i -= JOB_DUMP_ITEMS_OWN;
    if (i < JOB_CANAL_ITEMS) { /* CURVE, RADIUS: every SURFACE's */
        return job_canal_dump(j, i, a);
    }
    if (j->kind == PATH_CANAL) {
        return JOB_DUMP_END;
    }
    r = dump_model(j, i - JOB_CANAL_ITEMS, a);
    return r;
}

/* ---- the lines ---- */

int job_command(struct job *j, const char *line, size_t len)
{
    /* RUN and RESUME are the protocol's, whatever follows them (job_line checks
     * RESUME's argument; proto.c calls job_line, so this costs the image nothing) */
    uint16_t st, ln;
    uint32_t first;
    unsigned c = parse_split(line, len, &st, &ln, 1u) > 0u ? find_cmd(line + st, ln) : JOB_CMDS;
    if (c < (unsigned)JOB_CMDS && cmds[c].owner == JOB_OWNER_PROTO) {
        return JOB_NOT_MINE;
    }
    return job_line(j, line, len, &first);
}

/* The cause of a refusal (a->bad, a->limit) into j->cause_*: the token of the argument that
 * failed. */
static void job_cause(struct job *j, const struct job_tokens *t, const struct job_args *a)
{
    unsigned k = a->bad == JOB_ARG_U        ? a->tok_u
                 : a->bad == JOB_ARG_WORD   ? 1u
                 : a->bad == JOB_ARG_OPTION ? t->n - 1u
                 : a->bad >= JOB_ARG_V      ? a->tok_v + (a->bad - JOB_ARG_V)
                                            : 0u;
    if (k > 0u && k < t->n && k < JOB_MAX_TOKENS) {
        j->cause_st = (uint8_t)t->st[k];
        j->cause_len = (uint8_t)t->ln[k];
    }
    j->cause_limit = a->limit;
    j->cause_args_min = a->args_min;
    j->cause_args_max = a->args_max;
}

int job_line(struct job *j, const char *line, size_t len, uint32_t *first_k)
{
    struct job_tokens t;
    struct job_args a;
    const struct job_cmd_row *r;
    unsigned c;
    int s;
    t.line = line;
    j->cause_len = 0u;
    j->cause_limit = NULL;
    j->cause_args_max = 0u;
    t.n = parse_split(line, len, t.st, t.ln, JOB_MAX_TOKENS);
    /* (parse_split stored at most JOB_MAX_TOKENS tokens: n beyond that is error:3) */
    c = t.n > 0u ? find_cmd(line + t.st[0], t.ln[0]) : JOB_CMDS;
    if (c == JOB_CMDS || !owner_built(cmds[c].owner)) { /* no job command */
        return JOB_NOT_MINE;
    }
    r = &cmds[c];
    if (r->shape == JOB_ARGS_ALONE) { /* RUN, $J: alone on their line (the line is trimmed) */
        *first_k = 0u;
        if (t.n != 1u) {
            return JOB_NOT_MINE;
        }
        return c == PROTO_CMD_DUMP ? JOB_DUMP : JOB_RUN;
    }
    if (t.n > JOB_MAX_TOKENS) {
        return CP_ST_BAD_ARITY;
    }
    if (r->surface == JOB_SURFACE_OWN && j->kind != r->owner) {
        return CP_ST_WRONG_SURFACE;
    }
    s = job_args_of(&t, (enum job_cmd)c, &a);
    if (c == PROTO_CMD_RESUME) { /* RESUME k: the run from point k (k above 2^32 - 1: 21) */
        if (s == CP_ST_OK) {
            *first_k = a.u;
            return JOB_RUN;
        }
        return s == CP_ST_OUT_OF_RANGE ? CP_ST_RESUME_RANGE : s;
    }
    if (s == CP_ST_OK) {
        s = owner_command(j, r->owner, &a);
    }
    if (s != CP_ST_OK) {
        job_cause(j, &t, &a);
    }
    return s;
}
