/* canal_demo.c - host demo: stream two fillets through the firmware toolpath iterator,
 * write CSV and an SVG (top and isometric views, like the paper's Figures 1-2), and
 * print a summary (points, step counts, measured residuals).
 * SPDX-License-Identifier: MIT
 *
 * Usage: canal_demo OUTDIR
 */
#include <stdio.h>
#include <string.h>

#include "canal_path.h"

struct job {
    const char *name;
    const char *title;
    struct raster_cfg cfg;
    struct canal_cfg surf;
};

struct view {
    double x0, y0, scale, ox, oy; /* model -> svg */
};

static void project(int iso, double x, double y, double z, double *px, double *py)
{
    if (!iso) {
        *px = x;
        *py = -y;
    } else {
        /* isometric: rotate 45 deg about z, tilt 35.26 deg */
        double u = (x - y) * 0.70710678, v = (x + y) * 0.40824829 - z * 0.81649658;
        *px = u;
        *py = v;
    }
}

static int run(const struct job *jb, const char *dir)
{
    static struct canal_path tp;
    struct raster_pt pt;
    char path[512];
    FILE *csv, *svg;
    double minx[2] = {1e30, 1e30}, maxx[2] = {-1e30, -1e30}, miny[2] = {1e30, 1e30},
           maxy[2] = {-1e30, -1e30};
    double worst_r = 0.0;
    int err, iso, last_line = -2;
    uint32_t k;
    err = canal_path_init(&tp, &jb->surf, &jb->cfg);
    if (err != CP_OK) {
        fprintf(stderr, "%s: canal_path_init failed: %d\n", jb->name, err);
        return 1;
    }
    snprintf(path, sizeof path, "%s/%s.csv", dir, jb->name);
    csv = fopen(path, "w");
    if (csv == NULL) {
        perror(path);
        return 1;
    }
    fprintf(csv, "line,index,x,y,z,nx,ny,nz\n");
    for (k = 0; canal_path_next(&tp, &pt) == CP_OK; k++) {
        struct canal_jet j;
        double ex, ey, ez, r;
        fprintf(csv, "%d,%u,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f\n", pt.line, pt.index, (double)pt.p.x,
                (double)pt.p.y, (double)pt.p.z, (double)pt.n.x, (double)pt.n.y, (double)pt.n.z);
        for (iso = 0; iso < 2; iso++) {
            double px, py;
            project(iso, pt.p.x, pt.p.y, pt.p.z, &px, &py);
            minx[iso] = px < minx[iso] ? px : minx[iso];
            maxx[iso] = px > maxx[iso] ? px : maxx[iso];
            miny[iso] = py < miny[iso] ? py : miny[iso];
            maxy[iso] = py > maxy[iso] ? py : maxy[iso];
        }
        canal_jet(&tp.surf, pt.t, &j);
        ex = (double)pt.p.x - (double)j.x;
        ey = (double)pt.p.y - (double)j.y;
        /* tool centre (tip + r z) lies on the sphere of radius R - r_tool */
        ez = (double)pt.p.z - (double)j.r +
             (jb->cfg.output == RASTER_OUT_TIP ? (double)jb->cfg.tool_r : 0.0);
        r = sqrt(ex * ex + ey * ey + ez * ez) - ((double)j.r - (double)jb->cfg.tool_r);
        worst_r = fabs(r) > worst_r ? fabs(r) : worst_r;
    }
    fclose(csv);
    /* SVG: two panels side by side, 480 x 480 each */
    snprintf(path, sizeof path, "%s/%s.svg", dir, jb->name);
    svg = fopen(path, "w");
    if (svg == NULL) {
        perror(path);
        return 1;
    }
    fprintf(svg, "<svg xmlns='http://www.w3.org/2000/svg' width='980' height='540' "
                 "font-family='sans-serif' font-size='13'>\n<rect width='980' height='540' "
                 "fill='white'/>\n<text x='10' y='20'>%s: %u points (top view | isometric view)"
                 "</text>\n",
            jb->title, (unsigned)canal_path_count(&tp));
    for (iso = 0; iso < 2; iso++) {
        double w = maxx[iso] - minx[iso], h = maxy[iso] - miny[iso];
        double sc = 460.0 / (w > h ? w : h);
        double ox = 10.0 + iso * 490.0, oy = 40.0;
        int open = 0;
        if (canal_path_seek(&tp, 0) != CP_OK) {
            fclose(svg);
            return 1;
        }
        last_line = -2;
        while (canal_path_next(&tp, &pt) == CP_OK) {
            double px, py;
            project(iso, pt.p.x, pt.p.y, pt.p.z, &px, &py);
            px = ox + (px - minx[iso]) * sc;
            py = oy + (py - miny[iso]) * sc;
            if (pt.line != last_line) {
                if (open) {
                    fprintf(svg, "'/>\n");
                }
                fprintf(svg, "<polyline fill='none' stroke='%s' stroke-width='%s' points='",
                        pt.line < 0 ? "#d33" : (pt.line & 1 ? "#236" : "#28a"),
                        pt.line < 0 ? "1.2" : "0.8");
                open = 1;
                last_line = pt.line;
            }
            fprintf(svg, "%.2f,%.2f ", px, py);
        }
        if (open) {
            fprintf(svg, "'/>\n");
        }
    }
    fprintf(svg, "</svg>\n");
    fclose(svg);
    printf("%-8s %-52s points %6u  steps %4u  substeps %2u  link %2u  sphere residual %.2g mm\n",
           jb->name, jb->title, (unsigned)k, tp.head.steps, tp.substeps, tp.head.link, worst_r);
    return 0;
}

