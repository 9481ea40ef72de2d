// vispmorph-bench's result files: written from a finished run, or merged from the shards of one command.
#ifndef VISPMORPH_BENCH_RESULTS_H
#define VISPMORPH_BENCH_RESULTS_H

#include <map>
#include <string>

#include <visp3/morph_bench/vpMorphBenchReport.h>
#include <visp3/morph_bench/vpMorphBenchTimings.h>

//! The header of scenarios.csv.
extern const char *const kScenariosHeader;

/*!
  The run's results in \e out: runs.csv, curves.csv (from curves.partial.csv, the rows finished) when \e curves,
  summary.json and summary.md with \e meta, timings.csv and timings.* with \e machine (its "yardstick" printed), and
  the plots (vispmorph-bench-plots.py) when \e plots; the partial files removed.
*/
void writeResults(const std::string &out, vpMorphBenchReport &report, vpMorphBenchTimings &timings,
                  const std::map<std::string, std::string> &meta, const std::map<std::string, std::string> &machine,
                  bool curves, bool plots);

/*!
  vispmorph-bench merge --out DIR SHARD_DIR... [--no-plots]: the shards of one command (--shard K/N, every K once) as
  one run: the same objects.csv, scenarios.csv, runs.csv, curves.csv, summary.json and summary.md as the command
  without --shard, to the byte; timings.csv and timings.* with every shard's times. Shards of other settings, of
  another commit, missing or given twice are refused. Returns the exit status (0, 1 on an error, 2 on bad arguments).
*/
int mergeShards(int argc, char **argv);

#endif
