#include <visp3/morph_bench/vpMorphBench.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <thread>

#include <visp3/core/vpMath.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_bench/vpMorphBenchController.h>
#include <visp3/morph_bench/vpMorphBenchObservability.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>
#include <visp3/morph_sim/vpMorphTagPoseEstimator.h>
#include <visp3/morph_sim/vpMorphThreadCpuClock.h>

#include "vpMorphBenchJoint.h"

namespace
{
const unsigned int kLostFrames = 10;            // successive images without features before giving up
const unsigned int kStillFrames = 10;           // successive iterations with a negligible command before stopping
const double kStillTranslation = 1e-3;          // m/s: with lambda = 2.5/s, an error of 0.4 mm
const double kStillRotation = vpMath::rad(0.1); // rad/s: 0.04 deg
const double kMinDepth = 0.15, kMaxDepth = 1.5; // m: outside, the camera has diverged

void badParameter(const std::string &msg) { throw vpMorphException(vpMorphException::badParameterError, msg); }

//! Speed of a command in its frame: translation (m/s) and rotation (rad/s) norms; joint commands of the free
//! camera are end-effector twists, those of the arms are mapped through eJe.
void commandSpeed(const vpColVector &v, vpRobot::vpControlFrameType frame, const vpMatrix &eJe, double &vt, double &vr)
{
  vpColVector tw = v;
  if (frame == vpRobot::JOINT_STATE)
    tw = eJe * v;
  vt = std::sqrt(tw[0] * tw[0] + tw[1] * tw[1] + tw[2] * tw[2]);
  vr = std::sqrt(tw[3] * tw[3] + tw[4] * tw[4] + tw[5] * tw[5]);
}
} // namespace

//! One database: the templates of one variant seen by one camera, and the objects that could not be taught.
struct vpMorphBench::Taught
{
  std::unique_ptr<vpMorphPartRecognizer> recognizer;              // over the templates (none when none was taught)
  std::map<std::string, std::string> untaught;                    // object -> why
  std::map<std::string, vpMorphBenchObservability> observability; // object -> its taught view's
  //! The templates: the recognizer's database (empty when none was taught).
  const vpMorphDatabase &db() const
  {
    static const vpMorphDatabase none;
    return recognizer ? recognizer->getDatabase() : none;
  }
};

vpMorphBench::vpMorphBench(const vpMorphBenchObjectSet &objects, unsigned int seed, const Settings &settings)
  : m_objects(objects), m_seed(seed), m_settings(settings)
{
  if (!(settings.lambda > 0) || !std::isfinite(settings.lambda))
    badParameter("vpMorphBench: lambda must be finite and > 0");
  if (!(settings.samplingTime > 0) || !std::isfinite(settings.samplingTime))
    badParameter("vpMorphBench: sampling time must be finite and > 0");
  if (settings.maxIterations == 0)
    badParameter("vpMorphBench: the iteration budget must be > 0");
  if (!(settings.successTranslation > 0) || !(settings.successRotationDeg > 0))
    badParameter("vpMorphBench: success thresholds must be > 0");
  if (objects.empty())
    badParameter("vpMorphBench: no object");
  if (!settings.recognitionModel.empty())
    (void)vpMorphShapeDistance::fromName(settings.recognitionModel); // an unknown name: its error, before any work
}

vpMorphBench::~vpMorphBench() = default;

