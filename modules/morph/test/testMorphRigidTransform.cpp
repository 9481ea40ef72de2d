// Tests of vpMorphRigidTransform: the similarity itself, and the elongation vs least-squares estimators.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphMatcher.h>
#include <visp3/morph/vpMorphRigidTransform.h>

#include "testMorphShapes.h"

namespace
{
double angleError(double a, double b)
{
  double d = std::remainder(a - b, 2.0 * M_PI);
  return std::fabs(d);
}

// Random star-shaped polygon about (cx, cy): sorted angles, radii in [rmin, rmax], x stretched by `stretch`.
vpMorphContour starPolygon(std::mt19937 &rng, std::size_t n, double stretch = 1.5, double rmin = 60.0,
                           double rmax = 100.0, double cx = 320.0, double cy = 240.0)
{
  std::uniform_real_distribution<double> jitter(-0.35, 0.35), radius(rmin, rmax);
  std::vector<double> x(n), y(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double a = 2.0 * M_PI * (k + jitter(rng)) / n;
    const double r = radius(rng);
    x[k] = cx + stretch * r * std::cos(a);
    y[k] = cy + r * std::sin(a);
  }
  return vpMorphContour(x, y);
}

// Target vertex (k + shift) % n = T(input vertex k) + noise; perturb(k) may displace it further.
template <class F>
vpMorphContour makeTarget(const vpMorphContour &A, const vpMorphRigidTransform &T, std::size_t shift, std::mt19937 &rng,
                          double sigma, F perturb)
{
  const std::size_t n = A.size();
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<double> x(n), y(n);
  for (std::size_t k = 0; k < n; ++k) {
    double xo, yo;
    T.apply(A.x(k), A.y(k), xo, yo);
    perturb(k, xo, yo);
    x[(k + shift) % n] = xo + sigma * noise(rng);
    y[(k + shift) % n] = yo + sigma * noise(rng);
  }
  return vpMorphContour(x, y, A.units());
}

vpMorphRigidTransform randomSimilarity(std::mt19937 &rng, const vpMorphContour &A)
{
  std::uniform_real_distribution<double> th(-M_PI, M_PI), t(-80.0, 80.0), s(0.7, 1.4);
  double cx, cy;
  A.centroid(cx, cy);
  return vpMorphRigidTransform(th(rng), t(rng), t(rng), s(rng), cx, cy);
}

// Largest distance between the fitted image of an input vertex and where the true transform puts it.
double maxVertexError(const vpMorphContour &A, const vpMorphRigidTransform &fit, const vpMorphRigidTransform &truth)
{
  double e = 0.0;
  for (std::size_t k = 0; k < A.size(); ++k) {
    double x0, y0, x1, y1;
    fit.apply(A.x(k), A.y(k), x0, y0);
    truth.apply(A.x(k), A.y(k), x1, y1);
    e = std::max(e, std::hypot(x1 - x0, y1 - y0));
  }
  return e;
}
} // namespace

TEST_CASE("vpMorphRigidTransform: apply, inverse, composition, interpolation", "[morph][rigid]")
{
  const vpMorphRigidTransform T(0.7, 12.0, -5.0, 1.3, 100.0, 50.0);
  double x, y, xb, yb;
  T.apply(100.0, 50.0, x, y); // the centre moves by t only
  CHECK(x == Approx(112.0));
  CHECK(y == Approx(45.0));

  T.apply(130.0, 20.0, x, y);
  T.inverse().apply(x, y, xb, yb);
  CHECK(xb == Approx(130.0).margin(1e-9));
  CHECK(yb == Approx(20.0).margin(1e-9));

  const vpMorphRigidTransform U(-2.0, 3.0, 4.0, 0.8, -10.0, 7.0);
  double x1, y1, x2, y2;
  U.apply(30.0, 40.0, x, y);
  T.apply(x, y, x1, y1);
  (T * U).apply(30.0, 40.0, x2, y2);
  CHECK(x2 == Approx(x1).margin(1e-9));
  CHECK(y2 == Approx(y1).margin(1e-9));

  const vpMatrix M = T.toMatrix();
  T.apply(3.0, 4.0, x, y);
  CHECK(M[0][0] * 3 + M[0][1] * 4 + M[0][2] == Approx(x));
  CHECK(M[1][0] * 3 + M[1][1] * 4 + M[1][2] == Approx(y));

  const vpMorphRigidTransform R = T.recentred(-40.0, 8.0);
  R.apply(55.0, -3.0, x1, y1);
  T.apply(55.0, -3.0, x2, y2);
  CHECK(x1 == Approx(x2).margin(1e-9));
  CHECK(y1 == Approx(y2).margin(1e-9));

  // Interpolation: geometric scale, linear angle and translation, about the same centre.
  const vpMorphRigidTransform H = T.interpolated(0.5);
  CHECK(H.theta() == Approx(0.35));
  CHECK(H.scale() == Approx(std::sqrt(1.3)));
  CHECK(H.tx() == Approx(6.0));
  CHECK(H.cx() == 100.0);
  const vpMorphRigidTransform I0 = T.interpolated(0.0);
  CHECK(I0.theta() == 0.0);
  CHECK(I0.scale() == 1.0);
  // Angles are wrapped so that interpolation takes the short way round.
  CHECK(vpMorphRigidTransform(1.5 * M_PI, 0, 0).theta() == Approx(-0.5 * M_PI));
  // The long way round: the other sense (0.7 rad becomes 0.7 - 2 pi), the same end.
  const vpMorphRigidTransform L = T.interpolated(0.5, true);
  CHECK(L.theta() == Approx(0.35 - M_PI));
  CHECK(L.scale() == Approx(H.scale()));
  CHECK(L.tx() == Approx(H.tx()));
  CHECK(T.interpolated(0.25, true).theta() == Approx(0.25 * (0.7 - 2 * M_PI)));
  CHECK(T.interpolated(1.0, true).theta() == Approx(T.theta()));
  CHECK(vpMorphRigidTransform(-0.4, 0, 0).interpolated(0.5, true).theta() == Approx(0.5 * (2 * M_PI - 0.4)));

  CHECK_THROWS_AS(T.interpolated(1.5), vpMorphException);
  CHECK_THROWS_AS(T.interpolated(-0.1), vpMorphException);
  CHECK_THROWS_AS(T.interpolated(std::numeric_limits<double>::quiet_NaN()), vpMorphException);
  CHECK_THROWS_AS(vpMorphRigidTransform(std::numeric_limits<double>::quiet_NaN(), 0, 0), vpMorphException);
  CHECK_THROWS_AS(vpMorphRigidTransform(0, 0, 0, 0.0), vpMorphException);
  CHECK_THROWS_AS(vpMorphRigidTransform(0, 0, 0, -1.0), vpMorphException);
}

