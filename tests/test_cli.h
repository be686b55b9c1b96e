/*
 * test_cli.h -- running the `contact` program from a test (test_cli.c,
 * test_deck_select.c): the program built next to the test program
 * (bin/contact, found from /proc/self/exe as test_examples.c and
 * test_search_bucket_auto.c find theirs), started by the shell in a
 * directory of the test's own, with its exit code, standard output and
 * standard error captured whole; plus the temporary directories and files
 * the runs read and write.
 */
#ifndef TEST_CLI_H
#define TEST_CLI_H

#include <libgen.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "test_util.h"

/* One run of the program. */
typedef struct ctt_cli {
    int status; /* the exit code; -1 when the program did not exit normally */
    char *out;  /* its standard output, whole (never NULL after a run) */
    char *err;  /* its standard error, whole */
} ctt_cli;

/* The path of bin/contact next to this test program. */
static inline void ctt_contact_path(char *buf, size_t n)
{
    char self[1024];
    ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
    cr_assert(len > 0, "cannot read /proc/self/exe");
    self[len] = '\0';
    snprintf(buf, n, "%s/contact", dirname(self));
    cr_assert_eq(access(buf, X_OK), 0, "%s is not built (make build-tests builds it)", buf);
}

/* The whole content of a file (free it), or NULL when it cannot be read. */
static inline char *ctt_slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    size_t cap = 4096, len = 0, got;
    char *buf = malloc(cap);
    cr_assert_not_null(buf);
    while ((got = fread(buf + len, 1, cap - 1 - len, f)) > 0) {
        len += got;
        if (len + 1 == cap) {
            cap *= 2;
            buf = realloc(buf, cap);
            cr_assert_not_null(buf);
        }
    }
    buf[len] = '\0';
    fclose(f);
    return buf;
}

/* Write `text` to DIR/NAME. */
static inline void ctt_write_file(const char *dir, const char *name, const char *text)
{
    char p[1200];
    snprintf(p, sizeof p, "%s/%s", dir, name);
    FILE *f = fopen(p, "w");
    cr_assert_not_null(f, "cannot write %s", p);
    fputs(text, f);
    cr_assert_eq(fclose(f), 0);
}

/* 1 when DIR/NAME exists (file or directory). */
static inline int ctt_exists(const char *dir, const char *name)
{
    char p[1200];
    struct stat st;
    snprintf(p, sizeof p, "%s/%s", dir, name);
    return stat(p, &st) == 0;
}

/* A new empty directory /tmp/ct_TAG_XXXXXX in dir[64]. */
static inline void ctt_tmpdir(char *dir, const char *tag)
{
    snprintf(dir, 64, "/tmp/ct_%s_XXXXXX", tag);
    cr_assert_not_null(mkdtemp(dir), "mkdtemp %s failed", dir);
}

/* Remove a directory made by ctt_tmpdir, with its content. */
static inline void ctt_rmtree(const char *dir)
{
    char cmd[128];
    cr_assert(strncmp(dir, "/tmp/ct_", 8) == 0);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    cr_assert_eq(system(cmd), 0);
}

static inline void ctt_cli_free(ctt_cli *r)
{
    free(r->out);
    free(r->err);
    r->out = r->err = NULL;
}

/*
 * Run `PREFIX OMP_NUM_THREADS=threads contact ARGS` with the shell in
 * directory dir (threads 0: with OMP_NUM_THREADS unset, `contact` chooses):
 * PREFIX is shell text run first in the same shell (e.g.
 * "ulimit -v 100000;"), "" for none; ARGS is a printf format of shell
 * words (the caller quotes what needs quoting). The output and error
 * streams go to dir/.cli_out and dir/.cli_err, read back into r (which is
 * freed first if it holds a previous run).
 */
static inline void ctt_cli_vrun(ctt_cli *r, const char *dir, const char *prefix, int threads,
                                const char *fmt, va_list ap)
{
    char bin[1100], args[2048], cmd[4600];
    ctt_contact_path(bin, sizeof bin);
    int na = vsnprintf(args, sizeof args, fmt, ap);
    cr_assert(na >= 0 && (size_t)na < sizeof args, "arguments too long");
    char env[64] = "env -u OMP_NUM_THREADS";
    if (threads > 0)
        snprintf(env, sizeof env, "OMP_NUM_THREADS=%d", threads);
    int nc = snprintf(cmd, sizeof cmd, "cd '%s' && %s %s '%s' %s >'%s/.cli_out' 2>'%s/.cli_err'",
                      dir, prefix, env, bin, args, dir, dir);
    cr_assert(nc > 0 && (size_t)nc < sizeof cmd, "command too long");
    int st = system(cmd);
    cr_assert(st != -1, "system(%s) failed", cmd);
    char p[1200];
    free(r->out);
    free(r->err);
    snprintf(p, sizeof p, "%s/.cli_out", dir);
    r->out = ctt_slurp(p);
    snprintf(p, sizeof p, "%s/.cli_err", dir);
    r->err = ctt_slurp(p);
    cr_assert(r->out && r->err, "the output of `contact %s` was not captured", args);
    r->status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

/* Run `contact ARGS` in directory dir with OMP_NUM_THREADS=threads (see
 * ctt_cli_vrun). */
static inline void ctt_cli_run(ctt_cli *r, const char *dir, int threads, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    ctt_cli_vrun(r, dir, "", threads, fmt, ap);
    va_end(ap);
}

/* The same behind a shell prefix (see ctt_cli_vrun). */
static inline void ctt_cli_run_prefix(ctt_cli *r, const char *dir, const char *prefix,
                                      int threads, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    ctt_cli_vrun(r, dir, prefix, threads, fmt, ap);
    va_end(ap);
}

/* The number after "KEY": in a JSON text (the first occurrence), or NAN. */
static inline double ctt_json_num(const char *json, const char *key)
{
    char k[128];
    snprintf(k, sizeof k, "\"%s\":", key);
    const char *p = strstr(json, k);
    if (!p)
        return NAN;
    char *e;
    double v = strtod(p + strlen(k), &e);
    return e == p + strlen(k) ? NAN : v;
}

/* Expect exit code `code`, and `what` (when not NULL) in the error stream. */
#define EXPECT_FAIL(r, code, what)                                                            \
    do {                                                                                      \
        cr_expect_eq((r)->status, (code), "exit %d, expected %d; stderr: %s", (r)->status,    \
                     (code), (r)->err);                                                       \
        if ((what) != NULL)                                                                   \
            cr_expect(strstr((r)->err, (what)) != NULL, "stderr lacks \"%s\": %s",            \
                      (const char *)(what), (r)->err);                                        \
    } while (0)

/* The number of lines of s. */
static inline int count_lines(const char *s)
{
    int n = 0;
    for (; *s; s++)
        n += *s == '\n';
    return n;
}

#endif /* TEST_CLI_H */
