/* sim_out.c - CSV, G-code and SVG writers of host_sim.
 * SPDX-License-Identifier: MIT
 */
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
    if (strncmp(body, "G21", 3) == 0) {
        gc_pre();
        return;
    }
    gc_pre();
    fprintf(out_gc, "%s\n", body);
}

void sim_out_point(const struct sim_out_pt *p)
{
    char a[24], b[24], c[24];
    nwritten++;
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

/* the two projections, model mm -> view units */
static void proj(int view, const struct sim_out_pt *p, double *u, double *v)
{
    double x = p->x / 1e4, y = p->y / 1e4, z = p->z / 1e4;
    if (view == 0) {
        *u = x;
        *v = -y;
    } else {
        *u = (x - y) * 0.8660254037844386;
        *v = -((x + y) * 0.5 + z);
    }
}

#define SVG_GRID_T 48 /* characteristic circles drawn */
#define SVG_GRID_U 24 /* segments of each */
#define SVG_GRID_C 240 /* segments of C */

static void svg_write(const char *path)
{
    static struct sim_out_pt grid[(SVG_GRID_T + 1) * (SVG_GRID_U + 1) + SVG_GRID_C + 1];
    unsigned long ngrid;
    double ga = 0.0, gb = 0.0;
    FILE *f = fopen(path, "w");
    int view;
    unsigned long i;
    if (f == NULL) {
        perror(path);
        return;
    }
    fprintf(f, "<svg xmlns='http://www.w3.org/2000/svg' width='980' height='540' "
               "viewBox='0 0 980 540'>\n<rect width='980' height='540' fill='white'/>\n");
    fprintf(f, "<text x='20' y='24' font-family='sans-serif' font-size='14'>top view</text>\n"
               "<text x='510' y='24' font-family='sans-serif' font-size='14'>isometric view"
               "</text>\n<text x='20' y='530' font-family='sans-serif' font-size='11'>"
               "%lu points; curvature lines in blues, link moves red; the surface in grey "
               "(characteristic circles, and C darker)</text>\n", npts);
    /* the surface under the toolpath (the paper's Figures 1-2): characteristic circles
     * (t = const) over the raster's angle range widened by half, and the contact
     * curve C (u = 0), from the judge's own model; drawn faint, behind the path */
    ngrid = 0;
    if (judge_canal_urange(&ga, &gb)) {
        double w = 0.5 * (gb - ga) + 0.05;
        int c, q;
        ga = ga - w < -3.0 ? -3.0 : ga - w;
        gb = gb + w > 3.0 ? 3.0 : gb + w;
        for (c = 0; c <= SVG_GRID_T; c++) { /* circles */
            for (q = 0; q <= SVG_GRID_U; q++) {
                double P[3];
                if (!judge_canal_surface((double)c / SVG_GRID_T, ga + (gb - ga) * q / SVG_GRID_U, P)) {
                    break;
                }
                grid[ngrid].x = (int32_t)(P[0] * 1e4);
                grid[ngrid].y = (int32_t)(P[1] * 1e4);
                grid[ngrid].z = (int32_t)(P[2] * 1e4);
                grid[ngrid++].line = c;
            }
        }
        for (q = 0; q <= SVG_GRID_C && ngrid > 0; q++) { /* C itself */
            double P[3];
            (void)judge_canal_surface((double)q / SVG_GRID_C, 0.0, P);
            grid[ngrid].x = (int32_t)(P[0] * 1e4);
            grid[ngrid].y = (int32_t)(P[1] * 1e4);
            grid[ngrid].z = (int32_t)(P[2] * 1e4);
            grid[ngrid++].line = -1;
        }
    }
    for (view = 0; view < 2; view++) {
        double umin = 1e300, umax = -1e300, vmin = 1e300, vmax = -1e300, s, ox, oy;
        int32_t maxline = 1;
        for (i = 0; i < npts; i++) {
            double u, v;
            proj(view, &pts[i], &u, &v);
            umin = u < umin ? u : umin;
            umax = u > umax ? u : umax;
            vmin = v < vmin ? v : vmin;
            vmax = v > vmax ? v : vmax;
            maxline = pts[i].line > maxline ? pts[i].line : maxline;
        }
        if (npts == 0) {
            break;
        }
        for (i = 0; i < ngrid; i++) {
            double u, v;
            proj(view, &grid[i], &u, &v);
            umin = u < umin ? u : umin;
            umax = u > umax ? u : umax;
            vmin = v < vmin ? v : vmin;
            vmax = v > vmax ? v : vmax;
        }
        s = 460.0 / ((umax - umin > vmax - vmin ? umax - umin : vmax - vmin) + 1e-9);
        ox = 10.0 + view * 490.0 + (470.0 - (umax - umin) * s) / 2.0;
        oy = 40.0 + (470.0 - (vmax - vmin) * s) / 2.0;
        for (i = 0; i < ngrid;) {
            unsigned long j = i;
            fprintf(f, "<polyline fill='none' stroke='%s' stroke-width='0.5' points='",
                    grid[i].line < 0 ? "#888" : "#ccc");
            for (; j < ngrid && grid[j].line == grid[i].line; j++) {
                double u, v;
                proj(view, &grid[j], &u, &v);
                fprintf(f, "%.2f,%.2f ", ox + (u - umin) * s, oy + (v - vmin) * s);
            }
            fprintf(f, "'/>\n");
            i = j;
        }
        for (i = 0; i < npts;) {
            unsigned long j = i;
            int32_t ln = pts[i].line;
            const char *col;
            char blue[48];
            while (j < npts && pts[j].line == ln) {
                j++;
            }
            if (ln < 0) {
                col = "#d62728";
            } else {
                int t = (int)(ln * 160 / maxline) & 255;
                snprintf(blue, sizeof blue, "rgb(%d,%d,%d)", 20 + t / 4, 60 + t / 2, 150 + t / 2);
                col = blue;
            }
            fprintf(f, "<polyline fill='none' stroke='%s' stroke-width='%s' points='", col,
                    ln < 0 ? "0.6" : "0.9");
            /* include the previous point so the polylines join */
            for (j = i > 0 ? i - 1 : i; j < npts && (j < i || pts[j].line == ln); j++) {
                double u, v;
                proj(view, &pts[j], &u, &v);
                fprintf(f, "%.2f,%.2f ", ox + (u - umin) * s, oy + (v - vmin) * s);
            }
            fprintf(f, "'/>\n");
            i = j;
        }
    }
    fprintf(f, "</svg>\n");
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
    cap = 0;
    npts = 0;
    return nwritten;
}
