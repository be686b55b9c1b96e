"""How steady the host was under a `make bench` run: the spread of each
benchmark's repetitions, summed up per file, for bench/report.py.

Every table of the report shows the median of a benchmark's repetitions
(three by default). On a shared machine the host can move under a run: the
same code measured 1.2 to 1.9 times apart in two runs here. The coefficient
of variation of a benchmark's repetitions (cv = standard deviation / mean of
their wall times; Google Benchmark's "cv" aggregate) says how much it moved
under that one row. This section gives, per file, the median, the 90th
percentile and the largest cv over the rows, and names the rows whose cv
passes NOISY: their medians deserve less trust, and a comparison that
matters should be made in interleaved rounds (bench/interleave.py, the
report's interleaved tables), where both sides see the same host.
Standard library only.
"""

# A row whose repetitions spread by more than this (cv, a fraction) is
# named as noisy.
NOISY = 0.10
# At most this many noisy rows are named per file (the noisiest first).
MAX_NAMED = 12


def quantile(sorted_vals, q):
    """The q-quantile of a sorted, non-empty list, linear between ranks
    (the definition of numpy's default and of statistics.quantiles'
    "inclusive" method)."""
    pos = q * (len(sorted_vals) - 1)
    lo = int(pos)
    hi = min(lo + 1, len(sorted_vals) - 1)
    return sorted_vals[lo] + (sorted_vals[hi] - sorted_vals[lo]) * (pos - lo)


def pct(v):
    """A fraction as a percentage with one decimal."""
    return "%.1f %%" % (100 * v)


def print_noise(files, out):
    """files: (tag, records) per benchmark file, records as
    benchjson.collect() returns them. Prints nothing when no record has a
    cv (a run of one repetition)."""
    rows = []
    for tag, recs in files:
        cvs = [r for r in recs if r.get("cv") is not None and not r.get("error")]
        if cvs:
            rows.append((tag, cvs))
    if not rows:
        return
    out.append("## How steady the host was during this run\n")
    out.append("Each table shows the median of a benchmark's repetitions; cv = standard "
               "deviation / mean of the repetitions' wall times, per benchmark. A row above "
               "%d %% was measured while the host moved under it: trust its median less, and "
               "compare such figures in interleaved rounds (the interleaved tables, "
               "bench/interleave.py), where both sides see the same host. (The cycle's "
               "repetitions run successive cycles of the motion, so their cv also holds the "
               "motion's own variation.)\n" % round(100 * NOISY))
    out.append("| precision | rows | median cv | 90th percentile | largest | rows above %d %% |"
               % round(100 * NOISY))
    out.append("|---|---:|---:|---:|---:|---:|")
    for tag, recs in rows:
        v = sorted(r["cv"] for r in recs)
        out.append("| %s | %d | %s | %s | %s | %d |"
                   % (tag, len(v), pct(quantile(v, 0.5)), pct(quantile(v, 0.9)), pct(v[-1]),
                      sum(1 for c in v if c > NOISY)))
    out.append("")
    for tag, recs in rows:
        noisy = sorted((r for r in recs if r["cv"] > NOISY), key=lambda r: (-r["cv"], r["name"]))
        if not noisy:
            continue
        names = ["%s (%s)" % (r["name"], pct(r["cv"])) for r in noisy[:MAX_NAMED]]
        more = len(noisy) - len(names)
        out.append("Noisiest rows, %s: %s%s.\n"
                   % (tag, ", ".join(names), " and %d more" % more if more > 0 else ""))
