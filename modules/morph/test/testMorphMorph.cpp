// Tests of vpMorph: rigid rectification then Eq. 1, and the sequence of intermediate contours.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include <visp3/morph/vpMorph.h>
#include <visp3/morph/vpMorphException.h>

#include "testMorphShapes.h"

namespace
{
// A key: head on the left, shaft to the right with two teeth; elongated and not symmetric.
vpMorphContour keyShape()
{
  const std::vector<double> x = {0, 30, 30, 120, 120, 100, 100, 85, 85, 60, 60, 45, 45, 30, 30, 0};
  const std::vector<double> y = {-20, -20, 0, 0, 20, 20, 35, 35, 20, 20, 45, 45, 20, 20, 60, 60};
  std::vector<double> u, v;
  for (std::size_t k = 0; k < x.size(); ++k) {
    u.push_back(200 + 1.5 * x[k]);
    v.push_back(150 + 1.5 * y[k]);
  }
  return vpMorphContour(u, v);
}

bool sameContour(const vpMorphContour &a, const vpMorphContour &b)
{
  return a.xs() == b.xs() && a.ys() == b.ys() && a.units() == b.units();
}

// Largest distance between corresponded vertices of two contours.
double pairDistance(const vpMorphContour &a, const vpMorphContour &b, const vpMorphCorrespondence &c)
{
  double d = 0.0;
  for (const auto &p : c.pairs())
    d = std::max(d, std::hypot(a.x(p.first) - b.x(p.second), a.y(p.first) - b.y(p.second)));
  return d;
}

// Number of frames of a morph that are not valid simple polygons (degenerate, or self-intersecting).
int invalidFrames(const vpMorph &m, std::size_t n)
{
  int bad = 0;
  const std::size_t nr = m.rigidFrameCount(n), nd = n - nr;
  for (std::size_t k = 1; k <= nr; ++k)
    bad += !m.rigidTransform().interpolated(double(k) / nr).apply(m.input()).isSimple();
  for (std::size_t k = 1; k <= nd; ++k) {
    try {
      bad += !m.at(double(k) / nd).isSimple();
    } catch (const vpMorphException &) {
      ++bad; // collapsed
    }
  }
  return bad;
}

} // namespace

TEST_CASE("vpMorph: sequence sizes, split, and last frame == target", "[morph][vpMorph]")
{
  const vpMorphContour A = keyShape();
  const vpMorphContour B = A.transformed(2.0, 80.0, 40.0, 0.8).rotatedStart(5);
  const vpMorph m(A, B, vpMorphTest::shiftedIdentity(A.size(), A.size() - 5));

  CHECK(m.sequence(0).empty());
  REQUIRE(m.sequence(1).size() == 1);
  CHECK(sameContour(m.sequence(1)[0], B));
  const std::vector<vpMorphContour> s2 = m.sequence(2);
  REQUIRE(s2.size() == 2);
  CHECK(sameContour(s2[0], m.rectified()));
  CHECK(sameContour(s2[1], B));

  const std::vector<vpMorphContour> s = m.sequence(10);
  REQUIRE(s.size() == 10);
  CHECK(m.rigidFrameCount(10) == 5);
  CHECK(m.rigidFrameCount(7) == 4);
  CHECK(sameContour(s.back(), B));
  CHECK(sameContour(s[4], m.rectified()));
  CHECK(sameContour(m.at(1.0), B));
  CHECK(sameContour(m.at(0.0), m.rectified()));

  const std::vector<vpMorphContour> w = m.sequenceWithInput(10);
  REQUIRE(w.size() == 11);
  CHECK(sameContour(w.front(), A));
  CHECK(sameContour(w.back(), B));

  // The first rigid frame is a similarity of the input: constant edge-length ratio, same turning angles.
  const vpMorphContour &f = s.front();
  REQUIRE(f.size() == A.size());
  const double ratio = f.edgeLength(0) / A.edgeLength(0);
  CHECK(ratio == Approx(std::pow(m.rigidTransform().scale(), 1.0 / 5.0)));
  for (std::size_t k = 0; k < A.size(); ++k) {
    CHECK(f.edgeLength(k) / A.edgeLength(k) == Approx(ratio));
    CHECK(f.turningAngle(k) == Approx(A.turningAngle(k)).margin(1e-9));
  }
  // ... rotated about the input's centroid: the centroid only translates, by a fifth of the translation.
  double ax, ay, fx, fy;
  A.centroid(ax, ay);
  f.centroid(fx, fy);
  CHECK(fx - ax == Approx(m.rigidTransform().tx() / 5.0));
  CHECK(fy - ay == Approx(m.rigidTransform().ty() / 5.0));
}