const vpMorphBench::Taught &vpMorphBench::taught(const std::string &variant, const std::string &set) const
{
  vpCameraParameters cam;
  unsigned int width = 0, height = 0;
  vpMorphBenchScenario::cameraOf(set, cam, width, height);
  const std::string key = variant + "|" + std::to_string(width) + "x" + std::to_string(height);
  std::lock_guard<std::mutex> lock(m_mutex);
  std::unique_ptr<Taught> &t = m_taught[key];
  if (t)
    return *t;
  t.reset(new Taught);
  vpMorphDatabase db;
  if (!m_settings.recognitionModel.empty())
    db.setDistance(vpMorphShapeDistance::fromName(m_settings.recognitionModel));
  for (const vpMorphBenchObjectSet::Object &o : m_objects.objects()) {
    // The taught view: rendered at the desired pose, the tag where it fits (out of view when it fits nowhere: that
    // object's scenarios are set-up failures, but it still takes part in the recognition), masked, extracted.
    const std::string image = variant == "rough" ? o.roughImage : o.image;
    const vpHomogeneousMatrix cdMo = vpMorphBenchScenario::desiredPose(m_seed, o);
    try {
      vpMorphPlanarScene scene(image);
      scene.setCamera(cam, width, height);
      if (!vpMorphBenchScenario::stage(scene, cdMo).empty())
        scene.setTagPlacement(10.0, 10.0); // 10 m away
      vpMorphTemplate tpl(o.name, scene.silhouette(cdMo), image, cdMo);
      if (variant.empty() && !o.jointFile.empty())
        tpl.setArticulation(scene.articulation(vpMorphBenchJoint::read(o.jointFile).joint, cdMo));
      tpl.setMetadata("source", "rendered at the desired pose, tag masked");
      t->observability.emplace(o.name,
                               vpMorphBenchObservability(tpl.contour(), cam, cdMo, m_settings.successTranslation,
                                                         vpMath::rad(m_settings.successRotationDeg)));
      db.add(tpl);
    } catch (const vpException &e) {
      t->untaught[o.name] = e.getStringMessage();
    }
  }
  if (!db.empty()) {
    db.calibrate(1);
    t->recognizer.reset(new vpMorphPartRecognizer(db, 1));
  }
  return *t;
}

const vpMorphDatabase &vpMorphBench::database(const std::string &variant, const std::string &set) const
{
  return taught(variant, set).db();
}

const vpMorphBenchObservability *vpMorphBench::observability(const std::string &object, const std::string &variant,
                                                             const std::string &set) const
{
  const Taught &t = taught(variant, set);
  const auto it = t.observability.find(object);
  return it == t.observability.end() ? nullptr : &it->second;
}

void vpMorphBench::prepare(const std::vector<vpMorphBenchScenario> &scenarios) const
{
  for (const vpMorphBenchScenario &sc : scenarios)
    if (sc.setup.empty())
      taught(sc.variant, sc.set);
}

vpMorphRecognition vpMorphBench::recognizeStart(const vpMorphBenchScenario &sc, vpMorphContour *shown,
                                                vpMorphPartRecognizer::Stage *stage) const
{
  if (shown)
    *shown = vpMorphContour();
  if (!sc.setup.empty())
    return vpMorphRecognition();
  const vpMorphPlanarScene scene = sc.scene();
  vpImage<unsigned char> I;
  scene.render(sc.cdMc.inverse() * sc.cdMo, I); // frame 0, as a run's first image
  vpHomogeneousMatrix cMt;
  std::vector<vpImagePoint> corners;
  if (!scene.tagPoseEstimator().estimate(I, cMt, &corners))
    corners.clear(); // nothing to mask
  const std::vector<vpMorphContour> candidates = vpMorphTagPoseEstimator::silhouetteCandidates(I, corners);
  const Taught &t = taught(sc.variant, sc.set);
  if (candidates.empty() || !t.recognizer)
    return vpMorphRecognition();
  std::size_t chosen = 0;
  const vpMorphRecognition r = t.recognizer->recognize(candidates, chosen, stage);
  if (shown)
    *shown = candidates[chosen];
  return r;
}

vpMorphBenchResult vpMorphBench::run(const vpMorphBenchScenario &sc, const std::string &controllerName,
                                     const FrameObserver &observer) const
{
  const vpMorphThreadCpuClock::time_point t0 = vpMorphThreadCpuClock::now();
  vpMorphBenchResult res = runOnce(sc, controllerName, observer);
  res.runCpuS = vpMorphThreadCpuClock::millisecondsSince(t0) / 1000.0;
  return res;
}

