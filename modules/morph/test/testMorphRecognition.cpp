// Tests of recognition by morph distance (vpMorphDatabase::recognize): calibrated acceptance of the six
// generated objects under rotation, translation, image noise and 15 % occlusion of their outline, rejection of
// unknown objects, exactness of the pruned search against the exhaustive one, the lower bound, batch work on
// several threads with progress, and the named distance models.
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphShapeDistance.h>

#include "testMorphImages.h"

namespace
{
const char *kObjects[] = {"key", "pliers", "wedge", "wrench", "screwdriver", "hammer"};

std::string objectPath(const std::string &name)
{
  return std::string(VISPMORPH_DATA_DIR) + "/objects/" + name + ".png";
}

cv::Mat readGray(const std::string &path)
{
  cv::Mat m = cv::imread(path, cv::IMREAD_GRAYSCALE);
  REQUIRE_FALSE(m.empty());
  return m;
}

vpImage<unsigned char> toVisp(const cv::Mat &m)
{
  vpImage<unsigned char> I(static_cast<unsigned int>(m.rows), static_cast<unsigned int>(m.cols));
  for (int v = 0; v < m.rows; ++v)
    for (int u = 0; u < m.cols; ++u)
      I[v][u] = m.at<unsigned char>(v, u);
  return I;
}

vpMorphContour extract(const cv::Mat &m) { return vpMorphContourExtractor().extract(toVisp(m)); }

// The pieces of an object that an occluder split, joined across the occluder (as the benchmark's silhouettes).
vpMorphContour extractJoined(const cv::Mat &m) { return vpMorphContourExtractor().extractJoined(toVisp(m)); }

// The database of the six objects, built from their images (calibrated once per process), with the MULTISCALE
// distance: these tests pin the D_morph recognition (thresholds, support, re-ranking); RIGID is tested in
// testMorphRigid.cpp.
const vpMorphDatabase &objectDatabase()
{
  static vpMorphDatabase db = [] {
    vpMorphDatabase d(vpMorphShapeDistance(vpMorphShapeDistance::MULTISCALE));
    for (const char *n : kObjects)
      d.add(vpMorphTemplate(n, extract(readGray(objectPath(n))), objectPath(n)));
    d.calibrate();
    return d;
  }();
  return db;
}

// A new view: the object image rotated by deg about its centre and translated by (tx, ty) px (white background
// comes in from the borders), with Gaussian grey-level noise of std sigma.
cv::Mat view(const cv::Mat &src, double deg, double tx, double ty, double sigma, unsigned int seed)
{
  cv::Mat R = cv::getRotationMatrix2D(cv::Point2f(src.cols / 2.f, src.rows / 2.f), deg, 1.0);
  R.at<double>(0, 2) += tx;
  R.at<double>(1, 2) += ty;
  cv::Mat out;
  cv::warpAffine(src, out, R, src.size(), cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(255));
  if (sigma > 0) {
    cv::Mat noise(out.size(), CV_32F);
    cv::RNG rng(seed);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, sigma);
    cv::Mat f;
    out.convertTo(f, CV_32F);
    f += noise;
    f.convertTo(out, CV_8U);
  }
  return out;
}

using vpMorphTest::largestBoundary;
using vpMorphTest::squareOccluder;

// Hides \e fraction of the object's outline, the contiguous arc starting at \e where (fraction of the
// perimeter), behind an occluder of the background colour with a straight edge: the region between the arc and
// its chord is painted white, so that the chord replaces the arc in the new outline.
cv::Mat occlude(const cv::Mat &src, double where, double fraction)
{
  const std::vector<cv::Point> c = largestBoundary(src);
  const std::size_t a = static_cast<std::size_t>(where * c.size()) % c.size();
  const std::size_t len = static_cast<std::size_t>(fraction * c.size());
  std::vector<cv::Point> piece;
  for (std::size_t k = 0; k <= len; ++k)
    piece.push_back(c[(a + k) % c.size()]);
  cv::Mat out = src.clone();
  cv::fillPoly(out, std::vector<std::vector<cv::Point>>{piece}, cv::Scalar(255));
  cv::polylines(out, std::vector<std::vector<cv::Point>>{piece}, false, cv::Scalar(255), 2);
  return out;
}

