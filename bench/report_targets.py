"""The speed targets of the issues against this run, for bench/report.py: one
row per figure an issue names, what the run measured, the bound this machine
puts on it where the run measured one, and whether the target is met.

The figures are read from the other tables' records, so this table says
nothing they do not; it gathers them in one place. The sizes are the issues':
the searches at 10^6 nodes (plates, gap + margin 0.5, natural numbering), the
kernels at 10^6 pairs in double precision on 1 thread (the issues' figures are
per thread), the contact cycle on the self-contact scenes. A target whose
bound is above it cannot be met on this machine by any implementation of the
same call (bench/floor.h); one without a bound was not proved out of reach.
Standard library only.
"""
from report_driver import CYCLE_TARGET_NS
from report_fmt import fmt_ns
from report_kernels import EFF_TARGET, SINGLE_TARGET, moved_gbps
from report_noise import host_note
from report_search import PAIRED_TARGETS, ns_per_node, our_best

NMAX = 1000000
# Kernel targets of issue 3 (ns per pair per thread, 10^6 pairs, double).
KERNEL_TARGETS = [
    (("narrow", "tri"), 5.0, "node–triangle ≤ 5 ns/pair"),
    (("narrow", "4tri"), 10.0, "node–quad by 4 triangles ≤ 10 ns/pair"),
    (("narrow", "newton"), 20.0, "node–quad by Newton ≤ 20 ns/pair"),
    (("force", "penalty+coulomb-fused"), 5.0, "penalty + Coulomb friction ≤ 5 ns/pair"),
    (("assemble", "colour"), 3.0, "coloured assembly ≤ 3 ns/pair"),
]
BUCKET_TARGET_NS = 10.0
PEER_TARGET = 30.0
COLOUR_VS_FASTEST = 1.5


def threads(t):
    """'1 thread', '2 threads'."""
    return "%d thread%s" % (t, "s" if t != 1 else "")


def verdict(ok):
    """The met? cell: yes, **no**, or - when nothing was measured."""
    return "-" if ok is None else ("yes" if ok else "**no**")


def kernel_bound(rec, moved):
    """The bound of a kernel record: its per-pair bytes at the most GB/s any
    loop of the run moved with its threads (report_kernels.moved_gbps), or
    None."""
    sb = rec["counters"].get("stream_bytes_per_pair")
    g = moved.get(rec["threads"])
    return sb / g if sb and g else None


def search_rows(search, flo, paired):
    """Issue 2's figures: the bucket search's ns per node and the ratios."""
    rows = []
    rec = next((r for r in search if not r["error"] and r["n"] == NMAX and r["threads"] == 2
                and (r["family"], r["algo"], r["numbering"]) == ("plates", "bucket",
                                                                 "natural")), None)
    v = ns_per_node(rec) if rec else None
    fl = next((r for r in flo if r["what"] == "bucket/plates" and r["n"] == NMAX
               and r["threads"] == 2 and not r["error"]), None)
    fd = fl["counters"].get("floor_ns_dram") if fl else None
    rows.append((2, "bucket search ≤ %g ns/node (plates 10^6, 2 threads)" %
                 BUCKET_TARGET_NS, fmt_ns(v) + host_note(rec) if v else "-",
                 "%s (floor, bench/floor.h)" % fmt_ns(fd) if fd else "-",
                 verdict(None if v is None else v <= BUCKET_TARGET_NS)))
    for r in sorted(paired, key=lambda r: (r["family"], r["what"], r["threads"])):
        tgt = PAIRED_TARGETS.get((r["family"], r["what"]))
        ratio = r["counters"].get("ratio")
        if not tgt or r["error"] or ratio is None:
            continue
        c = r["counters"]
        cond, desc = tgt[0].split(" (", 1)
        rows.append((2, "%s: b/a %s (%s %d, %s)" % (
            desc.split(": ", 1)[-1].rstrip(")"), cond, r["family"], r["n"],
            threads(r["threads"])),
            "%.2f (rounds %.2f-%.2f)" % (ratio, c.get("ratio_min", 0), c.get("ratio_max", 0)),
            "-", verdict(tgt[1](ratio))))
    return rows


