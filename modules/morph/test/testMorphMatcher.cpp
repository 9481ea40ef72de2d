// Tests of the minimal-work cyclic correspondence (vpMorphMatcher): exactness of the fast search against
// the brute-force reference, the windowed search, invariances and bad input.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>

#include <string>

#include <visp3/core/vpMath.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphMatcher.h>
#include <visp3/morph/vpMorphRigidTransform.h>

#include "testMorphShapes.h"

namespace
{
// Random star-shaped polygon: n vertices at sorted random angles with random radii around \e r.
vpMorphContour randomPolygon(std::mt19937 &rng, std::size_t n, double r = 100.0, double roughness = 0.4)
{
  std::uniform_real_distribution<double> ang(0.0, 2 * M_PI), rad(1.0 - roughness, 1.0 + roughness);
  std::vector<double> a(n);
  for (double &v : a)
    v = ang(rng);
  std::sort(a.begin(), a.end());
  std::vector<double> x(n), y(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double rr = r * rad(rng);
    x[k] = 320 + rr * std::cos(a[k]);
    y[k] = 240 + rr * std::sin(a[k]);
  }
  return vpMorphContour(x, y);
}

// The correspondence is a valid closed monotone path: steps of (1,0), (0,1), (1,1), every vertex used.
// Indices advance in the direction of positive signed area of their polygon.
void checkValid(const vpMorphCorrespondence &c, const vpMorphContour &A, const vpMorphContour &B)
{
  const std::size_t m = A.size(), n = B.size();
  const bool backA = A.signedArea() < 0, backB = B.signedArea() < 0;
  REQUIRE(c.inputSize() == m);
  REQUIRE(c.targetSize() == n);
  REQUIRE(c.size() >= std::max(m, n));
  REQUIRE(c.size() <= m + n);
  std::set<std::size_t> si, sj;
  const auto &p = c.pairs();
  std::size_t advA = 0, advB = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    si.insert(p[k].first);
    sj.insert(p[k].second);
    const auto &q = p[(k + 1) % p.size()];
    const std::size_t da = backA ? (p[k].first + m - q.first) % m : (q.first + m - p[k].first) % m;
    const std::size_t db = backB ? (p[k].second + n - q.second) % n : (q.second + n - p[k].second) % n;
    REQUIRE(da <= 1);
    REQUIRE(db <= 1);
    REQUIRE(da + db >= 1);
    advA += da;
    advB += db;
  }
  REQUIRE(advA == m);
  REQUIRE(advB == n);
  REQUIRE(si.size() == m);
  REQUIRE(sj.size() == n);
}
} // namespace

TEST_CASE("work model rejects bad stiffness", "[matcher]")
{
  REQUIRE_THROWS_AS(vpMorphWorkModel(0.0), vpMorphException);
  REQUIRE_THROWS_AS(vpMorphWorkModel(-1.0), vpMorphException);
  REQUIRE_THROWS_AS(vpMorphWorkModel(NAN), vpMorphException);
  REQUIRE_THROWS_AS(vpMorphWorkModel(1.0, -0.1), vpMorphException);
  REQUIRE_THROWS_AS(vpMorphWorkModel(1.0, 0.0), vpMorphException);
  REQUIRE_THROWS_WITH(vpMorphWorkModel(-2.0), Catch::Contains("ks must be finite and > 0"));
  REQUIRE_THROWS_AS(vpMorphWorkModel(1.0, NAN), vpMorphException);
  REQUIRE_THROWS_AS(vpMorphWorkModel(1.0, 0.1, 0.0), vpMorphException);
  REQUIRE_THROWS_AS(vpMorphWorkModel(1.0, 0.1, 1.5), vpMorphException);
  REQUIRE_NOTHROW(vpMorphWorkModel(2.0, 1e-6, 1.0));
  const vpMorphWorkModel w(1.0, 0.5, 0.5);
  CHECK(w.stretching(2.0, 2.0) == 0.0);
  CHECK(w.stretching(1.0, 3.0) == Approx(4.0 / (0.5 * 1 + 0.5 * 3)));
  CHECK(w.stretching(2.0, 0.0) == Approx(2.0 / 0.5)); // collapse: ks L / cs
  CHECK(w.bending(0.2, -0.3) == Approx(0.5 * 0.25));
}

