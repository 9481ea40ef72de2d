// Faults in a vpServoMorph loop on the free-flying camera (vpSimulatorCamera) and the projected bracket of
// testMorphVsScene.h: frames without a contour (hold, resume on the same plan, stop after too long), a jump of
// the camera (re-plan, bounded, then convergence), a wrong target (stop instead of a false convergence), and the target
// check with a vpMorphPartRecognizer (a card over the target, rendered from the six tools' images).
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>

#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphPartRecognizer.h>
#include <visp3/morph_vs/vpServoMorph.h>
#include <visp3/robot/vpSimulatorCamera.h>

#include "../../morph/test/testMorphImages.h"
#include "testMorphVsScene.h"

using namespace vpMorphVsTest;

namespace
{
const vpHomogeneousMatrix cdMo = planarPose(20, 0.01, 0.0);
const vpHomogeneousMatrix eMc(0.01, 0.05, 0.12, 0, 0, vpMath::rad(90));

//! A free camera looking at the bracket, with the true eMc.
struct Loop
{
  vpSimulatorCamera robot;
  vpHomogeneousMatrix wMo;
  vpServoMorph servo;
  int iterations = 0;
  double maxSpeed = 0;

  explicit Loop(const vpHomogeneousMatrix &cMo0)
  {
    robot.setSamplingTime(0.1);
    robot.setMaxTranslationVelocity(10.0);
    robot.setMaxRotationVelocity(100.0);
    robot.setPosition(wMo * cMo0.inverse());
    servo.setCameraParameters(camera());
    servo.set_eMc(eMc);
    servo.setSamplingTime(0.1);
    servo.setGain(0.5);
    servo.setTarget(projectPixels(cdMo), depth(cdMo));
  }
  vpHomogeneousMatrix cMo() const { return robot.getPosition().inverse() * wMo; }
  //! One period: the contour seen (or \e none), the law, the robot moves; returns the velocity.
  vpColVector step(bool none = false)
  {
    const vpColVector ve = servo.computeControlLaw(none ? vpMorphContour() : projectPixels(cMo()));
    for (unsigned int i = 0; i < ve.size(); ++i)
      REQUIRE(std::isfinite(ve[i]));
    maxSpeed = std::max(maxSpeed, ve.frobeniusNorm());
    robot.setVelocity(vpRobot::CAMERA_FRAME, vpVelocityTwistMatrix(eMc.inverse()) * ve);
    ++iterations;
    return ve;
  }
  //! Steps until converged, a stop status, or \e max iterations; true when converged.
  bool run(int max = 400)
  {
    for (int k = 0; k < max; ++k) {
      step();
      if (servo.getStatus() == vpServoMorph::CONVERGED)
        return true;
      if (servo.getGuard().isHalted() || servo.getStatus() == vpServoMorph::DEGENERATE_CONTOUR ||
          servo.getStatus() == vpServoMorph::UNEXPLAINED_VIEW)
        return false;
    }
    return false;
  }
  void poseError(double &t, double &rDeg) const { vpMorphVsTest::poseError(cMo(), cdMo, t, rDeg); }
};

//! A T-shaped part of about the bracket's size: another object.
vpMorphContour otherObject(const vpHomogeneousMatrix &cMo)
{
  const double xy[][2] = {{-0.075, -0.05}, {0.075, -0.05}, {0.075, -0.02},  {0.015, -0.02},
                          {0.015, 0.07},   {-0.015, 0.07}, {-0.015, -0.02}, {-0.075, -0.02}};
  std::vector<double> u, v;
  for (const auto &p : xy) {
    vpColVector X(4);
    X[0] = p[0];
    X[1] = p[1];
    X[2] = 0;
    X[3] = 1;
    const vpColVector Xc = cMo * X;
    u.push_back(Xc[0] / Xc[2]);
    v.push_back(Xc[1] / Xc[2]);
  }
  return vpMorphContour(u, v, vpMorphContour::NORMALIZED).toPixels(camera());
}
} // namespace