// A shape that is none of the six tools: a filled star or a crescent.
cv::Mat unknownObject(int kind)
{
  cv::Mat m(480, 640, CV_8UC1, cv::Scalar(255));
  if (kind == 0) {
    std::vector<cv::Point> star;
    for (int k = 0; k < 10; ++k) {
      const double r = k % 2 ? 60 : 150, a = k * M_PI / 5;
      star.emplace_back(static_cast<int>(320 + r * std::cos(a)), static_cast<int>(240 + r * std::sin(a)));
    }
    cv::fillPoly(m, std::vector<std::vector<cv::Point>>{star}, cv::Scalar(0));
  } else {
    cv::circle(m, cv::Point(320, 240), 120, cv::Scalar(0), cv::FILLED);
    cv::circle(m, cv::Point(380, 220), 110, cv::Scalar(255), cv::FILLED);
  }
  return m;
}
} // namespace

TEST_CASE("recognition: each template is accepted under rotation, translation, noise and 15 % occlusion",
          "[recognition]")
{
  const vpMorphDatabase &db = objectDatabase();
  REQUIRE(db.isCalibrated());
  for (std::size_t k = 0; k < db.size(); ++k) {
    const cv::Mat src = readGray(objectPath(kObjects[k]));
    struct Case
    {
      const char *what;
      cv::Mat img;
    };
    const Case cases[] = {
        {"rotated 73 deg, translated (40, -25) px", view(src, 73, 40, -25, 0, 0)},
        {"rotated -150 deg, noise sigma 12", view(src, -150, -30, 20, 12, 7)},
        {"rotated 200 deg, noise sigma 20", view(src, 200, 10, 10, 20, 8)},
        {"15 % of the outline occluded (first place)", occlude(view(src, 30, 0, 0, 0, 0), 0.1, 0.15)},
        {"15 % of the outline occluded (second place)", occlude(view(src, -60, 15, 5, 8, 9), 0.6, 0.15)},
    };
    for (const Case &c : cases) {
      const vpMorphRecognition r = db.recognize(extract(c.img));
      CAPTURE(kObjects[k], c.what, r.distance, r.threshold, r.secondDistance, db[r.index].name(), r.support);
      CHECK(r.index == k);
      CHECK(r.accepted);
      CHECK(r.margin > 0.0);
    }
  }
}

TEST_CASE("recognition: objects that are not in the database are rejected", "[recognition]")
{
  const vpMorphDatabase &db = objectDatabase();
  for (int kind = 0; kind < 2; ++kind) {
    const vpMorphRecognition r = db.recognize(extract(unknownObject(kind)));
    CAPTURE(kind, r.distance, r.threshold, db[r.index].name());
    CHECK_FALSE(r.accepted);
  }
  // A tool left out of the database is not taken for one of the others.
  vpMorphDatabase five(objectDatabase().distance());
  for (int k = 0; k < 5; ++k)
    five.add(objectDatabase()[static_cast<std::size_t>(k)]);
  five.calibrate();
  const vpMorphRecognition r = five.recognize(extract(readGray(objectPath("hammer"))));
  CAPTURE(r.distance, r.threshold, five[r.index].name());
  CHECK_FALSE(r.accepted);
}

TEST_CASE("recognition: among candidate outlines of one view, the one a template explains best", "[recognition]")
{
  const vpMorphDatabase &db = objectDatabase();
  const vpMorphContour star = extract(unknownObject(0)), crescent = extract(unknownObject(1));
  for (std::size_t k = 0; k < db.size(); ++k) {
    const cv::Mat src = readGray(objectPath(kObjects[k]));
    const vpMorphContour clean = extract(view(src, 73, 40, -25, 0, 0));
    const vpMorphContour hidden = extract(occlude(view(src, 30, 0, 0, 0, 0), 0.1, 0.15));
    std::size_t chosen = 99;
    const vpMorphRecognition r = db.recognize({star, clean, crescent}, chosen);
    CAPTURE(kObjects[k], r.distance, r.threshold);
    CHECK(chosen == 1);
    CHECK(r.index == k);
    CHECK(r.accepted);
    // Two accepted candidates: the smaller share of its threshold wins, whatever the order.
    const vpMorphRecognition a = db.recognize(clean), b = db.recognize(hidden);
    REQUIRE(a.accepted);
    REQUIRE(b.accepted);
    const std::size_t better = a.distance / a.threshold <= b.distance / b.threshold ? 0 : 1;
    (void)db.recognize({clean, hidden}, chosen);
    CHECK(chosen == better);
    (void)db.recognize({hidden, clean}, chosen);
    CHECK(chosen == 1 - better);
  }
  // None accepted: the first candidate's answer, rejected.
  std::size_t chosen = 99;
  const vpMorphRecognition none = db.recognize({crescent, star}, chosen);
  CHECK(chosen == 0);
  CHECK_FALSE(none.accepted);
  CHECK(none.index == db.recognize(crescent).index);
  CHECK_THROWS_AS(db.recognize(std::vector<vpMorphContour>(), chosen), vpMorphException);
  CHECK_THROWS_AS(db.recognize({star, vpMorphContour()}, chosen), vpMorphException);
}

