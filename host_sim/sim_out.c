/* sim_out.c - CSV, G-code and SVG writers of host_sim.
 * SPDX-License-Identifier: MIT
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "judge.h"
#include <string.h>

#include "sim_out.h"

static FILE *out_csv, *out_gc;
static const char *out_svg_path;
static struct sim_out_pt *pts;
static unsigned long npts, cap, nwritten;
static int csv_header, gc_preamble, gc_direct; /* gc_direct: GCODE bodies arrive */

/* the runs, for the SVG */
struct out_run {
    unsigned long at; /* index in pts of its first point */
    uint32_t points, first;
    int mode; /* 0 LINES (family 2), 1 CIRCLES (family 1) */
    unsigned n, steps, link;
    int rapid_in; /* reached by a move that was not streamed (a new RUN) */
    char word[16];
    char tol[48], tool[48]; /* TOL / STEPS and TOOL of the job at RUN */
};
static struct out_run runs[SIM_OUT_RUNS_MAX];
static unsigned nruns;
static uint32_t next_k; /* k of the next point expected in this run */
static char tol_text[48], tool_text[48];

const char *sim_out_fixed4(int32_t v, char *buf)
{
    uint32_t a = v < 0 ? (uint32_t)(-(int64_t)v) : (uint32_t)v;
    sprintf(buf, "%s%lu.%04lu", v < 0 ? "-" : "", (unsigned long)(a / 10000u),
            (unsigned long)(a % 10000u));
    return buf;
}

int sim_out_open(const char *csv, const char *gcode, const char *svg)
{
    if (csv != NULL && (out_csv = fopen(csv, "w")) == NULL) {
        perror(csv);
        return -1;
    }
    if (gcode != NULL && (out_gc = fopen(gcode, "w")) == NULL) {
        perror(gcode);
        return -1;
    }
    out_svg_path = svg;
    return 0;
}

static void gc_pre(void)
{
    if (out_gc != NULL && !gc_preamble) {
        fputs("G21 G90 G17\n", out_gc);
        gc_preamble = 1;
    }
}

void sim_out_gcode(const char *body)
{
    gc_direct = 1;
    if (out_gc == NULL) {
        return;
    }
    /* one file for every RUN of the session: each program's end but the last would stop
     * an interpreter (rs274 reads nothing after M2), so the ends are left out and the
     * file gets one M2 when it closes; each program begins with its rapid to the safe
     * height, so no feed move joins two RUNs */
    if (strcmp(body, "M2") == 0 || strcmp(body, "M30") == 0 || strcmp(body, "M400") == 0) {
        return;
    }
    gc_pre();
    fprintf(out_gc, "%s\n", body);
}

void sim_out_point(const struct sim_out_pt *p)
{
    char a[24], b[24], c[24];
    nwritten++;
    next_k++;
    if (out_csv != NULL) {
        if (!csv_header) {
            fputs(p->has_n ? "line,index,x,y,z,nx,ny,nz\n" : "line,index,x,y,z\n", out_csv);
            csv_header = 1;
        }
        fprintf(out_csv, "%ld,%lu,%s,%s,%s", (long)p->line, (unsigned long)p->index,
                sim_out_fixed4(p->x, a), sim_out_fixed4(p->y, b), sim_out_fixed4(p->z, c));
        if (p->has_n) {
            fprintf(out_csv, ",%.5f,%.5f,%.5f", p->n[0] / 32767.0, p->n[1] / 32767.0,
                    p->n[2] / 32767.0);
        }
        fputc('\n', out_csv);
    }
    if (out_gc != NULL && !gc_direct) {
        gc_pre();
        fprintf(out_gc, "G1 X%s Y%s Z%s\n", sim_out_fixed4(p->x, a), sim_out_fixed4(p->y, b),
                sim_out_fixed4(p->z, c));
    }
    if (out_svg_path != NULL) {
        if (npts == cap) {
            unsigned long nc = cap ? cap * 2u : 4096u;
            struct sim_out_pt *q = realloc(pts, nc * sizeof *q);
            if (q == NULL) {
                return;
            }
            pts = q;
            cap = nc;
        }
        pts[npts++] = *p;
    }
}

/* ---- the SVG: job facts ---------------------------------------------------------------- */

