// Tests of vpMorphHomography: exact recovery of tilted views from projected polygons (any vertex placement),
// accuracy with vertex noise and a hidden part, the decomposition with a known fronto-parallel target plane, bad input.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphHomography.h>
#include <visp3/morph/vpMorphMatcher.h>

#include "testMorphShapes.h"

namespace
{
// A 15 cm asymmetric bracket in the plane z = 0 of its frame, each edge split into \e split parts (more vertices).
std::vector<vpColVector> object(int split = 1)
{
  const double xy[][2] = {{-0.07, -0.05}, {0.08, -0.05}, {0.08, -0.01}, {0.02, -0.01}, {0.02, 0.04},
                          {-0.01, 0.07},  {-0.03, 0.07}, {-0.03, 0.02}, {-0.07, 0.02}};
  const int n = 9;
  std::vector<vpColVector> P;
  for (int k = 0; k < n; ++k)
    for (int s = 0; s < split; ++s) {
      const double t = double(s) / split;
      vpColVector X(4);
      X[0] = (1 - t) * xy[k][0] + t * xy[(k + 1) % n][0];
      X[1] = (1 - t) * xy[k][1] + t * xy[(k + 1) % n][1];
      X[2] = 0;
      X[3] = 1;
      P.push_back(X);
    }
  return P;
}

vpMorphContour project(const vpHomogeneousMatrix &cMo, const std::vector<vpColVector> &P)
{
  std::vector<double> x, y;
  for (const vpColVector &X : P) {
    const vpColVector c = cMo * X;
    x.push_back(c[0] / c[2]);
    y.push_back(c[1] / c[2]);
  }
  return vpMorphContour(x, y, vpMorphContour::NORMALIZED);
}

// Desired view: fronto-parallel at 0.5 m, object turned by 20 deg and offset by 10 mm.
const double Zd = 0.5;
const vpHomogeneousMatrix cdMo(0.01, 0.0, Zd, 0, 0, vpMath::rad(20));

// A start as the benchmark draws it: orbit about the point of the plane on the desired optical axis (tilt about an
// in-plane axis of azimuth phi), depth change along the new axis, then in-plane rotation and translation.
vpHomogeneousMatrix start(double tiltDeg, double phiDeg, double depthChange, double rotDeg, double tx, double ty)
{
  const vpHomogeneousMatrix toPivot(0, 0, Zd, 0, 0, 0);
  const double a = vpMath::rad(tiltDeg), phi = vpMath::rad(phiDeg);
  const vpHomogeneousMatrix tilt(0, 0, 0, std::cos(phi) * a, std::sin(phi) * a, 0);
  const vpHomogeneousMatrix cdMc = toPivot * tilt * toPivot.inverse() * vpHomogeneousMatrix(0, 0, -depthChange * Zd, 0, 0, 0) *
                                   vpHomogeneousMatrix(tx, ty, 0, 0, 0, vpMath::rad(rotDeg));
  return cdMc.inverse() * cdMo; // cMo
}

void poseDiff(const vpHomogeneousMatrix &a, const vpHomogeneousMatrix &b, double &t, double &rDeg)
{
  const vpHomogeneousMatrix d = a.inverse() * b;
  t = d.getTranslationVector().frobeniusNorm();
  rDeg = vpMath::deg(vpThetaUVector(d.getRotationMatrix()).getTheta());
}

// Angle between the optical axis and the plane normal, in the frame of a camera with pose cMo (deg).
double tiltOf(const vpHomogeneousMatrix &cMo) { return vpMath::deg(std::acos(std::min(1.0, cMo[2][2]))); }

vpHomogeneousMatrix estimate(const vpMorphContour &current, const vpMorphContour &target, double minSigma = 0,
                             vpMorphHomography *h = nullptr)
{
  vpMorphMatcher matcher;
  const vpMorphCorrespondence corr = matcher.match(current, target);
  const vpMorphHomography G = vpMorphHomography::fit(current, target, corr, minSigma);
  if (h)
    *h = G;
  return G.inputMtarget(Zd);
}

const double starts[][6] = {{0, 0, 0, 0, 0, 0},         {5, 30, 0, 150, 0.04, -0.02}, {10, -100, 0.2, -170, -0.05, 0.03},
                            {30, 45, -0.4, 60, 0.03, 0.06}, {30, 200, 0.4, 180, -0.06, -0.04}, {20, 90, -0.3, -90, 0.0, 0.07}};
} // namespace