TEST_CASE("fast exact search returns the brute-force minimum on 1000 random pairs", "[matcher][exact]")
{
  std::mt19937 rng(20261122);
  std::uniform_int_distribution<int> size(3, 40);
  std::uniform_real_distribution<double> ang(-M_PI, M_PI), unit(0.0, 1.0);
  vpMorphMatcher matcher;
  std::size_t withRelatedShapes = 0;
  for (int trial = 0; trial < 1000; ++trial) {
    vpMorphContour A = randomPolygon(rng, static_cast<std::size_t>(size(rng)));
    vpMorphContour B;
    if (trial % 3 == 0) {
      // Related shapes: B is A rotated, translated, scaled, noisy, resampled, or with another start.
      B = vpMorphTest::noisy(A, rng, 3.0 * unit(rng))
              .transformed(ang(rng), 50 * unit(rng), -30 * unit(rng), 0.5 + unit(rng));
      if (trial % 2 == 0)
        B = B.resampled(static_cast<std::size_t>(size(rng)));
      B = B.rotatedStart(static_cast<std::size_t>(size(rng)));
      ++withRelatedShapes;
    } else {
      B = randomPolygon(rng, static_cast<std::size_t>(size(rng)), 80.0, 0.6 * unit(rng) + 0.05);
    }
    if (trial % 5 == 0)
      B = B.reversed(); // opposite orientation is handled internally
    const vpMorphCorrespondence ref = matcher.matchBruteForce(A, B);
    const vpMorphCorrespondence fast = matcher.match(A, B);
    INFO("trial " << trial << ": m = " << A.size() << ", n = " << B.size());
    REQUIRE(fast.work() == Approx(ref.work()).epsilon(1e-9).margin(1e-12));
    if (trial % 50 == 0) {
      checkValid(fast, A, B);
      checkValid(ref, A, B);
    }
  }
  CHECK(withRelatedShapes > 300);
}

TEST_CASE("fast exact search returns the brute-force minimum on large polygons", "[matcher][exact]")
{
  // Large enough for every stage of the fast search: deep recursion, direct solving of narrow ranges and the
  // lower-bound pruning of ranges that cannot win.
  std::mt19937 rng(424242);
  std::uniform_int_distribution<int> size(60, 160);
  std::uniform_real_distribution<double> ang(-M_PI, M_PI), unit(0.0, 1.0);
  vpMorphMatcher matcher;
  for (int trial = 0; trial < 40; ++trial) {
    const vpMorphContour A = randomPolygon(rng, static_cast<std::size_t>(size(rng)));
    vpMorphContour B = trial % 2 ? randomPolygon(rng, static_cast<std::size_t>(size(rng)))
                                 : vpMorphTest::noisy(A, rng, 2.0)
                                       .transformed(ang(rng), 10, 10, 0.7 + unit(rng))
                                       .resampled(static_cast<std::size_t>(size(rng)));
    if (trial % 3 == 0)
      B = B.reversed();
    INFO("trial " << trial << ": m = " << A.size() << ", n = " << B.size());
    REQUIRE(matcher.match(A, B).work() == Approx(matcher.matchBruteForce(A, B).work()).epsilon(1e-9).margin(1e-12));
  }
}

TEST_CASE("minimum over the n starts (0, b) equals the minimum over all m n starting pairs", "[matcher][exact]")
{
  std::mt19937 rng(7);
  vpMorphMatcher matcher;
  for (int trial = 0; trial < 20; ++trial) {
    const vpMorphContour A = randomPolygon(rng, 5 + trial % 7), B = randomPolygon(rng, 4 + trial % 9);
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t a = 0; a < A.size(); ++a)
      for (std::size_t b = 0; b < B.size(); ++b) {
        const vpMorphCorrespondence c = matcher.matchFromStart(A, B, a, b);
        REQUIRE(c.start() == std::make_pair(a, b));
        best = std::min(best, c.work());
      }
    REQUIRE(matcher.matchBruteForce(A, B).work() == Approx(best).epsilon(1e-12));
  }
}