vpMorphBenchResult vpMorphBench::runOnce(const vpMorphBenchScenario &sc, const std::string &controllerName,
                                         const FrameObserver &observer) const
{
  std::unique_ptr<vpMorphBenchController> controller = vpMorphBenchController::create(controllerName);
  vpMorphBenchResult res;
  res.scenario = sc;
  res.controller = controllerName;
  res.robot = vpMorphSimRobot::kindName(m_settings.robot);
  res.straightLine = sc.cdMc.getTranslationVector().frobeniusNorm();
  auto setupFailure = [&res](const std::string &why) {
    res.failure = "setup";
    res.setup = why;
    return res;
  };
  if (!sc.setup.empty())
    return setupFailure(sc.setup);
  const Taught &taughtViews = taught(sc.variant, sc.set);
  if (taughtViews.db().find(sc.object) == vpMorphRecognition::npos)
    return setupFailure("template-not-taught");

  vpMorphPlanarScene scene = sc.scene(); // not const: timed faults change it during the run
  const vpCameraParameters camTrue = scene.camera();
  const vpMorphTagPoseEstimator truthTag = scene.tagPoseEstimator();
  res.tagSize = scene.tagSize();

  vpMorphSimRobot robot(m_settings.robot, m_settings.samplingTime);
  // The Afma6's wrist turns the camera by about 100 deg either way from one configuration: the start and the goal
  // straddle its reference. The other robots reach every start from the goal's configuration.
  bool reachable = true;
  if (m_settings.robot == vpMorphSimRobot::AFMA6)
    reachable = robot.setDesiredPoseMidway(sc.cdMo, sc.cdMc);
  else
    robot.setDesiredPose(sc.cdMo);
  if (!reachable || !robot.initialiseCameraRelativeToDesired(sc.cdMc)) {
    res.failure = "unreachable";
    return res;
  }

  vpMorphBenchController::Context ctx;
  ctx.cam = sc.estimatedCamera(camTrue);
  ctx.eMc = robot.eMcTrue() * sc.eMcError;
  ctx.eMcRotationTolerance = sc.eMcRotationTolerance;
  ctx.eMcTranslationTolerance = sc.eMcTranslationTolerance;
  ctx.cdMo = sc.cdMo;
  {
    // The tag controllers' taught view: this scene (its object, so its tag placement) at the desired pose, without
    // the faults, measured by the detector as their current features are.
    vpMorphPlanarScene taught = scene; // a copy: the object image is not read again
    taught.setFaults(vpMorphPlanarScene::Faults());
    vpImage<unsigned char> Id;
    taught.render(sc.cdMo, Id);
    if (!taught.tagPoseEstimator().estimate(Id, ctx.taughtTagPose, &ctx.taughtTagCorners))
      return setupFailure("tag-not-found-in-taught-view");
    // The tag truth's own accuracy, where every run ends.
    vpMorphTagPoseEstimator::poseDifference(sc.cdMo, ctx.taughtTagPose, res.taughtTagTranslation,
                                            res.taughtTagRotation);
  }
  ctx.tagCorners3D = scene.tagCorners3D();
  ctx.tagId = scene.tagId();
  ctx.tagSize = scene.tagSize();
  ctx.oMt = scene.oMt();
  ctx.database = &taughtViews.db();
  ctx.recognizer = taughtViews.recognizer.get();
  ctx.expectedObject = sc.object;
  ctx.lambda = m_settings.lambda;
  ctx.samplingTime = m_settings.samplingTime;
  ctx.jointMin = robot.getJointMin();
  ctx.jointMax = robot.getJointMax();
  if (m_settings.robot != vpMorphSimRobot::FREE_CAMERA)
    ctx.robotModel = {[&robot](const vpColVector &q) { return robot.get_fMe(q); },
                      [&robot](const vpColVector &q) { return robot.get_eJe(q); }};
  for (const vpMorphBenchEvent &e : sc.events)
    if (e.kind == vpMorphBenchEvent::WRONG_TEMPLATE)
      ctx.forcedTemplate = e.wrongTemplate;
  controller->start(ctx);

  const bool tagController = controllerName.find("ibvs") == 0 || controllerName == "pbvs";
  const double rotThr = vpMath::rad(m_settings.successRotationDeg);
  // Scored modulo the template's symmetry (a rigid view of it): its equally good placements, or for a disc the
  // desired pose turned to the nearest; a view whose pose cannot be bounded is tallied apart.
  const vpMorphBenchObservability &obs = taughtViews.observability.at(sc.object);
  const bool rigidView = sc.objectImage == sc.templateImage;
  res.symmetry = obs.symmetryOrder();
  res.unobservable = obs.reason(vpMorphBenchScenario::needsTilt(sc.set));
  std::string failure;
  bool still = false, stopped = false, clippedLast = false; // clippedLast: a joint stopped at its limit last period
  unsigned int lost = 0, stillCount = 0, measuredIterations = 0;
  double sumMeasure = 0, sumControl = 0;
  vpImage<unsigned char> I;
  // The desired pose, and the equally good others of an object with several best placements (vpMorphBenchResult::goal).
  std::vector<vpHomogeneousMatrix> goals{sc.cdMo};
  for (const vpHomogeneousMatrix &W : scene.alternativePlacements())
    goals.push_back(sc.cdMo * W);
  if (rigidView)
    for (const vpHomogeneousMatrix &W : obs.symmetricPlacements())
      goals.push_back(sc.cdMo * W);
  const bool continuous = rigidView && obs.symmetryOrder() == 0;
  // The error to goal g: for a continuous symmetry, to the desired pose turned nearest to cMo.
  auto errorTo = [&](std::size_t g, const vpHomogeneousMatrix &cMo, double &et, double &er) {
    vpMorphTagPoseEstimator::poseDifference(continuous ? obs.nearestDesiredPose(cMo) : goals[g], cMo, et, er);
  };
  std::vector<std::vector<double>> curveT(goals.size()), curveR(goals.size());

  for (unsigned int it = 0; it < m_settings.maxIterations; ++it) {
    // Timed faults of this iteration: the scene's (occluder, object absent), the robot's (pose jump), the
    // controller's input (dropped frame).
    bool dropped = false;
    vpMorphPlanarScene::Faults faults = sc.faults;
    for (const vpMorphBenchEvent &e : sc.events) {
      if (!e.activeAt(it))
        continue;
      switch (e.kind) {
      case vpMorphBenchEvent::DROPPED_FRAMES:
        dropped = true;
        break;
      case vpMorphBenchEvent::NO_OBJECT:
        faults.objectHidden = true;
        break;
      case vpMorphBenchEvent::SUDDEN_OCCLUDER:
        faults.occludedShare = e.occludedShare;
        faults.occluderPosition = e.occluderPosition;
        break;
      case vpMorphBenchEvent::POSE_JUMP:
        robot.displaceCamera(e.cMcp); // out of reach: not moved (the arms)
        break;
      case vpMorphBenchEvent::WRONG_TEMPLATE:
        break; // given to the controller at the start
      }
    }
    if (faults.objectHidden != scene.faults().objectHidden || faults.occludedShare != scene.faults().occludedShare ||
        faults.occluderPosition != scene.faults().occluderPosition)
      scene.setFaults(faults);

    const vpHomogeneousMatrix cMo = robot.get_cMo();
    // Always kept, against each desired pose (the final error picks one): the settling iteration is read from them;
    // dropped at the end unless recordCurves.
    for (std::size_t g = 0; g < goals.size(); ++g) {
      double et, er;
      errorTo(g, cMo, et, er);
      curveT[g].push_back(et);
      curveR[g].push_back(er);
    }
    res.iterations = it + 1;
    const double Z = cMo[2][3];
    if (!(Z > kMinDepth && Z < kMaxDepth)) {
      failure = "diverged";
      break;
    }
    if (tagController ? !scene.tagInView(cMo) : !scene.objectInView(cMo)) {
      failure = "out-of-view";
      break;
    }
    const vpMatrix eJe = robot.get_eJe();
    vpMorphBenchController::Command cmd;
    try {
      if (dropped) {
        cmd = controller->missingFrame();
      } else {
        scene.render(cMo, I, it);
        cmd = controller->step(I, eJe, robot.getJointPositions());
      }
      res.replans += cmd.replanned ? 1 : 0;
      res.rerecognitions += cmd.rerecognized ? 1 : 0;
    } catch (const vpException &e) {
      cmd = vpMorphBenchController::Command();
      cmd.stop = true;
      cmd.reason = "controller-error";
    }
    if (observer && !dropped)
      observer({it, I, *controller, cmd, cMo});
    if (cmd.stop || cmd.converged)
      res.verification = cmd.verification;
    if (cmd.stop) {
      // The clipped joint moved the camera off the command: what the controller stopped on followed from it.
      failure = clippedLast ? "joint-limit" : cmd.reason;
      stopped = true;
      break;
    }
    if (!cmd.measured) {
      ++res.holds;
      if (++lost >= kLostFrames) {
        failure = "feature-lost";
        break;
      }
      continue; // hold: no command this period
    }
    lost = 0;
    ++measuredIterations;
    sumMeasure += cmd.measureMs;
    sumControl += cmd.controlMs;
    res.maxControlMs = std::max(res.maxControlMs, cmd.controlMs);
    if (measuredIterations > 1) { // the first period's recognition and plan excluded
      res.periodMs.push_back(cmd.measureMs + cmd.controlMs);
      res.periodMeasureMs.push_back(cmd.measureMs);
    }
    if (cmd.converged) {
      res.converged = true;
      still = true;
      break;
    }
    double vt, vr;
    commandSpeed(cmd.v, cmd.frame, eJe, vt, vr);
    res.maxSpeed = std::max(res.maxSpeed, vt);
    res.maxRotationSpeed = std::max(res.maxRotationSpeed, vr);
    stillCount = (vt < kStillTranslation && vr < kStillRotation) ? stillCount + 1 : 0;
    if (stillCount >= kStillFrames) {
      still = true;
      break;
    }
    const unsigned int hits = robot.jointLimitHits();
    robot.setVelocity(cmd.frame, cmd.v);
    clippedLast = robot.jointLimitHits() > hits;
  }

  // Final state, truth and tag (the scene without the transient faults).
  vpMorphPlanarScene::Faults last = scene.faults();
  last.objectHidden = false;
  scene.setFaults(last);
  const vpHomogeneousMatrix cMo = robot.get_cMo();
  // The nearest of the equally good desired poses (one unless the object has several best placements or a symmetry).
  errorTo(0, cMo, res.finalTranslation, res.finalRotation);
  for (std::size_t g = 1; g < goals.size(); ++g) {
    double et = 0.0, er = 0.0;
    errorTo(g, cMo, et, er);
    if (std::max(et / m_settings.successTranslation, er / rotThr) <
        std::max(res.finalTranslation / m_settings.successTranslation, res.finalRotation / rotThr)) {
      res.finalTranslation = et;
      res.finalRotation = er;
      res.goal = static_cast<unsigned int>(g);
    }
  }
  const vpHomogeneousMatrix cdMo = continuous ? obs.nearestDesiredPose(cMo) : goals[res.goal];
  res.curveTranslation = curveT[res.goal];
  res.curveRotation = curveR[res.goal];
  if (scene.tagInView(cMo)) {
    scene.render(cMo, I, res.iterations);
    vpHomogeneousMatrix cMo_tag;
    if (truthTag.estimate(I, cMo_tag)) {
      res.tagMeasured = true;
      vpMorphTagPoseEstimator::poseDifference(cdMo, cMo_tag, res.finalTagTranslation, res.finalTagRotation);
    }
  }
  res.pathLength = robot.cameraPathLength();
  res.recognized = controller->recognizedObject();
  res.jointLimitHits = robot.jointLimitHits();
  if (measuredIterations > 0) {
    res.measureMs = sumMeasure / measuredIterations;
    res.controlMs = sumControl / measuredIterations;
  }
  const bool accurate = res.finalTranslation < m_settings.successTranslation && res.finalRotation < rotThr;
  // The settling iteration, from the truth curve (success itself is decided by the final error).
  if (accurate) {
    res.convergedIteration = static_cast<int>(res.curveTranslation.size()) - 1;
    for (int k = static_cast<int>(res.curveTranslation.size()) - 1; k >= 0; --k) {
      if (res.curveTranslation[k] < m_settings.successTranslation && res.curveRotation[k] < rotThr)
        res.convergedIteration = k;
      else
        break;
    }
  }
  if (sc.truth == vpMorphBenchObjectSet::TRUTH_PART && sc.objectImage != sc.templateImage)
    vpMorphTagPoseEstimator::poseDifference(sc.cdMo * sc.overlapPlacement(), cMo, res.finalOverlapTranslation,
                                            res.finalOverlapRotation);
  const bool fatal = failure == "diverged" || failure == "out-of-view" || failure == "feature-lost";
  res.success = accurate && !fatal;
  res.falseConverged = res.converged && !accurate;
  if (res.success)
    res.failure = "none";
  else if (!failure.empty())
    res.failure = (!res.recognitionCorrect() && !fatal && failure != "target-mismatch") ? "recognition" : failure;
  else if (!res.recognitionCorrect())
    res.failure = "recognition";
  else if (robot.jointLimitHits() > 0)
    res.failure = "joint-limit";
  else
    res.failure = (still || stopped) ? "final-error" : "budget";
  if (!m_settings.recordCurves) {
    res.curveTranslation.clear();
    res.curveRotation.clear();
  }
  return res;
}

