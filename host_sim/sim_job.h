/* sim_job.h - job files of host_sim: one protocol command per line.
 * SPDX-License-Identifier: MIT
 *
 * Syntax (docs/HOST_SIM.md):
 *   # comment                     whole-line comment; blank lines are skipped
 *   CMD ARGS                      sent as "CMD ARGS\n" (leading/trailing blanks removed)
 *   CMD ARGS   # note             '#' starts a comment anywhere (protocol lines never use it)
 *   CMD ARGS   #! expect ok       directive: the reply must be "ok"
 *   CMD ARGS   #! expect error:N  directive: the reply must be "error:N <text>"
 * A line without a directive is sent and its reply read, but not checked (an
 * unknown or malformed reply is still a failure). The command itself may be empty
 * only with a directive ("#! expect ok" alone sends an empty line).
 * Limits: SIM_JOB_LINE_MAX bytes per line, SIM_JOB_MAX commands per file.
 */
#ifndef SIM_JOB_H
#define SIM_JOB_H

#include <stddef.h>

#define SIM_JOB_LINE_MAX 4096
#define SIM_JOB_MAX 10000

enum sim_job_expect {
    SIM_JOB_EXPECT_NONE = 0, /* reply is read but not checked */
    SIM_JOB_EXPECT_OK = 1,   /* "ok" */
    SIM_JOB_EXPECT_ERROR = 2 /* "error:<code> ..." with code == sim_job_cmd.code */
};

struct sim_job_cmd {
    char *text;    /* the command, without terminator (malloc'ed) */
    size_t len;    /* strlen(text) */
    int lineno;    /* line number in the file (1-based) */
    int expect;    /* enum sim_job_expect */
    int code;      /* expected error code (SIM_JOB_EXPECT_ERROR) */
};

struct sim_job {
    struct sim_job_cmd *cmd; /* n commands (malloc'ed) */
    size_t n;
};

/* Read and validate the whole job file. Returns 0, or -1 with a message
 * ("file:line: ...") in err. On error nothing needs freeing. */
int sim_job_load(struct sim_job *j, const char *path, char *err, size_t errcap);

/* Free what sim_job_load allocated. */
void sim_job_free(struct sim_job *j);

#endif /* SIM_JOB_H */
