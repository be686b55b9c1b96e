#!/usr/bin/env python3
"""Turn the Google Benchmark JSON of `make bench` into Markdown tables.

Usage: python3 bench/report.py build/bench.json [build/bench-single.json ...]
       [build/trade_precision.json] > /tmp/x.md

Several files (e.g. a double and a single precision run) are merged: the
kernel and floor tables show them side by side (the precision of a file is
its context's ct_precision, else the precision= of ct_build, else the
"prec=" of its labels); the search tables are printed per file.

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
  - the kernels (kernels/<group>/<kernel>/t<threads>/<pairs>): ns per pair
    (the ns_per_pair counter) with 1 and the most threads, the parallel
    efficiency, per precision, and the single-precision speed-up when both
    precisions are given;
  - the hardware floor (floor/...): triad bandwidth, the byte model of the
    search, the floor in ns per node and the ratio measured / floor for the
    bucket search on plates (the floor benchmark's own run, and the search
    benchmark's bucket run of the same size and threads when present);
  - the peers (peer/<family>/<peer>[@<setting>]/t<threads>/<nodes>: nanoflann,
    CGAL, Bullet on the same meshes and query, their pair sets checked equal to
    our bucket search's): build and query ns per node, and the ratio of the
    peer's cost to our best search on the same family and size (natural
    numbering, any thread count);
  - the speed/accuracy trade (trade/<knob>/<setting>, bench_trade.c): one row
    per knob setting with its cost and accuracy counters, the measures named
    by the label ("knob=K setting=S; cost: ...; accuracy: ...; prec=P case"),
    the x_* counters as further figures; the precision rows merge the files'
    trade/precision/<prec> runs, and their accuracy comes from the output of
    bench/trade_precision.py --json when that file is given too (a file with
    a top-level "trade_precision" key is that output, not a benchmark run);
  - the full contact cycle (cycle/<family>/t<threads>/<nodes>, bench_cycle.c):
    per precision, one row per family, size and threads with the ns per node
    per cycle of each phase (the search amortised over the re-sort interval),
    the total, the total times the threads against the target of 15 ns, and
    the speed-up over the 1-thread row of the same family and size;
  - the ratio targets of the search measured in interleaved rounds
    (paired/<family>/<b>-vs-<a>/t<threads>/<nodes>, bench_paired.c), with
    the issue's target;
  - the parallel efficiency measured in interleaved rounds
    (efficiency/<kernel>/t<threads>/<n>, bench_eff.c), kernels and the DRAM
    triad, against the target of 90 %;
  - the single-precision speed-up measured in interleaved rounds, from the
    output of bench/interleave.py --json when that file is given (a file
    with a top-level "interleaved" key);
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
COUNTERS = ["ns_per_node", "nsec", "nseg", "pairs", "bytes_per_node", "misses", "extra",
            "ns_per_pair", "threads", "npair", "active", "fallbacks", "ncolour", "GBps",
            "array_MiB", "GBps_dram", "GBps_ws", "floor_bytes_per_node", "floor_ns_dram",
            "floor_ns_ws", "ratio_dram", "ratio_ws", "nnode", "bytes_per_pair",
            "stream_bytes_per_pair"]
# The peers' benchmarks (bench_peers.c).
PEER_RE = re.compile(
    r"^peer/(?P<family>[^/]+)/(?P<peer>[^/@]+)(?:@(?P<setting>[^/]+))?/t(?P<threads>\d+)/"
    r"(?P<n>\d+)$")
COUNTERS += [c for c in ("build_ns_per_node", "query_ns_per_node", "candidates", "threads")
             if c not in COUNTERS]
KERNEL_RE = re.compile(
    r"^kernels/(?P<group>[^/]+)/(?P<kernel>[^/]+)/t(?P<threads>\d+)/(?P<n>\d+)"
    r"(?:/iterations:\d+)?(?:/(?:real_time|manual_time))?$")
FLOOR_RE = re.compile(
    r"^floor/(?P<what>triad/dram|triad/ws|bucket/plates)/t(?P<threads>\d+)/(?P<n>\d+)"
    r"(?:/iterations:\d+)?(?:/(?:real_time|manual_time))?$")
KERNEL_GROUPS = ["narrow", "force", "prepare", "assemble"]
# The speed/accuracy trade (bench_trade.c).
TRADE_RE = re.compile(
    r"^trade/(?P<knob>[^/]+)/(?P<setting>[^/]+)(?:/iterations:\d+)?"
    r"(?:/(?:real_time|manual_time))?$")
TRADE_KNOBS = ["search", "filter", "margin", "renumber", "dense", "quad", "precision", "assembly", "skip",
               "stiffness", "safety"]
COUNTERS += ["cost", "accuracy"]
# The full contact cycle (bench_cycle.c); its ns_* counters are ns per node
# per cycle, wall time.
CYCLE_RE = re.compile(
    r"^cycle/(?P<family>[^/]+)/t(?P<threads>\d+)/(?P<n>\d+)(?:/iterations:\d+)?"
    r"(?:/(?:real_time|manual_time))?$")
CYCLE_PHASES = ["ns_search", "ns_narrow", "ns_force", "ns_assemble", "ns_timestep"]
CYCLE_TARGET_NS = 15.0
COUNTERS += [c for c in CYCLE_PHASES + [
    "ns_total", "ns_total_x_threads", "ns_per_sort", "ns_check", "resort_interval",
    "resort_interval_seen", "cand_per_node", "eval_per_node", "active_per_node", "nodes"] if c not in COUNTERS]
# The ratio targets measured in interleaved rounds (bench_paired.c):
# paired/<family>/<b>-vs-<a>/t<threads>/<nodes>.
PAIRED_RE = re.compile(
    r"^paired/(?P<family>[^/]+)/(?P<what>[^/]+)/t(?P<threads>\d+)/(?P<n>\d+)"
    r"(?:/iterations:\d+)?(?:/(?:real_time|manual_time))?$")
COUNTERS += ["ns_a", "ns_b", "ratio", "ratio_min", "ratio_max", "rounds", "pairs_a", "pairs_b",
             "same_pairs"]
# The target for a (family, comparison): its text and its test.
PAIRED_TARGETS = {
    ("plates", "bsp-vs-bucket"): ("≤ 2 (issue 2: bsp within 2× of bucket, uniform mesh)",
                                  lambda r: r <= 2),
    ("graded", "bsp-vs-bucket"): ("< 1 (issue 2: bsp faster than bucket, graded mesh)",
                                  lambda r: r < 1),
    ("plates", "bucket-shuffled-vs-natural"): ("≤ 1.5 (issue 2: shuffled within 1.5× of "
                                               "ordered)", lambda r: r <= 1.5),
}
# The 2-thread efficiency target measured in interleaved rounds
# (bench_eff.c): efficiency/<kernel or triad/dram>/t<threads>/<n>.
EFF_RE = re.compile(
    r"^efficiency/(?P<what>.+?)/t(?P<threads>\d+)/(?P<n>\d+)"
    r"(?:/iterations:\d+)?(?:/(?:real_time|manual_time))?$")
COUNTERS += ["ns_t1", "ns_tn", "eff", "eff_min", "eff_max", "eff_best", "calls"]
EFF_TARGET = 0.9
# The driver's shell element forces (bench_elements.c):
# elements/shell/<mesh>/t<threads>/<nodes>.
ELEM_RE = re.compile(
    r"^elements/(?P<element>[^/]+)/(?P<family>[^/]+)/t(?P<threads>\d+)/(?P<n>\d+)"
    r"(?:/iterations:\d+)?(?:/(?:real_time|manual_time))?$")
COUNTERS += ["ns_per_elem", "ns_per_node", "elements", "triangles", "hinges"]
# Whole runs of the driver's scenes (bench_scene.c):
# scene/<name>/t<threads>/<cycles>.
SCENE_RE = re.compile(
    r"^scene/(?P<scene>[^/]+)/t(?P<threads>\d+)/(?P<n>\d+)"
    r"(?:/iterations:\d+)?(?:/(?:real_time|manual_time))?$")
COUNTERS += ["ns_per_node_cycle", "us_per_cycle", "cycles", "elements_share", "contact_share",
             "other_share"]
PREC_ORDER = ["double", "single"]


def base_name(run_name):
    return re.sub(r"(/iterations:\d+)?/(real_time|manual_time)$", "", run_name)


def counter_names(b):
    """The counters to keep of one JSON row: the known ones, then any x_*."""
    return COUNTERS + [k for k in b if k.startswith("x_") and k not in COUNTERS]


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
            for c in counter_names(src):
                if c in src:
                    rec["counters"][c] = float(src[c])
        elif r["reps"]:
            reps = r["reps"]
            rec["time_ns"] = statistics.median(
                x["real_time"] * TIME_NS[x.get("time_unit", "ns")] for x in reps)
            rec["label"] = reps[-1].get("label", "")
            for c in counter_names(reps[0]):
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


def split_named(records, regex):
    """Split the records whose name matches regex (groups threads and n among
    its named groups, which become fields) from the others."""
    hit, rest = [], []
    for r in records:
        m = regex.match(r["name"])
        if not m:
            rest.append(r)
            continue
        r.update(m.groupdict())
        r["threads"] = int(r["threads"])
        r["n"] = int(r["n"])
        hit.append(r)
    return hit, rest


def parse_search(records):
    return split_named(records, NAME_RE)


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


def parse_peers(other):
    peers, rest = [], []
    for r in other:
        m = PEER_RE.match(r["name"])
        if not m:
            rest.append(r)
            continue
        r.update(m.groupdict())
        r["threads"] = int(r["threads"])
        r["n"] = int(r["n"])
        r["tuned"] = not r["setting"]
        if not r["setting"]:
            lab = r["label"] or ""
            r["setting"] = lab.split(" same_as")[0].replace(" (tuned)", "") if lab else "-"
        peers.append(r)
    return peers, rest


def our_best(search, family, n):
    """Our fastest search (ns per node) on the same family and size, natural
    numbering, any thread count: (ns/node, algorithm, threads) or None."""
    best = None
    for r in search:
        if r["error"] or r["family"] != family or r["n"] != n or r["numbering"] != "natural":
            continue
        v = ns_per_node(r)
        if v is not None and (best is None or v < best[0]):
            best = (v, r["algo"], r["threads"])
    return best


def print_peers(peers, search, out):
    if not peers:
        return
    out.append("## Peers: the same query on the same meshes\n")
    out.append("Each peer's pairs, after the project's exact filter, are checked equal to "
               "the bucket search's before timing. ns/node = build + query per secondary "
               "node; × ours = peer ns/node / our best search's ns/node on the same family "
               "and size (natural numbering, any threads).\n")
    out.append("| family | nodes | peer | setting | threads | build ns/node | query ns/node "
               "| ns/node | ours (best) | × ours | pairs |")
    out.append("|---|---:|---|---|---:|---:|---:|---:|---|---:|---:|")
    rows = sorted(peers, key=lambda r: (r["family"], r["n"], not r["tuned"], r["peer"],
                                        r["setting"], r["threads"]))
    for r in rows:
        head = "| %s | %d | %s | %s | %d " % (r["family"], r["n"], r["peer"], r["setting"],
                                              r["threads"])
        if r["error"]:
            out.append(head + "| - | - | - | - | - | - | %s |" % r["error"])
            continue
        c = r["counters"]
        v = c.get("ns_per_node")
        if v is None:
            v = ns_per_node(r)
        b = our_best(search, r["family"], r["n"])
        ours = "%s %s t%d" % (fmt_ns(b[0]), b[1], b[2]) if b else "-"
        ratio = "%.1f" % (v / b[0]) if b and v is not None and b[0] > 0 else "-"
        out.append(head + "| %s | %s | %s | %s | %s | %s |" % (
            fmt_ns(c.get("build_ns_per_node")), fmt_ns(c.get("query_ns_per_node")), fmt_ns(v),
            ours, ratio, fmt_num(c.get("pairs"))))
    out.append("")


def parse_trade(other, prec):
    """Split the trade records (trade/<knob>/<setting>) from the others and
    parse their labels."""
    trade, rest = [], []
    for r in other:
        m = TRADE_RE.match(r["name"])
        if not m:
            rest.append(r)
            continue
        r.update(m.groupdict())
        lab = r["label"] or ""
        parts = [p.strip() for p in lab.split("; ", 3)]
        r["cost_what"], r["acc_what"], r["case"] = "", "", ""
        for p in parts[1:]:
            if p.startswith("cost: "):
                r["cost_what"] = p[6:]
            elif p.startswith("accuracy: "):
                r["acc_what"] = p[10:]
            else:
                r["case"] = p
        lm = re.search(r"prec=(\w+)", lab)
        r["prec"] = lm.group(1) if lm else prec
        r["case"] = re.sub(r"^prec=\w+\s*", "", r["case"])
        trade.append(r)
    return trade, rest


def fmt_val(v):
    if v is None:
        return "-"
    if v == 0:
        return "0"
    if abs(v) >= 1e5 or abs(v) < 1e-3:
        return "%.2e" % v
    return "%.4g" % v


def print_trade(trade, compare, out):
    """The speed/accuracy table: one row per knob setting (and precision)."""
    if not trade:
        return
    korder = {k: i for i, k in enumerate(TRADE_KNOBS)}
    rows = sorted(enumerate(trade), key=lambda ir: (korder.get(ir[1]["knob"], 99), ir[0]))
    out.append("## Speed/accuracy trade\n")
    out.append("One row per setting of each knob (DESIGN.md section 10): the cost and the "
               "accuracy figure the knob changes, both measured in the benchmark run "
               "(median of the repetitions; the measures are named in each row, the cases "
               "under the table). Other figures are the run's further counters.\n")
    out.append("| knob | setting | precision | cost | cost measure | accuracy | accuracy measure "
               "| other figures |")
    out.append("|---|---|---|---:|---|---:|---|---|")
    cost_double = {}
    for r in trade:
        if r["knob"] == "precision" and r["prec"] == "double" and not r["error"]:
            cost_double[r["knob"]] = r["counters"].get("cost")
    cases = []
    for _, r in rows:
        head = "| %s | %s | %s " % (r["knob"], r["setting"], r["prec"])
        if r["error"]:
            out.append(head + "| - | - | - | - | %s |" % r["error"])
            continue
        c = r["counters"]
        acc = fmt_val(c.get("accuracy"))
        other = ["%s=%s" % (k[2:], fmt_val(v)) for k, v in c.items() if k.startswith("x_")]
        if r["knob"] == "precision":
            cd = cost_double.get("precision")
            if r["prec"] == "double":
                acc = "0 (reference)"
            elif compare and compare.get("other") == r["prec"]:
                acc = fmt_val(compare.get("max_rel_pen"))
                other += ["max_dpen_over_gap=%s" % fmt_val(compare.get("max_pen_err_gap")),
                          "max_dnormal=%s" % fmt_val(compare.get("max_normal_diff")),
                          "max_ddist_over_h=%s" % fmt_val(compare.get("max_dist_err_h")),
                          "active_mismatch=%d" % compare.get("active_mismatch", 0),
                          "unmatched=%d+%d" % (compare.get("only_reference", 0),
                                               compare.get("only_other", 0))]
            else:
                acc = "- (run bench/trade_precision.py)"
            if cd and c.get("cost") and r["prec"] != "double":
                other.append("cost_vs_double=%.2f" % (c["cost"] / cd))
        out.append(head + "| %s | %s | %s | %s | %s |" % (
            fmt_val(c.get("cost")), r["cost_what"], acc, r["acc_what"], ", ".join(other)))
        note = (r["knob"], r["case"])
        if r["case"] and note not in cases:
            cases.append(note)
    out.append("")
    if cases:
        out.append("Cases:\n")
        for knob, case in cases:
            out.append("- %s: %s" % (knob, case))
        out.append("")


def parse_cycle(other, prec):
    """Split the full contact cycle records (cycle/<family>/t<threads>/<nodes>)
    from the others; the precision is the label's prec=, else the file's."""
    cyc, rest = split_named(other, CYCLE_RE)
    for r in cyc:
        lm = re.match(r"prec=(\w+)", r["label"] or "")
        r["prec"] = lm.group(1) if lm else prec
    return cyc, rest


def print_cycle(cyc, out):
    """The full contact cycle: per precision, one row per family, size and
    threads, sorted in that order."""
    if not cyc:
        return
    out.append("## Full contact cycle\n")
    out.append("Median of the repetitions, in ns per node per cycle (wall time); search "
               "amortised over the re-sort interval (check per cycle + one search / "
               "interval); evaluated = the candidates through the narrow phase (the others "
               "proved out of contact by the skip); × threads = total × threads, the per-thread figure of the target "
               "of issue 5 (≤ %s ns/node/cycle per thread); speed-up = total with 1 thread / "
               "total with this row's threads.\n" % fmt_num(CYCLE_TARGET_NS))
    present = sorted(set(r["prec"] for r in cyc),
                     key=lambda p: (PREC_ORDER.index(p) if p in PREC_ORDER else 99, p))
    for p in present:
        rows = sorted((r for r in cyc if r["prec"] == p),
                      key=lambda r: (r["family"], r["n"], r["threads"]))
        one = {(r["family"], r["n"]): r["counters"].get("ns_total") for r in rows
               if r["threads"] == 1 and not r["error"]}
        out.append("### %s precision\n" % p)
        out.append("| family | nodes | threads | candidates/node | evaluated/node | active/node "
                   "| re-sort interval (cycles) | search (amortised) | narrow | force | assembly "
                   "| time step | total ns/node/cycle | × threads (per thread) "
                   "| vs target %s | speed-up |" % fmt_num(CYCLE_TARGET_NS))
        out.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:"
                   "|---:|")
        for r in rows:
            head = "| %s | %d | %d " % (r["family"], r["n"], r["threads"])
            if r["error"]:
                out.append(head + "| %s | - | - | - | - | - | - | - | - | - | - | - | - |"
                           % r["error"])
                continue
            c = r["counters"]
            interval = fmt_num(c.get("resort_interval"))
            if "resort_interval_seen" in c:
                # The interval the interface saw, when it re-sorted by itself.
                interval += " (seen %s)" % fmt_num(c["resort_interval_seen"])
            total, per_thread = c.get("ns_total"), c.get("ns_total_x_threads")
            target = "%.1f×" % (per_thread / CYCLE_TARGET_NS) if per_thread is not None \
                else "-"
            t1 = one.get((r["family"], r["n"]))
            speedup = "%.2f" % (t1 / total) if r["threads"] > 1 and t1 and total else "-"
            out.append(head + "| %s | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                fmt_num(c.get("cand_per_node"), 2), fmt_num(c.get("eval_per_node"), 2),
                fmt_num(c.get("active_per_node"), 2),
                interval, " | ".join(fmt_ns(c.get(k)) for k in CYCLE_PHASES), fmt_ns(total),
                fmt_ns(per_thread), target, speedup))
        out.append("")


def print_elements(rows, out):
    """The driver's element forces: one row per element kind, mesh, size and
    threads."""
    if not rows:
        return
    out.append("## Element forces (the driver)\n")
    out.append("Median of the repetitions; one call of the element forces per iteration "
               "(wall time); speed-up = time with 1 thread / time with this row's threads.\n")
    out.append("| element | mesh | nodes | elements | triangles | hinges | threads "
               "| ns/element | ns/node | speed-up |")
    out.append("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    rows = sorted(rows, key=lambda r: (r["element"], r["family"], r["n"], r["threads"]))
    one = {(r["element"], r["family"], r["n"]): r["counters"].get("ns_per_elem")
           for r in rows if r["threads"] == 1 and not r["error"]}
    for r in rows:
        head = "| %s | %s | %d " % (r["element"], r["family"], r["n"])
        if r["error"]:
            out.append(head + "| - | - | - | %d | %s | - | - |" % (r["threads"], r["error"]))
            continue
        c = r["counters"]
        t1 = one.get((r["element"], r["family"], r["n"]))
        ns = c.get("ns_per_elem")
        speedup = "%.2f" % (t1 / ns) if r["threads"] > 1 and t1 and ns else "-"
        out.append(head + "| %s | %s | %s | %d | %s | %s | %s |" % (
            fmt_num(c.get("elements"), 0), fmt_num(c.get("triangles"), 0),
            fmt_num(c.get("hinges"), 0), r["threads"], fmt_ns(ns),
            fmt_ns(c.get("ns_per_node")), speedup))
    out.append("")


def print_scenes(rows, out):
    """Whole runs of the driver: one row per scene and thread count."""
    if not rows:
        return
    out.append("## Whole runs (the driver)\n")
    out.append("Median of the repetitions; one iteration is a run of the scene from its start "
               "for the given cycles, no output written (bench_scene.c); the split is the "
               "run's own timers; speed-up = time with 1 thread / time with this row's "
               "threads.\n")
    out.append("| scene | nodes | cycles | threads | µs/cycle | ns/node/cycle | elements "
               "| contact | other | speed-up |")
    out.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    rows = sorted(rows, key=lambda r: (r["scene"], r["threads"]))
    one = {r["scene"]: r["counters"].get("ns_per_node_cycle")
           for r in rows if r["threads"] == 1 and not r["error"]}
    pct = lambda v: "%.0f %%" % (100 * v) if v is not None else "-"
    for r in rows:
        if r["error"]:
            out.append("| %s | - | %d | %d | %s | - | - | - | - | - |" % (
                r["scene"], r["n"], r["threads"], r["error"]))
            continue
        c = r["counters"]
        t1, ns = one.get(r["scene"]), c.get("ns_per_node_cycle")
        speedup = "%.2f" % (t1 / ns) if r["threads"] > 1 and t1 and ns else "-"
        out.append("| %s | %s | %s | %d | %s | %s | %s | %s | %s | %s |" % (
            r["scene"], fmt_num(c.get("nodes"), 0), fmt_num(c.get("cycles"), 0),
            r["threads"], fmt_ns(c.get("us_per_cycle")), fmt_ns(ns),
            pct(c.get("elements_share")), pct(c.get("contact_share")),
            pct(c.get("other_share")), speedup))
    out.append("")


def parse_paired(other):
    """Split the paired records (paired/<family>/<b>-vs-<a>/t<threads>/<nodes>)
    from the others."""
    return split_named(other, PAIRED_RE)


def print_paired(paired, out):
    """One row per paired benchmark: both searches' ns per node, the median of
    the rounds' ratios, their range, and the issue's target when it has one."""
    if not paired:
        return
    out.append("## Ratio targets, measured in interleaved rounds\n")
    out.append("Each row times two searches in one benchmark, one whole search of each per "
               "round, alternating which runs first (bench_paired.c), so that both see the "
               "same state of the host. a and b: median ns per secondary node over the "
               "rounds; ratio: the median of the rounds' b / a (median of the repetitions); "
               "range: the smallest and largest round's ratio (medians of the "
               "repetitions).\n")
    out.append("| family | nodes | threads | b vs a | a ns/node | b ns/node | ratio b/a "
               "| range | same pairs | target | met? |")
    out.append("|---|---:|---:|---|---:|---:|---:|---|---|---|---|")
    for r in sorted(paired, key=lambda r: (r["family"], r["what"], r["n"], r["threads"])):
        head = "| %s | %d | %d | %s " % (r["family"], r["n"], r["threads"], r["what"])
        tgt = PAIRED_TARGETS.get((r["family"], r["what"]))
        if r["error"]:
            out.append(head + "| %s | - | - | - | - | %s | - |" % (r["error"],
                                                                 tgt[0] if tgt else "-"))
            continue
        c = r["counters"]
        ratio = c.get("ratio")
        same = c.get("same_pairs")
        same_s = "-" if same is None else ("yes" if same == 1 else "**no**")
        rng = "-"
        if c.get("ratio_min") is not None and c.get("ratio_max") is not None:
            rng = "%.2f-%.2f" % (c["ratio_min"], c["ratio_max"])
        met = "-"
        if tgt and ratio is not None:
            met = "yes" if tgt[1](ratio) else "**no**"
        out.append(head + "| %s | %s | %s | %s | %s | %s | %s |" % (
            fmt_ns(c.get("ns_a")), fmt_ns(c.get("ns_b")),
            "%.2f" % ratio if ratio is not None else "-", rng, same_s,
            tgt[0] if tgt else "-", met))
    out.append("")


# The single-precision speed-up target of issue 3 (kernel rows, 1 thread).
SINGLE_TARGET = 1.6


def print_interleaved(inter, out):
    """The ratio of one counter between two programs run in alternating
    rounds (bench/interleave.py): in `make bench`, the double and the single
    precision builds, so the ratio is the single build's speed-up."""
    if not inter or not inter.get("rows"):
        return
    out.append("## Single-precision speed-up, measured in interleaved rounds\n")
    out.append("The double (a) and single (b) precision programs run one after the other "
               "in %d rounds, alternating which goes first, one repetition each "
               "(bench/interleave.py; filter `%s`), so that both see the same state of the "
               "host. a and b: median %s over the rounds; speed-up: the median of the "
               "rounds' a / b; range: the smallest and largest round's. Target of issue 3: "
               "single precision at least %.1f× faster.\n"
               % (inter.get("rounds", 0), inter.get("filter", ""), inter.get("counter", ""),
                  SINGLE_TARGET))
    out.append("| benchmark | a (double) | b (single) | speed-up a/b | range | ≥ %.1f? |"
               % SINGLE_TARGET)
    out.append("|---|---:|---:|---:|---|---|")
    for r in inter["rows"]:
        met = "yes" if r["ratio"] >= SINGLE_TARGET else "**no**"
        out.append("| %s | %s | %s | %.2f | %.2f-%.2f | %s |" % (
            r["name"], fmt_ns(r["a"]), fmt_ns(r["b"]), r["ratio"], r["ratio_min"],
            r["ratio_max"], met))
    out.append("")


