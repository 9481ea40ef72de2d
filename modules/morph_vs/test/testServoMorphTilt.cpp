// Tests of vpServoMorph's out-of-plane (tilt) correction on a free-flying camera (vpSimulatorCamera): tilted starts
// with depth changes, and a hand-eye estimate whose rotation is off about an in-plane axis (the benchmark's calib
// set), which the planar law cannot undo; the planar behaviour and paths are kept on planar starts.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <functional>
#include <random>

#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_vs/vpServoMorph.h>
#include <visp3/robot/vpSimulatorCamera.h>

#include "testMorphVsScene.h"

using namespace vpMorphVsTest;

namespace
{
const double Zd = 0.5;
const vpHomogeneousMatrix cdMo = planarPose(20, 0.01, 0.0, Zd);
const vpHomogeneousMatrix eMcTrue(0.01, 0.05, 0.12, 0, 0, vpMath::rad(90));

// Start as the benchmark draws it: orbit about the plane point on the desired optical axis (tilt about an in-plane
// axis of azimuth phi), move along the new axis (depth change), then turn about it and translate in the image plane.
vpHomogeneousMatrix tiltedStart(double tiltDeg, double phiDeg, double depthChange, double rotDeg, double tx, double ty)
{
  const vpHomogeneousMatrix toPivot(0, 0, Zd, 0, 0, 0);
  const double a = vpMath::rad(tiltDeg), phi = vpMath::rad(phiDeg);
  const vpHomogeneousMatrix cdMc = toPivot * vpHomogeneousMatrix(0, 0, 0, std::cos(phi) * a, std::sin(phi) * a, 0) *
                                   toPivot.inverse() * vpHomogeneousMatrix(0, 0, -depthChange * Zd, 0, 0, 0) *
                                   vpHomogeneousMatrix(tx, ty, 0, 0, 0, vpMath::rad(rotDeg));
  return cdMc.inverse() * cdMo;
}

// The projected polygon with a dense edge outline attached, as vpMorphContourExtractor measures it on images: the
// object's outline sampled every 2 mm in its plane, projected exactly.
vpMorphContour withOutline(const vpMorphContour &polygon, const vpHomogeneousMatrix &cMo)
{
  const std::vector<vpColVector> P = objectPoints();
  std::vector<double> X, Y;
  for (const vpColVector &p : P) {
    X.push_back(p[0]);
    Y.push_back(p[1]);
  }
  const vpMorphContour plane = vpMorphContour(X, Y).resampled(340);
  std::vector<double> x, y;
  const vpCameraParameters cam = camera();
  for (std::size_t k = 0; k < plane.size(); ++k) {
    const vpColVector Q = cMo * vpColVector({plane.x(k), plane.y(k), 0.0, 1.0});
    x.push_back(cam.get_u0() + cam.get_px() * Q[0] / Q[2]);
    y.push_back(cam.get_v0() + cam.get_py() * Q[1] / Q[2]);
  }
  vpMorphContour c = polygon;
  c.setOutline(vpMorphContour(x, y));
  return c;
}

// The outline as a plane tilted by the small angles (ax, ay) (rad) about the axes through its centroid would show it:
// each point's depth changes in proportion to its offset from the centroid, which stays in place. A view-to-view
// perspective change that the outline fit explains exactly, so its covariance does not show it: it stands for what
// moves a thin object's tilt estimate from one view to the next by more than its reported deviation (the pixel grid's
// phase under the edges).
vpMorphContour withTiltJitter(const vpMorphContour &c, double ax, double ay)
{
  const vpCameraParameters cam = camera();
  const vpMorphContour &o = c.outline();
  double uc = 0, vc = 0;
  o.centroid(uc, vc);
  std::vector<double> x, y;
  for (std::size_t k = 0; k < o.size(); ++k) {
    const double dx = (o.x(k) - uc) / cam.get_px(), dy = (o.y(k) - vc) / cam.get_py();
    const double w = 1.0 + ay * dx - ax * dy; // relative depth of the point on the tilted plane
    x.push_back(uc + cam.get_px() * dx / w);
    y.push_back(vc + cam.get_py() * dy / w);
  }
  vpMorphContour out = c;
  out.setOutline(vpMorphContour(x, y));
  return out;
}

// The contour with its edge outline grown by \e px all round (a lighting that clips moves every edge of one view out).
vpMorphContour withOutlineGrown(const vpMorphContour &c, double px)
{
  const vpMorphContour &o = c.outline();
  const double out = o.isCounterClockwise() ? 1.0 : -1.0; // the right normal of a counter-clockwise outline is outward
  std::vector<double> x, y;
  for (std::size_t k = 0; k < o.size(); ++k) {
    const std::size_t a = (k + o.size() - 1) % o.size(), b = (k + 1) % o.size();
    const double tx = o.x(b) - o.x(a), ty = o.y(b) - o.y(a), l = std::hypot(tx, ty);
    x.push_back(o.x(k) + out * px * ty / l);
    y.push_back(o.y(k) - out * px * tx / l);
  }
  vpMorphContour grown = c;
  grown.setOutline(vpMorphContour(x, y));
  return grown;
}

struct Outcome
{
  bool converged = false;
  int iterations = 0;
  double tErr = 0, rDeg = 0, path = 0, straight = 0, tiltDeg = 0;
  vpServoMorph::Status status = vpServoMorph::NOT_STARTED;
};

Outcome run(const vpHomogeneousMatrix &cMo0, vpServoMorph::TiltCorrection mode, const vpHomogeneousMatrix &eMcEstimate,
            const vpCameraParameters &camEstimate = camera(), double noisePx = 0.0, int maxIterations = 300,
            bool outlines = false, bool defaultDeadZones = false, double outlineTiltJitterDeg = 0.0,
            double finalTiltDeg = 0.0, double outlineGrowthPx = 0.0)
{
  vpServoMorph servo;
  servo.setCameraParameters(camEstimate);
  servo.set_eMc(eMcEstimate);
  servo.getPlanner().setSubGoalCount(10);
  servo.setSamplingTime(0.1);
  servo.setGain(0.5);
  servo.setTiltCorrection(mode);
  if (!defaultDeadZones)
    servo.getTiltEstimator().setDeadZone(
        0.0); // exact (or vertex-noise) projected contours: every estimated tilt is commanded
  servo.setTarget(outlines ? withOutline(projectPixels(cdMo), cdMo) : projectPixels(cdMo), Zd);
  if (noisePx > 0) {
    servo.setFinalThresholds(0.004, 0.6);
    servo.getTiltEstimator().setFinalThreshold(outlines ? 0.002 : 0.006); // exact outlines: the tilt is seen exactly
  }
  if (finalTiltDeg > 0)
    servo.getTiltEstimator().setFinalThreshold(vpMath::rad(finalTiltDeg));
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, noisePx > 0 ? noisePx : 1.0);
  std::mt19937 jitterRng(23);
  std::normal_distribution<double> jitter(0.0, vpMath::rad(outlineTiltJitterDeg > 0 ? outlineTiltJitterDeg : 1.0));

