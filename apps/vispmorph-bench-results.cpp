// vispmorph-bench's result files: written from a finished run, or merged from the shards of one command.
#include "vispmorph-bench-results.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>
#include <utility>

#include <nlohmann/json.hpp>

#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_bench/vpMorphBenchScenario.h>

namespace fs = std::filesystem;

const char *const kScenariosHeader =
    "set,scenario,seed,object,start_rotation_deg,start_translation_mm,start_tilt_deg,start_depth_change,noise_sigma,"
    "blur_sigma,gain,offset,occluded_share,focal_scale_x,focal_scale_y,principal_shift_u,principal_shift_v,"
    "eMc_error_mm,eMc_error_deg,description";

namespace
{
//! Lines of a text file (its header first), or none when it is missing.
std::vector<std::string> readLines(const std::string &path)
{
  std::vector<std::string> lines;
  std::ifstream f(path);
  std::string line;
  while (std::getline(f, line))
    if (!line.empty())
      lines.push_back(line);
  return lines;
}

void writeLines(const std::string &path, const std::string &header, const std::vector<std::string> &rows)
{
  std::ofstream f(path);
  f << header << "\n";
  for (const std::string &r : rows)
    f << r << "\n";
}

//! scenarios.csv rows in the canonical order (set, index); rows that are not scenarios kept last.
void sortScenarioRows(std::vector<std::string> &rows)
{
  const std::vector<std::string> sets = vpMorphBenchScenario::setNames();
  auto key = [&](const std::string &r) {
    const std::size_t a = r.find(','), b = r.find(',', a + 1);
    const std::string set = r.substr(0, a);
    return std::make_pair(static_cast<long>(std::find(sets.begin(), sets.end(), set) - sets.begin()),
                          std::atol(r.substr(a + 1, b - a - 1).c_str()));
  };
  std::stable_sort(rows.begin(), rows.end(),
                   [&](const std::string &x, const std::string &y) { return key(x) < key(y); });
}

} // namespace

void writeResults(const std::string &out, vpMorphBenchReport &report, vpMorphBenchTimings &timings,
                  const std::map<std::string, std::string> &meta, const std::map<std::string, std::string> &machine,
                  bool curves, bool plots)
{
  report.sortRows();
  writeLines(out + "/runs.csv", vpMorphBenchReport::runsHeader(), report.rows());
  if (curves) {
    std::vector<std::string> rows = readLines(out + "/curves.partial.csv");
    if (!rows.empty())
      rows.erase(rows.begin()); // header
    vpMorphBenchReport::sortCurves(rows);
    writeLines(out + "/curves.csv", vpMorphBenchReport::curvesHeader(), rows);
  }
  timings.sortRows();
  writeLines(out + "/timings.csv", vpMorphBenchTimings::header(), timings.rows());
  std::ofstream(out + "/summary.json") << report.summaryJson(meta) << "\n";
  std::ofstream(out + "/summary.md") << report.summaryMarkdown();
  std::ofstream(out + "/timings.json") << timings.json(machine) << "\n";
  std::ostringstream t;
  t << timings.markdown() << "\nMachine yardstick: " << machine.at("yardstick")
    << ". Compare compute times across runs through their ratio to it.\n";
  std::ofstream(out + "/timings.md") << t.str();
  std::cout << report.summaryMarkdown() << "\n" << t.str();
  fs::remove(out + "/runs.partial.csv");
  fs::remove(out + "/curves.partial.csv");
  if (plots) {
    const std::string script = VISPMORPH_PLOT_SCRIPT;
    if (!fs::exists(script) || !fs::exists("/usr/bin/python3")) {
      std::cerr << "vispmorph-bench: plots skipped (" << script << " or /usr/bin/python3 missing)" << std::endl;
    } else {
      const std::string c = "MPLBACKEND=Agg /usr/bin/python3 '" + script + "' '" + out + "'";
      if (std::system(c.c_str()) != 0)
        std::cerr << "vispmorph-bench: the plot script failed (the CSV files are complete)" << std::endl;
    }
  }
}

