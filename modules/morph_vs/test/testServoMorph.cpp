// Tests of vpServoMorph on a free-flying camera (vpSimulatorCamera, deterministic) looking at a planar object:
// convergence through the morph sub-goals from large in-plane rotations, straight paths, online calibration,
// the stock-vpServo law, safety, and the 4-point IBVS failure that motivates the feature.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>

#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_vs/vpServoMorph.h>
#include <visp3/robot/vpSimulatorCamera.h>
#include <visp3/visual_features/vpFeaturePoint.h>
#include <visp3/vs/vpServo.h>

#include "testMorphVsRecordingDisplay.h"
#include "testMorphVsScene.h"

using namespace vpMorphVsTest;

namespace
{
struct Setup
{
  vpHomogeneousMatrix eMcTrue, eMcEstimate;
  vpCameraParameters camEstimate = camera();
  std::size_t subGoals = 10;
  vpServoMorph::ControlLaw law = vpServoMorph::HOMOGENEOUS_TRANSFORMS;
  vpMorphSubGoalPlanner::RigidPath rigidPath = vpMorphSubGoalPlanner::CAMERA_STRAIGHT_LINE;
  bool online = true;
  int maxIterations = 400;
  double noisePx = 0;                    // Gaussian noise on the vertices (seeded)
  double finalRotation = 0, finalPx = 0; // setFinalThresholds() when finalPx > 0
  double finalScale = 0;                 // setFinalScaleThreshold()
  // Limits of a roll joint about the optical axis (rad, from the start), given to setJointState() each period with
  // the end effector's twist as the other "joints" (no limits); none by default.
  bool joints = false;
  double rollMin = 0, rollMax = 0;
};

struct Result
{
  bool converged = false;
  int iterations = 0;
  double tErr = 0, rDeg = 0;     // final pose error against the simulator's truth
  double path = 0, straight = 0; // camera path length and straight-line distance (m)
  double maxDepth = 0;           // largest object depth seen (m)
  double eMcT0 = 0, eMcR0 = 0;   // hand-eye estimate error at the start (m, deg)
  double eMcT = 0, eMcR = 0;     // and at the end
  double scale = 1;              // final projection scale estimate
  std::size_t lastSubGoal = 0;
  unsigned int searches = 0; // correspondence searches (full + tracked) of the law in use
  vpServoMorph::Status status = vpServoMorph::NOT_STARTED;
  double rollDeg = 0, rollMinDeg = 0, rollMaxDeg = 0; // camera turn about its optical axis: final, least, most
  bool longWay = false;                               // the first sequence turned the long way round
  double plannedRollDeg = 0;                          // the roll joint's end predicted by the first plan
};

// Error of a hand-eye estimate: the transform truth^-1 * estimate (translation norm, rotation angle).
void handEyeError(const vpHomogeneousMatrix &est, const vpHomogeneousMatrix &truth, double &t, double &rDeg)
{
  const vpHomogeneousMatrix d = truth.inverse() * est;
  t = d.getTranslationVector().frobeniusNorm();
  rDeg = vpMath::deg(vpThetaUVector(d.getRotationMatrix()).getTheta());
}

Result run(const vpHomogeneousMatrix &cMo0, const vpHomogeneousMatrix &cdMo, const Setup &st)
{
  vpServoMorph servo;
  servo.setCameraParameters(st.camEstimate);
  servo.set_eMc(st.eMcEstimate);
  servo.setOnlineCalibration(st.online);
  servo.getPlanner().setSubGoalCount(st.subGoals);
  servo.setControlLaw(st.law);
  servo.getPlanner().setRigidPath(st.rigidPath);
  servo.setSamplingTime(0.1);
  servo.setGain(0.5);
  servo.setTarget(projectPixels(cdMo), depth(cdMo));
  if (st.noisePx > 0)
    servo.setFinalThresholds(0.004, 0.6); // a few times the noise of the fit
  if (st.finalPx > 0)
    servo.setFinalThresholds(st.finalRotation, st.finalPx);
  servo.setFinalScaleThreshold(st.finalScale);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, st.noisePx > 0 ? st.noisePx : 1.0);

  vpSimulatorCamera robot;
  robot.setSamplingTime(0.1);
  robot.setMaxTranslationVelocity(10.0);
  robot.setMaxRotationVelocity(100.0);
  const vpHomogeneousMatrix wMo;
  robot.setPosition(wMo * cMo0.inverse());
  const vpVelocityTwistMatrix cVe(st.eMcTrue.inverse());

