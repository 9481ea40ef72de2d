/*!
  \file vispmorph-soak.cpp
  \brief Soak test: many servo iterations and recognitions in one process, with the resident memory measured and
  the results checked for drift.

  \code
  vispmorph-soak [--servo-iterations N] [--recognitions N] [--task-length N] [--seed S] [--rounds R]
                 [--max-growth-kb K] [--csv FILE] [--data DIR]
  \endcode

  One process, one thread, interleaved in R rounds (default 100) so that both workloads are warm after the
  first rounds:
  - servo: vpServoMorph (10 sub-goals, Eq. 5-11, online hand-eye estimation from a hand-eye estimate 5 deg /
    10 mm off) on a free-flying camera (vpMorphSimRobot FREE_CAMERA); the contour is each object's outline
    projected through the true camera pose (vpMorphPlanarScene::projectedContour(): no rendering, so it is fast)
    with seeded Gaussian vertex noise (0.2 px) and 1 % of the frames dropped (an empty contour: the hold path).
    A task is one seeded planar start (rotation in [-180, 180] deg, translation up to 60 mm) of one of the six
    objects; it ends when converged, stopped, or after --task-length iterations, and the next task starts with
    restart() on the same vpServoMorph (the point is to reuse it for a long time).
  - recognition: vpMorphDatabase of the six objects (data/objects/<name>.png, calibrated); each query is a
    template's contour, seeded: rotated, scaled (0.5-1.5), translated, vertex noise (0.3 px), and in half of
    the queries a contiguous 5-15 % of the outline cut off by a straight chord (a partial occlusion).
  Resident memory (VmRSS of /proc/self/status) is sampled at the start and after every round; the growth is
  measured from the end of the warm-up (the first 5 % of the rounds, at least one) to the end, and the peak.
  Drift: servo task 0 and recognition query 0 run again at the end and must give bit-identical results
  (every velocity of the task, the recognition's index, distances and margin).
  Progress on stderr, summary on stdout, the RSS samples as CSV with --csv.
  Exit status: 0 when memory stayed within the bound and nothing drifted, 1 otherwise or on an error, 2 on bad
  arguments.
*/
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpMath.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>
#include <visp3/morph_sim/vpMorphSimRobot.h>
#include <visp3/morph_vs/vpServoMorph.h>