int main(int argc, char **argv)
{
    static struct job jobs[2];
    const char *dir = argc > 1 ? argv[1] : ".";
    int i, fails = 0;
    memset(jobs, 0, sizeof jobs);
    /* the paper's example: circle r = 3, R = 5.5 cos 2t + 10.5, regular band */
    jobs[0].name = "paper";
    jobs[0].title = "Frolov 2022 example, R = 5.5 cos 2t + 10.5, tol 2 um";
    jobs[0].surf.curve = CANAL_ARC;
    jobs[0].surf.radius = CANAL_R_COS;
    jobs[0].surf.cp[2] = CP_R(3.0);
    jobs[0].surf.cp[4] = CP_TWO_PI;
    jobs[0].surf.rp[0] = CP_R(5.5);
    jobs[0].surf.rp[1] = CP_R(10.5);
    jobs[0].surf.rp[2] = CP_R(2.0);
    jobs[0].cfg.mode = RASTER_LINES;
    jobs[0].cfg.n = 12;
    jobs[0].cfg.u0 = CP_R(-0.5);
    jobs[0].cfg.u1 = CP_R(0.18);
    jobs[0].cfg.tol = CP_R(0.002);
    jobs[0].cfg.link = RASTER_LINK_AUTO;
    /* a realistic fillet: variable radius 3..5 mm around a 50 mm boss, ball tool 2 mm */
    jobs[1] = jobs[0];
    jobs[1].name = "boss";
    jobs[1].title = "fillet around a boss, R = 4 + cos 3t mm, ball 2 mm tip";
    jobs[1].surf.cp[2] = CP_R(25.0);
    jobs[1].surf.rp[0] = CP_R(1.0);
    jobs[1].surf.rp[1] = CP_R(4.0);
    jobs[1].surf.rp[2] = CP_R(3.0);
    jobs[1].cfg.n = 10;
    jobs[1].cfg.u0 = CP_R(0.0);
    jobs[1].cfg.u1 = CP_R(1.5);
    jobs[1].cfg.tol = CP_R(0.005);
    jobs[1].cfg.output = RASTER_OUT_TIP;
    jobs[1].cfg.tool_r = CP_R(2.0);
    for (i = 0; i < 2; i++) {
        fails += run(&jobs[i], dir);
    }
    printf("demo: wrote %s/{paper,boss}.{csv,svg}\n", dir);
    return fails != 0;
}