  vpSimulatorCamera robot;
  robot.setSamplingTime(0.1);
  robot.setMaxTranslationVelocity(10.0);
  robot.setMaxRotationVelocity(100.0);
  const vpHomogeneousMatrix wMo;
  robot.setPosition(wMo * cMo0.inverse());
  const vpVelocityTwistMatrix cVe(eMcTrue.inverse());
  Outcome r;
  const vpHomogeneousMatrix wMcd = wMo * cdMo.inverse();
  vpTranslationVector prev = robot.getPosition().getTranslationVector();
  r.straight = (wMcd.getTranslationVector() - prev).frobeniusNorm();
  for (r.iterations = 0; r.iterations < maxIterations; ++r.iterations) {
    const vpHomogeneousMatrix cMo = robot.getPosition().inverse() * wMo;
    vpMorphContour c = projectPixels(cMo);
    if (noisePx > 0) {
      std::vector<double> x = c.xs(), y = c.ys();
      for (std::size_t k = 0; k < x.size(); ++k) {
        x[k] += noise(rng);
        y[k] += noise(rng);
      }
      c = vpMorphContour(x, y);
    }
    if (outlines)
      c = withOutline(c, cMo);
    if (outlines && outlineTiltJitterDeg > 0)
      c = withTiltJitter(c, jitter(jitterRng), jitter(jitterRng));
    if (outlines && outlineGrowthPx != 0.0)
      c = withOutlineGrown(c, outlineGrowthPx);
    const vpColVector ve = servo.computeControlLaw(c);
    for (unsigned int i = 0; i < ve.size(); ++i)
      REQUIRE(std::isfinite(ve[i]));
    if (servo.getStatus() == vpServoMorph::CONVERGED) {
      r.converged = true;
      break;
    }
    if (servo.getStatus() != vpServoMorph::MOVING && servo.getStatus() != vpServoMorph::SUBGOAL_REACHED)
      break;
    robot.setVelocity(vpRobot::CAMERA_FRAME, cVe * ve);
    const vpTranslationVector t = robot.getPosition().getTranslationVector();
    r.path += (t - prev).frobeniusNorm();
    prev = t;
  }
  r.status = servo.getStatus();
  const vpHomogeneousMatrix cMo = robot.getPosition().inverse() * wMo;
  poseError(cMo, cdMo, r.tErr, r.rDeg);
  r.tiltDeg = vpMath::deg(std::acos(std::min(1.0, cMo[2][2])));
  return r;
}

