#include <visp3/morph_bench/vpMorphBenchReport.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <tuple>

#include <nlohmann/json.hpp>

#include <visp3/core/vpMath.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_bench/vpMorphBenchController.h>

#include "vpMorphBenchCsv.h"

namespace
{
const double kNaN = std::numeric_limits<double>::quiet_NaN();
using vpMorphBenchCsv::num;
using vpMorphBenchCsv::orderOf;
using vpMorphBenchCsv::split;

double median(std::vector<double> v)
{
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty())
    return kNaN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
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

//! A free text as one CSV field: separators and quotes replaced.
std::string csvWord(std::string text)
{
  for (char &c : text)
    if (c == ',' || c == '"' || c == '\n' || c == '\r')
      c = c == ',' ? ';' : ' ';
  return text;
}

//! How a run's truth is held: "rigid", or for a deformed object "part", "overlap", "articulated".
std::string truthName(const vpMorphBenchScenario &s)
{
  if (s.objectImage == s.templateImage)
    return "rigid";
  switch (s.truth) {
  case vpMorphBenchObjectSet::TRUTH_PART:
    return "part";
  case vpMorphBenchObjectSet::TRUTH_ARTICULATED:
    return "articulated";
  default:
    return "overlap";
  }
}

const char *const kColumns[] = {"set",
                                "robot",
                                "controller",
                                "scenario",
                                "seed",
                                "object",
                                "start_rotation_deg",
                                "start_translation_mm",
                                "start_tilt_deg",
                                "start_depth_change",
                                "success",
                                "failure",
                                "iterations",
                                "converged_iteration",
                                "path_length_m",
                                "straight_line_m",
                                "path_ratio",
                                "final_t_mm",
                                "final_r_deg",
                                "final_tag_t_mm",
                                "final_tag_r_deg",
                                "recognized",
                                "recognition_correct",
                                "faults",
                                "holds",
                                "replans",
                                "rerecognitions",
                                "max_speed_mps",
                                "max_rotation_speed_degps",
                                "goal",
                                "setup",
                                "converged",
                                "false_converged",
                                "truth",
                                "tag_size_mm",
                                "taught_tag_t_mm",
                                "taught_tag_r_deg",
                                "final_overlap_t_mm",
                                "final_overlap_r_deg",
                                "symmetry",
                                "unobservable",
                                "verification"};
const std::size_t kColumnCount = sizeof(kColumns) / sizeof(kColumns[0]);
} // namespace

//! What the summaries read of a row.
struct vpMorphBenchReport::Record
{
  std::string set, robot, controller, faults, failure, unobservable, verification;
  int scenario = 0;
  bool success = false, converged = false, falseConverged = false;
  unsigned int iterations = 0, holds = 0, replans = 0, rerecognitions = 0, symmetry = 1;
  double convergedIteration = kNaN, pathLength = kNaN, pathRatio = kNaN;
  double finalT = kNaN, finalR = kNaN, tagT = kNaN, tagR = kNaN, overlapT = kNaN, overlapR = kNaN; // m, rad

  //! The set as summarised: with the run's fault kinds, and apart for symmetric and unobservable views.
  std::string group() const
  {
    std::string g = faults.empty() ? set : set + "/" + faults;
    if (!unobservable.empty())
      return g + "/unobservable";
    return symmetry != 1 ? g + "/symmetric" : g;
  }

  static Record parse(const std::string &row, const std::string &what)
  {
    const std::vector<std::string> f = split(row);
    if (f.size() != kColumnCount)
      throw vpMorphException(vpMorphException::ioError, what + ": a row of " + std::to_string(f.size()) +
                                                            " fields where the header has " +
                                                            std::to_string(kColumnCount) + ": " + row);
    auto at = [&](const char *name) -> const std::string & {
      return f[std::find_if(std::begin(kColumns), std::end(kColumns),
                            [&](const char *c) { return std::string(c) == name; }) -
               std::begin(kColumns)];
    };
    auto number = [&](const char *name) { return vpMorphBenchCsv::number(at(name)); };
    auto count = [&](const char *name) {
      const double v = number(name);
      return std::isfinite(v) && v >= 0 ? static_cast<unsigned int>(v) : 0u;
    };
    Record r;
    r.set = at("set");
    r.robot = at("robot");
    r.controller = at("controller");
    r.faults = at("faults");
    r.failure = at("failure");
    r.unobservable = at("unobservable");
    r.verification = at("verification");
    r.scenario = static_cast<int>(count("scenario"));
    r.success = at("success") == "1";
    r.converged = at("converged") == "1";
    r.falseConverged = at("false_converged") == "1";
    r.iterations = count("iterations");
    r.holds = count("holds");
    r.replans = count("replans");
    r.rerecognitions = count("rerecognitions");
    r.symmetry = at("symmetry").empty() ? 1u : count("symmetry");
    r.convergedIteration = number("converged_iteration");
    r.pathLength = number("path_length_m");
    r.pathRatio = number("path_ratio");
    r.finalT = number("final_t_mm") / 1000;
    r.finalR = vpMath::rad(number("final_r_deg"));
    r.tagT = number("final_tag_t_mm") / 1000;
    r.tagR = vpMath::rad(number("final_tag_r_deg"));
    r.overlapT = number("final_overlap_t_mm") / 1000;
    r.overlapR = vpMath::rad(number("final_overlap_r_deg"));
    return r;
  }
};