  Result r;
  handEyeError(st.eMcEstimate, st.eMcTrue, r.eMcT0, r.eMcR0);
  const vpHomogeneousMatrix wMc0 = robot.getPosition(), wMcd = wMo * cdMo.inverse();
  r.straight = (wMcd.getTranslationVector() - wMc0.getTranslationVector()).frobeniusNorm();
  vpTranslationVector prev = wMc0.getTranslationVector();
  double roll = 0.0; // rad, summed over the periods' turns about the optical axis
  for (r.iterations = 0; r.iterations < st.maxIterations; ++r.iterations) {
    if (st.joints) {
      // Joints: the end effector's twist (eJe = I); the sixth turns about z_e, the optical axis here.
      vpMatrix eJe;
      eJe.eye(6);
      vpColVector q(6, 0.0), qMin(6, -std::numeric_limits<double>::infinity()),
          qMax(6, std::numeric_limits<double>::infinity());
      q[5] = roll;
      qMin[5] = std::min(roll, st.rollMin);
      qMax[5] = std::max(roll, st.rollMax);
      servo.getPlanner().setJointState(eJe, q, qMin, qMax);
    }
    const vpHomogeneousMatrix cMo = robot.getPosition().inverse() * wMo;
    r.maxDepth = std::max(r.maxDepth, depth(cMo));
    vpMorphContour c = projectPixels(cMo);
    if (st.noisePx > 0) {
      std::vector<double> x = c.xs(), y = c.ys();
      for (std::size_t k = 0; k < x.size(); ++k) {
        x[k] += noise(rng);
        y[k] += noise(rng);
      }
      c = vpMorphContour(x, y);
    }
    const vpColVector ve = servo.computeControlLaw(c);
    if (r.iterations == 0) {
      r.longWay = servo.getPlanner().isLongWay();
      r.plannedRollDeg =
          servo.getPlanner().getJointEnd().size() == 6 ? vpMath::deg(servo.getPlanner().getJointEnd()[5]) : 0.0;
    }
    if (servo.getStatus() == vpServoMorph::CONVERGED) {
      r.converged = true;
      break;
    }
    if (servo.getStatus() != vpServoMorph::MOVING && servo.getStatus() != vpServoMorph::SUBGOAL_REACHED)
      break;
    const vpHomogeneousMatrix wMcBefore = robot.getPosition();
    robot.setVelocity(vpRobot::CAMERA_FRAME, cVe * ve);
    roll += vpThetaUVector((wMcBefore.inverse() * robot.getPosition()).getRotationMatrix())[2];
    r.rollMinDeg = std::min(r.rollMinDeg, vpMath::deg(roll));
    r.rollMaxDeg = std::max(r.rollMaxDeg, vpMath::deg(roll));
    const vpTranslationVector t = robot.getPosition().getTranslationVector();
    r.path += (t - prev).frobeniusNorm();
    prev = t;
  }
  r.status = servo.getStatus();
  r.rollDeg = vpMath::deg(roll);
  r.lastSubGoal = servo.getSubGoalIndex();
  r.searches = servo.getAligner().getTracker().fullMatchCount() + servo.getAligner().getTracker().trackedMatchCount();
  poseError(robot.getPosition().inverse() * wMo, cdMo, r.tErr, r.rDeg);
  handEyeError(servo.get_eMc(), st.eMcTrue, r.eMcT, r.eMcR);
  r.scale = servo.getHandEyeEstimator().translationScale();
  return r;
}

const vpHomogeneousMatrix cdMo = planarPose(20, 0.01, 0.0);
const vpHomogeneousMatrix eMcTrue(0.01, 0.05, 0.12, 0, 0, vpMath::rad(90));
} // namespace

TEST_CASE("vpServoMorph converges from in-plane rotations 0, 90, 170, 180 deg with translations up to 80 mm", "[servo]")
{
  const double starts[][3] = {
      {0, 0.08, 0.0}, {90, 0.05, -0.06}, {170, -0.06, 0.05}, {180, 0.0, 0.08}, {-170, 0.04, 0.04}};
  Setup st;
  st.eMcTrue = st.eMcEstimate = eMcTrue;
  for (const auto &s : starts) {
    const Result r = run(planarPose(20 + s[0], s[1], s[2]), cdMo, st);
    std::printf("[servo] start %6.1f deg (%4.0f, %4.0f) mm: %s after %d iterations, error %.4f mm %.4f deg, path "
                "%.1f mm (straight %.1f mm), max depth %.3f m\n",
                s[0], s[1] * 1000, s[2] * 1000, vpServoMorph::statusName(r.status), r.iterations, r.tErr * 1000, r.rDeg,
                r.path * 1000, r.straight * 1000, r.maxDepth);
    INFO("start " << s[0] << " deg: " << vpServoMorph::statusName(r.status) << " after " << r.iterations);
    CHECK(r.converged);
    CHECK(r.tErr < 1e-3);
    CHECK(r.rDeg < 0.5);
    CHECK(r.lastSubGoal == 9);
    CHECK(r.maxDepth < 0.5 + 1e-3); // never retreats
  }
}