TEST_CASE("vpMorphRigidTransform: both estimators recover an exact similarity", "[morph][rigid]")
{
  std::mt19937 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    const vpMorphContour A = starPolygon(rng, 12 + trial % 20);
    const vpMorphRigidTransform truth = randomSimilarity(rng, A);
    const std::size_t shift = trial % A.size();
    const vpMorphContour B = makeTarget(A, truth, shift, rng, 0.0, [](std::size_t, double &, double &) {});
    const vpMorphCorrespondence c = vpMorphTest::shiftedIdentity(A.size(), shift);

    const vpMorphRigidTransform e = vpMorphRigidTransform::fitElongation(A, B, c);
    const vpMorphRigidTransform l = vpMorphRigidTransform::fitLeastSquares(A, B, c);
    CHECK(angleError(e.theta(), truth.theta()) < 1e-9);
    CHECK(angleError(l.theta(), truth.theta()) < 1e-9);
    CHECK(e.scale() == Approx(truth.scale()).epsilon(1e-9));
    CHECK(l.scale() == Approx(truth.scale()).epsilon(1e-9));
    CHECK(maxVertexError(A, e, truth) < 1e-7);
    CHECK(maxVertexError(A, l, truth) < 1e-7);
    // Written about the input's area centroid, so interpolation rotates the shape about itself.
    double cx, cy;
    A.centroid(cx, cy);
    CHECK(l.cx() == Approx(cx));
    CHECK(e.cy() == Approx(cy));
  }
}

TEST_CASE("vpMorphRigidTransform: the elongation estimate does not depend on where the vertices lie along the edges",
          "[morph][rigid]")
{
  // A screwdriver (a handle 80 x 24, a shaft 160 x 8) whose two views are approximated with their extra vertices at
  // different places along the shaft's edges: the corresponded vertices are not the same points of the part, its
  // region is. (Its vertices' moments, each weighted by the length it stands for, put the scale 5 % off.)
  auto driver = [](const std::vector<double> &lower, const std::vector<double> &upper) {
    std::vector<double> x{0.0, 80.0, 80.0}, y{0.0, 0.0, 8.0};
    for (double f : lower) {
      x.push_back(80.0 + 160.0 * f);
      y.push_back(8.0);
    }
    x.insert(x.end(), {240.0, 240.0});
    y.insert(y.end(), {8.0, 16.0});
    for (double f : upper) {
      x.push_back(240.0 - 160.0 * f);
      y.push_back(16.0);
    }
    x.insert(x.end(), {80.0, 80.0, 0.0});
    y.insert(y.end(), {16.0, 24.0, 24.0});
    return vpMorphContour(x, y);
  };
  const vpMorphContour A = driver({0.1, 0.15, 0.2}, {0.7});
  double cx, cy;
  A.centroid(cx, cy);
  const vpMorphRigidTransform truth(0.7, 35.0, -20.0, 1.04, cx, cy);
  const vpMorphContour B = truth.apply(driver({0.55}, {0.3, 0.8, 0.85, 0.9}));
  const vpMorphCorrespondence c = vpMorphMatcher().match(A, B);
  const vpMorphRigidTransform e = vpMorphRigidTransform::fitElongation(A, B, c);
  CHECK(angleError(e.theta(), truth.theta()) < 1e-9);
  CHECK(e.scale() == Approx(truth.scale()).epsilon(1e-9));
  CHECK(e.tx() == Approx(truth.tx()).margin(1e-7));
  CHECK(e.ty() == Approx(truth.ty()).margin(1e-7));
}

TEST_CASE("vpMorphRigidTransform: rotation + translation only (scale fixed to 1)", "[morph][rigid]")
{
  std::mt19937 rng(11);
  const vpMorphContour A = starPolygon(rng, 25);
  double cx, cy;
  A.centroid(cx, cy);
  const vpMorphRigidTransform truth(2.5, 30.0, -12.0, 1.0, cx, cy);
  const vpMorphContour B = makeTarget(A, truth, 3, rng, 0.0, [](std::size_t, double &, double &) {});
  const vpMorphCorrespondence c = vpMorphTest::shiftedIdentity(A.size(), 3);
  for (const vpMorphRigidTransform &f :
       {vpMorphRigidTransform::fitElongation(A, B, c, false), vpMorphRigidTransform::fitLeastSquares(A, B, c, false)}) {
    CHECK(f.scale() == 1.0);
    CHECK(angleError(f.theta(), 2.5) < 1e-9);
    CHECK(maxVertexError(A, f, truth) < 1e-7);
  }
  // With a true scale of 1.25 and scale fixed, the rotation is still right and the centroids still match.
  const vpMorphRigidTransform scaled(2.5, 30.0, -12.0, 1.25, cx, cy);
  const vpMorphContour B2 = makeTarget(A, scaled, 3, rng, 0.0, [](std::size_t, double &, double &) {});
  const vpMorphRigidTransform f =
      vpMorphRigidTransform::fitLeastSquares(A, B2, c, false, vpMorphRigidTransform::NO_ROBUST);
  CHECK(f.scale() == 1.0);
  CHECK(angleError(f.theta(), 2.5) < 1e-9);
}

