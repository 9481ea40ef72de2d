/*!
  \file vispmorph-bench.cpp
  \brief The comparison: VISPMorph and ViSP's stock controllers on identical simulated starts.

  \code
  vispmorph-bench --set planar|planar-hard|6dof|calib|calib-no-tilt|noise|occlusion|deformable|faults|all[,...]
                  [--controllers morph,morph-planar,morph-vpservo,ibvs-current,ibvs-desired,ibvs-mean,pbvs,moments,
                                 moments-planar]
                  [--robot camera|viper850|afma6] [--count N] [--seed S] --out DIR
                  [--threads T] [--max-iterations N] [--lambda L] [--no-curves] [--no-plots] [--recognition]
  \endcode
  Generates the scenarios of each set (vpMorphBenchScenario::generate, seeded), runs every controller on every
  scenario (vpMorphBench, all cores, progress on stderr) and writes in DIR:
  - scenarios.csv: the starts, to replay any run (set, index, seed, object, start, faults, calibration errors);
  - runs.csv: one row per run, appended as runs finish (an interrupted bench keeps what it finished);
  - curves.csv: the truth pose error at every iteration of every run;
  - summary.json and summary.md: per set, robot and controller (vpMorphBenchReport);
  - PNG plots made by vispmorph-bench-plots.py (Debian's /usr/bin/python3 with matplotlib) unless --no-plots.
  With --recognition, no run: the first view of every scenario is recognised (vpMorphBench::recognizeStart()), one
  row each in recognition.csv, and the counts per set (right tool, another tool, rejected, re-ranked) are printed and
  written to recognition.md: the recognition checked on more starts than the servo can afford.
  Exit status: 0 when the bench ran (whatever the controllers did), 1 on an error, 2 on bad arguments.
*/
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <thread>
#include <unistd.h>
#include <vector>

#include <opencv2/core.hpp>

#include <visp3/core/vpMath.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_bench/vpMorphBench.h>
#include <visp3/morph_bench/vpMorphBenchController.h>
#include <visp3/morph_bench/vpMorphBenchReport.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>
#include <visp3/morph_sim/vpMorphTagPoseEstimator.h>

namespace fs = std::filesystem;

namespace
{
void usage(std::ostream &os)
{
  os << "Usage: vispmorph-bench --set SETS --out DIR [options]\n"
        "  --set SETS         comma-separated: planar, planar-hard, 6dof, calib, noise, occlusion, deformable,\n"
        "                     faults (timed faults, 5 kinds in turn), calib-no-tilt (calib's starts, the hand-eye\n"
        "                     rotation error about the optical axis only), all\n"
        "  --controllers L    comma-separated (default all): morph, morph-planar, morph-vpservo, ibvs-current, "
        "ibvs-desired,\n"
        "                     ibvs-mean, pbvs, moments, moments-planar\n"
        "  --robot R          camera (default), viper850 or afma6\n"
        "  --count N          scenarios per set (default 10)\n"
        "  --only LIST        replay only these scenario indices of each set (comma-separated, each < N)\n"
        "  --seed S           seed of the scenario sets (default 1)\n"
        "  --threads T        threads (default: all cores)\n"
        "  --max-iterations N iteration budget per run (default 600)\n"
        "  --lambda L         gain of every controller, 1/s (default 2.5)\n"
        "  --data DIR         the data/ folder (default: the repository's)\n"
        "  --no-curves        do not write curves.csv\n"
        "  --recognition      no runs: recognise each scenario's first view (recognition.csv, recognition.md)\n"
        "  --no-plots         do not run the plot script\n";
}

std::vector<std::string> splitList(const std::string &s)
{
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty())
      out.push_back(item);
  return out;
}

struct BadArgs
{
  std::string msg;
};

unsigned long parseUnsigned(const std::string &opt, const std::string &v, unsigned long min)
{
  try {
    std::size_t pos = 0;
    const unsigned long x = std::stoul(v, &pos);
    if (pos == v.size() && x >= min && v.find('-') == std::string::npos)
      return x;
  } catch (const std::exception &) {
  }
  throw BadArgs{"option " + opt + " needs an integer >= " + std::to_string(min) + ", got '" + v + "'"};
}

double parsePositive(const std::string &opt, const std::string &v)
{
  try {
    std::size_t pos = 0;
    const double x = std::stod(v, &pos);
    if (pos == v.size() && std::isfinite(x) && x > 0)
      return x;
  } catch (const std::exception &) {
  }
  throw BadArgs{"option " + opt + " needs a finite number > 0, got '" + v + "'"};
}