TEST_CASE("vpMorphHomography is exact on projected polygons, whatever the vertex placement", "[homography]")
{
  const vpMorphContour target = project(cdMo, object());
  for (const auto &s : starts) {
    const vpHomogeneousMatrix cMo = start(s[0], s[1], s[2], s[3], s[4], s[5]);
    const vpHomogeneousMatrix cMcd = cMo * cdMo.inverse();
    for (int split : {1, 3}) { // split = 3: the current outline has vertices where the target has none
      vpMorphHomography H;
      const vpHomogeneousMatrix est = estimate(project(cMo, object(split)), target, 0.0, &H);
      double t, r;
      poseDiff(est, cMcd, t, r);
      INFO("tilt " << s[0] << " deg, depth " << s[2] << ", rotation " << s[3] << " deg, split " << split
                   << ": error " << t << " m " << r << " deg, residual " << H.residual() << ", " << H.iterations()
                   << " iterations");
      CHECK(t < 1e-9);
      CHECK(r < 1e-7);
      CHECK(H.residual() < 1e-10);
    }
  }
}

TEST_CASE("vpMorphHomography maps the input outline onto the target and inverts", "[homography]")
{
  const vpMorphContour target = project(cdMo, object());
  const vpMorphContour current = project(start(20, 60, 0.2, 120, 0.02, 0.03), object());
  vpMorphHomography H;
  estimate(current, target, 0.0, &H);
  const vpMorphContour mapped = H.apply(current);
  REQUIRE(mapped.size() == current.size());
  double worst = 0; // vertex k of the object is vertex k of both contours
  for (std::size_t k = 0; k < mapped.size(); ++k)
    worst = std::max(worst, std::hypot(mapped.x(k) - target.x(k), mapped.y(k) - target.y(k)));
  CHECK(worst < 1e-10);
  const vpMorphContour back = H.inverse().apply(mapped);
  for (std::size_t k = 0; k < back.size(); ++k)
    CHECK(std::hypot(back.x(k) - current.x(k), back.y(k) - current.y(k)) < 1e-10);
  double x, y;
  CHECK(vpMorphHomography().apply(0.1, -0.2, x, y));
  CHECK(x == Approx(0.1));
  CHECK(y == Approx(-0.2));
}

