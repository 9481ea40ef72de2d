/*!
  \file vpMorphBenchTimings.h
  \brief The benchmark's compute times, apart from its results: per run, per period, and per set with percentiles.
*/
#ifndef VP_MORPH_BENCH_TIMINGS_H
#define VP_MORPH_BENCH_TIMINGS_H

#include <istream>
#include <map>
#include <string>
#include <vector>

#include <visp3/morph_bench/vpMorphBenchResult.h>

/*!
  \class vpMorphBenchTimings
  \ingroup group_morph_bench
  \brief Collects the compute times of runs (timings.csv) and summarises them per set, robot and controller.

  The times are the CPU time of each run's thread (vpMorphThreadCpuClock): measure (the silhouette's extraction, or
  the tag's detection), control (the law). A period's compute is measure + control, for every measured period but the
  first (its recognition and plan; vpMorphBenchResult::periodMs), rendering excluded. Per group: the median and the
  95th percentile (nearest rank) of the periods, in ms and as a ratio to the machine yardstick of the run they came
  from (each row carries its run's), the medians of a period's measure and of its control (where a typical period's
  time goes; they need not add up to the median period), the mean measure and control (where the rare long periods
  weigh), the worst control, and the mean CPU time of a whole run (rendering included: what a sweep of such runs
  costs).

  They are kept apart from runs.csv because they differ from one run to the next: merged shards give the results
  of one run to the byte, and these times as they were taken.

  \code
  vpMorphBenchTimings timings;
  for (const vpMorphBenchResult &r : results)
    timings.add(r, yardstickMs);                   // the machine's yardstick of this run
  std::cout << timings.markdown();
  \endcode
  \sa vpMorphThreadCpuClock, \ref page_benchmarks
*/
class vpMorphBenchTimings
{
public:
  //! One group's times.
  struct Summary
  {
    std::string set;            //!< the set
    std::string robot;          //!< robot kind name
    std::string controller;     //!< controller name
    unsigned int runs = 0;      //!< runs
    unsigned int periods = 0;   //!< periods measured
    double medianMs = 0;        //!< median compute per period (NaN without periods)
    double p95Ms = 0;           //!< 95th percentile per period
    double medianRatio = 0;     //!< median per period over its run's yardstick (NaN without one)
    double p95Ratio = 0;        //!< 95th percentile of that ratio
    double medianMeasureMs = 0; //!< median measure time of a period (NaN without the periods' measures)
    double medianControlMs = 0; //!< median control time of a period
    double meanMeasureMs = 0;   //!< mean measure time over the runs that measured
    double meanControlMs = 0;   //!< mean control time
    double maxControlMs = 0;    //!< worst control time
    double meanRunCpuS = 0;     //!< CPU time of a whole run, rendering included (what a sweep costs), s
  };

  //! Adds a run's times, with the machine yardstick of its run (ms, 0: unknown).
  void add(const vpMorphBenchResult &r, double yardstickMs);
  //! Adds the rows of a timings.csv text. \throw vpMorphException::ioError for another header or a bad row.
  void readTimings(std::istream &in, const std::string &what = "timings.csv");
  //! Canonical order: set, scenario, robot, controller (as vpMorphBenchReport::sortRows()).
  void sortRows();
  //! The timings.csv rows, without the header.
  std::vector<std::string> rows() const;
  //! Summaries per set, robot and controller.
  std::vector<Summary> summarize() const;

  //! The header line of timings.csv.
  static std::string header();
  //! JSON: \e meta (the runs' machine, command, wall time, yardsticks) and the summaries.
  std::string json(const std::map<std::string, std::string> &meta) const;
  //! A markdown table, one line per summary.
  std::string markdown() const;

private:
  struct Entry
  {
    std::string set, robot, controller, object;
    int scenario = 0;
    double yardstick = 0, measure = 0, control = 0, maxControl = 0, runCpu = 0;
    std::vector<double> periods, periodMeasures; // each period's compute, and its measure's part
  };
  std::vector<Entry> m_entries;
};

#endif