void sim_out_run_begin(const char *surface, uint32_t points, uint32_t first, int mode, unsigned n,
                       unsigned steps, unsigned link)
{
    struct out_run *r;
    int rapid = nruns > 0u && npts > 0u && first != next_k;
    next_k = first;
    if (nruns == SIM_OUT_RUNS_MAX) {
        return; /* later runs join the last one drawn */
    }
    r = &runs[nruns++];
    r->at = npts;
    r->points = points;
    r->first = first;
    r->mode = mode;
    r->n = n;
    r->steps = steps;
    r->link = link;
    r->rapid_in = rapid;
    snprintf(r->word, sizeof r->word, "%s", surface != NULL ? surface : "?");
    snprintf(r->tol, sizeof r->tol, "%s",
             tol_text[0] ? tol_text : "TOL 1 \xc2\xb5m (chord, default)");
    snprintf(r->tool, sizeof r->tool, "%s", tool_text[0] ? tool_text : "no TOOL: surface points");
}

void sim_out_job_line(const char *line)
{
    char buf[128], *tok[JUDGE_MAX_TOKENS + 1u];
    unsigned nt, i;
    size_t L = strlen(line), o = 0;
    if (L >= sizeof buf) {
        return;
    }
    memcpy(buf, line, L + 1u);
    nt = judge_words(buf, tok, JUDGE_MAX_TOKENS);
    if (nt == 2u && judge_kw(tok[0], "TOL")) {
        snprintf(tol_text, sizeof tol_text, "TOL %.20s \xc2\xb5m (chord)", tok[1]);
    } else if (nt == 2u && judge_kw(tok[0], "STEPS")) {
        snprintf(tol_text, sizeof tol_text, "STEPS %.20s (fixed, no TOL)", tok[1]);
    } else if (nt >= 2u && nt <= 4u && judge_kw(tok[0], "TOOL")) {
        for (i = 0; i < nt && o + 1u < sizeof tool_text; i++) {
            int w = snprintf(tool_text + o, sizeof tool_text - o, "%s%.12s", i ? " " : "", tok[i]);
            o += w > 0 ? (size_t)w : 0u;
        }
    }
    for (o = 0; tool_text[o] != '\0'; o++) { /* plain text in the SVG */
        tool_text[o] = strchr("<>&'\"", tool_text[o]) != NULL ? '?' : tool_text[o];
    }
    for (o = 0; tol_text[o] != '\0'; o++) {
        tol_text[o] = strchr("<>&'\"", tol_text[o]) != NULL ? '?' : tol_text[o];
    }
}

/* ---- the SVG: geometry ------------------------------------------------------------------ */

#define SVG_W 1000
#define SVG_H 660
#define SVG_PY0 96.0 /* plot area of both views: y from here ... */
#define SVG_PH 400.0 /* ... this high */
#define SVG_PW 400.0 /* each view this wide, from SVG_PX0[view] */
static const double SVG_PX0[2] = {70.0, 560.0};
#define SVG_GRID_T 48  /* characteristic circles drawn */
#define SVG_GRID_U 24  /* segments of each */
#define SVG_GRID_C 240 /* segments of C */
#define SVG_FONT "font-family='sans-serif'"

struct box3 {
    double lo[3], hi[3];
};
struct view {
    int iso;
    double umin, vmin, s, ox, oy; /* screen = o + (proj - min) * s */
    double w, h;                  /* the framed data area, px */
    double step;                  /* tick step (top) or axis length (iso), mm */
};

static struct sim_out_pt grid[(SVG_GRID_T + 1) * (SVG_GRID_U + 1) + SVG_GRID_C + 1];
static unsigned long ngrid;

static void pt_mm(const struct sim_out_pt *p, double m[3])
{
    m[0] = p->x / 1e4;
    m[1] = p->y / 1e4;
    m[2] = p->z / 1e4;
}

/* model mm -> view units (v grows downwards); the isometric projection keeps unit
 * length along X, Y and Z */
static void proj(int iso, const double m[3], double *u, double *v)
{
    if (!iso) {
        *u = m[0];
        *v = -m[1];
    } else {
        *u = (m[0] - m[1]) * 0.8660254037844386;
        *v = -((m[0] + m[1]) * 0.5 + m[2]);
    }
}

static void view_map(const struct view *w, const double m[3], double *X, double *Y)
{
    double u, v;
    proj(w->iso, m, &u, &v);
    *X = w->ox + (u - w->umin) * w->s;
    *Y = w->oy + (v - w->vmin) * w->s;
}

/* 1, 2 or 5 times a power of ten, at least range / target */
static double nice_step(double range, double target)
{
    double raw = range / target, p = 1.0;
    if (!(raw > 1e-6)) {
        return 1e-6;
    }
    while (p * 10.0 <= raw) {
        p *= 10.0;
    }
    while (p > raw) {
        p /= 10.0;
    }
    return raw <= p ? p : raw <= 2.0 * p ? 2.0 * p : raw <= 5.0 * p ? 5.0 * p : 10.0 * p;
}

