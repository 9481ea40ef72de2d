#include <visp3/morph_bench/vpMorphBenchTimings.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>

#include <nlohmann/json.hpp>

#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_bench/vpMorphBenchController.h>

#include "vpMorphBenchCsv.h"

namespace
{
const double kNaN = std::numeric_limits<double>::quiet_NaN();
using vpMorphBenchCsv::num;

//! The q-quantile by nearest rank (NaN for none).
double quantile(std::vector<double> v, double q)
{
  if (v.empty())
    return kNaN;
  std::sort(v.begin(), v.end());
  const std::size_t rank = static_cast<std::size_t>(std::ceil(q * v.size()));
  return v[std::min(v.size() - 1, rank > 0 ? rank - 1 : 0)];
}

nlohmann::json jnum(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }
} // namespace

std::string vpMorphBenchTimings::header()
{
  return "set,robot,controller,scenario,object,yardstick_ms,measure_ms,control_ms,max_control_ms,run_cpu_s,period_ms,"
         "period_measure_ms";
}

void vpMorphBenchTimings::add(const vpMorphBenchResult &r, double yardstickMs)
{
  Entry e;
  e.set = r.scenario.set;
  e.robot = r.robot;
  e.controller = r.controller;
  e.object = r.scenario.object;
  e.scenario = static_cast<int>(r.scenario.index);
  e.yardstick = yardstickMs;
  e.measure = r.measureMs;
  e.control = r.controlMs;
  e.maxControl = r.maxControlMs;
  e.runCpu = r.runCpuS;
  e.periods = r.periodMs;
  e.periodMeasures = r.periodMeasureMs;
  m_entries.push_back(e);
}

void vpMorphBenchTimings::readTimings(std::istream &in, const std::string &what)
{
  std::string line;
  if (!std::getline(in, line) || line != header())
    throw vpMorphException(vpMorphException::ioError,
                           what + ": not a timings.csv of this version (its header differs)");
  while (std::getline(in, line)) {
    if (line.empty())
      continue;
    const std::vector<std::string> f = vpMorphBenchCsv::split(line);
    if (f.size() != 12)
      throw vpMorphException(vpMorphException::ioError, what + ": a row without its 12 fields: " + line);
    Entry e;
    e.set = f[0];
    e.robot = f[1];
    e.controller = f[2];
    e.scenario = static_cast<int>(vpMorphBenchCsv::number(f[3]));
    e.object = f[4];
    e.yardstick = vpMorphBenchCsv::number(f[5]);
    e.measure = vpMorphBenchCsv::number(f[6]);
    e.control = vpMorphBenchCsv::number(f[7]);
    e.maxControl = vpMorphBenchCsv::number(f[8]);
    e.runCpu = vpMorphBenchCsv::number(f[9]);
    std::istringstream periods(f[10]), measures(f[11]);
    double p;
    while (periods >> p)
      e.periods.push_back(p);
    while (measures >> p)
      e.periodMeasures.push_back(p);
    if (!e.periodMeasures.empty() && e.periodMeasures.size() != e.periods.size())
      throw vpMorphException(vpMorphException::ioError,
                             what + ": a row whose periods and their measures differ in number: " + line);
    m_entries.push_back(e);
  }
}

void vpMorphBenchTimings::sortRows()
{
  const std::vector<std::string> sets = vpMorphBenchScenario::setNames(), ctrls = vpMorphBenchController::names();
  std::stable_sort(m_entries.begin(), m_entries.end(), [&](const Entry &a, const Entry &b) {
    return std::make_tuple(vpMorphBenchCsv::orderOf(sets, a.set), a.set, a.scenario, a.robot,
                           vpMorphBenchCsv::orderOf(ctrls, a.controller), a.controller) <
           std::make_tuple(vpMorphBenchCsv::orderOf(sets, b.set), b.set, b.scenario, b.robot,
                           vpMorphBenchCsv::orderOf(ctrls, b.controller), b.controller);
  });
}

std::vector<std::string> vpMorphBenchTimings::rows() const
{
  std::vector<std::string> out;
  for (const Entry &e : m_entries) {
    std::ostringstream os;
    os << e.set << ',' << e.robot << ',' << e.controller << ',' << e.scenario << ',' << e.object << ','
       << num(e.yardstick) << ',' << num(e.measure) << ',' << num(e.control) << ',' << num(e.maxControl) << ','
       << num(e.runCpu) << ',';
    auto list = [&os](const std::vector<double> &v) {
      for (std::size_t k = 0; k < v.size(); ++k)
        os << (k ? " " : "") << num(v[k]);
    };
    list(e.periods);
    os << ',';
    list(e.periodMeasures);
    out.push_back(os.str());
  }
  return out;
}

