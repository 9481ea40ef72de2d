/*!
  \file vispmorph-perf-match.cpp
  \brief Micro-benchmark of the cyclic correspondence: brute force vs fast exact vs windowed search.

  Two random star-shaped N-vertex polygons (seeded), N = 32, 64, 128, 256. The brute force runs the very
  same single-start kernel as the fast search from every start, so the ratio printed at the end measures
  the algorithm (Maes' divide and conquer), not the implementation. Single threaded.

  \code
  vispmorph-perf-match --benchmark_repetitions=5   # all, then the ratio table
  vispmorph-perf-match --benchmark_filter=fast
  \endcode
*/
#include <benchmark/benchmark.h>

#include "vispmorph-perf-reporter.h"

#include <cmath>
#include <iomanip>
#include <iostream>
#include <map>
#include <random>

#include <visp3/morph/vpMorphMatcher.h>

namespace
{
vpMorphContour randomPolygon(std::mt19937 &rng, std::size_t n)
{
  std::uniform_real_distribution<double> ang(0.0, 2 * M_PI), rad(0.6, 1.4);
  std::vector<double> a(n), x(n), y(n);
  for (double &v : a)
    v = ang(rng);
  std::sort(a.begin(), a.end());
  for (std::size_t k = 0; k < n; ++k) {
    const double r = 100.0 * rad(rng);
    x[k] = r * std::cos(a[k]);
    y[k] = r * std::sin(a[k]);
  }
  return vpMorphContour(x, y);
}

struct Pair
{
  vpMorphContour A, B;
};

Pair makePair(int n)
{
  std::mt19937 rng(1000 + n);
  return {randomPolygon(rng, n), randomPolygon(rng, n)};
}

void BM_brute(benchmark::State &state)
{
  const Pair p = makePair(static_cast<int>(state.range(0)));
  vpMorphMatcher matcher;
  for (auto _ : state)
    benchmark::DoNotOptimize(matcher.matchBruteForce(p.A, p.B).work());
}

void BM_fast(benchmark::State &state)
{
  const Pair p = makePair(static_cast<int>(state.range(0)));
  vpMorphMatcher matcher;
  for (auto _ : state)
    benchmark::DoNotOptimize(matcher.match(p.A, p.B).work());
}

// Tracking: starts within +-4 vertices of the previous frame's start.
void BM_window(benchmark::State &state)
{
  const Pair p = makePair(static_cast<int>(state.range(0)));
  vpMorphMatcher matcher;
  const std::size_t center = matcher.match(p.A, p.B).start().second;
  for (auto _ : state)
    benchmark::DoNotOptimize(matcher.matchWindow(p.A, p.B, 0, center, 4).work());
}

BENCHMARK(BM_brute)->RangeMultiplier(2)->Range(32, 256)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_fast)->RangeMultiplier(2)->Range(32, 256)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_window)->RangeMultiplier(2)->Range(32, 256)->Unit(benchmark::kMicrosecond);

// Console output plus, at the end, the speed-up of fast and window over brute force at each N.
class RatioReporter : public vpMorphPerfReporter
{
public:
  void Finalize() override
  {
    ConsoleReporter::Finalize();
    std::ostream &os = GetOutputStream();
    os << "\nspeed-up over brute force (same kernel, same process; CPU time of the fastest repetition)\n"
       << std::setw(6) << "N" << std::setw(14) << "brute us" << std::setw(14) << "fast us" << std::setw(10) << "fast x"
       << std::setw(14) << "window us" << std::setw(10) << "window x"
       << "\n";
    for (int n = 32; n <= 256; n *= 2) {
      const std::string s = "/" + std::to_string(n);
      if (!m_time.count("BM_brute" + s) || !m_time.count("BM_fast" + s))
        continue;
      const double b = m_time["BM_brute" + s], f = m_time["BM_fast" + s];
      const double w = m_time.count("BM_window" + s) ? m_time["BM_window" + s] : NAN;
      os << std::setw(6) << n << std::fixed << std::setprecision(1) << std::setw(14) << b << std::setw(14) << f
         << std::setw(10) << b / f << std::setw(14) << w << std::setw(10) << b / w << "\n";
    }
  }
};
} // namespace

int main(int argc, char **argv)
{
  RatioReporter reporter;
  return vpMorphPerfMain(argc, argv, reporter);
}
