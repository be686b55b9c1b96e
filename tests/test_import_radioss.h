/*
 * test_import_radioss.h -- helpers shared by the Radioss reader tests
 * (test_import_radioss.c, test_import_radioss_bricks.c).
 */
#ifndef TEST_IMPORT_RADIOSS_H
#define TEST_IMPORT_RADIOSS_H

#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "import_radioss.h"
#include "test_util.h"

/* tests/data/radioss/NAME, found from this file's path. */
static inline void data_path(char *buf, size_t n, const char *name)
{
    char rel[512];
    snprintf(rel, sizeof rel, "data/radioss/%s", name);
    ctt_tests_path(buf, n, rel);
}

static inline void load(const char *path, ctd_deck *d)
{
    ct_diag g;
    memset(&g, 0, sizeof g);
    int rc = ctd_deck_read(path, d, &g);
    cr_assert_eq(rc, CT_OK, "%s: %s (%s)", path, g.msg, ct_strerror(rc));
}

/* load(), timed (seconds of wall clock), for the complexity guards. */
static inline double load_timed(const char *path, ctd_deck *d)
{
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    load(path, d);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    return (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
}

static inline void tmp_path(char *buf, size_t n, const char *name)
{
    snprintf(buf, n, "/tmp/ct_import_%ld_%s", (long)getpid(), name);
}

#endif /* TEST_IMPORT_RADIOSS_H */