std::string scenarioRow(const vpMorphBenchScenario &s)
{
  std::ostringstream os;
  os << std::setprecision(6) << s.set << ',' << s.index << ',' << s.seed << ',' << s.object << ',' << s.startRotationDeg
     << ',' << s.startTranslationMm << ',' << s.startTiltDeg << ',' << s.startDepthChange << ',' << s.faults.noiseSigma
     << ',' << s.faults.blurSigma << ',' << s.faults.gain << ',' << s.faults.offset << ',' << s.faults.occludedShare
     << ',' << s.focalScaleX << ',' << s.focalScaleY << ',' << s.principalShiftU << ',' << s.principalShiftV << ','
     << 1000 * s.eMcError.getTranslationVector().frobeniusNorm() << ','
     << vpMath::deg(vpThetaUVector(s.eMcError.getRotationMatrix()).getTheta()) << ",\"" << s.describe() << "\"";
  return os.str();
}

/*
  CPU time (ms) of one silhouette extraction of the pliers' taught view, the fastest of 5 batches of 20: a yardstick
  of the machine's speed. The per-set compute times move with it (the development machine's slowed by 1.8 times in
  one session), so runs on different days or machines are compared through their ratio to it.
*/
double yardstickMs(const std::string &dataDir)
{
  const vpMorphPlanarScene scene(dataDir + "/objects/pliers.png");
  const vpHomogeneousMatrix cdMo = vpMorphBenchScenario::desiredPose("pliers");
  vpImage<unsigned char> I;
  scene.render(cdMo, I);
  const std::vector<vpImagePoint> corners = scene.projectedTagCorners(cdMo);
  double best = std::numeric_limits<double>::infinity();
  for (int batch = 0; batch < 5; ++batch) {
    double sum = 0.0;
    for (int k = 0; k < 20; ++k) {
      double ms = 0.0;
      vpMorphTagPoseEstimator::silhouette(I, corners, &ms);
      sum += ms;
    }
    best = std::min(best, sum / 20.0);
  }
  return best;
}
/*
  --recognition: the first view of each scenario recognised, a row each in recognition.csv, and the counts per set in
  recognition.md and on stdout. Progress on stderr every 10 views.
*/
int recognizeStarts(const vpMorphBench &bench, const std::vector<vpMorphBenchScenario> &scenarios,
                    const std::string &out)
{
  const vpMorphDatabase &db = bench.database();
  vpMorphDatabase distanceAlone = db; // the same database without the support, for comparison
  distanceAlone.setMinimumSupport(std::numeric_limits<double>::infinity());
  std::ofstream f(out + "/recognition.csv");
  f << "set,scenario,seed,object,recognized,accepted,correct,distance,threshold,support,reranked,runner_up,"
       "distance_alone_recognized,distance_alone_accepted\n";
  struct Counts
  {
    int views = 0, right = 0, wrong = 0, rejected = 0, reranked = 0, empty = 0, aloneRight = 0, aloneWrong = 0;
  };
  std::vector<std::pair<std::string, Counts>> perSet;
  for (std::size_t k = 0; k < scenarios.size(); ++k) {
    const vpMorphBenchScenario &sc = scenarios[k];
    vpMorphContour c;
    const vpMorphRecognition r = bench.recognizeStart(sc, &c);
    const vpMorphRecognition a = c.empty() ? vpMorphRecognition() : distanceAlone.recognize(c);
    const std::string aloneName = c.empty() ? std::string() : db[a.index].name();
    if (perSet.empty() || perSet.back().first != sc.set)
      perSet.emplace_back(sc.set, Counts());
    Counts &n = perSet.back().second;
    ++n.views;
    const bool none = r.index == vpMorphRecognition::npos;
    const std::string name = none ? std::string() : db[r.index].name();
    n.empty += none ? 1 : 0;
    n.right += r.accepted && name == sc.object ? 1 : 0;
    n.wrong += r.accepted && name != sc.object ? 1 : 0;
    n.rejected += !none && !r.accepted ? 1 : 0;
    n.reranked += r.reranked ? 1 : 0;
    n.aloneRight += a.accepted && aloneName == sc.object ? 1 : 0;
    n.aloneWrong += a.accepted && aloneName != sc.object ? 1 : 0;
    f << std::setprecision(6) << sc.set << ',' << sc.index << ',' << sc.seed << ',' << sc.object << ',' << name << ','
      << r.accepted << ',' << (r.accepted && name == sc.object) << ',' << r.distance << ',' << r.threshold << ','
      << r.support << ',' << r.reranked << ','
      << (r.secondIndex == vpMorphRecognition::npos ? std::string() : db[r.secondIndex].name()) << ',' << aloneName
      << ',' << a.accepted << "\n";
    if ((k + 1) % 10 == 0 || k + 1 == scenarios.size())
      std::cerr << "[" << k + 1 << "/" << scenarios.size() << "] first views recognised" << std::endl;
  }
  std::ostringstream md;
  md << "| set | first views | right tool | another tool | rejected | re-ranked | no silhouette | distance alone: "
        "right / another tool |\n|---|---|---|---|---|---|---|---|\n";
  for (const auto &p : perSet)
    md << "| " << p.first << " | " << p.second.views << " | " << p.second.right << " | " << p.second.wrong << " | "
       << p.second.rejected << " | " << p.second.reranked << " | " << p.second.empty << " | " << p.second.aloneRight
       << " / " << p.second.aloneWrong << " |\n";
  std::ofstream(out + "/recognition.md") << md.str();
  std::cout << md.str() << "results in " << out << "/recognition.csv" << std::endl;
  return EXIT_SUCCESS;
}
} // namespace

