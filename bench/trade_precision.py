#!/usr/bin/env python3
"""Compare the narrow-phase dumps of a double and a single precision build.

Usage:
  bench/trade_precision.py DOUBLE_DUMP SINGLE_DUMP [--json OUT.json]

The dumps come from `bench --dump-narrow FILE` (bench/bench_trade.c): the
same case (crumpled sheet, seed 12345, bucket candidates, Newton projection,
two-sided) in each binary's precision, one line per candidate pair
"node seg flag dist pen nx ny nz" after a "# ... h=H gap=G ..." header.

Pairs are matched by (node, seg); the candidate sets may differ at the
boundary of the search distance (the coordinates are rounded to float in
the single build), and the counts of unmatched pairs are reported. Over the
matched pairs:
  max_rel_pen         max |p_s - p_d| / p_d over pairs with p_d >= 1% of the
                      gap (the relative difference of the penetration);
  max_pen_err_gap     max |p_s - p_d| / gap over all matched pairs;
  max_normal_diff     max |n_s - n_d| over pairs active (p > 0) in both
                      (unit vectors: absolute = relative);
  max_dist_err_h      max |D_s - D_d| / h;
  active_mismatch     pairs active in one precision only.
Skipped pairs (flag bits 1 or 2) are left out. Prints a summary; with
--json, writes {"trade_precision": {...}} for bench/report.py (pass it with
the benchmark files: report.py bench.json bench-single.json OUT.json).
Standard library only.
"""
import json
import math
import re
import sys

SKIP_FLAGS = 1 | 2  # CT_NARROW_DEGENERATE | CT_NARROW_NONFINITE
PEN_FLOOR = 0.01    # relative penetration only where p_d >= PEN_FLOOR * gap


def read_dump(path):
    """(header dict, {(node, seg): (flag, dist, pen, nx, ny, nz)})."""
    head, pairs = {}, {}
    with open(path) as f:
        for line in f:
            line = line.strip()
            if not line:
                continue
            if line.startswith("#"):
                for k, v in re.findall(r"(\w+)=(\S+)", line):
                    head[k] = v
                continue
            parts = line.split()
            if len(parts) != 8:
                raise ValueError("%s: bad line: %s" % (path, line))
            key = (int(parts[0]), int(parts[1]))
            pairs[key] = (int(parts[2]),) + tuple(float(v) for v in parts[3:])
    for k in ("gap", "h"):
        if k not in head:
            raise ValueError("%s: no %s= in the header" % (path, k))
    return head, pairs


def compare(ref_head, ref, oth_head, oth):
    gap = float(ref_head["gap"])
    h = float(ref_head["h"])
    common = [k for k in ref if k in oth]
    res = {
        "reference": ref_head.get("precision", "?"),
        "other": oth_head.get("precision", "?"),
        "pairs_reference": len(ref),
        "pairs_other": len(oth),
        "pairs_common": 0,
        "only_reference": sum(1 for k in ref if k not in oth),
        "only_other": sum(1 for k in oth if k not in ref),
        "active_mismatch": 0,
        "max_rel_pen": 0.0,
        "max_pen_err_gap": 0.0,
        "max_normal_diff": 0.0,
        "max_dist_err_h": 0.0,
        "pen_floor": PEN_FLOOR,
    }
    for k in sorted(common):
        a, b = ref[k], oth[k]
        if (a[0] | b[0]) & SKIP_FLAGS:
            continue
        res["pairs_common"] += 1
        _, da, pa, ax, ay, az = a
        _, db, pb, bx, by, bz = b
        dp = abs(pb - pa)
        res["max_pen_err_gap"] = max(res["max_pen_err_gap"], dp / gap)
        if pa >= PEN_FLOOR * gap:
            res["max_rel_pen"] = max(res["max_rel_pen"], dp / pa)
        res["max_dist_err_h"] = max(res["max_dist_err_h"], abs(db - da) / h)
        if (pa > 0) != (pb > 0):
            res["active_mismatch"] += 1
        elif pa > 0:
            dn = math.sqrt((bx - ax) ** 2 + (by - ay) ** 2 + (bz - az) ** 2)
            res["max_normal_diff"] = max(res["max_normal_diff"], dn)
    return res


def summary(res):
    return "\n".join([
        "narrow phase, %s against %s:" % (res["other"], res["reference"]),
        "  pairs: %d common, %d only in %s, %d only in %s, %d active in one only" % (
            res["pairs_common"], res["only_reference"], res["reference"], res["only_other"],
            res["other"], res["active_mismatch"]),
        "  max relative penetration difference (p >= %g gap): %.3g" % (
            res["pen_floor"], res["max_rel_pen"]),
        "  max penetration difference / gap: %.3g" % res["max_pen_err_gap"],
        "  max normal difference |n_s - n_d|: %.3g" % res["max_normal_diff"],
        "  max distance difference / h: %.3g" % res["max_dist_err_h"],
    ])


def main(argv):
    args = argv[1:]
    out = None
    if "--json" in args:
        i = args.index("--json")
        if i + 1 >= len(args):
            sys.stderr.write("trade_precision.py: --json needs a file name\n")
            return 2
        out = args[i + 1]
        del args[i:i + 2]
    if len(args) != 2:
        sys.stderr.write("usage: trade_precision.py DOUBLE_DUMP SINGLE_DUMP [--json OUT]\n")
        return 2
    try:
        rh, rp = read_dump(args[0])
        oh, op = read_dump(args[1])
    except (OSError, ValueError) as e:
        sys.stderr.write("trade_precision.py: cannot read: %s\n" % e)
        return 1
    if not rp or not op:
        sys.stderr.write("trade_precision.py: a dump holds no pairs\n")
        return 1
    res = compare(rh, rp, oh, op)
    sys.stdout.write(summary(res) + "\n")
    if out:
        try:
            with open(out, "w") as f:
                json.dump({"trade_precision": res}, f, indent=1)
                f.write("\n")
        except OSError as e:
            sys.stderr.write("trade_precision.py: cannot write %s: %s\n" % (out, e))
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