TEST_CASE("recognition: a view with a square bitten out of its outline is accepted by its support", "[recognition]")
{
  const vpMorphDatabase &db = objectDatabase();
  vpMorphDatabase distanceOnly = db;
  distanceOnly.setMinimumSupport(std::numeric_limits<double>::infinity());
  int byDistance = 0, bySupport = 0, wrongByDistance = 0, reranked = 0, correct = 0;
  for (std::size_t k = 0; k < db.size(); ++k) {
    const cv::Mat src = readGray(objectPath(kObjects[k]));
    for (double where : {0.1, 0.35, 0.6, 0.85})
      for (double share : {0.1, 0.15}) {
        const vpMorphContour c = extractJoined(squareOccluder(view(src, 40.0 * where, 10, -5, 4, 3), where, share));
        const vpMorphRecognition r = db.recognize(c);
        const vpMorphRecognition d = distanceOnly.recognize(c);
        CAPTURE(kObjects[k], where, share, r.distance, r.threshold, r.support, db[r.index].name(), r.reranked,
                db[d.index].name());
        CHECK(std::isnan(d.support)); // not measured with the support off
        CHECK(std::isfinite(r.support));
        if (d.accepted) {
          ++byDistance;
          wrongByDistance += d.index != k ? 1 : 0;
          if (!r.accepted) { // only a view that shows almost nothing of its template
            CHECK(r.support < db.supportFloor());
            CHECK(r.index != k);
          }
        } else if (r.accepted) {
          ++bySupport;
        }
        if (r.reranked) {
          // Re-ranked: the distance's choice showed too little of its outline, the new one enough.
          ++reranked;
          CHECK(r.secondIndex == d.index);
          CHECK(r.support >= db.minimumSupport());
          CHECK(r.margin == 0.0);
          CHECK(r.index == k);
        }
        if (r.accepted && r.distance > r.threshold) {
          // What the support accepts is the object shown, and it shows most of its outline.
          CHECK(r.index == k);
          CHECK(r.support >= db.minimumSupport());
        }
        correct += r.accepted && r.index == k ? 1 : 0;
      }
  }
  // Why the support is there: the distance alone rejects some of these views (a notch costs far more work than
  // the calibration's straight edges) and takes others for another tool; the support accepts the first and puts
  // the right tool in place of the wrong one where the view shows enough of the right tool's outline.
  std::printf("[recognition] square occluders: %d of 48 views accepted by the distance (%d as another tool), %d more "
              "by the support; %d re-ranked; %d recognised as the right tool\n",
              byDistance, wrongByDistance, bySupport, reranked, correct);
  CHECK(bySupport > 0);
  CHECK(wrongByDistance > 0);
  CHECK(reranked > 0);
  CHECK(byDistance + bySupport >= 46); // of 48
  CHECK(correct >= 46);
  // It accepts nothing that is not one of the tools: the unknown shapes show little of their best template.
  for (int kind = 0; kind < 2; ++kind) {
    const vpMorphRecognition r = db.recognize(extract(unknownObject(kind)));
    CAPTURE(kind, r.distance, r.threshold, r.support, db[r.index].name());
    CHECK_FALSE(r.accepted);
    CHECK(r.support < 0.5);
  }
}

