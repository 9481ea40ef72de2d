#include <visp3/morph_bench/vpMorphBenchReport.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include <visp3/core/vpMath.h>
#include <visp3/morph_bench/vpMorphBenchController.h>

namespace
{
const double kNaN = std::numeric_limits<double>::quiet_NaN();

double median(std::vector<double> v)
{
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty())
    return kNaN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string num(double x, int precision = 4)
{
  if (!std::isfinite(x))
    return "";
  std::ostringstream os;
  os << std::setprecision(precision) << x;
  return os.str();
}

int orderOf(const std::vector<std::string> &names, const std::string &n)
{
  const auto it = std::find(names.begin(), names.end(), n);
  return it == names.end() ? static_cast<int>(names.size()) : static_cast<int>(it - names.begin());
}

nlohmann::json jnum(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

//! The kinds of a run's timed faults, joined by '+' (empty without).
std::string faultKinds(const vpMorphBenchScenario &s)
{
  std::string k;
  for (const vpMorphBenchEvent &e : s.events)
    k += (k.empty() ? "" : "+") + vpMorphBenchEvent::kindName(e.kind);
  return k;
}

//! The set as summarised: runs with timed faults are grouped per fault kind ("faults/pose-jump").
std::string groupSet(const vpMorphBenchScenario &s)
{
  const std::string k = faultKinds(s);
  return k.empty() ? s.set : s.set + "/" + k;
}
} // namespace

void vpMorphBenchReport::add(const vpMorphBenchResult &r) { m_results.push_back(r); }

std::vector<vpMorphBenchReport::Summary> vpMorphBenchReport::summarize() const
{
  const std::vector<std::string> sets = vpMorphBenchScenario::setNames();
  const std::vector<std::string> ctrls = vpMorphBenchController::names();
  std::vector<std::string> robots;
  for (const vpMorphBenchResult &r : m_results)
    if (std::find(robots.begin(), robots.end(), r.robot) == robots.end())
      robots.push_back(r.robot);
  std::map<std::tuple<int, int, int, std::string>, std::vector<const vpMorphBenchResult *>> groups;
  for (const vpMorphBenchResult &r : m_results)
    groups[std::make_tuple(orderOf(sets, r.scenario.set), orderOf(robots, r.robot), orderOf(ctrls, r.controller),
                           groupSet(r.scenario))]
        .push_back(&r);

  std::vector<Summary> out;
  for (const auto &g : groups) {
    Summary s;
    const vpMorphBenchResult &first = *g.second.front();
    s.set = groupSet(first.scenario);
    s.robot = first.robot;
    s.controller = first.controller;
    std::vector<double> its, path, ratio, ft, fr, tt, tr;
    double sumM = 0, sumC = 0;
    unsigned int started = 0;
    for (const vpMorphBenchResult *r : g.second) {
      ++s.runs;
      // A start the robot could not reach ran no iteration: it has no final pose of its own and no compute time,
      // and its zeros would pull the medians and means down (the Afma6 reaches fewer than half of the starts).
      if (r->iterations > 0) {
        ++started;
        ft.push_back(r->finalTranslation);
        fr.push_back(r->finalRotation);
        if (r->tagMeasured) {
          tt.push_back(r->finalTagTranslation);
          tr.push_back(r->finalTagRotation);
        }
        sumM += r->measureMs;
        sumC += r->controlMs;
      }
      s.holds += r->holds;
      s.replans += r->replans;
      s.rerecognitions += r->rerecognitions;
      s.maxControlMs = std::max(s.maxControlMs, r->maxControlMs);
      if (r->success) {
        ++s.successes;
        its.push_back(r->convergedIteration);
        path.push_back(r->pathLength);
        ratio.push_back(r->pathRatio());
      } else {
        ++s.failures[r->failure];
      }
    }
    s.medianIterations = median(its);
    s.medianPathLength = median(path);
    s.medianPathRatio = median(ratio);
    s.medianFinalTranslation = median(ft);
    s.medianFinalRotation = median(fr);
    s.medianFinalTagTranslation = median(tt);
    s.medianFinalTagRotation = median(tr);
    s.meanMeasureMs = started ? sumM / started : kNaN; // none started: no time, as no median
    s.meanControlMs = started ? sumC / started : kNaN;
    out.push_back(s);
  }
  return out;
}

std::string vpMorphBenchReport::runsHeader()
{
  return "set,robot,controller,scenario,seed,object,start_rotation_deg,start_translation_mm,start_tilt_deg,"
         "start_depth_change,success,failure,iterations,converged_iteration,path_length_m,straight_line_m,path_ratio,"
         "final_t_mm,final_r_deg,final_tag_t_mm,final_tag_r_deg,recognized,recognition_correct,measure_ms,"
         "control_ms,faults,holds,replans,rerecognitions,max_speed_mps,max_rotation_speed_degps,goal";
}

std::string vpMorphBenchReport::runsRow(const vpMorphBenchResult &r)
{
  const vpMorphBenchScenario &s = r.scenario;
  std::ostringstream os;
  os << s.set << ',' << r.robot << ',' << r.controller << ',' << s.index << ',' << s.seed << ',' << s.object << ','
     << num(s.startRotationDeg) << ',' << num(s.startTranslationMm) << ',' << num(s.startTiltDeg) << ','
     << num(s.startDepthChange) << ',' << (r.success ? 1 : 0) << ',' << r.failure << ',' << r.iterations << ','
     << (r.convergedIteration >= 0 ? std::to_string(r.convergedIteration) : std::string()) << ','
     << num(r.pathLength, 5) << ',' << num(r.straightLine, 5) << ',' << num(r.pathRatio()) << ','
     << num(1000 * r.finalTranslation) << ',' << num(vpMath::deg(r.finalRotation)) << ','
     << (r.tagMeasured ? num(1000 * r.finalTagTranslation) : std::string()) << ','
     << (r.tagMeasured ? num(vpMath::deg(r.finalTagRotation)) : std::string()) << ',' << r.recognized << ','
     << (r.recognitionCorrect() ? 1 : 0) << ',' << num(r.measureMs) << ',' << num(r.controlMs) << ',' << faultKinds(s)
     << ',' << r.holds << ',' << r.replans << ',' << r.rerecognitions << ',' << num(r.maxSpeed) << ','
     << num(vpMath::deg(r.maxRotationSpeed)) << ',' << r.goal;
  return os.str();
}

std::string vpMorphBenchReport::curvesHeader() { return "set,robot,controller,scenario,iteration,t_mm,r_deg"; }

std::string vpMorphBenchReport::curvesRows(const vpMorphBenchResult &r)
{
  std::ostringstream os;
  for (std::size_t k = 0; k < r.curveTranslation.size(); ++k)
    os << r.scenario.set << ',' << r.robot << ',' << r.controller << ',' << r.scenario.index << ',' << k << ','
       << num(1000 * r.curveTranslation[k]) << ',' << num(vpMath::deg(r.curveRotation[k])) << '\n';
  return os.str();
}

std::string vpMorphBenchReport::summaryJson(const std::map<std::string, std::string> &meta) const
{
  nlohmann::json j;
  j["version"] = 1;
  for (const auto &m : meta)
    j["meta"][m.first] = m.second;
  j["summaries"] = nlohmann::json::array();
  for (const Summary &s : summarize()) {
    nlohmann::json e;
    e["set"] = s.set;
    e["robot"] = s.robot;
    e["controller"] = s.controller;
    e["runs"] = s.runs;
    e["successes"] = s.successes;
    e["success_rate"] = s.successRate();
    e["median_iterations"] = jnum(s.medianIterations);
    e["median_path_length_m"] = jnum(s.medianPathLength);
    e["median_path_ratio"] = jnum(s.medianPathRatio);
    e["median_final_t_mm"] = jnum(1000 * s.medianFinalTranslation);
    e["median_final_r_deg"] = jnum(vpMath::deg(s.medianFinalRotation));
    e["median_final_tag_t_mm"] = jnum(1000 * s.medianFinalTagTranslation);
    e["median_final_tag_r_deg"] = jnum(vpMath::deg(s.medianFinalTagRotation));
    e["mean_measure_ms"] = jnum(s.meanMeasureMs);
    e["mean_control_ms"] = jnum(s.meanControlMs);
    e["max_control_ms"] = s.maxControlMs;
    e["failures"] = s.failures;
    e["holds"] = s.holds;
    e["replans"] = s.replans;
    e["rerecognitions"] = s.rerecognitions;
    j["summaries"].push_back(e);
  }
  return j.dump(2);
}

std::string vpMorphBenchReport::summaryMarkdown() const
{
  std::ostringstream os;
  os << "| set | robot | controller | success | median iter. | median path (mm) | path ratio | final error "
        "truth (mm / deg) | final error tag (mm / deg) | measure / control (ms) | failures | holds / re-plans / "
        "re-recognitions |\n";
  os << "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Summary &s : summarize()) {
    std::ostringstream fails;
    for (const auto &f : s.failures)
      fails << (fails.tellp() > 0 ? ", " : "") << f.first << " " << f.second;
    auto dash = [](const std::string &x) { return x.empty() ? std::string("-") : x; };
    os << "| " << s.set << " | " << s.robot << " | " << s.controller << " | " << s.successes << "/" << s.runs << " ("
       << num(100 * s.successRate(), 3) << " %) | " << dash(num(s.medianIterations, 4)) << " | "
       << dash(num(1000 * s.medianPathLength, 4)) << " | " << dash(num(s.medianPathRatio, 3)) << " | "
       << dash(num(1000 * s.medianFinalTranslation, 3)) << " / " << dash(num(vpMath::deg(s.medianFinalRotation), 3))
       << " | " << dash(num(1000 * s.medianFinalTagTranslation, 3)) << " / "
       << dash(num(vpMath::deg(s.medianFinalTagRotation), 3)) << " | " << dash(num(s.meanMeasureMs, 3)) << " / "
       << dash(num(s.meanControlMs, 3)) << " | " << dash(fails.str()) << " | " << s.holds << " / " << s.replans << " / "
       << s.rerecognitions << " |\n";
  }
  return os.str();
}