TEST_CASE("work of a correspondence is the sum of its stretching and bending", "[matcher]")
{
  std::mt19937 rng(3);
  vpMorphMatcher matcher;
  const vpMorphContour A = randomPolygon(rng, 17), B = randomPolygon(rng, 23);
  const vpMorphCorrespondence c = matcher.match(A, B);
  CHECK(c.stretchingWork() > 0.0);
  CHECK(c.bendingWork() > 0.0);
  CHECK(c.work() == Approx(c.stretchingWork() + c.bendingWork()));
  // The bending part of a correspondence is proportional to kb: evaluated on the same correspondence
  // (matchFromStart at the same starting pair, with the bending made negligible), doubling kb doubles it.
  const auto start = c.start();
  vpMorphMatcher k1(vpMorphWorkModel(1.0, 1e-3, 0.5)), k2(vpMorphWorkModel(1.0, 2e-3, 0.5));
  const vpMorphCorrespondence c1 = k1.matchFromStart(A, B, start.first, start.second);
  const vpMorphCorrespondence c2 = k2.matchFromStart(A, B, start.first, start.second);
  REQUIRE(c1.pairs() == c2.pairs());
  CHECK(c2.bendingWork() == Approx(2 * c1.bendingWork()));
  CHECK(c2.stretchingWork() == Approx(c1.stretchingWork()));
}

TEST_CASE("reported work is the documented model evaluated on the reported pairs", "[matcher]")
{
  // An independent evaluation of the model as vpMorphMatcher's documentation states it: polygons traversed
  // with positive area and scaled to unit perimeter; each step charges Eq. 2 on the segment it creates (0 on the
  // side that does not advance) and Eq. 3 on the turning at the new vertex (0 on the side that does not advance).
  std::mt19937 rng(77);
  const vpMorphWorkModel model(1.3, 0.07, 0.4);
  vpMorphMatcher matcher(model);
  for (int trial = 0; trial < 30; ++trial) {
    vpMorphContour A = randomPolygon(rng, 5 + trial % 17), B = randomPolygon(rng, 4 + trial % 23);
    if (trial % 2)
      B = B.reversed();
    const vpMorphCorrespondence c = matcher.match(A, B);
    const vpMorphContour Ap = A.counterClockwise(), Bp = B.counterClockwise();
    const double sA = 1.0 / A.perimeter(), sB = 1.0 / B.perimeter();
    // Index of caller vertex k in the positive traversal (reversed() keeps vertex 0 first).
    auto posA = [&](std::size_t k) { return A.isCounterClockwise() ? k : (A.size() - k) % A.size(); };
    auto posB = [&](std::size_t k) { return B.isCounterClockwise() ? k : (B.size() - k) % B.size(); };
    double work = 0.0;
    const auto &p = c.pairs();
    for (std::size_t k = 0; k < p.size(); ++k) {
      const auto &q = p[(k + 1) % p.size()];
      const bool advA = q.first != p[k].first, advB = q.second != p[k].second;
      const std::size_t ia = posA(q.first), jb = posB(q.second);
      const double lA = advA ? Ap.edgeLength(ia) * sA : 0.0, lB = advB ? Bp.edgeLength(jb) * sB : 0.0;
      const double fA = advA ? Ap.turningAngle(ia) : 0.0, fB = advB ? Bp.turningAngle(jb) : 0.0;
      work += model.stretching(lA, lB) + model.bending(fA, fB);
    }
    INFO("trial " << trial);
    CHECK(c.work() == Approx(work).epsilon(1e-9));
  }
}

TEST_CASE("windowed search is exact within its window", "[matcher][window]")
{
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> size(6, 30);
  vpMorphMatcher matcher;
  for (int trial = 0; trial < 200; ++trial) {
    const vpMorphContour A = randomPolygon(rng, static_cast<std::size_t>(size(rng)));
    vpMorphContour B = randomPolygon(rng, static_cast<std::size_t>(size(rng)));
    if (trial % 4 == 0)
      B = B.reversed();
    const std::size_t n = B.size();
    const std::size_t a = static_cast<std::size_t>(trial) % A.size();
    const std::size_t center = static_cast<std::size_t>(trial * 7) % n, half = 1 + trial % 4;
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t d = 0; d <= 2 * half; ++d) {
      const std::size_t b = (center + n - half + d) % n;
      best = std::min(best, matcher.matchFromStart(A, B, a, b).work());
    }
    const vpMorphCorrespondence w = matcher.matchWindow(A, B, a, center, half);
    INFO("trial " << trial);
    REQUIRE(w.work() == Approx(best).epsilon(1e-9));
    REQUIRE(w.start().first == a);
    const std::size_t off = (w.start().second + n - (center + n - half) % n) % n;
    REQUIRE(off <= 2 * half);
    // The window never does better than the global optimum, and a full window finds it.
    REQUIRE(w.work() >= matcher.match(A, B).work() - 1e-12);
    REQUIRE(matcher.matchWindow(A, B, 0, center, n).work() == Approx(matcher.match(A, B).work()));
  }
}

