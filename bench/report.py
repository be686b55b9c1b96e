#!/usr/bin/env python3
"""Turn the Google Benchmark JSON of `make bench` into Markdown tables.

Usage: python3 bench/report.py build/bench.json > /tmp/x.md

Reads the search benchmarks (search/<family>/<algo>/<numbering>/t<threads>/
<nodes>), takes the median of the repetitions (the "median" aggregate when
present, else the median of the repetition rows), and prints:
  - the provenance block (the context the benchmark program stored);
  - the headline: plates at its largest size, bucket and bsp, per numbering
    and thread count;
  - per family, one row per size / numbering / threads / algorithm: time per
    search, ns per secondary node, ratio to the best algorithm of the same
    size, numbering and threads, candidate pairs, workspace bytes per node,
    misses against the reference (topological only); a direct search that was
    skipped over its budget shows its time extrapolated from the largest
    measured direct run (cost proportional to nsec * nseg), marked "(extrap.)";
  - the fitted scaling exponent k (time proportional to nsec^k) per family and
    algorithm;
  - the speed-up from 1 thread to the most threads, and the parallel
    efficiency, at the largest size measured with both;
  - any other benchmark as name / median time.
Standard library only.
"""
import json
import math
import re
import statistics
import sys

TIME_NS = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}
ALGOS = ["direct", "topological", "bucket", "bsp"]
NUMBERINGS = ["natural", "shuffled", "sfc"]
NAME_RE = re.compile(
    r"^search/(?P<family>[^/]+)/(?P<algo>[^/]+)/(?P<numbering>[^/]+)/t(?P<threads>\d+)/"
    r"(?P<n>\d+)(?:/(?:real_time|manual_time))?$")
COUNTERS = ["ns_per_node", "nsec", "nseg", "pairs", "bytes_per_node", "misses", "extra"]


def base_name(run_name):
    return re.sub(r"/(real_time|manual_time)$", "", run_name)


def collect(benchmarks):
    """One record per run: median time (ns), counters, label or error."""
    runs = {}
    order = []
    for b in benchmarks:
        key = b.get("run_name", b.get("name", ""))
        if key not in runs:
            runs[key] = {"median": None, "reps": [], "error": None}
            order.append(key)
        r = runs[key]
        if b.get("error_occurred"):
            r["error"] = b.get("error_message", "error")
            continue
        if b.get("run_type") == "aggregate":
            if b.get("aggregate_name") == "median":
                r["median"] = b
        else:
            r["reps"].append(b)
    out = []
    for key in order:
        r = runs[key]
        rec = {"name": base_name(key), "error": None, "label": "", "time_ns": None,
               "counters": {}}
        src = r["median"]
        if src is not None:
            rec["time_ns"] = src["real_time"] * TIME_NS[src.get("time_unit", "ns")]
            rec["label"] = src.get("label", "")
            for c in COUNTERS:
                if c in src:
                    rec["counters"][c] = float(src[c])
        elif r["reps"]:
            reps = r["reps"]
            rec["time_ns"] = statistics.median(
                x["real_time"] * TIME_NS[x.get("time_unit", "ns")] for x in reps)
            rec["label"] = reps[-1].get("label", "")
            for c in COUNTERS:
                vals = [float(x[c]) for x in reps if c in x]
                if vals:
                    rec["counters"][c] = statistics.median(vals)
        else:
            rec["error"] = r["error"] or "no result"
        out.append(rec)
    return out


def fmt_time(ns):
    if ns is None:
        return "-"
    for unit, scale in (("s", 1e9), ("ms", 1e6), ("µs", 1e3)):
        if ns >= scale:
            return "%.3g %s" % (ns / scale, unit)
    return "%.3g ns" % ns


def fmt_num(v, digits=1):
    if v is None:
        return "-"
    if abs(v - round(v)) < 1e-9 and abs(v) >= 1:
        return "%d" % round(v)
    return "%.*f" % (digits, v)


def fmt_ns(v):
    if v is None:
        return "-"
    return "%.1f" % v if v < 1000 else "%.0f" % v


def sort_key(rec):
    return (int(rec["n"]), NUMBERINGS.index(rec["numbering"]) if rec["numbering"] in NUMBERINGS
            else 99, int(rec["threads"]),
            ALGOS.index(rec["algo"]) if rec["algo"] in ALGOS else 99)


def parse_search(records):
    search, other = [], []
    for r in records:
        m = NAME_RE.match(r["name"])
        if not m:
            other.append(r)
            continue
        r.update(m.groupdict())
        r["threads"] = int(r["threads"])
        r["n"] = int(r["n"])
        search.append(r)
    return search, other