def print_eff(rows, out):
    """The efficiency rows: the kernels (ns per pair) and the DRAM triad
    (GB/s), against the target of issue 3."""
    if not rows:
        return
    out.append("## Parallel efficiency, measured in interleaved rounds\n")
    out.append("Each row times one call with 1 thread and with all threads, round after "
               "round, alternating which goes first (bench_eff.c; a timing is the median of "
               "a few calls lasting about 20 ms). efficiency: the median of the rounds' "
               "t1 / (threads × tN); range: the smallest and largest round's; best: from "
               "the best 1-thread and all-threads times (a busy host only adds time). "
               "Target of issue 3: at least %d %%. The DRAM triad is the machine's own "
               "efficiency on a loop that only streams memory: the ceiling of the kernels "
               "that stream their pairs from memory; compute, on a loop that only computes "
               "(multiply-adds in registers): the ceiling of the kernels bound by their "
               "arithmetic, below %d %% when the host's second core was not all ours.\n"
               % (round(100 * EFF_TARGET), round(100 * EFF_TARGET)))
    out.append("| benchmark | size | threads | 1 thread | all threads | efficiency | range "
               "| best | ≥ %d %%? |" % round(100 * EFF_TARGET))
    out.append("|---|---:|---:|---:|---:|---:|---|---:|---|")
    ceil = lambda w: w.startswith("triad") or w == "compute"
    for r in sorted(rows, key=lambda r: (ceil(r["what"]), r["what"], r["n"])):
        head = "| %s | %d | %d " % (r["what"], r["n"], r["threads"])
        if r["error"]:
            out.append(head + "| %s | - | - | - | - | - |" % r["error"])
            continue
        c = r["counters"]
        t1, tn = c.get("ns_t1"), c.get("ns_tn")
        ceiling = r["what"].startswith("triad") or r["what"] == "compute"
        if r["what"].startswith("triad"):
            a = "%.1f GB/s" % (1 / t1) if t1 else "-"
            b = "%.1f GB/s" % (1 / tn) if tn else "-"
        elif r["what"] == "compute":
            a = "%.1f G mul-add/s" % (1 / t1) if t1 else "-"
            b = "%.1f G mul-add/s" % (1 / tn) if tn else "-"
        else:
            a = "%s ns/pair" % fmt_ns(t1) if t1 is not None else "-"
            b = "%s ns/pair" % fmt_ns(tn) if tn is not None else "-"
        e = c.get("eff")
        pct = lambda v: "%d %%" % round(100 * v) if v is not None else "-"
        rng = "%s-%s" % (pct(c.get("eff_min")), pct(c.get("eff_max")))
        met = "-" if e is None else ("yes" if e >= EFF_TARGET else "**no**")
        if ceiling:
            met = "(ceiling)"
        out.append(head + "| %s | %s | %s | %s | %s | %s |" % (a, b, pct(e), rng,
                                                              pct(c.get("eff_best")), met))
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