/* v with the decimals a tick step needs (1, 2, 5 times a power of ten), never "-0" */
static const char *fmt_mm(double v, double step, char *buf, size_t bufsz)
{
    int d = 0;
    double q = 0.5;
    while (d < 6 && step < 0.999999) {
        step *= 10.0;
        q /= 10.0;
        d++;
    }
    snprintf(buf, bufsz, "%.*f", d, fabs(v) < q ? 0.0 : v);
    return buf;
}

static void part_box(struct box3 *b)
{
    unsigned long i;
    int a;
    for (a = 0; a < 3; a++) {
        b->lo[a] = 1e300;
        b->hi[a] = -1e300;
    }
    for (i = 0; i < npts; i++) {
        double m[3];
        pt_mm(&pts[i], m);
        for (a = 0; a < 3; a++) {
            b->lo[a] = m[a] < b->lo[a] ? m[a] : b->lo[a];
            b->hi[a] = m[a] > b->hi[a] ? m[a] : b->hi[a];
        }
    }
}

/* 1 if the origin is near enough to the part to be shown in the views */
static int origin_near(const struct box3 *b)
{
    double ext = 0.0, d = 0.0;
    int a;
    for (a = 0; a < 3; a++) {
        double e = b->hi[a] - b->lo[a];
        double o = b->lo[a] > 0.0 ? b->lo[a] : b->hi[a] < 0.0 ? -b->hi[a] : 0.0;
        ext = e > ext ? e : ext;
        d = o > d ? o : d;
    }
    return d <= 0.6 * ext + 1e-9;
}

static void grow(double u, double v, double lim[4])
{
    lim[0] = u < lim[0] ? u : lim[0];
    lim[1] = u > lim[1] ? u : lim[1];
    lim[2] = v < lim[2] ? v : lim[2];
    lim[3] = v > lim[3] ? v : lim[3];
}

/* fit a view: the part, the surface grid, the origin (if near) and, isometric, the axes */
static void view_fit(struct view *w, int iso, const struct box3 *b, int with_origin)
{
    double lim[4] = {1e300, -1e300, 1e300, -1e300}, ext = 0.0, m[3], u, v, pad, du, dv;
    unsigned long i;
    int a, c;
    w->iso = iso;
    for (a = 0; a < 3; a++) {
        ext = b->hi[a] - b->lo[a] > ext ? b->hi[a] - b->lo[a] : ext;
    }
    w->step = iso ? nice_step(ext, 4.0) : 0.0;
    for (c = 0; c < 8; c++) { /* the corners of the part's box */
        m[0] = c & 1 ? b->hi[0] : b->lo[0];
        m[1] = c & 2 ? b->hi[1] : b->lo[1];
        m[2] = c & 4 ? b->hi[2] : b->lo[2];
        proj(iso, m, &u, &v);
        grow(u, v, lim);
    }
    for (i = 0; i < ngrid; i++) {
        pt_mm(&grid[i], m);
        proj(iso, m, &u, &v);
        grow(u, v, lim);
    }
    for (a = -1; a < 3 && with_origin; a++) { /* the origin, and the axes' ends */
        m[0] = m[1] = m[2] = 0.0;
        if (a >= 0 && iso) {
            m[a] = w->step * 1.15;
        }
        proj(iso, m, &u, &v);
        grow(u, v, lim);
    }
    du = lim[1] - lim[0];
    dv = lim[3] - lim[2];
    pad = 0.1 * (du > dv ? du : dv) + 1e-6;
    w->umin = lim[0] - pad;
    w->vmin = lim[2] - pad;
    du += 2.0 * pad;
    dv += 2.0 * pad;
    w->s = SVG_PW / du < SVG_PH / dv ? SVG_PW / du : SVG_PH / dv;
    w->w = du * w->s;
    w->h = dv * w->s;
    w->ox = SVG_PX0[iso] + (SVG_PW - w->w) / 2.0;
    w->oy = SVG_PY0 + (SVG_PH - w->h) / 2.0;
    if (!iso) {
        w->step = nice_step(du > dv ? du : dv, 10.0);
    }
}

/* ---- the SVG: drawing ------------------------------------------------------------------- */

/* the canal surface under the toolpath (the paper's Figures 1-2): characteristic circles
 * (t = const) over the raster's angle range widened by half, and the contact curve C
 * (u = 0), from the canal judge's own model; only for a canal job */
