/*!
  \file vispmorph-perf-reporter.h
  \brief The console reporter of the micro-benchmarks, keeping the CPU time of each benchmark's fastest repetition
  for the ratio tables they print at the end.
*/
#ifndef VISPMORPH_PERF_REPORTER_H
#define VISPMORPH_PERF_REPORTER_H

#include <benchmark/benchmark.h>

#include "vispmorph-source-commit.h"

#include <algorithm>
#include <map>
#include <string>
#include <vector>

class vpMorphPerfReporter : public benchmark::ConsoleReporter
{
public:
  void ReportRuns(const std::vector<Run> &runs) override
  {
    for (const Run &r : runs)
      if (r.run_type == Run::RT_Iteration && r.iterations > 0) {
        // Fastest repetition: the least disturbed by whatever else the machine runs; CPU time: robust to other
        // processes taking the core.
        const std::string name = r.run_name.str();
        const double t = r.GetAdjustedCPUTime();
        m_time[name] = m_time.count(name) ? std::min(m_time[name], t) : t;
      }
    ConsoleReporter::ReportRuns(runs);
  }

protected:
  //! Benchmark name -> CPU time per iteration of its fastest repetition (the benchmark's time unit).
  std::map<std::string, double> m_time;
};

/*!
  The main() of a micro-benchmark: Google Benchmark's options, every benchmark run and reported by \e reporter (a
  vpMorphPerfReporter whose Finalize() prints the ratio table). The context of every report (the console's header, the
  JSON of --benchmark_out) holds the commit the tool was built at. Exit status 1 on an unknown option.
*/
inline int vpMorphPerfMain(int argc, char **argv, vpMorphPerfReporter &reporter)
{
  benchmark::AddCustomContext("commit", VISPMORPH_SOURCE_COMMIT);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv))
    return 1;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  benchmark::Shutdown();
  return 0;
}

#endif
