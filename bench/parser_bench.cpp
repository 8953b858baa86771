// placeholder: parser throughput benchmark (issue 2)
#include <benchmark/benchmark.h>
BENCHMARK_MAIN();