static void grid_build(void)
{
    double ga = 0.0, gb = 0.0, P[3], w;
    int c, q;
    ngrid = 0;
    if (!judge_canal_urange(&ga, &gb)) {
        return;
    }
    w = 0.5 * (gb - ga) + 0.05;
    ga = ga - w < -3.0 ? -3.0 : ga - w;
    gb = gb + w > 3.0 ? 3.0 : gb + w;
    for (c = 0; c <= SVG_GRID_T; c++) { /* circles */
        for (q = 0; q <= SVG_GRID_U; q++) {
            if (!judge_canal_surface((double)c / SVG_GRID_T, ga + (gb - ga) * q / SVG_GRID_U, P)) {
                return;
            }
            grid[ngrid].x = (int32_t)(P[0] * 1e4);
            grid[ngrid].y = (int32_t)(P[1] * 1e4);
            grid[ngrid].z = (int32_t)(P[2] * 1e4);
            grid[ngrid++].line = c;
        }
    }
    for (q = 0; q <= SVG_GRID_C; q++) { /* C itself */
        (void)judge_canal_surface((double)q / SVG_GRID_C, 0.0, P);
        grid[ngrid].x = (int32_t)(P[0] * 1e4);
        grid[ngrid].y = (int32_t)(P[1] * 1e4);
        grid[ngrid].z = (int32_t)(P[2] * 1e4);
        grid[ngrid++].line = -1;
    }
}

static void svg_surface(FILE *f, const struct view *w)
{
    unsigned long i, j;
    for (i = 0; i < ngrid; i = j) {
        fprintf(f, "<polyline fill='none' stroke='%s' stroke-width='0.5' points='",
                grid[i].line < 0 ? "#999" : "#d8d8d8");
        for (j = i; j < ngrid && grid[j].line == grid[i].line; j++) {
            double m[3], X, Y;
            pt_mm(&grid[j], m);
            view_map(w, m, &X, &Y);
            fprintf(f, "%.2f,%.2f ", X, Y);
        }
        fprintf(f, "'/>\n");
    }
}

/* top view: frame, mm grid and ticks with round numbers, axis names, the origin */
static void svg_axes_top(FILE *f, const struct view *w)
{
    double x0 = w->ox, y0 = w->oy, x1 = w->ox + w->w, y1 = w->oy + w->h, t, X, Y, m[3] = {0, 0, 0};
    double ulo = w->umin, uhi = w->umin + w->w / w->s, vlo = w->vmin, vhi = w->vmin + w->h / w->s;
    char b[32];
    fprintf(f,
            "<rect x='%.2f' y='%.2f' width='%.2f' height='%.2f' fill='none' stroke='#444' "
            "stroke-width='0.8'/>\n",
            x0, y0, w->w, w->h);
    for (t = ceil(ulo / w->step) * w->step; t <= uhi + 1e-9; t += w->step) { /* X */
        X = x0 + (t - ulo) * w->s;
        fprintf(f,
                "<line x1='%.2f' y1='%.2f' x2='%.2f' y2='%.2f' stroke='#eee' stroke-width='0.6'/>"
                "<line x1='%.2f' y1='%.2f' x2='%.2f' y2='%.2f' stroke='#444' stroke-width='0.8'/>"
                "<text x='%.2f' y='%.2f' %s font-size='10' text-anchor='middle'>%s</text>\n",
                X, y0, X, y1, X, y1, X, y1 + 5, X, y1 + 16, SVG_FONT,
                fmt_mm(t, w->step, b, sizeof b));
    }
    for (t = ceil(vlo / w->step) * w->step; t <= vhi + 1e-9; t += w->step) { /* Y = -v */
        Y = y0 + (t - vlo) * w->s;
        fprintf(f,
                "<line x1='%.2f' y1='%.2f' x2='%.2f' y2='%.2f' stroke='#eee' stroke-width='0.6'/>"
                "<line x1='%.2f' y1='%.2f' x2='%.2f' y2='%.2f' stroke='#444' stroke-width='0.8'/>"
                "<text x='%.2f' y='%.2f' %s font-size='10' text-anchor='end'>%s</text>\n",
                x0, Y, x1, Y, x0 - 5, Y, x0, Y, x0 - 7, Y + 3.5, SVG_FONT,
                fmt_mm(-t, w->step, b, sizeof b));
    }
    fprintf(f,
            "<text x='%.2f' y='%.2f' %s font-size='11' text-anchor='middle'>X mm</text>\n"
            "<text x='%.2f' y='%.2f' %s font-size='11' text-anchor='middle' transform='rotate(-90 "
            "%.2f %.2f)'>Y mm</text>\n",
            (x0 + x1) / 2, y1 + 30, SVG_FONT, x0 - 44, (y0 + y1) / 2, SVG_FONT, x0 - 44,
            (y0 + y1) / 2);
    view_map(w, m, &X, &Y);
    if (X >= x0 && X <= x1 && Y >= y0 && Y <= y1) {
        fprintf(f,
                "<line x1='%.2f' y1='%.2f' x2='%.2f' y2='%.2f' stroke='#999' stroke-width='0.7'/>"
                "<line x1='%.2f' y1='%.2f' x2='%.2f' y2='%.2f' stroke='#999' stroke-width='0.7'/>\n"
                "<circle cx='%.2f' cy='%.2f' r='4' fill='none' stroke='#000' stroke-width='1'/>"
                "<text x='%.2f' y='%.2f' %s font-size='10' text-anchor='end'>origin</text>\n",
                x0, Y, x1, Y, X, y0, X, y1, X, Y, X - 5, Y + 13, SVG_FONT);
    } else {
        fprintf(f,
                "<text x='%.2f' y='%.2f' %s font-size='10'>origin 0,0 outside this view</text>\n",
                x0 + 4, y0 + 12, SVG_FONT);
    }
}