vpMorphBenchReport::vpMorphBenchReport() = default;
vpMorphBenchReport::~vpMorphBenchReport() = default;
vpMorphBenchReport::vpMorphBenchReport(const vpMorphBenchReport &other) = default;
vpMorphBenchReport &vpMorphBenchReport::operator=(const vpMorphBenchReport &other) = default;

void vpMorphBenchReport::add(const vpMorphBenchResult &r)
{
  m_rows.push_back(runsRow(r));
  m_records.push_back(Record::parse(m_rows.back(), "vpMorphBenchReport::add"));
}

void vpMorphBenchReport::readRuns(std::istream &in, const std::string &what)
{
  std::string line;
  if (!std::getline(in, line) || line != runsHeader())
    throw vpMorphException(vpMorphException::ioError, what + ": not a runs.csv of this version (its header differs)");
  while (std::getline(in, line)) {
    if (line.empty())
      continue;
    m_records.push_back(Record::parse(line, what));
    m_rows.push_back(line);
  }
}

void vpMorphBenchReport::sortRows()
{
  const std::vector<std::string> sets = vpMorphBenchScenario::setNames(), ctrls = vpMorphBenchController::names();
  std::vector<std::size_t> order(m_rows.size());
  for (std::size_t k = 0; k < order.size(); ++k)
    order[k] = k;
  auto key = [&](std::size_t k) {
    const Record &r = m_records[k];
    return std::make_tuple(orderOf(sets, r.set), r.set, r.scenario, r.robot, orderOf(ctrls, r.controller),
                           r.controller);
  };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key(a) < key(b); });
  std::vector<std::string> rows;
  std::vector<Record> records;
  for (std::size_t k : order) {
    rows.push_back(m_rows[k]);
    records.push_back(m_records[k]);
  }
  m_rows.swap(rows);
  m_records.swap(records);
}

bool vpMorphBenchReport::hasDuplicates() const
{
  std::vector<std::tuple<std::string, int, std::string, std::string>> keys;
  for (const Record &r : m_records)
    keys.emplace_back(r.set, r.scenario, r.robot, r.controller);
  std::sort(keys.begin(), keys.end());
  return std::adjacent_find(keys.begin(), keys.end()) != keys.end();
}

void vpMorphBenchReport::interval(unsigned int k, unsigned int n, double &low, double &high)
{
  if (n == 0) {
    low = 0.0;
    high = 1.0;
    return;
  }
  if (k == 0) { // the rule of three
    low = 0.0;
    high = std::min(1.0, 3.0 / n);
    return;
  }
  const double z = 1.959963984540054, p = static_cast<double>(k) / n, z2n = z * z / n;
  const double centre = (p + z2n / 2) / (1 + z2n);
  const double half = z * std::sqrt(p * (1 - p) / n + z2n / (4 * n)) / (1 + z2n);
  low = std::max(0.0, centre - half);
  high = std::min(1.0, centre + half);
}

