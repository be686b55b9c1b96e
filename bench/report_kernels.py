"""The kernel tables of bench/report.py: the kernels (bench_kernels.c), the
hardware floor (bench_floor.c), and the parallel efficiency and the
single-precision speed-up measured in interleaved rounds (bench_eff.c,
bench/interleave.py).

  - the kernels (kernels/<group>/<kernel>/t<threads>/<pairs>): ns per pair
    (the ns_per_pair counter) with 1 and the most threads, the parallel
    efficiency, per precision, and the single-precision speed-up when both
    precisions are given;
  - the kernels at their largest pair count against the memory floor: the
    byte model of a call (bytes_per_pair) at the DRAM triad bandwidth of the
    run with the same threads;
  - the single-precision speed-up measured in interleaved rounds, from the
    output of bench/interleave.py --json (its "interleaved" object);
  - the parallel efficiency measured in interleaved rounds
    (efficiency/<kernel>/t<threads>/<n>), kernels and the DRAM triad, against
    the target of 90 %;
  - the hardware floor (floor/...): triad bandwidth, the byte model of the
    search, the floor in ns per node and the ratio measured / floor for the
    bucket search on plates (the floor benchmark's own run, and the search
    benchmark's bucket run of the same size and threads when present).
Standard library only.
"""
import re

from benchjson import NAME_TAIL, label_precision, split_named
from interleave import moved_cpus
from report_fmt import fmt_ns, fmt_num, prec_rank
from report_search import ns_per_node

KERNEL_RE = re.compile(
    r"^kernels/(?P<group>[^/]+)/(?P<kernel>[^/]+)/t(?P<threads>\d+)/(?P<n>\d+)" + NAME_TAIL)
FLOOR_RE = re.compile(
    r"^floor/(?P<what>triad/dram|triad/ws|bucket/plates|sync/region|sync/barrier)/t(?P<threads>\d+)/(?P<n>\d+)"
    + NAME_TAIL)
KERNEL_GROUPS = ["narrow", "force", "prepare", "assemble"]
# The 2-thread efficiency target measured in interleaved rounds
# (bench_eff.c): efficiency/<kernel or triad/dram>/t<threads>/<n>.
EFF_RE = re.compile(r"^efficiency/(?P<what>.+?)/t(?P<threads>\d+)/(?P<n>\d+)" + NAME_TAIL)
EFF_TARGET = 0.9
# The single-precision speed-up target of issue 3 (kernel rows, 1 thread).
SINGLE_TARGET = 1.6


def split_records(records, prec):
    """Kernel, floor and other records; kernel and floor records get their
    fields parsed and the precision (label's prec=, else the file's)."""
    kern, rest = split_named(records, KERNEL_RE)
    flo, other = split_named(rest, FLOOR_RE)
    for r in kern + flo:
        r["prec"] = label_precision(r["label"]) or prec
    return kern, flo, other


def kernel_setting(label):
    """The setting named in a kernel label: after prec=..., up to ';'."""
    label = re.sub(r"^prec=\w+\s*", "", label or "")
    return label.split(";")[0].strip()


def print_kernels(kern, precs, out):
    """The kernels' ns per pair with 1 and the most threads, per precision
    (precs, in the order of the columns)."""
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


def largest_rows(kern):
    """The kernel records with a byte model at their kernel's largest pair
    count (the ones whose per-pair arrays must come from memory)."""
    rows = [r for r in kern if not r["error"] and "bytes_per_pair" in r["counters"]]
    nmax = {}
    for r in rows:
        key = (r["group"], r["kernel"])
        nmax[key] = max(nmax.get(key, 0), r["n"])
    return [r for r in rows if r["n"] == nmax[(r["group"], r["kernel"])]]


def moved_gbps(kern, flo):
    """{threads: the most GB/s any loop of the run moved}: the dram triad's
    real traffic (4/3 of its STREAM count: the write-allocate read of its
    written array counted), or a kernel's per-pair arrays at its largest pair
    count over its time, when that is more (a read-heavy loop, a kernel timed
    in a faster spell of the host than the triad, or one whose arrays partly
    stay in cache from one of its passes to the next: all make the bound
    lower, never higher). A time below what
    this rate allows is not observed in the run by construction; the bound
    assumes the machine moves memory no faster than its fastest loop did."""
    bw = {t: 4.0 / 3.0 * g for t, g in triad_gbps(flo).items()}
    for r in largest_rows(kern):
        c = r["counters"]
        sb, ns = c.get("stream_bytes_per_pair"), c.get("ns_per_pair")
        if sb and ns and r["threads"] in bw:
            bw[r["threads"]] = max(bw[r["threads"]], sb / ns)
    return bw