def precision_of(data):
    """The precision of one benchmark file: ct_precision, ct_build's
    precision=, or the first label's prec=."""
    ctx = data.get("context", {})
    if ctx.get("ct_precision"):
        return ctx["ct_precision"]
    m = re.search(r"precision=(\w+)", ctx.get("ct_build", ""))
    if m:
        return m.group(1)
    for b in data.get("benchmarks", []):
        m = re.match(r"prec=(\w+)", b.get("label", ""))
        if m:
            return m.group(1)
    return "?"


def split_records(records, prec):
    """Kernel, floor and other records; kernel and floor records get their
    fields parsed and the precision (label's prec=, else the file's)."""
    kern, flo, other = [], [], []
    for r in records:
        m = KERNEL_RE.match(r["name"]) or FLOOR_RE.match(r["name"])
        if not m:
            other.append(r)
            continue
        r.update(m.groupdict())
        r["threads"] = int(r["threads"])
        r["n"] = int(r["n"])
        lm = re.match(r"prec=(\w+)", r["label"] or "")
        r["prec"] = lm.group(1) if lm else prec
        (kern if "group" in r else flo).append(r)
    return kern, flo, other


def kernel_setting(label):
    """The setting named in a kernel label: after prec=..., up to ';'."""
    label = re.sub(r"^prec=\w+\s*", "", label or "")
    return label.split(";")[0].strip()


