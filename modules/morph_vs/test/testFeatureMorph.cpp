// Tests of vpFeatureMorph: interaction matrices against finite differences of a simulated camera motion, the
// error from the correspondence, and convergence in a stock vpServo (every interaction matrix type, both
// eye-in-hand control laws).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include <visp3/core/vpExponentialMap.h>
#include <visp3/core/vpMomentObject.h>
#include <visp3/core/vpPoint.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_vs/vpFeatureMorph.h>
#include <visp3/robot/vpSimulatorCamera.h>
#include <visp3/vs/vpServo.h>
#include <visp3/vs/vpServoDisplay.h>

#include "testMorphVsRecordingDisplay.h"
#include "testMorphVsScene.h"

using namespace vpMorphVsTest;

namespace
{
// The feature seen from cMo: with the depth of a plane parallel to the image, or with the plane itself (tilted).
vpFeatureMorph featureAt(const vpHomogeneousMatrix &cMo, bool withPlane = false)
{
  vpFeatureMorph f;
  if (withPlane) {
    double A, B, C;
    vpFeatureMorph::planeFromPose(cMo, A, B, C);
    f.buildFrom(projectPixels(cMo), camera(), A, B, C);
  } else {
    f.buildFrom(projectPixels(cMo), camera(), depth(cMo));
  }
  return f;
}

// The feature's values seen from the camera moved by v during dt: xg, yg and sigma as measured, theta as the rotation
// of its alignment on \e ref (s has no absolute theta).
vpColVector movedValue(const vpHomogeneousMatrix &cMo, const vpColVector &v, double dt, const vpFeatureMorph &ref)
{
  const vpHomogeneousMatrix cMcp = vpExponentialMap::direct(v, dt);
  vpFeatureMorph f = featureAt(cMcp.inverse() * cMo, true);
  f.error(ref);
  return vpColVector({f.get_xg(), f.get_yg(), -f.getAlignment().transform.theta(), f.get_sigma()});
}

// Whether L's row r, column k is checked against finite differences: theta's rotation is measured by a similarity,
// which a tilt of the camera (columns 3 and 4, wx and wy) does not keep, so its row is checked on the planar motions.
bool checked(unsigned int r, unsigned int k) { return r != 2 || (k != 3 && k != 4); }
} // namespace

TEST_CASE("vpFeatureMorph interaction matrices match finite differences of a camera motion", "[feature]")
{
  const double poses[][3] = {{30, 0.03, -0.02}, {150, -0.05, 0.04}, {0, 0.0, 0.0}, {-100, 0.08, 0.05}};
  for (const auto &p : poses) {
    const vpHomogeneousMatrix cMo = planarPose(p[0], p[1], p[2]);
    vpFeatureMorph s0 = featureAt(cMo);
    const vpMatrix L = s0.interaction();
    REQUIRE(L.getRows() == 4);
    REQUIRE(L.getCols() == 6);
    const double dt = 1e-5;
    for (unsigned int k = 0; k < 6; ++k) {
      vpColVector v(6, 0.0);
      v[k] = 1.0;
      const vpColVector fd = (movedValue(cMo, v, dt, s0) - movedValue(cMo, -v, dt, s0)) / (2 * dt);
      for (unsigned int r = 0; r < 4; ++r) {
        INFO("pose theta=" << p[0] << " row " << r << " column " << k << ": analytic " << L[r][k] << " finite "
                           << fd[r]);
        if (checked(r, k))
          CHECK(std::fabs(L[r][k] - fd[r]) < 1e-4 * (1 + std::fabs(L[r][k])));
      }
    }
  }
}