/* a dimension label on a white ground, centred at x, y (rotated by rot degrees) */
static void svg_dim(FILE *f, double x, double y, int rot, const char *text)
{
    double hw = 3.3 * (double)strlen(text) + 3.0;
    fprintf(f,
            "<g transform='translate(%.2f %.2f) rotate(%d)'><rect x='%.2f' y='-8' width='%.2f' "
            "height='11' fill='white' fill-opacity='0.85'/><text x='0' y='0' %s font-size='11' "
            "text-anchor='middle' fill='#333'>%s</text></g>\n",
            x, y, rot, -hw, 2.0 * hw, SVG_FONT, text);
}

/* top view: the part's extent, dashed, with its width and depth in mm */
static void svg_box_top(FILE *f, const struct view *w, const struct box3 *b)
{
    double lo[3] = {b->lo[0], b->hi[1], 0}, hi[3] = {b->hi[0], b->lo[1], 0}, X0, Y0, X1, Y1;
    char t[48];
    view_map(w, lo, &X0, &Y0);
    view_map(w, hi, &X1, &Y1);
    fprintf(f,
            "<rect x='%.2f' y='%.2f' width='%.2f' height='%.2f' fill='none' stroke='#555' "
            "stroke-width='0.7' stroke-dasharray='2,3'/>\n",
            X0, Y0, X1 - X0, Y1 - Y0);
    snprintf(t, sizeof t, "X %.3f mm", b->hi[0] - b->lo[0]);
    svg_dim(f, (X0 + X1) / 2, Y0 - 5, 0, t);
    snprintf(t, sizeof t, "Y %.3f mm", b->hi[1] - b->lo[1]);
    svg_dim(f, X0 - 5, (Y0 + Y1) / 2, -90, t);
}

/* isometric view: the part's box as a wireframe, the X, Y, Z axes from the origin with
 * their length (the projection keeps lengths along the axes) */
static void svg_axes_iso(FILE *f, const struct view *w, const struct box3 *b, int with_origin)
{
    static const char *const name[3] = {"X", "Y", "Z"};
    double m0[3], m1[3], X0, Y0, X1, Y1;
    char buf[32];
    int e, a;
    for (e = 0; e < 12; e++) { /* edge e: along axis e / 4, at corner bits e % 4 */
        int ax = e / 4, o1 = (ax + 1) % 3, o2 = (ax + 2) % 3;
        m0[ax] = b->lo[ax];
        m1[ax] = b->hi[ax];
        m0[o1] = m1[o1] = e & 1 ? b->hi[o1] : b->lo[o1];
        m0[o2] = m1[o2] = e & 2 ? b->hi[o2] : b->lo[o2];
        view_map(w, m0, &X0, &Y0);
        view_map(w, m1, &X1, &Y1);
        fprintf(f,
                "<line x1='%.2f' y1='%.2f' x2='%.2f' y2='%.2f' stroke='#999' stroke-width='0.6' "
                "stroke-dasharray='2,3'/>\n",
                X0, Y0, X1, Y1);
    }
    if (!with_origin) {
        fprintf(f,
                "<text x='%.2f' y='%.2f' %s font-size='10'>origin 0,0,0 outside this view</text>\n",
                SVG_PX0[1], SVG_PY0 + 12, SVG_FONT);
        return;
    }
    m0[0] = m0[1] = m0[2] = 0.0;
    view_map(w, m0, &X0, &Y0);
    for (a = 0; a < 3; a++) {
        m1[0] = m1[1] = m1[2] = 0.0;
        m1[a] = w->step;
        view_map(w, m1, &X1, &Y1);
        fprintf(f,
                "<line x1='%.2f' y1='%.2f' x2='%.2f' y2='%.2f' stroke='#000' stroke-width='1.2'/>"
                "<text x='%.2f' y='%.2f' %s font-size='11' font-weight='bold' text-anchor='middle'>"
                "%s</text>\n",
                X0, Y0, X1, Y1, X0 + (X1 - X0) * 1.12, Y0 + (Y1 - Y0) * 1.12 + 4, SVG_FONT,
                name[a]);
    }
    fprintf(
        f,
        "<circle cx='%.2f' cy='%.2f' r='4' fill='none' stroke='#000' stroke-width='1'/>"
        "<text x='%.2f' y='%.2f' %s font-size='10' text-anchor='end'>origin; axes %s mm</text>\n",
        X0, Y0, X0 - 6, Y0 + 14, SVG_FONT, fmt_mm(w->step, w->step, buf, sizeof buf));
}