TEST_CASE("recognition: a view whose notch throws the correspondence off shows its outline by the shapes' alignment",
          "[recognition]")
{
  const vpMorphDatabase &db = objectDatabase();
  // A card hiding a fifth of the screwdriver's outline (a square bite) and a straight edge hiding a fifth of the key's:
  // about 0.8 of each outline shows, but the minimal-work correspondence matches the notch somewhere and its fit shows
  // 0.60 and 0.63. The outline shapes' alignment, voted by the parts that show, puts the view in place.
  const std::size_t screwdriver = db.find("screwdriver"), key = db.find("key");
  const vpMorphContour bitten =
      extractJoined(squareOccluder(view(readGray(objectPath("screwdriver")), 30, 10, -5, 4, 3), 0.75, 0.2));
  const vpMorphContour cut = extract(occlude(view(readGray(objectPath("key")), 34, 10, -5, 4, 3), 0.85, 0.2));
  for (const auto &[c, k] : {std::make_pair(bitten, screwdriver), std::make_pair(cut, key)}) {
    const vpMorphRecognition r = db.recognize(c);
    CAPTURE(db[k].name(), r.distance, r.threshold, r.support, db[r.index].name(), r.mirrored);
    CHECK(db.support(c, k) >= db.minimumSupport());
    CHECK(db.support(c, k) < 0.9);
    CHECK(r.accepted);
    CHECK(r.index == k);
    CHECK(r.support == db.support(c, k, r.mirrored));
  }
  // Below the minimum, the correspondence's share stands: the best of more alignments would show more of any template,
  // and the floor that rejects an unknown shape is set for one. A fifth of the pliers' outline bitten off: the
  // distance takes the view for the wedge, whose outline it does not show (rejected).
  const vpMorphContour jaw =
      extractJoined(squareOccluder(view(readGray(objectPath("pliers")), 34, 10, -5, 4, 3), 0.85, 0.2));
  const vpMorphRecognition r = db.recognize(jaw);
  CAPTURE(r.distance, r.threshold, r.support, db[r.index].name());
  CHECK(db[r.index].name() == "wedge");
  CHECK(r.distance <= r.threshold);
  CHECK(r.support < db.supportFloor());
  CHECK_FALSE(r.accepted);
}

TEST_CASE("recognition: support and acceptance of a given template, and bad input", "[recognition]")
{
  const vpMorphDatabase &db = objectDatabase();
  const std::size_t key = db.find("key"), wedge = db.find("wedge");
  const vpMorphContour c = extract(view(readGray(objectPath("key")), 120, 5, 5, 6, 2));
  CHECK(db.support(c, key) > 0.95);
  // Fitted either way, about half of the wedge's outline comes within 2 px of the key's (0.51): short of the 0.75 that
  // an occluded view shows.
  CHECK(db.support(c, wedge) < 0.6);
  double d = -1.0;
  CHECK(db.accepts(c, key, 1.0, &d));
  CHECK(d == Approx(db.distance().distance(c, db[key].contour())));
  CHECK_FALSE(db.accepts(c, wedge));
  // The slack widens the distance's side only.
  CHECK(db.accepts(c, wedge, 100.0));
  // A part turned over: its mirror image is aligned when asked (as recognize() does when the mirror matched).
  const vpMorphContour turned = c.mirrored();
  CHECK(db.support(turned, key, true) > 0.95);
  CHECK(db.accepts(turned, key));
  // The wedge is nearly symmetric end for end: with a card on its upper side, the minimal-work correspondence puts
  // the view the wrong way round (0.19 of the outline on the template's from there); it is also tried half a turn
  // round.
  cv::Mat w = readGray(objectPath("wedge"));
  int top = 0;
  while (top < w.rows && w.at<unsigned char>(top, 340) >= 128)
    ++top;
  cv::rectangle(w, cv::Point(340 - 26, top - 26), cv::Point(340 + 26, top + 26), cv::Scalar(170), cv::FILLED);
  CHECK(db.support(extract(w), wedge) > 0.85);
  CHECK_THROWS_AS(db.support(vpMorphContour(), key), vpMorphException);
  CHECK_THROWS_AS(db.support(c, 99), vpMorphException);
  const vpMorphContour normalized(c.xs(), c.ys(), vpMorphContour::NORMALIZED);
  CHECK_THROWS_AS(db.support(normalized, key), vpMorphException);
  CHECK_THROWS_AS(db.accepts(c, key, 0.5), vpMorphException);
  CHECK_THROWS_AS(db.accepts(c, key, std::nan("")), vpMorphException);
  CHECK_THROWS_AS(db.accepts(vpMorphContour(), key), vpMorphException);
  vpMorphDatabase copy = db;
  CHECK(copy.minimumSupport() == 0.75);
  for (double bad : {0.0, -0.5, 1.5, std::nan("")})
    CHECK_THROWS_AS(copy.setMinimumSupport(bad), vpMorphException);
  copy.setMinimumSupport(1.0);
  CHECK(copy.minimumSupport() == 1.0);
}