TEST_CASE("vpServoMorph faults: frames without a contour hold, then the same plan resumes", "[servo][faults]")
{
  Loop clean(planarPose(170, -0.06, 0.05));
  REQUIRE(clean.run());

  Loop l(planarPose(170, -0.06, 0.05));
  for (int k = 0; k < 6; ++k)
    l.step();
  REQUIRE(l.servo.getStatus() != vpServoMorph::CONVERGED);
  const std::vector<vpMorphContour> plan = l.servo.getSubGoals();
  const std::size_t k0 = l.servo.getSubGoalIndex();
  const vpHomogeneousMatrix before = l.robot.getPosition();
  for (int k = 0; k < 5; ++k) { // dropped frames / object absent
    const vpColVector v = l.step(true);
    CHECK(l.servo.getStatus() == vpServoMorph::TARGET_LOST);
    CHECK(v.frobeniusNorm() == 0);
  }
  // Zero velocity: the camera did not move.
  CHECK((l.robot.getPosition().getTranslationVector() - before.getTranslationVector()).frobeniusNorm() < 1e-12);
  l.step();
  CHECK((l.servo.getStatus() == vpServoMorph::MOVING || l.servo.getStatus() == vpServoMorph::SUBGOAL_REACHED));
  CHECK(l.servo.getGuard().getReplanCount() == 0);
  CHECK(l.servo.getSubGoalIndex() >= k0);
  REQUIRE(l.servo.getSubGoals().size() == plan.size());
  for (std::size_t k = 0; k < plan.size(); ++k)
    CHECK(l.servo.getSubGoals()[k].xs() == plan[k].xs()); // the same sequence, not a new morph
  REQUIRE(l.run());
  double t, r;
  l.poseError(t, r);
  CHECK(t < 0.001);
  CHECK(r < 0.1);
  CHECK(l.iterations == clean.iterations + 5); // the hold only delayed the run
}

TEST_CASE("vpServoMorph faults: too long without a contour is a stop until restart()", "[servo][faults]")
{
  Loop l(planarPose(90, 0.05, -0.06));
  l.servo.getGuard().setMaxLostIterations(3);
  l.step();
  for (int k = 0; k < 3; ++k) {
    l.step(true);
    CHECK(l.servo.getStatus() == vpServoMorph::TARGET_LOST);
    CHECK_FALSE(l.servo.getGuard().isHalted());
  }
  l.step(true);
  CHECK(l.servo.getStatus() == vpServoMorph::LOST_TOO_LONG);
  CHECK(l.servo.getGuard().isHalted());
  const vpColVector v = l.step(); // the object is back, but a stop stays a stop
  CHECK(l.servo.getStatus() == vpServoMorph::LOST_TOO_LONG);
  CHECK(v.frobeniusNorm() == 0);
  l.servo.restart();
  CHECK_FALSE(l.servo.getGuard().isHalted());
  CHECK(l.run());
  CHECK(std::string(vpServoMorph::statusName(vpServoMorph::LOST_TOO_LONG)) == "lost too long");
}

TEST_CASE("vpServoMorph faults: a camera jump (20 mm, 10 deg) re-plans from the new view, then converges",
          "[servo][faults]")
{
  Loop clean(planarPose(170, -0.06, 0.05));
  REQUIRE(clean.run());

  for (double sign : {1.0, -1.0}) {
    Loop l(planarPose(170, -0.06, 0.05));
    for (int k = 0; k < 8; ++k)
      l.step();
    REQUIRE_FALSE(l.servo.getStatus() == vpServoMorph::CONVERGED);
    // Bumped: the camera moves by 20 mm in its image plane and 10 deg about its axis.
    l.robot.setPosition(l.robot.getPosition() * vpHomogeneousMatrix(0.02 * std::cos(0.5), sign * 0.02 * std::sin(0.5),
                                                                    0, 0, 0, sign * vpMath::rad(10)));
    const vpColVector v = l.step();
    INFO("sign " << sign << ": status after the jump " << vpServoMorph::statusName(l.servo.getStatus()));
    CHECK(l.servo.getStatus() == vpServoMorph::REPLANNED);
    CHECK(v.frobeniusNorm() == 0);
    CHECK(l.servo.getGuard().getReplanCount() == 1);
    CHECK(l.servo.getSubGoalIndex() == 0); // a new sequence from the new view
    REQUIRE(l.run());
    double t, r;
    l.poseError(t, r);
    CHECK(t < 0.001);
    CHECK(r < 0.1);
    CHECK(l.maxSpeed <= 1.05 * clean.maxSpeed); // no wild velocity after the jump
  }
}