std::vector<vpMorphBenchReport::Summary> vpMorphBenchReport::summarize() const
{
  const std::vector<std::string> sets = vpMorphBenchScenario::setNames();
  const std::vector<std::string> ctrls = vpMorphBenchController::names();
  std::vector<std::string> robots;
  for (const Record &r : m_records)
    if (std::find(robots.begin(), robots.end(), r.robot) == robots.end())
      robots.push_back(r.robot);
  std::map<std::tuple<int, int, int, std::string>, std::vector<const Record *>> groups;
  for (const Record &r : m_records)
    groups[std::make_tuple(orderOf(sets, r.set), orderOf(robots, r.robot), orderOf(ctrls, r.controller), r.group())]
        .push_back(&r);

  std::vector<Summary> out;
  for (const auto &g : groups) {
    Summary s;
    const Record &first = *g.second.front();
    s.set = first.group();
    s.robot = first.robot;
    s.controller = first.controller;
    std::vector<double> its, path, ratio, ft, fr, tt, tr, ot, orr;
    for (const Record *r : g.second) {
      ++s.runs;
      if (r->failure == "setup")
        ++s.setups;
      // A start the robot could not reach ran no iteration: it has no final pose of its own, and its zeros would
      // pull the medians down (the Afma6 reaches fewer than half of the starts).
      if (r->iterations > 0) {
        ft.push_back(r->finalT);
        fr.push_back(r->finalR);
        tt.push_back(r->tagT);
        tr.push_back(r->tagR);
        ot.push_back(r->overlapT);
        orr.push_back(r->overlapR);
      }
      s.holds += r->holds;
      s.replans += r->replans;
      s.rerecognitions += r->rerecognitions;
      s.falseConverged += r->falseConverged ? 1 : 0;
      if (r->success) {
        ++s.successes;
        s.declaredConverged += r->converged ? 1 : 0;
        if (!r->converged && !r->verification.empty())
          ++s.unverifiedSuccesses[r->verification];
        its.push_back(r->convergedIteration);
        path.push_back(r->pathLength);
        ratio.push_back(r->pathRatio);
      } else {
        ++s.failures[r->failure];
      }
    }
    interval(s.successes, s.attempted(), s.successLow, s.successHigh);
    double low = 0.0;
    interval(s.falseConverged, s.attempted(), low, s.falseConvergedHigh);
    s.medianIterations = median(its);
    s.medianPathLength = median(path);
    s.medianPathRatio = median(ratio);
    s.medianFinalTranslation = median(ft);
    s.medianFinalRotation = median(fr);
    s.medianFinalTagTranslation = median(tt);
    s.medianFinalTagRotation = median(tr);
    s.medianFinalOverlapTranslation = median(ot);
    s.medianFinalOverlapRotation = median(orr);
    out.push_back(s);
  }
  return out;
}

std::string vpMorphBenchReport::runsHeader()
{
  std::string h;
  for (const char *c : kColumns)
    h += (h.empty() ? "" : ",") + std::string(c);
  return h;
}

std::string vpMorphBenchReport::runsRow(const vpMorphBenchResult &r)
{
  const vpMorphBenchScenario &s = r.scenario;
  const bool tag = r.tagSize > 0;
  std::ostringstream os;
  os << s.set << ',' << r.robot << ',' << r.controller << ',' << s.index << ',' << s.seed << ',' << s.object << ','
     << num(s.startRotationDeg) << ',' << num(s.startTranslationMm) << ',' << num(s.startTiltDeg) << ','
     << num(s.startDepthChange) << ',' << (r.success ? 1 : 0) << ',' << r.failure << ',' << r.iterations << ','
     << (r.convergedIteration >= 0 ? std::to_string(r.convergedIteration) : std::string()) << ','
     << num(r.pathLength, 5) << ',' << num(r.straightLine, 5) << ',' << num(r.pathRatio()) << ','
     << num(1000 * r.finalTranslation) << ',' << num(vpMath::deg(r.finalRotation)) << ','
     << (r.tagMeasured ? num(1000 * r.finalTagTranslation) : std::string()) << ','
     << (r.tagMeasured ? num(vpMath::deg(r.finalTagRotation)) : std::string()) << ',' << r.recognized << ','
     << (r.recognitionCorrect() ? 1 : 0) << ',' << faultKinds(s) << ',' << r.holds << ',' << r.replans << ','
     << r.rerecognitions << ',' << num(r.maxSpeed) << ',' << num(vpMath::deg(r.maxRotationSpeed)) << ',' << r.goal
     << ',' << csvWord(r.setup) << ',' << (r.converged ? 1 : 0) << ',' << (r.falseConverged ? 1 : 0) << ','
     << truthName(s) << ',' << (tag ? num(1000 * r.tagSize) : std::string()) << ','
     << (tag ? num(1000 * r.taughtTagTranslation) : std::string()) << ','
     << (tag ? num(vpMath::deg(r.taughtTagRotation)) : std::string()) << ',' << num(1000 * r.finalOverlapTranslation)
     << ',' << num(vpMath::deg(r.finalOverlapRotation)) << ',' << r.symmetry << ',' << r.unobservable << ','
     << r.verification;
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

void vpMorphBenchReport::sortCurves(std::vector<std::string> &rows)
{
  const std::vector<std::string> sets = vpMorphBenchScenario::setNames(), ctrls = vpMorphBenchController::names();
  using Key = std::tuple<int, int, std::string, double, std::string, int, std::string, double>;
  std::vector<std::pair<Key, std::size_t>> keys;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const std::vector<std::string> f = split(rows[k]);
    if (f.size() != 7)
      keys.emplace_back(Key(1, 0, "", 0, "", 0, "", k), k); // unparsed: last, in order
    else
      keys.emplace_back(Key(0, orderOf(sets, f[0]), f[0], vpMorphBenchCsv::number(f[3]), f[1], orderOf(ctrls, f[2]),
                            f[2], vpMorphBenchCsv::number(f[4])),
                        k);
  }
  std::stable_sort(keys.begin(), keys.end(), [](const auto &a, const auto &b) { return a.first < b.first; });
  std::vector<std::string> out;
  for (const auto &k : keys)
    out.push_back(rows[k.second]);
  rows.swap(out);
}