TEST_CASE("vpMorphRigidTransform: least squares beats elongation on noisy contours", "[morph][rigid][accuracy]")
{
  std::mt19937 rng(2024);
  const int trials = 300;
  const double sigma = 2.0; // px, on input and target vertices (shapes are ~300 x 200 px)
  double errE = 0.0, errL = 0.0, errP = 0.0, maxE = 0.0, maxL = 0.0;
  double terrE = 0.0, terrL = 0.0;
  int lsBetter = 0;
  for (int trial = 0; trial < trials; ++trial) {
    const vpMorphContour A0 = starPolygon(rng, 16 + trial % 25);
    const vpMorphRigidTransform truth = randomSimilarity(rng, A0);
    const std::size_t shift = trial % A0.size();
    const vpMorphContour B = makeTarget(A0, truth, shift, rng, sigma, [](std::size_t, double &, double &) {});
    const vpMorphContour A = vpMorphTest::noisy(A0, rng, sigma);
    const vpMorphCorrespondence c = vpMorphTest::shiftedIdentity(A.size(), shift);
    const vpMorphRigidTransform e = vpMorphRigidTransform::fitElongation(A, B, c);
    const vpMorphRigidTransform l = vpMorphRigidTransform::fitLeastSquares(A, B, c);
    const vpMorphRigidTransform p =
        vpMorphRigidTransform::fitLeastSquares(A, B, c, true, vpMorphRigidTransform::NO_ROBUST);
    const double ee = angleError(e.theta(), truth.theta()), el = angleError(l.theta(), truth.theta());
    errE += ee;
    errL += el;
    errP += angleError(p.theta(), truth.theta());
    maxE = std::max(maxE, ee);
    maxL = std::max(maxL, el);
    terrE += maxVertexError(A0, e, truth);
    terrL += maxVertexError(A0, l, truth);
    lsBetter += el < ee;
  }
  errE /= trials;
  errL /= trials;
  errP /= trials;
  std::printf("[rigid accuracy, noise %.1f px, %d seeded star polygons] mean |rotation error| (deg): elongation %.4f "
              "(max %.3f), least squares Tukey %.4f (max %.3f), plain LS %.4f; LS better in %d/%d; mean max vertex "
              "error (px): elongation %.3f, LS %.3f\n",
              sigma, trials, errE * 180 / M_PI, maxE * 180 / M_PI, errL * 180 / M_PI, maxL * 180 / M_PI,
              errP * 180 / M_PI, lsBetter, trials, terrE / trials, terrL / trials);
  REQUIRE(errL < errE);
  REQUIRE(terrL < terrE);
}

TEST_CASE("vpMorphRigidTransform: robust least squares ignores a deformed part of the contour",
          "[morph][rigid][accuracy]")
{
  std::mt19937 rng(99);
  const int trials = 200;
  double errE = 0.0, errP = 0.0, errH = 0.0, errT = 0.0;
  for (int trial = 0; trial < trials; ++trial) {
    const vpMorphContour A = starPolygon(rng, 30);
    const vpMorphRigidTransform truth = randomSimilarity(rng, A);
    // 20 % of consecutive vertices pushed 40 px away from the centre (an occluder or a deformation).
    const std::size_t first = rng() % A.size(), count = A.size() / 5;
    double tcx, tcy;
    truth.apply(truth.cx(), truth.cy(), tcx, tcy);
    const vpMorphContour B = makeTarget(A, truth, 0, rng, 1.0, [&](std::size_t k, double &x, double &y) {
      if ((k + A.size() - first) % A.size() < count) {
        const double dx = x - tcx, dy = y - tcy, r = std::hypot(dx, dy);
        x += 40.0 * dx / r;
        y += 40.0 * dy / r;
      }
    });
    const vpMorphCorrespondence c = vpMorphTest::shiftedIdentity(A.size(), 0);
    errE += angleError(vpMorphRigidTransform::fitElongation(A, B, c).theta(), truth.theta());
    errP += angleError(vpMorphRigidTransform::fitLeastSquares(A, B, c, true, vpMorphRigidTransform::NO_ROBUST).theta(),
                       truth.theta());
    errH += angleError(vpMorphRigidTransform::fitLeastSquares(A, B, c, true, vpMorphRigidTransform::HUBER).theta(),
                       truth.theta());
    errT += angleError(vpMorphRigidTransform::fitLeastSquares(A, B, c).theta(), truth.theta());
  }
  const double k = 180.0 / M_PI / trials;
  std::printf("[rigid robustness, 20%% of vertices displaced 40 px, noise 1 px, %d trials] mean |rotation error| "
              "(deg): elongation %.3f, plain LS %.3f, Huber %.3f, Tukey %.3f\n",
              trials, errE * k, errP * k, errH * k, errT * k);
  REQUIRE(errT < errP);
  REQUIRE(errT < errE);
  REQUIRE(errH < errP);
}

TEST_CASE("vpMorphRigidTransform: isotropic shapes make elongation ill-posed, least squares still works",
          "[morph][rigid]")
{
  // A square and a regular 24-gon ("disc"): isotropic second moments, no elongation axis.
  std::vector<vpMorphContour> shapes;
  shapes.emplace_back(std::vector<double>{100, 200, 200, 100}, std::vector<double>{100, 100, 200, 200});
  std::vector<double> x, y;
  for (int k = 0; k < 24; ++k) {
    x.push_back(300 + 80 * std::cos(2 * M_PI * k / 24));
    y.push_back(200 + 80 * std::sin(2 * M_PI * k / 24));
  }
  shapes.emplace_back(x, y);
  std::mt19937 rng(5);
  double maxElongationError = 0.0, maxNoisyLsError = 0.0;
  for (const vpMorphContour &A : shapes) {
    double cx, cy;
    A.centroid(cx, cy);
    for (double theta : {0.3, 1.2, -2.0, 3.0}) {
      const vpMorphRigidTransform truth(theta, 15.0, -25.0, 1.2, cx, cy);
      const std::size_t shift = 1;
      const vpMorphContour B = makeTarget(A, truth, shift, rng, 0.0, [](std::size_t, double &, double &) {});
      const vpMorphCorrespondence c = vpMorphTest::shiftedIdentity(A.size(), shift);
      double anisotropy = -1.0;
      const vpMorphRigidTransform e = vpMorphRigidTransform::fitElongation(A, B, c, true, &anisotropy);
      CHECK(anisotropy < 1e-6); // the caller can tell the axis is meaningless
      maxElongationError = std::max(maxElongationError, angleError(e.theta(), theta));
      const vpMorphRigidTransform l = vpMorphRigidTransform::fitLeastSquares(A, B, c);
      CHECK(angleError(l.theta(), theta) < 1e-9);
      CHECK(maxVertexError(A, l, truth) < 1e-7);
      // With noise the least-squares fit degrades gracefully.
      const vpMorphContour Bn = vpMorphTest::noisy(B, rng, 1.0);
      const double en = angleError(vpMorphRigidTransform::fitLeastSquares(A, Bn, c).theta(), theta);
      maxNoisyLsError = std::max(maxNoisyLsError, en);
      CHECK(en < 0.05);
    }
  }
  std::printf("[rigid, isotropic square and 24-gon, noise-free] max |rotation error| (deg): elongation %.2f (axis "
              "undefined), least squares exact; with 1 px noise, least squares max %.3f\n",
              maxElongationError * 180 / M_PI, maxNoisyLsError * 180 / M_PI);
}