def print_kernel_floor(kern, flo, out):
    """The kernels at their largest pair count against the memory floor."""
    bw = triad_gbps(flo)
    moved = moved_gbps(kern, flo)
    rows = [r for r in largest_rows(kern) if r["threads"] in bw]
    if not rows:
        return
    gorder = {g: i for i, g in enumerate(KERNEL_GROUPS)}
    first = {}
    for i, r in enumerate(kern):
        first.setdefault((r["group"], r["kernel"]), i)
    rows.sort(key=lambda r: (gorder.get(r["group"], 99), first[(r["group"], r["kernel"])],
                             prec_rank(r["prec"]),
                             r["threads"]))
    out.append("## Kernels against the memory floor\n")
    out.append("At the largest pair count. bytes/pair: the least any implementation of the "
               "call must move (bench/floor.h: every array the call reads read once, every "
               "array it writes written once; node and segment arrays once per node or "
               "segment the pairs touch); floor = bytes / the dram triad bandwidth of the "
               "run with the same threads (STREAM's count, as for the search); ratio = "
               "measured / floor: near 1 the kernel is bound by memory, far above it by its "
               "arithmetic or latency. bound: the per-pair arrays alone (they exceed the "
               "last-level cache several times and must cross the memory bus) at the most "
               "any loop of the run moved with the same threads (moved GB/s: the triad's "
               "real traffic, its write-allocate read counted, or a kernel's per-pair "
               "arrays over its time when that is more): no call with these arrays runs "
               "faster on this machine unless it moves memory faster than any loop "
               "measured here.\n")
    out.append("| kernel | precision | pairs | threads | bytes/pair | GB/s | floor ns/pair | "
               "per-pair bytes | moved GB/s | bound ns/pair | measured ns/pair | ratio |")
    out.append("|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        c = r["counters"]
        g = bw[r["threads"]]
        floor = c["bytes_per_pair"] / g
        sb = c.get("stream_bytes_per_pair")
        m = moved[r["threads"]]
        bound = "%.2f" % (sb / m) if sb else "-"
        ns = c.get("ns_per_pair")
        out.append("| %s/%s | %s | %d | %d | %.1f | %.2f | %.2f | %s | %.2f | %s | %s | %s |"
                   % (r["group"], r["kernel"], r["prec"], r["n"], r["threads"],
                      c["bytes_per_pair"], g, floor, "%.1f" % sb if sb else "-", m, bound,
                      fmt_ns(ns) if ns else "-",
                      "%.1f" % (ns / floor) if ns and floor > 0 else "-"))
    out.append("")


def print_sync(sync, out):
    """What a parallel region and a barrier cost (bench_sync.c), one row
    per precision and thread count."""
    if not sync:
        return
    out.append("What the OpenMP runtime the programs link (provenance: \"OpenMP runtime\") "
               "costs per parallel region (a static loop of one store per thread) and per "
               "barrier (inside one region): the fixed cost of each of the fifty or so loops "
               "of a driver cycle, whatever the model's size.\n")
    out.append("| precision | threads | µs per region | µs per barrier |")
    out.append("|---|---:|---:|---:|")
    rows = {}
    for r in sync:
        rows.setdefault((r["prec"], r["threads"]), {})[r["what"]] = r
    for (prec, t) in sorted(rows):
        cells = []
        for what, ctr in (("sync/region", "us_per_region"), ("sync/barrier", "us_per_barrier")):
            r = rows[(prec, t)].get(what)
            if r is None:
                cells.append("-")
            elif r["error"] or ctr not in r["counters"]:
                cells.append(r["error"] or "-")
            else:
                cells.append("%.2f" % r["counters"][ctr])
        out.append("| %s | %d | %s | %s |" % (prec, t, cells[0], cells[1]))
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
    print_sync([r for r in flo if r["what"].startswith("sync/")], out)
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
    moved = [r for r in inter["rows"] if moved_cpus(r)]
    if moved:
        out.append("The host moved its CPUs between the rounds of %s (the probe's barrier of "
                   "both CPUs, bench/bench_host.c, from %.2f to %.2f µs): their range holds "
                   "rounds under both placements.\n"
                   % (", ".join(r["name"] for r in moved), min(r["barrier_min"] for r in moved),
                      max(r["barrier_max"] for r in moved)))


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