int mergeShards(int argc, char **argv)
{
  std::string out;
  std::vector<std::string> shards;
  bool plots = true;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--out" && i + 1 < argc)
      out = argv[++i];
    else if (a == "--no-plots")
      plots = false;
    else if (!a.empty() && a[0] == '-') {
      std::cerr << "vispmorph-bench merge: unknown option '" << a << "'\nUsage: vispmorph-bench merge --out DIR "
                << "SHARD_DIR... [--no-plots]\n";
      return 2;
    } else
      shards.push_back(a);
  }
  if (out.empty() || shards.empty()) {
    std::cerr << "vispmorph-bench merge: --out DIR and at least one shard folder are needed\n";
    return 2;
  }
  try {
    auto fail = [](const std::string &msg) { throw vpMorphException(vpMorphException::badParameterError, msg); };
    std::map<std::string, std::string> meta;
    std::set<unsigned int> seen;
    unsigned int total = 0;
    std::vector<std::string> objects, scenarioRows, scenarioJson, curveRows;
    vpMorphBenchReport report;
    vpMorphBenchTimings timings;
    nlohmann::json machines = nlohmann::json::array();
    for (const std::string &dir : shards) {
      std::ifstream sf(dir + "/summary.json");
      if (!sf)
        fail("cannot read " + dir + "/summary.json (a finished shard?)");
      nlohmann::json m = nlohmann::json::parse(sf).at("meta");
      const std::string shard = m.value("shard", "1/1");
      m.erase("shard");
      unsigned int k = 0, n = 0;
      if (std::sscanf(shard.c_str(), "%u/%u", &k, &n) != 2 || k < 1 || k > n)
        fail(dir + ": bad shard '" + shard + "'");
      const std::map<std::string, std::string> mm = m.get<std::map<std::string, std::string>>();
      // One run is measured at one commit: shards built at different ones are refused, not stamped "mixed".
      auto commit = [](const std::map<std::string, std::string> &x) {
        const auto c = x.find("commit");
        return c == x.end() ? std::string("an unrecorded commit") : c->second;
      };
      if (!meta.empty() && commit(mm) != commit(meta))
        fail(dir + ": measured at " + commit(mm) + ", " + shards[0] + " at " + commit(meta) +
             " (the shards of one run are built at one commit)");
      if (meta.empty()) {
        meta = mm;
        total = n;
      } else if (mm != meta || n != total)
        fail(dir + ": a shard of another command (its settings differ from " + shards[0] + "'s)");
      if (!seen.insert(k).second)
        fail(dir + ": shard " + shard + " given twice");
      const std::vector<std::string> o = readLines(dir + "/objects.csv");
      if (objects.empty())
        objects = o;
      else if (o != objects)
        fail(dir + ": its objects differ from " + shards[0] + "'s");
      std::vector<std::string> rows = readLines(dir + "/scenarios.csv");
      if (rows.empty() || rows[0] != kScenariosHeader)
        fail(dir + ": no scenarios.csv of this version");
      scenarioRows.insert(scenarioRows.end(), rows.begin() + 1, rows.end());
      std::ifstream js(dir + "/scenarios.json");
      if (js)
        for (const nlohmann::json &x : nlohmann::json::parse(js))
          scenarioJson.push_back(x.dump());
      std::ifstream runs(dir + "/runs.csv");
      if (!runs)
        fail("cannot read " + dir + "/runs.csv");
      report.readRuns(runs, dir + "/runs.csv");
      rows = readLines(dir + "/curves.csv");
      if (!rows.empty())
        curveRows.insert(curveRows.end(), rows.begin() + 1, rows.end());
      std::ifstream t(dir + "/timings.csv");
      if (t)
        timings.readTimings(t, dir + "/timings.csv");
      std::ifstream tj(dir + "/timings.json");
      if (tj)
        machines.push_back(nlohmann::json::parse(tj).value("meta", nlohmann::json::object()));
    }
    for (unsigned int k = 1; k <= total; ++k)
      if (!seen.count(k))
        fail("shard " + std::to_string(k) + "/" + std::to_string(total) + " is missing");
    if (report.hasDuplicates())
      fail("two shards hold the same run");
    fs::create_directories(out);
    {
      std::ofstream f(out + "/objects.csv");
      for (const std::string &l : objects)
        f << l << "\n";
    }
    sortScenarioRows(scenarioRows);
    writeLines(out + "/scenarios.csv", kScenariosHeader, scenarioRows);
    {
      std::vector<std::pair<std::pair<long, long>, std::string>> keyed;
      const std::vector<std::string> sets = vpMorphBenchScenario::setNames();
      for (const std::string &x : scenarioJson) {
        const vpMorphBenchScenario sc = vpMorphBenchScenario::fromJson(x);
        keyed.push_back({{static_cast<long>(std::find(sets.begin(), sets.end(), sc.set) - sets.begin()),
                          static_cast<long>(sc.index)},
                         x});
      }
      std::stable_sort(keyed.begin(), keyed.end(), [](const auto &a, const auto &b) { return a.first < b.first; });
      std::ofstream f(out + "/scenarios.json");
      f << "[";
      for (std::size_t k = 0; k < keyed.size(); ++k)
        f << (k ? ",\n" : "\n") << keyed[k].second;
      f << "\n]\n";
    }
    {
      std::ofstream f(out + "/curves.partial.csv");
      f << vpMorphBenchReport::curvesHeader() << "\n";
      for (const std::string &r : curveRows)
        f << r << "\n";
    }
    std::map<std::string, std::string> machine;
    machine["merged_from"] = std::to_string(shards.size()) + " shards";
    machine["shards"] = machines.dump();
    machine["yardstick"] = "each shard's own (timings.csv: yardstick_ms)";
    writeResults(out, report, timings, meta, machine, !curveRows.empty(), plots);
    std::cerr << "vispmorph-bench merge: " << report.rows().size() << " runs of " << total << " shards in " << out
              << std::endl;
    return EXIT_SUCCESS;
  } catch (const vpException &e) {
    std::cerr << "vispmorph-bench merge: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  } catch (const std::exception &e) {
    std::cerr << "vispmorph-bench merge: " << e.what() << std::endl;
    return EXIT_FAILURE;
  }
}