def peer_row(search, peers):
    """Issue 5: our best search against the best peer library at 10^6 nodes,
    per family; the row shows the family where the ratio is smallest. The
    textbook grid (peer "grid") is a reference, not a library: left out."""
    best = {}
    for r in peers:
        if r["error"] or r["n"] != NMAX or r["peer"] == "grid":
            continue
        v = r["counters"].get("ns_per_node") or ns_per_node(r)
        if v and (r["family"] not in best or v < best[r["family"]][0]):
            best[r["family"]] = (v, r["peer"])
    worst = None
    for fam, (v, peer) in sorted(best.items()):
        ours = our_best(search, fam, NMAX)
        if ours and ours[0] > 0 and (worst is None or v / ours[0] < worst[0]):
            worst = (v / ours[0], fam, peer, v, ours)
    if worst is None:
        return None
    ratio, fam, peer, v, ours = worst
    return (5, "best search ≥ %.0f× faster than the best peer (10^6 nodes)" % PEER_TARGET,
            "%.1f× (%s: %s %s ns/node against our %s %s)" % (ratio, fam, peer, fmt_ns(v),
                                                             ours[1], fmt_ns(ours[0])),
            "-", verdict(ratio >= PEER_TARGET))


def kernel_rows(kern, flo):
    """Issue 3's kernel figures at 10^6 pairs, double, 1 thread."""
    moved = moved_gbps(kern, flo)
    at = {}
    for r in kern:
        if not r["error"] and r["n"] == NMAX and r["prec"] == "double":
            at[(r["group"], r["kernel"], r["threads"])] = r
    rows = []
    for (g, k), tgt, text in KERNEL_TARGETS:
        rec = at.get((g, k, 1))
        v = rec["counters"].get("ns_per_pair") if rec else None
        b = kernel_bound(rec, moved) if rec else None
        bound = "-"
        if b is not None:
            bound = "%.2f%s" % (b, ": out of reach" if b > tgt else "")
        rows.append((3, text + " (10^6 pairs, 1 thread)", fmt_ns(v) + host_note(rec) if v else "-",
                     bound, verdict(None if v is None else v <= tgt)))
    # The coloured assembly against the fastest variant, per thread count.
    for t in sorted(set(r[2] for r in at)):
        col = at.get(("assemble", "colour", t))
        others = [r["counters"]["ns_per_pair"] for key, r in at.items()
                  if key[0] == "assemble" and key[2] == t and "ns_per_pair" in r["counters"]]
        if not col or not others or "ns_per_pair" not in col["counters"]:
            continue
        ratio = col["counters"]["ns_per_pair"] / min(others)
        rows.append((3, "coloured assembly within %.1f× of the fastest variant (%s)"
                     % (COLOUR_VS_FASTEST, threads(t)), "%.2f×" % ratio, "-",
                     verdict(ratio <= COLOUR_VS_FASTEST)))
    return rows


def single_row(inter):
    """Issue 3: single precision at least 1.6× faster, interleaved, 10^6 pairs."""
    rows = [r for r in (inter or {}).get("rows", []) if r["name"].endswith("/%d" % NMAX)]
    if not rows:
        return None
    lo = min(rows, key=lambda r: r["ratio"])
    return (3, "single precision ≥ %.1f× faster (interleaved, 10^6 pairs, %d kernels)"
            % (SINGLE_TARGET, len(rows)),
            "%.2f-%.2f (smallest: %s)" % (lo["ratio"], max(r["ratio"] for r in rows),
                                          lo["name"].split("/")[2]),
            "-", verdict(lo["ratio"] >= SINGLE_TARGET))


