// The benchmark executable's entry point (benchmarks live in bench_*.cpp).
#include <benchmark/benchmark.h>

BENCHMARK_MAIN();
