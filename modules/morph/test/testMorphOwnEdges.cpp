// Tests of the object's own edges: the marks the extractor sets on an edge outline (vpMorphContour::ownEdge(): the
// background or the object itself beyond, not an occluder nor a bridge), how contours carry them, the background's
// level beside an occluder, and how the rigid check and the database use them (fit, unexplained share).
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphRigidCheck.h>
#include <visp3/morph/vpMorphRigidShape.h>

#include "../src/vpMorphOwnEdges.h"
#include "testMorphImages.h"

namespace
{
// \e m with Gaussian noise of std \e sigma (seeded), as a ViSP image.
vpImage<unsigned char> noisy(const cv::Mat &m, double sigma, unsigned int seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, sigma);
  vpImage<unsigned char> I(static_cast<unsigned int>(m.rows), static_cast<unsigned int>(m.cols));
  for (int v = 0; v < m.rows; ++v)
    for (int u = 0; u < m.cols; ++u)
      I[v][u] = cv::saturate_cast<unsigned char>(m.at<unsigned char>(v, u) + (sigma > 0.0 ? g(rng) : 0.0));
  return I;
}

// The distance of each pixel to the nearest pixel of \e m's grey level \e level (an occluder drawn at that level).
cv::Mat distanceTo(const cv::Mat &m, unsigned char level)
{
  cv::Mat d;
  cv::distanceTransform(m != level, d, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  return d;
}

// An octagon's vertices, counter-clockwise.
vpMorphContour octagon()
{
  std::vector<double> x, y;
  for (int k = 0; k < 8; ++k) {
    x.push_back(100.0 + 50.0 * std::cos(k * M_PI / 4.0));
    y.push_back(100.0 + 50.0 * std::sin(k * M_PI / 4.0));
  }
  return vpMorphContour(x, y);
}
} // namespace

TEST_CASE("contour: the own-edge marks follow their edges through the geometric operations", "[contour][own]")
{
  const std::vector<bool> marks{true, false, true, true, false, false, true, true};
  vpMorphContour c = octagon();
  CHECK_FALSE(c.hasOwnEdges());
  CHECK_FALSE(c.ownEdge(0)); // not measured
  c.setOwnEdges(marks);
  REQUIRE(c.hasOwnEdges());
  for (std::size_t k = 0; k < 8; ++k)
    CHECK(c.ownEdge(k) == marks[k]);
  // Re-ordered: vertex k of the result starts the edge that vertex (k + 3) % 8 started.
  const vpMorphContour r = c.rotatedStart(3);
  for (std::size_t k = 0; k < 8; ++k)
    CHECK(r.ownEdge(k) == marks[(k + 3) % 8]);
  // Reversed: the edge from new vertex j to j + 1 is the old edge between the same two vertices.
  const vpMorphContour b = c.reversed();
  for (std::size_t j = 0; j < 8; ++j) {
    std::size_t from = 8;
    for (std::size_t k = 0; k < 8; ++k)
      if (c.x(k) == b.x((j + 1) % 8) && c.y(k) == b.y((j + 1) % 8))
        from = k; // the old edge runs from the new vertex j + 1 to the new vertex j
    REQUIRE(from < 8);
    CHECK(b.ownEdge(j) == marks[from]);
  }
  // Resampled: each new vertex carries the mark of the old edge it lies on.
  const vpMorphContour s = c.resampled(40);
  REQUIRE(s.hasOwnEdges());
  for (std::size_t k = 0; k < s.size(); ++k) {
    std::size_t on = 0;
    double best = 1e9;
    for (std::size_t e = 0; e < 8; ++e) {
      const double d = vpMorphTest::segDist(c.x(e), c.y(e), c.x((e + 1) % 8), c.y((e + 1) % 8), s.x(k), s.y(k));
      if (d < best - 1e-9) {
        best = d;
        on = e;
      }
    }
    CHECK(s.ownEdge(k) == marks[on]);
  }
  // Moved, mirrored (and so reversed), set as an outline: kept.
  const vpMorphContour t = c.transformed(0.3, 5.0, -2.0, 1.5);
  for (std::size_t k = 0; k < 8; ++k)
    CHECK(t.ownEdge(k) == marks[k]);
  std::size_t own = 0;
  const vpMorphContour m = c.mirrored();
  for (std::size_t k = 0; k < 8; ++k)
    own += m.ownEdge(k);
  CHECK(own == 5);
  vpMorphContour parent = octagon();
  parent.setOutline(c);
  for (std::size_t k = 0; k < 8; ++k)
    CHECK(parent.outline().ownEdge(k) == marks[k]);
  // A mark per vertex, or none.
  CHECK_THROWS_AS(c.setOwnEdges(std::vector<bool>(7, true)), vpMorphException);
  c.setOwnEdges({});
  CHECK_FALSE(c.hasOwnEdges());
}

