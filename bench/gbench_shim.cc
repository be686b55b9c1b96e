// gbench_shim.cc -- the C API of gbench.h implemented over Google
// Benchmark (1.7 API). Each C benchmark is registered as a lambda holding
// the C function pointer and its argument; gb_state is the
// benchmark::State itself, seen from C as an opaque type.
#include "gbench.h"

#include <benchmark/benchmark.h>

#include <exception>
#include <string>

namespace {

benchmark::State &S(gb_state *st) { return *reinterpret_cast<benchmark::State *>(st); }

// The host probe run after every call of a benchmark (gb_set_host_probe).
gb_probe_fn host_probe = nullptr;

benchmark::Counter::Flags counter_flags(int f)
{
    int g = benchmark::Counter::kDefaults;
    if (f & GB_RATE)
        g |= benchmark::Counter::kIsRate;
    if (f & GB_AVG_THREADS)
        g |= benchmark::Counter::kAvgThreads;
    if (f & GB_ITER_INVARIANT)
        g |= benchmark::Counter::kIsIterationInvariant;
    if (f & GB_AVG_ITERATIONS)
        g |= benchmark::Counter::kAvgIterations;
    if (f & GB_INVERT)
        g |= benchmark::Counter::kInvert;
    return static_cast<benchmark::Counter::Flags>(g);
}

} // namespace

extern "C" {

int gb_register(const char *name, gb_fn fn, void *arg, int64_t range0, int use_real_time,
                int64_t iterations, double min_time_s)
{
    if (!name || !fn)
        return -1;
    auto *b = benchmark::RegisterBenchmark(name, [fn, arg](benchmark::State &st) {
        fn(reinterpret_cast<gb_state *>(&st), arg);
        double v[GB_HOST_N];
        if (host_probe && !st.error_occurred() && host_probe(v) == 0) {
            st.counters[GB_HOST_THREADS] = benchmark::Counter(v[0]);
            st.counters[GB_HOST_CHAIN] = benchmark::Counter(v[1]);
            if (v[2] > 0) // no barrier with one processor (and no 0/0 in its cv)
                st.counters[GB_HOST_BARRIER] = benchmark::Counter(v[2]);
            st.counters[GB_HOST_READ] = benchmark::Counter(v[3]);
        }
    });
    if (range0 >= 0)
        b->Arg(range0);
    if (use_real_time)
        b->UseRealTime();
    if (iterations > 0)
        b->Iterations(iterations);
    else if (min_time_s > 0)
        b->MinTime(min_time_s);
    return 0;
}

int gb_keep_running(gb_state *st) { return S(st).KeepRunning() ? 1 : 0; }

int64_t gb_range(gb_state *st, int i) { return S(st).range(static_cast<std::size_t>(i)); }

int64_t gb_iterations(gb_state *st) { return static_cast<int64_t>(S(st).iterations()); }

void gb_set_counter(gb_state *st, const char *name, double value, int flags)
{
    S(st).counters[name] = benchmark::Counter(value, counter_flags(flags));
}

void gb_set_label(gb_state *st, const char *label) { S(st).SetLabel(label); }

void gb_skip_with_error(gb_state *st, const char *msg) { S(st).SkipWithError(msg); }

void gb_pause_timing(gb_state *st) { S(st).PauseTiming(); }

void gb_resume_timing(gb_state *st) { S(st).ResumeTiming(); }

void gb_set_items_processed(gb_state *st, int64_t n) { S(st).SetItemsProcessed(n); }

void gb_set_host_probe(gb_probe_fn fn) { host_probe = fn; }

void gb_add_context(const char *key, const char *value)
{
    if (key && value)
        benchmark::AddCustomContext(key, value);
}

int gb_run(int *argc, char **argv)
{
    try {
        benchmark::Initialize(argc, argv);
        if (benchmark::ReportUnrecognizedArguments(*argc, argv))
            return 1;
        std::size_t n = benchmark::RunSpecifiedBenchmarks();
        benchmark::Shutdown();
        return n > 0 ? 0 : 2;
    } catch (const std::exception &) {
        return 3;
    }
}

} // extern "C"