void print(const char *what, const Outcome &r)
{
  std::printf("[tilt] %s: %s after %d iterations, pose error %.3f mm %.3f deg (tilt %.3f deg), path %.1f / %.1f mm\n",
              what, vpServoMorph::statusName(r.status), r.iterations, 1000 * r.tErr, r.rDeg, r.tiltDeg, 1000 * r.path,
              1000 * r.straight);
}
} // namespace

TEST_CASE("vpServoMorph tilt correction: converges from tilted starts with depth changes where the planar law does not",
          "[servo][tilt]")
{
  const double starts[][6] = {
      {10, 30, 0.0, 150, 0.04, -0.02}, {25, -120, 0.3, 60, -0.03, 0.03}, {30, 200, -0.3, -170, 0.02, 0.05}};
  for (const auto &s : starts) {
    const vpHomogeneousMatrix cMo0 = tiltedStart(s[0], s[1], s[2], s[3], s[4], s[5]);
    const Outcome on = run(cMo0, vpServoMorph::TILT_ALWAYS, eMcTrue);
    const Outcome fin = run(cMo0, vpServoMorph::TILT_FINAL_APPROACH, eMcTrue);
    const Outcome off = run(cMo0, vpServoMorph::TILT_OFF, eMcTrue);
    char what[160];
    std::snprintf(what, sizeof what, "tilt %g deg, depth %+g %%, rotation %g deg, always", s[0], 100 * s[2], s[3]);
    print(what, on);
    std::snprintf(what, sizeof what, "tilt %g deg, depth %+g %%, rotation %g deg, final approach", s[0], 100 * s[2],
                  s[3]);
    print(what, fin);
    std::snprintf(what, sizeof what, "tilt %g deg, depth %+g %%, rotation %g deg, off (planar)", s[0], 100 * s[2],
                  s[3]);
    print(what, off);
    CHECK(on.converged);
    CHECK(on.tErr < 1e-3);
    CHECK(on.rDeg < 0.5);
    CHECK(fin.converged);
    CHECK(fin.tErr < 1e-3);
    CHECK(fin.rDeg < 0.5);
    CHECK(!(off.tErr < 1e-3 && off.rDeg < 0.5)); // the planar law keeps the tilt
  }
}

TEST_CASE("vpServoMorph tilt correction: a hand-eye rotation error about an in-plane axis (calib set)",
          "[servo][tilt][calibration]")
{
  // The estimate is off by 8 deg about an axis 30 deg from the camera's x axis (in the image plane: a tilt of eMc)
  // and by 15 mm; turning 150-170 deg about the believed optical axis tilts the camera by several degrees.
  const vpHomogeneousMatrix Yerr(0.012, -0.008, 0.006, vpMath::rad(8) * std::cos(vpMath::rad(30)),
                                 vpMath::rad(8) * std::sin(vpMath::rad(30)), 0);
  const vpHomogeneousMatrix eMcEstimate = eMcTrue * Yerr;
  const vpHomogeneousMatrix starts[] = {planarPose(20 + 170, 0.06, -0.03), planarPose(20 - 150, -0.04, 0.05)};
  const vpCameraParameters cams[] = {camera(), vpCameraParameters(900, 720, 330, 232)};
  for (const auto &cam : cams)
    for (const auto &cMo0 : starts) {
      const Outcome on = run(cMo0, vpServoMorph::TILT_ALWAYS, eMcEstimate, cam);
      const Outcome off = run(cMo0, vpServoMorph::TILT_OFF, eMcEstimate, cam);
      char what[160];
      std::snprintf(what, sizeof what, "eMc off by 8 deg (in-plane axis), 15 mm, px %g py %g: always", cam.get_px(),
                    cam.get_py());
      print(what, on);
      std::snprintf(what, sizeof what, "eMc off by 8 deg (in-plane axis), 15 mm, px %g py %g: off (planar)",
                    cam.get_px(), cam.get_py());
      print(what, off);
      CHECK(on.converged);
      CHECK(on.tErr < 1e-3);
      CHECK(on.rDeg < 0.5);
      CHECK(!(off.tErr < 1e-3 && off.rDeg < 0.5));
    }
}