std::vector<vpMorphBenchResult> vpMorphBench::runAll(const std::vector<vpMorphBenchScenario> &scenarios,
                                                     const std::vector<std::string> &controllers, unsigned int threads,
                                                     const Progress &progress) const
{
  for (const std::string &c : controllers)
    vpMorphBenchController::create(c); // unknown names fail before any work
  const std::size_t total = scenarios.size() * controllers.size();
  std::vector<vpMorphBenchResult> results(total);
  if (threads == 0)
    threads = std::max(1u, std::thread::hardware_concurrency());
  threads = static_cast<unsigned int>(std::min<std::size_t>(threads, std::max<std::size_t>(total, 1)));
  std::atomic<std::size_t> next(0);
  std::size_t done = 0;
  std::mutex mutex;
  std::exception_ptr error;
  auto worker = [&]() {
    for (std::size_t k = next++; k < total; k = next++) {
      vpMorphBenchResult r;
      try {
        r = run(scenarios[k / controllers.size()], controllers[k % controllers.size()]);
      } catch (const vpException &e) {
        // One scenario never stops the others: its runs fail with the bench's own error.
        r = vpMorphBenchResult();
        r.scenario = scenarios[k / controllers.size()];
        r.controller = controllers[k % controllers.size()];
        r.robot = vpMorphSimRobot::kindName(m_settings.robot);
        r.failure = "bench-error";
        r.setup = e.getStringMessage();
      } catch (...) {
        std::lock_guard<std::mutex> lock(mutex);
        if (!error)
          error = std::current_exception();
        next = total; // stop the other workers too
        return;
      }
      std::lock_guard<std::mutex> lock(mutex);
      results[k] = std::move(r);
      ++done;
      if (progress)
        progress(done, total, results[k]);
    }
  };
  std::vector<std::thread> pool;
  for (unsigned int t = 1; t < threads; ++t)
    pool.emplace_back(worker);
  worker();
  for (std::thread &t : pool)
    t.join();
  if (error)
    std::rethrow_exception(error);
  return results;
}