TEST_CASE("recognition: the calibration follows the documented rule", "[recognition]")
{
  const vpMorphDatabase &db = objectDatabase();
  const std::vector<double> &w = db.withinDistances(), &b = db.betweenDistances();
  REQUIRE(w.size() == db.size());
  REQUIRE(b.size() == db.size());
  for (std::size_t k = 0; k < db.size(); ++k) {
    CAPTURE(db[k].name(), w[k], b[k]);
    CHECK(w[k] > 0.0);
    CHECK(std::isfinite(b[k]));
    CHECK(db.threshold(k) == Approx(vpMorphDatabase::calibrationSlack() * w[k]));
    // within(t) is the worst of its perturbations.
    double worst = 0.0;
    for (const vpMorphContour &p : vpMorphDatabase::perturbations(db[k].contour()))
      worst = std::max(worst, db.distance().distance(p, db[k].contour()));
    CHECK(w[k] == Approx(worst));
  }
  // Overridable by one value; a calibration afterwards keeps the user's value.
  vpMorphDatabase copy = db;
  copy.setThreshold(1e-9);
  CHECK(copy.isThresholdManual());
  CHECK(copy.recognize(db[0].contour()).accepted); // distance 0
  // A new view is beyond that threshold, but it shows the whole outline: the support accepts it, unless disabled.
  const vpMorphContour other = extract(view(readGray(objectPath(kObjects[0])), 40, 0, 0, 10, 1));
  const vpMorphRecognition bySupport = copy.recognize(other);
  CHECK(bySupport.accepted);
  CHECK(bySupport.support > 0.95);
  copy.setMinimumSupport(std::numeric_limits<double>::infinity());
  const vpMorphRecognition byDistance = copy.recognize(other);
  CHECK_FALSE(byDistance.accepted);
  CHECK(std::isnan(byDistance.support));
  copy.calibrate();
  CHECK(copy.threshold(0) == 1e-9);
  copy.clearThreshold();
  CHECK(copy.threshold(0) == db.threshold(0));
  CHECK_THROWS_AS(copy.setThreshold(-1.0), vpMorphException);
  CHECK_THROWS_AS(copy.setThreshold(std::nan("")), vpMorphException);
  CHECK_THROWS_AS(copy.threshold(99), vpMorphException);
}

TEST_CASE("recognition: the calibration occludes a template in normalised units as one in pixels", "[recognition]")
{
  // A template taught in the metric image plane (x = X/Z) is a few hundredths wide: its occluding edges must
  // not be rounded to whole units, which would hide nothing and calibrate its threshold on whole outlines.
  const vpMorphContour px = extract(readGray(objectPath("key")));
  std::vector<double> x = px.xs(), y = px.ys();
  for (std::size_t k = 0; k < x.size(); ++k)
    x[k] = (x[k] - 320.0) / 800.0, y[k] = (y[k] - 240.0) / 800.0;
  const vpMorphContour normalized(x, y, vpMorphContour::NORMALIZED);
  const std::vector<vpMorphContour> p = vpMorphDatabase::perturbations(px),
                                    q = vpMorphDatabase::perturbations(normalized);
  REQUIRE(p.size() == q.size());
  REQUIRE(p.size() > 16);
  // The last sixteen copies are the occluded ones. Their renderings' scales differ between the units, so each
  // copy's area is compared with the largest of them (the least hidden): the edges hide as much in both units.
  auto shares = [](const std::vector<vpMorphContour> &v) {
    std::vector<double> a;
    for (std::size_t k = v.size() - 16; k < v.size(); ++k)
      a.push_back(v[k].area());
    const double most = *std::max_element(a.begin(), a.end());
    for (double &x : a)
      x = 1.0 - x / most;
    return a;
  };
  const std::vector<double> a = shares(p), b = shares(q);
  for (std::size_t k = 0; k < a.size(); ++k) {
    CAPTURE(k, a[k], b[k]);
    CHECK(b[k] == Approx(a[k]).margin(0.03));
  }
  CHECK(*std::max_element(a.begin(), a.end()) > 0.2);
}