TEST_CASE("vpServoMorph faults: re-plans are bounded", "[servo][faults]")
{
  Loop l(planarPose(170, -0.06, 0.05));
  l.servo.getGuard().setMaxReplans(1);
  CHECK(l.servo.getGuard().getMaxReplans() == 1);
  const vpHomogeneousMatrix bump(0.02, 0, 0, 0, 0, vpMath::rad(10));
  for (int jump = 0; jump < 2; ++jump) {
    for (int k = 0; k < 4; ++k)
      l.step();
    l.robot.setPosition(l.robot.getPosition() * bump);
    l.step();
  }
  CHECK(l.servo.getStatus() == vpServoMorph::TOO_MANY_REPLANS);
  CHECK(l.servo.getGuard().isHalted());
  CHECK(l.servo.getGuard().getReplanCount() == 1);
  CHECK(l.step().frobeniusNorm() == 0);
  CHECK_THROWS_AS(l.servo.getGuard().setJumpPixels(0), vpMorphException);
  vpMorphDatabase db;
  db.add(vpMorphTemplate("bracket", projectPixels(cdMo)));
  CHECK_THROWS_AS(l.servo.getGuard().setTargetCheck(db, "gear"), vpMorphException);
  CHECK_THROWS_AS(l.servo.getGuard().setTargetCheck(db, "bracket", std::nan("")), vpMorphException);
  CHECK_THROWS_AS(l.servo.getGuard().setTargetCheck(db, "bracket", 0.5), vpMorphException);
}

TEST_CASE("vpServoMorph faults: a wrong target is reported (TARGET_MISMATCH), never CONVERGED on", "[servo][faults]")
{
  // The two objects in a calibrated database, as recognition would have them.
  vpMorphDatabase db;
  db.add(vpMorphTemplate("bracket", projectPixels(cdMo)));
  db.add(vpMorphTemplate("tee", otherObject(cdMo)));
  db.calibrate(1);
  const std::size_t tee = db.find("tee"), bracket = db.find("bracket");
  const vpHomogeneousMatrix start = planarPose(120, 0.04, 0.03);

  // Without the check, the measurement alone: more than half of the bracket's outline and of the tee's lie on each
  // other, which the model test reads as the tee with a part bent; with no check to say that the view is the tee, the
  // servo stops without claiming it.
  {
    Loop l(start);
    l.servo.setTarget(otherObject(cdMo), depth(cdMo));
    CHECK_FALSE(l.run());
    INFO("stopped after " << l.iterations << " periods");
    CHECK(l.servo.getStatus() == vpServoMorph::UNVERIFIED);
    CHECK(l.servo.getHistory().back().model == vpMorphViewAlignment::PART_BENT);
  }
  // With it: a stop at once, zero velocity, whatever comes next.
  {
    Loop l(start);
    l.servo.setTarget(otherObject(cdMo), depth(cdMo));
    l.servo.getGuard().setTargetCheck(db, "tee");
    const vpColVector v = l.step();
    INFO("distance " << l.servo.getGuard().getTargetDistance() << ", threshold " << db.threshold(tee));
    CHECK(l.servo.getStatus() == vpServoMorph::TARGET_MISMATCH);
    CHECK(v.frobeniusNorm() == 0);
    // The threshold alone would not tell (calibrated on occlusions, the tee's exceeds the distance between the
    // two): the bracket's template is the database's clear best.
    const vpMorphRecognition rec = db.recognize(projectPixels(start));
    CHECK(rec.index == bracket);
    CHECK(l.servo.getGuard().getTargetDistance() >= vpMorphServoGuard::getMismatchRatio() * rec.distance);
    for (int k = 0; k < 50; ++k) {
      l.step();
      CHECK_FALSE(l.servo.getStatus() == vpServoMorph::CONVERGED);
    }
    CHECK(l.servo.getStatus() == vpServoMorph::TARGET_MISMATCH);
  }
  // The right target with the check converges as before.
  {
    Loop l(start);
    l.servo.getGuard().setTargetCheck(db, "bracket");
    CHECK(l.run());
    CHECK(l.servo.getGuard().getTargetDistance() <= db.threshold(bracket));
  }
}