TEST_CASE("vpMorph: exact recovery of a pure similarity", "[morph][vpMorph]")
{
  const vpMorphContour A = keyShape().resampled(40);
  const vpMorphContour B = A.transformed(-2.6, -50.0, 30.0, 1.3).rotatedStart(11);
  const vpMorphCorrespondence c = vpMorphTest::shiftedIdentity(A.size(), A.size() - 11);
  for (vpMorph::Estimator e : {vpMorph::LEAST_SQUARES, vpMorph::ELONGATION}) {
    const vpMorph m(A, B, c, e);
    CHECK(m.estimator() == e);
    CHECK(pairDistance(m.rectified(), B, c) < 1e-7);
    CHECK(m.rigidTransform().scale() == Approx(1.3));
    CHECK(std::fabs(std::remainder(m.rigidTransform().theta() + 2.6, 2 * M_PI)) < 1e-9);
  }
  // Without scale: rotation still exact, scale 1.
  const vpMorph m1(A, B, c, vpMorph::LEAST_SQUARES, false);
  CHECK(m1.rigidTransform().scale() == 1.0);
  CHECK(std::fabs(std::remainder(m1.rigidTransform().theta() + 2.6, 2 * M_PI)) < 1e-9);

  // The same with the correspondence found by vpMorphMatcher.
  const vpMorph mm(A, B);
  CHECK(mm.correspondence().inputSize() == A.size());
  CHECK(mm.distance() >= 0.0);
  CHECK(pairDistance(mm.rectified(), B, mm.correspondence()) < 1e-6);
  CHECK(sameContour(mm.sequence(6).back(), B));
}

TEST_CASE("vpMorph: a rigid part given by the caller rectifies the input and leads the rigid frames",
          "[morph][vpMorph]")
{
  const vpMorphContour A = keyShape().resampled(40);
  const vpMorphContour B = A.transformed(0.9, 20.0, -10.0, 1.1);
  const vpMorphCorrespondence c = vpMorphTest::shiftedIdentity(A.size(), 0);
  // A rigid part other than the least squares' (as a fit on the edges of an occluded view would give): kept as given.
  double cx, cy;
  A.centroid(cx, cy);
  const vpMorphRigidTransform given(0.8, 18.0, -12.0, 1.05, cx, cy);
  const vpMorph m(A, B, c, given);
  CHECK(m.estimator() == vpMorph::GIVEN);
  CHECK(m.rigidTransform().theta() == 0.8);
  CHECK(m.rigidTransform().scale() == 1.05);
  CHECK(sameContour(m.rectified(), given.apply(A)));
  const std::vector<vpMorphContour> frames = m.sequence(6);
  CHECK(pairDistance(frames[m.rigidFrameCount(6) - 1], given.apply(A), c) < 1e-9);
  CHECK(sameContour(frames.back(), B));
  // The least squares would have found the similarity itself, not the given part.
  CHECK(vpMorph(A, B, c).rigidTransform().scale() == Approx(1.1));
  // GIVEN without a rigid part is an error, as is a correspondence that does not fit the contours.
  CHECK_THROWS_AS(vpMorph(A, B, c, vpMorph::GIVEN), vpMorphException);
  CHECK_THROWS_AS(vpMorph(A, B.resampled(30), c, given), vpMorphException);
}