TEST_CASE("vpServoMorph camera path is straight on a pure translation", "[servo]")
{
  Setup st;
  st.eMcTrue = st.eMcEstimate = eMcTrue;
  const Result r = run(planarPose(20, 0.07, -0.04), cdMo, st);
  const double ratio = r.path / r.straight;
  std::printf("[servo] pure translation: path %.2f mm, straight line %.2f mm, ratio %.4f, %d iterations\n",
              r.path * 1000, r.straight * 1000, ratio, r.iterations);
  CHECK(r.converged);
  CHECK(ratio <= 1.1);
}

TEST_CASE("vpServoMorph rigid sub-goals on the straight camera path: short paths at 150 and 180 deg, the paper's "
          "arc about the object for comparison",
          "[servo]")
{
  Setup st;
  st.eMcTrue = st.eMcEstimate = eMcTrue;
  const double starts[][3] = {{150, 0.05, -0.03}, {180, -0.04, 0.02}, {-100, 0.06, 0.04}};
  for (const auto &s : starts) {
    st.rigidPath = vpMorphSubGoalPlanner::CAMERA_STRAIGHT_LINE;
    const Result straight = run(planarPose(20 + s[0], s[1], s[2]), cdMo, st);
    st.rigidPath = vpMorphSubGoalPlanner::ABOUT_OBJECT_CENTROID;
    const Result arc = run(planarPose(20 + s[0], s[1], s[2]), cdMo, st);
    std::printf("[servo] start %6.1f deg: path ratio %.3f on the straight camera path, %.3f about the object\n", s[0],
                straight.path / straight.straight, arc.path / arc.straight);
    INFO("start " << s[0] << " deg");
    CHECK(straight.converged);
    CHECK(arc.converged);
    CHECK(straight.tErr < 1e-3);
    CHECK(straight.rDeg < 0.5);
    CHECK(straight.path / straight.straight <= 1.1);
    CHECK(arc.path / arc.straight > 1.2); // the rotation about the object's centroid bends the path
  }
}

