"""How bench/report.py writes its numbers in the Markdown tables: a time with
its unit, a count, a figure in ns; and the order of the precisions in the
tables that show several.
Standard library only.
"""

# The precisions in the order the tables show them; any other after them.
PREC_ORDER = ["double", "single"]


def prec_rank(prec):
    """The place of a precision in PREC_ORDER, 99 for any other."""
    return PREC_ORDER.index(prec) if prec in PREC_ORDER else 99


def fmt_time(ns):
    """A time in ns with three significant digits and the largest unit below it."""
    if ns is None:
        return "-"
    for unit, scale in (("s", 1e9), ("ms", 1e6), ("µs", 1e3)):
        if ns >= scale:
            return "%.3g %s" % (ns / scale, unit)
    return "%.3g ns" % ns


def fmt_num(v, digits=1):
    """A whole number as such, any other with the given decimals."""
    if v is None:
        return "-"
    if abs(v - round(v)) < 1e-9 and abs(v) >= 1:
        return "%d" % round(v)
    return "%.*f" % (digits, v)


def fmt_ns(v):
    """A figure in ns: one decimal below 1000, none from there."""
    if v is None:
        return "-"
    return "%.1f" % v if v < 1000 else "%.0f" % v