TEST_CASE("vpMorphHomography recovers tilt and depth from noisy outlines and a hidden part", "[homography]")
{
  // Outlines as an extractor gives them: many vertices (split edges), 0.25 px noise at px = 800, on both the
  // current and the stored view; robust scale floored at half a pixel.
  const double px = 800, noisePx = 0.25, halfPixel = 0.5 / px;
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, noisePx / px);
  auto noisy = [&](const vpMorphContour &c) {
    std::vector<double> x = c.xs(), y = c.ys();
    for (std::size_t k = 0; k < x.size(); ++k) {
      x[k] += noise(rng);
      y[k] += noise(rng);
    }
    return vpMorphContour(x, y, vpMorphContour::NORMALIZED);
  };
  const vpMorphContour target = noisy(project(cdMo, object(4)));
  double worstT = 0, worstR = 0, worstTilt = 0;
  for (const auto &s : starts) {
    const vpHomogeneousMatrix cMo = start(s[0], s[1], s[2], s[3], s[4], s[5]);
    const vpHomogeneousMatrix est = estimate(noisy(project(cMo, object(5))), target, halfPixel);
    double t, r;
    poseDiff(est, cMo * cdMo.inverse(), t, r);
    // The tilt the estimate implies, against the true one.
    const double tiltErr = std::fabs(tiltOf(est.inverse() * cdMo) - tiltOf(cMo));
    std::printf("[homography] noise %.2f px, tilt %4.1f deg, depth %+4.0f %%, rotation %4.0f deg: pose error %.2f mm "
                "%.3f deg, tilt error %.3f deg\n",
                noisePx, s[0], 100 * s[2], s[3], 1000 * t, r, tiltErr);
    worstT = std::max(worstT, t);
    worstR = std::max(worstR, r);
    worstTilt = std::max(worstTilt, tiltErr);
  }
  // The tilt is seen only through the perspective distortion: at 0.5 m, 0.5 deg of tilt moves the outline of a 15 cm
  // object by at most 0.16 px, so vertex noise of 0.25 px on both outlines (about 40 vertices each) leaves an error
  // of a few tenths of a degree (measured 0.2-0.6 deg), up to about 2 deg when the object is seen from 0.6-0.7 m
  // (smaller in the image); the translation error is mostly the orbit about the object this tilt error implies.
  CHECK(worstT < 25e-3);
  CHECK(worstR < 3.0);
  CHECK(worstTilt < 2.5);

  // A hidden part: the corner of the long arm is cut by a chord in the current view (about 10 % of the outline).
  std::vector<vpColVector> P = object(1);
  P[1][0] = 0.05; // (0.08, -0.05) -> (0.05, -0.05) and a new vertex (0.08, -0.03)
  vpColVector X = P[1];
  X[0] = 0.08;
  X[1] = -0.03;
  P[2][1] = -0.01;
  P.insert(P.begin() + 2, X);
  const vpHomogeneousMatrix cMo = start(15, 20, 0.1, 100, 0.02, 0.0);
  const vpHomogeneousMatrix est = estimate(project(cMo, P), project(cdMo, object()), halfPixel);
  double t, r;
  poseDiff(est, cMo * cdMo.inverse(), t, r);
  std::printf("[homography] corner cut off (chord over 5 of 58 cm of outline), tilt 15 deg: pose error %.2f mm %.3f deg\n",
              1000 * t, r);
  CHECK(t < 3e-3);
  CHECK(r < 0.5);
}

TEST_CASE("vpMorphHomography takes an outline grown all round for an edge offset, not a tilt", "[homography][refine]")
{
  // Near the goal (the final approach), the current view's outline measured a pixel out all round (px = 800: a
  // lighting that clips). The bracket is asymmetric: grown, it is no similar or projective image of itself, so a
  // homography without the offset bends the growth into a tilt.
  const double px = 800;
  const vpMorphContour target = project(cdMo, object(40));
  const double near[][6] = {
      {1.0, 30, 0.0, 10, 0.005, 0.0}, {0.5, -120, 0.1, -40, 0.0, 0.01}, {2.0, 200, -0.1, 170, -0.01, 0.0}};
  for (const auto &s : near) {
    const vpHomogeneousMatrix cMo = start(s[0], s[1], s[2], s[3], s[4], s[5]);
    const vpMorphContour exact = project(cMo, object(40));
    // The edges a pixel out (the left normals point in on a counter-clockwise outline).
    const vpMorphContour grown = vpMorphTest::offsetEdges(exact, (exact.isCounterClockwise() ? -1.0 : 1.0) / px);
    const vpMorphContour coarse = project(cMo, object()), coarseTarget = project(cdMo, object());
    const vpMorphHomography G0 =
        vpMorphHomography::fit(coarse, coarseTarget, vpMorphMatcher().match(coarse, coarseTarget));
    const vpMorphHomography G = vpMorphHomography::refine(grown, target, G0, 0.5 / px, 200, 20, true);
    const vpMorphHomography plain = vpMorphHomography::refine(grown, target, G0, 0.5 / px);
    const vpHomogeneousMatrix est = G.inputMtarget(Zd);
    const double tiltErr = std::fabs(tiltOf(est.inverse() * cdMo) - tiltOf(cMo));
    double t, r, tPlain, rPlain;
    poseDiff(est, cMo * cdMo.inverse(), t, r);
    poseDiff(plain.inputMtarget(Zd), cMo * cdMo.inverse(), tPlain, rPlain);
    std::printf("[homography] outline 1 px out all round, tilt %.1f deg: tilt error %.3f deg, pose error %.2f mm %.3f "
                "deg, offset %.3f px; without the offset %.2f mm %.3f deg\n",
                s[0], tiltErr, 1000 * t, r, G.edgeOffset() * px, 1000 * tPlain, rPlain);
    CHECK(plain.edgeOffset() == 0.0);
    CHECK(tPlain > 10e-3);
    // Without the offset the growth is read as a tilt and tens of millimetres; with it, what is left is the corners,
    // which the test grows mitred, not rounded as the offset's level set.
    CHECK(G.edgeOffset() * px == Approx(1.0).margin(0.15));
    CHECK(tiltErr < 0.1);
    CHECK(r < 0.1);
    CHECK(t < 1e-3);
  }
}