TEST_CASE("vpServoMorph plans a half turn the way its joints allow", "[servo][joints]")
{
  Setup st;
  st.eMcTrue = st.eMcEstimate = eMcTrue;
  for (const vpMorphSubGoalPlanner::RigidPath path :
       {vpMorphSubGoalPlanner::CAMERA_STRAIGHT_LINE, vpMorphSubGoalPlanner::ABOUT_OBJECT_CENTROID})
    for (const double startDeg : {150.0, 179.0, -179.0}) {
      st.rigidPath = path;
      st.joints = false;
      const vpHomogeneousMatrix cMo0 = planarPose(20 + startDeg, 0.03, -0.02);
      const Result free = run(cMo0, cdMo, st);
      // A roll joint whose limit lies 5 deg beyond where the short way ends, on its side (range 585 deg: the margin
      // is 17.6 deg), and far on the other.
      const double shortDeg = free.rollDeg, side = shortDeg > 0 ? 1.0 : -1.0;
      st.joints = true;
      st.rollMin = vpMath::rad(side > 0 ? -400.0 : shortDeg - 5.0);
      st.rollMax = vpMath::rad(side > 0 ? shortDeg + 5.0 : 400.0);
      const Result bounded = run(cMo0, cdMo, st);
      std::printf("[servo] start %6.1f deg (%s): the short way turns %.1f deg; with a limit 5 deg beyond, %s %.1f deg "
                  "(planned %.1f, from %.1f to %.1f), %s after %d iterations, %.3f mm %.3f deg\n",
                  startDeg, path == vpMorphSubGoalPlanner::CAMERA_STRAIGHT_LINE ? "straight line" : "about the object",
                  shortDeg, bounded.longWay ? "the long way" : "the short way", bounded.rollDeg, bounded.plannedRollDeg,
                  bounded.rollMinDeg, bounded.rollMaxDeg, vpServoMorph::statusName(bounded.status), bounded.iterations,
                  bounded.tErr * 1000, bounded.rDeg);
      INFO("start " << startDeg << " deg");
      CHECK(!free.longWay);
      CHECK(std::fabs(shortDeg) < 181.0);
      CHECK(bounded.longWay);
      CHECK(bounded.converged);
      CHECK(bounded.tErr < 1e-3);
      CHECK(bounded.rDeg < 0.5);
      // The other way round, by the rest of the turn, as planned, never towards the limit.
      const double longDeg = shortDeg - side * 360.0;
      CHECK(std::fabs(bounded.rollDeg - longDeg) < 1.0);
      CHECK(std::fabs(bounded.plannedRollDeg - longDeg) < 2.0);
      CHECK(side * (side > 0 ? bounded.rollMaxDeg : bounded.rollMinDeg) < 1.0);
    }
  // Limits that the short way stays clear of change nothing (+-200 deg: margin 12 deg, the turn ends 50 deg short).
  st.rigidPath = vpMorphSubGoalPlanner::CAMERA_STRAIGHT_LINE;
  st.rollMin = vpMath::rad(-200.0);
  st.rollMax = vpMath::rad(200.0);
  const Result clear = run(planarPose(20 + 150.0, 0.03, -0.02), cdMo, st);
  CHECK(!clear.longWay);
  CHECK(std::fabs(clear.plannedRollDeg - clear.rollDeg) < 2.0);

  vpServoMorph servo;
  vpMatrix eJe;
  eJe.eye(6);
  const vpColVector q(6, 0.0), lo(6, -1.0), hi(6, 1.0);
  vpColVector bad = q;
  bad[5] = 1.5;
  CHECK_THROWS_AS(servo.getPlanner().setJointState(eJe, bad, lo, hi), vpMorphException);
  bad[5] = std::numeric_limits<double>::quiet_NaN();
  CHECK_THROWS_AS(servo.getPlanner().setJointState(eJe, bad, lo, hi), vpMorphException);
  CHECK_THROWS_AS(servo.getPlanner().setJointState(eJe, vpColVector(5, 0.0), lo, hi), vpMorphException);
  CHECK_THROWS_AS(servo.getPlanner().setJointState(vpMatrix(5, 6), q, lo, hi), vpMorphException);
  servo.getPlanner().setJointState(eJe, q, lo, hi);
  CHECK(servo.getPlanner().getJointEnd().size() == 0); // nothing planned yet
}

TEST_CASE("vpServoMorph online calibration: wrong eMc (15 deg, 30 mm) and intrinsics (20 %) still converge",
          "[servo][calibration]")
{
  Setup st;
  st.eMcTrue = eMcTrue;
  // The estimate is off by 15 deg about the optical axis and 30 mm in the image plane.
  const vpHomogeneousMatrix Yerr(0.024, -0.018, 0, 0, 0, vpMath::rad(15));
  st.eMcEstimate = eMcTrue * Yerr.inverse();
  st.camEstimate = vpCameraParameters(960, 960, 320, 240); // focal length 20 % too long
  const Result r = run(planarPose(20 + 170, 0.06, -0.03), cdMo, st);
  std::printf("[calibration] online: %s after %d iterations, pose error %.4f mm %.4f deg; eMc error %.1f mm %.2f deg "
              "-> %.2f mm %.3f deg; projection scale %.4f (true 1.2)\n",
              vpServoMorph::statusName(r.status), r.iterations, r.tErr * 1000, r.rDeg, r.eMcT0 * 1000, r.eMcR0,
              r.eMcT * 1000, r.eMcR, r.scale);
  CHECK(r.converged);
  CHECK(r.tErr < 1e-3);
  CHECK(r.rDeg < 0.5);
  CHECK(r.eMcR < 0.25 * r.eMcR0);
  CHECK(r.eMcT < 0.25 * r.eMcT0);
  // True image-plane translation = k * translation seen with the too long focal length: k = 960 / 800.
  CHECK(r.scale == Approx(960.0 / 800.0).epsilon(0.02));

  st.online = false; // the same start without the estimator, for the record
  const Result off = run(planarPose(20 + 170, 0.06, -0.03), cdMo, st);
  std::printf("[calibration] offline (fixed wrong estimate): %s after %d iterations, pose error %.4f mm %.4f deg, "
              "path %.1f mm vs %.1f mm online\n",
              vpServoMorph::statusName(off.status), off.iterations, off.tErr * 1000, off.rDeg, off.path * 1000,
              r.path * 1000);

  // The other side: focal length 20 % too short, the hand-eye error the other way round, from -175 deg.
  st.online = true;
  st.eMcEstimate = eMcTrue * Yerr;
  st.camEstimate = vpCameraParameters(640, 640, 320, 240);
  const Result r2 = run(planarPose(20 - 175, -0.05, -0.06), cdMo, st);
  std::printf("[calibration] online, focal -20 %%: %s after %d iterations, pose error %.4f mm %.4f deg; eMc error "
              "%.1f mm %.2f deg -> %.2f mm %.3f deg; projection scale %.4f (true 0.8)\n",
              vpServoMorph::statusName(r2.status), r2.iterations, r2.tErr * 1000, r2.rDeg, r2.eMcT0 * 1000, r2.eMcR0,
              r2.eMcT * 1000, r2.eMcR, r2.scale);
  CHECK(r2.converged);
  CHECK(r2.tErr < 1e-3);
  CHECK(r2.rDeg < 0.5);
  CHECK(r2.eMcR < 0.25 * r2.eMcR0);
  CHECK(r2.eMcT < 0.25 * r2.eMcT0);
  CHECK(r2.scale == Approx(640.0 / 800.0).epsilon(0.02));
}