TEST_CASE("recognition: the pruned search equals the exhaustive search", "[recognition]")
{
  // 24 templates and 40 queries: noisy, rotated, occluded views of the tools and of their deformed variants,
  // under the paper's resampled model (mirrors) and the default polygon model.
  std::vector<vpMorphContour> images;
  for (const char *n : kObjects) {
    images.push_back(extract(readGray(objectPath(n))));
    images.push_back(extract(readGray(objectPath(std::string(n) + "-deformed"))));
  }
  std::vector<vpMorphContour> queries;
  std::mt19937 rng(3);
  for (std::size_t k = 0; k < 40; ++k) {
    const std::string n = kObjects[k % 6];
    const cv::Mat src = readGray(objectPath(k % 12 < 6 ? n : n + "-deformed"));
    std::uniform_real_distribution<double> u(-180, 180);
    cv::Mat v = view(src, u(rng), 0, 0, 10, static_cast<unsigned int>(k));
    if (k % 3 == 0)
      v = occlude(v, (k % 7) / 7.0, 0.1);
    queries.push_back(extract(v));
  }
  for (int model = 0; model < 2; ++model) {
    vpMorphDatabase db(vpMorphShapeDistance(model ? vpMorphShapeDistance::PAPER : vpMorphShapeDistance::POLYGON));
    for (std::size_t k = 0; k < images.size(); ++k) {
      db.add(vpMorphTemplate("t" + std::to_string(k), images[k]));
      // Variants of the same outlines, to make near ties.
      db.add(vpMorphTemplate("r" + std::to_string(k), images[k].rotatedStart(3).transformed(0.3, 5, 5, 1.5)));
    }
    std::size_t evaluated = 0, total = 0;
    for (const vpMorphContour &q : queries) {
      const vpMorphRecognition a = db.recognize(q, true), b = db.recognize(q, false);
      CHECK(a.index == b.index);
      CHECK(a.distance == b.distance);
      CHECK(a.secondIndex == b.secondIndex);
      CHECK(a.secondDistance == b.secondDistance);
      CHECK(a.mirrored == b.mirrored);
      CHECK(a.accepted == b.accepted);
      CHECK(a.correspondence.pairs() == b.correspondence.pairs());
      evaluated += a.evaluated;
      total += b.evaluated;
    }
    // The bound must actually prune something to be worth its cost.
    CAPTURE(model, evaluated, total);
    CHECK(evaluated < total);
    WARN("pruned search, model " << db.distance().name() << ": " << evaluated << " of " << total
                                 << " distances computed");
  }
}

TEST_CASE("recognition: the lower bound never exceeds the distance", "[recognition]")
{
  std::vector<vpMorphContour> cs;
  for (const char *n : kObjects) {
    cs.push_back(extract(readGray(objectPath(n))));
    cs.push_back(extract(readGray(objectPath(std::string(n) + "-deformed"))));
  }
  for (vpMorphShapeDistance::Model m :
       {vpMorphShapeDistance::POLYGON, vpMorphShapeDistance::PAPER, vpMorphShapeDistance::MULTISCALE}) {
    const vpMorphShapeDistance d(m);
    vpMorphMatcher matcher = d.matcher();
    const std::vector<vpMorphShapeDistance::Shape> s = d.prepareAll(cs);
    for (std::size_t i = 0; i < s.size(); ++i)
      for (std::size_t j = 0; j < s.size(); ++j) {
        const double lb = d.lowerBound(s[i], s[j]), dist = d.distance(s[i], s[j], matcher);
        CAPTURE(d.name(), i, j, lb, dist);
        CHECK(lb >= 0.0);
        CHECK(lb <= dist);
      }
  }
}