std::string vpMorphBenchReport::summaryJson(const std::map<std::string, std::string> &meta) const
{
  nlohmann::json j;
  j["version"] = 2;
  for (const auto &m : meta)
    j["meta"][m.first] = m.second;
  j["summaries"] = nlohmann::json::array();
  for (const Summary &s : summarize()) {
    nlohmann::json e;
    e["set"] = s.set;
    e["robot"] = s.robot;
    e["controller"] = s.controller;
    e["runs"] = s.runs;
    e["setups"] = s.setups;
    e["attempted"] = s.attempted();
    e["successes"] = s.successes;
    e["success_rate"] = s.successRate();
    e["success_ci95"] = {s.successLow, s.successHigh};
    e["false_converged"] = s.falseConverged;
    e["false_converged_upper95"] = s.falseConvergedHigh;
    e["declared_converged"] = s.declaredConverged;
    e["unverified_successes"] = s.unverifiedSuccesses;
    e["median_iterations"] = jnum(s.medianIterations);
    e["median_path_length_m"] = jnum(s.medianPathLength);
    e["median_path_ratio"] = jnum(s.medianPathRatio);
    e["median_final_t_mm"] = jnum(1000 * s.medianFinalTranslation);
    e["median_final_r_deg"] = jnum(vpMath::deg(s.medianFinalRotation));
    e["median_final_tag_t_mm"] = jnum(1000 * s.medianFinalTagTranslation);
    e["median_final_tag_r_deg"] = jnum(vpMath::deg(s.medianFinalTagRotation));
    e["median_final_overlap_t_mm"] = jnum(1000 * s.medianFinalOverlapTranslation);
    e["median_final_overlap_r_deg"] = jnum(vpMath::deg(s.medianFinalOverlapRotation));
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
  os << "| set | robot | controller | success (95 % interval) | declared converged | false-converged | "
        "set-up failures | median iter. | median path (mm) | path ratio | final error truth (mm / deg) | "
        "final error tag (mm / deg) | failures | holds / re-plans / re-recognitions |\n";
  os << "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  auto dash = [](const std::string &x) { return x.empty() ? std::string("-") : x; };
  for (const Summary &s : summarize()) {
    std::ostringstream fails;
    for (const auto &f : s.failures)
      fails << (fails.tellp() > 0 ? ", " : "") << f.first << " " << f.second;
    // The successes that declared convergence, and why the others did not (their verification).
    std::ostringstream declared;
    declared << s.declaredConverged << "/" << s.successes;
    for (auto u = s.unverifiedSuccesses.begin(); u != s.unverifiedSuccesses.end(); ++u)
      declared << (u == s.unverifiedSuccesses.begin() ? " (" : ", ") << u->first << " " << u->second;
    declared << (s.unverifiedSuccesses.empty() ? "" : ")");
    os << "| " << s.set << " | " << s.robot << " | " << s.controller << " | " << s.successes << "/" << s.attempted()
       << " (" << num(100 * s.successRate(), 3) << " %, " << num(100 * s.successLow, 3) << "-"
       << num(100 * s.successHigh, 3) << ") | " << declared.str() << " | " << s.falseConverged
       << " (<= " << num(100 * s.falseConvergedHigh, 3) << " %) | " << s.setups << " | "
       << dash(num(s.medianIterations, 4)) << " | " << dash(num(1000 * s.medianPathLength, 4)) << " | "
       << dash(num(s.medianPathRatio, 3)) << " | " << dash(num(1000 * s.medianFinalTranslation, 3)) << " / "
       << dash(num(vpMath::deg(s.medianFinalRotation), 3)) << " | " << dash(num(1000 * s.medianFinalTagTranslation, 3))
       << " / " << dash(num(vpMath::deg(s.medianFinalTagRotation), 3)) << " | " << dash(fails.str()) << " | " << s.holds
       << " / " << s.replans << " / " << s.rerecognitions << " |\n";
  }
  return os.str();
}