TEST_CASE("vpServoMorph online calibration: principal point and anisotropic focal errors, the planar model's limits",
          "[servo][calibration]")
{
  // The estimator models the intrinsics error as one scale k. The task still converges when the principal point
  // or only one focal length is off by 20 %, but the eMc estimate absorbs what k cannot express.
  Setup st;
  st.eMcTrue = eMcTrue;
  st.eMcEstimate = eMcTrue * vpHomogeneousMatrix(0.024, -0.018, 0, 0, 0, vpMath::rad(15)).inverse();
  const double cams[][4] = {{960, 960, 384, 288}, {960, 800, 320, 240}};
  for (const auto &c : cams) {
    st.camEstimate = vpCameraParameters(c[0], c[1], c[2], c[3]);
    const Result r = run(planarPose(20 + 170, 0.06, -0.03), cdMo, st);
    std::printf("[calibration] px %g py %g u0 %g v0 %g (true 800 800 320 240): %s after %d iterations, pose error "
                "%.4f mm %.4f deg; eMc error %.1f mm %.2f deg -> %.2f mm %.3f deg; projection scale %.4f\n",
                c[0], c[1], c[2], c[3], vpServoMorph::statusName(r.status), r.iterations, r.tErr * 1000, r.rDeg,
                r.eMcT0 * 1000, r.eMcR0, r.eMcT * 1000, r.eMcR, r.scale);
    CHECK(r.converged);
    CHECK(r.tErr < 1e-3);
    CHECK(r.rDeg < 0.5);
    CHECK(r.eMcR < 0.5 * r.eMcR0); // the rotation about the optical axis is still corrected
  }
}

TEST_CASE("vpServoMorph: Eq. 5-11 law and stock vpServo over vpFeatureMorph compared", "[servo]")
{
  Setup st;
  st.eMcTrue = st.eMcEstimate = eMcTrue;
  const vpHomogeneousMatrix cMo0 = planarPose(20 + 170, -0.05, 0.05);
  const Result h = run(cMo0, cdMo, st);
  st.law = vpServoMorph::STOCK_VPSERVO;
  const Result s = run(cMo0, cdMo, st);
  std::printf("[compare] Eq. 5-11: %d iterations, path %.1f mm; stock vpServo: %d iterations, path %.1f mm "
              "(straight %.1f mm); correspondence searches %u and %u\n",
              h.iterations, h.path * 1000, s.iterations, s.path * 1000, h.straight * 1000, h.searches, s.searches);
  CHECK(h.converged);
  CHECK(s.converged);
  // One correspondence, at the plan: every fit after it starts from the last one.
  CHECK(h.searches == 1);
  CHECK(s.searches == 1);
  CHECK(s.tErr < 1e-3);
  CHECK(s.rDeg < 0.5);
}