def mesh_sizes(rec, search):
    """nsec and nseg of the record's mesh: its counters, another algorithm's
    run on the same mesh, or the numbers in a skip message."""
    c = rec["counters"]
    if "nsec" in c and "nseg" in c:
        return c["nsec"], c["nseg"]
    for o in search:
        if (o["family"], o["numbering"], o["n"]) == (rec["family"], rec["numbering"], rec["n"]) \
                and "nsec" in o["counters"] and "nseg" in o["counters"]:
            return o["counters"]["nsec"], o["counters"]["nseg"]
    m = re.search(r"nsec=(\d+) nseg=(\d+)", rec["error"] or "")
    if m:
        return float(m.group(1)), float(m.group(2))
    return None, None


def extrapolate_direct(rec, search):
    """Time of a skipped direct run from the largest measured direct run of the
    same family, numbering and threads (cost proportional to nsec * nseg)."""
    nsec, nseg = mesh_sizes(rec, search)
    if not nsec or not nseg:
        return None
    best = None
    for o in search:
        if o["algo"] != "direct" or o["error"] or o["time_ns"] is None:
            continue
        if (o["family"], o["numbering"], o["threads"]) != \
                (rec["family"], rec["numbering"], rec["threads"]):
            continue
        w = o["counters"].get("nsec", 0) * o["counters"].get("nseg", 0)
        if w > 0 and (best is None or w > best[0]):
            best = (w, o["time_ns"])
    if best is None:
        return None
    t = best[1] / best[0] * nsec * nseg
    return t, t / nsec


def ns_per_node(rec):
    """Median time per search divided by the secondary nodes."""
    nsec = rec["counters"].get("nsec")
    if rec["time_ns"] is None or not nsec:
        return None
    return rec["time_ns"] / nsec


def print_context(ctx, out):
    out.append("## Provenance\n")
    keys = [k for k in ctx if k.startswith("ct_")]
    for k in keys:
        out.append("- %s: %s" % (k[3:], ctx[k]))
    for k in ("date", "host_name", "num_cpus", "mhz_per_cpu", "library_build_type"):
        if k in ctx:
            out.append("- %s: %s" % (k, ctx[k]))
    caches = ctx.get("caches") or []
    if caches:
        parts = ["L%d %s %dKiB (shared by %d)" % (c["level"], c["type"], c["size"] // 1024,
                                                  c["num_sharing"]) for c in caches]
        out.append("- caches: " + ", ".join(parts))
    out.append("")


def print_headline(search, out):
    plates = [r for r in search if r["family"] == "plates" and r["algo"] in ("bucket", "bsp")]
    measured = [r for r in plates if not r["error"]]
    if not measured:
        return
    nmax = max(r["n"] for r in measured)
    rows = sorted((r for r in plates if r["n"] == nmax), key=sort_key)
    out.append("## Headline: plates, %d nodes\n" % nmax)
    out.append("| numbering | algorithm | threads | time/search | ns/node | pairs |")
    out.append("|---|---|---:|---:|---:|---:|")
    for r in rows:
        if r["error"]:
            out.append("| %s | %s | %d | %s | - | - |" % (r["numbering"], r["algo"], r["threads"],
                                                       r["error"]))
            continue
        out.append("| %s | %s | %d | %s | %s | %s |" % (
            r["numbering"], r["algo"], r["threads"], fmt_time(r["time_ns"]),
            fmt_ns(ns_per_node(r)), fmt_num(r["counters"].get("pairs"))))
    out.append("")


def print_family(fam, search, out):
    rows = sorted((r for r in search if r["family"] == fam), key=sort_key)
    best = {}
    for r in rows:
        v = ns_per_node(r) if not r["error"] else None
        if v is not None:
            k = (r["n"], r["numbering"], r["threads"])
            best[k] = min(best.get(k, v), v)
    out.append("### %s\n" % fam)
    out.append("| nodes | numbering | threads | algorithm | time/search | ns/node | × best "
               "| pairs | bytes/node | misses | note |")
    out.append("|---:|---|---:|---|---:|---:|---:|---:|---:|---:|---|")
    for r in rows:
        head = "| %d | %s | %d | %s " % (r["n"], r["numbering"], r["threads"], r["algo"])
        if r["error"]:
            ex = extrapolate_direct(r, search) if r["algo"] == "direct" else None
            if ex:
                out.append(head + "| %s (extrap.) | %s (extrap.) | - | - | - | - | %s |" % (
                    fmt_time(ex[0]), fmt_ns(ex[1]), r["error"]))
            else:
                out.append(head + "| - | - | - | - | - | - | %s |" % r["error"])
            continue
        v = ns_per_node(r)
        b = best.get((r["n"], r["numbering"], r["threads"]))
        ratio = "%.2f" % (v / b) if v is not None and b else "-"
        c = r["counters"]
        misses = fmt_num(c["misses"]) if "misses" in c else "-"
        note = r["label"] if "misses_vs=" in r["label"] else ""
        note = note[note.find("misses_vs="):] if note else ""
        if "extra" in c:
            note += " %s pairs not in the reference" % fmt_num(c["extra"])
        out.append(head + "| %s | %s | %s | %s | %s | %s | %s |" % (
            fmt_time(r["time_ns"]), fmt_ns(v), ratio, fmt_num(c.get("pairs")),
            fmt_num(c.get("bytes_per_node")), misses, note.strip()))
    out.append("")