enum seg { SEG_F2, SEG_F1, SEG_LINK, SEG_RAPID, SEG_N };
static const char *const seg_style[SEG_N] = {
    "stroke='#1f5fbf' stroke-width='1'",
    "stroke='#1a9641' stroke-width='1'",
    "stroke='#f08c00' stroke-width='0.7' stroke-dasharray='3,2'",
    "stroke='#d7191c' stroke-width='1' stroke-dasharray='7,4'",
};
static unsigned long seg_count[SEG_N];

/* the move into point i (i >= 1) of run r */
static enum seg seg_of(unsigned long i, unsigned r)
{
    if (r < nruns && i == runs[r].at && runs[r].rapid_in) {
        return SEG_RAPID;
    }
    if (pts[i].line >= 0 && pts[i].line == pts[i - 1].line) {
        return r < nruns && runs[r].mode == 1 ? SEG_F1 : SEG_F2;
    }
    return SEG_LINK;
}

/* the toolpath: one polyline per stretch of moves of one kind */
static void svg_path(FILE *f, const struct view *w)
{
    unsigned long i, j;
    unsigned r = 0;
    double m[3], X, Y;
    for (i = 1; i < npts; i = j) {
        enum seg k;
        while (r + 1u < nruns && i >= runs[r + 1u].at) {
            r++;
        }
        k = seg_of(i, r);
        fprintf(f, "<polyline fill='none' stroke-linejoin='round' %s points='", seg_style[k]);
        pt_mm(&pts[i - 1], m);
        view_map(w, m, &X, &Y);
        fprintf(f, "%.2f,%.2f", X, Y);
        for (j = i; j < npts; j++) {
            unsigned rj = r;
            while (rj + 1u < nruns && j >= runs[rj + 1u].at) {
                rj++;
            }
            if (seg_of(j, rj) != k) {
                break;
            }
            pt_mm(&pts[j], m);
            view_map(w, m, &X, &Y);
            fprintf(f, " %.2f,%.2f", X, Y);
            if (!w->iso) {
                seg_count[k]++;
            }
        }
        fprintf(f, "'/>\n");
    }
}

/* the start point (first point streamed) and the end point */
static void svg_marks(FILE *f, const struct view *w)
{
    double m[3], X, Y;
    pt_mm(&pts[npts - 1u], m);
    view_map(w, m, &X, &Y);
    fprintf(f,
            "<rect x='%.2f' y='%.2f' width='7' height='7' fill='white' stroke='#000' "
            "stroke-width='1.2'/>\n",
            X - 3.5, Y - 3.5);
    pt_mm(&pts[0], m);
    view_map(w, m, &X, &Y);
    fprintf(f,
            "<circle cx='%.2f' cy='%.2f' r='5' fill='#ffd400' stroke='#000' stroke-width='1.2'/>"
            "<text x='%.2f' y='%.2f' %s font-size='11' font-weight='bold'>start</text>\n",
            X, Y, X + 7, Y - 6, SVG_FONT);
}
/* what the model calls its families */
static const char *family_name(int mode)
{
    int canal = nruns > 0u && strcmp(runs[0].word, "CANAL") == 0;
    if (mode == 1) {
        return canal ? "characteristic circles" : "section rings";
    }
    return canal ? "curvature lines" : "lines along the surface";
}

static unsigned long run_received(unsigned r)
{
    return (r + 1u < nruns ? runs[r + 1u].at : npts) - runs[r].at;
}