TEST_CASE("extractor: an occluder's edge is no edge of the object's own, the background and the object beyond are",
          "[extract][own]")
{
  int cards = 0; // views whose outline runs along the card
  for (const char *name : {"key", "wrench", "hammer"}) {
    const cv::Mat src = vpMorphTest::readObject(name);
    // The object's own outline: its pixels next to the background.
    cv::Mat nearBackground;
    cv::dilate(src == 255, nearBackground, cv::Mat());
    const cv::Mat toOutline = distanceTo((src == 0) & nearBackground, 255);
    for (double where : {0.15, 0.55}) {
      const cv::Mat hidden = vpMorphTest::squareOccluder(src, where, 0.2);
      const cv::Mat toCard = distanceTo(hidden, 170);
      for (double sigma : {3.0, 8.0}) {
        const vpMorphContour c = vpMorphContourExtractor().extractJoined(noisy(hidden, sigma, 11));
        const vpMorphContour &o = c.outline();
        REQUIRE(o.hasOwnEdges());
        // Next to the card (its pixels within 1.5 px) and off the object's own outline, an occluder's edge; away from
        // the card, beyond the reach of the patch read past the edge and of a stretch's end, the object's own.
        std::size_t card = 0, cardOwn = 0, free = 0, freeOwn = 0;
        for (std::size_t k = 0; k < o.size(); ++k) {
          const int u = static_cast<int>(std::lround(o.x(k))), v = static_cast<int>(std::lround(o.y(k)));
          const float d = toCard.at<float>(v, u);
          if (d <= 1.5f && toOutline.at<float>(v, u) >= 6.0f) {
            ++card;
            cardOwn += o.ownEdge(k);
          } else if (d >= 8.0f) {
            ++free;
            freeOwn += o.ownEdge(k);
          }
        }
        CAPTURE(name, where, sigma, card, cardOwn, free, freeOwn);
        // The card's edge on the outline: one stretch, whose two ends are within the patch's reach (4.5 px) of the
        // object's own edge for about as many points each.
        if (card >= 10) {
          ++cards;
          CHECK(cardOwn <= 10);
        }
        CHECK(freeOwn >= free - free / 100);
      }
    }
    // Seen whole: every edge its own, grooves (the object beyond) included.
    const vpMorphContour whole = vpMorphContourExtractor().extract(noisy(src, 8.0, 12));
    std::size_t own = 0;
    for (std::size_t k = 0; k < whole.outline().size(); ++k)
      own += whole.outline().ownEdge(k);
    CAPTURE(name);
    CHECK(own >= whole.outline().size() - whole.outline().size() / 100);
  }
  CHECK(cards >= 6);
}

TEST_CASE("extractor: a blurred object's outermost edges are its own, wherever the patch past them lies",
          "[extract][own]")
{
  // The patch read past each edge point lies beyond the edge's blur reach, several pixels out at a blur of 1.5 px:
  // past the outermost points, beyond any margin a box drawn about the object keeps, yet on the background. Levels
  // within the sensor's range (object 40, background 210, as the benchmark's scenes), so that the blur is measured.
  for (const char *name : {"key", "wrench", "hammer"})
    for (double blur : {1.0, 1.5, 2.0}) {
      cv::Mat levels, blurred;
      vpMorphTest::readObject(name).convertTo(levels, CV_8U, 170.0 / 255.0, 40.0);
      cv::GaussianBlur(levels, blurred, cv::Size(), blur);
      const vpMorphContour c = vpMorphContourExtractor().extract(noisy(blurred, 0.0, 1));
      const vpMorphContour &o = c.outline();
      REQUIRE(o.hasOwnEdges());
      std::size_t own = 0;
      for (std::size_t k = 0; k < o.size(); ++k)
        own += o.ownEdge(k);
      CAPTURE(name, blur, o.size(), own);
      // All but a point or two at the sharpest tips (the key's teeth at 2 px), whose measured edge the blur pulls
      // about a pixel inside the tip, and with it the patch towards the tip's spread.
      CHECK(own >= o.size() - o.size() / 100);
    }
}