TEST_CASE("vpServoMorph tilt correction keeps the planar paths and copes with vertex noise", "[servo][tilt]")
{
  // Planar starts: the same convergence and path as the planar law (the homography sees no tilt).
  const vpHomogeneousMatrix cMo0 = planarPose(20 + 90, 0.05, -0.06);
  const Outcome on = run(cMo0, vpServoMorph::TILT_ALWAYS, eMcTrue);
  const Outcome off = run(cMo0, vpServoMorph::TILT_OFF, eMcTrue);
  print("planar 90 deg start, always", on);
  print("planar 90 deg start, off (planar)", off);
  CHECK(on.converged);
  CHECK(on.tErr < 1e-3);
  CHECK(on.path == Approx(off.path).epsilon(0.02));
  CHECK(on.path < 1.1 * on.straight);

  // 0.25 px vertex noise on the 9 vertices, tilted start: converges within the noise-level thresholds, never a NaN
  // (checked in run()). With 9 noisy vertices a single homography sees the tilt to about 0.5 deg (0.5 deg moves the
  // outline by at most 0.16 px), hence the looser bounds; extracted outlines have many more vertices.
  const Outcome noisy =
      run(tiltedStart(20, 70, 0.2, 120, 0.03, -0.02), vpServoMorph::TILT_ALWAYS, eMcTrue, camera(), 0.25);
  print("tilt 20 deg, depth +20 %, rotation 120 deg, 0.25 px noise, always", noisy);
  CHECK(noisy.converged);
  CHECK(noisy.tErr < 6e-3);
  CHECK(noisy.rDeg < 1.0);
}

TEST_CASE("vpServoMorph tilt correction refines on measured edge outlines, with their finer dead zone", "[servo][tilt]")
{
  // Polygons with 0.25 px vertex noise (as polygonisations of extracted silhouettes differ) and the default dead
  // zones: from the polygons alone the tilt is left within the 4 deg dead zone; with the edge outlines attached
  // (exact here), the homography is refined on them and the 0.15 deg dead zone applies.
  const vpHomogeneousMatrix cMo0 = tiltedStart(3.5, 40, 0.1, 60, 0.02, -0.01);
  // The tilt tolerated is 0.5 deg; the polygons' dead zone leaves it unknown to a few degrees: not verified.
  const Outcome poly = run(cMo0, vpServoMorph::TILT_FINAL_APPROACH, eMcTrue, camera(), 0.25, 300, false, true, 0, 0.5);
  const Outcome edge = run(cMo0, vpServoMorph::TILT_FINAL_APPROACH, eMcTrue, camera(), 0.25, 300, true, true, 0, 0.5);
  print("tilt 3.5 deg, 0.25 px vertex noise, final approach, polygons", poly);
  print("tilt 3.5 deg, 0.25 px vertex noise, final approach, edge outlines", edge);
  CHECK(poly.tiltDeg > 1.0);
  CHECK(poly.status == vpServoMorph::UNVERIFIED);
  CHECK(edge.converged);
  CHECK(edge.tiltDeg < 0.3);
  CHECK(edge.rDeg < 0.5);
  // Asked for 0.06 deg, below the outline's dead zone (0.15 deg) where it leaves the tilt: it cannot vouch for it.
  const Outcome strict =
      run(cMo0, vpServoMorph::TILT_FINAL_APPROACH, eMcTrue, camera(), 0.25, 300, true, true, 0, 0.06);
  print("tilt 3.5 deg, 0.25 px vertex noise, final approach, edge outlines, 0.06 deg asked", strict);
  CHECK(strict.status == vpServoMorph::UNVERIFIED);
}

