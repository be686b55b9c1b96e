/*
 * test_examples.c -- the programs of examples/ (suite "examples"), built
 * next to this test program: each runs, passes its own verification (exit
 * 0), and its printed results agree with the answers computed here.
 *
 * examples/slide.c: nine masses launched at 1 m/s on a rigid floor with
 * Coulomb friction mu = 0.3 stop after v0^2 / (2 mu g), resting where
 * K p = m g (the gap minus m g / K above the floor).
 */
#include <libgen.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "test_util.h"

/* The path of bin/example_NAME next to this program. */
static void example_path(char *buf, size_t n, const char *name)
{
    char self[1024];
    ssize_t len = readlink("/proc/self/exe", self, sizeof self - 1);
    cr_assert(len > 0);
    self[len] = '\0';
    snprintf(buf, n, "%s/example_%s", dirname(self), name);
}

Test(examples, slide_stops_where_coulomb_says)
{
    char path[1100], cmd[1200], line[512];
    example_path(path, sizeof path, "slide");
    cr_assert_eq(access(path, X_OK), 0, "%s not built", path);
    snprintf(cmd, sizeof cmd, "OMP_NUM_THREADS=2 '%s'", path);
    FILE *f = popen(cmd, "r");
    cr_assert_not_null(f);
    const double v0 = 1, mu = 0.3, g = 9.81, m = 0.01, K = 1e4, gap = 0.002;
    const double s_exact = v0 * v0 / (2 * mu * g), z_rest = gap - m * g / K;
    int masses = 0, passed = 0;
    while (fgets(line, sizeof line, f)) {
        int q;
        double s, v, z;
        if (sscanf(line, "slide: mass %d: slid %lf m, speed %lf m/s, height %lf m", &q, &s, &v,
                   &z) == 4) {
            masses++;
            cr_expect(fabs(s - s_exact) < 0.01 * s_exact, "mass %d slid %.6f, expected %.6f",
                      q, s, s_exact);
            /* Stopped: what is left is the swing on the stick spring. */
            cr_expect(v < 1.5 * mu * g * sqrt(m / 1e4), "mass %d still moves at %g", q, v);
            cr_expect(fabs(z - z_rest) < 0.01 * m * g / K, "mass %d at %.9g, rest %.9g", q, z,
                      z_rest);
        }
        passed += strcmp(line, "slide: verification passed\n") == 0;
    }
    int st = pclose(f);
    cr_assert(WIFEXITED(st) && WEXITSTATUS(st) == 0, "the example failed (status %d)", st);
    cr_assert_eq(masses, 9);
    cr_assert_eq(passed, 1);
}