TEST_CASE("own edges: views of a box read past it into their image, standalone copies stop at its border", "[own]")
{
  // A disc of radius 40 px blurred 1.5 px, its edge points every 5 deg, a box 6 px about it: the patches (reach 5 px,
  // 7.5 px out) of the points nearest the box's sides lie past it.
  cv::Mat image(200, 200, CV_8UC1, cv::Scalar(210)), mask(200, 200, CV_8UC1, cv::Scalar(0));
  cv::circle(image, cv::Point(100, 100), 40, cv::Scalar(40), cv::FILLED);
  cv::circle(mask, cv::Point(100, 100), 40, cv::Scalar(255), cv::FILLED);
  cv::GaussianBlur(image, image, cv::Size(), 1.5);
  std::vector<cv::Point2d> points, outward;
  for (int k = 0; k < 72; ++k) {
    const double a = k * M_PI / 36.0;
    outward.emplace_back(std::cos(a), std::sin(a));
    points.emplace_back(100.0 + 40.0 * std::cos(a), 100.0 + 40.0 * std::sin(a));
  }
  const cv::Rect box(54, 54, 93, 93);
  const std::vector<bool> views = vpMorphOwnEdges(image(box), mask(box), box.tl(), points, outward, 7.5, 5.0),
                          copies = vpMorphOwnEdges(image(box).clone(), mask(box).clone(), box.tl(), points, outward,
                                                   7.5, 5.0),
                          whole = vpMorphOwnEdges(image, mask, cv::Point(0, 0), points, outward, 7.5, 5.0);
  std::size_t cut = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    CAPTURE(k);
    CHECK(views[k]);
    CHECK(views[k] == whole[k]);
    const cv::Point2d p = points[k] + 7.5 * outward[k];
    const bool inside = p.x - 1.5 > box.x && p.y - 1.5 > box.y && p.x + 1.5 < box.x + box.width - 1 &&
                        p.y + 1.5 < box.y + box.height - 1;
    if (inside)
      CHECK(copies[k]);
    else
      cut += !copies[k];
  }
  CHECK(cut >= 4); // the four sides' nearest points at least: cut off where the copy ends
}

TEST_CASE("extractor: a comb's narrow grooves are its own edges, a bridge across a gap is not", "[extract][own]")
{
  // A comb: a 200 x 40 px back with ten teeth 60 px long, 8 px wide and 6 px apart (grooves narrower than the patch
  // read beyond an edge reaches: the object lies beyond).
  vpMorphTest::Poly comb;
  comb.x = {120, 320};
  comb.y = {200, 200};
  for (int t = 9; t >= 0; --t) {
    const double x0 = 180 + 14 * t;
    comb.x.insert(comb.x.end(), {x0 + 8, x0 + 8, x0, x0});
    comb.y.insert(comb.y.end(), {240, 300, 300, 240});
  }
  comb.x.push_back(120);
  comb.y.push_back(240);
  const vpMorphContour c = vpMorphContourExtractor().extract(vpMorphTest::render({comb}, 40, 210, 4.0, 5));
  std::size_t own = 0;
  for (std::size_t k = 0; k < c.outline().size(); ++k)
    own += c.outline().ownEdge(k);
  CHECK(own >= c.outline().size() - c.outline().size() / 100);

  // A bar cut in two by a 40 px gap of background: the pieces joined, the bridge no edge of its own.
  vpMorphTest::Poly left, right;
  left.x = {100, 300, 300, 100};
  left.y = {228, 228, 252, 252};
  right.x = {340, 500, 500, 340};
  right.y = {228, 228, 252, 252};
  const vpMorphContour joined = vpMorphContourExtractor().extractJoined(vpMorphTest::render({left, right}, 40, 210));
  const vpMorphContour &o = joined.outline();
  std::size_t across = 0, acrossOwn = 0;
  for (std::size_t k = 0; k < o.size(); ++k) {
    const std::size_t l = (k + 1) % o.size();
    if ((o.x(k) < 310 && o.x(l) > 330) || (o.x(l) < 310 && o.x(k) > 330)) {
      ++across;
      acrossOwn += o.ownEdge(k);
    }
  }
  CHECK(across == 2); // one edge over the gap on each side of the bar
  CHECK(acrossOwn == 0);
}