TEST_CASE("vpServoMorph tilt correction: edge outlines measured grown all round are not read as a tilt",
          "[servo][tilt]")
{
  // Every current view's edges a pixel out all round, the taught view's not (the current lighting clips): the
  // homographies fit a common edge offset, which eight parameters alone would bend into a tilt and a depth.
  const vpHomogeneousMatrix cMo0 = tiltedStart(3.5, 40, 0.1, 60, 0.02, -0.01);
  const Outcome plain = run(cMo0, vpServoMorph::TILT_FINAL_APPROACH, eMcTrue, camera(), 0.25, 300, true, true, 0, 0.5);
  const Outcome grown =
      run(cMo0, vpServoMorph::TILT_FINAL_APPROACH, eMcTrue, camera(), 0.25, 300, true, true, 0, 0.5, 1.0);
  print("tilt 3.5 deg, edge outlines grown by 1 px, final approach", grown);
  CHECK(grown.converged);
  CHECK(grown.tiltDeg < 0.3);
  CHECK(grown.rDeg < 0.5);
  // Where the same views without the growth end (the vertex noise's share of the error).
  CHECK(std::fabs(grown.tiltDeg - plain.tiltDeg) < 0.05);
  CHECK(std::fabs(grown.tErr - plain.tErr) < 0.5e-3);
}

TEST_CASE("vpServoMorph tilt correction: settings and a contour without a homography", "[servo][tilt][safety]")
{
  vpServoMorph servo;
  CHECK(servo.getTiltCorrection() == vpServoMorph::TILT_OFF);
  CHECK(servo.getTiltEstimator().getDeadZone() == Approx(0.07));
  CHECK_THROWS_AS(servo.getTiltEstimator().setDeadZone(-0.01), vpMorphException);
  servo.getTiltEstimator().setDeadZone(0.0);
  CHECK(servo.getTiltEstimator().getDeadZone() == 0.0);
  servo.setTiltCorrection(vpServoMorph::TILT_ALWAYS);
  CHECK_THROWS_AS(servo.getTiltEstimator().setFinalThreshold(0.0), vpMorphException);
  CHECK_THROWS_AS(servo.getTiltEstimator().setFinalThreshold(std::nan("")), vpMorphException);
  servo.getTiltEstimator().setFinalThreshold(0.01);
  CHECK(servo.getTiltEstimator().getFinalThreshold() == 0.01);
  CHECK(servo.getTiltEstimator().getOutlineDeadZone() == Approx(0.0026));
  CHECK_THROWS_AS(servo.getTiltEstimator().setOutlineDeadZone(-0.01), vpMorphException);
  CHECK_THROWS_AS(servo.getTiltEstimator().setOutlineDeadZone(std::nan("")), vpMorphException);
  servo.getTiltEstimator().setOutlineDeadZone(0.001);
  CHECK(servo.getTiltEstimator().getOutlineDeadZone() == 0.001);
  // A triangle has no homography: the planar law runs alone (finite velocity, no tilt estimate).
  const vpMorphContour tri({200.0, 420.0, 260.0}, {150.0, 190.0, 330.0});
  servo.setTarget(tri, 0.5);
  const vpColVector ve = servo.computeControlLaw(tri.transformed(0.3, 10, -5));
  CHECK((servo.getStatus() == vpServoMorph::MOVING || servo.getStatus() == vpServoMorph::SUBGOAL_REACHED));
  CHECK(!servo.getTiltEstimator().isEstimated());
  for (unsigned int i = 0; i < ve.size(); ++i)
    CHECK(std::isfinite(ve[i]));
}