def fit_exponent(points):
    """Least-squares slope of log(time) against log(nsec)."""
    xs = [math.log(p[0]) for p in points]
    ys = [math.log(p[1]) for p in points]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    if sxx <= 0:
        return None
    return sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx


def print_scaling(families, search, out):
    lines = []
    tmax = max((r["threads"] for r in search), default=1)
    for fam in families:
        for algo in ALGOS:
            pts = sorted((r["counters"]["nsec"], r["time_ns"]) for r in search
                         if r["family"] == fam and r["algo"] == algo and not r["error"]
                         and r["numbering"] == "natural" and r["threads"] == tmax
                         and r["counters"].get("nsec"))
            if len(pts) < 2:
                continue
            k = fit_exponent(pts)
            if k is None:
                continue
            lines.append("| %s | %s | %.2f | %s – %s |" % (fam, algo, k, fmt_num(pts[0][0]),
                                                          fmt_num(pts[-1][0])))
    if not lines:
        return
    out.append("## Scaling: time ∝ nsec^k (natural numbering, %d threads)\n" % tmax)
    out.append("| family | algorithm | k | nsec range |")
    out.append("|---|---|---:|---|")
    out.extend(lines)
    out.append("")


def print_speedup(families, search, out):
    tmax = max((r["threads"] for r in search), default=1)
    if tmax <= 1:
        return
    ok = {(r["family"], r["algo"], r["numbering"], r["n"], r["threads"]): r for r in search
          if not r["error"] and r["time_ns"]}
    lines = []
    for fam in families:
        for algo in ALGOS:
            for num in NUMBERINGS:
                ns = [n for (f, a, nb, n, t) in ok if (f, a, nb, t) == (fam, algo, num, 1)
                      and (fam, algo, num, n, tmax) in ok]
                if not ns:
                    continue
                n = max(ns)
                t1 = ok[(fam, algo, num, n, 1)]["time_ns"]
                tm = ok[(fam, algo, num, n, tmax)]["time_ns"]
                s = t1 / tm
                lines.append("| %s | %s | %s | %d | %s | %s | %.2f | %.0f%% |" % (
                    fam, algo, num, n, fmt_time(t1), fmt_time(tm), s, 100.0 * s / tmax))
    if not lines:
        return
    out.append("## Speed-up, 1 → %d threads (largest size with both)\n" % tmax)
    out.append("| family | algorithm | numbering | nodes | 1 thread | %d threads | speed-up "
               "| efficiency |" % tmax)
    out.append("|---|---|---|---:|---:|---:|---:|---:|")
    out.extend(lines)
    out.append("")


def print_other(other, out):
    if not other:
        return
    out.append("## Other benchmarks\n")
    out.append("| benchmark | median time | note |")
    out.append("|---|---:|---|")
    for r in other:
        out.append("| %s | %s | %s |" % (r["name"], fmt_time(r["time_ns"]),
                                         r["error"] or r["label"]))
    out.append("")


def report(data):
    out = []
    print_context(data.get("context", {}), out)
    search, other = parse_search(collect(data.get("benchmarks", [])))
    families = []
    for r in search:
        if r["family"] not in families:
            families.append(r["family"])
    print_headline(search, out)
    if search:
        out.append("## Search cost per family\n")
        out.append("Median of the repetitions; ns/node = time per search / secondary nodes; "
                   "× best = ratio to the fastest algorithm at the same size, numbering and "
                   "threads; bytes/node = search workspace / secondary nodes.\n")
    for fam in families:
        print_family(fam, search, out)
    print_scaling(families, search, out)
    print_speedup(families, search, out)
    print_other(other, out)
    return "\n".join(out)


def main(argv):
    if len(argv) != 2:
        sys.stderr.write("usage: report.py BENCH.json\n")
        return 2
    try:
        with open(argv[1]) as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        sys.stderr.write("report.py: cannot read %s: %s\n" % (argv[1], e))
        return 1
    sys.stdout.write(report(data) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