TEST_CASE("extractor: a card beside the object, in noise, does not pull the background's level nor the edges",
          "[extract][own]")
{
  // A 200 x 120 px rectangle (the object 40, the background 210) whose left 30 px a light-grey card (170) covers, in a
  // noise of 6 grey levels: the card lies 6.7 sigma off the background, within the 4 sigma window that a spread read
  // over both surfaces would give. The object's free edges stay where they are without the card.
  const vpMorphTest::Poly object{{200, 400, 400, 200}, {180, 180, 300, 300}};
  const vpImage<unsigned char> clean = vpMorphTest::render({object}, 40, 210);
  auto inwards = [&](bool card) { // the top and bottom edges' mean offset inwards, px, away from the card and corners
    cv::Mat m(480, 640, CV_8UC1);
    for (int v = 0; v < m.rows; ++v)
      for (int u = 0; u < m.cols; ++u)
        m.at<unsigned char>(v, u) = clean[v][u];
    if (card)
      cv::rectangle(m, cv::Point(150, 120), cv::Point(229, 360), cv::Scalar(170), cv::FILLED);
    double sum = 0.0;
    std::size_t n = 0;
    for (unsigned int seed = 0; seed < 4; ++seed) {
      const vpMorphContour c = vpMorphContourExtractor().extract(noisy(m, 6.0, 20 + seed));
      const vpMorphContour &o = c.outline();
      for (std::size_t k = 0; k < o.size(); ++k)
        if (o.x(k) > 240 && o.x(k) < 390) {
          sum += std::fabs(o.y(k) - 180.0) < 5.0 ? o.y(k) - 180.0 : 300.0 - o.y(k);
          ++n;
        }
    }
    REQUIRE(n > 500);
    return sum / n;
  };
  const double without = inwards(false), with = inwards(true);
  CAPTURE(without, with);
  CHECK(std::fabs(with - without) < 0.02);
}

TEST_CASE("rigid check: the view's own edge that the template lacks is unexplained, an occluder's edge is not",
          "[rigid][own]")
{
  // The key, the key with a tab 40 px long, and the key with a card over a fifth of its outline.
  const cv::Mat key = vpMorphTest::readObject("key");
  cv::Mat tabbed = key.clone();
  cv::rectangle(tabbed, cv::Point(300, 190), cv::Point(308, 230), cv::Scalar(0), cv::FILLED);
  const std::vector<cv::Point> boundary = vpMorphTest::largestBoundary(key);
  REQUIRE(cv::pointPolygonTest(boundary, cv::Point2f(304, 230), false) >= 0); // the tab grows out of the shaft
  const vpMorphRigidShape plain(vpMorphContourExtractor().extract(noisy(key, 3.0, 1)));
  const vpMorphRigidShape withTab(vpMorphContourExtractor().extract(noisy(tabbed, 3.0, 2)));
  const vpMorphContour cardView =
      vpMorphContourExtractor().extractJoined(noisy(vpMorphTest::squareOccluder(key, 0.4, 0.2), 3.0, 3));
  const vpMorphRigidShape carded(cardView);
  vpMorphContour unmarkedView = cardView, unmarkedOutline = cardView.outline();
  unmarkedOutline.setOwnEdges({});
  unmarkedView.setOutline(unmarkedOutline, cardView.outlineBlur());
  const vpMorphRigidShape keyTemplate(vpMorphContourExtractor().extract(noisy(key, 0.0, 0)));
  auto check = [&](const vpMorphRigidShape &view) {
    const vpMorphRigidCheck::Result r = vpMorphRigidCheck::check(view, keyTemplate, view.alignOn(keyTemplate));
    REQUIRE(r.fitted);
    return r;
  };
  const vpMorphRigidCheck::Result same = check(plain), tab = check(withTab), card = check(carded),
                                  unmarked = check(vpMorphRigidShape(unmarkedView));
  CAPTURE(same.unexplainedShare, tab.unexplainedShare, tab.inputShare, card.unexplainedShare, card.inputShare,
          card.targetShare, card.cost, unmarked.targetShare, unmarked.cost);
  CHECK(same.unexplainedShare < 0.01);
  CHECK(tab.unexplainedShare > 0.03);                         // the tab's sides and end
  CHECK(tab.unexplainedShare >= 1.0 - tab.inputShare - 0.01); // all it leaves unexplained is its own
  CHECK(card.inputShare < 0.9);                               // the card's edge, explained by no template...
  CHECK(card.unexplainedShare < 0.01);                        // ...and no edge of the key's own
  // Fitted on the view's own edges, not pulled by the card's: as much of the key shown as when fitted on them all.
  CHECK(card.targetShare >= unmarked.targetShare);
}