namespace
{
const char *const kObjects[] = {"pliers", "wedge", "key", "hammer", "screwdriver", "wrench"};
const std::size_t kObjectCount = 6;

struct BadArgs
{
  std::string msg;
};

void usage(std::ostream &os)
{
  os << "Usage: vispmorph-soak [options]\n"
        "  --servo-iterations N  vpServoMorph iterations in all (default 100000)\n"
        "  --recognitions N      recognitions in all (default 100000)\n"
        "  --task-length N       iterations before a servo task is restarted (default 300)\n"
        "  --seed S              seed of the tasks and queries (default 1)\n"
        "  --rounds R            rounds interleaving the two workloads, RSS sampled after each (default 100)\n"
        "  --max-growth-kb K     largest accepted RSS growth after warm-up, KiB (default 8192)\n"
        "  --csv FILE            write the RSS samples (round, iterations, recognitions, rss_kb)\n"
        "  --data DIR            the data/ folder (default: the repository's)\n"
        "  --help                this text\n";
}

unsigned long parseCount(const std::string &opt, const std::string &v, unsigned long min)
{
  std::size_t pos = 0;
  unsigned long long x = 0;
  try {
    if (v.empty() || v[0] == '-' || v[0] == '+')
      throw std::invalid_argument("sign");
    x = std::stoull(v, &pos);
  } catch (const std::exception &) {
    pos = 0;
  }
  if (pos != v.size() || v.empty() || x < min || x > 1000000000ULL)
    throw BadArgs{opt + " needs an integer >= " + std::to_string(min) + " (and <= 1e9), got '" + v + "'"};
  return static_cast<unsigned long>(x);
}

//! A field of /proc/self/status in KiB ("VmRSS:" resident set size, "VmHWM:" its high-water mark), 0 if unavailable.
long statusKb(const char *field = "VmRSS:")
{
  std::ifstream f("/proc/self/status");
  std::string line;
  const std::size_t n = std::strlen(field);
  while (std::getline(f, line))
    if (line.compare(0, n, field) == 0)
      return std::atol(line.c_str() + n);
  return 0;
}
long rssKb() { return statusKb("VmRSS:"); }

//! FNV-1a over the bytes of doubles: a fingerprint of a result, equal only when bit-identical.
struct Fingerprint
{
  std::uint64_t h = 1469598103934665603ULL;
  void add(double x)
  {
    unsigned char b[sizeof(double)];
    std::memcpy(b, &x, sizeof(double));
    for (unsigned char c : b) {
      h ^= c;
      h *= 1099511628211ULL;
    }
  }
};

//! The six objects: their scenes (outline projected without rendering) and templates.
struct Objects
{
  std::vector<vpMorphPlanarScene> scenes;
  vpMorphDatabase db;
};

Objects loadObjects(const std::string &dataDir)
{
  Objects o;
  for (const char *name : kObjects) {
    const std::string path = dataDir + "/objects/" + name + ".png";
    vpImage<unsigned char> I;
    try {
      vpImageIo::read(I, path);
    } catch (const vpException &) {
      throw vpMorphException(vpMorphException::ioError, "vispmorph-soak: cannot read " + path);
    }
    o.db.add(vpMorphTemplate(name, vpMorphContourExtractor().extract(I), path));
    o.scenes.emplace_back(path);
  }
  o.db.calibrate(1);
  return o;
}

//! One servo task: seeded start, a fresh sequence on the same servo, until done or \e length iterations.
struct TaskResult
{
  unsigned int iterations = 0;
  vpServoMorph::Status status = vpServoMorph::NOT_STARTED;
  std::uint64_t fingerprint = 0;
};

TaskResult runTask(vpServoMorph &servo, const Objects &obj, unsigned int task, unsigned int seed, unsigned int length)
{
  std::mt19937 rng(seed * 1000003u + task);
  auto uni = [&rng](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  std::normal_distribution<double> noise(0.0, 0.2);
  const vpMorphPlanarScene &scene = obj.scenes[task % kObjectCount];
  const vpHomogeneousMatrix cdMo(0, 0, 0.5, 0, 0, 0);
  const double r = 0.06 * uni(0, 1), a = uni(-M_PI, M_PI);
  const vpHomogeneousMatrix cdMc(r * std::cos(a), r * std::sin(a), 0, 0, 0, vpMath::rad(uni(-180, 180)));

  vpMorphSimRobot robot(vpMorphSimRobot::FREE_CAMERA, 0.04);
  robot.setDesiredPose(cdMo);
  robot.initialiseCameraRelativeToDesired(cdMc);
  servo.set_eMc(vpMorphSimRobot::perturbed(robot.eMcTrue(), 0.01 / std::sqrt(3.0), vpMath::rad(5)));
  servo.setTarget(scene.projectedContour(cdMo), 0.5); // restarts the sequence and the fault counters

  TaskResult res;
  Fingerprint fp;
  for (unsigned int it = 0; it < length; ++it) {
    vpMorphContour c;
    if (uni(0, 1) >= 0.01) { // 1 % dropped frames: the hold path
      c = scene.projectedContour(robot.get_cMo());
      std::vector<double> x = c.xs(), y = c.ys();
      for (std::size_t k = 0; k < x.size(); ++k) {
        x[k] += noise(rng);
        y[k] += noise(rng);
      }
      c = vpMorphContour(x, y);
    }
    const vpColVector ve = servo.computeControlLaw(c);
    ++res.iterations;
    for (unsigned int i = 0; i < ve.size(); ++i)
      fp.add(ve[i]);
    res.status = servo.getStatus();
    if (vpServoMorph::isStop(res.status) || res.status == vpServoMorph::DEGENERATE_CONTOUR ||
        res.status == vpServoMorph::UNEXPLAINED_VIEW)
      break;
    robot.setVelocity(vpRobot::END_EFFECTOR_FRAME, ve);
  }
  res.fingerprint = fp.h;
  return res;
}

//! Query \e q: a template's contour, seeded similarity, noise and (half of the time) a cut-off part.
vpMorphContour makeQuery(const vpMorphDatabase &db, unsigned long q, unsigned int seed, std::size_t &truth)
{
  std::mt19937 rng(seed * 7919u + static_cast<unsigned int>(q) * 2654435761u);
  auto uni = [&rng](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  truth = q % db.size();
  const vpMorphContour &t = db[truth].contour();
  std::vector<double> x = t.xs(), y = t.ys();
  const std::size_t n = x.size();
  if (uni(0, 1) < 0.5 && n > 12) { // cut a contiguous 5-15 % of the vertices by a chord
    const std::size_t cut = std::max<std::size_t>(1, static_cast<std::size_t>(uni(0.05, 0.15) * n));
    const std::size_t from = static_cast<std::size_t>(uni(0, 1) * n) % n;
    std::vector<double> xx, yy;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t d = (k + n - from) % n;
      if (d >= 1 && d <= cut)
        continue;
      xx.push_back(x[k]);
      yy.push_back(y[k]);
    }
    x.swap(xx);
    y.swap(yy);
  }
  std::normal_distribution<double> noise(0.0, 0.3);
  for (std::size_t k = 0; k < x.size(); ++k) {
    x[k] += noise(rng);
    y[k] += noise(rng);
  }
  return vpMorphContour(x, y).transformed(uni(-M_PI, M_PI), uni(-100, 100), uni(-100, 100), uni(0.5, 1.5));
}

std::uint64_t recognitionFingerprint(const vpMorphRecognition &r)
{
  Fingerprint fp;
  fp.add(static_cast<double>(r.index));
  fp.add(static_cast<double>(r.secondIndex));
  fp.add(r.distance);
  fp.add(r.secondDistance);
  fp.add(r.margin);
  fp.add(r.accepted ? 1.0 : 0.0);
  return fp.h;
}

std::string mb(long kb)
{
  std::ostringstream os;
  os << std::fixed << std::setprecision(1) << kb / 1024.0 << " MiB";
  return os.str();
}
} // namespace

int main(int argc, char **argv)
{
  unsigned long servoIterations = 100000, recognitions = 100000, taskLength = 300, seed = 1, rounds = 100;
  unsigned long maxGrowthKb = 8192;
  std::string csvPath, dataDir = VISPMORPH_DATA_DIR;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> std::string {
        if (i + 1 >= argc)
          throw BadArgs{"option " + a + " needs a value"};
        return argv[++i];
      };
      if (a == "--servo-iterations")
        servoIterations = parseCount(a, value(), 1);
      else if (a == "--recognitions")
        recognitions = parseCount(a, value(), 1);
      else if (a == "--task-length")
        taskLength = parseCount(a, value(), 10);
      else if (a == "--seed")
        seed = parseCount(a, value(), 0);
      else if (a == "--rounds")
        rounds = parseCount(a, value(), 2);
      else if (a == "--max-growth-kb")
        maxGrowthKb = parseCount(a, value(), 0);
      else if (a == "--csv")
        csvPath = value();
      else if (a == "--data")
        dataDir = value();
      else if (a == "--help" || a == "-h") {
        usage(std::cout);
        return 0;
      } else
        throw BadArgs{"unknown option '" + a + "'"};
    }
  } catch (const BadArgs &e) {
    std::cerr << "vispmorph-soak: " << e.msg << "\n";
    usage(std::cerr);
    return 2;
  }

  try {
    const auto t0 = std::chrono::steady_clock::now();
    std::vector<long> rss{rssKb()};
    std::vector<unsigned long> doneIt{0}, doneRec{0};
    std::cerr << "vispmorph-soak: building the database of the six objects (calibration)...\n";
    const Objects obj = loadObjects(dataDir);

    vpServoMorph servo;
    servo.setCameraParameters(vpMorphPlanarScene::defaultCamera());
    servo.getPlanner().setSubGoalCount(10);
    servo.setSamplingTime(0.04);
    servo.setGain(0.5);
    servo.setFinalThresholds(0.004, 0.6); // above the 0.2 px vertex noise

    // Reference results for the drift check, before anything else has run.
    const TaskResult task0 = runTask(servo, obj, 0, static_cast<unsigned int>(seed), taskLength);
    std::size_t truth0 = 0;
    const vpMorphContour query0 = makeQuery(obj.db, 0, static_cast<unsigned int>(seed), truth0);
    const std::uint64_t rec0 = recognitionFingerprint(obj.db.recognize(query0));

    unsigned long it = 0, rec = 0, tasks = 0, recCorrect = 0, recAccepted = 0;
    std::map<std::string, unsigned long> outcomes;
    const unsigned long warmRounds = std::max(1UL, rounds / 20);
    long warmRss = 0;
    for (unsigned long round = 1; round <= rounds; ++round) {
      const unsigned long itEnd = servoIterations * round / rounds, recEnd = recognitions * round / rounds;
      while (it < itEnd) {
        const TaskResult r = runTask(servo, obj, static_cast<unsigned int>(tasks), static_cast<unsigned int>(seed),
                                     static_cast<unsigned int>(std::min(taskLength, itEnd - it)));
        it += r.iterations;
        ++tasks;
        ++outcomes[vpServoMorph::statusName(r.status)];
      }
      for (; rec < recEnd; ++rec) {
        std::size_t truth = 0;
        const vpMorphRecognition r = obj.db.recognize(makeQuery(obj.db, rec, static_cast<unsigned int>(seed), truth));
        recCorrect += r.index == truth ? 1 : 0;
        recAccepted += r.accepted ? 1 : 0;
      }
      rss.push_back(rssKb());
      doneIt.push_back(it);
      doneRec.push_back(rec);
      if (round == warmRounds)
        warmRss = rss.back();
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::cerr << "round " << round << "/" << rounds << ": " << it << " servo iterations (" << tasks << " tasks), "
                << rec << " recognitions, RSS " << mb(rss.back()) << ", " << std::fixed << std::setprecision(1) << s
                << " s\n";
    }

    // Drift: the first task and query again, on the same objects, after everything.
    const TaskResult task0b = runTask(servo, obj, 0, static_cast<unsigned int>(seed), taskLength);
    const std::uint64_t rec0b = recognitionFingerprint(obj.db.recognize(query0));
    const bool servoSame = task0b.fingerprint == task0.fingerprint && task0b.iterations == task0.iterations &&
                           task0b.status == task0.status;
    const bool recSame = rec0b == rec0;

    const long startRss = rss.front(), endRss = rss.back();
    long peakRss = 0;
    for (std::size_t k = warmRounds; k < rss.size(); ++k)
      peakRss = std::max(peakRss, rss[k]);
    const long growth = endRss - warmRss, peakGrowth = peakRss - warmRss;
    const bool memoryOk = growth <= static_cast<long>(maxGrowthKb) && peakGrowth <= static_cast<long>(maxGrowthKb);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    if (!csvPath.empty()) {
      std::ofstream f(csvPath);
      if (!f)
        throw vpMorphException(vpMorphException::ioError, "vispmorph-soak: cannot write " + csvPath);
      f << "round,servo_iterations,recognitions,rss_kb\n";
      for (std::size_t k = 0; k < rss.size(); ++k)
        f << k << ',' << doneIt[k] << ',' << doneRec[k] << ',' << rss[k] << '\n';
    }

    std::cout << "vispmorph-soak: seed " << seed << ", " << rounds << " rounds, warm-up " << warmRounds
              << " round(s)\n";
    std::cout << "servo: " << it << " iterations in " << tasks << " tasks (restarted every <= " << taskLength
              << " iterations); last status of each task (moving / sub-goal reached: cut at the task length or at"
                 " a round's end):";
    for (const auto &o : outcomes)
      std::cout << " " << o.first << " " << o.second << ";";
    std::cout << "\nrecognition: " << rec << " queries, " << recCorrect << " correct (" << std::setprecision(4)
              << 100.0 * recCorrect / std::max(1UL, rec) << " %), " << recAccepted << " accepted\n";
    std::cout << "RSS: start " << mb(startRss) << ", after warm-up " << mb(warmRss) << ", peak after warm-up "
              << mb(peakRss) << ", end " << mb(endRss) << "; growth after warm-up " << growth << " KiB (peak "
              << peakGrowth << " KiB; bound " << maxGrowthKb << " KiB): " << (memoryOk ? "OK" : "EXCEEDED")
              << "; high-water mark of the process (VmHWM, calibration included) " << mb(statusKb("VmHWM:")) << "\n";
    std::cout << "drift: servo task 0 " << (servoSame ? "bit-identical" : "DIFFERENT") << " (" << task0.iterations
              << " iterations, " << vpServoMorph::statusName(task0.status) << "), recognition query 0 "
              << (recSame ? "bit-identical" : "DIFFERENT") << "\n";
    std::cout << "wall time " << std::fixed << std::setprecision(1) << wall << " s\n";
    return memoryOk && servoSame && recSame ? 0 : 1;
  } catch (const vpException &e) {
    std::cerr << "vispmorph-soak: " << e.getMessage() << "\n";
    return 1;
  } catch (const std::exception &e) {
    std::cerr << "vispmorph-soak: " << e.what() << "\n";
    return 1;
  }
}