TEST_CASE("vpMorphHomography::refine from a start within the noise goes straight to its Tukey rounds",
          "[homography][refine]")
{
  // The servo's case at every period of its final approach: the last period's homography, already within the edges'
  // noise, refined again on dense noisy outlines. The Huber rounds only bring a far start within the noise, where
  // Tukey's weights can tell the inliers: from there one Huber update, one Tukey update, and the check that settles.
  const double px = 800, noisePx = 0.25;
  std::mt19937 rng(11);
  const vpMorphContour target = vpMorphTest::noisy(project(cdMo, object(40)), rng, noisePx / px);
  for (const bool offset : {false, true}) {
    const vpHomogeneousMatrix cMo = start(2.0, 60, 0.05, 30, 0.01, -0.005);
    const vpMorphContour current = vpMorphTest::noisy(project(cMo, object(40)), rng, noisePx / px);
    const vpMorphContour coarse = project(cMo, object()), coarseTarget = project(cdMo, object());
    const vpMorphHomography G0 =
        vpMorphHomography::fit(coarse, coarseTarget, vpMorphMatcher().match(coarse, coarseTarget));
    const vpMorphHomography far = vpMorphHomography::refine(current, target, G0, 0.1 / px, 400, 20, offset);
    const vpMorphHomography again = vpMorphHomography::refine(current, target, far, 0.1 / px, 400, 20, offset);
    double t, r;
    poseDiff(far.inputMtarget(Zd), again.inputMtarget(Zd), t, r);
    std::printf(
        "[homography] refined again from its own result (offset %d): %u iterations (from the polygons' fit %u), "
        "moved %.2g mm %.2g deg\n",
        int(offset), again.iterations(), far.iterations(), 1000 * t, r);
    CHECK(again.iterations() <= 3);
    CHECK(t < 0.05e-3);
    CHECK(r < 0.01);
  }
}

