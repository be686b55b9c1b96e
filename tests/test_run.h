/*
 * test_run.h -- running a command (the benchmark scripts: python3
 * bench/report.py, bench/plots.py) from a test and capturing its output.
 */
#ifndef TEST_RUN_H
#define TEST_RUN_H

#include <stdio.h>
#include <stdlib.h>
#include <sys/wait.h>

#include "test_util.h"

/* Run `cmd` with the shell (popen); returns what it wrote on its standard
 * output (free it; redirect stderr with 2>&1 to have it too) and its exit
 * status in *status (-1 when it did not exit normally). */
static inline char *ctt_run_cmd(const char *cmd, int *status)
{
    FILE *p = popen(cmd, "r");
    cr_assert(p != NULL, "popen(%s) failed", cmd);
    size_t cap = 1 << 16, len = 0, got;
    char *buf = malloc(cap);
    cr_assert(buf != NULL);
    while ((got = fread(buf + len, 1, cap - 1 - len, p)) > 0) {
        len += got;
        if (len + 1 == cap) {
            cap *= 2;
            buf = realloc(buf, cap);
            cr_assert(buf != NULL);
        }
    }
    buf[len] = '\0';
    int st = pclose(p);
    *status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    return buf;
}

#endif /* TEST_RUN_H */
