// Tests of vpMorphHeightFunction: invariance to a similarity, to the start and the traversal of the outline, mirror
// images, what tells shapes apart, the candidate starts against the exact search, the model in
// vpMorphShapeDistance, and bad input.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphHeightFunction.h>
#include <visp3/morph/vpMorphShapeDistance.h>

#include "testMorphShapes.h"

namespace
{
vpMorphContour polygon(const std::vector<double> &xy)
{
  std::vector<double> x, y;
  for (std::size_t k = 0; k + 1 < xy.size(); k += 2) {
    x.push_back(xy[k]);
    y.push_back(xy[k + 1]);
  }
  return vpMorphContour(x, y).resampled(240);
}

// An L (asymmetric: its mirror image is another shape for a planar part), a T, and a T whose stem is twice as long.
vpMorphContour lShape() { return polygon({0, 0, 40, 0, 40, 10, 10, 10, 10, 60, 0, 60}); }
vpMorphContour tShape() { return polygon({0, 0, 60, 0, 60, 10, 35, 10, 35, 40, 25, 40, 25, 10, 0, 10}); }
vpMorphContour longT() { return polygon({0, 0, 60, 0, 60, 10, 35, 10, 35, 80, 25, 80, 25, 10, 0, 10}); }

double dist(const vpMorphHeightFunction &h, const vpMorphContour &a, const vpMorphContour &b, bool *m = nullptr)
{
  return h.distance(h.describe(a), h.describe(b), m);
}
} // namespace

TEST_CASE("vpMorphHeightFunction: a similarity, another start and the other traversal change the distance little",
          "[height]")
{
  const vpMorphHeightFunction h;
  for (const vpMorphContour &c : {lShape(), tShape()}) {
    CHECK(dist(h, c, c) == 0.0);
    CHECK(dist(h, c, c.transformed(1.0, 30, -12, 2.5)) == Approx(0.0).margin(1e-6));
    // Another start: the samples fall elsewhere on the outline (a third of their spacing here), so the distance is
    // small, not 0 (other shapes: about 0.2).
    const vpMorphContour moved = c.transformed(1.0, 30, -12, 2.5).rotatedStart(c.size() / 3);
    const double d = dist(h, c, moved), reversed = dist(h, c, c.reversed().rotatedStart(17));
    CAPTURE(d, reversed);
    CHECK(d < 0.05);
    CHECK(reversed < 0.05);
    CHECK(dist(h, moved, c) == Approx(d).margin(1e-5)); // symmetric
  }
}

TEST_CASE("vpMorphHeightFunction: mirror images, and what tells shapes apart", "[height]")
{
  vpMorphHeightFunction h;
  const vpMorphContour L = lShape();
  bool mirrored = false;
  const double mirror = dist(h, L, L.mirrored().transformed(0.4, 0, 0, 0.7), &mirrored);
  CHECK(mirror < 0.02);
  CHECK(mirrored);
  CHECK_FALSE([&] {
    bool m = true;
    dist(h, L, L.transformed(0.4, 0, 0, 0.7), &m);
    return m;
  }());
  vpMorphHeightFunction direct = h;
  direct.setMirrors(false);
  CHECK(dist(direct, L, L.mirrored()) > 5.0 * (mirror + 0.01));

  // Noise of 0.3 % of the size on the outline costs far less than a stem twice as long or another shape.
  std::mt19937 rng(100);
  const vpMorphContour T = tShape();
  const double noisy = dist(h, T, vpMorphTest::noisy(T, rng, 0.2)), stem = dist(h, T, longT()), other = dist(h, T, L);
  CAPTURE(noisy, stem, other);
  CHECK(2.0 * noisy < stem);
  CHECK(2.0 * noisy < other);
}

TEST_CASE("vpMorphHeightFunction: the candidate starts never beat the exact search over every start", "[height]")
{
  vpMorphHeightFunction exact;
  exact.setCandidateStarts(0);
  const vpMorphHeightFunction fast;
  std::mt19937 rng(101);
  const std::vector<vpMorphContour> shapes = {lShape(), tShape(), longT(), vpMorphTest::noisy(tShape(), rng, 1.0),
                                              lShape().transformed(2.0, 3, 4, 0.5).rotatedStart(50)};
  for (std::size_t i = 0; i < shapes.size(); ++i)
    for (std::size_t j = 0; j < shapes.size(); ++j) {
      const double e = dist(exact, shapes[i], shapes[j]), f = dist(fast, shapes[i], shapes[j]);
      CAPTURE(i, j, e, f);
      CHECK(e <= f);
      // The same shape moved or noisy: its start is a candidate, the distance the exact one.
      if ((i == 0 && j == 4) || (i == 1 && j == 3))
        CHECK(f == Approx(e).epsilon(1e-6));
    }
}

TEST_CASE("vpMorphHeightFunction: the HEIGHT model of vpMorphShapeDistance, and bad input", "[height]")
{
  vpMorphShapeDistance d = vpMorphShapeDistance::fromName("height");
  CHECK(d.name() == "height");
  CHECK(d.model() == vpMorphShapeDistance::HEIGHT);
  CHECK(d.points() == 100);
  CHECK(d.mirrors());
  CHECK(d.lowerBound(d.prepare(lShape()), d.prepare(tShape())) == 0.0);
  const vpMorphHeightFunction h;
  CHECK(d.distance(lShape(), tShape()) == dist(h, lShape(), tShape()));
  d.setPoints(120);
  CHECK(d.heightFunction().getPoints() == 120);
  CHECK_THROWS_AS(d.setPoints(110), vpMorphException); // 20 segments do not divide 110 points
  d.setMirrors(false);
  CHECK_FALSE(d.heightFunction().getMirrors());
  bool mirrored = true;
  vpMorphMatcher m = d.matcher();
  d.distance(d.prepare(lShape()), d.prepare(lShape().mirrored()), m, -1.0, &mirrored);
  CHECK_FALSE(mirrored);
  // The settings a database file and a benchmark summary record: the height model's own only for it.
  const std::string settings = d.settingsJson();
  CHECK(settings.find("\"model\":\"height\"") != std::string::npos);
  CHECK(settings.find("\"points\":120") != std::string::npos);
  CHECK(settings.find("\"segments\":20") != std::string::npos);
  CHECK(settings.find("\"mirrors\":false") != std::string::npos);
  CHECK(vpMorphShapeDistance::fromName("multiscale").settingsJson().find("segments") == std::string::npos);

  vpMorphHeightFunction bad;
  CHECK_THROWS_AS(bad.setPoints(4, 2), vpMorphException);
  CHECK_THROWS_AS(bad.setPoints(100, 1), vpMorphException);
  CHECK_THROWS_AS(bad.setPoints(100, 30), vpMorphException);
  CHECK_THROWS_AS(bad.setSkipCost(0.0), vpMorphException);
  CHECK_THROWS_AS(bad.setSkipCost(std::nan("")), vpMorphException);
  CHECK_THROWS_AS(bad.setSkipCost(std::numeric_limits<double>::infinity()), vpMorphException);
  CHECK_THROWS_AS(bad.describe(vpMorphContour()), vpMorphException);
  CHECK_THROWS_AS(bad.describe(vpMorphContour({0, 1, 2}, {0, 1, 2})), vpMorphException); // zero area
  vpMorphHeightFunction other;
  other.setPoints(120, 20);
  CHECK_THROWS_AS(h.distance(h.describe(lShape()), other.describe(lShape())), vpMorphException);
  CHECK_THROWS_AS(d.prepare(vpMorphContour()), vpMorphException);
}