TEST_CASE("vpServoMorph state: history, sub-goals, template target", "[servo]")
{
  vpServoMorph servo;
  vpMorphTemplate t("bracket", projectPixels(cdMo));
  CHECK_THROWS_AS(servo.setTarget(t), vpMorphException); // no desired pose in the template
  t.setCdMo(cdMo);
  servo.setTarget(t);
  servo.getPlanner().setSubGoalCount(6);
  vpSimulatorCamera robot;
  robot.setSamplingTime(0.1);
  robot.setMaxTranslationVelocity(10.0);
  robot.setMaxRotationVelocity(100.0);
  robot.setPosition(planarPose(20 + 150, 0.04, 0.02).inverse());
  for (int i = 0; i < 200 && servo.getStatus() != vpServoMorph::CONVERGED; ++i) {
    const vpColVector ve = servo.computeControlLaw(projectPixels(robot.getPosition().inverse()));
    robot.setVelocity(vpRobot::CAMERA_FRAME, vpVelocityTwistMatrix(servo.get_eMc().inverse()) * ve);
  }
  REQUIRE(servo.getStatus() == vpServoMorph::CONVERGED);
  CHECK(servo.getGuard().getVerification() == vpMorphServoGuard::VERIFIED);
  vpImage<vpRGBa> I(480, 640);
  CHECK_NOTHROW(servo.display(I)); // headless: no display attached, nothing drawn
  {
    // Converged: the contour (9 edges, red), the target (9 edges, green) and their correspondence (a cyan line per
    // pair of vertices); the sub-goal is the target.
    RecordingDisplay rec;
    rec.attach(I);
    servo.display(I);
    RecordingDisplay::detach(I);
    CHECK(rec.count(vpColor::red) == 9);
    CHECK(rec.count(vpColor::green) == 9);
    CHECK(rec.count(vpColor::cyan) == servo.alignmentLines().size());
    CHECK(rec.lines.size() == 18 + rec.count(vpColor::cyan));
  }
  CHECK(servo.getSubGoals().size() == 6);
  CHECK(servo.getSubGoalIndex() == 5);
  const auto &h = servo.getHistory();
  REQUIRE(!h.empty());
  CHECK(h.front().status == vpServoMorph::MOVING);
  CHECK(h.back().status == vpServoMorph::CONVERGED);
  CHECK(h.back().ve.frobeniusNorm() == 0);
  std::size_t reached = 0;
  for (std::size_t k = 0; k < h.size(); ++k) {
    CHECK(h[k].iteration == k + 1);
    if (k > 0)
      CHECK(h[k].subGoal >= h[k - 1].subGoal); // sub-goals are never revisited
    reached += h[k].status == vpServoMorph::SUBGOAL_REACHED;
    CHECK(h[k].model == vpMorphViewAlignment::RIGID); // the view seen again: every period explained whole
  }
  CHECK(reached >= 1);
  CHECK(servo.getAligner().getTracker().fullMatchCount() == 1); // one correspondence, at the plan: the rest is warm
  servo.restart();
  CHECK(servo.getStatus() == vpServoMorph::NOT_STARTED);
  CHECK(servo.getHistory().empty());
  CHECK_THROWS_AS(servo.setGain(0), vpMorphException);
  CHECK_THROWS_AS(servo.setGain(1.5), vpMorphException);
  CHECK_THROWS_AS(servo.setSamplingTime(-1), vpMorphException);
  CHECK_THROWS_AS(servo.setTarget(projectPixels(cdMo), 0), vpMorphException);
  CHECK_THROWS_AS(servo.setTarget(projectNormalized(cdMo), 0.5), vpMorphException);
  CHECK_THROWS_AS(servo.computeControlLaw(projectNormalized(cdMo)), vpMorphException);
}

TEST_CASE("vpServoMorph sub-goal switching thresholds are configurable", "[servo]")
{
  const vpMorphContour start = projectPixels(planarPose(20 + 170, 0.06, -0.03));
  vpServoMorph servo;
  servo.setTarget(projectPixels(cdMo), depth(cdMo));
  // Defaults (0.10 rad, 5 px): the first rigid frame is about 0.6 rad away, so the servo stays on it.
  CHECK(servo.computeControlLaw(start).frobeniusNorm() > 0);
  CHECK(servo.getStatus() == vpServoMorph::MOVING);
  CHECK(servo.getSubGoalIndex() == 0);
  CHECK(servo.getRotationResidual() > 0.10);
  {
    // Moving: the contour, the current sub-goal and the target, each a 9-edge polygon in its colour.
    vpImage<unsigned char> I(480, 640, 0);
    RecordingDisplay rec;
    rec.attach(I);
    servo.display(I, vpColor::blue, vpColor::orange, vpColor::green);
    RecordingDisplay::detach(I);
    CHECK(rec.count(vpColor::blue) == 9);
    CHECK(rec.count(vpColor::orange) == 9);
    CHECK(rec.count(vpColor::green) == 9);
    // The drawn contour is the one given, in pixels.
    const auto first = std::find_if(rec.lines.begin(), rec.lines.end(),
                                    [](const RecordingDisplay::Line &l) { return l.color == vpColor::blue; });
    REQUIRE(first != rec.lines.end());
    CHECK(first->a.get_u() == Approx(start.x(0)));
    CHECK(first->a.get_v() == Approx(start.y(0)));
  }
  // Thresholds above any residual: every intermediate sub-goal counts as reached at once, only the goal is left.
  servo.setSubGoalThresholds(4.0, 1000.0);
  servo.restart();
  servo.computeControlLaw(start);
  CHECK(servo.getStatus() == vpServoMorph::SUBGOAL_REACHED);
  CHECK(servo.getSubGoalIndex() == 9);
  CHECK_THROWS_AS(servo.setSubGoalThresholds(0, 5), vpMorphException);
  CHECK_THROWS_AS(servo.setFinalThresholds(0.001, -1), vpMorphException);
  CHECK_THROWS_AS(servo.setFinalScaleThreshold(-1e-3), vpMorphException);
  CHECK_THROWS_AS(servo.setFinalScaleThreshold(1.0), vpMorphException);
  CHECK_THROWS_AS(servo.setFinalScaleThreshold(std::nan("")), vpMorphException);
}