TEST_CASE("vpMorphRigidTransform: bad input is rejected with vpMorphException", "[morph][rigid]")
{
  std::mt19937 rng(3);
  const vpMorphContour A = starPolygon(rng, 10);
  const vpMorphContour B = starPolygon(rng, 10);
  const vpMorphCorrespondence c = vpMorphTest::shiftedIdentity(10, 0);
  CHECK_THROWS_AS(vpMorphRigidTransform::fitLeastSquares(vpMorphContour(), B, c), vpMorphException);
  CHECK_THROWS_AS(vpMorphRigidTransform::fitElongation(A, vpMorphContour(), c), vpMorphException);
  const vpMorphContour Bn(B.xs(), B.ys(), vpMorphContour::NORMALIZED);
  CHECK_THROWS_AS(vpMorphRigidTransform::fitLeastSquares(A, Bn, c), vpMorphException);
  CHECK_THROWS_AS(vpMorphRigidTransform::fitLeastSquares(A, B, vpMorphTest::shiftedIdentity(9, 0)), vpMorphException);
  CHECK_THROWS_AS(vpMorphRigidTransform::fitLeastSquares(A, B, vpMorphCorrespondence()), vpMorphException);
  std::vector<std::pair<std::size_t, std::size_t>> p = c.pairs();
  p[3].second = 42; // out of range
  CHECK_THROWS_AS(vpMorphRigidTransform::fitElongation(A, B, vpMorphCorrespondence(10, 10, p, 0, 0)), vpMorphException);
  p = c.pairs();
  p[3] = p[2]; // input vertex 3 and target vertex 3 missing
  CHECK_THROWS_AS(vpMorphRigidTransform::fitElongation(A, B, vpMorphCorrespondence(10, 10, p, 0, 0)), vpMorphException);
  try {
    vpMorphRigidTransform::fitLeastSquares(A, Bn, c);
  } catch (const vpMorphException &e) {
    CHECK(e.getCode() == vpMorphException::badParameterError);
    CHECK(e.getStringMessage().find("units") != std::string::npos);
  }
}

TEST_CASE("vpMorphRigidTransform: minSigma keeps quantised contours from locking onto coinciding vertices",
          "[morph][rigid]")
{
  // Two contours extracted (vertices on the pixel grid) from rendered views of the pliers: the goal view, and a
  // view 0.17 deg and 2 mm away in which 12 of the 19 vertices coincide exactly with goal vertices.
  const std::vector<double> ax = {351, 360, 369, 424, 450, 451, 442, 451, 451, 424,
                                  370, 358, 342, 219, 211, 215, 211, 219, 344};
  const std::vector<double> ay = {226, 224, 228, 233, 232, 236, 240, 244, 247, 246,
                                  252, 256, 248, 255, 248, 240, 232, 226, 232};
  const std::vector<double> bx = {342, 358, 375, 424, 451, 451, 442, 451, 451,
                                  424, 371, 358, 342, 219, 211, 215, 211, 219};
  const std::vector<double> by = {232, 224, 229, 233, 232, 236, 240, 244, 247,
                                  246, 252, 256, 248, 255, 248, 240, 232, 226};
  const vpMorphContour A(ax, ay), B(bx, by);
  const vpMorphCorrespondence c = vpMorphMatcher().match(A, B);
  const vpMorphRigidTransform ls =
      vpMorphRigidTransform::fitLeastSquares(A, B, c, true, vpMorphRigidTransform::NO_ROBUST);
  const vpMorphRigidTransform collapsed = vpMorphRigidTransform::fitLeastSquares(A, B, c);
  const vpMorphRigidTransform floored =
      vpMorphRigidTransform::fitLeastSquares(A, B, c, true, vpMorphRigidTransform::TUKEY, 30, 0.5);
  INFO("LS theta " << ls.theta() << " t " << ls.tx() << " " << ls.ty() << " s " << ls.scale());
  INFO("no floor theta " << collapsed.theta() << " t " << collapsed.tx() << " " << collapsed.ty());
  INFO("floor theta " << floored.theta() << " t " << floored.tx() << " " << floored.ty() << " s " << floored.scale());
  // Without a floor the MAD is 0 and the fit is the identity although the contours differ.
  CHECK(std::hypot(collapsed.tx(), collapsed.ty()) < 1e-6);
  CHECK(std::fabs(collapsed.theta()) < 1e-9);
  // With the half-pixel resolution as floor, the fit sees the difference (here mostly scale: 2 mm of depth), as
  // plain least squares does (s = 1.0014).
  CHECK(std::fabs(collapsed.scale() - 1.0) < 1e-9);
  CHECK(floored.scale() > 1.0003);
  CHECK_THROWS_AS(vpMorphRigidTransform::fitLeastSquares(A, B, c, true, vpMorphRigidTransform::TUKEY, 30, -1.0),
                  vpMorphException);
}