TEST_CASE("vpMorphHomography::refine lays a dense view with a part hidden on the whole target", "[homography][refine]")
{
  // The bracket's long arm cut by a chord (8 cm of its 58 cm of outline hidden), both outlines dense (each edge split
  // in 40), the target whole. The samples off the other outline (the chord, the hidden corner) are left out by the
  // Tukey rounds, which search the nearest edges only within their cut-off. What is left near the chord's ends (the
  // hidden corner's samples a few pixels from it) biases the pose by about a millimetre at 0.5 m.
  std::vector<vpColVector> P = object(1);
  P[1][0] = 0.02; // (0.08, -0.05) -> (0.02, -0.05), and a new vertex (0.08, -0.03)
  vpColVector X = P[1];
  X[0] = 0.08;
  X[1] = -0.03;
  P.insert(P.begin() + 2, X);
  std::vector<vpColVector> dense;
  for (std::size_t k = 0; k < P.size(); ++k)
    for (int s = 0; s < 40; ++s) {
      const double t = s / 40.0;
      dense.push_back((1 - t) * P[k] + t * P[(k + 1) % P.size()]);
    }
  const vpMorphContour target = project(cdMo, object(40));
  for (const auto &s : starts) {
    const vpHomogeneousMatrix cMo = start(s[0], s[1], s[2], s[3], s[4], s[5]);
    const vpMorphContour current = project(cMo, dense);
    const vpMorphContour coarse = project(cMo, object()), coarseTarget = project(cdMo, object());
    const vpMorphHomography G0 =
        vpMorphHomography::fit(coarse, coarseTarget, vpMorphMatcher().match(coarse, coarseTarget));
    // Started a little off (the polygons' own fit is exact): a homography 1 % larger.
    vpMatrix M = G0.matrix();
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        M[i][j] *= 1.01;
    const vpMorphHomography G = vpMorphHomography::refine(current, target, vpMorphHomography(M), 0.5 / 800, 400);
    double t, r;
    poseDiff(G.inputMtarget(Zd), cMo * cdMo.inverse(), t, r);
    INFO("tilt " << s[0] << " deg: " << 1000 * t << " mm " << r << " deg, inliers " << G.inlierShare());
    CHECK(t < 3e-3);
    CHECK(r < 0.3);
    CHECK(G.inlierShare() > 0.8);
    CHECK(G.inlierShare() < 0.95);
  }
}

TEST_CASE("vpMorphHomography rejects degenerate input", "[homography][safety]")
{
  const vpMorphContour target = project(cdMo, object());
  const vpMorphContour current = project(start(10, 0, 0, 30, 0, 0), object());
  const vpMorphCorrespondence corr = vpMorphMatcher().match(current, target);
  // Triangles: points may slide along the edges.
  const vpMorphContour tri({0.0, 0.1, 0.0}, {0.0, 0.0, 0.1}, vpMorphContour::NORMALIZED);
  const vpMorphContour tri2({0.0, 0.12, 0.0}, {0.0, 0.0, 0.1}, vpMorphContour::NORMALIZED);
  const vpMorphCorrespondence triCorr(3, 3, {{0, 0}, {1, 1}, {2, 2}}, 0, 0);
  CHECK_THROWS_AS(vpMorphHomography::fit(tri, tri2, triCorr), vpMorphException);
  try {
    vpMorphHomography::fit(tri, tri2, triCorr);
  } catch (const vpMorphException &e) {
    CHECK(e.getCode() == vpMorphException::badContourError);
    CHECK(std::string(e.getMessage()).find("at least 4 vertices") != std::string::npos);
  }
  // A sliver: four vertices almost on a line.
  const vpMorphContour sliver({0.0, 0.1, 0.2, 0.1}, {0.0, 1e-9, 0.0, -1e-9}, vpMorphContour::NORMALIZED);
  const vpMorphCorrespondence id4(4, 4, {{0, 0}, {1, 1}, {2, 2}, {3, 3}}, 0, 0);
  CHECK_THROWS_AS(vpMorphHomography::fit(sliver, sliver, id4), vpMorphException);
  // Empty, different units, a correspondence that does not fit, bad parameters.
  CHECK_THROWS_AS(vpMorphHomography::fit(vpMorphContour(), target, corr), vpMorphException);
  CHECK_THROWS_AS(vpMorphHomography::fit(current, target.toPixels(vpCameraParameters(800, 800, 320, 240)), corr),
                  vpMorphException);
  CHECK_THROWS_AS(vpMorphHomography::fit(current, target, id4), vpMorphException);
  CHECK_THROWS_AS(vpMorphHomography::fit(current, target, corr, -1.0), vpMorphException);
  CHECK_THROWS_AS(vpMorphHomography::fit(current, target, corr, 0.0, 8), vpMorphException);
  CHECK_THROWS_AS(vpMorphHomography::fit(current, target, corr, 0.0, 200, 0), vpMorphException);
  const vpMorphHomography H = vpMorphHomography::fit(current, target, corr);
  CHECK_THROWS_AS(H.inputMtarget(0.0), vpMorphException);
  CHECK_THROWS_AS(H.inputMtarget(std::nan("")), vpMorphException);
  CHECK_THROWS_AS(vpMorphHomography(vpMatrix(2, 3)), vpMorphException);
  CHECK_THROWS_AS(vpMorphHomography(vpMatrix(3, 3)), vpMorphException); // zero: singular
}