TEST_CASE("vpServoMorph's final scale threshold holds CONVERGED until the depth is reached", "[servo]")
{
  // Final thresholds of a fraction of a pixel count a scale error at the object's RMS radius: on this object,
  // 0.5 px there is about half a percent of the depth. The relative scale threshold keeps the loop going.
  Setup loose;
  loose.finalRotation = 0.002;
  loose.finalPx = 0.5;
  Setup tight = loose;
  tight.finalScale = 1e-4;
  const vpHomogeneousMatrix cMo0 = vpHomogeneousMatrix(0, 0, 0.08, 0, 0, 0) * planarPose(40, -0.02, 0.03);
  const Result a = run(cMo0, cdMo, loose), b = run(cMo0, cdMo, tight);
  std::printf("[servo] final scale threshold: none %.3f mm after %d iterations, 1e-4 %.3f mm after %d\n", 1000 * a.tErr,
              a.iterations, 1000 * b.tErr, b.iterations);
  REQUIRE(a.converged);
  REQUIRE(b.converged);
  CHECK(b.iterations > a.iterations);
  CHECK(b.tErr < 0.5 * a.tErr);
  CHECK(b.tErr < 2e-4 * depth(cdMo));
}

TEST_CASE("vpServoMorph with image noise (0.3 px) and calibration errors", "[servo][noise]")
{
  Setup st;
  st.eMcTrue = eMcTrue;
  st.eMcEstimate = eMcTrue * vpHomogeneousMatrix(0.024, -0.018, 0, 0, 0, vpMath::rad(15)).inverse();
  st.camEstimate = vpCameraParameters(960, 960, 320, 240);
  st.noisePx = 0.3;
  const Result r = run(planarPose(20 + 175, -0.05, 0.06), cdMo, st);
  std::printf("[noise] 0.3 px: %s after %d iterations, pose error %.3f mm %.3f deg; eMc error %.1f mm %.2f deg -> "
              "%.2f mm %.3f deg\n",
              vpServoMorph::statusName(r.status), r.iterations, r.tErr * 1000, r.rDeg, r.eMcT0 * 1000, r.eMcR0,
              r.eMcT * 1000, r.eMcR);
  CHECK(r.converged);
  CHECK(r.tErr < 1e-3);
  CHECK(r.rDeg < 0.5);
  CHECK(r.eMcR < 0.5 * r.eMcR0);
  CHECK(r.eMcT < 0.5 * r.eMcT0);
}

TEST_CASE("vpServoMorph goal only (0 sub-goals)", "[servo]")
{
  Setup st;
  st.eMcTrue = st.eMcEstimate = eMcTrue;
  st.subGoals = 0;
  const Result r = run(planarPose(20 + 120, 0.03, 0.02), cdMo, st);
  INFO(vpServoMorph::statusName(r.status)
       << " after " << r.iterations << " iterations, " << r.tErr * 1000 << " mm " << r.rDeg << " deg");
  CHECK(r.converged);
  CHECK(r.lastSubGoal == 0);
}