TEST_CASE("vpMorphRigidTransform: refineOnOutline aligns a cut outline to the whole one", "[morph][rigid]")
{
  // The target outline, and the input: the same outline with a part cut away by a chord (an occluder's edge) and
  // its vertices placed elsewhere (every edge split at a random point), seen through a similarity.
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> at(0.2, 0.8);
  for (int trial = 0; trial < 20; ++trial) {
    const vpMorphContour B = starPolygon(rng, 24, 2.5);
    std::vector<double> x, y;
    const std::size_t cutFrom = static_cast<std::size_t>(trial) % 24, cutLength = 3 + trial % 4;
    for (std::size_t k = 0; k < B.size(); ++k) {
      const std::size_t rel = (k + B.size() - cutFrom) % B.size();
      if (rel > 0 && rel < cutLength)
        continue; // hidden: the chord from vertex cutFrom to cutFrom + cutLength replaces them
      x.push_back(B.x(k));
      y.push_back(B.y(k));
      if (rel == 0)
        continue;
      const std::size_t k1 = (k + 1) % B.size();
      const double a = at(rng);
      x.push_back(B.x(k) + a * (B.x(k1) - B.x(k)));
      y.push_back(B.y(k) + a * (B.y(k1) - B.y(k)));
    }
    const vpMorphRigidTransform truth = randomSimilarity(rng, B);
    const vpMorphContour A = truth.inverse().apply(vpMorphContour(x, y));
    // A start a few pixels and degrees off, as a fit over corresponded vertices gives.
    const vpMorphRigidTransform initial = vpMorphRigidTransform(0.05, 4.0, -3.0, 1.02, truth.cx(), truth.cy()) * truth;
    const vpMorphRigidTransform refined = vpMorphRigidTransform::refineOnOutline(A, B, initial, true, 0.01);
    INFO("trial " << trial);
    CHECK(maxVertexError(A, initial, truth) > 3.0);
    CHECK(maxVertexError(A, refined, truth) < 0.05);
  }
  const vpMorphContour B = starPolygon(rng, 12);
  CHECK_THROWS_AS(vpMorphRigidTransform::refineOnOutline(vpMorphContour(), B, vpMorphRigidTransform()),
                  vpMorphException);
  CHECK_THROWS_AS(vpMorphRigidTransform::refineOnOutline(B, B, vpMorphRigidTransform(), true, -1.0), vpMorphException);
  CHECK_THROWS_AS(vpMorphRigidTransform::refineOnOutline(B, B, vpMorphRigidTransform(), true, 0.0, 0),
                  vpMorphException);
}

TEST_CASE("vpMorphRigidTransform: refineOnOutline with an edge offset is not fooled by an outline grown all round",
          "[morph][rigid]")
{
  // A thin outline measured a tenth of a pixel too large all round (an edge level biased by a clipped background)
  // and seen through a similarity: a plain fit takes part of the band for scale, the fit with an offset takes it for
  // what it is and finds the similarity.
  std::mt19937 rng(5);
  for (int trial = 0; trial < 10; ++trial) {
    const vpMorphContour B = starPolygon(rng, 40, 4.0).counterClockwise(); // 480 x 120 px at most
    const double grown = 0.1 + 0.02 * trial;                               // pixels, outwards
    const vpMorphRigidTransform truth = randomSimilarity(rng, B);
    // Counter-clockwise: the left normals point inwards, so growing is a negative offset along them.
    const vpMorphContour A = truth.inverse().apply(vpMorphTest::offsetEdges(B, -grown));
    const vpMorphRigidTransform initial = vpMorphRigidTransform(0.01, 1.0, -1.0, 1.002, truth.cx(), truth.cy()) * truth;
    const vpMorphRigidTransform plain = vpMorphRigidTransform::refineOnOutline(A, B, initial, true, 0.01, 30);
    double offset = 1.0;
    const vpMorphRigidTransform fitted = vpMorphRigidTransform::refineOnOutline(A, B, initial, true, 0.01, 30, &offset);
    INFO("trial " << trial << ": plain scale " << plain.scale() / truth.scale() << ", with the offset "
                  << fitted.scale() / truth.scale() << " and offset " << offset);
    CHECK(std::fabs(plain.scale() / truth.scale() - 1.0) > 2e-4);
    CHECK(std::fabs(fitted.scale() / truth.scale() - 1.0) < 5e-5);
    CHECK(offset == Approx(-grown).margin(2e-3));
    CHECK(maxVertexError(A, fitted, truth) < 0.01);
  }
  // On a disc, growing and scaling are the same: the offset stays 0 and the fit is the plain one.
  std::vector<double> x, y;
  for (int k = 0; k < 64; ++k) {
    x.push_back(100.0 * std::cos(2.0 * M_PI * k / 64));
    y.push_back(100.0 * std::sin(2.0 * M_PI * k / 64));
  }
  const vpMorphContour disc(x, y);
  const vpMorphContour bigger = vpMorphRigidTransform(0.0, 0.0, 0.0, 1.01, 0.0, 0.0).apply(disc);
  double offset = 1.0;
  const vpMorphRigidTransform T =
      vpMorphRigidTransform::refineOnOutline(bigger, disc, vpMorphRigidTransform(), true, 0.01, 30, &offset);
  CHECK(std::fabs(offset) < 1e-3);
  CHECK(T.scale() == Approx(1.0 / 1.01).epsilon(1e-5));
}

TEST_CASE("vpMorphRigidTransform::apply moves a contour's measured edge outline with it", "[morph][rigid][outline]")
{
  vpMorphContour c({0.0, 40.0, 40.0, 0.0}, {0.0, 0.0, 40.0, 40.0});
  const vpMorphContour dense = c.resampled(80);
  c.setOutline(dense);
  const vpMorphRigidTransform T(0.7, 3.0, -2.0, 1.3, 20.0, 20.0);
  const vpMorphContour m = T.apply(c);
  REQUIRE(m.hasOutline());
  REQUIRE(m.outline().size() == dense.size());
  double e = 0;
  for (std::size_t k = 0; k < dense.size(); ++k) {
    double x, y;
    T.apply(dense.x(k), dense.y(k), x, y);
    e = std::max(e, std::hypot(m.outline().x(k) - x, m.outline().y(k) - y));
  }
  CHECK(e < 1e-9);
  CHECK(!m.hasRegion()); // none was measured: none is made up
}

