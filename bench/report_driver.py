"""The driver's tables of bench/report.py: the full contact cycle
(bench_cycle.c), the element forces (bench_elements.c) and whole runs of the
scenes (bench_scene.c).

  - the full contact cycle (cycle/<family>/t<threads>/<nodes>): per
    precision, one row per family, size and threads with the ns per node per
    cycle of each phase (the search amortised over the re-sort interval), the
    total, the total times the threads against the target of 15 ns, and the
    speed-up over the 1-thread row of the same family and size;
  - the element forces (elements/<element>/<mesh>/t<threads>/<nodes>): ns per
    element and per node, and the speed-up over 1 thread;
  - whole runs (scene/<name>/t<threads>/<cycles>): µs per cycle, ns per node
    per cycle, the split between the elements, the contact and the rest, and
    the speed-up over 1 thread.
Standard library only.
"""
import re

from benchjson import NAME_TAIL, label_precision, split_named
from report_fmt import fmt_ns, fmt_num, prec_rank

# The full contact cycle (bench_cycle.c); its ns_* counters are ns per node
# per cycle, wall time.
CYCLE_RE = re.compile(r"^cycle/(?P<family>[^/]+)/t(?P<threads>\d+)/(?P<n>\d+)" + NAME_TAIL)
CYCLE_PHASES = ["ns_search", "ns_narrow", "ns_force", "ns_assemble", "ns_timestep"]
CYCLE_TARGET_NS = 15.0
# The driver's shell element forces (bench_elements.c):
# elements/shell/<mesh>/t<threads>/<nodes>.
ELEM_RE = re.compile(
    r"^elements/(?P<element>[^/]+)/(?P<family>[^/]+)/t(?P<threads>\d+)/(?P<n>\d+)" + NAME_TAIL)
# Whole runs of the driver's scenes (bench_scene.c):
# scene/<name>/t<threads>/<cycles>.
SCENE_RE = re.compile(r"^scene/(?P<scene>[^/]+)/t(?P<threads>\d+)/(?P<n>\d+)" + NAME_TAIL)


def parse_cycle(other, prec):
    """Split the full contact cycle records (cycle/<family>/t<threads>/<nodes>)
    from the others; the precision is the label's prec=, else the file's."""
    cyc, rest = split_named(other, CYCLE_RE)
    for r in cyc:
        r["prec"] = label_precision(r["label"]) or prec
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
               "proved out of contact by the skip); × threads = total × threads, the "
               "per-thread figure of the target of issue 5 (≤ %s ns/node/cycle per thread); "
               "speed-up = total with 1 thread / "
               "total with this row's threads. The cycle chooses the pairs that carry each "
               "node (ct_select_pairs, one per side) and hands a node's friction history to "
               "its new carrier, as the driver's interfaces do: active = the carrying pairs "
               "in contact; the selection's time is in the narrow phase's."
               "\n" % fmt_num(CYCLE_TARGET_NS))
    present = sorted(set(r["prec"] for r in cyc), key=lambda p: (prec_rank(p), p))
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
