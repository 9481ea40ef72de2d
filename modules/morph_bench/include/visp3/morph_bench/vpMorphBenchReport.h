/*!
  \file vpMorphBenchReport.h
  \brief Benchmark results as CSV rows, and their summary per set and controller as JSON and markdown.
*/
#ifndef VP_MORPH_BENCH_REPORT_H
#define VP_MORPH_BENCH_REPORT_H

#include <istream>
#include <map>
#include <string>
#include <vector>

#include <visp3/morph_bench/vpMorphBenchResult.h>

/*!
  \class vpMorphBenchReport
  \ingroup group_morph_bench
  \brief Collects results as runs.csv rows and summarises them the way the comparison is read.

  runs.csv holds one row per run and nothing that depends on the machine (the compute times are
  vpMorphBenchTimings'): a sweep split into shards and merged (readRuns(), sortRows()) gives the same rows, the
  same summaries and the same files as one run, to the byte. The summaries are computed from the rows as written
  (add() formats the result, then reads the row back), so that a merge cannot round differently.

  Groups: (set, robot, controller), the set named with the run's fault kinds ("faults/pose-jump") and apart for a
  view with a rotational symmetry ("planar/symmetric", scored modulo it) or whose pose cannot be bounded at pixel
  noise ("planar/unobservable"; vpMorphBenchObservability). Per group: the runs, the set-up failures (scenarios that
  could not be set up: no run, left out of the rates), the successes and the false convergences with their 95 %
  intervals (Wilson's; for a count of 0 the upper bound is 3 / n), the median settling iteration, camera path and
  path ratio of the successful runs, the median final errors (truth, tag, largest overlap) of the runs that started,
  and the failure reasons with their counts.

  \code
  vpMorphBenchReport report;
  for (const vpMorphBenchResult &r : bench.runAll(starts, {"morph", "pbvs"}))
    report.add(r);
  std::cout << report.summaryMarkdown();                 // one line per (set, robot, controller)
  \endcode
  \sa vpMorphBenchTimings, \ref page_benchmarks
*/
class vpMorphBenchReport
{
public:
  //! One group's figures (see the class description).
  struct Summary
  {
    std::string set;                    //!< the set, with its fault kinds or its scoring ("planar/symmetric")
    std::string robot;                  //!< robot kind name
    std::string controller;             //!< controller name
    unsigned int runs = 0;              //!< rows
    unsigned int setups = 0;            //!< rows that could not be set up (failure "setup"): out of the rates
    unsigned int successes = 0;         //!< successful runs
    unsigned int falseConverged = 0;    //!< runs converged with the truth out of tolerance
    unsigned int declaredConverged = 0; //!< successful runs whose controller declared convergence (others stopped)
    //! Successful runs that stopped at the goal without declaring convergence, by what their verification found
    //! (vpMorphBenchResult::verification; runs without one not counted).
    std::map<std::string, unsigned int> unverifiedSuccesses;
    double successLow = 0;                        //!< low end of the success rate's 95 % interval
    double successHigh = 0;                       //!< high end of the success rate's 95 % interval
    double falseConvergedHigh = 0;                //!< upper end of the false-convergence rate's 95 % interval
    double medianIterations = 0;                  //!< settling iteration of the successful runs (NaN if none)
    double medianPathLength = 0;                  //!< m, successful runs
    double medianPathRatio = 0;                   //!< successful runs with a defined ratio (NaN if none)
    double medianFinalTranslation = 0;            //!< truth, runs that started (m)
    double medianFinalRotation = 0;               //!< truth, runs that started (rad)
    double medianFinalTagTranslation = 0;         //!< tag, runs that started where it was seen (m)
    double medianFinalTagRotation = 0;            //!< tag (rad)
    double medianFinalOverlapTranslation = 0;     //!< largest overlap, part truth (m)
    double medianFinalOverlapRotation = 0;        //!< largest overlap, part truth (rad)
    std::map<std::string, unsigned int> failures; //!< reason -> count (without "none")
    unsigned int holds = 0;                       //!< holds summed over the runs (timed faults)
    unsigned int replans = 0;                     //!< re-plans summed over the runs
    unsigned int rerecognitions = 0;              //!< re-recognitions summed over the runs
    //! Runs that could be set up.
    unsigned int attempted() const { return runs - setups; }
    //! successes over attempted().
    double successRate() const { return attempted() ? double(successes) / attempted() : 0.0; }
  };

  vpMorphBenchReport();
  ~vpMorphBenchReport();
  //! A copy of the rows and records.
  vpMorphBenchReport(const vpMorphBenchReport &other);
  //! Copies the rows and records of \e other.
  vpMorphBenchReport &operator=(const vpMorphBenchReport &other);

  //! Adds a run (its row).
  void add(const vpMorphBenchResult &r);
  /*!
    Adds the rows of a runs.csv text (header first). \throw vpMorphException::ioError for another header or a row
    that does not match it.
  */
  void readRuns(std::istream &in, const std::string &what = "runs.csv");
  //! Puts the rows in the canonical order: set (setNames()), scenario index, robot, controller (names()).
  void sortRows();
  //! The rows, without the header.
  const std::vector<std::string> &rows() const { return m_rows; }
  //! True when two rows are of the same run (set, scenario, robot, controller): a merge of shards that overlap.
  bool hasDuplicates() const;
  //! Summaries in the order: set, robot (first seen), controller (vpMorphBenchController::names() order).
  std::vector<Summary> summarize() const;

  //! The header line of runs.csv.
  static std::string runsHeader();
  //! The runs.csv row of a result.
  static std::string runsRow(const vpMorphBenchResult &r);
  //! The header line of curves.csv.
  static std::string curvesHeader();
  //! The curves.csv rows of a result (one per iteration).
  static std::string curvesRows(const vpMorphBenchResult &r);
  /*!
    Sorts curves.csv rows (without header) into the canonical order of sortRows(), iterations ascending.
    Rows that do not parse are kept at the end, in their order.
  */
  static void sortCurves(std::vector<std::string> &rows);
  //! JSON object: \e meta (free key/values: the command's deterministic settings) and the summaries.
  std::string summaryJson(const std::map<std::string, std::string> &meta) const;
  //! A markdown table, one line per summary.
  std::string summaryMarkdown() const;
  /*!
    The 95 % interval of a rate of \e k in \e n: Wilson's score interval, but [0, 3 / n] for k = 0 (the rule of
    three). [0, 1] for n = 0.
  */
  static void interval(unsigned int k, unsigned int n, double &low, double &high);

private:
  struct Record;
  std::vector<std::string> m_rows;
  std::vector<Record> m_records;
};

#endif
