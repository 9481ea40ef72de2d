/*!
  \file vispmorph-bench.cpp
  \brief The comparison: VISPMorph and ViSP's stock controllers on identical simulated starts, on any objects.

  \code
  vispmorph-bench --set SETS|all --out DIR [--objects DIR|LIST | --pool development|evaluation] [--shard K/N] ...
  vispmorph-bench merge --out DIR SHARD_DIR...
  \endcode
  Generates the scenarios of each set (vpMorphBenchScenario::generate, seeded), runs every controller on every
  scenario (vpMorphBench, all cores, progress on stderr) and writes in DIR:
  - objects.csv: the objects used and the inputs skipped, with why; objects/: their laid-out images and variants;
  - scenarios.csv and scenarios.json: the starts (the JSON to the bit, vpMorphBenchScenario::fromJson());
  - runs.csv: one row per run (runs.partial.csv while they run: an interrupted bench keeps what it finished);
  - curves.csv: the truth pose error at every iteration of every run;
  - summary.json and summary.md: per set, robot and controller (vpMorphBenchReport); summary.json's meta holds the
    settings and the commit the tool was built at ("-dirty" with uncommitted changes, "unknown" outside git);
  - timings.csv, timings.json and timings.md: the compute times (vpMorphBenchTimings) and the machine;
  - PNG plots made by vispmorph-bench-plots.py (Debian's /usr/bin/python3 with matplotlib) unless --no-plots.
  With --shard K/N only the scenarios at positions K - 1, K - 1 + N, ... of the command's list run; merge joins
  the shards' folders into the files of one run, identical to the byte but for the timings; shards of other settings
  or built at another commit are refused.
  With --recognition, no run: the first view of every scenario is recognised (vpMorphBench::recognizeStart()), one
  row each in recognition.csv, and the counts per set (right object, another, rejected, re-ranked) are printed and
  written to recognition.md: the recognition checked on more starts than the servo can afford.
  With --video, no summary: each run, one at a time, recorded in DIR/video/SET-INDEX-CONTROLLER/ (the camera's frames,
  the frames with the controller's state drawn and as a video, the templates and the camera) for a person to watch
  and for vispmorph-replay (vispmorph-bench-video.h).
  Exit status: 0 when the bench ran (whatever the controllers did), 1 on an error, 2 on bad arguments.
*/
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
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
#include <visp3/morph_bench/vpMorphBenchObjectSet.h>
#include <visp3/morph_bench/vpMorphBenchReport.h>
#include <visp3/morph_bench/vpMorphBenchTimings.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>
#include <visp3/morph_sim/vpMorphTagPoseEstimator.h>

#include "vispmorph-bench-results.h"
#include "vispmorph-bench-video.h"
#include "vispmorph-source-commit.h"

namespace fs = std::filesystem;

