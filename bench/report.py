#!/usr/bin/env python3
"""Turn the Google Benchmark JSON of `make bench` into Markdown tables.

Usage: python3 bench/report.py build/bench.json [build/bench-single.json ...]
       [build/trade_precision.json] [build/bench-interleaved.json] > /tmp/x.md

Several files (e.g. a double and a single precision run) are merged: the
kernel and floor tables show them side by side (the precision of a file is
its context's ct_precision, else the precision= of ct_build, else the
"prec=" of its labels); the search tables are printed per file. A file with a
top-level "trade_precision" key is the output of bench/trade_precision.py
--json, one with a top-level "interleaved" key that of bench/interleave.py
--json: they are not benchmark runs but add to the tables named below.

Of each run it takes the median of the repetitions (the "median" aggregate
when present, else the median of the repetition rows; bench/benchjson.py)
and prints, in this order:
  - the provenance block (the context the benchmark program stored);
  - the speed targets of the issues (bench/report_targets.py) and how
    steady the host was: the spread of the repetitions (bench/report_noise.py);
  - per file, the search tables: the headline, the cost per family, the
    scaling exponent and the speed-up (bench/report_search.py);
  - the kernels, the kernels against the memory floor, the single-precision
    speed-up and the parallel efficiency measured in interleaved rounds, and
    the hardware floor (bench/report_kernels.py);
  - the full contact cycle, the element forces and the whole runs of the
    driver (bench/report_driver.py);
  - the ratio targets of the search measured in interleaved rounds, and per
    file the peers (bench/report_search.py);
  - the speed/accuracy trade (bench/report_trade.py);
  - any other benchmark as name / median time.
Standard library only.
"""
import json
import sys

from benchjson import SEARCH_RE, collect, precision_of, split_named
from report_driver import (ELEM_RE, SCENE_RE, parse_cycle, print_cycle, print_elements,
                           print_scenes)
from report_fmt import fmt_time, prec_rank
from report_noise import annotate_host, print_noise
from report_kernels import (EFF_RE, print_eff, print_floor, print_interleaved,
                            print_kernel_floor, print_kernels, split_records)
from report_search import PAIRED_RE, parse_peers, print_paired, print_peers, report_search
from report_trade import parse_trade, print_trade
from report_targets import print_targets


def print_context(ctx, out):
    """The provenance block: the context the benchmark program stored."""
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


def print_other(other, out):
    """Any benchmark no other table shows: name, median time, error or label."""
    if not other:
        return
    out.append("## Other benchmarks\n")
    out.append("| benchmark | median time | note |")
    out.append("|---|---:|---|")
    for r in other:
        out.append("| %s | %s | %s |" % (r["name"], fmt_time(r["time_ns"]),
                                         r["error"] or r["label"]))
    out.append("")


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
        recs = collect(data.get("benchmarks", []))
        annotate_host(recs)
        search, rest = split_named(list(recs), SEARCH_RE)
        kern, flo, other = split_records(rest, tag)
        peers, other = parse_peers(other)
        trade, other = parse_trade(other, tag)
        cyc, other = parse_cycle(other, tag)
        paired, other = split_named(other, PAIRED_RE)
        eff, other = split_named(other, EFF_RE)
        elem, other = split_named(other, ELEM_RE)
        scen, other = split_named(other, SCENE_RE)
        files.append({"tag": tag, "name": name, "data": data, "recs": recs, "search": search,
                      "kern": kern, "flo": flo, "other": other, "peers": peers,
                      "trade": trade, "cycle": cyc, "paired": paired, "eff": eff,
                      "elem": elem, "scene": scen})
    for f in files:
        if multi:
            out.append("# %s precision (%s)\n" % (f["tag"], f["name"]))
        print_context(f["data"].get("context", {}), out)
    main = next((f for f in files if f["tag"] == "double"), files[0])
    print_targets(main["search"], [r for f in files for r in f["flo"]], main["paired"],
                  main["peers"], [r for f in files for r in f["kern"]],
                  [r for f in files for r in f["eff"]], [r for f in files for r in f["cycle"]],
                  inter, out)
    print_noise([(f["tag"], f["recs"]) for f in files], out)
    for f in files:
        if multi and f["search"]:
            out.append("# Search benchmarks, %s precision\n" % f["tag"])
        report_search(f["search"], out)
    precs = []
    for f in files:
        for r in f["kern"] + f["flo"]:
            if r["prec"] not in precs:
                precs.append(r["prec"])
    precs.sort(key=lambda p: (prec_rank(p), p))
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
    """The command line: the files named in argv[1:]; the report on stdout."""
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