/* "LINES n=8, steps=514, link=0, 4117 points" of run r */
static void run_text(unsigned r, char *buf, size_t bufsz)
{
    const struct out_run *u = &runs[r];
    unsigned long got = run_received(r), want = u->points - u->first;
    int o = snprintf(buf, bufsz, "%s n=%u, steps=%u, link=%u, %lu points",
                     u->mode ? "CIRCLES" : "LINES", u->n, u->steps, u->link, got);
    if (o > 0 && (size_t)o < bufsz && got != want) {
        o += snprintf(buf + o, bufsz - (size_t)o, " of %lu", want);
    }
    if (o > 0 && (size_t)o < bufsz && u->first != 0u) {
        snprintf(buf + o, bufsz - (size_t)o, " (RESUME %lu)", (unsigned long)u->first);
    }
}

/* the caption: the job's model, mode, n, steps, points, tolerance, tool, extent */
static void svg_caption(FILE *f, const struct box3 *b)
{
    char line[640], rt[128];
    unsigned r, st = 1, su = 1; /* the same TOL/STEPS, the same TOOL in every run */
    int o = snprintf(line, sizeof line, "SURFACE %s", runs[0].word);
    for (r = 1; r < nruns; r++) {
        if (strcmp(runs[r].word, runs[r - 1u].word) != 0 && o > 0 && (size_t)o < sizeof line) {
            o += snprintf(line + o, sizeof line - (size_t)o, ", then %s", runs[r].word);
        }
        st = st && strcmp(runs[r].tol, runs[0].tol) == 0;
        su = su && strcmp(runs[r].tool, runs[0].tool) == 0;
    }
    run_text(0, rt, sizeof rt);
    if (nruns == 1u) {
        snprintf(line + o, sizeof line - (size_t)o, " \xe2\x80\x94 %s", rt);
    } else {
        snprintf(line + o, sizeof line - (size_t)o, " \xe2\x80\x94 %u runs, %lu points", nruns,
                 npts);
    }
    fprintf(f, "<text x='20' y='24' %s font-size='16' font-weight='bold'>%s</text>\n", SVG_FONT,
            line);
    fprintf(
        f,
        "<text x='20' y='44' %s font-size='12'>%s \xc2\xb7 %s \xc2\xb7 part extent X %.3f \xc3\x97 "
        "Y %.3f \xc3\x97 Z %.3f mm (X %.3f..%.3f, Y %.3f..%.3f, Z %.3f..%.3f)</text>\n",
        SVG_FONT, st ? runs[0].tol : "TOL/STEPS per run", su ? runs[0].tool : "TOOL per run",
        b->hi[0] - b->lo[0], b->hi[1] - b->lo[1], b->hi[2] - b->lo[2], b->lo[0], b->hi[0], b->lo[1],
        b->hi[1], b->lo[2], b->hi[2]);
    for (r = 0, o = 0; r < nruns && nruns > 1u && o < 150; r++) {
        run_text(r, rt, sizeof rt);
        o +=
            snprintf(line + o, sizeof line - (size_t)o, "%srun %u: %s%s%s%s%s%s",
                     r ? " \xc2\xb7 " : "", r + 1u, rt, runs[r].rapid_in ? " (rapid in)" : "",
                     st ? "" : ", ", st ? "" : runs[r].tol, su ? "" : ", ", su ? "" : runs[r].tool);
    }
    if (r < nruns) {
        snprintf(line + o, sizeof line - (size_t)o, " \xc2\xb7 %u more", nruns - r);
    }
    if (nruns > 1u) {
        fprintf(f, "<text x='20' y='62' %s font-size='11'>%s</text>\n", SVG_FONT, line);
    }
}

static void legend_row(FILE *f, double x, double y, const char *swatch, const char *text)
{
    fprintf(f, "%s<text x='%.1f' y='%.1f' %s font-size='12'>%s</text>\n", swatch, x + 34, y + 4,
            SVG_FONT, text);
}