namespace
{
void usage(std::ostream &os)
{
  os << "Usage: vispmorph-bench --set SETS --out DIR [options]\n"
        "  --set SETS         comma-separated, or all: planar, planar-hard, 6dof, calib, noise, occlusion, "
        "deformable,\n"
        "                     faults, calib-no-tilt, calib-wide, saturated, low-contrast, rough, gradient, "
        "plane-edge,\n"
        "                     large-distractor, res-1280, res-320\n"
        "  --controllers L    comma-separated (default all): morph, morph-planar, morph-paper, morph-vpservo, "
        "ibvs-current, "
        "ibvs-desired,\n"
        "                     ibvs-mean, pbvs, moments, moments-planar\n"
        "  --robot R          camera (default), viper850 or afma6\n"
        "  --objects D|LIST   the objects: every image of folder D (or each path of a list file), any polarity and\n"
        "                     size, named by its file stem (default: the six tools of DATA/objects)\n"
        "  --pool P           the objects of pool P of data/pools/split.json: development or evaluation\n"
        "  --per-class N      with --pool: images per class (default 1)\n"
        "  --datasets DIR     the shape datasets' folder (default: $VISPMORPH_DATASETS_DIR, else ../shared/datasets\n"
        "                     beside the repository)\n"
        "  --count N          scenarios per set (default 10), objects in turn\n"
        "  --starts K         starts per object and set (instead of --count: K x the objects)\n"
        "  --only LIST        replay only these scenario indices of each set (comma-separated, each < N)\n"
        "  --seed S           seed of the scenario sets (default 100; development 100-999, evaluation 1000 and up)\n"
        "  --shard K/N        run the K-th of N deterministic shares of the scenarios (vispmorph-bench merge joins "
        "them)\n"
        "  --threads T        threads (default: all cores)\n"
        "  --max-iterations N iteration budget per run (default 600)\n"
        "  --lambda L         gain of every controller, 1/s (default 2.5)\n"
        "  --data DIR         the data/ folder (default: the repository's)\n"
        "  --no-curves        do not write curves.csv\n"
        "  --recognition      no runs: recognise each scenario's first view (recognition.csv, recognition.md)\n"
        "  --recognition-model M  the databases' distance: polygon, paper, multiscale (default), rigid or height\n"
        "  --video            no summary: each run recorded in DIR/video/ (frames, overlays, a video; choose the\n"
        "                     runs with --set, --only and --controllers)\n"
        "  --no-plots         do not run the plot script\n"
        "       vispmorph-bench merge --out DIR SHARD_DIR... [--no-plots]\n"
        "                     the shards of one command as one run (the same files, to the byte, but the timings)\n";
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
  CPU time (ms) of one silhouette extraction of a fixed view of the pliers (10 mm off the optical axis at 0.5 m,
  turned by 20 deg, 640 x 480, tag beside it), the fastest of 5 batches of 20: a yardstick of the machine's speed.
  The per-set compute times move with it (the development machine's slowed by 1.8 times in one session), so runs on
  different days or machines are compared through their ratio to it.
*/
double yardstickMs(const std::string &dataDir)
{
  const vpMorphPlanarScene scene(dataDir + "/objects/pliers.png");
  const vpHomogeneousMatrix cdMo(0.010, 0.0, 0.5, 0.0, 0.0, vpMath::rad(20.0));
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
  std::map<const vpMorphDatabase *, vpMorphDatabase> alone; // each database without the support, for comparison
  std::ofstream f(out + "/recognition.csv");
  f << "set,scenario,seed,object,recognized,accepted,correct,distance,threshold,support,reranked,runner_up,"
       "distance_alone_recognized,distance_alone_accepted,stage,ambiguous\n";
  struct Counts
  {
    int views = 0, right = 0, wrong = 0, rejected = 0, reranked = 0, empty = 0, aloneRight = 0, aloneWrong = 0;
  };
  std::vector<std::pair<std::string, Counts>> perSet;
  for (std::size_t k = 0; k < scenarios.size(); ++k) {
    const vpMorphBenchScenario &sc = scenarios[k];
    const vpMorphDatabase &db = bench.database(sc.variant, sc.set);
    if (!alone.count(&db)) {
      alone[&db] = db;
      alone[&db].setMinimumSupport(std::numeric_limits<double>::infinity());
    }
    const vpMorphDatabase &distanceAlone = alone[&db];
    vpMorphContour c;
    vpMorphPartRecognizer::Stage stage = vpMorphPartRecognizer::RIGID_STAGE;
    const vpMorphRecognition r = bench.recognizeStart(sc, &c, &stage);
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
      << ',' << a.accepted << ','
      << (none                                          ? std::string()
          : stage == vpMorphPartRecognizer::RIGID_STAGE ? "rigid"
                                                        : db.distance().name())
      << ',' << r.ambiguous << "\n";
    if ((k + 1) % 10 == 0 || k + 1 == scenarios.size())
      std::cerr << "[" << k + 1 << "/" << scenarios.size() << "] first views recognised" << std::endl;
  }
  std::ostringstream md;
  md << "| set | first views | right object | another object | rejected | re-ranked | no silhouette | distance alone: "
        "right / another object |\n|---|---|---|---|---|---|---|---|\n";
  for (const auto &p : perSet)
    md << "| " << p.first << " | " << p.second.views << " | " << p.second.right << " | " << p.second.wrong << " | "
       << p.second.rejected << " | " << p.second.reranked << " | " << p.second.empty << " | " << p.second.aloneRight
       << " / " << p.second.aloneWrong << " |\n";
  std::ofstream(out + "/recognition.md") << md.str();
  std::cout << md.str() << "results in " << out << "/recognition.csv" << std::endl;
  return EXIT_SUCCESS;
}
//! The command's deterministic settings (summary.json's meta): the same for one run and for its merged shards.
std::map<std::string, std::string> settingsMeta(const std::vector<std::string> &sets,
                                                const std::vector<std::string> &controllers, const std::string &robot,
                                                unsigned int seed, unsigned int count, const std::string &objects,
                                                const vpMorphBench::Settings &settings)
{
  std::map<std::string, std::string> meta;
  std::string s, c;
  for (const std::string &x : sets)
    s += (s.empty() ? "" : ",") + x;
  for (const std::string &x : controllers)
    c += (c.empty() ? "" : ",") + x;
  meta["sets"] = s;
  meta["controllers"] = c;
  meta["robot"] = robot;
  meta["seed"] = std::to_string(seed);
  meta["seed_class"] = seed >= 1000 ? "evaluation" : seed >= 100 ? "development" : "outside the split's seeds";
  meta["scenarios_per_set"] = std::to_string(count);
  meta["objects"] = objects;
  std::ostringstream budget;
  budget << settings.maxIterations << " periods of " << settings.samplingTime << " s";
  meta["budget"] = budget.str();
  meta["lambda_per_s"] = std::to_string(settings.lambda);
  meta["recognition_model"] =
      settings.recognitionModel.empty() ? vpMorphDatabase().distance().name() : settings.recognitionModel;
  meta["success"] = "final truth error under " + std::to_string(1000 * settings.successTranslation).substr(0, 4) +
                    " mm and " + std::to_string(settings.successRotationDeg).substr(0, 4) +
                    " deg, target never out of view, within the budget";
  return meta;
}

} // namespace

int main(int argc, char **argv)
{
  // The runs already share the cores among them; OpenCV's own pool would put part of each extraction on other
  // threads (findContours() thresholds through it), which oversubscribes the cores and which a run's CPU clock, the
  // calling thread's, does not count. With one OpenCV thread a run's compute time is all its work.
  cv::setNumThreads(1);
  if (argc > 1 && std::string(argv[1]) == "merge")
    return mergeShards(argc, argv);
  std::vector<std::string> sets, controllers = vpMorphBenchController::names();
  std::string out, robotName = "camera", dataDir = VISPMORPH_DATA_DIR, datasetsDir = VISPMORPH_DATASETS_DIR;
  std::string objectsArg, pool;
  unsigned int count = 10, seed = 100, threads = 0, starts = 0, perClass = 1, shardK = 1, shardN = 1;
  if (const char *env = std::getenv("VISPMORPH_DATASETS_DIR"))
    datasetsDir = env;
  std::vector<unsigned int> only;
  vpMorphBench::Settings settings;
  bool curves = true, plots = true, recognitionOnly = false, video = false;
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
      else if (a == "--starts")
        starts = static_cast<unsigned int>(parseUnsigned(a, value(), 1));
      else if (a == "--objects")
        objectsArg = value();
      else if (a == "--pool") {
        pool = value();
        if (pool != "development" && pool != "evaluation")
          throw BadArgs{"unknown pool '" + pool + "' (development, evaluation)"};
      } else if (a == "--per-class")
        perClass = static_cast<unsigned int>(parseUnsigned(a, value(), 1));
      else if (a == "--datasets")
        datasetsDir = value();
      else if (a == "--shard") {
        const std::string v = value();
        const std::size_t slash = v.find('/');
        if (slash == std::string::npos)
          throw BadArgs{"option --shard needs K/N (1 <= K <= N), got '" + v + "'"};
        try {
          shardK = static_cast<unsigned int>(parseUnsigned(a, v.substr(0, slash), 1));
          shardN = static_cast<unsigned int>(parseUnsigned(a, v.substr(slash + 1), 1));
        } catch (const BadArgs &) {
          throw BadArgs{"option --shard needs K/N (1 <= K <= N), got '" + v + "'"};
        }
        if (shardK > shardN)
          throw BadArgs{"option --shard needs K/N (1 <= K <= N), got '" + v + "'"};
      } else if (a == "--only") {
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
      else if (a == "--recognition-model") {
        settings.recognitionModel = value();
        try {
          (void)vpMorphShapeDistance::fromName(settings.recognitionModel);
        } catch (const vpException &e) {
          throw BadArgs{e.getStringMessage()};
        }
      } else if (a == "--video")
        video = true;
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
    if (!objectsArg.empty() && !pool.empty())
      throw BadArgs{"--objects and --pool are exclusive"};
    if (!starts)
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
    std::cerr << "vispmorph-bench: seed " << seed << " ("
              << (seed >= 1000  ? "evaluation"
                  : seed >= 100 ? "development"
                                : "outside the split's seeds")
              << ")" << std::endl;
    vpMorphBenchObjectSet objects;
    std::string source;
    if (!pool.empty()) {
      const std::string split = dataDir + "/pools/split.json";
      std::vector<vpMorphBenchObjectSet::Source> sources;
      try {
        sources = vpMorphBenchObjectSet::poolImages(split, datasetsDir, pool, perClass);
      } catch (const vpMorphException &e) {
        if (e.getCode() != vpMorphException::notFoundError)
          throw;
        std::cerr << "vispmorph-bench: SKIPPED: the " << pool << " pool needs the shape datasets ("
                  << e.getStringMessage() << "; --datasets DIR gives their folder)" << std::endl;
        return EXIT_SUCCESS;
      }
      objects = vpMorphBenchObjectSet::images(sources, out, seed);
      source = pool + " pool, " + std::to_string(perClass) + " a class";
    } else if (!objectsArg.empty()) {
      objects = vpMorphBenchObjectSet::images(vpMorphBenchObjectSet::listImages(objectsArg), out, seed);
      source = "images of " + fs::path(objectsArg).filename().string();
    } else {
      objects = vpMorphBenchObjectSet::tools(dataDir, out);
      source = "the six tools";
    }
    // Paths under the output folder are written relative to it: the shards of a sweep list the same objects.
    auto relative = [&out](const std::string &path) {
      const std::string base = fs::path(out).lexically_normal().string() + "/";
      const std::string p = fs::path(path).lexically_normal().string();
      return p.compare(0, base.size(), base) == 0 ? p.substr(base.size()) : path;
    };
    {
      std::ofstream f(out + "/objects.csv");
      f << "object,status,image,deformed_image,truth,undeformed_share,reason\n";
      for (const vpMorphBenchObjectSet::Object &o : objects.objects())
        f << o.name << ",used," << relative(o.image) << ',' << relative(o.deformedImage) << ','
          << (o.truth == vpMorphBenchObjectSet::TRUTH_PART      ? "part"
              : o.truth == vpMorphBenchObjectSet::TRUTH_OVERLAP ? "overlap"
                                                                : "articulated")
          << ',' << (o.undeformedShare > 0 ? std::to_string(o.undeformedShare) : std::string()) << ",\n";
      for (const vpMorphBenchObjectSet::Skipped &k : objects.skipped()) {
        std::string reason = k.reason;
        std::replace(reason.begin(), reason.end(), ',', ';');
        f << fs::path(k.source).stem().string() << ",skipped," << k.source << ",,,," << reason << "\n";
        std::cerr << "vispmorph-bench: skipped " << k.source << ": " << k.reason << std::endl;
      }
    }
    if (objects.empty()) {
      std::cerr << "vispmorph-bench: no usable object" << std::endl;
      return EXIT_FAILURE;
    }
    if (starts)
      count = starts * static_cast<unsigned int>(objects.size());
    for (unsigned int k : only)
      if (k >= count)
        throw vpMorphException(vpMorphException::badParameterError,
                               "--only: scenario " + std::to_string(k) + " is not below " + std::to_string(count));
    const vpMorphBench bench(objects, seed, settings);

    // Every scenario of the command, then this shard's share: position j of the list when j mod N = K - 1. A
    // scenario depends on (seed, set, object, start) only: replaying a few of them gives the same starts.
    std::vector<vpMorphBenchScenario> scenarios;
    std::size_t position = 0;
    for (const std::string &s : sets)
      for (const vpMorphBenchScenario &sc : vpMorphBenchScenario::generate(s, count, seed, objects))
        if (only.empty() || std::find(only.begin(), only.end(), sc.index) != only.end())
          if (position++ % shardN == shardK - 1)
            scenarios.push_back(sc);
    {
      std::ofstream f(out + "/scenarios.csv"), j(out + "/scenarios.json");
      f << kScenariosHeader << "\n";
      j << "[";
      for (std::size_t k = 0; k < scenarios.size(); ++k) {
        f << scenarioRow(scenarios[k]) << "\n";
        j << (k ? ",\n" : "\n") << scenarios[k].toJson(out);
      }
      j << "\n]\n";
    }
    std::cerr << "vispmorph-bench: " << objects.size() << " objects (" << source << "); teaching the templates and "
              << "calibrating recognition..." << std::endl;
    bench.prepare(scenarios);

    if (recognitionOnly)
      return recognizeStarts(bench, scenarios, out);
    if (video)
      return recordRuns(bench, scenarios, controllers, out);

    std::ofstream runs(out + "/runs.partial.csv");
    runs << vpMorphBenchReport::runsHeader() << "\n" << std::flush;
    std::ofstream curvesFile;
    if (curves) {
      curvesFile.open(out + "/curves.partial.csv");
      curvesFile << vpMorphBenchReport::curvesHeader() << "\n";
    }
    const bool tty = isatty(STDERR_FILENO);
    const double yardstickBefore = yardstickMs(dataDir);
    const auto t0 = std::chrono::steady_clock::now();
    std::cerr << "vispmorph-bench: " << scenarios.size() << " scenarios x " << controllers.size() << " controllers on "
              << robotName << ", seed " << seed;
    if (shardN > 1)
      std::cerr << ", shard " << shardK << "/" << shardN;
    std::cerr << std::endl;
    vpMorphBenchReport report;
    std::vector<vpMorphBenchResult> timed;
    auto progress = [&](std::size_t done, std::size_t total, const vpMorphBenchResult &r) {
      // Called under the runner's lock: rows are written as runs finish (runs.csv is written in order at the end).
      runs << vpMorphBenchReport::runsRow(r) << "\n" << std::flush;
      if (curves)
        curvesFile << vpMorphBenchReport::curvesRows(r);
      report.add(r);
      vpMorphBenchResult t = r; // its times, without the curves
      t.curveTranslation.clear();
      t.curveRotation.clear();
      timed.push_back(t);
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::ostringstream line;
      line << "[" << std::setw(4) << done << "/" << total << ", " << std::fixed << std::setprecision(0) << s << " s] "
           << r.scenario.set << "#" << r.scenario.index << " " << r.scenario.object << " " << r.controller << ": "
           << (r.success ? "success" : r.failure) << (r.setup.empty() ? "" : " (" + r.setup + ")") << " ("
           << r.iterations << " it)";
      if (tty)
        std::cerr << "\r" << std::left << std::setw(100) << line.str() << std::flush;
      else
        std::cerr << line.str() << "\n";
    };
    bench.runAll(scenarios, controllers, threads, progress);
    if (tty)
      std::cerr << "\n";
    runs.close();
    curvesFile.close();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double yardstickAfter = yardstickMs(dataDir);
    vpMorphBenchTimings timings;
    for (const vpMorphBenchResult &r : timed)
      timings.add(r, 0.5 * (yardstickBefore + yardstickAfter));

    std::map<std::string, std::string> meta = settingsMeta(sets, controllers, robotName, seed, count, source, settings);
    meta["commit"] = VISPMORPH_SOURCE_COMMIT;
    if (shardN > 1)
      meta["shard"] = std::to_string(shardK) + "/" + std::to_string(shardN);
    std::map<std::string, std::string> machine;
    std::ostringstream cmd;
    for (int i = 0; i < argc; ++i)
      cmd << (i ? " " : "") << argv[i];
    machine["command"] = cmd.str();
    machine["wall_time_s"] = std::to_string(wall);
    machine["threads"] = std::to_string(threads ? threads : std::thread::hardware_concurrency());
    machine["hardware_threads"] = std::to_string(std::thread::hardware_concurrency());
    machine["yardstick_extract_ms_before"] = std::to_string(yardstickBefore);
    machine["yardstick_extract_ms_after"] = std::to_string(yardstickAfter);
    std::ostringstream ys;
    ys << std::fixed << std::setprecision(3) << "CPU time of one silhouette extraction of a fixed pliers view, "
       << "fastest of 5 x 20: " << yardstickBefore << " ms before the runs, " << yardstickAfter << " ms after";
    machine["yardstick"] = ys.str();
    writeResults(out, report, timings, meta, machine, curves, plots);
    std::cout << "wall time " << std::fixed << std::setprecision(1) << wall << " s; results in " << out << "/"
              << std::endl;
    return EXIT_SUCCESS;
  } catch (const vpException &e) {
    std::cerr << "vispmorph-bench: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  } catch (const std::exception &e) {
    std::cerr << "vispmorph-bench: " << e.what() << std::endl;
    return EXIT_FAILURE;
  }
}