TEST_CASE("vpFeatureMorph interaction matrices with a tilted plane match finite differences", "[feature]")
{
  const double poses[][6] = {{0.02, -0.01, 0.5, 20, -15, 40}, {-0.04, 0.03, 0.6, -25, 10, 160}};
  for (const auto &p : poses) {
    const vpHomogeneousMatrix cMo(p[0], p[1], p[2], vpMath::rad(p[3]), vpMath::rad(p[4]), vpMath::rad(p[5]));
    vpFeatureMorph s0 = featureAt(cMo, true);
    const vpMatrix L = s0.interaction();
    const double dt = 1e-5;
    for (unsigned int k = 0; k < 6; ++k) {
      vpColVector v(6, 0.0);
      v[k] = 1.0;
      const vpColVector fd = (movedValue(cMo, v, dt, s0) - movedValue(cMo, -v, dt, s0)) / (2 * dt);
      for (unsigned int r = 0; r < 4; ++r) {
        INFO("tilted pose " << p[3] << "/" << p[4] << " row " << r << " column " << k << ": analytic " << L[r][k]
                            << " finite " << fd[r]);
        if (checked(r, k) && r != 2) // a tilted plane's view is no similarity of itself moved: theta unchecked
          CHECK(std::fabs(L[r][k] - fd[r]) < 1e-4 * (1 + std::fabs(L[r][k])));
      }
    }
  }
  // The parallel-plane build is the special case A = B = 0, C = 1/Z.
  const vpHomogeneousMatrix cMo = planarPose(30, 0.03, -0.02);
  vpFeatureMorph a = featureAt(cMo, false), b = featureAt(cMo, true);
  const vpMatrix La = a.interaction(), Lb = b.interaction();
  CHECK((La - Lb).frobeniusNorm() < 1e-9);
  vpFeatureMorph f;
  CHECK_THROWS_AS(f.buildFrom(projectPixels(cMo), camera(), 0.0, 0.0, -2.0), vpMorphException); // behind
}

TEST_CASE("vpFeatureMorph selection, error from the correspondence, duplicate and bad input", "[feature]")
{
  const vpHomogeneousMatrix cdMo = planarPose(0, 0.0, 0.0);
  const vpHomogeneousMatrix cMo = planarPose(120, 0.02, -0.01, 0.6);
  vpFeatureMorph sd = featureAt(cdMo), s = featureAt(cMo);
  const unsigned int sel = vpFeatureMorph::selectTheta() | vpFeatureMorph::selectScale();
  CHECK(s.getDimension(sel) == 2);
  CHECK(s.interaction(sel).getRows() == 2);
  const vpColVector e = s.error(sd);
  // Theta: the current view is the desired one rotated by +120 deg about the optical axis.
  CHECK(e[2] == Approx(vpMath::rad(120)).margin(1e-6));
  CHECK(e[3] == Approx(std::log(0.5 / 0.6)).margin(1e-6)); // ln(Z*/Z)
  const vpColVector es = s.error(sd, sel);
  REQUIRE(es.size() == 2);
  CHECK(es[0] == Approx(e[2]));
  // The error does not depend on the vertex numbering: a contour listed from another vertex gives the same.
  vpFeatureMorph s2;
  s2.buildFrom(projectPixels(cMo).rotatedStart(4), camera(), 0.6);
  CHECK(s2.error(sd)[2] == Approx(e[2]).margin(1e-9));

  std::unique_ptr<vpFeatureMorph> d(s.duplicate());
  CHECK(d->isBuilt());
  CHECK(d->error(sd)[2] == Approx(e[2]).margin(1e-9));
  d->init();
  CHECK(!d->isBuilt());
  CHECK_THROWS_AS(d->error(sd), vpMorphException);
  CHECK_THROWS_AS(s.error(*d), vpMorphException);
  CHECK_THROWS_AS(d->interaction(), vpMorphException);
  CHECK_THROWS_AS(s.buildFrom(projectPixels(cMo), camera(), 0.0), vpMorphException);
  CHECK_THROWS_AS(s.buildFrom(projectPixels(cMo), camera(), std::nan("")), vpMorphException);
  CHECK_THROWS_AS(s.buildFrom(projectPixels(cMo), 0.5), vpMorphException); // pixels need the intrinsics
  CHECK_THROWS_AS(s.buildFrom(vpMorphContour(), camera(), 0.5), vpMorphException);

  // display() draws with vpDisplay: without a display attached to the image it does nothing (headless runs).
  vpImage<unsigned char> I(480, 640, 0);
  vpImage<vpRGBa> Ic(480, 640);
  CHECK_NOTHROW(s.display(camera(), I));
  CHECK_NOTHROW(s.display(camera(), Ic, vpColor::red, 2));
  CHECK_NOTHROW(d->display(camera(), I)); // not built: nothing to draw
}

