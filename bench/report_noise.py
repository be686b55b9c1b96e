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

A row's repetitions can also agree while the host differed for all of them
(between two runs, it had moved its two virtual CPUs). The bench probes the
host after the calls of a benchmark (bench/bench_host.c, counters host_*);
print_host gives each file's spread of the probe and names the rows measured
while the host differed from the rest of the run.
Standard library only.
"""
from benchjson import HOST_BARRIER, HOST_CHAIN, HOST_OFF, HOST_READ, HOST_THREADS

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
    cv (a run of one repetition) or the host probe's counters."""
    rows = []
    for tag, recs in files:
        cvs = [r for r in recs if r.get("cv") is not None and not r.get("error")]
        if cvs:
            rows.append((tag, cvs))
    if not rows and not any(host_probed(recs) for _, recs in files):
        return
    out.append("## How steady the host was during this run\n")
    if not rows:
        print_host(files, out)
        return
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
    print_host(files, out)


# (counter, per team size, its name in the report, its format). The barrier
# is always on every processor: one reference for the whole file.
HOST_KEYS = ((HOST_CHAIN, True, "chain µs", "%.1f"),
             (HOST_BARRIER, False, "barrier µs", "%.2f"),
             (HOST_READ, True, "read GB/s", "%.1f"))


def host_group(rec, per_team):
    """The group a record's figure is compared within: its team size, or 0
    for a figure taken on every processor."""
    return int(rec["counters"][HOST_THREADS]) if per_team else 0


def host_refs(probed):
    """{(counter, group): the median of the group's figures}."""
    vals = {}
    for r in probed:
        for key, per_team, _, _ in HOST_KEYS:
            if r["counters"].get(key, 0) > 0:
                vals.setdefault((key, host_group(r, per_team)), []).append(r["counters"][key])
    return {k: quantile(sorted(v), 0.5) for k, v in vals.items()}


def host_probed(recs):
    """The records that carry the probe's counters."""
    return [r for r in recs if not r.get("error") and r["counters"].get(HOST_THREADS, 0) >= 1
            and r["counters"].get(HOST_CHAIN, 0) > 0 and r["counters"].get(HOST_READ, 0) > 0]


def host_offsets(recs):
    """[(record, {name: figure / the file's median})] for the probed
    records: above 1, a time longer or a bandwidth higher than usual."""
    probed = host_probed(recs)
    refs = host_refs(probed)
    out = []
    for r in probed:
        off = {}
        for key, per_team, name, _ in HOST_KEYS:
            ref = refs.get((key, host_group(r, per_team)), 0)
            if r["counters"].get(key, 0) > 0 and ref > 0:
                off[name] = r["counters"][key] / ref
        out.append((r, off))
    return out


def host_apart(off):
    """The figures of an offsets dict beyond HOST_OFF either way, as text
    ("barrier µs ×4.00, read GB/s ×0.60"), or ""."""
    return ", ".join("%s ×%.2f" % (k.split()[0], v) for k, v in off.items()
                     if v > HOST_OFF or v < 1 / HOST_OFF)


def annotate_host(recs):
    """Store, on each probed record measured while the host differed from
    the rest of its file, that difference as text (its "host")."""
    for r, off in host_offsets(recs):
        apart = host_apart(off)
        if apart:
            r["host"] = apart


def host_note(*recs, inside=False):
    """" (host: ...)", or ", host: ..." inside a parenthesis already open:
    how the host differed from the rest of the run under the records a
    figure is read from; "" when it did not."""
    v = [r["host"] for r in recs if r and r.get("host")]
    if not v:
        return ""
    text = "host: " + "; ".join(v)
    return ", " + text if inside else " (%s)" % text


def print_host(files, out):
    """The host probe's table, per file and team size, and the rows
    measured while the host differed; nothing when no record carries the
    probe's counters."""
    rows = [(tag, host_offsets(recs)) for tag, recs in files]
    rows = [(tag, hs) for tag, hs in rows if hs]
    if not rows:
        return
    out.append("The repetitions of a row can agree while the whole row ran on a different host: "
               "two runs of this bench on one of these shared virtual machines read the same "
               "rows up to 2.5 times apart, each row steady. Between two such runs the host "
               "had moved its two virtual CPUs: a barrier of the two took 0.19 µs in one and "
               "0.8 in the other, and the rows moved both ways (sync-bound rows on two threads "
               "faster with the short barrier, memory-bound rows on two threads and rows on "
               "one thread faster with the long one). Right after the calls of a benchmark "
               "the bench probes the host (bench/bench_host.c): a fixed chain of integer "
               "operations on each thread the row used (the cores' clock and share), one "
               "barrier of a team on every processor (how far apart the virtual CPUs are) "
               "and one 64 MiB read shared among the row's threads (the memory bus). Below: "
               "each figure's median, lowest and highest over the rows (the medians of their "
               "repetitions). A row whose figure is more than %.2f times off the run's median "
               "for as many threads was measured while the host differed from the rest of "
               "the run: compare it with other runs, not with its neighbours.\n" % HOST_OFF)
    out.append("| precision | threads | rows | %s | rows off |"
               % " | ".join("%s: median (lowest-highest)" % name for _, _, name, _ in HOST_KEYS))
    out.append("|---|---:|---:|%s---:|" % ("---|" * len(HOST_KEYS)))
    for tag, hs in rows:
        for t in sorted(set(int(r["counters"][HOST_THREADS]) for r, _ in hs)):
            mine = [(r, off) for r, off in hs if int(r["counters"][HOST_THREADS]) == t]
            cells = []
            for key, _, _, fmt in HOST_KEYS:
                v = sorted(r["counters"][key] for r, _ in mine if r["counters"].get(key, 0) > 0)
                cells.append(("%s (%s-%s)" % (fmt, fmt, fmt) % (quantile(v, 0.5), v[0], v[-1]))
                             if v else "-")
            out.append("| %s | %d | %d | %s | %d |"
                       % (tag, t, len(mine), " | ".join(cells),
                          sum(1 for _, off in mine if host_apart(off))))
    out.append("")
    for tag, hs in rows:
        apart = [(r, off) for r, off in hs if host_apart(off)]
        worst = lambda off: max(max(v, 1 / v) for v in off.values())
        apart.sort(key=lambda h: (-worst(h[1]), h[0]["name"]))
        if not apart:
            continue
        names = ["%s (%s)" % (r["name"], host_apart(off)) for r, off in apart[:MAX_NAMED]]
        more = len(apart) - len(names)
        out.append("Rows measured while the host differed, %s: %s%s.\n"
                   % (tag, ", ".join(names), " and %d more" % more if more > 0 else ""))