int main(int argc, char **argv)
{
  // The runs already share the cores among them; OpenCV's own pool would put part of each extraction on other
  // threads (findContours() thresholds through it), which oversubscribes the cores and which a run's CPU clock, the
  // calling thread's, does not count. With one OpenCV thread a run's compute time is all its work.
  cv::setNumThreads(1);
  std::vector<std::string> sets, controllers = vpMorphBenchController::names();
  std::string out, robotName = "camera", dataDir = VISPMORPH_DATA_DIR;
  unsigned int count = 10, seed = 1, threads = 0;
  std::vector<unsigned int> only;
  vpMorphBench::Settings settings;
  bool curves = true, plots = true, recognitionOnly = false;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc)
          throw BadArgs{"option " + a + " needs a value"};
        return argv[++i];
      };
      if (a == "--set") {
        for (const std::string &s : splitList(value())) {
          if (s == "all") {
            for (const std::string &n : vpMorphBenchScenario::setNames())
              sets.push_back(n);
            continue;
          }
          const auto names = vpMorphBenchScenario::setNames();
          if (std::find(names.begin(), names.end(), s) == names.end())
            throw BadArgs{"unknown set '" + s + "'"};
          sets.push_back(s);
        }
      } else if (a == "--controllers") {
        controllers = splitList(value());
        const auto names = vpMorphBenchController::names();
        for (const std::string &c : controllers)
          if (std::find(names.begin(), names.end(), c) == names.end())
            throw BadArgs{"unknown controller '" + c + "'"};
      } else if (a == "--robot") {
        robotName = value();
        if (robotName == "camera")
          settings.robot = vpMorphSimRobot::FREE_CAMERA;
        else if (robotName == "viper850")
          settings.robot = vpMorphSimRobot::VIPER850;
        else if (robotName == "afma6")
          settings.robot = vpMorphSimRobot::AFMA6;
        else
          throw BadArgs{"unknown robot '" + robotName + "' (camera, viper850, afma6)"};
      } else if (a == "--count")
        count = static_cast<unsigned int>(parseUnsigned(a, value(), 1));
      else if (a == "--only") {
        for (const std::string &k : splitList(value()))
          only.push_back(static_cast<unsigned int>(parseUnsigned(a, k, 0)));
      } else if (a == "--seed")
        seed = static_cast<unsigned int>(parseUnsigned(a, value(), 0));
      else if (a == "--threads")
        threads = static_cast<unsigned int>(parseUnsigned(a, value(), 1));
      else if (a == "--max-iterations")
        settings.maxIterations = static_cast<unsigned int>(parseUnsigned(a, value(), 1));
      else if (a == "--lambda")
        settings.lambda = parsePositive(a, value());
      else if (a == "--out")
        out = value();
      else if (a == "--data")
        dataDir = value();
      else if (a == "--no-curves")
        curves = false;
      else if (a == "--no-plots")
        plots = false;
      else if (a == "--recognition")
        recognitionOnly = true;
      else if (a == "--help" || a == "-h") {
        usage(std::cout);
        return EXIT_SUCCESS;
      } else
        throw BadArgs{"unknown option '" + a + "'"};
    }
    if (sets.empty())
      throw BadArgs{"--set is required"};
    if (out.empty())
      throw BadArgs{"--out is required"};
    if (controllers.empty())
      throw BadArgs{"--controllers is empty"};
    for (unsigned int k : only)
      if (k >= count)
        throw BadArgs{"--only: scenario " + std::to_string(k) + " is not below --count " + std::to_string(count)};
  } catch (const BadArgs &e) {
    std::cerr << "vispmorph-bench: " << e.msg << "\n";
    usage(std::cerr);
    return 2;
  }

  try {
    settings.recordCurves = curves;
    fs::create_directories(out);
    std::cerr << "vispmorph-bench: teaching the six templates and calibrating recognition..." << std::endl;
    const vpMorphBench bench(dataDir, settings);

    std::vector<vpMorphBenchScenario> scenarios;
    for (const std::string &s : sets) {
      // A scenario depends on (seed, set, index) only: replaying a few of them gives the same starts.
      for (const vpMorphBenchScenario &sc : vpMorphBenchScenario::generate(s, count, seed, dataDir))
        if (only.empty() || std::find(only.begin(), only.end(), sc.index) != only.end())
          scenarios.push_back(sc);
    }
    {
      std::ofstream f(out + "/scenarios.csv");
      f << "set,scenario,seed,object,start_rotation_deg,start_translation_mm,start_tilt_deg,start_depth_change,"
           "noise_sigma,blur_sigma,gain,offset,occluded_share,focal_scale_x,focal_scale_y,principal_shift_u,"
           "principal_shift_v,eMc_error_mm,eMc_error_deg,description\n";
      for (const vpMorphBenchScenario &s : scenarios)
        f << scenarioRow(s) << "\n";
    }

    if (recognitionOnly)
      return recognizeStarts(bench, scenarios, out);

    std::ofstream runs(out + "/runs.csv");
    runs << vpMorphBenchReport::runsHeader() << "\n" << std::flush;
    std::ofstream curvesFile;
    if (curves) {
      curvesFile.open(out + "/curves.csv");
      curvesFile << vpMorphBenchReport::curvesHeader() << "\n";
    }
    const bool tty = isatty(STDERR_FILENO);
    const double yardstickBefore = yardstickMs(dataDir);
    const auto t0 = std::chrono::steady_clock::now();
    std::cerr << "vispmorph-bench: " << scenarios.size() << " scenarios x " << controllers.size() << " controllers on "
              << robotName << ", seed " << seed << std::endl;
    vpMorphBenchReport report;
    auto progress = [&](std::size_t done, std::size_t total, const vpMorphBenchResult &r) {
      // Called under the runner's lock: rows are written as runs finish.
      runs << vpMorphBenchReport::runsRow(r) << "\n" << std::flush;
      if (curves)
        curvesFile << vpMorphBenchReport::curvesRows(r);
      report.add(r);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::ostringstream line;
      line << "[" << std::setw(4) << done << "/" << total << ", " << std::fixed << std::setprecision(0) << s << " s] "
           << r.scenario.set << "#" << r.scenario.index << " " << r.scenario.object << " " << r.controller << ": "
           << (r.success ? "success" : r.failure) << " (" << r.iterations << " it)";
      if (tty)
        std::cerr << "\r" << std::left << std::setw(100) << line.str() << std::flush;
      else
        std::cerr << line.str() << "\n";
    };
    bench.runAll(scenarios, controllers, threads, progress);
    if (tty)
      std::cerr << "\n";
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double yardstickAfter = yardstickMs(dataDir);
    std::ostringstream yardstick;
    yardstick << std::fixed << std::setprecision(3) << "Machine yardstick (CPU time of one silhouette extraction of "
              << "the taught pliers view, fastest of 5 x 20): " << yardstickBefore << " ms before the runs, "
              << yardstickAfter << " ms after. Compare compute times across runs through their ratio to it.\n";

    std::map<std::string, std::string> meta;
    std::ostringstream cmd;
    for (int i = 0; i < argc; ++i)
      cmd << (i ? " " : "") << argv[i];
    meta["command"] = cmd.str();
    meta["seed"] = std::to_string(seed);
    meta["robot"] = robotName;
    meta["lambda_per_s"] = std::to_string(settings.lambda);
    meta["sampling_time_s"] = std::to_string(settings.samplingTime);
    meta["max_iterations"] = std::to_string(settings.maxIterations);
    meta["wall_time_s"] = std::to_string(wall);
    meta["hardware_threads"] = std::to_string(std::thread::hardware_concurrency());
    meta["yardstick_extract_ms_before"] = std::to_string(yardstickBefore);
    meta["yardstick_extract_ms_after"] = std::to_string(yardstickAfter);
    std::ofstream(out + "/summary.json") << report.summaryJson(meta) << "\n";
    const std::string md = report.summaryMarkdown() + "\n" + yardstick.str();
    std::ofstream(out + "/summary.md") << md;
    std::cout << md << "wall time " << std::fixed << std::setprecision(1) << wall << " s; results in " << out << "/"
              << std::endl;

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
    return EXIT_SUCCESS;
  } catch (const vpException &e) {
    std::cerr << "vispmorph-bench: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  } catch (const std::exception &e) {
    std::cerr << "vispmorph-bench: " << e.what() << std::endl;
    return EXIT_FAILURE;
  }
}
