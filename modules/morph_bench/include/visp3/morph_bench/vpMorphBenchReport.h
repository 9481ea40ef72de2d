/*!
  \file vpMorphBenchReport.h
  \brief Benchmark results as CSV rows, and their summary per set and controller as JSON and markdown.
*/
#ifndef VP_MORPH_BENCH_REPORT_H
#define VP_MORPH_BENCH_REPORT_H

#include <map>
#include <string>
#include <vector>

#include <visp3/morph_bench/vpMorphBenchResult.h>

/*!
  \class vpMorphBenchReport
  \ingroup group_morph_bench
  \brief Collects results and summarises them the way the comparison is read.

  CSV: runsHeader()/runsRow() (one row per run, written as runs finish so that an interrupted bench keeps what it
  did) and curvesRows() (truth error per iteration). The summary groups by (set, robot, controller), runs with
  timed faults by fault kind as well (set "faults/pose-jump", ...): success rate,
  median settling iteration, median camera path and path ratio of the successful runs, median final errors
  (truth and tag) of all runs, mean and worst compute times, and the failure reasons with their counts.
*/
class vpMorphBenchReport
{
public:
  struct Summary
  {
    std::string set, robot, controller;
    unsigned int runs = 0, successes = 0;
    double medianIterations = 0; //!< settling iteration of the successful runs (NaN if none)
    double medianPathLength = 0; //!< m, successful runs
    double medianPathRatio = 0;  //!< successful runs with a defined ratio (NaN if none)
    double medianFinalTranslation = 0, medianFinalRotation = 0;       //!< truth, runs that started (m, rad)
    double medianFinalTagTranslation = 0, medianFinalTagRotation = 0; //!< tag, runs that started where it was seen
    //! Means over the runs that started (an unreachable start runs no iteration; NaN when none did), and the worst.
    double meanMeasureMs = 0, meanControlMs = 0, maxControlMs = 0;
    std::map<std::string, unsigned int> failures; //!< reason -> count (without "none")
    unsigned int holds = 0, replans = 0, rerecognitions = 0; //!< sums over the runs (timed faults)
    double successRate() const { return runs ? double(successes) / runs : 0.0; }
  };

  void add(const vpMorphBenchResult &r);
  const std::vector<vpMorphBenchResult> &results() const { return m_results; }
  //! Summaries in the order: set, robot (first seen), controller (vpMorphBenchController::names() order).
  std::vector<Summary> summarize() const;

  static std::string runsHeader();
  static std::string runsRow(const vpMorphBenchResult &r);
  static std::string curvesHeader();
  static std::string curvesRows(const vpMorphBenchResult &r);
  //! JSON object: \e meta (free key/values: command, seed, machine...) and the summaries.
  std::string summaryJson(const std::map<std::string, std::string> &meta) const;
  //! A markdown table, one line per summary.
  std::string summaryMarkdown() const;

private:
  std::vector<vpMorphBenchResult> m_results;
};

#endif