TEST_CASE("vpServoMorph safety: lost target, degenerate contour, a view its goal does not explain", "[servo][safety]")
{
  vpServoMorph servo;
  CHECK_THROWS_AS(servo.computeControlLaw(projectPixels(planarPose(0, 0, 0))), vpMorphException); // no target
  servo.setTarget(projectPixels(cdMo), depth(cdMo));
  const vpMorphContour c = projectPixels(planarPose(100, 0.02, 0.01));
  vpColVector v = servo.computeControlLaw(c);
  CHECK(servo.getStatus() == vpServoMorph::MOVING);
  CHECK(v.frobeniusNorm() > 0);

  v = servo.computeControlLaw(vpMorphContour()); // lost
  CHECK(servo.getStatus() == vpServoMorph::TARGET_LOST);
  CHECK(v.frobeniusNorm() == 0);

  const vpMorphContour tiny({320, 322, 322, 320}, {240, 240, 242, 242}); // 4 px^2
  v = servo.computeControlLaw(tiny);
  CHECK(servo.getStatus() == vpServoMorph::DEGENERATE_CONTOUR);
  CHECK(v.frobeniusNorm() == 0);

  // Another object suddenly (a long thin bar): no part of it lies on the goal (a hold), then the object again.
  v = servo.computeControlLaw(c);
  CHECK(servo.getStatus() == vpServoMorph::MOVING);
  const vpMorphContour bar({200, 440, 440, 200}, {230, 230, 250, 250});
  v = servo.computeControlLaw(bar);
  CHECK(servo.getStatus() == vpServoMorph::UNEXPLAINED_VIEW);
  CHECK(v.frobeniusNorm() == 0);
  v = servo.computeControlLaw(c); // back to the object: moving again
  CHECK(servo.getStatus() == vpServoMorph::MOVING);
  for (const auto &it : servo.getHistory())
    for (unsigned int i = 0; i < it.ve.size(); ++i)
      CHECK(std::isfinite(it.ve[i]));
}

TEST_CASE("4-point IBVS (current L) from the 180 deg start fails: why the morph feature exists", "[servo][ibvs]")
{
  // The four outer corners of the same object, classical IBVS with the current interaction matrix.
  const std::size_t idx[4] = {0, 1, 5, 8};
  const vpHomogeneousMatrix cMo0 = planarPose(20 + 180, 0.0, 0.08);
  const std::vector<vpColVector> P = objectPoints();
  vpFeaturePoint s[4], sd[4];
  vpServo task;
  task.setServo(vpServo::EYEINHAND_CAMERA);
  task.setInteractionMatrixType(vpServo::CURRENT);
  task.setLambda(5.0); // lambda * dt = 0.5: the same per-step fraction as vpServoMorph (gain 0.5, dt 0.1)
  for (int i = 0; i < 4; ++i) {
    const vpColVector X = cdMo * P[idx[i]];
    sd[i].buildFrom(X[0] / X[2], X[1] / X[2], X[2]);
    task.addFeature(s[i], sd[i]);
  }
  vpSimulatorCamera robot;
  robot.setSamplingTime(0.1);
  robot.setMaxTranslationVelocity(10.0);
  robot.setMaxRotationVelocity(100.0);
  const vpHomogeneousMatrix wMo;
  robot.setPosition(wMo * cMo0.inverse());
  double maxDepth = 0, err = 1;
  int it = 0;
  bool converged = false;
  // The simulator reports every saturated velocity on std::cout, and the retreating IBVS saturates all the time.
  std::ostringstream sink;
  std::streambuf *coutBuf = std::cout.rdbuf(sink.rdbuf());
  for (; it < 400; ++it) {
    const vpHomogeneousMatrix cMo = robot.getPosition().inverse() * wMo;
    maxDepth = std::max(maxDepth, depth(cMo));
    for (int i = 0; i < 4; ++i) {
      const vpColVector X = cMo * P[idx[i]];
      s[i].buildFrom(X[0] / X[2], X[1] / X[2], X[2]);
    }
    const vpColVector v = task.computeControlLaw();
    err = task.getError().frobeniusNorm();
    if (err < 1e-4) {
      converged = true;
      break;
    }
    robot.setVelocity(vpRobot::CAMERA_FRAME, v);
  }
  std::cout.rdbuf(coutBuf);
  double tErr, rDeg;
  poseError(robot.getPosition().inverse() * wMo, cdMo, tErr, rDeg);
  std::printf("[ibvs] 4 points, current L, 180 deg start: %s after %d iterations, max depth %.3f m (desired 0.5), "
              "final pose error %.1f mm %.2f deg\n",
              converged ? "converged" : "not converged", it, maxDepth, tErr * 1000, rDeg);
  task.kill();
  // The failure: the camera retreats along the optical axis (the classical 180 deg case), and does not converge.
  CHECK(maxDepth > 1.0);
  CHECK(!converged);
}