TEST_CASE("windowed search on pixel-grid polygons: tied optima traced crossing", "[matcher][window]")
{
  // Two measured silhouettes whose bounding paths, traced among tied optima, cross: the band between them is empty
  // (it once sized a table negatively).
  std::ifstream in((std::filesystem::path(__FILE__).parent_path() / "data" / "crossing-window.txt").string());
  std::string line;
  while (in.peek() == '#')
    std::getline(in, line);
  std::size_t m = 0, n = 0, a = 0, center = 0, half = 0;
  REQUIRE(static_cast<bool>(in >> m >> n >> a >> center >> half));
  auto read = [&](std::size_t k) {
    std::vector<double> x(k), y(k);
    for (std::size_t i = 0; i < k; ++i) {
      REQUIRE(static_cast<bool>(in >> x[i] >> y[i]));
      x[i] /= 800.0;
      y[i] /= 800.0;
    }
    return vpMorphContour(x, y, vpMorphContour::NORMALIZED);
  };
  const vpMorphContour A = read(m), B = read(n);
  vpMorphMatcher matcher;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t d = 0; d <= 2 * half; ++d)
    best = std::min(best, matcher.matchFromStart(A, B, a, (center + n - half + d) % n).work());
  CHECK(vpMorphMatcher().matchWindow(A, B, a, center, half).work() == Approx(best).epsilon(1e-9));
  CHECK(matcher.matchWindow(A, B, a, center, half).work() == Approx(best).epsilon(1e-9));
}

TEST_CASE("morph distance invariances", "[matcher][invariance]")
{
  std::mt19937 rng(5);
  vpMorphMatcher matcher;
  for (int trial = 0; trial < 20; ++trial) {
    const vpMorphContour A = randomPolygon(rng, 12 + trial), B = randomPolygon(rng, 20 + trial % 5);
    const double d = matcher.distance(A, B);
    SECTION("identity") { CHECK(matcher.distance(A, A) == Approx(0.0).margin(1e-12)); }
    CHECK(matcher.distance(A, A) == Approx(0.0).margin(1e-12));
    CHECK(d > 0.0);
    // Translation and rotation of either shape.
    CHECK(matcher.distance(A.transformed(0.0, 123.0, -45.0), B) == Approx(d).epsilon(1e-9));
    CHECK(matcher.distance(A, B.transformed(2.1 + trial, 0.0, 0.0)) == Approx(d).epsilon(1e-9));
    // Starting vertex.
    CHECK(matcher.distance(A.rotatedStart(trial % A.size()), B.rotatedStart(3)) == Approx(d).epsilon(1e-9));
    // Traversal direction.
    CHECK(matcher.distance(A.reversed(), B) == Approx(d).epsilon(1e-9));
    // Scale, normalised for recognition.
    CHECK(matcher.distance(A.transformed(0.0, 0.0, 0.0, 3.7), B.transformed(0.0, 0.0, 0.0, 0.4)) ==
          Approx(d).epsilon(1e-9));
    // Symmetry.
    CHECK(matcher.distance(B, A) == Approx(d).epsilon(1e-9));
  }
  // Without scale normalisation the work is in pixel units and changes with scale.
  vpMorphMatcher raw(vpMorphWorkModel(), false);
  const vpMorphContour A = randomPolygon(rng, 15), B = randomPolygon(rng, 18);
  CHECK(raw.distance(A, B.transformed(0.0, 0.0, 0.0, 2.0)) != Approx(raw.distance(A, B)));
}