def print_kernels(kern, precs, out):
    if not kern:
        return
    tmax = max(r["threads"] for r in kern)
    rows, cells = [], {}
    for r in kern:
        key = (r["group"], r["kernel"], r["n"])
        if key not in cells:
            cells[key] = {}
            rows.append(key)
        cells[key][(r["prec"], r["threads"])] = r
    gorder = {g: i for i, g in enumerate(KERNEL_GROUPS)}
    first = {}
    for i, k in enumerate(rows):
        first.setdefault((k[0], k[1]), i)
    rows.sort(key=lambda k: (gorder.get(k[0], 99), first[(k[0], k[1])], k[2]))

    def ns(rec):
        if rec is None or rec["error"]:
            return None
        return rec["counters"].get("ns_per_pair")

    out.append("## Kernels: ns per pair\n")
    out.append("Median of the repetitions of the ns_per_pair counter (wall time per call / "
               "pairs); pairs in node order (plates case, bucket search); efficiency = "
               "ns(1 thread) / (%d × ns(%d threads)). The setting is the benchmark's label."
               "\n" % (tmax, tmax))
    head = "| kernel | setting | pairs |"
    rule = "|---|---|---:|"
    for p in precs:
        head += " %s 1 thr | %s %d thr | %s eff. |" % (p, p, tmax, p)
        rule += "---:|---:|---:|"
    both = "double" in precs and "single" in precs
    if both:
        head += " single speed-up (1 thr) |"
        rule += "---:|"
    out.append(head)
    out.append(rule)
    for key in rows:
        c = cells[key]
        setting = ""
        for p in precs:
            for t in (1, tmax):
                rec = c.get((p, t))
                if rec is not None and not setting:
                    setting = kernel_setting(rec["label"]) or (rec["error"] or "")
        line = "| %s/%s | %s | %d |" % (key[0], key[1], setting, key[2])
        for p in precs:
            a, b = ns(c.get((p, 1))), ns(c.get((p, tmax)))
            err = c.get((p, 1)) or c.get((p, tmax))
            if a is None and b is None and err is not None and err["error"]:
                line += " %s | - | - |" % err["error"]
                continue
            eff = "%.0f%%" % (100.0 * a / (tmax * b)) if a and b and tmax > 1 else "-"
            line += " %s | %s | %s |" % (fmt_ns(a) if a is not None else "-",
                                         fmt_ns(b) if b is not None and tmax > 1 else "-", eff)
        if both:
            a, b = ns(c.get(("double", 1))), ns(c.get(("single", 1)))
            line += " %s |" % ("%.2f" % (a / b) if a and b else "-")
        out.append(line)
    out.append("")