TEST_CASE("vpMorphServoGuard: with a recognizer, a view its rigid stage names as the target passes the target check",
          "[servo][faults][recognizer]")
{
  using vpMorphTest::extract;
  vpMorphDatabase db;
  for (const char *name : {"key", "pliers", "wedge", "wrench", "screwdriver", "hammer"})
    db.add(vpMorphTemplate(name, extract(vpMorphTest::readObject(name), false)));
  db.calibrate(0);
  const vpMorphPartRecognizer recognizer(db);
  // A card over a fifth (a quarter) of the wedge's (the key's) outline: the view shows less of it than the distance's
  // support asks, and the distance's rules alone take the target's own view for another.
  const struct
  {
    const char *name;
    double share, where;
    unsigned int seed;
  } cards[] = {{"wedge", 0.2, 0.95, 16}, {"key", 0.25, 0.25, 9}};
  for (const auto &card : cards) {
    const cv::Mat hidden = vpMorphTest::squareOccluder(vpMorphTest::readObject(card.name), card.where, card.share);
    const vpMorphContour c = extract(
        vpMorphTest::warp(hidden, vpMorphTest::similarity(hidden, 30.0 + 100.0 * card.where, 1.0, 0, 0), 3, card.seed),
        true);
    const vpMorphContour &target = db[card.name].contour();
    CAPTURE(card.name);
    vpMorphServoGuard alone, withRecognizer, other;
    alone.setTargetCheck(db, card.name);
    withRecognizer.setTargetCheck(recognizer, card.name);
    other.setTargetCheck(recognizer, "hammer");
    REQUIRE(recognizer.namedAs(c, db.find(card.name)) == vpMorphPartRecognizer::NAMED_TEMPLATE);
    CHECK(alone.targetMismatch(c, target, false));
    CHECK_FALSE(withRecognizer.targetMismatch(c, target, false));
    CHECK(other.targetMismatch(c, db["hammer"].contour(), false)); // named as another part: not the hammer
    withRecognizer.clearTargetCheck();
    CHECK_FALSE(withRecognizer.hasTargetCheck());
    CHECK_FALSE(withRecognizer.targetMismatch(c, target, false));
  }
  CHECK_THROWS_AS(vpMorphServoGuard().setTargetCheck(recognizer, "saw"), vpMorphException);
}

