#!/usr/bin/env python3
"""Draw the validation cases' curves and tabulate their figures.

Usage: validation_plots.py DIR --out FOLDER [--page PAGE]

DIR is what the validation tests wrote with CT_VALIDATION_OUT=DIR
(tests/test_validation.h): NAME.csv and NAME.plot for each curve, and
results.tsv, one line per measured figure. For each NAME.plot this writes
FOLDER/NAME.png with gnuplot (pngcairo when available, else png). With
--page, the Markdown table of results.tsv replaces the lines between
"<!-- results:begin -->" and "<!-- results:end -->" of PAGE (both markers
must be there). Exit status 1 when a file cannot be read, a plot spec is
malformed or gnuplot fails; the message names the file and line.
"""
import argparse
import csv
import os
import subprocess
import sys

BEGIN, END = "<!-- results:begin -->", "<!-- results:end -->"
STYLES = {"lines": "with lines lw 2", "points": "with points pt 7 ps 0.6",
          "linespoints": "with linespoints lw 1.5 pt 7 ps 0.5",
          "dashed": "with lines lw 2 dt 2"}


def die(msg):
    print("validation_plots.py: " + msg, file=sys.stderr)
    sys.exit(1)


def quote(s):
    return '"' + s.replace("\\", "\\\\").replace('"', '\\"') + '"'


def read_spec(path):
    spec = {}
    with open(path, encoding="utf-8") as f:
        for ln, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if not line:
                continue
            if "\t" not in line:
                die(f"{path}:{ln}: expected KEY<tab>VALUE, got {line!r}")
            k, v = line.split("\t", 1)
            spec[k] = v
    for k in ("title", "xlabel", "ylabel", "series"):
        if k not in spec:
            die(f"{path}: missing key {k!r}")
    series = []
    for i, s in enumerate(x for x in spec["series"].split(";") if x.strip()):
        parts = s.split(",", 3)
        if len(parts) != 4 or not parts[0].isdigit() or not parts[1].isdigit() \
                or parts[2] not in STYLES:
            die(f"{path}: series entry {i + 1} {s!r}: expected XCOL,YCOL,STYLE,LEGEND with "
                f"STYLE one of {', '.join(STYLES)}")
        series.append((int(parts[0]), int(parts[1]), parts[2], parts[3]))
    spec["series"] = series
    spec["options"] = spec.get("options", "").split()
    return spec


def terminal():
    try:
        p = subprocess.run(["gnuplot", "-e", "set terminal pngcairo; exit"],
                           capture_output=True, text=True, check=False)
        return "pngcairo" if p.returncode == 0 and "unknown" not in p.stderr else "png"
    except FileNotFoundError:
        die("gnuplot not found (Debian package gnuplot-nox; make deps installs it)")
    return "png"


def plot(name, spec, src, out, term):
    csv_path = os.path.join(src, name + ".csv")
    if not os.path.exists(csv_path):
        die(f"{csv_path}: missing (the .plot file names it)")
    lines = [f"set terminal {term} size 800,520 font ',10'",
             f"set output {quote(os.path.join(out, name + '.png'))}",
             "set datafile separator ','", "set key autotitle columnhead",
             f"set title {quote(spec['title'])}", f"set xlabel {quote(spec['xlabel'])}",
             f"set ylabel {quote(spec['ylabel'])}", "set grid"]
    if "logx" in spec["options"]:
        lines.append("set logscale x")
    if "logy" in spec["options"]:
        lines.append("set logscale y")
    parts = [f"{quote(csv_path)} using {x}:{y} {STYLES[st]} title {quote(leg)}"
             for x, y, st, leg in spec["series"]]
    lines.append("plot " + ", \\\n     ".join(parts))
    p = subprocess.run(["gnuplot"], input="\n".join(lines) + "\n", capture_output=True,
                       text=True, check=False)
    if p.returncode != 0:
        die(f"gnuplot failed on {name}: {p.stderr.strip()}")


def table(src):
    path = os.path.join(src, "results.tsv")
    if not os.path.exists(path):
        die(f"{path}: missing (run the validation tests with CT_VALIDATION_OUT set)")
    rows = []
    with open(path, encoding="utf-8") as f:
        for ln, r in enumerate(csv.reader(f, delimiter="\t"), 1):
            if len(r) != 8:
                die(f"{path}:{ln}: expected 8 tab-separated fields, got {len(r)}")
            rows.append(r)
    # Criterion may run the cases in any order: sort by case, keep each
    # case's own order of figures.
    order = {}
    for i, r in enumerate(rows):
        order.setdefault(r[0], i)
    rows.sort(key=lambda r: order[r[0]])
    out = ["| case | quantity | measured | reference | error | tolerance | verdict | note |",
           "|---|---|---:|---:|---:|---:|---|---|"]
    for c, q, m, ref, err, tol, v, note in rows:
        tol_s = "reported" if float(tol) == 0 else tol
        out.append(f"| {c} | {q} | {m} | {ref} | {err} | {tol_s} | {v} | {note} |")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("dir")
    ap.add_argument("--out", required=True)
    ap.add_argument("--page")
    a = ap.parse_args()
    if not os.path.isdir(a.dir):
        die(f"{a.dir}: not a folder")
    os.makedirs(a.out, exist_ok=True)
    term = terminal()
    names = sorted(f[:-5] for f in os.listdir(a.dir) if f.endswith(".plot"))
    for n in names:
        plot(n, read_spec(os.path.join(a.dir, n + ".plot")), a.dir, a.out, term)
    rows = table(a.dir)
    if a.page:
        try:
            with open(a.page, encoding="utf-8") as f:
                text = f.read()
        except OSError as e:
            die(f"{a.page}: {e.strerror}")
        if BEGIN not in text or END not in text:
            die(f"{a.page}: the markers {BEGIN} and {END} are missing")
        head, rest = text.split(BEGIN, 1)
        _, tail = rest.split(END, 1)
        with open(a.page, "w", encoding="utf-8") as f:
            f.write(head + BEGIN + "\n" + "\n".join(rows) + "\n" + END + tail)
    print(f"validation: {len(names)} plots in {a.out}, {len(rows) - 2} figures"
          + (f", table in {a.page}" if a.page else ""))


if __name__ == "__main__":
    main()