TEST_CASE("vpMorphContour::overlapArea is the area of the regions' intersection", "[morph][overlap]")
{
  auto rect = [](double x0, double y0, double x1, double y1) {
    return vpMorphContour({x0, x1, x1, x0}, {y0, y0, y1, y1});
  };
  const vpMorphContour a = rect(0, 0, 10, 6), b = rect(4, -2, 20, 3);
  CHECK(a.overlapArea(b) == Approx(6 * 3));
  CHECK(b.overlapArea(a) == Approx(6 * 3));
  CHECK(a.overlapArea(a) == Approx(60));
  CHECK(a.overlapArea(rect(20, 20, 30, 30)) == 0.0);
  CHECK(a.overlapArea(rect(2, 1, 5, 4)) == Approx(9)); // inside: no crossing at all
  CHECK(rect(2, 1, 5, 4).overlapArea(a) == Approx(9));
  const vpMorphContour reversed({10, 0, 0, 10}, {0, 0, 6, 6}); // the same rectangle, clockwise
  CHECK(reversed.overlapArea(b) == Approx(18));
  // Dense polygons (the grid path): two 720-gons of radius r whose centres are d apart: the lens between two
  // circles, to the polygons' own accuracy.
  auto disc = [](double cx, double r) {
    std::vector<double> x, y;
    for (int k = 0; k < 720; ++k) {
      x.push_back(cx + r * std::cos(k * M_PI / 360));
      y.push_back(r * std::sin(k * M_PI / 360));
    }
    return vpMorphContour(x, y);
  };
  const double r = 50, d = 30;
  const double lens = 2 * r * r * std::acos(d / (2 * r)) - d / 2 * std::sqrt(4 * r * r - d * d);
  CHECK(disc(0, r).overlapArea(disc(d, r)) == Approx(lens).epsilon(1e-4));
  // A non-convex pair against a fine raster count.
  std::mt19937 rng(5);
  for (int trial = 0; trial < 5; ++trial) {
    const vpMorphContour p = starPolygon(rng, 30, 2.0), q = randomSimilarity(rng, p).apply(p);
    const double exact = p.overlapArea(q);
    double xmin = 1e9, xmax = -1e9, ymin = 1e9, ymax = -1e9;
    for (const vpMorphContour *c : {&p, &q})
      for (std::size_t k = 0; k < c->size(); ++k) {
        xmin = std::min(xmin, c->x(k));
        xmax = std::max(xmax, c->x(k));
        ymin = std::min(ymin, c->y(k));
        ymax = std::max(ymax, c->y(k));
      }
    auto inside = [](const vpMorphContour &c, double x, double y) {
      bool in = false;
      for (std::size_t i = 0, j = c.size() - 1; i < c.size(); j = i++)
        if ((c.y(i) > y) != (c.y(j) > y) && x < (c.x(j) - c.x(i)) * (y - c.y(i)) / (c.y(j) - c.y(i)) + c.x(i))
          in = !in;
      return in;
    };
    const double h = 0.25;
    double counted = 0.0;
    for (double y = ymin + h / 2; y < ymax; y += h)
      for (double x = xmin + h / 2; x < xmax; x += h)
        counted += inside(p, x, y) && inside(q, x, y) ? h * h : 0.0;
    INFO("trial " << trial);
    CHECK(exact == Approx(counted).epsilon(5e-3));
  }
  CHECK_THROWS_AS(a.overlapArea(vpMorphContour()), vpMorphException);
  CHECK_THROWS_AS(a.overlapArea(a.toNormalized(vpCameraParameters(800, 800, 320, 240))), vpMorphException);
}

TEST_CASE("vpMorphRigidTransform: refineOnOverlap and fitOnOverlap find placements of largest overlap",
          "[morph][rigid][overlap]")
{
  std::mt19937 rng(23);
  // A rigid pair: the largest overlap is where the two coincide.
  for (int trial = 0; trial < 10; ++trial) {
    const vpMorphContour B = starPolygon(rng, 40, 2.0);
    vpMorphRigidTransform truth = randomSimilarity(rng, B);
    const vpMorphContour A = truth.inverse().apply(B);
    const vpMorphRigidTransform initial = vpMorphRigidTransform(0.06, 5.0, -4.0, 1.0, truth.cx(), truth.cy()) * truth;
    const vpMorphRigidTransform refined = vpMorphRigidTransform::refineOnOverlap(A, B, initial);
    INFO("trial " << trial);
    CHECK(maxVertexError(A, initial, truth) > 4.0);
    CHECK(maxVertexError(A, refined, truth) < 0.01);
    CHECK(refined.scale() == Approx(initial.scale()).epsilon(1e-12)); // the scale is the caller's
  }
  // A bent bar (one half turned by 12 deg about the middle) on the straight one: no placement lays it on the
  // target. From where the unbent halves coincide, the local search stays (a kink: any move uncovers that half
  // faster than it covers the other); with starts over +-10 deg, fitOnOverlap finds the larger overlap, turned by
  // about half the bend. Both are local maxima: every small move loses area.
  const vpMorphContour straight({-100, 100, 100, -100}, {-8, -8, 8, 8});
  const double bend = 12 * M_PI / 180;
  std::vector<double> bx{
      -100, 0, 100 * std::cos(bend) + 8 * std::sin(bend), 100 * std::cos(bend) - 8 * std::sin(bend), 0, -100};
  std::vector<double> by{-8, -8, 100 * std::sin(bend) - 8 * std::cos(bend), 100 * std::sin(bend) + 8 * std::cos(bend),
                         8,  8};
  const vpMorphContour bent(bx, by);
  const vpMorphRigidTransform start(0.0, 0.0, 0.0);
  const vpMorphRigidTransform local = vpMorphRigidTransform::refineOnOverlap(bent, straight, start);
  const vpMorphRigidTransform best = vpMorphRigidTransform::fitOnOverlap(bent, straight, start, 10 * M_PI / 180, 9);
  const double f0 = start.apply(bent).overlapArea(straight), f = best.apply(bent).overlapArea(straight);
  CHECK(local.apply(bent).overlapArea(straight) == Approx(f0));
  CHECK(f > f0 + 50.0);
  for (const vpMorphRigidTransform &m : {local, best}) {
    const double fm = m.apply(bent).overlapArea(straight);
    const double cx = m.cx() + m.tx(), cy = m.cy() + m.ty();
    for (const vpMorphRigidTransform &d :
         {vpMorphRigidTransform(1e-3, 0, 0, 1, cx, cy), vpMorphRigidTransform(-1e-3, 0, 0, 1, cx, cy),
          vpMorphRigidTransform(0, 0.05, 0), vpMorphRigidTransform(0, -0.05, 0), vpMorphRigidTransform(0, 0, 0.05),
          vpMorphRigidTransform(0, 0, -0.05)})
      CHECK((d * m).apply(bent).overlapArea(straight) < fm);
  }
  CHECK(std::fabs(best.theta()) > 0.25 * bend);
  CHECK(std::fabs(best.theta()) < 0.75 * bend);

  const vpMorphContour B = starPolygon(rng, 12);
  CHECK_THROWS_AS(vpMorphRigidTransform::refineOnOverlap(vpMorphContour(), B, vpMorphRigidTransform()),
                  vpMorphException);
  CHECK_THROWS_AS(vpMorphRigidTransform::refineOnOverlap(B, B, vpMorphRigidTransform(), 0), vpMorphException);
  CHECK_THROWS_AS(vpMorphRigidTransform::refineOnOverlap(B, B, vpMorphRigidTransform(), 10, 0.0), vpMorphException);
  CHECK_THROWS_AS(vpMorphRigidTransform::fitOnOverlap(B, B, vpMorphRigidTransform(), -0.1, 3), vpMorphException);
  CHECK_THROWS_AS(vpMorphRigidTransform::fitOnOverlap(B, B, vpMorphRigidTransform(), 0.1, 4), vpMorphException);
  CHECK_THROWS_AS(vpMorphRigidTransform::refineOnOverlap(B, B.toNormalized(vpCameraParameters(800, 800, 320, 240)),
                                                         vpMorphRigidTransform()),
                  vpMorphException);
}

