"""Reading the Google Benchmark JSON of `make bench`, shared by bench/report.py
and bench/plots.py.

collect() turns the rows of a file into one record per run: its name (the
run name without Google Benchmark's timing suffix), the median time in ns (the
"median" aggregate when present, else the median of the repetition rows),
the coefficient of variation of the repetitions' times (the "cv" aggregate,
else computed from two or more repetition rows; None without either), every
numeric user counter, the label, or the error. precision_of() tells the
precision of a file, split_named() splits the records whose name matches a
pattern and adds the pattern's fields to them, and the patterns of the run
names that both scripts read (the searches and the peers) are here.
Standard library only.
"""
import math
import re
import statistics

TIME_NS = {"ns": 1.0, "us": 1e3, "ms": 1e6, "s": 1e9}
# Fields of a Google Benchmark row that are not user counters.
STD_KEYS = {"name", "family_index", "per_family_instance_index", "run_name", "run_type",
            "repetitions", "repetition_index", "aggregate_name", "aggregate_unit",
            "iterations", "real_time", "cpu_time", "time_unit", "items_per_second",
            "bytes_per_second", "label", "error_occurred", "error_message", "threads"}
# What may follow the fields of a run name once base_name() has taken the
# timing suffix away: a fixed iteration count, and the suffix itself.
NAME_TAIL = r"(?:/iterations:\d+)?(?:/(?:real_time|manual_time))?$"
# The host probe's counters (bench/bench_host.c, set by the shim after the
# calls of a benchmark): the benchmark's team size, a fixed chain's time on
# its slowest thread, one barrier of a team on every processor, and one
# read's bandwidth shared among the benchmark's team; and how far (either
# way) a figure may stray from the run's usual one before the host counts as
# different (the report's rows "measured while the host differed",
# interleave.py's rounds under two placements of the CPUs).
HOST_THREADS = "host_threads"
HOST_CHAIN = "host_chain_us"
HOST_BARRIER = "host_barrier_us"
HOST_READ = "host_read_GBps"
HOST_OFF = 1.25
# The search benchmarks (bench_search.c) and their algorithms, in the order
# the tables and the plots show them.
ALGOS = ["direct", "topological", "bucket", "bsp"]
SEARCH_RE = re.compile(
    r"^search/(?P<family>[^/]+)/(?P<algo>[^/]+)/(?P<numbering>[^/]+)/t(?P<threads>\d+)/"
    r"(?P<n>\d+)(?:/(?:real_time|manual_time))?$")
# The peers' benchmarks (bench_peers.c).
PEER_RE = re.compile(
    r"^peer/(?P<family>[^/]+)/(?P<peer>[^/@]+)(?:@(?P<setting>[^/]+))?/t(?P<threads>\d+)/"
    r"(?P<n>\d+)$")


def base_name(run_name):
    """The run name without its fixed iteration count and timing suffix."""
    return re.sub(r"(/iterations:\d+)?/(real_time|manual_time)$", "", run_name)


def numeric(v):
    """Whether a JSON value is a finite number (not a boolean)."""
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def row_time_ns(row):
    """The wall time of one JSON row in ns."""
    return row["real_time"] * TIME_NS[row.get("time_unit", "ns")]


def collect(benchmarks):
    """One record per run: name, median time (ns), every counter, label, error.

    The counters are every key of the rows that is not a standard field of
    Google Benchmark (STD_KEYS) and holds a finite number; from the repetition
    rows, each counter is the median of the rows that have it."""
    runs, order = {}, []
    for b in benchmarks:
        key = b.get("run_name", b.get("name", ""))
        if key not in runs:
            runs[key] = {"median": None, "cv": None, "reps": [], "error": None}
            order.append(key)
        r = runs[key]
        if b.get("error_occurred"):
            r["error"] = b.get("error_message", "error")
        elif b.get("run_type") == "aggregate":
            if b.get("aggregate_name") == "median":
                r["median"] = b
            elif b.get("aggregate_name") == "cv" and numeric(b.get("real_time")):
                r["cv"] = float(b["real_time"])
        else:
            r["reps"].append(b)
    out = []
    for key in order:
        r = runs[key]
        rec = {"name": base_name(key), "error": None, "label": "", "time_ns": None,
               "cv": r["cv"], "counters": {}}
        times = [row_time_ns(x) for x in r["reps"]]
        if rec["cv"] is None and len(times) >= 2 and statistics.mean(times) > 0:
            rec["cv"] = statistics.stdev(times) / statistics.mean(times)
        if r["median"] is not None:
            src = r["median"]
            rec["time_ns"] = row_time_ns(src)
            rec["label"] = src.get("label", "")
            rec["counters"] = {k: float(v) for k, v in src.items()
                               if k not in STD_KEYS and numeric(v)}
        elif r["reps"]:
            reps = r["reps"]
            rec["time_ns"] = statistics.median(row_time_ns(x) for x in reps)
            rec["label"] = reps[-1].get("label", "")
            keys = []
            for x in reps:
                keys += [k for k, v in x.items()
                         if k not in STD_KEYS and numeric(v) and k not in keys]
            for k in keys:
                vals = [float(x[k]) for x in reps if numeric(x.get(k))]
                rec["counters"][k] = statistics.median(vals)
        else:
            rec["error"] = r["error"] or "no result"
        out.append(rec)
    return out


def label_precision(label):
    """The precision a label starts with ("prec=single ..."), or None."""
    m = re.match(r"prec=(\w+)", label or "")
    return m.group(1) if m else None


def precision_of(data):
    """The precision of one parsed benchmark file: its context's ct_precision,
    else the precision= of its ct_build, else the first label's prec=, else
    "?"."""
    ctx = data.get("context", {})
    if ctx.get("ct_precision"):
        return ctx["ct_precision"]
    m = re.search(r"precision=(\w+)", ctx.get("ct_build", ""))
    if m:
        return m.group(1)
    for b in data.get("benchmarks", []):
        p = label_precision(b.get("label", ""))
        if p:
            return p
    return "?"


def split_named(records, regex):
    """Split the records whose name matches regex from the others. The named
    groups of regex become fields of the record; threads and n, when among
    them, as integers."""
    hit, rest = [], []
    for r in records:
        m = regex.match(r["name"])
        if not m:
            rest.append(r)
            continue
        fields = m.groupdict()
        r.update(fields)
        for k in ("threads", "n"):
            if k in fields:
                r[k] = int(r[k])
        hit.append(r)
    return hit, rest
