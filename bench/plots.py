#!/usr/bin/env python3
"""Turn the Google Benchmark JSON of `make bench` into PNG plots with gnuplot.

Usage: python3 bench/plots.py build/bench.json [build/bench-single.json ...]
                              [--out docs/] [--data DIR]

Reads the same files as bench/report.py, with the same reading
(bench/benchjson.py: the median of the repetitions, the "median" aggregate
when present, else the median of the repetition rows) and
writes, for each file (the first file's plots have no suffix, the others get
"_<precision>", e.g. search_cost_single.png):

  search_cost.png   log-log time per search against the secondary nodes N
                    for the four searches on the plates family (natural
                    numbering, 1 thread dashed and open, the most threads
                    solid and filled), a direct search skipped over its budget
                    extrapolated from the largest measured one (cost
                    proportional to nsec * nseg, dotted, marked "extrap."),
                    the peers (peer/plates/<peer>/t<T>/<N>, their tuned
                    setting, ns_per_node counter * nsec), and the bandwidth
                    floor (floor/bucket/plates: floor_bytes_per_node at the
                    triad bandwidth GBps_dram, and GBps_ws, drawn as
                    ns/node * N over the whole range: the byte model is about
                    constant per node);
  speedup.png       speed-up t(1 thread) / t(T threads) against T for each
                    search (and each peer run with several thread counts) on
                    plates, at the largest N measured with every thread
                    count, with the ideal line;
  real_meshes.png   ns per node of the four searches on each real mesh
                    (real/<deck>/<algo>/t<T>), 1 thread and the most threads;
and once for all files together:
  trade.png         the speed/accuracy trade table as scatters of cost against
                    error, one panel per knob (its own units): every record
                    whose label starts with "knob=<name>" (bench_trade.c:
                    "knob=K setting=S; cost: what; accuracy: what; ..."); its
                    cost is the counter "cost" (else the first ns_per_*
                    counter, else the time), its error the counter "accuracy"
                    (else the first counter named like an error, see
                    ERROR_HINTS); each point labelled with its setting (and
                    precision when several files are given). A panel whose
                    errors span more than a factor 100 is drawn in log scale,
                    an error of 0 then on a dotted line below the others.
A plot whose records are absent is skipped with a message on stderr; the exit
status is then still 0. Exit status 1 when a file cannot be read or gnuplot
fails, 2 on a usage error.

--data DIR keeps the gnuplot scripts and data files there (one .gp and its
.dat files per plot); by default they are written to a temporary folder.
Needs gnuplot (Debian gnuplot-nox; the pngcairo terminal, else png).
Standard library only.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

from benchjson import ALGOS, PEER_RE, SEARCH_RE, collect, precision_of, split_named
from report_search import direct_ns_per_work

ALGO_COLOUR = {"direct": "#d62728", "topological": "#9467bd", "bucket": "#1f77b4",
               "bsp": "#2ca02c"}
PEER_COLOURS = ["#ff7f0e", "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"]
KNOB_COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b",
                "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"]
# Counter names taken as the error of a trade record, by the first hint they
# contain (lower case), in this order of preference.
ERROR_HINTS = ["accuracy", "error", "err", "miss", "penetration", "diff", "drift"]
SIZE = (1200, 750)


def peer_title(peer):
    """A peer's name in a legend; the textbook grid is a reference, not a
    library (bench/peers/grid_peer.cc)."""
    return "reference: textbook grid" if peer == "grid" else "peer " + peer


# The runs only the plots read; those of the searches and the peers are in
# bench/benchjson.py.
FLOOR_RE = re.compile(r"^floor/bucket/(?P<family>[^/]+)/t(?P<threads>\d+)/(?P<n>\d+)$")
REAL_RE = re.compile(r"^real/(?P<deck>[^/]+)/(?P<algo>[^/]+)/t(?P<threads>\d+)$")


def log(msg):
    sys.stderr.write("plots.py: %s\n" % msg)


# ---- Reading -----------------------------------------------------------------

def parse(records):
    """Split the records by kind, the first pattern a name matches; the name's
    fields are added to each. Of the others, those whose label starts with
    "knob=" and that have no error are the trade records."""
    kinds = {}
    rest = records
    for kind, rx in (("search", SEARCH_RE), ("peer", PEER_RE), ("floor", FLOOR_RE),
                     ("real", REAL_RE)):
        kinds[kind], rest = split_named(rest, rx)
    kinds["knob"] = [r for r in rest if (r["label"] or "").startswith("knob=") and not r["error"]]
    return kinds


def load(path):
    with open(path) as f:
        data = json.load(f)
    kinds = parse(collect(data.get("benchmarks", [])))
    kinds["precision"] = precision_of(data)
    kinds["path"] = path
    return kinds


# ---- gnuplot -----------------------------------------------------------------

def q(s):
    """A gnuplot string literal."""
    return '"%s"' % str(s).replace("\\", "\\\\").replace('"', '\\"')


def write_dat(folder, name, rows):
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        for row in rows:
            f.write(" ".join(x if isinstance(x, str) else "%.6g" % x for x in row) + "\n")
    return name


def terminal():
    """pngcairo when this gnuplot has it, else png."""
    try:
        p = subprocess.run(["gnuplot", "-e", "set terminal pngcairo; exit"],
                           capture_output=True, text=True, timeout=30)
        if p.returncode == 0 and not p.stderr.strip():
            return "pngcairo size %d,%d enhanced font 'Sans,11' linewidth 1.5" % SIZE
    except (OSError, subprocess.SubprocessError):
        pass
    return "png size %d,%d enhanced" % SIZE


def run_gnuplot(folder, stem, lines, png):
    script = os.path.join(folder, stem + ".gp")
    head = ["set terminal " + terminal(), "set output " + q(os.path.abspath(png)),
            "set encoding utf8", "set grid lc rgb '#dddddd'", "set key box opaque noenhanced"]
    with open(script, "w") as f:
        f.write("\n".join(head + lines) + "\n")
    p = subprocess.run(["gnuplot", stem + ".gp"], cwd=folder, capture_output=True, text=True)
    if p.returncode != 0 or not os.path.exists(png) or os.path.getsize(png) == 0:
        log("gnuplot failed on %s:\n%s" % (script, p.stderr))
        if os.path.exists(png):
            os.remove(png)
        return False
    print("wrote %s" % png)
    return True


def log_axes(xlabel, ylabel, title):
    return ["set title %s noenhanced" % q(title), "set xlabel %s noenhanced" % q(xlabel),
            "set ylabel %s noenhanced" % q(ylabel), "set logscale xy",
            "set format x '10^{%L}'", "set format y '10^{%L}'", "set mxtics 10",
            "set mytics 10"]


# ---- Plot 1: search cost against N ---------------------------------------------

def extrapolate(rec, search):
    """A skipped direct run's (nsec, time) from the largest measured direct run
    of the same family, numbering and threads (cost proportional to nsec *
    nseg, the sizes read from the skip message)."""
    m = re.search(r"nsec=(\d+) nseg=(\d+)", rec["error"] or "")
    if not m:
        return None
    nsec, nseg = float(m.group(1)), float(m.group(2))
    per_work = direct_ns_per_work(rec, search)
    if per_work is None:
        return None
    return nsec, per_work * nsec * nseg


def plot_cost(f, out, folder, suffix):
    family = "plates"
    search = [r for r in f["search"] if r["family"] == family and r["numbering"] == "natural"]
    measured = [r for r in search if not r["error"] and r["time_ns"] and
                r["counters"].get("nsec")]
    if not measured:
        log("%s: no search records on plates: search_cost%s.png skipped" % (f["path"], suffix))
        return None
    tmax = max(r["threads"] for r in measured)
    plots, xs = [], []
    for algo in ALGOS + sorted({r["algo"] for r in measured} - set(ALGOS)):
        colour = ALGO_COLOUR.get(algo, "#333333")
        for t in sorted({r["threads"] for r in search if r["algo"] == algo}):
            pts = sorted((r["counters"]["nsec"], r["time_ns"] * 1e-9) for r in measured
                         if r["algo"] == algo and r["threads"] == t)
            if pts:
                xs += [p[0] for p in pts]
                name = write_dat(folder, "cost%s_%s_t%d.dat" % (suffix, algo, t), pts)
                plots.append("%s using 1:2 with linespoints lc rgb '%s' dt %d pt %d ps 1.2 "
                             "title %s" % (q(name), colour, 1 if t == tmax else 2,
                                           7 if t == tmax else 6,
                                           q("%s, %d thread%s" % (algo, t, "s" if t > 1 else ""))))
            if algo != "direct":
                continue
            ex = [extrapolate(r, search) for r in search
                  if r["algo"] == algo and r["threads"] == t and r["error"]]
            ex = sorted(e for e in ex if e)
            if ex and pts:
                xs += [e[0] for e in ex]
                ex_pts = [pts[-1]] + [(e[0], e[1] * 1e-9) for e in ex]
                name = write_dat(folder, "cost%s_direct_t%d_extrap.dat" % (suffix, t), ex_pts)
                plots.append("%s using 1:2 with linespoints lc rgb '%s' dt 3 pt 4 ps 1.2 "
                             "title %s" % (q(name), colour,
                                           q("direct, %d thread%s (extrap. ∝ nsec·nseg)"
                                             % (t, "s" if t > 1 else ""))))
    peers = [r for r in f["peer"] if r["family"] == family and not r["error"] and
             not r["setting"] and r["counters"].get("ns_per_node") is not None]
    pnames = sorted({r["peer"] for r in peers})
    for i, peer in enumerate(pnames):
        colour = PEER_COLOURS[i % len(PEER_COLOURS)]
        pt_max = max(r["threads"] for r in peers if r["peer"] == peer)
        for t in sorted({r["threads"] for r in peers if r["peer"] == peer}):
            pts = sorted((r["counters"].get("nsec", r["n"]),
                          r["counters"]["ns_per_node"] * r["counters"].get("nsec", r["n"]) * 1e-9)
                         for r in peers if r["peer"] == peer and r["threads"] == t)
            xs += [p[0] for p in pts]
            name = write_dat(folder, "cost%s_peer_%s_t%d.dat" % (suffix, peer, t), pts)
            plots.append("%s using 1:2 with linespoints lc rgb '%s' dt %d pt %d ps 1.2 "
                         "title %s" % (q(name), colour, 1 if t == pt_max else 2,
                                       9 if t == pt_max else 8,
                                       q("%s, %d thread%s"
                                         % (peer_title(peer), t, "s" if t > 1 else ""))))
    xmin, xmax = min(xs) / 1.5, max(xs) * 1.5
    floors = [r for r in f["floor"] if r["family"] == family and not r["error"] and
              r["counters"].get("floor_bytes_per_node")]
    note = ""
    if floors:
        ft = max(r["threads"] for r in floors)
        fr = max((r for r in floors if r["threads"] == ft), key=lambda r: r["n"])
        c = fr["counters"]
        bpn = c["floor_bytes_per_node"]
        for key, dt, what in (("GBps_dram", 2, "DRAM"), ("GBps_ws", 4, "working-set")):
            gbps = c.get(key)
            if gbps and gbps > 0:
                # bytes / (GB/s) is ns; per node, times N nodes, in seconds.
                slope = bpn / gbps * 1e-9
                plots.append("[%.6g:%.6g] %.6g*x with lines lc rgb 'black' dt %d lw 2 "
                             "title %s" % (xmin, xmax, slope, dt,
                                           q("floor: %.0f B/node at %.1f GB/s (%s triad, %d thr;"
                                             " model at N = %d, drawn ∝ N)"
                                             % (bpn, gbps, what, ft, fr["n"]))))
    else:
        log("%s: no floor/bucket/plates records: the floor line is omitted" % f["path"])
        note = " (no floor records in this run)"
    lines = log_axes("secondary nodes N", "time per search (s)",
                     "Contact search on plates, natural numbering: cost against size "
                     "(%s precision)%s" % (f["precision"], note))
    lines += ["set xrange [%.6g:%.6g]" % (xmin, xmax), "set key outside below maxrows 7 font ',9'",
              "plot " + ", \\\n     ".join(plots)]
    png = os.path.join(out, "search_cost%s.png" % suffix)
    return png if run_gnuplot(folder, "search_cost" + suffix, lines, png) else False


# ---- Plot 2: speed-up against threads ------------------------------------------

def speedup_series(recs, key):
    """For each key value: (N, [(threads, speed-up)]) at the largest N measured
    with every thread count of that key."""
    out = {}
    for k in sorted({key(r) for r in recs}):
        rs = [r for r in recs if key(r) == k]
        threads = sorted({r["threads"] for r in rs})
        if len(threads) < 2 or 1 not in threads:
            continue
        by = {(r["n"], r["threads"]): r["time_ns"] for r in rs}
        ns = [n for n in {r["n"] for r in rs} if all((n, t) in by for t in threads)]
        if not ns:
            continue
        n = max(ns)
        out[k] = (n, [(t, by[(n, 1)] / by[(n, t)]) for t in threads])
    return out


def plot_speedup(f, out, folder, suffix):
    family = "plates"
    search = [r for r in f["search"] if r["family"] == family and r["numbering"] == "natural"
              and not r["error"] and r["time_ns"]]
    series = speedup_series(search, lambda r: r["algo"])
    peers = [dict(r, time_ns=r["counters"]["ns_per_node"]) for r in f["peer"]
             if r["family"] == family and not r["error"] and not r["setting"]
             and r["counters"].get("ns_per_node")]
    pseries = speedup_series(peers, lambda r: r["peer"])
    if not series and not pseries:
        log("%s: no plates runs with 1 and more threads: speedup%s.png skipped"
            % (f["path"], suffix))
        return None
    tmax = max(t for s in list(series.values()) + list(pseries.values()) for t, _ in s[1])
    ideal = write_dat(folder, "speedup%s_ideal.dat" % suffix, [(1, 1), (tmax, tmax)])
    plots = ["%s using 1:2 with lines lc rgb 'black' dt 2 title 'ideal (linear)'" % q(ideal)]
    smax = 1.0
    for algo in sorted(series, key=lambda a: ALGOS.index(a) if a in ALGOS else 99):
        n, pts = series[algo]
        smax = max([smax] + [s for _, s in pts])
        name = write_dat(folder, "speedup%s_%s.dat" % (suffix, algo), pts)
        plots.append("%s using 1:2 with linespoints lc rgb '%s' pt 7 ps 1.5 lw 2 title %s"
                     % (q(name), ALGO_COLOUR.get(algo, "#333333"), q("%s (N = %d)" % (algo, n))))
    for i, peer in enumerate(sorted(pseries)):
        n, pts = pseries[peer]
        smax = max([smax] + [s for _, s in pts])
        name = write_dat(folder, "speedup%s_peer_%s.dat" % (suffix, peer), pts)
        plots.append("%s using 1:2 with linespoints lc rgb '%s' dt 2 pt 9 ps 1.5 title %s"
                     % (q(name), PEER_COLOURS[i % len(PEER_COLOURS)],
                        q("%s (N = %d)" % (peer_title(peer), n))))
    lines = ["set title %s noenhanced" % q(
                 "Speed-up from 1 to %d threads, plates, natural numbering, largest N with "
                 "every thread count (%s precision)" % (tmax, f["precision"])),
             "set xlabel 'threads'", "set ylabel 'speed-up  t(1 thread) / t(T threads)'",
             "set xrange [0.8:%g]" % (tmax + 0.2), "set xtics 1",
             "set yrange [0:%g]" % (max(smax, tmax) * 1.15), "set key left top",
             "plot " + ", \\\n     ".join(plots)]
    png = os.path.join(out, "speedup%s.png" % suffix)
    return png if run_gnuplot(folder, "speedup" + suffix, lines, png) else False


# ---- Plot 3: real meshes ---------------------------------------------------------

def plot_real(f, out, folder, suffix):
    real = [r for r in f["real"] if not r["error"] and r["counters"].get("ns_per_node")]
    if not real:
        log("%s: no real/ records: real_meshes%s.png skipped" % (f["path"], suffix))
        return None
    decks = sorted({r["deck"] for r in real})
    tlist = sorted({r["threads"] for r in real})
    tlist = sorted({tlist[0], tlist[-1]})
    cols = [(a, t) for t in tlist for a in ALGOS if any(
        r["algo"] == a and r["threads"] == t for r in real)]
    val = {(r["deck"], r["algo"], r["threads"]): r["counters"]["ns_per_node"] for r in real}
    rows = []
    for d in decks:
        nsec = next(r["counters"].get("nsec", 0) for r in real if r["deck"] == d)
        row = ["%s\\n(%d nodes)" % (d, nsec)]
        row += [val.get((d, a, t), "NaN") for a, t in cols]
        rows.append(row)
    with open(os.path.join(folder, "real%s.dat" % suffix), "w") as fh:
        for row in rows:
            fh.write('"%s" ' % row[0] + " ".join(x if isinstance(x, str) else "%.6g" % x
                                                 for x in row[1:]) + "\n")
    plots = []
    for i, (a, t) in enumerate(cols):
        plots.append("'real%s.dat' using %d%s lc rgb '%s' fs %s title %s" % (
            suffix, i + 2, ":xtic(1)" if i == 0 else "", ALGO_COLOUR.get(a, "#333333"),
            "solid 0.8" if t == tlist[-1] else "pattern 4", q("%s, %d thr" % (a, t))))
    lines = ["set title %s noenhanced" % q(
                 "Search on real meshes (Radioss decks): self contact over the shells, "
                 "gap + margin = 0.5 h (%s precision)" % f["precision"]),
             "set ylabel 'time per search / secondary nodes (ns per node)'",
             "set logscale y", "set format y '10^{%L}'", "set style data histograms",
             "set style histogram clustered gap 1", "set boxwidth 0.9", "set key outside right top",
             "set xtics noenhanced", "set bmargin 4",
             "plot " + ", \\\n     ".join(plots)]
    png = os.path.join(out, "real_meshes%s.png" % suffix)
    return png if run_gnuplot(folder, "real_meshes" + suffix, lines, png) else False


# ---- Plot 4: the trade table ---------------------------------------------------------

def trade_point(r):
    """A knob record as a dict: knob, setting, cost (and what it is), error (and
    what it is); None when it has no error counter. The cost is the counter
    "cost", else the first ns_per_* counter, else the time per iteration; the
    error the counter "accuracy", else the first counter named like an error
    (ERROR_HINTS). What they are comes from the label's "cost: ...;" and
    "accuracy: ...;" parts when present, else from the counter names."""
    lab = r["label"]
    m = re.match(r"knob=(\S+)", lab)
    knob = m.group(1).rstrip(";")
    c = r["counters"]
    cname = "cost" if "cost" in c else next((k for k in c if k.startswith("ns_per")), None)
    cost = c[cname] if cname else r["time_ns"]
    ename = "accuracy" if "accuracy" in c else None
    for hint in ERROR_HINTS:
        if ename:
            break
        ename = next((k for k in c if hint in k.lower() and not k.startswith("x_")), None)
    if ename is None or cost is None:
        return None
    sm = re.search(r"(?:setting|value)=([^;\s]+)", lab)
    setting = sm.group(1) if sm else r["name"].split("/")[-1]
    cm = re.search(r"cost: ([^;]+)", lab)
    am = re.search(r"accuracy: ([^;]+)", lab)
    return {"knob": knob, "setting": setting, "cost": cost, "error": c[ename],
            "cost_what": cm.group(1).strip() if cm else (cname or "time per iteration (ns)"),
            "error_what": am.group(1).strip() if am else ename}


def plot_trade(files, out, folder):
    pts = []
    for f in files:
        for r in f["knob"]:
            p = trade_point(r)
            if p:
                p["prec"] = f["precision"]
                pts.append(p)
    if not pts:
        log("no trade records (labels starting with \"knob=\" with a cost and an accuracy "
            "counter): trade.png skipped")
        return None
    knobs = []
    for p in pts:
        if p["knob"] not in knobs:
            knobs.append(p["knob"])
    precs = sorted({p["prec"] for p in pts})
    ncol = 1 if len(knobs) == 1 else 2 if len(knobs) <= 4 else 3
    nrow = (len(knobs) + ncol - 1) // ncol
    lines = ["set multiplot layout %d,%d title %s noenhanced" % (
                 nrow, ncol, q("Speed/accuracy trade: one point per setting, one panel per knob"
                               " (%s precision)" % ", ".join(precs))),
             "set key off", "set format x '%g'", "set format y '%g'"]
    for i, k in enumerate(knobs):
        kp = [p for p in pts if p["knob"] == k]
        lines += ["unset logscale", "set autoscale", "set format y '%g'", "set format x '%g'",
                  "set title %s noenhanced" % q(k),
                  "set xlabel %s noenhanced" % q("cost: " + kp[0]["cost_what"]),
                  "set ylabel %s noenhanced" % q("accuracy: " + kp[0]["error_what"])]
        costs = [p["cost"] for p in kp]
        if all(v > 0 for v in costs) and max(costs) / min(costs) > 10:
            lines += ["set logscale x", "set xrange [%.6g:%.6g]" % (min(costs) / 1.6,
                                                                     max(costs) * 1.6)]
        else:
            # Less than a decade: a linear axis (a log one would have no tics).
            lo, hi = min(costs + [0]), max(costs)
            lines.append("set xrange [%.6g:%.6g]" % (lo, hi * 1.25 if hi > 0 else 1))
        pos = [p["error"] for p in kp if p["error"] > 0]
        zero = None
        if pos and max(pos) / min(pos) > 100:
            # A wide range: log scale, an error of 0 drawn at a tenth of the
            # smallest positive one, on a dotted line.
            zero = min(pos) / 10 if len(pos) < len(kp) else None
            lo = zero if zero else min(pos)
            lines += ["set logscale y", "set format y '10^{%L}'",
                      "set yrange [%.6g:%.6g]" % (lo / 3, max(pos) * 3)]
        else:
            top = max([p["error"] for p in kp] + [0])
            bot = min([p["error"] for p in kp] + [0])
            span = (top - bot) or 1.0
            lines.append("set yrange [%.6g:%.6g]" % (bot - 0.08 * span, top + 0.15 * span))
        rows = [(p["cost"], zero if (zero and p["error"] <= 0) else p["error"],
                 (p["setting"] + ("/" + p["prec"] if len(precs) > 1 else "")).replace(" ", "_"))
                for p in kp]
        name = write_dat(folder, "trade_%d.dat" % i, rows)
        colour = KNOB_COLOURS[i % len(KNOB_COLOURS)]
        plot = ["%s using 1:2 with points lc rgb '%s' pt 7 ps 1.4 notitle" % (q(name), colour),
                "%s using 1:2:3 with labels offset 0.6,0.6 left font ',8' tc rgb '%s' "
                "noenhanced notitle" % (q(name), colour)]
        if zero:
            plot.append("%.6g with lines lc rgb '#888888' dt 3 notitle" % zero)
            lines.append("set label 1 'error 0 (dotted line)' at graph 0.02, graph 0.05 "
                         "font ',8' tc rgb '#888888'")
        else:
            lines.append("unset label 1")
        lines.append("plot " + ", ".join(plot))
    lines.append("unset multiplot")
    png = os.path.join(out, "trade.png")
    return png if run_gnuplot(folder, "trade", lines, png) else False


# ---- Main ------------------------------------------------------------------------------

def main(argv):
    ap = argparse.ArgumentParser(description="Plots of the benchmark JSON (gnuplot).")
    ap.add_argument("json", nargs="+", help="Google Benchmark JSON files of `make bench`")
    ap.add_argument("--out", default="docs", help="folder of the PNG files (default docs)")
    ap.add_argument("--data", help="keep the gnuplot scripts and data files in this folder")
    a = ap.parse_args(argv[1:])
    if shutil.which("gnuplot") is None:
        log("gnuplot not found (Debian package gnuplot-nox: make deps)")
        return 1
    files = []
    for path in a.json:
        try:
            files.append(load(path))
        except (OSError, ValueError) as e:
            log("cannot read %s: %s" % (path, e))
            return 1
    os.makedirs(a.out, exist_ok=True)
    tmp = None
    if a.data:
        os.makedirs(a.data, exist_ok=True)
        folder = a.data
    else:
        tmp = tempfile.TemporaryDirectory(prefix="ct-plots-")
        folder = tmp.name
    ok = True
    try:
        seen = []
        for i, f in enumerate(files):
            tag = f["precision"]
            while tag in seen:
                tag += "_%d" % (i + 1)
            seen.append(tag)
            suffix = "" if i == 0 else "_" + re.sub(r"[^A-Za-z0-9_.-]", "_", tag)
            for fn in (plot_cost, plot_speedup, plot_real):
                ok = fn(f, a.out, folder, suffix) is not False and ok
        ok = plot_trade(files, a.out, folder) is not False and ok
    finally:
        if tmp:
            tmp.cleanup()
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