// vpMorphNearestEdge (internal to the module, behind every outline and overlap fit) against a plain scan of every
// edge, which is what its grid must reproduce: query points on, near and far from a dense outline, inside and outside
// the grid's box (a bent limb mapped beyond the template's box; the grid used to fall back on the scan there).
#include "../src/vpMorphNearestEdge.h"

TEST_CASE(
    "vpMorphNearestEdge finds the scan's nearest point, inside and outside its grid, and what is within a distance",
    "[rigid][nearest]")
{
  // The plain scan: the nearest point of every edge, the first of equal distances.
  struct Nearest
  {
    double fx = 0, fy = 0;
    std::size_t edge = 0;
    bool interior = true;
  };
  auto scan = [](const vpMorphContour &c, double px, double py) {
    const std::size_t n = c.size();
    double best = std::numeric_limits<double>::max();
    Nearest r;
    for (std::size_t k = 0; k < n; ++k) {
      const double ax = c.x(k), ay = c.y(k), dx = c.x((k + 1) % n) - ax, dy = c.y((k + 1) % n) - ay;
      const double l2 = dx * dx + dy * dy;
      const double t = l2 > 0 ? std::min(1.0, std::max(0.0, ((px - ax) * dx + (py - ay) * dy) / l2)) : 0.0;
      const double qx = ax + t * dx, qy = ay + t * dy, d2 = (px - qx) * (px - qx) + (py - qy) * (py - qy);
      if (d2 < best) {
        best = d2;
        r = {qx, qy, k, t > 0.0 && t < 1.0};
      }
    }
    return r;
  };
  // The answer expected from the nearest point: inside an edge, the distance signed along the edge's left normal;
  // at a vertex, the distance itself, along the direction from the vertex to p.
  auto check = [](const vpMorphContour &c, const Nearest &o, double px, double py, double d, double mx, double my) {
    const std::size_t j = (o.edge + 1) % c.size();
    const double len = std::hypot(c.x(j) - c.x(o.edge), c.y(j) - c.y(o.edge));
    const double off = std::hypot(px - o.fx, py - o.fy);
    INFO("query (" << px << ", " << py << "), edge " << o.edge << (o.interior ? " (inside)" : " (at a vertex)"));
    REQUIRE(std::fabs(d) == Approx(off).margin(1e-9));
    if (o.interior || off == 0.0) {
      CHECK(mx == Approx((c.y(o.edge) - c.y(j)) / len).margin(1e-9));
      CHECK(my == Approx((c.x(j) - c.x(o.edge)) / len).margin(1e-9));
      CHECK(d == Approx(mx * (px - o.fx) + my * (py - o.fy)).margin(1e-9));
    } else {
      CHECK(d == Approx(off).margin(1e-9));
      CHECK(mx * off == Approx(px - o.fx).margin(1e-9));
      CHECK(my * off == Approx(py - o.fy).margin(1e-9));
    }
  };
  std::mt19937 rng(5);
  for (int trial = 0; trial < 6; ++trial) {
    // A dense outline (a point per pixel or so), thin or round: a grid of many cells.
    const vpMorphContour c = starPolygon(rng, 24, trial % 2 ? 4.0 : 1.2).resampled(600);
    const vpMorphNearestEdge nearest(c);
    const double cell = 4.0 * c.perimeter() / static_cast<double>(c.size()); // the grid's cell, about
    const auto bx = std::minmax_element(c.xs().begin(), c.xs().end());
    const auto by = std::minmax_element(c.ys().begin(), c.ys().end());
    const double x0 = *bx.first, x1 = *bx.second, y0 = *by.first, y1 = *by.second;
    const double w = x1 - x0, h = y1 - y0;
    std::uniform_real_distribution<double> ux(x0 - 1.5 * w, x1 + 1.5 * w), uy(y0 - 1.5 * h, y1 + 1.5 * h);
    std::normal_distribution<double> off(0.0, 2.0);
    std::uniform_int_distribution<std::size_t> vertex(0, c.size() - 1);
    int outside = 0;
    for (int q = 0; q < 4000; ++q) {
      double px, py;
      if (q % 2) { // near the outline (where the fits query), some of it beyond the box
        const std::size_t k = vertex(rng);
        px = c.x(k) + off(rng);
        py = c.y(k) + off(rng);
      } else {
        px = ux(rng);
        py = uy(rng);
      }
      outside += px < x0 || px > x1 || py < y0 || py > y1;
      double mx, my;
      const double d = nearest(px, py, mx, my);
      const Nearest o = scan(c, px, py);
      check(c, o, px, py, d, mx, my);
      // within(): whether the scan's nearest point is within a tolerance, at tolerances about the distance and
      // about the cell (a reach whose box meets a few cells is searched there, a longer one by rings).
      const double off = std::hypot(px - o.fx, py - o.fy);
      for (const double tol : {0.25, 0.9 * off, 1.1 * off, 3.0, 0.3 * cell, 0.6 * cell, 2.0 * cell})
        if (tol > 0.0 && std::fabs(off - tol) > 1e-9 * tol) {
          CHECK(nearest.within(px, py, tol) == (off < tol));
          // The distance within a reach: operator()'s answer within it (the same edge, bit for bit), +inf beyond.
          double wx, wy, wAlong, ax, ay, along;
          const double wd = nearest.within(px, py, tol, wx, wy, &wAlong);
          const double ad = nearest(px, py, ax, ay, along);
          if (off < tol) {
            CHECK(wd == ad);
            CHECK(wx == ax);
            CHECK(wy == ay);
            CHECK(wAlong == along);
          } else {
            CHECK(wd == std::numeric_limits<double>::infinity());
            CHECK((wx == 0.0 && wy == 0.0 && wAlong == 0.0));
          }
        }
    }
    CHECK(outside > 1000);
    // Far away and non-finite: a distance, then NaN.
    double mx, my;
    const Nearest far = scan(c, 1e12, -3e11);
    CHECK(nearest(1e12, -3e11, mx, my) == Approx(std::hypot(1e12 - far.fx, -3e11 - far.fy)).epsilon(1e-12));
    CHECK(std::isnan(nearest(std::numeric_limits<double>::quiet_NaN(), 0.0, mx, my)));
    CHECK(std::isnan(nearest(0.0, std::numeric_limits<double>::infinity(), mx, my)));
    CHECK(!nearest.within(std::numeric_limits<double>::quiet_NaN(), 0.0, 1.0));
    CHECK(mx == 0.0);
    CHECK(my == 0.0);
  }
  // A polygon of a few edges, scanned without a grid.
  const vpMorphContour poly = starPolygon(rng, 12, 1.2);
  const vpMorphNearestEdge nearPoly(poly);
  std::normal_distribution<double> off(0.0, 3.0);
  for (int q = 0; q < 500; ++q) {
    const std::size_t k = std::size_t(q) % poly.size();
    const double px = poly.x(k) + off(rng), py = poly.y(k) + off(rng);
    double mx, my;
    const Nearest o = scan(poly, px, py);
    const double signedDistance = nearPoly(px, py, mx, my);
    check(poly, o, px, py, signedDistance, mx, my);
    const double d = std::hypot(px - o.fx, py - o.fy);
    CHECK(nearPoly.within(px, py, 1.1 * d + 1e-12));
    CHECK(!nearPoly.within(px, py, 0.9 * d));
    double wx, wy;
    CHECK(nearPoly.within(px, py, 1.1 * d + 1e-12, wx, wy) == signedDistance);
    CHECK(nearPoly.within(px, py, 0.9 * d, wx, wy) == std::numeric_limits<double>::infinity());
  }
}