static void svg_legend(FILE *f, int surface)
{
    static const char *const what[SEG_N] = {"family 2", "family 1", "link moves", "rapid moves"};
    char sw[256], tx[160];
    double x = 70.0, y = 556.0;
    int k;
    for (k = 0; k < SEG_N; k++) {
        if (seg_count[k] == 0u && k != SEG_LINK) {
            continue;
        }
        snprintf(sw, sizeof sw, "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' %s/>", x, y, x + 26,
                 y, seg_style[k]);
        if (k <= SEG_F1) {
            snprintf(tx, sizeof tx, "%s: %s (%s, line \xe2\x89\xa5 0), %lu moves", what[k],
                     family_name(k == SEG_F1), k == SEG_F1 ? "CIRCLES" : "LINES", seg_count[k]);
        } else if (k == SEG_LINK) {
            snprintf(tx, sizeof tx,
                     "%s (line \xe2\x88\x92"
                     "1 and between lines, at feed), %lu moves",
                     what[k], seg_count[k]);
        } else {
            snprintf(tx, sizeof tx, "%s between runs (not streamed: the machine's own travel), %lu",
                     what[k], seg_count[k]);
        }
        legend_row(f, x, y, sw, tx);
        y += 18.0;
    }
    x = 560.0;
    y = 556.0;
    snprintf(sw, sizeof sw,
             "<circle cx='%.1f' cy='%.1f' r='5' fill='#ffd400' stroke='#000' "
             "stroke-width='1.2'/><rect x='%.1f' y='%.1f' width='7' height='7' "
             "fill='white' stroke='#000' stroke-width='1.2'/>",
             x + 6, y, x + 17, y - 3.5);
    legend_row(f, x, y, sw, "start (first point streamed), end (last point)");
    snprintf(sw, sizeof sw,
             "<rect x='%.1f' y='%.1f' width='26' height='8' fill='none' stroke='#555' "
             "stroke-width='0.7' stroke-dasharray='2,3'/>",
             x, y + 14);
    legend_row(f, x, y + 18, sw, "part extent: the points' bounding box, mm");
    snprintf(sw, sizeof sw, "<circle cx='%.1f' cy='%.1f' r='4' fill='none' stroke='#000'/>", x + 13,
             y + 36);
    legend_row(f, x, y + 36, sw, "origin (0, 0, 0) of the job's coordinates");
    if (surface) {
        snprintf(sw, sizeof sw, "<line x1='%.1f' y1='%.1f' x2='%.1f' y2='%.1f' stroke='#999'/>", x,
                 y + 54, x + 26, y + 54);
        legend_row(f, x, y + 54, sw, "canal surface (judge's model): circles, C darker");
    }
}

static void svg_write(const char *path)
{
    static const char *const title[2] = {"top view (looking down Z), to scale",
                                         "isometric view, lengths true along X, Y, Z"};
    struct box3 b;
    struct view w;
    unsigned r;
    int view, near, canal = nruns > 0u;
    FILE *f = fopen(path, "w");
    if (f == NULL) {
        perror(path);
        return;
    }
    fprintf(f,
            "<?xml version='1.0' encoding='UTF-8'?>\n<svg xmlns='http://www.w3.org/2000/svg' "
            "version='1.1' width='%d' height='%d' viewBox='0 0 %d %d'>\n<title>host_sim toolpath"
            "</title>\n<rect width='%d' height='%d' fill='white'/>\n",
            SVG_W, SVG_H, SVG_W, SVG_H, SVG_W, SVG_H);
    if (npts < 2u || nruns == 0u) {
        fprintf(f,
                "<text x='20' y='40' %s font-size='16'>%lu points received%s: no toolpath drawn"
                "</text>\n</svg>\n",
                SVG_FONT, npts, nruns == 0u && npts > 0u ? " without a run header" : "");
        fclose(f);
        return;
    }
    for (r = 0; r < nruns; r++) {
        canal = canal && strcmp(runs[r].word, "CANAL") == 0;
    }
    ngrid = 0;
    if (canal) {
        grid_build();
    }
    part_box(&b);
    near = origin_near(&b);
    svg_caption(f, &b);
    memset(seg_count, 0, sizeof seg_count);
    for (view = 0; view < 2; view++) {
        view_fit(&w, view, &b, near);
        fprintf(f, "<text x='%.1f' y='84' %s font-size='13' fill='#333'>%s</text>\n",
                SVG_PX0[view] - 50, SVG_FONT, title[view]);
        svg_surface(f, &w);
        if (!view) {
            svg_axes_top(f, &w);
            svg_box_top(f, &w, &b);
        } else {
            svg_axes_iso(f, &w, &b, near);
        }
        svg_path(f, &w);
        svg_marks(f, &w);
    }
    svg_legend(f, ngrid > 0u);
    fprintf(f,
            "<text x='20' y='%d' %s font-size='10' fill='#555'>the points as the firmware streamed "
            "them and host_sim received them intact (a TOOL BALL job: the tool tip, or its centre "
            "with CENTRE; no TOOL: surface points); Z up, mm</text>\n</svg>\n",
            SVG_H - 12, SVG_FONT);
    fclose(f);
}
unsigned long sim_out_close(void)
{
    if (out_csv != NULL) {
        fclose(out_csv);
        out_csv = NULL;
    }
    if (out_gc != NULL) {
        gc_pre();
        fputs("M2\n", out_gc);
        fclose(out_gc);
        out_gc = NULL;
    }
    if (out_svg_path != NULL) {
        svg_write(out_svg_path);
        out_svg_path = NULL;
    }
    free(pts);
    pts = NULL;
    nruns = 0;
    cap = 0;
    npts = 0;
    return nwritten;
}
