#!/usr/bin/env python3
"""The coefficients of the shell's atan (shell_forces.c, cti_atan2).

atan(u) = u P(u^2) for |u| <= tan(pi/8): P is the polynomial of the given
degree in z = u^2 whose relative error max |P(z) - f(z)| / f(z), with
f(z) = atan(sqrt z) / sqrt z, is smallest on [0, tan^2(pi/8)] (Remez's
exchange algorithm, in 60-digit arithmetic with mpmath). Prints the
coefficients with 17 significant digits, the error of the polynomial and
that of its coefficients rounded to the working precision.

    python3 driver/elements/shell_atan_poly.py 11 double
    python3 driver/elements/shell_atan_poly.py 5 single
"""
import struct
import sys

import mpmath as mp

mp.mp.dps = 60
ZMAX = mp.tan(mp.pi / 8) ** 2


def f(z):
    if z == 0:
        return mp.mpf(1)
    u = mp.sqrt(z)
    return mp.atan(u) / u


def peval(c, z):
    r = mp.mpf(0)
    for a in reversed(c):
        r = r * z + a
    return r


def remez(deg, rounds=12, grid_n=4000):
    n = deg + 1
    xs = [ZMAX / 2 * (1 - mp.cos(mp.pi * k / n)) for k in range(n + 1)]
    grid = [ZMAX * k / grid_n for k in range(grid_n + 1)]
    c, worst = None, None
    for _ in range(rounds):
        # p(x_i) + (-1)^i E f(x_i) = f(x_i): equioscillating relative error.
        a = mp.matrix(n + 1, n + 1)
        b = mp.matrix(n + 1, 1)
        for i, x in enumerate(xs):
            for j in range(n):
                a[i, j] = x**j
            a[i, n] = (-1) ** i * f(x)
            b[i] = f(x)
        s = mp.lu_solve(a, b)
        c = [s[j] for j in range(n)]
        err = [(peval(c, x) - f(x)) / f(x) for x in grid]
        worst = max(abs(e) for e in err)
        # The largest error of each run of one sign: the new reference.
        runs, cur = [], [0]
        for k in range(1, len(grid)):
            if mp.sign(err[k]) == mp.sign(err[cur[0]]):
                cur.append(k)
            else:
                runs.append(cur)
                cur = [k]
        runs.append(cur)
        if len(runs) != n + 1:
            break
        xs = [grid[max(r, key=lambda k: abs(err[k]))] for r in runs]
    return c, worst


def rounded(v, prec):
    if prec == "double":
        return mp.mpf(float(v))
    return mp.mpf(struct.unpack("f", struct.pack("f", float(v)))[0])


def main():
    deg, prec = int(sys.argv[1]), sys.argv[2]
    c, worst = remez(deg)
    cr = [rounded(v, prec) for v in c]
    grid = [ZMAX * k / 3000 for k in range(3001)]
    er = max(abs((peval(cr, x) - f(x)) / f(x)) for x in grid)
    print(f"/* degree {deg} ({prec}): relative error {mp.nstr(worst, 3)}, "
          f"{mp.nstr(er, 3)} with the coefficients rounded */")
    for j, v in enumerate(c):
        print(f"#define CTI_ATAN_C{j} {mp.nstr(v, 17, min_fixed=-1, max_fixed=1)}")


if __name__ == "__main__":
    main()