def eff_row(eff):
    """Issue 3: 2-thread efficiency of the kernels, with the machine's own."""
    ok = [r for r in eff if not r["error"] and r["counters"].get("eff") is not None]
    kern = [r for r in ok if not (r["what"].startswith("triad") or r["what"] == "compute")]
    if not kern:
        return None
    pct = lambda v: "%d %%" % round(100 * v)
    lo = min(kern, key=lambda r: r["counters"]["eff"])
    hi = max(kern, key=lambda r: r["counters"]["eff"])
    ceil = ", ".join("%s %s" % ("DRAM triad" if r["what"].startswith("triad") else "compute",
                                pct(r["counters"]["eff"]))
                     for r in sorted(ok, key=lambda r: r["what"]) if r not in kern)
    span = "%s (%s)" % (pct(lo["counters"]["eff"]), lo["what"])
    if hi is not lo:
        span += " to %s (%s)" % (pct(hi["counters"]["eff"]), hi["what"])
    return (3, "2-thread efficiency ≥ %d %% (interleaved, %d kernel%s)" % (
        round(100 * EFF_TARGET), len(kern), "s" if len(kern) != 1 else ""), span,
        "machine: %s" % ceil if ceil else "-",
        verdict(lo["counters"]["eff"] >= EFF_TARGET))


def cycle_row(cyc):
    """Issue 5: the full contact cycle per thread, double precision."""
    rows = [r for r in cyc if not r["error"] and r["prec"] == "double"
            and r["counters"].get("ns_total_x_threads") is not None]
    if not rows:
        return None
    lo = min(rows, key=lambda r: r["counters"]["ns_total_x_threads"])
    hi = max(rows, key=lambda r: r["counters"]["ns_total_x_threads"])
    name = lambda r: "%s %d, %s%s" % (r["family"], r["n"], threads(r["threads"]),
                                       host_note(r, inside=True))
    return (5, "full contact cycle ≤ %g ns/node/cycle per thread" % CYCLE_TARGET_NS,
            "%s (%s) to %s (%s)" % (fmt_ns(lo["counters"]["ns_total_x_threads"]), name(lo),
                                    fmt_ns(hi["counters"]["ns_total_x_threads"]), name(hi)),
            "-", verdict(hi["counters"]["ns_total_x_threads"] <= CYCLE_TARGET_NS))


def print_targets(search, flo, paired, peers, kern, eff, cyc, inter, out):
    """The table; search, paired and peers are the double-precision file's."""
    rows = search_rows(search, flo, paired)
    rows += [r for r in (peer_row(search, peers),) if r]
    rows += kernel_rows(kern, flo)
    rows += [r for r in (single_row(inter), eff_row(eff), cycle_row(cyc)) if r]
    if not any(r[2] != "-" for r in rows):
        return
    out.append("## Speed targets of the issues, in this run\n")
    out.append("Each figure an issue names, read from the tables below (searches at 10^6 "
               "nodes, plates, natural numbering; kernels at 10^6 pairs, double precision, 1 "
               "thread; ratios from the interleaved rounds). bound: what this machine allows "
               "where the run measured it: the search's floor (bench/floor.h), a kernel's "
               "per-pair arrays at the most any loop of the run moved (the kernels' floor "
               "table); "
               "\"out of reach\": the bound is above the target, so no call with the same "
               "arrays meets it here. For the efficiency, the machine's own 2-thread "
               "efficiency on a loop that only streams memory and on one that only "
               "computes. \"host: barrier ×4.00\": the host differed from the rest of the run "
               "under the row a figure comes from (the probe's figure against the run's "
               "median; the section \"How steady the host was\").\n")
    out.append("| issue | target | measured | bound on this machine | met? |")
    out.append("|---:|---|---|---|---|")
    for r in sorted(rows, key=lambda r: r[0]):
        out.append("| %d | %s | %s | %s | %s |" % r)
    out.append("")