namespace
{
struct StockResult
{
  bool converged = false;
  int iterations = 0;
  double tErr = 0, rDeg = 0;
  unsigned int fullMatches = 0, searches = 0;
};

// Runs a stock vpServo over vpFeatureMorph on a free-flying camera. With useEJe, the task is
// EYEINHAND_L_cVe_eJe for a 4-joint planar robot (the paper's task: translations x, y, z and rotation about z of
// its end-effector frame e, whose z axis is parallel to the optical axis) carrying the camera at eMc.
vpMatrix planarRobotJacobian()
{
  vpMatrix eJe(6, 4, 0.0);
  eJe[0][0] = eJe[1][1] = eJe[2][2] = eJe[5][3] = 1.0;
  return eJe;
}

StockResult runStock(const vpHomogeneousMatrix &cMo0, const vpHomogeneousMatrix &cdMo,
                     vpServo::vpServoIteractionMatrixType type, bool useEJe)
{
  const vpCameraParameters cam = camera();
  const double Zd = depth(cdMo);
  vpFeatureMorph s, sd;
  sd.buildFrom(projectPixels(cdMo), cam, Zd);
  const double ad = projectPixels(cdMo).area();

  const vpHomogeneousMatrix eMc(0.05, -0.02, 0.1, 0, 0, vpMath::rad(30));
  vpServo task;
  if (useEJe) {
    task.setServo(vpServo::EYEINHAND_L_cVe_eJe);
    task.set_cVe(vpVelocityTwistMatrix(eMc.inverse()));
    task.set_eJe(planarRobotJacobian());
  } else {
    task.setServo(vpServo::EYEINHAND_CAMERA);
    // The feature constrains the planar task (4 dof): the tilt velocities of the camera are left at zero.
    vpColVector dof(6, 1.0);
    dof[3] = dof[4] = 0;
    task.setCameraDoF(dof);
  }
  task.setInteractionMatrixType(type);
  task.setLambda(1.0);
  s.buildFrom(projectPixels(cMo0), cam, Zd);
  task.addFeature(s, sd);
  vpSimulatorCamera robot;
  robot.setSamplingTime(0.1);
  robot.setMaxTranslationVelocity(1.0);
  robot.setMaxRotationVelocity(vpMath::rad(360));
  const vpHomogeneousMatrix wMo;
  robot.setPosition(wMo * cMo0.inverse());
  StockResult r;
  for (r.iterations = 0; r.iterations < 600; ++r.iterations) {
    const vpHomogeneousMatrix cMo = robot.getPosition().inverse() * wMo;
    const vpMorphContour c = projectPixels(cMo);
    REQUIRE(!c.empty());
    s.buildFrom(c, cam, Zd * std::sqrt(ad / c.area())); // depth from the area ratio
    if (useEJe) {
      task.set_cVe(vpVelocityTwistMatrix(eMc.inverse()));
      task.set_eJe(planarRobotJacobian());
    }
    vpColVector v = task.computeControlLaw();
    if (task.getError().frobeniusNorm() < 1e-6) {
      r.converged = true;
      break;
    }
    if (useEJe)
      v = vpVelocityTwistMatrix(eMc.inverse()) * (planarRobotJacobian() * v); // joints -> camera velocity
    robot.setVelocity(vpRobot::CAMERA_FRAME, v);
  }
  {
    // vpServoDisplay draws the current contour and its goal (the desired feature) through display().
    vpImage<unsigned char> I(480, 640, 0);
    RecordingDisplay rec;
    rec.attach(I);
    vpServoDisplay::display(task, cam, I, vpColor::green, vpColor::red);
    RecordingDisplay::detach(I);
    CHECK(rec.count(vpColor::green) == 9);
    CHECK(rec.count(vpColor::red) == 9);
  }
  r.fullMatches = s.getAligner().getTracker().fullMatchCount();
  r.searches = r.fullMatches + s.getAligner().getTracker().trackedMatchCount();
  poseError(robot.getPosition().inverse() * wMo, cdMo, r.tErr, r.rDeg);
  task.kill();
  return r;
}
} // namespace