// vpMorphNearestEdge::alongRow() (the coarse stage's distance grid) against single queries: a raster over and around
// polygons of long edges and a dense outline, with a subset of edges kept, a point repeated and a non-finite one.
TEST_CASE("vpMorphNearestEdge gives a raster's rows the distances of single queries, bit for bit", "[rigid][nearest]")
{
  std::mt19937 rng(11);
  for (int trial = 0; trial < 4; ++trial) {
    const vpMorphContour c =
        trial < 2 ? starPolygon(rng, 20 + 10 * trial, 1.5) : starPolygon(rng, 24, 3.0).resampled(500);
    std::vector<char> keep(c.size(), 1);
    if (trial % 2)
      for (std::size_t k = 0; k < keep.size(); k += 3)
        keep[k] = 0; // a third of the edges are not the object's own
    const vpMorphNearestEdge nearest(c, keep);
    const auto bx = std::minmax_element(c.xs().begin(), c.xs().end());
    const auto by = std::minmax_element(c.ys().begin(), c.ys().end());
    const double x0 = *bx.first, w = *bx.second - x0, y0 = *by.first, h = *by.second - y0;
    std::vector<double> xs, row;
    for (int i = 0; i < 40; ++i)
      xs.push_back(x0 - 0.5 * w + 2.0 * w * i / 39.0);
    xs.push_back(xs[7]); // a point again, after a far one
    for (int j = 0; j < 40; ++j) {
      const double y = y0 - 0.5 * h + 2.0 * h * j / 39.0;
      nearest.alongRow(y, xs, row);
      REQUIRE(row.size() == xs.size());
      for (std::size_t i = 0; i < xs.size(); ++i) {
        double mx, my;
        INFO("trial " << trial << ", point (" << xs[i] << ", " << y << ")");
        CHECK(row[i] == nearest(xs[i], y, mx, my));
      }
    }
  }
  const vpMorphContour poly = starPolygon(rng, 12, 1.2);
  std::vector<double> row;
  vpMorphNearestEdge(poly).alongRow(0.0, {std::numeric_limits<double>::quiet_NaN(), 0.0}, row);
  CHECK(std::isnan(row[0]));
  CHECK(std::isfinite(row[1]));
  vpMorphNearestEdge(poly, std::vector<char>(poly.size(), 0)).alongRow(0.0, {0.0, 1.0}, row);
  CHECK(row == std::vector<double>(2, std::numeric_limits<double>::infinity()));
}