TEST_CASE("vpMorphServoGuard: CONVERGED only for an alignment within the final thresholds that pins the pose",
          "[servo][faults]")
{
  vpMorphServoGuard guard;
  CHECK(guard.getVerification() == vpMorphServoGuard::NOT_VERIFIED);
  const double px = 800.0, radius = 100.0; // pixels per normalised unit, the view's RMS radius (px)
  auto alignment = [&](double tPx, double sigmaPx) {
    vpMorphViewAlignment a;
    a.model = vpMorphViewAlignment::RIGID;
    a.transform = vpMorphRigidTransform(0.0, tPx / px, 0.0, 1.0, 0.0, 0.0);
    const double s = sigmaPx / px;
    for (unsigned int i = 0; i < 4; ++i)
      a.covariance[i][i] = s * s;
    return a;
  };
  CHECK(guard.verify(alignment(0.05, 0.01), 0.002, 0.2, 0.2, radius, px, true) == vpServoMorph::CONVERGED);
  CHECK(guard.getVerification() == vpMorphServoGuard::VERIFIED);
  // Beyond the threshold by its own residual: another measurement stopped there (vpServoMorph::PAPER).
  CHECK(guard.verify(alignment(0.5, 0.01), 0.002, 0.2, 0.2, radius, px, true) == vpServoMorph::UNVERIFIED);
  CHECK(guard.getVerification() == vpMorphServoGuard::OUTSIDE_THRESHOLDS);
  // Within it, but not pinned within it.
  CHECK(guard.verify(alignment(0.05, 0.1), 0.002, 0.2, 0.2, radius, px, true) == vpServoMorph::UNVERIFIED);
  CHECK(guard.getVerification() == vpMorphServoGuard::NOT_PINNED);
  // Pinned in the plane, the tilt not bounded.
  CHECK(guard.verify(alignment(0.05, 0.01), 0.002, 0.2, 0.2, radius, px, false) == vpServoMorph::UNVERIFIED);
  CHECK(guard.getVerification() == vpMorphServoGuard::TILT_UNBOUNDED);
  CHECK(std::string(vpMorphServoGuard::verificationName(guard.getVerification())) == "tilt unbounded");
  // Explained only in part: the target check must name it.
  vpMorphViewAlignment part = alignment(0.05, 0.01);
  part.model = vpMorphViewAlignment::PART_HIDDEN;
  CHECK(guard.verify(part, 0.002, 0.2, 0.2, radius, px, true) == vpServoMorph::UNVERIFIED);
  CHECK(guard.getVerification() == vpMorphServoGuard::PART_UNCHECKED);
  // Not explained (no model), whatever else.
  CHECK(guard.verify(vpMorphViewAlignment(), 0.002, 0.2, 0.2, radius, px, true) == vpServoMorph::UNVERIFIED);
  CHECK(guard.getVerification() == vpMorphServoGuard::UNEXPLAINED);
  guard.reset();
  CHECK(guard.getVerification() == vpMorphServoGuard::NOT_VERIFIED);
}

TEST_CASE("vpServoMorph PAPER: the paper's measurement servoes to the goal and stops there UNVERIFIED",
          "[servo][faults]")
{
  // Its measurement carries no covariance and sees no tilt: it cannot vouch for the pose, whatever its thresholds say.
  for (const vpHomogeneousMatrix &start : {planarPose(120, 0.04, 0.03), planarPose(-60, -0.03, 0.05)}) {
    Loop l(start);
    l.servo.setMeasurement(vpServoMorph::PAPER);
    l.servo.setTarget(projectPixels(cdMo), depth(cdMo));
    REQUIRE(l.servo.getMeasurement() == vpServoMorph::PAPER);
    CHECK_FALSE(l.run());
    double t, r;
    l.poseError(t, r);
    INFO("status " << vpServoMorph::statusName(l.servo.getStatus()) << " after " << l.iterations << " periods, "
                   << t * 1000 << " mm, " << r << " deg");
    CHECK(l.servo.getStatus() == vpServoMorph::UNVERIFIED);
    // Why, as the display says it: never verified (no covariance to pin the pose with).
    CHECK(l.servo.getGuard().getVerification() != vpMorphServoGuard::VERIFIED);
    CHECK(l.servo.getGuard().getVerification() != vpMorphServoGuard::NOT_VERIFIED);
    CHECK(l.servo.statusText()[0].rfind(std::string("unverified (") +
                                            vpMorphServoGuard::verificationName(l.servo.getGuard().getVerification()),
                                        0) == 0);
    CHECK(l.servo.getSubGoalIndex() + 1 == l.servo.getSubGoals().size()); // stopped at the target
    CHECK(t < 0.001);
    CHECK(r < 0.5);
  }
}
