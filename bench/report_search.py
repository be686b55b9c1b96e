"""The search tables of bench/report.py: the searches (bench_search.c), the
peers (bench_peers.c) and the ratio targets of the search measured in
interleaved rounds (bench_paired.c).

From the search benchmarks (search/<family>/<algo>/<numbering>/t<threads>/
<nodes>, the median of the repetitions):
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
    efficiency, at the largest size measured with both.
The peers (peer/<family>/<peer>[@<setting>]/t<threads>/<nodes>: nanoflann,
CGAL, Bullet on the same meshes and query, their pair sets checked equal to
our bucket search's): build and query ns per node, and the ratio of the peer's
cost to our best search on the same family and size (natural numbering, any
thread count).
The ratio targets (paired/<family>/<b>-vs-<a>/t<threads>/<nodes>): both
searches' ns per node, the median of the rounds' ratios, and the issue's
target.
Standard library only.
"""
import math
import re

from benchjson import ALGOS, NAME_TAIL, PEER_RE, split_named
from report_fmt import fmt_ns, fmt_num, fmt_time

NUMBERINGS = ["natural", "shuffled", "sfc"]
# The ratio targets measured in interleaved rounds (bench_paired.c):
# paired/<family>/<b>-vs-<a>/t<threads>/<nodes>.
PAIRED_RE = re.compile(
    r"^paired/(?P<family>[^/]+)/(?P<what>[^/]+)/t(?P<threads>\d+)/(?P<n>\d+)" + NAME_TAIL)
# The target for a (family, comparison): its text and its test.
PAIRED_TARGETS = {
    ("plates", "bsp-vs-bucket"): ("≤ 2 (issue 2: bsp within 2× of bucket, uniform mesh)",
                                  lambda r: r <= 2),
    ("graded", "bsp-vs-bucket"): ("< 1 (issue 2: bsp faster than bucket, graded mesh)",
                                  lambda r: r < 1),
    ("plates", "bucket-shuffled-vs-natural"): ("≤ 1.5 (issue 2: shuffled within 1.5× of "
                                               "ordered)", lambda r: r <= 1.5),
}


def sort_key(rec):
    """The order of the search rows: size, numbering, threads, algorithm."""
    return (int(rec["n"]), NUMBERINGS.index(rec["numbering"]) if rec["numbering"] in NUMBERINGS
            else 99, int(rec["threads"]),
            ALGOS.index(rec["algo"]) if rec["algo"] in ALGOS else 99)


def ns_per_node(rec):
    """Median time per search divided by the secondary nodes."""
    nsec = rec["counters"].get("nsec")
    if rec["time_ns"] is None or not nsec:
        return None
    return rec["time_ns"] / nsec


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


def direct_ns_per_work(rec, search):
    """The time of the largest measured direct run of rec's family, numbering
    and threads per unit of its work, nsec * nseg (ns), or None when there is
    none: the cost model of a direct search skipped over its budget."""
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
    return None if best is None else best[1] / best[0]


def extrapolate_direct(rec, search):
    """Time of a skipped direct run from the largest measured direct run of the
    same family, numbering and threads (cost proportional to nsec * nseg):
    (ns per search, ns per node), or None."""
    nsec, nseg = mesh_sizes(rec, search)
    if not nsec or not nseg:
        return None
    per_work = direct_ns_per_work(rec, search)
    if per_work is None:
        return None
    t = per_work * nsec * nseg
    return t, t / nsec


def print_headline(search, out):
    """The headline: bucket and bsp on plates at its largest measured size."""
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
    """The cost of every search on one family, one row per size, numbering,
    threads and algorithm."""
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
        if c.get("cell_factor"):
            note += " cells ×%g" % c["cell_factor"]
        if c.get("renumbered"):
            note += " renumbered"
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
    """The fitted exponent k of time proportional to nsec^k, per family and
    algorithm (natural numbering, the most threads)."""
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
    """The speed-up from 1 thread to the most threads at the largest size
    measured with both."""
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


def report_search(search, out):
    """The search tables of one file: the headline, per family, the scaling
    exponent and the speed-up."""
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


def parse_peers(other):
    """Split the peers' records from the others; a record without a setting in
    its name is the peer's tuned run, its setting taken from its label."""
    peers, rest = split_named(other, PEER_RE)
    for r in peers:
        r["tuned"] = not r["setting"]
        if not r["setting"]:
            lab = r["label"] or ""
            r["setting"] = lab.split(" same_as")[0].replace(" (tuned)", "") if lab else "-"
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
    """The peers on the same meshes and query, against our best search."""
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