def triad_gbps(flo):
    """{threads: the best dram triad GB/s (STREAM's count) of any file}."""
    bw = {}
    for r in flo:
        g = r["counters"].get("GBps")
        if r["what"] == "triad/dram" and not r["error"] and g:
            bw[r["threads"]] = max(bw.get(r["threads"], 0), g)
    return bw


def print_kernel_floor(kern, flo, out):
    """The kernels at their largest pair count against the memory floor."""
    bw = triad_gbps(flo)
    rows = [r for r in kern if not r["error"] and "bytes_per_pair" in r["counters"]]
    if not rows or not bw:
        return
    nmax = {}
    for r in rows:
        key = (r["group"], r["kernel"])
        nmax[key] = max(nmax.get(key, 0), r["n"])
    rows = [r for r in rows if r["n"] == nmax[(r["group"], r["kernel"])]
            and r["threads"] in bw]
    gorder = {g: i for i, g in enumerate(KERNEL_GROUPS)}
    first = {}
    for i, r in enumerate(kern):
        first.setdefault((r["group"], r["kernel"]), i)
    rows.sort(key=lambda r: (gorder.get(r["group"], 99), first[(r["group"], r["kernel"])],
                             PREC_ORDER.index(r["prec"]) if r["prec"] in PREC_ORDER else 99,
                             r["threads"]))
    out.append("## Kernels against the memory floor\n")
    out.append("At the largest pair count. bytes/pair: the least any implementation of the "
               "call must move (bench/floor.h: every array the call reads read once, every "
               "array it writes written once; node and segment arrays once per node or "
               "segment the pairs touch); floor = bytes / the dram triad bandwidth of the "
               "run with the same threads (STREAM's count, as for the search); ratio = "
               "measured / floor: near 1 the kernel is bound by memory, far above it by its "
               "arithmetic or latency. bound: the per-pair arrays alone (they exceed the "
               "last-level cache several times and must cross the memory bus) at the "
               "triad's real traffic, its write-allocate read counted (4/3 of its GB/s): "
               "no call with these arrays can run faster on this machine.\n")
    out.append("| kernel | precision | pairs | threads | bytes/pair | GB/s | floor ns/pair | "
               "per-pair bytes | bound ns/pair | measured ns/pair | ratio |")
    out.append("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        c = r["counters"]
        g = bw[r["threads"]]
        floor = c["bytes_per_pair"] / g
        sb = c.get("stream_bytes_per_pair")
        bound = "%.2f" % (sb / (g * 4.0 / 3.0)) if sb else "-"
        ns = c.get("ns_per_pair")
        out.append("| %s/%s | %s | %d | %d | %.1f | %.2f | %.2f | %s | %s | %s | %s |" % (
            r["group"], r["kernel"], r["prec"], r["n"], r["threads"], c["bytes_per_pair"], g,
            floor, "%.1f" % sb if sb else "-", bound, fmt_ns(ns) if ns else "-",
            "%.1f" % (ns / floor) if ns and floor > 0 else "-"))
    out.append("")


def print_floor(flo, searches, out):
    """searches: {precision: search records of that file}."""
    bucket = [r for r in flo if r["what"] == "bucket/plates"]
    triads = [r for r in flo if r["what"].startswith("triad/")]
    if not flo:
        return
    out.append("## Hardware floor\n")
    if triads:
        out.append("Triad a[i] = b[i] + s·c[i], 24 bytes per element (STREAM's count); "
                   "dram: arrays together 4× the last-level cache; ws: arrays the size of the "
                   "search's working set.\n")
        out.append("| precision | kind | threads | MiB per array | GB/s |")
        out.append("|---|---|---:|---:|---:|")
        for r in sorted(triads, key=lambda r: (r["prec"], r["what"], r["threads"])):
            c = r["counters"]
            out.append("| %s | %s | %d | %s | %s |" % (
                r["prec"], r["what"][6:], r["threads"], fmt_num(c.get("array_MiB"), 0),
                "%.2f" % c["GBps"] if "GBps" in c else (r["error"] or "-")))
        out.append("")
    if not bucket:
        return
    out.append("Bucket search on plates against its floor: bytes/node is the minimum any "
               "search must move per secondary node (secondary list, coordinates of the "
               "touched nodes, main connectivity, pairs written; bench/floor.h); floor = "
               "bytes / best triad bandwidth of the run with the same threads; ratio = "
               "measured / floor. \"search run\" is the search benchmark's bucket on plates "
               "(natural numbering) of the same size and threads.\n")
    out.append("| precision | nodes | threads | bytes/node | GB/s dram | floor ns/node | "
               "measured ns/node | ratio | GB/s ws | floor ns/node (ws) | ratio (ws) "
               "| search run ns/node | its ratio |")
    out.append("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in sorted(bucket, key=lambda r: (r["prec"], r["n"], r["threads"])):
        c = r["counters"]
        if r["error"]:
            out.append("| %s | %d | %d | %s | - | - | - | - | - | - | - | - | - |" % (
                r["prec"], r["n"], r["threads"], r["error"]))
            continue
        sv, sr = "-", "-"
        for s in searches.get(r["prec"], []):
            if (s["family"], s["algo"], s["numbering"], s["n"], s["threads"]) == \
                    ("plates", "bucket", "natural", r["n"], r["threads"]) and not s["error"]:
                v = ns_per_node(s)
                fd = c.get("floor_ns_dram")
                if v is not None:
                    sv = fmt_ns(v)
                    sr = "%.1f" % (v / fd) if fd and fd > 0 else "-"
        out.append("| %s | %d | %d | %.1f | %.2f | %.2f | %s | %.1f | %.2f | %.2f | %.1f "
                   "| %s | %s |" % (
                       r["prec"], r["n"], r["threads"], c.get("floor_bytes_per_node", 0),
                       c.get("GBps_dram", 0), c.get("floor_ns_dram", 0),
                       fmt_ns(c.get("ns_per_node")), c.get("ratio_dram", 0),
                       c.get("GBps_ws", 0), c.get("floor_ns_ws", 0), c.get("ratio_ws", 0),
                       sv, sr))
    out.append("")


def report_search(data, search, out):
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


def report(datas, names=None, compare=None, inter=None):
    """datas: one parsed JSON file, or a list of them (merged); compare: the
    "trade_precision" object of bench/trade_precision.py, or None; inter:
    the "interleaved" object of bench/interleave.py, or None."""
    if isinstance(datas, dict):
        datas = [datas]
    names = names or ["file %d" % (i + 1) for i in range(len(datas))]
    multi = len(datas) > 1
    out = []
    files = []
    for data, name in zip(datas, names):
        prec = precision_of(data)
        tag = prec
        k = 2
        while tag in [f["tag"] for f in files]:
            tag = "%s#%d" % (prec, k)
            k += 1
        search, rest = parse_search(collect(data.get("benchmarks", [])))
        kern, flo, other = split_records(rest, tag)
        peers, other = parse_peers(other)
        trade, other = parse_trade(other, tag)
        cyc, other = parse_cycle(other, tag)
        paired, other = parse_paired(other)
        eff, other = split_named(other, EFF_RE)
        elem, other = split_named(other, ELEM_RE)
        scen, other = split_named(other, SCENE_RE)
        files.append({"tag": tag, "name": name, "data": data, "search": search,
                      "kern": kern, "flo": flo, "other": other, "peers": peers,
                      "trade": trade, "cycle": cyc, "paired": paired, "eff": eff,
                      "elem": elem, "scene": scen})
    for f in files:
        if multi:
            out.append("# %s precision (%s)\n" % (f["tag"], f["name"]))
        print_context(f["data"].get("context", {}), out)
    for f in files:
        if multi and f["search"]:
            out.append("# Search benchmarks, %s precision\n" % f["tag"])
        report_search(f["data"], f["search"], out)
    precs = []
    for f in files:
        for r in f["kern"] + f["flo"]:
            if r["prec"] not in precs:
                precs.append(r["prec"])
    precs.sort(key=lambda p: (PREC_ORDER.index(p) if p in PREC_ORDER else 99, p))
    print_kernels([r for f in files for r in f["kern"]], precs, out)
    print_kernel_floor([r for f in files for r in f["kern"]],
                       [r for f in files for r in f["flo"]], out)
    print_interleaved(inter, out)
    print_eff([r for f in files for r in f["eff"]], out)
    print_floor([r for f in files for r in f["flo"]], {f["tag"]: f["search"] for f in files},
                out)
    print_cycle([r for f in files for r in f["cycle"]], out)
    print_elements([r for f in files for r in f["elem"]], out)
    print_scenes([r for f in files for r in f["scene"]], out)
    print_paired([r for f in files for r in f["paired"]], out)
    for f in files:
        print_peers(f["peers"], f["search"], out)
    print_trade([r for f in files for r in f["trade"]], compare, out)
    for f in files:
        print_other(f["other"], out)
    return "\n".join(out)


def main(argv):
    if len(argv) < 2:
        sys.stderr.write("usage: report.py BENCH.json [BENCH2.json ...]\n")
        return 2
    datas, names, compare, inter = [], [], None, None
    for path in argv[1:]:
        try:
            with open(path) as f:
                data = json.load(f)
        except (OSError, ValueError) as e:
            sys.stderr.write("report.py: cannot read %s: %s\n" % (path, e))
            return 1
        if isinstance(data, dict) and "trade_precision" in data:
            compare = data["trade_precision"]
            continue
        if isinstance(data, dict) and "interleaved" in data:
            inter = data["interleaved"]
            continue
        datas.append(data)
        names.append(path)
    if not datas:
        sys.stderr.write("report.py: no benchmark file given\n")
        return 2
    sys.stdout.write(report(datas, names, compare, inter) + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