TEST_CASE("vpFeatureMorph measures its error on the outlines, and its values on the region", "[feature]")
{
  const vpHomogeneousMatrix cdMo = planarPose(0, 0.0, 0.0), cMo = planarPose(30, 0.02, -0.01, 0.6);
  const vpMorphContour exactD = projectPixels(cdMo), exact = projectPixels(cMo);
  // The current polygon as a polygonisation may leave it: one vertex 1.5 px off the edge it approximates.
  vpMorphContour poly = exact;
  std::vector<vpImagePoint> pts = poly.points();
  pts[2].set_u(pts[2].get_u() + 1.5);
  poly = vpMorphContour(pts, vpMorphContour::PIXEL);
  auto error = [&](const vpMorphContour &c, const vpMorphContour &cd, double Z) {
    vpFeatureMorph s, sd;
    sd.buildFrom(cd, camera(), 0.5);
    s.buildFrom(c, camera(), Z);
    return s.error(sd);
  };
  const double thetaPoly = error(poly, exactD, 0.6)[2];
  // Both outlines measured (here the exact polygons, densely): the rotation from them, the stray vertex left out.
  vpMorphContour withOutline = poly, desiredWithOutline = exactD;
  withOutline.setOutline(exact.resampled(400));
  desiredWithOutline.setOutline(exactD.resampled(400));
  const double thetaOutline = error(withOutline, desiredWithOutline, 0.6)[2];
  INFO("theta error: polygons " << vpMath::deg(thetaPoly - vpMath::rad(30)) << " deg, outlines "
                                << vpMath::deg(thetaOutline - vpMath::rad(30)) << " deg");
  CHECK(std::fabs(thetaOutline - vpMath::rad(30)) < vpMath::rad(1e-4));
  CHECK(std::fabs(thetaPoly - vpMath::rad(30)) < vpMath::rad(0.05)); // a polygon's edges fitted robustly

  // A measured region 2 px to the right of the polygon's: s's centroid is the region's, and the error lays that
  // centroid where the alignment (of the outlines) puts it, so the region's offset does not bias the error.
  double cx, cy;
  exact.centroid(cx, cy);
  vpMorphContour region = exact;
  region.setRegion(exact.area(), cx + 2.0, cy, 100.0, 0.0, 100.0);
  vpFeatureMorph s, sd;
  sd.buildFrom(exactD, camera(), 0.5);
  s.buildFrom(region, camera(), 0.6);
  CHECK(s.get_xg() == Approx((cx + 2.0 - camera().get_u0()) / camera().get_px()).margin(1e-12));
  const vpColVector e = s.error(sd), ePoly = error(exact, exactD, 0.6);
  // The same motion of the camera is left to do: a point 2 px aside goes where the same similarity takes it.
  CHECK(std::fabs(e[2] - ePoly[2]) < 1e-9);
  CHECK(std::fabs(e[3] - ePoly[3]) < 1e-9);
  CHECK(s.getAlignment().model == vpMorphViewAlignment::RIGID);
}

