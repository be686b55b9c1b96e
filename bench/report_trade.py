"""The speed/accuracy trade table of bench/report.py (bench_trade.c).

One row per knob setting (trade/<knob>/<setting>) with its cost and accuracy
counters, the measures named by the label ("knob=K setting=S; cost: ...;
accuracy: ...; prec=P case"), the x_* counters as further figures. The
precision rows merge the files' trade/precision/<prec> runs, and their
accuracy comes from the output of bench/trade_precision.py --json when that
file is given too (its "trade_precision" object).
Standard library only.
"""
import re

from benchjson import NAME_TAIL, split_named

TRADE_RE = re.compile(r"^trade/(?P<knob>[^/]+)/(?P<setting>[^/]+)" + NAME_TAIL)
# The knobs in the order of the table; any other after them.
TRADE_KNOBS = ["search", "filter", "margin", "renumber", "dense", "cells", "quad", "precision",
               "assembly", "skip", "stiffness", "safety"]


def parse_trade(other, prec):
    """Split the trade records (trade/<knob>/<setting>) from the others and
    parse their labels."""
    trade, rest = split_named(other, TRADE_RE)
    for r in trade:
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
    return trade, rest


def fmt_val(v):
    """A figure of the trade table: four significant digits, an exponent
    when it is very large or very small."""
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
