/* judge_util.c - helpers shared by the judges and sim_check.c (judge.h).
 * SPDX-License-Identifier: MIT
 */
#include "judge.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

int judge_split(const char *line, char *buf, size_t bufsz, char **tok)
{
    char *p;
    int nt = 0;
    size_t n = strlen(line);
    if (n >= bufsz) {
        return -1;
    }
    memcpy(buf, line, n + 1u);
    for (p = strtok(buf, " \t\r\n"); p != NULL && nt < (int)JUDGE_MAX_TOKENS;
         p = strtok(NULL, " \t\r\n")) {
        if (p[0] == '#') {
            break;
        }
        tok[nt++] = p;
    }
    return nt;
}

unsigned judge_words(char *buf, char **tok, unsigned max)
{
    char *p = buf;
    unsigned nt = 0;
    while (*p) {
        while (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\n') {
            *p++ = '\0';
        }
        if (*p == '\0') {
            break;
        }
        if (nt <= max) {
            tok[nt] = p;
        }
        nt++;
        while (*p && *p != ' ' && *p != '\t' && *p != '\r' && *p != '\n') {
            p++;
        }
    }
    return nt;
}

int judge_kw(const char *a, const char *b)
{
    return strcasecmp(a, b) == 0;
}

int judge_nums(char **tok, unsigned first, unsigned n, double *v)
{
    unsigned i;
    for (i = 0; i < n; i++) {
        char *e;
        v[i] = strtod(tok[first + i], &e);
        if (*e != '\0' || !isfinite(v[i])) {
            return 1;
        }
    }
    return 0;
}

double judge_angle_deg(const double *a, const double *b)
{
    double c[3], s, d;
    c[0] = a[1] * b[2] - a[2] * b[1];
    c[1] = a[2] * b[0] - a[0] * b[2];
    c[2] = a[0] * b[1] - a[1] * b[0];
    s = sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    return atan2(s, d) * (180.0 / 3.14159265358979323846);
}

void judge_stat_add(struct judge_stat *s, double v, double lim, uint32_t k)
{
    if (s->n == 0ul || v > s->max || v != v) {
        s->max = v;
        s->worst = k;
    }
    s->sum2 += v * v;
    s->n++;
    if (lim > 0.0 && !(v <= lim)) {
        s->fails++;
    }
}

void judge_stat_row(FILE *f, int *passed, int *failed, const char *model, const char *name,
                    const struct judge_stat *s, double lim, const char *unit, int counted)
{
    double rms = s->n ? sqrt(s->sum2 / (double)s->n) : 0.0;
    int ok = s->fails == 0ul;
    if (!counted || s->n == 0ul) {
        fprintf(f, "  INFO judge %s-%-7s max %.3e %s rms %.3e %s n=%lu (not counted)\n", model,
                name, s->max, unit, rms, unit, s->n);
        return;
    }
    (*(ok ? passed : failed))++;
    fprintf(f, "  %s judge %s-%-7s max %.3e %s rms %.3e %s limit %.1e %s n=%lu worst k=%lu%s\n",
            ok ? "PASS" : "FAIL", model, name, s->max, unit, rms, unit, lim, unit, s->n,
            (unsigned long)s->worst, s->fails ? " OVER THE LIMIT" : "");
}