TEST_CASE("vpMorphHomography::refine is exact on dense outlines and matches the exhaustive nearest-edge search",
          "[homography][refine]")
{
  // Dense outlines (each edge split in 40: 360 vertices, above the size where edges are searched through a grid),
  // refined from a homography found on 1 %-noisy polygons: the true one is found to numerical precision, as fit()
  // finds it on the polygons themselves.
  const vpMorphContour target = project(cdMo, object(40));
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 1.0 / 800);
  for (const auto &s : starts) {
    const vpHomogeneousMatrix cMo = start(s[0], s[1], s[2], s[3], s[4], s[5]);
    const vpHomogeneousMatrix cMcd = cMo * cdMo.inverse();
    const vpMorphContour current = project(cMo, object(40));
    vpMorphContour noisy = project(cMo, object());
    std::vector<double> x = noisy.xs(), y = noisy.ys();
    for (std::size_t k = 0; k < x.size(); ++k) {
      x[k] += noise(rng);
      y[k] += noise(rng);
    }
    noisy = vpMorphContour(x, y, vpMorphContour::NORMALIZED);
    const vpMorphContour coarseTarget = project(cdMo, object());
    const vpMorphHomography G0 =
        vpMorphHomography::fit(noisy, coarseTarget, vpMorphMatcher().match(noisy, coarseTarget), 0.5 / 800);
    const vpMorphHomography G = vpMorphHomography::refine(current, target, G0, 0.0, 600, 30);
    double t0, r0, t, r;
    poseDiff(G0.inputMtarget(Zd), cMcd, t0, r0);
    poseDiff(G.inputMtarget(Zd), cMcd, t, r);
    INFO("tilt " << s[0] << " deg: from the noisy polygons " << 1000 * t0 << " mm " << r0 << " deg, refined " << t
                 << " m " << r << " deg, residual " << G.residual());
    CHECK(t < 1e-9);
    CHECK(r < 1e-7);
    CHECK(G.residual() < 1e-10);
    CHECK(G.inlierShare() == 1.0);
  }
  // Bad input: as fit(), without a correspondence.
  const vpMorphHomography I;
  CHECK_THROWS_AS(vpMorphHomography::refine(vpMorphContour(), target, I), vpMorphException);
  CHECK_THROWS_AS(vpMorphHomography::refine(target, target.toPixels(vpCameraParameters(800, 800, 320, 240)), I),
                  vpMorphException);
  CHECK_THROWS_AS(vpMorphHomography::refine(target, target, I, -1.0), vpMorphException);
  CHECK_THROWS_AS(vpMorphHomography::refine(target, target, I, 0.0, 8), vpMorphException);
  CHECK_THROWS_AS(vpMorphHomography::refine(target, target, I, 0.0, 200, 0), vpMorphException);
  const vpMorphContour tri({0.0, 0.1, 0.0}, {0.0, 0.0, 0.1}, vpMorphContour::NORMALIZED);
  CHECK_THROWS_AS(vpMorphHomography::refine(tri, tri, I), vpMorphException);
}