std::vector<vpMorphBenchTimings::Summary> vpMorphBenchTimings::summarize() const
{
  const std::vector<std::string> sets = vpMorphBenchScenario::setNames(), ctrls = vpMorphBenchController::names();
  std::vector<std::string> robots;
  for (const Entry &e : m_entries)
    if (std::find(robots.begin(), robots.end(), e.robot) == robots.end())
      robots.push_back(e.robot);
  std::map<std::tuple<int, std::string, int, int, std::string>, std::vector<const Entry *>> groups;
  for (const Entry &e : m_entries)
    groups[std::make_tuple(vpMorphBenchCsv::orderOf(sets, e.set), e.set, vpMorphBenchCsv::orderOf(robots, e.robot),
                           vpMorphBenchCsv::orderOf(ctrls, e.controller), e.controller)]
        .push_back(&e);
  std::vector<Summary> out;
  for (const auto &g : groups) {
    Summary s;
    s.set = g.second.front()->set;
    s.robot = g.second.front()->robot;
    s.controller = g.second.front()->controller;
    std::vector<double> ms, ratio, measures, controls;
    double sumM = 0, sumC = 0, sumRun = 0;
    unsigned int measured = 0;
    for (const Entry *e : g.second) {
      ++s.runs;
      sumRun += std::isfinite(e->runCpu) ? e->runCpu : 0.0;
      for (double p : e->periods) {
        ms.push_back(p);
        if (e->yardstick > 0)
          ratio.push_back(p / e->yardstick);
      }
      for (std::size_t k = 0; k < e->periodMeasures.size() && k < e->periods.size(); ++k) {
        measures.push_back(e->periodMeasures[k]);
        controls.push_back(e->periods[k] - e->periodMeasures[k]);
      }
      if (e->measure > 0 || e->control > 0) {
        ++measured;
        sumM += e->measure;
        sumC += e->control;
        s.maxControlMs = std::max(s.maxControlMs, e->maxControl);
      }
    }
    s.periods = static_cast<unsigned int>(ms.size());
    s.medianMs = quantile(ms, 0.5);
    s.p95Ms = quantile(ms, 0.95);
    s.medianRatio = quantile(ratio, 0.5);
    s.p95Ratio = quantile(ratio, 0.95);
    s.medianMeasureMs = quantile(measures, 0.5);
    s.medianControlMs = quantile(controls, 0.5);
    s.meanMeasureMs = measured ? sumM / measured : kNaN;
    s.meanControlMs = measured ? sumC / measured : kNaN;
    s.meanRunCpuS = s.runs ? sumRun / s.runs : kNaN;
    out.push_back(s);
  }
  return out;
}

std::string vpMorphBenchTimings::json(const std::map<std::string, std::string> &meta) const
{
  nlohmann::json j;
  j["version"] = 1;
  for (const auto &m : meta)
    j["meta"][m.first] = m.second;
  j["summaries"] = nlohmann::json::array();
  for (const Summary &s : summarize())
    j["summaries"].push_back({{"set", s.set},
                              {"robot", s.robot},
                              {"controller", s.controller},
                              {"runs", s.runs},
                              {"periods", s.periods},
                              {"median_period_ms", jnum(s.medianMs)},
                              {"p95_period_ms", jnum(s.p95Ms)},
                              {"median_period_over_yardstick", jnum(s.medianRatio)},
                              {"p95_period_over_yardstick", jnum(s.p95Ratio)},
                              {"median_measure_ms", jnum(s.medianMeasureMs)},
                              {"median_control_ms", jnum(s.medianControlMs)},
                              {"mean_measure_ms", jnum(s.meanMeasureMs)},
                              {"mean_control_ms", jnum(s.meanControlMs)},
                              {"max_control_ms", jnum(s.maxControlMs)},
                              {"mean_run_cpu_s", jnum(s.meanRunCpuS)}});
  return j.dump(2);
}

std::string vpMorphBenchTimings::markdown() const
{
  std::ostringstream os;
  os << "| set | robot | controller | periods | compute a period, median / p95 (ms) | over the yardstick, median / p95 "
        "| a period's measure / control, median (ms) | mean measure / control (ms) | CPU a run (s) |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
  auto dash = [](const std::string &x) { return x.empty() ? std::string("-") : x; };
  for (const Summary &s : summarize())
    os << "| " << s.set << " | " << s.robot << " | " << s.controller << " | " << s.periods << " | "
       << dash(num(s.medianMs, 3)) << " / " << dash(num(s.p95Ms, 3)) << " | " << dash(num(s.medianRatio, 3)) << " / "
       << dash(num(s.p95Ratio, 3)) << " | " << dash(num(s.medianMeasureMs, 3)) << " / "
       << dash(num(s.medianControlMs, 3)) << " | " << dash(num(s.meanMeasureMs, 3)) << " / "
       << dash(num(s.meanControlMs, 3)) << " | " << dash(num(s.meanRunCpuS, 3)) << " |\n";
  return os.str();
}