namespace
{
// The bracket seen from cMo, in pixels, with the region and the edges a measurement gives (here the polygon's own),
// optionally with the end of its long arm hidden beyond x = cutX (metres, the object frame): a card on the plane.
vpMorphContour measuredBracket(const vpHomogeneousMatrix &cMo, double cutX = 1.0)
{
  std::vector<vpImagePoint> pts;
  for (vpColVector P : objectPoints()) {
    P[0] = std::min(P[0], cutX);
    const vpColVector X = cMo * P;
    const double x = X[0] / X[2], y = X[1] / X[2];
    pts.emplace_back(camera().get_v0() + camera().get_py() * y, camera().get_u0() + camera().get_px() * x);
  }
  vpMorphContour c(pts, vpMorphContour::PIXEL);
  // The region's moments from ViSP's own dense-polygon moments (an oracle independent of the feature's).
  std::vector<vpPoint> vertices(c.size());
  for (std::size_t i = 0; i < c.size(); ++i) {
    vertices[i].set_x(c.x(i));
    vertices[i].set_y(c.y(i));
  }
  vpMomentObject m(2);
  m.setType(vpMomentObject::DENSE_POLYGON);
  m.fromVector(vertices);
  const double a = m.get(0, 0), xg = m.get(1, 0) / a, yg = m.get(0, 1) / a;
  c.setRegion(std::fabs(a), xg, yg, m.get(2, 0) / a - xg * xg, m.get(1, 1) / a - xg * yg, m.get(0, 2) / a - yg * yg);
  c.setOutline(c.resampled(400));
  return c;
}
} // namespace

TEST_CASE("vpFeatureMorph lays a view with part of the object hidden by the part it shows", "[feature]")
{
  // A card hides the end of the bracket's long arm (a fifth of its area). The regions' centroid and area would carry
  // the hidden part into the error, centimetres off at the goal; the visible outline's robust fit does not. Its
  // desired values are where that fit lays the visible part: the error is the whole view's similarity applied to it.
  const vpHomogeneousMatrix cdMo = planarPose(10, 0.01, 0.0);
  const double px = camera().get_px();
  for (const auto &st : {std::array<double, 4>{{0, 0.0, 0.0, 0.5}}, std::array<double, 4>{{40, 0.03, -0.02, 0.55}},
                         std::array<double, 4>{{-150, -0.02, 0.03, 0.45}}}) {
    const vpHomogeneousMatrix cMo = planarPose(10 + st[0], 0.01 + st[1], st[2], st[3]);
    vpFeatureMorph sd, whole, hidden;
    sd.buildFrom(measuredBracket(cdMo), camera(), 0.5);
    whole.buildFrom(measuredBracket(cMo), camera(), st[3]);
    hidden.buildFrom(measuredBracket(cMo, 0.04), camera(), st[3]);
    const vpColVector eWhole = whole.error(sd), eHidden = hidden.error(sd);
    double gx, gy; // where the whole view's similarity lays the visible part's centroid
    whole.getAlignment().transform.apply(hidden.get_xg(), hidden.get_yg(), gx, gy);
    INFO("start " << st[0] << " deg: error whole (" << eWhole.t() << "), hidden (" << eHidden.t() << "), the hidden "
                  << "region's sigma " << hidden.get_sigma() - sd.get_sigma() << " from the desired's");
    CHECK(px * std::fabs(eHidden[0] - (hidden.get_xg() - gx)) < 0.02);
    CHECK(px * std::fabs(eHidden[1] - (hidden.get_yg() - gy)) < 0.02);
    CHECK(std::fabs(eHidden[2] - eWhole[2]) < vpMath::rad(0.005));
    CHECK(std::fabs(eHidden[3] - eWhole[3]) < 1e-4);
    // The test's premise: the hidden region is far from the whole one's (its area a fifth smaller).
    CHECK(std::fabs(hidden.get_sigma() - sd.get_sigma() - eWhole[3]) > 0.05);
    if (st[0] == 0.0) { // at the goal: no error
      CHECK(px * std::hypot(eHidden[0], eHidden[1]) < 0.02);
      CHECK(std::fabs(eHidden[2]) < vpMath::rad(0.005));
      CHECK(std::fabs(eHidden[3]) < 1e-4);
    }
  }
}

