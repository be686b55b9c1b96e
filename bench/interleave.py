#!/usr/bin/env python3
"""Run two benchmark binaries in alternating rounds and report the ratio of
one counter, round by round.

Usage:
  bench/interleave.py A_BIN B_BIN --filter REGEX [--rounds N] [--repetitions R]
                      [--counter ns_per_pair] [--json OUT.json]

The double and single precision builds are two programs, so `make bench`
runs them one after the other, minutes apart; on a shared host the single
rows then compare against a double run made in other conditions (the
node-triangle speed-up read 1.05x and 1.65x in two runs of the same code).
Here each round runs A then B on the same filter (B then A in every other
round), with one repetition each; for every benchmark name present in both,
the round's ratio is A's counter over B's (for times: B's speed-up over A).
With --repetitions R, each program runs R repetitions in its turn and the
round keeps, per name, the smallest value of the counter (the least
disturbed of the R: on a shared host the other tenants slow a repetition
down, they hardly ever speed one up; in stop 47 the fastest of 3 per round read the
contact cycle's total 0.97 (0.87-1.07) where single repetitions read 0.89
(0.65-1.12)).
Reported per name: the median of A's and B's counter over the rounds, the
median of the rounds' ratios and their range, and the range of the host
probe's barrier (host_barrier_us, bench/bench_host.c) over both programs'
runs: when it spans more than HOST_OFF (benchjson.py), the host moved its CPUs between
rounds and the ratio's range holds both placements. With --json, writes
{"interleaved": {...}} for bench/report.py (pass it with the benchmark
files). Standard library only.
"""
import json
import os
import statistics
import subprocess
import sys
import tempfile

from benchjson import HOST_BARRIER, HOST_OFF, base_name


def run_once(binary, flt, out_path, reps=1, counter=None):
    """Run binary on the filter, reps repetitions; {name: counters} of its
    runs (errors left out), per name the run with the smallest counter."""
    cmd = [binary, "--benchmark_filter=" + flt, "--benchmark_repetitions=%d" % reps,
           "--benchmark_report_aggregates_only=false", "--benchmark_out=" + out_path,
           "--benchmark_out_format=json"]
    r = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        raise RuntimeError("%s failed (%d): %s" % (binary, r.returncode, r.stderr[-500:]))
    with open(out_path) as f:
        data = json.load(f)
    runs = {}
    for b in data.get("benchmarks", []):
        if b.get("error_occurred") or b.get("run_type") == "aggregate":
            continue
        name = base_name(b.get("run_name", b.get("name", "")))
        old = runs.get(name)
        if old is None or (counter in b and (counter not in old
                                             or float(b[counter]) < float(old[counter]))):
            runs[name] = b
    return runs, data.get("context", {})


def interleave(a_bin, b_bin, flt, rounds, counter, reps=1):
    per = {}  # name -> {"a": [...], "b": [...], "r": [...]}
    ctx = {}
    with tempfile.TemporaryDirectory() as tmp:
        pa, pb = os.path.join(tmp, "a.json"), os.path.join(tmp, "b.json")
        for i in range(rounds):
            if i % 2 == 0:
                ra, ctx["a"] = run_once(a_bin, flt, pa, reps, counter)
                rb, ctx["b"] = run_once(b_bin, flt, pb, reps, counter)
            else:
                rb, ctx["b"] = run_once(b_bin, flt, pb, reps, counter)
                ra, ctx["a"] = run_once(a_bin, flt, pa, reps, counter)
            for name in ra:
                if name not in rb or counter not in ra[name] or counter not in rb[name]:
                    continue
                va, vb = float(ra[name][counter]), float(rb[name][counter])
                if not (va > 0 and vb > 0):
                    continue
                e = per.setdefault(name, {"a": [], "b": [], "r": [], "bar": [], "label": ""})
                e["a"].append(va)
                e["b"].append(vb)
                e["r"].append(va / vb)
                e["bar"] += [float(x[name][HOST_BARRIER]) for x in (ra, rb)
                             if float(x[name].get(HOST_BARRIER, 0)) > 0]
                e["label"] = rb[name].get("label", "")
    rows = []
    for name in sorted(per):
        e = per[name]
        row = {"name": name, "a": statistics.median(e["a"]), "b": statistics.median(e["b"]),
               "ratio": statistics.median(e["r"]), "ratio_min": min(e["r"]),
               "ratio_max": max(e["r"]), "rounds": len(e["r"]), "label": e["label"]}
        if e["bar"]:
            row["barrier_min"], row["barrier_max"] = min(e["bar"]), max(e["bar"])
        rows.append(row)
    return {"counter": counter, "filter": flt, "rounds": rounds, "repetitions": reps,
            "a_build": ctx.get("a", {}).get("ct_build", os.path.basename(a_bin)),
            "b_build": ctx.get("b", {}).get("ct_build", os.path.basename(b_bin)),
            "rows": rows}


def moved_cpus(row):
    """Whether a row's rounds ran under two placements of the host's CPUs:
    the probe's barrier spans more than HOST_OFF."""
    lo, hi = row.get("barrier_min", 0), row.get("barrier_max", 0)
    return lo > 0 and hi > HOST_OFF * lo


def positive(text):
    """The integer in text, or 0 when it is not one."""
    try:
        return int(text)
    except ValueError:
        return 0


def main(argv):
    args, opts = [], {"--rounds": "5", "--repetitions": "1", "--counter": "ns_per_pair",
                      "--filter": None, "--json": None}
    i = 1
    while i < len(argv):
        if argv[i] in opts and i + 1 < len(argv):
            opts[argv[i]] = argv[i + 1]
            i += 2
        else:
            args.append(argv[i])
            i += 1
    if len(args) != 2 or not opts["--filter"]:
        sys.stderr.write(__doc__)
        return 2
    rounds, reps = positive(opts["--rounds"]), positive(opts["--repetitions"])
    for key, val in (("--rounds", rounds), ("--repetitions", reps)):
        if val < 1:
            sys.stderr.write("interleave.py: %s must be a positive integer\n" % key)
            return 2
    try:
        res = interleave(args[0], args[1], opts["--filter"], rounds, opts["--counter"], reps)
    except (OSError, RuntimeError, ValueError) as e:
        sys.stderr.write("interleave.py: %s\n" % e)
        return 1
    if not res["rows"]:
        sys.stderr.write("interleave.py: no benchmark ran in both programs\n")
        return 1
    for r in res["rows"]:
        moved = ""
        if moved_cpus(r):
            moved = "  barrier %.2f-%.2f us: the host moved its CPUs between rounds" % (
                r["barrier_min"], r["barrier_max"])
        print("%-50s a %8.2f  b %8.2f  a/b %.2f (%.2f-%.2f, %d rounds)%s" % (
            r["name"], r["a"], r["b"], r["ratio"], r["ratio_min"], r["ratio_max"],
            r["rounds"], moved))
    if opts["--json"]:
        with open(opts["--json"], "w") as f:
            json.dump({"interleaved": res}, f, indent=2)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
