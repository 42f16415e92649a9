#!/usr/bin/env bash
# How much two processes slow each other down on this machine through memory alone: a
# STREAM-like triad a = b + s c on arrays far larger than the caches, timed in one
# process alone and in two at once (doc/scaling.md, "Speedup 1 → 2 ranks"). The solver's
# matrix products and AMG smoothers stream their matrices the same way, so the ratio
# bounds what a second rank can give them on a shared memory bus.
#
# Usage (regenerate):  bash benchmarks/memory_bandwidth.sh
# WORK=DIR overrides the work directory; MB=N the size of each array (800 by default).
set -euo pipefail
top="$(cd "$(dirname "$0")/.." && pwd)"
work="${WORK:-$top/benchmarks/work/memory_bandwidth}"
mb="${MB:-800}"
mkdir -p "$work"
cat > "$work/triad.cc" <<'CC'
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>
// Best of ten triads over arrays of argv[1] MB each; prints GB/s (three arrays moved).
int main(int, char **argv)
{
  const std::size_t n = std::atol(argv[1]) * 1000000 / sizeof(double);
  std::vector<double> a(n, 0.0), b(n, 1.0), c(n, 2.0);
  double best = 1e30;
  for (int k = 0; k < 10; ++k)
    {
      const auto start = std::chrono::steady_clock::now();
      for (std::size_t i = 0; i < n; ++i)
        a[i] = b[i] + 0.5 * c[i];
      const std::chrono::duration<double> t = std::chrono::steady_clock::now() - start;
      best = t.count() < best ? t.count() : best;
    }
  std::printf("%.2f %.1f\n", 3 * n * sizeof(double) / best / 1e9, a[n / 2]);
}
CC
g++ -O2 -o "$work/triad" "$work/triad.cc"
alone=$("$work/triad" "$mb" | cut -d' ' -f1)
"$work/triad" "$mb" > "$work/first" & "$work/triad" "$mb" > "$work/second"; wait
first=$(cut -d' ' -f1 "$work/first"); second=$(cut -d' ' -f1 "$work/second")
echo "triad, arrays of $mb MB: one process alone $alone GB/s; two at once $first + $second GB/s"
/usr/bin/python3 -c "print('two processes move %.2f times the data of one' % (($first + $second) / $alone))"