TEST_CASE("recognition: batch work on two threads equals serial work and reports progress", "[recognition]")
{
  std::vector<vpMorphContour> cs;
  for (const char *n : kObjects) {
    cs.push_back(extract(readGray(objectPath(n))));
    cs.push_back(extract(readGray(objectPath(std::string(n) + "-deformed"))));
  }
  const vpMorphShapeDistance d(vpMorphShapeDistance::PAPER);
  const std::vector<vpMorphShapeDistance::Shape> s = d.prepareAll(cs, 2);
  std::size_t lastDone = 0, lastTotal = 0, calls = 0;
  bool monotone = true;
  const std::vector<double> D2 = d.matrix(s, 2, [&](std::size_t done, std::size_t total) {
    monotone = monotone && done >= lastDone;
    lastDone = done;
    lastTotal = total;
    ++calls;
  });
  const std::vector<double> D1 = d.matrix(s, 1);
  CHECK(D1 == D2);
  CHECK(monotone);
  CHECK(calls >= 1);
  CHECK(lastTotal == cs.size() * (cs.size() - 1) / 2);
  CHECK(lastDone == lastTotal);
  const std::size_t N = cs.size();
  vpMorphMatcher matcher = d.matcher();
  for (std::size_t i = 0; i < N; ++i) {
    CHECK(D2[i * N + i] == 0.0);
    for (std::size_t j = 0; j < N; ++j)
      CHECK(D2[i * N + j] == D2[j * N + i]);
  }
  CHECK(D2[1] == d.distance(s[0], s[1], matcher));

  // recognizeAll on two threads equals recognize one by one.
  const vpMorphDatabase &db = objectDatabase();
  const std::vector<vpMorphRecognition> rs = db.recognizeAll(cs, 2);
  REQUIRE(rs.size() == cs.size());
  for (std::size_t k = 0; k < cs.size(); ++k) {
    const vpMorphRecognition r = db.recognize(cs[k]);
    CHECK(rs[k].index == r.index);
    CHECK(rs[k].distance == r.distance);
  }
  // A failing job is reported once all threads stopped.
  std::atomic<int> ran(0);
  CHECK_THROWS_AS(d.parallelFor(50, 2,
                                [&](std::size_t k, vpMorphMatcher &) {
                                  ++ran;
                                  if (k == 3)
                                    throw vpMorphException(vpMorphException::badParameterError, "job 3");
                                }),
                  vpMorphException);
}

TEST_CASE("recognition: distance models by name, and bad input", "[recognition]")
{
  for (const char *n : {"polygon", "paper", "multiscale", "rigid", "height"})
    CHECK(vpMorphShapeDistance::fromName(n).name() == n);
  CHECK(vpMorphDatabase().distance().name() == "multiscale"); // the default
  CHECK_FALSE(vpMorphShapeDistance::fromName("rigid").mirrors());
  CHECK(vpMorphShapeDistance::fromName("paper").points() == 64);
  CHECK(vpMorphShapeDistance::fromName("paper").mirrors());
  CHECK_FALSE(vpMorphShapeDistance::fromName("polygon").mirrors());
  CHECK_THROWS_AS(vpMorphShapeDistance::fromName("bogus"), vpMorphException);
  vpMorphShapeDistance p(vpMorphShapeDistance::PAPER);
  CHECK_THROWS_AS(p.setPoints(3), vpMorphException);
  CHECK_THROWS_AS(p.setScales({}), vpMorphException);
  CHECK_THROWS_AS(p.setScales({-0.1}), vpMorphException);

  // Invariance of the distance: the same outline moved, turned, scaled and listed from another vertex. Exact for
  // the polygons; resampled models only approximately (the samples fall elsewhere on the outline): 0.25 here,
  // against 1.18 from the key to its nearest other tool.
  const vpMorphContour key = extract(readGray(objectPath("key")));
  for (const vpMorphShapeDistance &d :
       {vpMorphShapeDistance(vpMorphShapeDistance::POLYGON), vpMorphShapeDistance(vpMorphShapeDistance::MULTISCALE)})
    CHECK(d.distance(key, key.transformed(1.0, 30, -12, 2.0).rotatedStart(key.size() / 3)) ==
          Approx(0.0).margin(d.model() == vpMorphShapeDistance::POLYGON ? 1e-9 : 0.3));

  vpMorphDatabase empty;
  CHECK_THROWS_AS(empty.recognize(key), vpMorphException);
  CHECK_THROWS_AS(empty.calibrate(), vpMorphException);
  CHECK_THROWS_AS(objectDatabase().recognize(vpMorphContour()), vpMorphException);
}