TEST_CASE("vpMorph: 180 deg rotation - rectification keeps the contours simple, plain Eq. 1 does not",
          "[morph][vpMorph]")
{
  const vpMorphContour key = keyShape();
  // Exact copy, same vertices: Eq. 1 with a 180 deg rotation is (1 - 2t) times the shape, so it shrinks
  // through a single point at t = 0.5 (in 2-D, (1-t) I + t R is itself a scaled rotation).
  {
    const vpMorphContour B = key.transformed(M_PI, 60.0, -20.0);
    const vpMorphCorrespondence c = vpMorphTest::shiftedIdentity(key.size(), 0);
    const vpMorph raw(key, B, c, vpMorph::NONE);
    CHECK(raw.rigidFrameCount(10) == 0);
    CHECK_THROWS_AS(raw.at(0.5), vpMorphException);
    CHECK(invalidFrames(raw, 10) > 0);
    CHECK(invalidFrames(vpMorph(key, B, c), 10) == 0);
    CHECK(invalidFrames(vpMorph(key, B, c, vpMorph::ELONGATION), 10) == 0);
  }
  // Two views sampled differently, with vertex noise, correspondence from vpMorphMatcher: near t = 0.5 the
  // plain morph is left with the sampling differences only, which cross over.
  std::mt19937 rng(1);
  int rawBad = 0, lsBad = 0, elBad = 0;
  const int trials = 10;
  for (int trial = 0; trial < trials; ++trial) {
    const double angle = M_PI - 0.02 * trial;
    const vpMorphContour A = vpMorphTest::noisy(key.resampled(36 + trial), rng, 0.5);
    const vpMorphContour B = vpMorphTest::noisy(key.transformed(angle, 40.0, 25.0).resampled(29).rotatedStart(7), rng, 0.5);
    const vpMorph ls(A, B);
    const vpMorph el(A, B, ls.correspondence(), vpMorph::ELONGATION);
    const vpMorph raw(A, B, ls.correspondence(), vpMorph::NONE);
    lsBad += invalidFrames(ls, 10);
    elBad += invalidFrames(el, 10);
    rawBad += invalidFrames(raw, 10) > 0;
  }
  std::printf("[morph validity, 180 deg, %d trials x 10 frames] invalid frames: least squares %d, elongation %d; "
              "plain Eq. 1 invalid in %d/%d morphs\n",
              trials, lsBad, elBad, rawBad, trials);
  CHECK(lsBad == 0);
  CHECK(elBad == 0);
  CHECK(rawBad == trials);
}

TEST_CASE("vpMorph: coincident consecutive vertices are merged", "[morph][vpMorph]")
{
  const vpMorphContour A = keyShape();
  const vpMorphContour B = A.transformed(0.4, 10.0, 5.0);
  std::vector<std::pair<std::size_t, std::size_t>> p = vpMorphTest::shiftedIdentity(A.size(), 0).pairs();
  p.insert(p.begin() + 4, p[3]); // pair 3 twice: the same point twice at every t
  const vpMorph m(A, B, vpMorphCorrespondence(A.size(), B.size(), p, 0, 0));
  CHECK(m.at(0.5).size() == A.size());
  CHECK(m.at(0.5).isSimple());
}

TEST_CASE("vpMorph: bad input is rejected with vpMorphException", "[morph][vpMorph]")
{
  const vpMorphContour A = keyShape();
  const vpMorphContour B = A.transformed(0.4, 10.0, 5.0);
  const vpMorphCorrespondence c = vpMorphTest::shiftedIdentity(A.size(), 0);
  const vpMorph m(A, B, c);
  CHECK_THROWS_AS(m.at(-0.01), vpMorphException);
  CHECK_THROWS_AS(m.at(1.01), vpMorphException);
  CHECK_THROWS_AS(m.at(std::numeric_limits<double>::quiet_NaN()), vpMorphException);
  CHECK_THROWS_AS(vpMorph(vpMorphContour(), B), vpMorphException);
  CHECK_THROWS_AS(vpMorph(A, vpMorphContour(), c), vpMorphException);
  CHECK_THROWS_AS(vpMorph(A, B, vpMorphTest::shiftedIdentity(A.size() - 1, 0)), vpMorphException);
  const vpMorphContour Bn(std::vector<double>{0.1, 0.2, 0.1}, std::vector<double>{0.0, 0.1, 0.2},
                          vpMorphContour::NORMALIZED);
  try {
    vpMorph bad(A, Bn);
    FAIL("mismatched units accepted");
  } catch (const vpMorphException &e) {
    CHECK(e.getCode() == vpMorphException::badParameterError);
  }
}
