/*
 * test_errors.h -- helpers of the error-path tests (tests/test_errors_*.c):
 * a scene directory of the test's own, `contact` run there behind a shell
 * prefix (a resource limit, an ignored signal), and the checks every
 * error test makes: the exit code, and a message that names the file, the
 * line and the field.
 */
#ifndef TEST_ERRORS_H
#define TEST_ERRORS_H

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "solver.h"
#include "test_cli.h"

/*
 * Run `PREFIX contact ARGS` with the shell in directory dir, with one
 * OpenMP thread: PREFIX is shell text run first in the same shell (e.g.
 * "ulimit -v 100000;"), "" for none. As ctt_cli_run otherwise.
 */
#define cte_run(r, dir, prefix, ...) ctt_cli_run_prefix((r), (dir), (prefix), 1, __VA_ARGS__)

/* The run exited with `code` and its error stream holds `want` (a whole
 * "FILE:LINE: FIELD: ..." prefix) and, when not NULL, `also`. */
static inline void cte_expect(const ctt_cli *r, int code, const char *want, const char *also)
{
    cr_expect_eq(r->status, code, "exit %d, expected %d; stderr: %s", r->status, code, r->err);
    cr_expect(strstr(r->err, want) != NULL, "stderr lacks \"%s\": %s", want, r->err);
    if (also)
        cr_expect(strstr(r->err, also) != NULL, "stderr lacks \"%s\": %s", also, r->err);
}
#define CTE_EXPECT(r, code, want, also) cte_expect((r), (code), (want), (also))

/* The whole content of DIR/NAME (free it), NULL when it cannot be read. */
static inline char *cte_slurp_in(const char *dir, const char *name)
{
    char p[1200];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    return ctt_slurp(p);
}

#endif /* TEST_ERRORS_H */