TEST_CASE("recognition: a part turned over is recognised as the mirror image of its template", "[recognition]")
{
  const vpMorphDatabase &db = objectDatabase();
  const std::size_t k = db.find("wrench");
  REQUIRE(k != vpMorphRecognition::npos);
  const vpMorphRecognition r = db.recognize(db[k].contour().mirrored().transformed(2.0, 10, 20, 0.7));
  CHECK(r.index == k);
  CHECK(r.mirrored);
  CHECK(r.accepted);
  // Without mirror images, the turned-over part is no longer the same shape.
  vpMorphShapeDistance noMirror = db.distance();
  noMirror.setMirrors(false);
  CHECK(noMirror.distance(db[k].contour(), db[k].contour().mirrored()) > 10 * r.distance);
}

TEST_CASE("recognition: unknown shapes that the distance accepts show little of the template and are rejected",
          "[recognition][datasets]")
{
  const vpMorphDatabase &db = objectDatabase();
  REQUIRE(db.supportFloor() == 0.5);
  vpMorphDatabase noFloor = db;
  noFloor.setSupportFloor(0.0);
  // Kimia-99 shapes that are none of the six tools but cost the distance little work: a fish (taken for the wrench)
  // and six 'kk' silhouettes (taken for the screwdriver).
  const std::string dir = std::string(VISPMORPH_DATASETS_DIR) + "/kimia99/";
  int byDistance = 0, rejected = 0;
  for (const char *f :
       {"fish14.png", "kk0729.png", "kk0732.png", "kk0735.png", "kk0737.png", "kk0740.png", "kk0741.png"}) {
    const cv::Mat m = cv::imread(dir + f, cv::IMREAD_GRAYSCALE);
    if (m.empty()) {
      WARN("Kimia-99 image " << dir + f << " not found: dataset test skipped");
      return;
    }
    const vpMorphContour c = extract(m);
    const vpMorphRecognition loose = noFloor.recognize(c), r = db.recognize(c);
    CAPTURE(f, r.distance, r.threshold, r.support, db[r.index].name());
    CHECK(r.index == loose.index);
    CHECK(r.support == loose.support);
    byDistance += loose.accepted ? 1 : 0;
    if (loose.accepted && !r.accepted) {
      ++rejected;
      CHECK(r.distance <= r.threshold); // within the threshold: the floor rejected it
      CHECK(r.support < db.supportFloor());
    }
  }
  std::printf("[recognition] Kimia-99: %d of 7 unknown shapes accepted by the distance, %d of them rejected by the "
              "support floor\n",
              byDistance, rejected);
  CHECK(byDistance >= 5);
  CHECK(rejected == byDistance);
  // Bad floors.
  vpMorphDatabase copy = db;
  for (double bad : {-0.1, 1.5, std::nan("")})
    CHECK_THROWS_AS(copy.setSupportFloor(bad), vpMorphException);
}

TEST_CASE("recognition: nearest neighbours on a few Kimia-99 silhouettes, read in place", "[recognition][datasets]")
{
  const std::string dir = std::string(VISPMORPH_DATASETS_DIR) + "/kimia99/";
  // Three images of each of four classes (classes.csv of the dataset).
  const char *files[] = {"fish14.png", "fish23.png", "herrings.png", "f15.png",   "f16.png",   "harrier.png",
                         "tool04.png", "tool07.png", "tool08.png",   "dude0.png", "dude1.png", "dude2.png"};
  std::vector<vpMorphContour> cs;
  for (const char *f : files) {
    const cv::Mat m = cv::imread(dir + f, cv::IMREAD_GRAYSCALE);
    if (m.empty()) {
      WARN("Kimia-99 image " << dir + f << " not found: dataset test skipped");
      return;
    }
    cs.push_back(extract(m));
  }
  for (const char *model : {"paper", "multiscale", "height"}) {
    const vpMorphShapeDistance d = vpMorphShapeDistance::fromName(model);
    const std::vector<double> D = d.matrix(d.prepareAll(cs));
    const std::size_t N = cs.size();
    std::size_t correct = 0;
    for (std::size_t i = 0; i < N; ++i) {
      std::size_t best = i == 0 ? 1 : 0;
      for (std::size_t j = 0; j < N; ++j)
        if (j != i && D[i * N + j] < D[i * N + best])
          best = j;
      correct += best / 3 == i / 3;
    }
    CAPTURE(model, correct);
    CHECK(correct >= 10);
    if (d.model() == vpMorphShapeDistance::HEIGHT)
      CHECK(correct == 12); // every nearest neighbour: a limb's length and place tell these classes apart
  }
}
