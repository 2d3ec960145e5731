/* sim_job.c - job files of host_sim.
 * SPDX-License-Identifier: MIT
 */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sim_job.h"

static int job_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

/* Parse the text after "#!" into c->expect / c->code. Returns 0 or -1. */
static int job_directive(const char *d, struct sim_job_cmd *c)
{
    char *end;
    long v;
    while (job_blank(*d)) {
        d++;
    }
    if (strncmp(d, "expect", 6) != 0 || !job_blank(d[6])) {
        return -1;
    }
    d += 6;
    while (job_blank(*d)) {
        d++;
    }
    if (strncmp(d, "ok", 2) == 0) {
        c->expect = SIM_JOB_EXPECT_OK;
        d += 2;
    } else if (strncmp(d, "error:", 6) == 0 && d[6] >= '0' && d[6] <= '9') {
        errno = 0;
        v = strtol(d + 6, &end, 10);
        if (errno != 0 || v < 1 || v > 255) {
            return -1;
        }
        c->expect = SIM_JOB_EXPECT_ERROR;
        c->code = (int)v;
        d = end;
    } else {
        return -1;
    }
    while (job_blank(*d)) {
        d++;
    }
    return *d == '\0' ? 0 : -1;
}

int sim_job_load(struct sim_job *j, const char *path, char *err, size_t errcap)
{
    static char buf[SIM_JOB_LINE_MAX + 2];
    FILE *f = fopen(path, "r");
    size_t cap = 0;
    int lineno = 0;
    j->cmd = NULL;
    j->n = 0;
    if (f == NULL) {
        snprintf(err, errcap, "%s: %s", path, strerror(errno));
        return -1;
    }
    while (fgets(buf, sizeof buf, f) != NULL) {
        struct sim_job_cmd c;
        char *hash, *a, *b;
        size_t len = strlen(buf);
        lineno++;
        if (len == sizeof buf - 1 && buf[len - 1] != '\n') {
            snprintf(err, errcap, "%s:%d: line longer than %d bytes", path, lineno,
                     SIM_JOB_LINE_MAX);
            goto fail;
        }
        c.expect = SIM_JOB_EXPECT_NONE;
        c.code = 0;
        c.lineno = lineno;
        hash = strchr(buf, '#');
        if (hash != NULL) {
            if (hash[1] == '!' && job_directive(hash + 2, &c) != 0) {
                snprintf(err, errcap, "%s:%d: bad directive (want '#! expect ok' or "
                         "'#! expect error:N')", path, lineno);
                goto fail;
            }
            *hash = '\0';
        }
        for (a = buf; job_blank(*a); a++) {
        }
        for (b = a + strlen(a); b > a && job_blank(b[-1]); b--) {
        }
        *b = '\0';
        if (*a == '\0' && c.expect == SIM_JOB_EXPECT_NONE) {
            continue; /* blank or comment */
        }
        if (strpbrk(a, "\r\n") != NULL) {
            snprintf(err, errcap, "%s:%d: stray line terminator", path, lineno);
            goto fail;
        }
        if (j->n == SIM_JOB_MAX) {
            snprintf(err, errcap, "%s:%d: more than %d commands", path, lineno, SIM_JOB_MAX);
            goto fail;
        }
        if (j->n == cap) {
            size_t ncap = cap ? cap * 2u : 64u;
            struct sim_job_cmd *p = realloc(j->cmd, ncap * sizeof *p);
            if (p == NULL) {
                snprintf(err, errcap, "%s: out of memory", path);
                goto fail;
            }
            j->cmd = p;
            cap = ncap;
        }
        c.len = (size_t)(b - a);
        c.text = malloc(c.len + 1u);
        if (c.text == NULL) {
            snprintf(err, errcap, "%s: out of memory", path);
            goto fail;
        }
        memcpy(c.text, a, c.len + 1u);
        j->cmd[j->n++] = c;
    }
    if (ferror(f)) {
        snprintf(err, errcap, "%s: read error", path);
        goto fail;
    }
    fclose(f);
    return 0;
fail:
    fclose(f);
    sim_job_free(j);
    return -1;
}

void sim_job_free(struct sim_job *j)
{
    size_t i;
    for (i = 0; i < j->n; i++) {
        free(j->cmd[i].text);
    }
    free(j->cmd);
    j->cmd = NULL;
    j->n = 0;
}