TEST_CASE("a shape and a noisy rotated copy are closer than two different shapes", "[matcher]")
{
  std::mt19937 rng(9);
  vpMorphMatcher matcher;
  int ok = 0;
  for (int trial = 0; trial < 50; ++trial) {
    const vpMorphContour A = randomPolygon(rng, 24), B = randomPolygon(rng, 24);
    const vpMorphContour A2 =
        vpMorphTest::noisy(A, rng, 1.0).transformed(1.0 + trial, 10, 20, 1.3).rotatedStart(trial % 24);
    if (matcher.distance(A, A2) < matcher.distance(A, B))
      ++ok;
  }
  CHECK(ok >= 48);
}

TEST_CASE("correspondence of a copy with another start is the shifted identity", "[matcher]")
{
  std::mt19937 rng(1);
  vpMorphMatcher matcher;
  const vpMorphContour A = randomPolygon(rng, 20);
  const vpMorphContour B = A.transformed(2.5, 40, -10, 1.5).rotatedStart(7);
  const vpMorphCorrespondence c = matcher.match(A, B);
  CHECK(c.work() == Approx(0.0).margin(1e-9));
  REQUIRE(c.size() == 20);
  for (const auto &p : c.pairs())
    CHECK((p.second + 7) % 20 == p.first);
  // Opposite traversal: indices are reported in B's own numbering.
  const vpMorphContour R = A.reversed();
  const vpMorphCorrespondence r = matcher.match(A, R);
  CHECK(r.work() == Approx(0.0).margin(1e-9));
  for (const auto &p : r.pairs())
    CHECK((20 - p.second) % 20 == p.first);
}

TEST_CASE("matcher bad input gives a clear error", "[matcher][bad-input]")
{
  vpMorphMatcher matcher;
  const vpMorphContour A({0.0, 10.0, 0.0}, {0.0, 0.0, 10.0});
  REQUIRE_THROWS_AS(matcher.match(A, vpMorphContour()), vpMorphException);
  REQUIRE_THROWS_AS(matcher.match(vpMorphContour(), A), vpMorphException);
  REQUIRE_THROWS_AS(matcher.matchFromStart(A, A, 3, 0), vpMorphException);
  REQUIRE_THROWS_AS(matcher.matchWindow(A, A, 0, 5, 1), vpMorphException);
  const vpMorphContour N({0.0, 0.1, 0.0}, {0.0, 0.0, 0.1}, vpMorphContour::NORMALIZED);
  REQUIRE_THROWS_AS(matcher.match(A, N), vpMorphException);
  REQUIRE_THROWS_WITH(matcher.match(A, N), Catch::Contains("units"));
}

namespace
{
vpMorphContour objectContour(const std::string &file)
{
  vpImage<unsigned char> I;
  vpImageIo::read(I, std::string(VISPMORPH_DATA_DIR) + "/objects/" + file);
  return vpMorphContourExtractor().extract(I);
}

double fittedDegrees(const vpMorphContour &A, const vpMorphContour &B, const vpMorphCorrespondence &c)
{
  return vpMath::deg(vpMorphRigidTransform::fitLeastSquares(A, B, c, true).theta());
}
} // namespace

TEST_CASE("matchOnRegions: a deformed view is matched the way its region lies on the target's", "[matcher][regions]")
{
  vpMorphMatcher matcher;
  // The sagging wedge: its minimal work lies half a turn round (measured -155 deg), under which no rigid move lays
  // its region on the template's.
  const vpMorphContour bent = objectContour("wedge-deformed.png"), wedge = objectContour("wedge.png");
  const vpMorphCorrespondence least = matcher.match(bent, wedge);
  REQUIRE(std::fabs(fittedDegrees(bent, wedge, least)) > 90.0);
  double gain = -1.0;
  const vpMorphCorrespondence placed = matcher.matchOnRegions(bent, wedge, 0.1, &gain);
  CHECK(gain > 0.1);
  CHECK(std::fabs(fittedDegrees(bent, wedge, placed)) < 15.0);
  CHECK(placed.work() >= least.work());
  // Turned by 120 deg, the same.
  const vpMorphContour turned = vpMorphRigidTransform(vpMath::rad(120.0), 15.0, -8.0, 1.1, 320, 240).apply(bent);
  const vpMorphCorrespondence placedTurned = matcher.matchOnRegions(turned, wedge, 0.1, &gain);
  CHECK(gain > 0.1);
  CHECK(std::fabs(std::remainder(fittedDegrees(turned, wedge, placedTurned) + 120.0, 360.0)) < 15.0);
  // A demand above what the other placement wins keeps the minimal work.
  CHECK(matcher.matchOnRegions(bent, wedge, 0.5, &gain).work() == Approx(least.work()).epsilon(1e-12));
  CHECK(gain == 0.0);
}