TEST_CASE("vpFeatureMorph converges in a stock vpServo with current, desired and mean L, camera and cVe eJe laws",
          "[feature][servo]")
{
  const vpHomogeneousMatrix cdMo = planarPose(20, 0.01, 0.0);
  const double starts[][3] = {{90, 0.05, -0.03}, {170, -0.06, 0.04}, {180, 0.03, 0.03}};
  const vpServo::vpServoIteractionMatrixType types[] = {vpServo::CURRENT, vpServo::DESIRED, vpServo::MEAN};
  const char *names[] = {"CURRENT", "DESIRED", "MEAN"};
  for (const auto &st : starts) {
    const vpHomogeneousMatrix cMo0 = planarPose(20 + st[0], st[1], st[2]);
    for (int t = 0; t < 3; ++t) {
      for (int law = 0; law < 2; ++law) {
        const StockResult r = runStock(cMo0, cdMo, types[t], law == 1);
        INFO("start " << st[0] << " deg, L " << names[t] << (law ? ", EYEINHAND_L_cVe_eJe" : ", EYEINHAND_CAMERA")
                      << ": " << r.iterations << " iterations, error " << r.tErr * 1000 << " mm " << r.rDeg
                      << " deg, full matches " << r.fullMatches);
        CHECK(r.converged);
        CHECK(r.tErr < 1e-3);
        CHECK(r.rDeg < 0.5);
        CHECK(r.fullMatches == 1); // the correspondence starts the first fit; each next starts from the last
      }
    }
  }
}

// Found by fuzzing (tests/fuzz/regressions/servo/): a valid contour of about 1e-160 normalised units has an
// area that underflows and a centroid that divides by it; buildFrom() accepted it and error() returned
// infinities to vpServo (at 1e-150, interaction() divided by zero). Such contours are refused now (below 1e-50),
// by buildFrom() or by vpMorphContour itself, and the feature stays unbuilt.
TEST_CASE("vpFeatureMorph refuses a contour whose moments are not finite", "[feature][bad][fuzz]")
{
  const vpCameraParameters cam(800, 800, 320, 240);
  for (double e : {1e-51, 1e-150, 1e-155, 1e-160, 1e-161}) {
    CAPTURE(e);
    vpFeatureMorph s;
    try {
      s.buildFrom(vpMorphContour({0.0, e, e, 0.0}, {0.0, 0.0, e, e}, vpMorphContour::NORMALIZED), 0.5);
      FAIL("a contour too small for double precision was accepted");
    } catch (const vpMorphException &ex) {
      CHECK(ex.getCode() == vpMorphException::badContourError);
    }
    CHECK_FALSE(s.isBuilt());
  }
  // At 1e-40 normalised units, and at a usable pixel scale, the square is accepted with finite values.
  for (double e : {1e-40, 1e-3}) {
    CAPTURE(e);
    vpFeatureMorph s, sd;
    const vpMorphContour c({0.0, e, e, 0.0}, {0.0, 0.0, e, e}, vpMorphContour::NORMALIZED);
    s.buildFrom(c, 0.5);
    sd.buildFrom(c.transformed(0.3, e, 0.0), 0.5);
    const vpColVector err = s.error(sd);
    const vpMatrix L = s.interaction();
    for (unsigned int i = 0; i < err.getRows(); ++i)
      CHECK(std::isfinite(err[i]));
    for (unsigned int i = 0; i < L.getRows(); ++i)
      for (unsigned int j = 0; j < L.getCols(); ++j)
        CHECK(std::isfinite(L[i][j]));
  }
  vpFeatureMorph s;
  CHECK_NOTHROW(s.buildFrom(vpMorphContour({320.0, 321.0, 321.0, 320.0}, {240.0, 240.0, 241.0, 241.0}), cam, 0.5));
  CHECK(s.isBuilt());
}