TEST_CASE("vpServoMorph tilt correction: outline tilt estimates that jump from one view to the next are averaged",
          "[servo][tilt]")
{
  // Each period's outline is seen as if the plane were tilted by a random 0.25 deg (standard deviation per axis) that
  // the fit's covariance does not show: beyond the 0.15 deg dead zone in most periods. Followed period by period,
  // these jumps turn the camera about the object back and forth (measured: paths 1.12-1.24 times the straight line,
  // ending 0.07 deg off); averaged over the last periods, with the covariance scaled by their scatter, they are not
  // commanded (paths 1.00-1.02). A tilt that every view shows is still corrected, to within the dead zone.
  const double jitterDeg = 0.25;
  const vpHomogeneousMatrix flat[] = {tiltedStart(0.0, 0, 0.1, 60, 0.02, -0.01),
                                      tiltedStart(0.0, 0, -0.1, -120, -0.03, 0.02),
                                      tiltedStart(0.0, 0, 0.0, 170, 0.01, 0.03)};
  // The jitter is known from the periods' scatter (0.25 deg about each axis): the tilt is verified within three of
  // its deviations (1.5 deg asked), not within 0.5 deg.
  for (const vpHomogeneousMatrix &cMo0 : flat) {
    const Outcome r =
        run(cMo0, vpServoMorph::TILT_FINAL_APPROACH, eMcTrue, camera(), 0.0, 300, true, true, jitterDeg, 1.5);
    print("no tilt, outline tilt jitter 0.25 deg, final approach", r);
    CHECK(r.converged);
    CHECK(r.path < 1.1 * r.straight);
    CHECK(r.tiltDeg < vpMath::deg(vpMorphTiltEstimator().getOutlineDeadZone())); // within the estimator's floor
  }
  const Outcome tilted = run(tiltedStart(2.0, 40, 0.1, 60, 0.02, -0.01), vpServoMorph::TILT_FINAL_APPROACH, eMcTrue,
                             camera(), 0.0, 300, true, true, jitterDeg, 1.5);
  print("tilt 2 deg, outline tilt jitter 0.25 deg, final approach", tilted);
  CHECK(tilted.converged);
  CHECK(tilted.tiltDeg < 0.2);
  const Outcome strict =
      run(flat[0], vpServoMorph::TILT_FINAL_APPROACH, eMcTrue, camera(), 0.0, 300, true, true, jitterDeg, 0.5);
  print("no tilt, outline tilt jitter 0.25 deg, final approach, 0.5 deg asked", strict);
  CHECK(strict.status == vpServoMorph::UNVERIFIED);
}

TEST_CASE("vpServoMorph tilt correction: a view no homography explains is given no tilt", "[servo][tilt]")
{
  // A view 1.5 deg tilted near its goal, with a bump pushed 8 px out of a fifth of its outline (no homography explains
  // it: a bent or partly hidden object) or as it is.
  const vpHomogeneousMatrix cMo = tiltedStart(1.5, 40, 0.0, 2, 0.002, -0.001);
  const vpMorphContour clean = withOutline(projectPixels(cMo), cMo);
  const vpMorphContour &o = clean.outline();
  double uc = 0, vc = 0;
  o.centroid(uc, vc);
  std::vector<double> x = o.xs(), y = o.ys();
  const std::size_t n = o.size(), bump = n / 5;
  for (std::size_t k = 0; k < bump; ++k) {
    const double push = 8.0 * std::sin(M_PI * double(k) / double(bump));
    const double d = std::hypot(x[k] - uc, y[k] - vc);
    x[k] += push * (x[k] - uc) / d;
    y[k] += push * (y[k] - vc) / d;
  }
  vpMorphContour bumped = clean;
  bumped.setOutline(vpMorphContour(x, y));
  // The periods whose tilt was estimated, the view bumped where \e isBumped says so.
  auto fittedPeriods = [&](const std::function<bool(int)> &isBumped) {
    vpServoMorph servo;
    servo.setCameraParameters(camera());
    servo.set_eMc(eMcTrue);
    servo.getPlanner().setSubGoalCount(10);
    servo.setTiltCorrection(vpServoMorph::TILT_FINAL_APPROACH);
    servo.setTarget(withOutline(projectPixels(cdMo), cdMo), Zd);
    std::vector<int> fitted;
    for (int period = 0; period < 24; ++period) {
      servo.computeControlLaw(isBumped(period) ? bumped : clean);
      REQUIRE((servo.getStatus() == vpServoMorph::MOVING || servo.getStatus() == vpServoMorph::SUBGOAL_REACHED));
      if (servo.getTiltEstimator().isEstimated())
        fitted.push_back(period);
    }
    return fitted;
  };
  // Bumped in periods 0-9: no tilt read there, read from period 10 on.
  const std::vector<int> late = fittedPeriods([](int period) { return period < 10; });
  REQUIRE(late.size() >= 3u);
  CHECK(late[0] == 10);
  CHECK(late[1] == 11);
  // Read in period 0, bumped in periods 1-10, read again at 11.
  const std::vector<int> again = fittedPeriods([](int period) { return period >= 1 && period <= 10; });
  REQUIRE(again.size() >= 2u);
  CHECK(again[0] == 0);
  CHECK(again[1] == 11);
}