TEST_CASE("matchOnRegions keeps the minimal work where it lays the regions best", "[matcher][regions]")
{
  vpMorphMatcher matcher;
  for (const std::string name : {"hammer", "key", "pliers", "screwdriver", "wedge", "wrench"}) {
    const vpMorphContour object = objectContour(name + ".png");
    for (const std::string &file : {name + ".png", name + "-deformed.png"}) {
      INFO(file);
      // Rigid views (here turned by 170 deg) and the other deformed objects: the minimal work is already right.
      if (file == "wedge-deformed.png")
        continue;
      const vpMorphContour view =
          vpMorphRigidTransform(vpMath::rad(170.0), 5.0, 3.0, 0.9, 320, 240).apply(objectContour(file));
      double gain = -1.0;
      const vpMorphCorrespondence checked = matcher.matchOnRegions(view, object, 0.1, &gain);
      const vpMorphCorrespondence least = matcher.match(view, object);
      CHECK(gain == 0.0);
      CHECK(checked.start() == least.start());
      CHECK(checked.work() == Approx(least.work()).epsilon(1e-12));
    }
  }
}

TEST_CASE("matchOnRegions bad input gives a clear error", "[matcher][regions][bad-input]")
{
  vpMorphMatcher matcher;
  const vpMorphContour A({0.0, 10.0, 0.0}, {0.0, 0.0, 10.0});
  for (const double g : {0.0, -0.1, 1.5, std::nan("")})
    REQUIRE_THROWS_WITH(matcher.matchOnRegions(A, A, g), Catch::Contains("minGain"));
  REQUIRE_THROWS_AS(matcher.matchOnRegions(A, vpMorphContour()), vpMorphException);
}

TEST_CASE("contour validation rejects degenerate polygons", "[contour][bad-input]")
{
  REQUIRE_THROWS_AS((vpMorphContour({0.0, 1.0}, {0.0, 1.0})), vpMorphException);
  REQUIRE_THROWS_AS((vpMorphContour({0.0, 1.0, 2.0}, {0.0, 1.0})), vpMorphException);
  REQUIRE_THROWS_AS((vpMorphContour({0.0, NAN, 2.0}, {0.0, 1.0, 0.0})), vpMorphException);
  REQUIRE_THROWS_AS((vpMorphContour({0.0, INFINITY, 2.0}, {0.0, 1.0, 0.0})), vpMorphException);
  REQUIRE_THROWS_AS((vpMorphContour({0.0, 1.0, 1.0, 0.0}, {0.0, 0.0, 0.0, 1.0})), vpMorphException); // repeated
  REQUIRE_THROWS_AS((vpMorphContour({0.0, 1.0, 2.0, 3.0}, {0.0, 1.0, 2.0, 3.0})), vpMorphException); // collinear
  REQUIRE_THROWS_WITH(vpMorphContour(std::vector<double>{0.0, 1.0, 2.0}, std::vector<double>{0.0, 1.0, 2.0}),
                      Catch::Contains("collinear"));
  // A bow tie is a valid contour but not simple.
  const vpMorphContour bow({0.0, 10.0, 10.0, 0.0}, {0.0, 10.0, 0.0, 20.0});
  CHECK_FALSE(bow.isSimple());
  CHECK(vpMorphContour({0.0, 10.0, 10.0, 0.0}, {0.0, 0.0, 10.0, 10.0}).isSimple());
  const vpMorphContour sq({0.0, 10.0, 10.0, 0.0}, {0.0, 0.0, 10.0, 10.0});
  REQUIRE_THROWS_AS(sq.transformed(NAN, 0, 0), vpMorphException);
  REQUIRE_THROWS_AS(sq.transformed(0, 0, 0, 0.0), vpMorphException);
  REQUIRE_THROWS_AS(sq.resampled(2), vpMorphException);
}