TEST_CASE("RIGID: a view whose own edge is mostly not the template's is refused, however much of it lies on it",
          "[rigid][own]")
{
  // A disc, and a ring cut from its rim, open by a slit, whose inner edge is a comb: teeth reaching far into the disc
  // lay most of the view's own edge inside the disc's region, where the disc has none (a coiled spring taken for an
  // apple). The same disc under a card is accepted.
  const cv::Point2d c(320.0, 240.0);
  const double R = 150.0;
  auto drawn = [](const std::vector<cv::Point> &poly) {
    cv::Mat m(480, 640, CV_8UC1, cv::Scalar(210));
    cv::fillPoly(m, std::vector<std::vector<cv::Point>>{poly}, cv::Scalar(40), cv::LINE_AA);
    cv::GaussianBlur(m, m, cv::Size(0, 0), 0.7);
    return m;
  };
  auto at = [&](double r, double deg) {
    const double a = deg * M_PI / 180.0;
    return cv::Point(static_cast<int>(std::lround(c.x + r * std::cos(a))),
                     static_cast<int>(std::lround(c.y + r * std::sin(a))));
  };
  std::vector<cv::Point> disc, comb;
  for (int k = 0; k < 360; ++k)
    disc.push_back(at(R, k));
  for (int k = 0; k <= 350; ++k) // the rim, but a slit of 10 deg
    comb.push_back(at(R, k));
  for (int k = 350; k >= 12; k -= 12) { // the comb, back along the inside: a tooth every 12 deg
    comb.push_back(at(0.85 * R, k));
    comb.push_back(at(0.30 * R, k - 4.0));
    comb.push_back(at(0.30 * R, k - 8.0));
    comb.push_back(at(0.85 * R, k - 12.0));
  }
  const vpMorphContour discView = vpMorphContourExtractor().extract(noisy(drawn(disc), 3.0, 1));
  const vpMorphContour combView = vpMorphContourExtractor().extract(noisy(drawn(comb), 3.0, 2));
  const vpMorphContour cardView =
      vpMorphContourExtractor().extractJoined(noisy(vpMorphTest::squareOccluder(drawn(disc), 0.3, 0.2), 3.0, 3));

  vpMorphDatabase db(vpMorphShapeDistance(vpMorphShapeDistance::RIGID));
  db.add(vpMorphTemplate("disc", discView));
  db.calibrate(1);
  // The comb lies on the disc as the other rules read it: nearly all the rim shown, nothing outside the disc, none of
  // the disc's outline absent from a view that hides nothing but the slit.
  const vpMorphRigidShape t(discView), q(combView);
  const vpMorphRigidCheck::Result r = vpMorphRigidCheck::check(q, t, q.alignOn(t));
  CAPTURE(r.targetShare, r.outsideShare, r.absentShare, r.unexplainedShare, r.inputShare);
  REQUIRE(r.fitted);
  CHECK(r.targetShare >= db.minimumSupport());
  CHECK(r.outsideShare <= vpMorphDatabase::maximumOutside());
  CHECK(r.absentShare <= vpMorphDatabase::maximumOutside());
  CHECK(r.unexplainedShare > 1.0 - db.minimumSupport());
  CHECK_FALSE(db.recognize(combView).accepted);
  CHECK(db.recognize(discView).accepted);
  CHECK(db.recognize(cardView).accepted);
}
