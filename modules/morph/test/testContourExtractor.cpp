// Tests of the automatic contour extraction (vpMorphContourExtractor) and of the parameterless polygonal
// approximation (vpMorphPolygonApproximation): polarity, colour, regions, noise stability, accuracy, border,
// datasets and bad input.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <string>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpImageConvert.h>
#include <visp3/core/vpMath.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphPolygonApproximation.h>
#include <visp3/morph/vpMorphRigidTransform.h>

#include "../src/vpMorphPixelChain.h"
#include "testMorphImages.h"

namespace
{
using vpMorphTest::blurred;
using vpMorphTest::distToOutline;
using vpMorphTest::Poly;
using vpMorphTest::readObject;
using vpMorphTest::render;
using vpMorphTest::segDist;
using vpMorphTest::similarity;
using vpMorphTest::testPolygon;
using vpMorphTest::warp;

// Largest distance from the polygon c (sampled along its edges) to the outline (X, Y).
double maxDistTo(const vpMorphContour &c, const std::vector<double> &X, const std::vector<double> &Y)
{
  double h = 0.0;
  for (std::size_t k = 0; k < c.size(); ++k) {
    const std::size_t k1 = (k + 1) % c.size();
    for (int s = 0; s <= 20; ++s) {
      const double t = s / 20.0;
      h = std::max(h, distToOutline(X, Y, c.x(k) + t * (c.x(k1) - c.x(k)), c.y(k) + t * (c.y(k1) - c.y(k))));
    }
  }
  return h;
}

vpImage<vpRGBa> toRGBa(const vpImage<unsigned char> &I, bool tint)
{
  vpImage<vpRGBa> C(I.getHeight(), I.getWidth());
  for (unsigned int r = 0; r < I.getHeight(); ++r)
    for (unsigned int c = 0; c < I.getWidth(); ++c) {
      const unsigned char v = I[r][c];
      C[r][c] = tint ? vpRGBa(v, static_cast<unsigned char>(v / 2), static_cast<unsigned char>(255 - v / 2))
                     : vpRGBa(v, v, v);
    }
  return C;
}

bool readPng(const std::string &file, vpImage<unsigned char> &I)
{
  const cv::Mat m = cv::imread(file, cv::IMREAD_GRAYSCALE);
  if (m.empty())
    return false;
  vpImageConvert::convert(m, I);
  return true;
}

void checkValid(const vpMorphContour &c)
{
  REQUIRE(c.size() >= 3);
  CHECK(c.units() == vpMorphContour::PIXEL);
  CHECK(c.isSimple());
  CHECK(c.signedArea() > 0.0);
}
} // namespace

TEST_CASE("extractor: dark object on light background and light on dark give the same polygon", "[extract]")
{
  const Poly p = testPolygon();
  const vpMorphContour dark = vpMorphContourExtractor().extract(render({p}, 30, 220));
  const vpMorphContour light = vpMorphContourExtractor().extract(render({p}, 220, 30));
  checkValid(dark);
  checkValid(light);
  CHECK(dark.size() == 10);
  CHECK(light.size() == dark.size());
  CHECK(dark.area() == Approx(light.area()).epsilon(0.01));
  CHECK(maxDistTo(dark, p.x, p.y) < 1.5);
  CHECK(maxDistTo(light, p.x, p.y) < 1.5);
  // The polygon covers the object (within the digitisation inset).
  double trueArea = 0.0;
  for (std::size_t k = 0; k < p.x.size(); ++k) {
    const std::size_t k1 = (k + 1) % p.x.size();
    trueArea += 0.5 * (p.x[k] * p.y[k1] - p.x[k1] * p.y[k]);
  }
  CHECK(dark.area() == Approx(std::fabs(trueArea)).epsilon(0.02));
}

TEST_CASE("extractor: grey and RGBa images agree", "[extract]")
{
  const vpImage<unsigned char> I = render({testPolygon(300, 250, 0.7)}, 40, 200);
  const vpMorphContour g = vpMorphContourExtractor().extract(I);
  const vpMorphContour c = vpMorphContourExtractor().extract(toRGBa(I, false));
  const vpMorphContour t = vpMorphContourExtractor().extract(toRGBa(I, true));
  checkValid(g);
  checkValid(c);
  checkValid(t);
  CHECK(c.size() == g.size());
  CHECK(c.area() == Approx(g.area()).epsilon(0.01));
  CHECK(t.area() == Approx(g.area()).epsilon(0.02));
  CHECK(vpMorphContourExtractor().boundary(toRGBa(I, false)).size() == vpMorphContourExtractor().boundary(I).size());
}

TEST_CASE("extractor: largest object first, extractAll returns every region", "[extract]")
{
  Poly small, big = testPolygon(380, 260);
  // A 40 x 30 rectangle (top left) and a triangle (bottom left).
  small.x = {20, 60, 60, 20};
  small.y = {20, 20, 50, 50};
  Poly tri;
  tri.x = {30, 110, 40};
  tri.y = {400, 440, 460};
  const vpImage<unsigned char> I = render({small, big, tri}, 0, 255);
  const vpMorphContourExtractor ex;
  const vpMorphContour largest = ex.extract(I);
  const std::vector<vpMorphContour> all = ex.extractAll(I);
  REQUIRE(all.size() == 3);
  for (const vpMorphContour &c : all)
    checkValid(c);
  CHECK(all[0].area() == Approx(largest.area()));
  CHECK(all[0].area() > all[1].area());
  CHECK(all[1].area() > all[2].area());
  CHECK(all[2].size() == 4); // the rectangle
  CHECK(all[1].size() == 3); // the triangle
  CHECK(maxDistTo(all[2], small.x, small.y) <= 1.0 + 1e-9);
  CHECK(ex.boundaries(I).size() == 3);
  // The boundary of the largest is an 8-connected closed chain.
  const std::vector<vpImagePoint> b = ex.boundary(I);
  REQUIRE(b.size() > 100);
  for (std::size_t k = 0; k < b.size(); ++k) {
    const vpImagePoint &p = b[k], &q = b[(k + 1) % b.size()];
    CHECK(std::max(std::fabs(p.get_u() - q.get_u()), std::fabs(p.get_v() - q.get_v())) == 1.0);
  }
  // The object mask marks the shapes, not the background.
  const vpImage<unsigned char> M = ex.objectMask(I);
  CHECK(M[240][380] == 255);
  CHECK(M[5][600] == 0);
}

TEST_CASE("extractor: extractJoined joins the pieces an occluder cut, not distant objects or specks", "[extract]")
{
  // A slanted bar (300 x 24 px) cut across by a 40 px gap into pieces of 160 and 100 px.
  const double c = std::cos(0.3), s = std::sin(0.3);
  auto bar = [&](double a, double b) {
    Poly p;
    const double u[] = {a, b, b, a}, v[] = {-12, -12, 12, 12};
    for (int k = 0; k < 4; ++k) {
      p.x.push_back(320 + c * u[k] - s * v[k]);
      p.y.push_back(240 + s * u[k] + c * v[k]);
    }
    return p;
  };
  const Poly whole = bar(-150, 150), left = bar(-150, 10), right = bar(50, 150);
  const vpMorphContourExtractor ex;
  const vpMorphContour full = ex.extract(render({whole}, 0, 255));
  const vpImage<unsigned char> cut = render({left, right}, 0, 255);
  const vpMorphContour largest = ex.extract(cut), joined = ex.extractJoined(cut);
  checkValid(joined);
  CHECK(largest.area() < 0.6 * full.area());
  // The gap is closed with the bar's own width: the joined outline is the whole bar's.
  CHECK(joined.area() == Approx(full.area()).epsilon(0.02));
  CHECK(maxDistTo(joined, whole.x, whole.y) <= 2.0); // measured 1.8 px (the bar alone: 1.45 px)
  CHECK_FALSE(joined.hasRegion());                   // part of its area is bridged, not seen
  CHECK(largest.hasRegion());

  // A key: a bow (a disc of radius 40) on a shaft (200 x 16 px) cut by a 60 px gap next to the bow. Only the cut
  // edges are bridged: the bow within 1.5 gaps of the cut stays out of the bridge (with it, a triangle from the
  // bow to the shaft: 69 % more area).
  auto keyPart = [](double a, double b, bool bow) {
    Poly p;
    if (bow) { // the arc from where the shaft's lower edge leaves it, round the left, to its upper edge
      const double alpha = std::asin(8.0 / 40.0);
      for (int k = 0; k <= 60; ++k) {
        const double t = alpha + (2.0 * M_PI - 2.0 * alpha) * k / 60.0;
        p.x.push_back(200 + 40 * std::cos(t));
        p.y.push_back(240 + 40 * std::sin(t));
      }
    } else {
      p.x = {a, a};
      p.y = {248, 232};
    }
    p.x.insert(p.x.end(), {b, b});
    p.y.insert(p.y.end(), {232, 248});
    return p;
  };
  const Poly key = keyPart(0, 440, true), bowSide = keyPart(0, 280, true), tip = keyPart(340, 440, false);
  const vpMorphContour keyWhole = ex.extract(render({key}, 0, 255));
  const vpMorphContour keyJoined = ex.extractJoined(render({bowSide, tip}, 0, 255));
  checkValid(keyJoined);
  CHECK(keyJoined.area() == Approx(keyWhole.area()).epsilon(0.02));
  CHECK(maxDistTo(keyJoined, key.x, key.y) <= 2.0);

  // Nothing to join: extract() itself, region included.
  const vpImage<unsigned char> one = render({whole}, 0, 255);
  const vpMorphContour alone = ex.extractJoined(one);
  CHECK(alone.size() == full.size());
  CHECK(alone.hasRegion());
  CHECK(alone.regionArea() == Approx(full.regionArea()));

  // A speck (under joinedMinShare() of the bar) next to it and a large object far away are left alone.
  Poly speck, far;
  speck.x = {320, 326, 326, 320};
  speck.y = {280, 280, 286, 286};
  far.x = {20, 80, 80, 20}; // a third of the bar's area, 230 px away (the largest gap joined: 150 px)
  far.y = {400, 400, 440, 440};
  const vpMorphContour lone = ex.extractJoined(render({whole, speck, far}, 0, 255));
  CHECK(lone.area() == Approx(full.area()).epsilon(1e-9));
  CHECK(lone.hasRegion());
  CHECK_THROWS_AS(ex.extractJoined(vpImage<unsigned char>(50, 50, 128)), vpMorphException);
}

TEST_CASE("extractor: beside a region the image's border cuts (the floor beyond the plane's edge), the largest region "
          "seen whole is a candidate",
          "[extract]")
{
  // A dark floor from the left border (about 75000 px) and a bar of 120 x 24 px, under 4 % of it, seen whole.
  Poly floor, bar;
  floor.x = {-1, 360, -1};
  floor.y = {60, 481, 481};
  bar.x = {420, 540, 540, 420};
  bar.y = {150, 150, 174, 174};
  const vpMorphContourExtractor ex;
  const vpMorphContour alone = ex.extract(render({bar}, 0, 255));
  const vpImage<unsigned char> I = render({floor, bar}, 0, 255);
  REQUIRE(ex.extract(I).area() > 20.0 * alone.area()); // the largest region is the floor
  const std::vector<vpMorphContour> cands = ex.extractCandidates(I);
  REQUIRE(cands.size() >= 2);
  CHECK(cands.front().area() == Approx(ex.extractJoined(I).area()).epsilon(1e-12));
  int bars = 0;
  for (const vpMorphContour &k : cands) // on the bar, its area within a pixel's band of its outline
    bars += maxDistTo(k, bar.x, bar.y) <= 2.0 && std::fabs(k.area() - alone.area()) <= alone.perimeter() ? 1 : 0;
  CHECK(bars == 1);

  // The region the border cuts may be the object itself: the specks beside it (twenty 4 x 4 px dots) are not all
  // candidates, only the largest region seen whole (with the pieces near it, then alone).
  std::vector<Poly> dotted{floor};
  for (int k = 0; k < 20; ++k) {
    Poly dot;
    const double u = 380 + 12 * k;
    dot.x = {u, u + 4, u + 4, u};
    dot.y = {400, 400, 404, 404};
    dotted.push_back(dot);
  }
  CHECK(ex.extractCandidates(render(dotted, 0, 255)).size() <= 3);
}

namespace
{
// The two extractions to the last bit: the polygon, the measured region, the edge outline with its marks and blur.
void checkSame(const vpMorphContour &a, const vpMorphContour &b)
{
  CHECK(a.xs() == b.xs());
  CHECK(a.ys() == b.ys());
  REQUIRE(a.hasRegion() == b.hasRegion());
  if (a.hasRegion()) {
    double ax, ay, bx, by, a20, a11, a02, b20, b11, b02;
    a.regionCentroid(ax, ay);
    b.regionCentroid(bx, by);
    a.regionMoments(a20, a11, a02);
    b.regionMoments(b20, b11, b02);
    CHECK(a.regionArea() == b.regionArea());
    CHECK((ax == bx && ay == by && a20 == b20 && a11 == b11 && a02 == b02));
  }
  REQUIRE(a.hasOutline() == b.hasOutline());
  CHECK(a.outline().xs() == b.outline().xs());
  CHECK(a.outline().ys() == b.outline().ys());
  CHECK(a.outlineBlur() == b.outlineBlur());
  for (std::size_t k = 0; k < a.outline().size(); ++k)
    CHECK(a.outline().ownEdge(k) == b.outline().ownEdge(k));
}

vpImage<unsigned char> toVisp(const cv::Mat &m)
{
  vpImage<unsigned char> I;
  vpImageConvert::convert(m, I);
  return I;
}
} // namespace

TEST_CASE("extractor: an object followed is read about where it was, with the whole image's answer", "[extract]")
{
  // extractJoined(I, previous) traces a window about the previous outline when the object is small in the image. Its
  // answer must be the whole image's to the last bit: in a view of one object, extractJoined(I) (the largest region,
  // the pieces an occluder cut from it joined), whether the object moved a little (the window) or grew past it (the
  // whole image again), under noise, a shading, a cut.
  const vpMorphContourExtractor ex;
  int views = 0;
  for (const char *name : {"pliers", "wrench", "key"}) {
    const cv::Mat src = readObject(name);
    const vpMorphContour before = ex.extract(toVisp(warp(src, similarity(src, 10, 0.6, 0, 0), 2.0, 1)));
    for (const double scale : {0.6, 0.62, 0.95})
      for (int look = 0; look < 4; ++look) {
        const double shift = scale == 0.62 ? 8.0 : 2.0;
        cv::Mat m = warp(src, similarity(src, 11, scale, shift, 0.5 * shift), look == 1 ? 6.0 : 2.0, 2);
        if (look == 2) { // a light that falls off across the view
          cv::Mat f;
          m.convertTo(f, CV_32F);
          for (int v = 0; v < f.rows; ++v)
            for (int u = 0; u < f.cols; ++u)
              f.at<float>(v, u) *= static_cast<float>(1.0 - 0.5 * u / f.cols);
          f.convertTo(m, CV_8U);
        }
        if (look == 3) // cut across by a card of the background's level
          cv::line(m, cv::Point(0, 150), cv::Point(640, 330), cv::Scalar(255), 12);
        const vpImage<unsigned char> I = toVisp(m);
        INFO(name << ", scaled by " << scale << ", look " << look);
        checkSame(ex.extractJoined(I, before), ex.extractJoined(I));
        ++views;
      }
  }
  CHECK(views == 36);
  // Bad images are refused as the whole image's extraction refuses them, whatever the previous outline.
  const vpMorphContour small({300, 340, 340, 300}, {220, 220, 260, 260});
  for (const vpImage<unsigned char> &bad :
       {vpImage<unsigned char>(), vpImage<unsigned char>(480, 640, 128), vpImage<unsigned char>(2, 2, 0)}) {
    try {
      (void)ex.extractJoined(bad, small);
      FAIL("a bad image: an error expected");
    } catch (const vpMorphException &e) {
      CHECK(e.getCode() == vpMorphException::badImageError);
    }
  }
}

TEST_CASE("extractor: a larger region elsewhere is not the object: candidates first, then where the object was",
          "[extract]")
{
  // The slanted bar of the test above, whole and cut by a 40 px gap, beside a slab larger than the bar (120 x 90 px
  // against 300 x 24) whose nearest corner is within the largest gap extractJoined() bridges.
  const double c = std::cos(0.3), s = std::sin(0.3);
  auto bar = [&](double a, double b, double du = 0.0, double dv = 0.0) {
    Poly p;
    const double u[] = {a, b, b, a}, v[] = {-12, -12, 12, 12};
    for (int k = 0; k < 4; ++k) {
      p.x.push_back(320 + du + c * u[k] - s * v[k]);
      p.y.push_back(240 + dv + s * u[k] + c * v[k]);
    }
    return p;
  };
  Poly slab;
  slab.x = {420, 540, 540, 420};
  slab.y = {340, 340, 430, 430};
  const Poly whole = bar(-150, 150), left = bar(-150, 10), right = bar(50, 150);
  const vpMorphContourExtractor ex;
  const vpMorphContour full = ex.extract(render({whole}, 0, 255));
  const vpImage<unsigned char> withSlab = render({whole, slab}, 0, 255),
                               cutWithSlab = render({left, right, slab}, 0, 255);
  REQUIRE(ex.extract(withSlab).area() > 1.4 * full.area()); // the largest region is the slab

  // A first image: the candidates hold the bar, alone and (cut) joined without the slab; the first is extractJoined().
  for (const vpImage<unsigned char> *I : {&withSlab, &cutWithSlab}) {
    const std::vector<vpMorphContour> cands = ex.extractCandidates(*I);
    REQUIRE(!cands.empty());
    CHECK(cands.front().area() == Approx(ex.extractJoined(*I).area()).epsilon(1e-12));
    int bars = 0;
    for (const vpMorphContour &k : cands) {
      checkValid(k);
      bars += std::fabs(k.area() / full.area() - 1.0) < 0.02 && maxDistTo(k, whole.x, whole.y) <= 2.0 ? 1 : 0;
    }
    CHECK(bars == 1);
  }

  // Afterwards: the region where the bar was a frame before (3 px right, 2 px down), its cut pieces joined, the slab
  // left out although it is larger and nearer than the largest gap.
  const vpMorphContour before = ex.extract(render({bar(-150, 150, 3, 2)}, 0, 255));
  const vpMorphContour tracked = ex.extractJoined(withSlab, before), trackedCut = ex.extractJoined(cutWithSlab, before);
  CHECK(tracked.hasRegion());
  CHECK(tracked.regionArea() == Approx(full.regionArea()).epsilon(1e-9));
  checkValid(trackedCut);
  CHECK_FALSE(trackedCut.hasRegion());
  CHECK(trackedCut.area() == Approx(full.area()).epsilon(0.02));
  CHECK(maxDistTo(trackedCut, whole.x, whole.y) <= 2.0);
  // The same as where the window about the bar is the whole image (an outline with spikes out to two corners, which
  // pass no region): the slab, which the window cuts, changes nothing.
  for (const vpImage<unsigned char> *I : {&withSlab, &cutWithSlab}) {
    Poly spiked = bar(-150, 150, 3, 2);
    spiked.x.insert(spiked.x.begin() + 2, {639.0, spiked.x[1]});
    spiked.y.insert(spiked.y.begin() + 2, {0.0, spiked.y[1]});
    spiked.x.insert(spiked.x.end(), {0.0, spiked.x.back()});
    spiked.y.insert(spiked.y.end(), {479.0, spiked.y.back()});
    checkSame(ex.extractJoined(*I, before), ex.extractJoined(*I, vpMorphContour(spiked.x, spiked.y)));
  }
  // An outline inside the bar that none of its boundary pixels reach overlaps it all the same.
  Poly core;
  core.x = {315, 330, 330, 315};
  core.y = {236, 236, 246, 246};
  CHECK(ex.extractJoined(withSlab, vpMorphContour(core.x, core.y)).regionArea() ==
        Approx(full.regionArea()).epsilon(1e-9));
  // The slab followed the same way is the slab, alone.
  const vpMorphContour slabBefore = ex.extract(render({slab}, 0, 255));
  CHECK(ex.extractJoined(cutWithSlab, slabBefore).regionArea() == Approx(slabBefore.regionArea()).epsilon(1e-9));
  // An outline around the whole view, however large its coordinates: every region was there, extractJoined(I).
  const vpMorphContour everywhere({-1e20, 1e20, 1e20, -1e20}, {-1e20, -1e20, 1e20, 1e20});
  CHECK(ex.extractJoined(cutWithSlab, everywhere).area() == Approx(ex.extractJoined(cutWithSlab).area()));
  // No previous outline: extractJoined(I). Nothing where the object was, or a previous outline in other units: errors.
  CHECK(ex.extractJoined(cutWithSlab, vpMorphContour()).area() == Approx(ex.extractJoined(cutWithSlab).area()));
  Poly corner;
  corner.x = {5, 40, 40, 5};
  corner.y = {5, 5, 30, 30};
  const vpMorphContour elsewhere = ex.extract(render({corner}, 0, 255));
  try {
    (void)ex.extractJoined(withSlab, elsewhere);
    FAIL("no region where the previous outline was: an error expected");
  } catch (const vpMorphException &e) {
    CHECK(e.getCode() == vpMorphException::badImageError);
  }
  vpCameraParameters cam(800, 800, 320, 240);
  try {
    (void)ex.extractJoined(withSlab, before.toNormalized(cam));
    FAIL("a previous outline in normalised units: an error expected");
  } catch (const vpMorphException &e) {
    CHECK(e.getCode() == vpMorphException::badParameterError);
  }
}

TEST_CASE("extractor: the edge outline of a grooved part survives a change of units", "[extract][outline]")
{
  // A rendered view of a triangular part with narrow grooves (an MPEG-7 development shape, as the bench renders it):
  // where its boundary chain turns at a groove's lip, two chain pixels measure the same edge crossing. Kept as two
  // points a rounding error apart (7e-15 px), they became one repeated vertex in normalised units, and every rigid fit
  // on the outline threw (the servo held on a "degenerate contour" until it stopped).
  vpImage<unsigned char> I;
  vpImageIo::read(I, (std::filesystem::path(__FILE__).parent_path() / "data" / "grooved-part-view.png").string());
  const vpMorphContour e = vpMorphContourExtractor().extract(I);
  REQUIRE(e.hasOutline());
  const vpMorphContour &o = e.outline();
  double closest = INFINITY;
  for (std::size_t k = 0; k < o.size(); ++k) {
    const std::size_t p = (k + o.size() - 1) % o.size();
    closest = std::min(closest, std::hypot(o.x(k) - o.x(p), o.y(k) - o.y(p)));
  }
  CHECK(closest > 1e-6);
  const vpCameraParameters cam(800, 800, 320, 240);
  CHECK_NOTHROW(vpMorphRigidTransform(0.3, 0.01, -0.02, 1.1).apply(e.toNormalized(cam)));
}

TEST_CASE("extractor: a washer's levels, edge outline and blur are read on its own pixels, not on its hole",
          "[extract][outline]")
{
  // A washer 100 px across with a hole 80 px across: its filled outline encloses four times more background than it
  // holds of the washer's own pixels. Read on the filled outline, the object's level was the background's: the
  // contour had no edge outline and no blur.
  auto circle = [](double r) {
    Poly p;
    for (int k = 0; k < 360; ++k) {
      p.x.push_back(320.3 + r * std::cos(k * M_PI / 180.0));
      p.y.push_back(240.6 + r * std::sin(k * M_PI / 180.0));
    }
    return p;
  };
  for (double s : {0.0, 1.0}) {
    vpImage<unsigned char> I = render({circle(50.0), circle(40.0)}, 40, 210); // the inner circle: a hole
    if (s > 0.0) {
      const cv::Mat b = blurred(I, s);
      std::copy(b.data, b.data + I.getSize(), I.bitmap);
    }
    const vpMorphContour c = vpMorphContourExtractor().extract(I);
    INFO("image blur " << s << " px: outline blur " << c.outlineBlur() << " px");
    REQUIRE(c.hasOutline());
    // The edge blur is the image's and the pixel's area's (1/12 px^2) in quadrature.
    CHECK(c.outlineBlur() == Approx(std::sqrt(s * s + 1.0 / 12.0)).margin(0.05));
    const vpMorphContour &o = c.outline();
    double worst = 0.0;
    for (std::size_t k = 0; k < o.size(); ++k)
      worst = std::max(worst, std::fabs(std::hypot(o.x(k) - 320.3, o.y(k) - 240.6) - 50.0));
    CHECK(worst < 0.15);
  }
}

TEST_CASE("approximation: vertex count is stable under image noise and sub-pixel motion", "[approx][noise]")
{
  // 40 renderings of the same 10-vertex polygon, each with a random sub-pixel offset, a small rotation and
  // Gaussian noise (sigma 20 grey levels on a contrast of 150): the boundary jitters by about one pixel.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> off(-0.5, 0.5), rot(-0.05, 0.05);
  std::map<std::size_t, int> counts;
  std::vector<double> errs;
  for (unsigned int trial = 0; trial < 40; ++trial) {
    const Poly p = testPolygon(320 + off(rng), 240 + off(rng), rot(rng));
    const vpMorphContour c = vpMorphContourExtractor().extract(render({p}, 50, 200, 20.0, 100 + trial));
    checkValid(c);
    counts[c.size()]++;
    errs.push_back(maxDistTo(c, p.x, p.y));
  }
  std::sort(errs.begin(), errs.end());
  const std::size_t vmin = counts.begin()->first, vmax = counts.rbegin()->first;
  std::string hist;
  for (const auto &kv : counts)
    hist += std::to_string(kv.first) + "x" + std::to_string(kv.second) + " ";
  INFO("vertex counts: " << hist << "; median / max distance to the true outline: " << errs[errs.size() / 2] << " / "
                         << errs.back());
  CHECK(vmin >= 10);
  CHECK(vmax - vmin <= 3);
  CHECK(counts[10] >= 30); // the true count in at least 3 renderings out of 4
  CHECK(errs[errs.size() / 2] < 1.5);
  CHECK(errs.back() < 2.0);
}

TEST_CASE("approximation: exact on clean polygons, start-point independent, parameter-free tolerance", "[approx]")
{
  const vpImage<unsigned char> I = render({testPolygon(320, 240, 0.3)}, 0, 255);
  const std::vector<vpImagePoint> chain = vpMorphContourExtractor().boundary(I);
  const vpMorphContour ref = vpMorphPolygonApproximation::approximate(chain);
  checkValid(ref);
  CHECK(ref.size() == 10);
  for (std::size_t shift : {std::size_t(1), chain.size() / 3, chain.size() - 7}) {
    std::vector<vpImagePoint> rotated(chain);
    std::rotate(rotated.begin(), rotated.begin() + static_cast<std::ptrdiff_t>(shift), rotated.end());
    const vpMorphContour c = vpMorphPolygonApproximation::approximate(rotated);
    REQUIRE(c.size() == ref.size());
    CHECK(c.area() == Approx(ref.area()));
  }
  // Reversed chain: same polygon, still counter-clockwise.
  std::vector<vpImagePoint> rev(chain.rbegin(), chain.rend());
  const vpMorphContour r = vpMorphPolygonApproximation::approximate(rev);
  CHECK(r.size() == ref.size());
  CHECK(r.signedArea() == Approx(ref.signedArea()));
  CHECK(vpMorphPolygonApproximation::vertexIndices(chain).size() == ref.size());

  CHECK(vpMorphPolygonApproximation::tolerance(0, 0, 10, 0) == Approx(1.0));
  CHECK(vpMorphPolygonApproximation::tolerance(0, 0, 10, 10) == Approx(std::sqrt(2.0)));
  CHECK(vpMorphPolygonApproximation::tolerance(0, 0, 0, 0) == Approx(1.0));

  // A digital circle: many vertices, all within the digitisation bound of the true circle.
  vpImage<unsigned char> D(200, 200, 0);
  for (unsigned int v = 0; v < 200; ++v)
    for (unsigned int u = 0; u < 200; ++u)
      if (std::hypot(u - 100.0, v - 100.0) <= 70.0)
        D[v][u] = 255;
  const vpMorphContour circ = vpMorphContourExtractor().extract(D);
  checkValid(circ);
  CHECK(circ.size() >= 12);
  for (std::size_t k = 0; k < circ.size(); ++k)
    CHECK(std::hypot(circ.x(k) - 100.0, circ.y(k) - 100.0) == Approx(70.0).margin(1.5));
}

TEST_CASE("approximation: a thin spur at the diameter's end gives one polygon from any start", "[approx]")
{
  // A spur ends at the pixels farthest from the block's far corners: the diameter the split starts from, found among
  // each row's leftmost and rightmost pixels. Three pixels wide, it is a thin part of the polygon; one pixel wide, the
  // chain passes its pixels twice and the stages' polygons fold back along it, so the last resort drops vertices until
  // the polygon is simple. Whatever the chain's start, the polygon is the same.
  for (unsigned int width : {3u, 1u}) {
    vpImage<unsigned char> I(120, 160, 0);
    for (unsigned int v = 40; v < 80; ++v)
      for (unsigned int u = 30; u < 90; ++u)
        I[v][u] = 255;
    for (unsigned int v = 60 - width / 2; v <= 60 + width / 2; ++v)
      for (unsigned int u = 90; u < 140; ++u)
        I[v][u] = 255;
    const std::vector<vpImagePoint> chain = vpMorphContourExtractor().boundary(I);
    std::set<std::pair<double, double>> pixels;
    for (const vpImagePoint &ip : chain)
      pixels.insert({ip.get_u(), ip.get_v()});
    CHECK((pixels.size() < chain.size()) == (width == 1)); // a one-pixel spur's pixels passed twice
    auto vertices = [](const vpMorphContour &c) {
      std::set<std::pair<double, double>> s;
      for (std::size_t k = 0; k < c.size(); ++k)
        s.insert({c.x(k), c.y(k)});
      return s;
    };
    const vpMorphContour ref = vpMorphPolygonApproximation::approximate(chain);
    checkValid(ref);
    const std::set<std::pair<double, double>> refVertices = vertices(ref);
    if (width == 3)
      CHECK(refVertices.count({139.0, 59.0}) + refVertices.count({139.0, 61.0}) == 2); // the spur's end
    for (std::size_t shift = 1; shift < chain.size(); shift += 7) {
      std::vector<vpImagePoint> rotated(chain);
      std::rotate(rotated.begin(), rotated.begin() + static_cast<std::ptrdiff_t>(shift), rotated.end());
      INFO("spur " << width << " px wide, start " << shift);
      CHECK(vertices(vpMorphPolygonApproximation::approximate(rotated)) == refVertices);
    }
  }
}

// The L1 error of the chain pixels strictly between a and b (unwrapped indices) against the segment a-b.
double chainL1(const std::vector<vpImagePoint> &chain, long a, long b)
{
  const long n = static_cast<long>(chain.size());
  auto at = [&](long i) { return chain[static_cast<std::size_t>(((i % n) + n) % n)]; };
  double s = 0.0;
  for (long i = a + 1; i < b; ++i)
    s += segDist(at(a).get_u(), at(a).get_v(), at(b).get_u(), at(b).get_v(), at(i).get_u(), at(i).get_v());
  return s;
}

TEST_CASE("approximation: a chord's L1 error is the sum of its pixels' distances, and an abandoned sum stays at its "
          "limit",
          "[approx]")
{
  // Chains of integer pixels (where the chord's error is summed as crosses) and of sub-pixel points (one distance at a
  // time), chords of every length, both ways round the chain's end, and pixels beyond the chord's ends (corners).
  std::mt19937 rng(7);
  for (const bool integral : {true, false}) {
    const vpMorphContourExtractor ex;
    const std::vector<vpImagePoint> boundary = ex.boundary(render({testPolygon(320.3, 240.6, 0.3)}, 50, 200, 20.0, 3));
    std::vector<vpImagePoint> chain = boundary;
    if (!integral)
      for (vpImagePoint &ip : chain)
        ip.set_uv(ip.get_u() + 0.25, ip.get_v() - 0.125 * std::sin(ip.get_u()));
    std::vector<vpMorphPixelChain::Pt> pts;
    for (const vpImagePoint &ip : chain)
      pts.push_back({ip.get_u(), ip.get_v()});
    const vpMorphPixelChain c(pts);
    const long n = static_cast<long>(chain.size());
    std::uniform_int_distribution<long> start(-n, n - 1), length(2, n - 1);
    for (int t = 0; t < 400; ++t) {
      const long a = start(rng), b = a + length(rng);
      const double reference = chainL1(chain, a, b);
      INFO((integral ? "pixels" : "sub-pixel points") << ", chord " << a << " to " << b << " of " << n);
      CHECK(c.l1(a, b) == Approx(reference).epsilon(1e-12).margin(1e-9));
      CHECK(c.lowerBound(a, b) <= c.l1(a, b) * (1.0 + 1e-12) + 1e-9);
      // Abandoned past a limit: the value returned, with its base, is still at or above the limit; under it, whole.
      const double base = 0.5 * reference, limit = base + 0.5 * reference;
      CHECK(base + c.l1(a, b, base, limit) >= limit * (1.0 - 1e-12));
      CHECK(c.l1(a, b, base, base + 2.0 * reference + 1.0) == Approx(reference).epsilon(1e-12).margin(1e-9));
    }
  }
}

TEST_CASE("approximation: every vertex is at the least L1 error between its neighbours", "[approx]")
{
  // The refinement's fixed point, checked against every place between the neighbours: the candidates it drops on a
  // lower bound, without summing their errors, must all be worse.
  std::vector<std::vector<vpImagePoint>> chains;
  const vpMorphContourExtractor ex;
  for (unsigned int seed : {1u, 2u, 3u})
    chains.push_back(ex.boundary(render({testPolygon(320.3, 240.6, 0.1 * seed)}, 50, 200, 20.0, seed)));
  vpImage<unsigned char> I;
  for (const char *f : {"/mpeg7/horse-1.png", "/mpeg7/device0-1.png", "/kimia99/cat1.png"})
    if (readPng(std::string(VISPMORPH_DATASETS_DIR) + f, I))
      chains.push_back(ex.boundary(I));
  for (const std::vector<vpImagePoint> &chain : chains) {
    const std::vector<std::size_t> v = vpMorphPolygonApproximation::vertexIndices(chain);
    const long n = static_cast<long>(chain.size()), m = static_cast<long>(v.size());
    REQUIRE(m >= 3);
    for (long j = 0; j < m; ++j) {
      const long x = static_cast<long>(v[static_cast<std::size_t>(j)]);
      const long p = j == 0 ? static_cast<long>(v.back()) - n : static_cast<long>(v[static_cast<std::size_t>(j - 1)]);
      const long q =
          j + 1 == m ? static_cast<long>(v.front()) + n : static_cast<long>(v[static_cast<std::size_t>(j + 1)]);
      const double here = chainL1(chain, p, x) + chainL1(chain, x, q);
      double best = here;
      long arg = x;
      for (long k = p + 1; k < q; ++k) {
        const double c = chainL1(chain, p, k) + chainL1(chain, k, q);
        if (c < best) {
          best = c;
          arg = k;
        }
      }
      INFO("chain of " << n << " pixels, vertex " << j << " at " << x << ", best place " << arg);
      CHECK(best >= here - 1e-6);
    }
  }
}

TEST_CASE("approximation: a comb of one-pixel spikes (a chain that retraces itself) gives a simple polygon",
          "[approx][bad]")
{
  // 150 spikes one pixel wide on a bar: the 8-connected outline goes up and down each spike over the same pixels,
  // so the approximation is not simple and must be repaired (this took O(V^4) before: a hang on noisy outlines).
  vpImage<unsigned char> I(200, 640, 255);
  for (unsigned int u = 10; u < 630; ++u)
    for (unsigned int v = 150; v < 160; ++v)
      I[v][u] = 0;
  for (unsigned int k = 0; k < 150; ++k)
    for (unsigned int v = 40 + (k * 37) % 90; v < 150; ++v)
      I[v][12 + 4 * k] = 0;
  const vpMorphContour c = vpMorphContourExtractor().extract(I);
  checkValid(c);
  CHECK(c.isSimple());
  CHECK(c.area() > 0.9 * 620 * 10);
}

TEST_CASE("approximation: bad chains throw", "[approx][bad]")
{
  std::vector<vpImagePoint> two{vpImagePoint(0, 0), vpImagePoint(0, 1)};
  REQUIRE_THROWS_AS(vpMorphPolygonApproximation::approximate(two), vpMorphException);
  REQUIRE_THROWS_AS(vpMorphPolygonApproximation::approximate({}), vpMorphException);
  // A one-pixel-wide line traced out and back: no area.
  std::vector<vpImagePoint> line;
  for (int u = 0; u <= 10; ++u)
    line.emplace_back(5, u);
  for (int u = 9; u >= 1; --u)
    line.emplace_back(5, u);
  REQUIRE_THROWS_AS(vpMorphPolygonApproximation::approximate(line), vpMorphException);
}

TEST_CASE("extractor: an object touching or crossing the image border is closed along the border", "[extract]")
{
  Poly p;
  p.x = {-50, 200, 260, -50};
  p.y = {100, 80, 300, 360};
  const vpImage<unsigned char> I = render({p}, 0, 255);
  const vpMorphContour c = vpMorphContourExtractor().extract(I);
  checkValid(c);
  double umin = 1e9;
  for (std::size_t k = 0; k < c.size(); ++k)
    umin = std::min(umin, c.x(k));
  CHECK(umin == 0.0); // closed along column 0
  CHECK(c.size() >= 4);
  CHECK(c.size() <= 6);

  // A corner object covering part of two borders.
  Poly q;
  q.x = {400, 640, 640, 500};
  q.y = {-10, -10, 200, 150};
  const vpMorphContour d = vpMorphContourExtractor().extract(render({q}, 255, 0));
  checkValid(d);
}

TEST_CASE("extractor: MPEG-7 and Kimia-99 samples", "[extract][datasets]")
{
  const std::string root = VISPMORPH_DATASETS_DIR;
  const char *mpeg7[] = {"apple-1.png", "bat-1.png", "device0-1.png", "key-1.png", "horse-1.png", "Bone-1.png"};
  const char *kimia[] = {"bunny04.png", "calf1.png", "cat1.png", "bonefishes.png"};
  vpImage<unsigned char> I;
  if (!readPng(root + "/mpeg7/apple-1.png", I)) {
    WARN("datasets not found in " << root << ": skipping");
    return;
  }
  const vpMorphContourExtractor ex;
  for (const char *f : mpeg7) {
    INFO("mpeg7/" << f);
    if (!readPng(root + "/mpeg7/" + f, I)) {
      WARN("missing mpeg7/" << f);
      continue;
    }
    const vpMorphContour c = ex.extract(I);
    checkValid(c);
    // The polygon covers the object: its area is close to the object mask's (holes excluded, they are not
    // part of the outer boundary, so the polygon can only be larger).
    const vpImage<unsigned char> M = ex.objectMask(I);
    double white = 0;
    for (unsigned int k = 0; k < M.getSize(); ++k)
      white += M.bitmap[k] != 0;
    CHECK(M[0][0] == 0); // MPEG-7: white shape on black, the object is the white class
    CHECK(c.area() > 0.5 * white);
    CHECK(c.size() < ex.boundary(I).size() / 2);
  }
  for (const char *f : kimia) {
    INFO("kimia99/" << f);
    if (!readPng(root + "/kimia99/" + f, I)) {
      WARN("missing kimia99/" << f);
      continue;
    }
    const vpMorphContour c = ex.extract(I);
    checkValid(c);
    const vpImage<unsigned char> M = ex.objectMask(I);
    CHECK(M[0][0] == 0); // Kimia-99: black shape on white, the object is the dark class
    CHECK(c.size() >= 8);
  }
}

TEST_CASE("extractor: Otsu's threshold is cv::threshold's, on rendered, noisy, random and odd-sized images",
          "[extract][otsu]")
{
  auto check = [](const vpImage<unsigned char> &I, const std::string &what) {
    const cv::Mat m(static_cast<int>(I.getHeight()), static_cast<int>(I.getWidth()), CV_8UC1,
                    const_cast<unsigned char *>(I.bitmap));
    cv::Mat dst;
    const double expected = cv::threshold(m, dst, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
    INFO(what << " (" << I.getWidth() << "x" << I.getHeight() << ")");
    CHECK(vpMorphContourExtractor::otsuThreshold(I) == static_cast<int>(expected));
  };
  vpImage<unsigned char> I;
  for (const char *name : {"pliers", "wedge", "key-deformed", "hammer"}) {
    REQUIRE(readPng(std::string(VISPMORPH_DATA_DIR) + "/objects/" + name + ".png", I));
    check(I, name);
  }
  for (const char *name : {"pliers-view", "key-view"}) { // rendered views: runs of equal background pixels
    REQUIRE(readPng(std::string(VISPMORPH_DATA_DIR) + "/demo/" + name + ".png", I));
    check(I, name);
  }
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> level(0, 255), side(3, 700);
  for (int trial = 0; trial < 60; ++trial) {
    const int w = trial < 2 ? 3 : side(rng), h = trial < 2 ? 3 + trial : side(rng) % 500 + 3;
    cv::Mat m(h, w, CV_8UC1);
    const int a = level(rng), b = std::min(255, a + 1 + level(rng) % 64);
    if (trial % 3 == 0) { // two levels with an object, blurred: a rendered view
      m.setTo(a);
      m(cv::Rect(w / 4, h / 4, std::max(1, w / 3), std::max(1, h / 3))).setTo(b);
      cv::GaussianBlur(m, m, cv::Size(5, 5), 1.2);
    } else {
      cv::randu(m, a, b + 1);
      if (trial % 3 == 1)
        m(cv::Rect(0, 0, std::max(1, w / 2), h)).setTo(level(rng));
    }
    if (trial == 5)
      m.setTo(a), m.at<unsigned char>(h - 1, w - 1) = static_cast<unsigned char>(255 - a); // one odd pixel
    vpImageConvert::convert(m, I);
    check(I, "random image " + std::to_string(trial));
  }
  CHECK_THROWS_AS(vpMorphContourExtractor::otsuThreshold(vpImage<unsigned char>()), vpMorphException);
}

TEST_CASE("extractor: bad images throw vpMorphException", "[extract][bad]")
{
  const vpMorphContourExtractor ex;
  auto isBadImage = [](const vpMorphException &e) { return e.getCode() == vpMorphException::badImageError; };

  SECTION("empty")
  {
    vpImage<unsigned char> E;
    REQUIRE_THROWS_AS(ex.extract(E), vpMorphException);
    REQUIRE_THROWS_AS(ex.extract(vpImage<vpRGBa>()), vpMorphException);
    REQUIRE_THROWS_AS(ex.extractAll(E), vpMorphException);
    REQUIRE_THROWS_AS(ex.boundary(E), vpMorphException);
    try {
      ex.extract(E);
    } catch (const vpMorphException &e) {
      CHECK(isBadImage(e));
      CHECK(std::string(e.getMessage()).find("empty") != std::string::npos);
    }
  }
  SECTION("too small")
  {
    vpImage<unsigned char> S(2, 5, 0);
    S[0][2] = 255;
    REQUIRE_THROWS_AS(ex.extract(S), vpMorphException);
    vpImage<unsigned char> T(40, 2, 0);
    REQUIRE_THROWS_AS(ex.extract(T), vpMorphException);
  }
  SECTION("uniform")
  {
    vpImage<unsigned char> U(100, 100, 128);
    REQUIRE_THROWS_AS(ex.extract(U), vpMorphException);
    REQUIRE_THROWS_AS(ex.extract(vpImage<vpRGBa>(50, 60, vpRGBa(10, 20, 30))), vpMorphException);
    try {
      ex.extract(U);
    } catch (const vpMorphException &e) {
      CHECK(isBadImage(e));
      CHECK(std::string(e.getMessage()).find("uniform") != std::string::npos);
    }
  }
  SECTION("only specks below the validity floor")
  {
    vpImage<unsigned char> K(100, 100, 0);
    K[10][10] = 255;
    K[50][50] = K[50][51] = 255;
    K[80][20] = K[81][20] = K[80][21] = K[81][21] = 255; // 2x2: encloses 1 square pixel
    K[30][70] = K[31][71] = K[32][72] = 255;             // a diagonal line: no area
    REQUIRE_THROWS_AS(ex.extract(K), vpMorphException);
    REQUIRE_THROWS_AS(ex.extractAll(K), vpMorphException);
    try {
      ex.extract(K);
    } catch (const vpMorphException &e) {
      CHECK(isBadImage(e));
      CHECK(std::string(e.getMessage()).find("no object") != std::string::npos);
    }
    // A 3x3 block reaches the floor and is found.
    for (unsigned int v = 60; v < 63; ++v)
      for (unsigned int u = 60; u < 63; ++u)
        K[v][u] = 255;
    // (a 3x3 square is a triangle within the digitisation bound: its corners are only sqrt(2) px off the diagonal)
    const vpMorphContour c = ex.extract(K);
    checkValid(c);
    CHECK(c.size() >= 3);
  }
  SECTION("checkerboard noise: no crash, no hang")
  {
    vpImage<unsigned char> N(64, 64);
    std::mt19937 rng(3);
    for (unsigned int k = 0; k < N.getSize(); ++k)
      N.bitmap[k] = static_cast<unsigned char>(rng() & 0xff);
    try {
      const std::vector<vpMorphContour> all = ex.extractAll(N);
      for (const vpMorphContour &c : all)
        CHECK(c.isSimple());
    } catch (const vpMorphException &) {
      SUCCEED("rejected with a clear exception");
    }
  }
}

TEST_CASE("extractor: the region's grey-level area, centroid and axis are sub-pixel, unlike the polygon's",
          "[extract][region]")
{
  // The anti-aliased test polygon at several angles, each at sub-pixel shifts, clean and noisy. What a servo needs
  // is a measure that follows the object steadily: its error must not change when the object moves by a fraction of
  // a pixel. The absolute errors are bounded by the test renderer's own (vertices rounded to 1/8 px, edges filled
  // inclusively: +0.16 % of area at most).
  double worstArea = 0, worstCentroid = 0, worstAxis = 0, worstAreaSpread = 0, worstPolySpread = 0,
         worstCentroidSpread = 0;
  for (double th : {0.0, 0.3, 1.1, 2.5})
    for (double sigma : {0.0, 5.0}) {
      double aMin = 1, aMax = -1, pMin = 1, pMax = -1, exMin = 1, exMax = -1, eyMin = 1, eyMax = -1;
      for (double shift : {0.0, 0.25, 0.5, 0.75}) { // multiples of the renderer's 1/8 px grid
        const Poly p = testPolygon(300 + shift, 250 + shift, th);
        const vpMorphContour truth(p.x, p.y);
        const unsigned char obj = sigma > 0 ? 60 : 30, bg = sigma > 0 ? 170 : 220;
        const vpMorphContour c = vpMorphContourExtractor().extract(render({p}, obj, bg, sigma, 11));
        REQUIRE(c.hasRegion());
        double cx, cy, tx, ty, m20, m11, m02;
        c.regionCentroid(cx, cy);
        truth.centroid(tx, ty);
        c.regionMoments(m20, m11, m02);
        const double axis = 0.5 * std::atan2(2 * m11, m20 - m02);
        const double ea = c.regionArea() / truth.area() - 1, ep = c.area() / truth.area() - 1;
        aMin = std::min(aMin, ea);
        aMax = std::max(aMax, ea);
        pMin = std::min(pMin, ep);
        pMax = std::max(pMax, ep);
        exMin = std::min(exMin, cx - tx);
        exMax = std::max(exMax, cx - tx);
        eyMin = std::min(eyMin, cy - ty);
        eyMax = std::max(eyMax, cy - ty);
        worstArea = std::max(worstArea, std::fabs(ea));
        worstCentroid = std::max(worstCentroid, std::hypot(cx - tx, cy - ty));
        worstAxis = std::max(worstAxis, std::fabs(std::remainder(axis - truth.orientation(), M_PI)));
      }
      worstAreaSpread = std::max(worstAreaSpread, aMax - aMin);
      worstPolySpread = std::max(worstPolySpread, pMax - pMin);
      worstCentroidSpread = std::max(worstCentroidSpread, std::hypot(exMax - exMin, eyMax - eyMin));
    }
  std::printf("[region] relative area error: worst %.5f, spread over sub-pixel shifts %.6f (polygon: %.5f); centroid "
              "error %.4f px, spread %.4f px; axis error %.4f deg\n",
              worstArea, worstAreaSpread, worstPolySpread, worstCentroid, worstCentroidSpread, vpMath::deg(worstAxis));
  CHECK(worstArea < 2e-3);
  CHECK(worstCentroid < 0.15);
  CHECK(vpMath::deg(worstAxis) < 0.15);
  CHECK(worstAreaSpread < 3e-4);
  CHECK(worstCentroidSpread < 0.03);
  CHECK(worstAreaSpread < worstPolySpread / 5); // why the region is measured at all
}

TEST_CASE("extractor: extractAll measures every region, the region excludes neighbouring objects", "[extract][region]")
{
  Poly a = testPolygon(200, 240), b;
  // A small square 4 px to the right of the big polygon's rightmost vertex (350, 260): inside its edge band.
  for (double dx : {0.0, 30.0, 30.0, 0.0})
    b.x.push_back(354 + dx);
  for (double dy : {245.0, 245.0, 275.0, 275.0})
    b.y.push_back(dy);
  const vpImage<unsigned char> I = render({a, b}, 30, 220);
  const std::vector<vpMorphContour> all = vpMorphContourExtractor().extractAll(I);
  REQUIRE(all.size() == 2);
  const vpMorphContour alone = vpMorphContourExtractor().extract(render({a}, 30, 220));
  for (const vpMorphContour &c : all)
    CHECK(c.hasRegion());
  CHECK(all[0].regionArea() == Approx(alone.regionArea()).epsilon(2e-3));
  CHECK(all[1].regionArea() == Approx(900).epsilon(2e-2));
}

TEST_CASE("extractor: a background clipped by the sensor does not shrink the region", "[extract][region]")
{
  // A brighter light saturates the background at 255 (the bench's noise set: gain up to 1.3 on a blurred image).
  // The edge's far half is then flat: linear weights between the two medians lost a few tenths of a pixel all
  // round (1.3 % of the area of a thin wedge, millimetres of depth for a servo).
  const Poly p = testPolygon(300, 250, 0.4);
  const vpMorphContour truth(p.x, p.y);
  auto measured = [&](double gain, double offset) {
    const vpImage<unsigned char> I = render({p}, 40, 210);
    const cv::Mat b = blurred(I, 1.2);
    std::mt19937 rng(5);
    std::normal_distribution<double> noise(0.0, 1.0);
    vpImage<unsigned char> J(I.getHeight(), I.getWidth());
    for (unsigned int k = 0; k < J.getSize(); ++k)
      J.bitmap[k] = cv::saturate_cast<unsigned char>(gain * b.data[k] + offset + noise(rng));
    const vpMorphContour c = vpMorphContourExtractor().extract(J);
    REQUIRE(c.hasRegion());
    return c.regionArea() / truth.area() - 1;
  };
  const double plain = measured(1.0, 0.0), clipped = measured(1.3, 13.0), objectClipped = measured(1.3, -60.0);
  std::printf("[region] relative area error: unclipped %.5f, background clipped %.5f, object clipped %.5f\n", plain,
              clipped, objectClipped);
  CHECK(std::fabs(plain) < 2e-3);
  CHECK(std::fabs(clipped) < 2e-3);
  CHECK(std::fabs(objectClipped) < 2e-3);
  // Against the same edge unclipped (the renderer's polygon is slightly larger than the truth): the edge's level read
  // at the gradient peaks left the clipped region 0.27 % smaller, its antisymmetric level 0.03-0.08 %.
  CHECK(std::fabs(clipped - plain) < 1e-3);
}

namespace
{
// \e b under the benchmark's gradient set: a gain of \e gain (1 + fallOff d), d the position along \e angle over the
// half-diagonal from the centre, then unit noise (seeded), rounded and clipped.
vpImage<unsigned char> shaded(const cv::Mat &b, double gain, double fallOff, double angle, unsigned int seed)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  const double cu = 0.5 * (b.cols - 1), cv = 0.5 * (b.rows - 1), half = std::hypot(cu, cv);
  vpImage<unsigned char> J(static_cast<unsigned int>(b.rows), static_cast<unsigned int>(b.cols));
  for (unsigned int v = 0; v < J.getHeight(); ++v)
    for (unsigned int u = 0; u < J.getWidth(); ++u) {
      const double g = gain * (1.0 + fallOff * ((u - cu) * std::cos(angle) + (v - cv) * std::sin(angle)) / half);
      J[v][u] = cv::saturate_cast<unsigned char>(g * b.at<unsigned char>(int(v), int(u)) + noise(rng));
    }
  return J;
}
} // namespace

TEST_CASE("extractor: a light falling off across the view neither joins the plane's dark side to the object nor moves "
          "its edge",
          "[extract][region][light]")
{
  // A gain affine in the image position on plane (210) and object (40), as the bench's gradient set renders it: at
  // 0.45 the plane's far corner is as dark as the object under Otsu's single threshold, and the bright corner clips.
  const Poly p = testPolygon(300, 250, 0.4);
  const cv::Mat b = blurred(render({p}, 40, 210), 1.0);
  auto view = [&](double fallOff, double angle) {
    return vpMorphContourExtractor().extract(shaded(b, 1.0, fallOff, angle, 9));
  };
  const vpMorphContour even = view(0.0, 0.0);
  REQUIRE(even.hasRegion());
  for (double fallOff : {0.3, 0.45, 0.6})
    for (int deg = -180; deg < 180; deg += 45) {
      const vpMorphContour c = view(fallOff, deg * M_PI / 180.0);
      REQUIRE(c.hasRegion());
      double x, y;
      c.regionCentroid(x, y);
      double ex, ey;
      even.regionCentroid(ex, ey);
      INFO("fall-off " << fallOff << " toward " << deg << " deg, against the evenly lit view: polygon area "
                       << c.area() / even.area() << ", region area " << c.regionArea() / even.regionArea()
                       << ", centroid moved " << std::hypot(x - ex, y - ey) << " px");
      CHECK(std::fabs(c.area() / even.area() - 1.0) < 0.01); // the object alone, not the plane's dark side
      CHECK(std::fabs(c.regionArea() / even.regionArea() - 1.0) < 2e-3);
      CHECK(std::hypot(x - ex, y - ey) < 0.05);
    }
}

// vpMorphLevelSpread (internal to the module): the spread of a surface's levels, from their rounded values.
#include "../src/vpMorphLevelSpread.h"

TEST_CASE("level spread: the median deviation read from rounded levels is the continuous levels' one",
          "[extract][light]")
{
  // Levels spread evenly over +-h about 40 (a dark surface under a light that falls off spans a few grey levels),
  // rounded; the deviations below the median level binned as vpMorphRegionMeasure bins them, the median's own bin
  // included. The continuous median deviation is h / 2; of 150 000 draws on a side, its deviation is h / (2 sqrt(n)),
  // under 0.008 levels: 0.03 is four of them.
  std::mt19937 rng(3);
  for (double h : {1.5, 3.0, 6.0}) {
    std::uniform_real_distribution<double> level(40.0 - h, 40.0 + h);
    std::array<long, 256> below{};
    for (int k = 0; k < 300000; ++k) {
      const long v = std::lround(level(rng));
      if (v <= 40)
        ++below[std::size_t(40 - v)];
    }
    INFO("levels 40 +- " << h << ": median deviation " << vpMorphLevelSpread::quantizedDeviationMedian(below)
                         << ", of the rounded deviations " << vpMorphLevelSpread::medianOf(below));
    CHECK(std::fabs(vpMorphLevelSpread::quantizedDeviationMedian(below) - 0.5 * h) < 0.03);
    if (h == 1.5) // a third of the levels at the median's: the rounded deviations' median is 0
      CHECK(vpMorphLevelSpread::medianOf(below) == 0.0);
  }
  // Every level at the median's (a flat surface, no noise): half a rounding step's median, a quarter of a grey level.
  std::array<long, 256> flat{};
  flat[0] = 1000;
  CHECK(vpMorphLevelSpread::quantizedDeviationMedian(flat) == Approx(0.25));
  CHECK(vpMorphLevelSpread::quantizedDeviationMedian(std::array<long, 256>{}) == 0.0);
}

// vpMorphGreyClasses (internal to the module) splits a shaded view pixel by pixel at its threshold plane.
#include "../src/vpMorphGreyClasses.h"

TEST_CASE("grey classes: a shaded view's pixels are split at the threshold plane, those at the sensor's limits on "
          "their side",
          "[extract][light]")
{
  // The gradient set's views, the bright side clipped at 255, and the same with specks at 0 and 255 all over; and a
  // bright object on a light plane, the threshold plane itself above 255 on the bright side.
  std::mt19937 rng(3);
  int shadedViews = 0, beyondLimit = 0;
  for (const cv::Mat &b : {blurred(render({testPolygon(300, 250, 0.4)}, 40, 210), 1.0),
                           blurred(render({testPolygon(300, 250, 0.4)}, 235, 120), 1.0)})
    for (double fallOff : {0.3, 0.6})
      for (int deg : {-150, -30, 45, 120})
        for (bool specks : {false, true}) {
          std::uniform_int_distribution<int> pixel(0, b.rows * b.cols - 1);
          vpImage<unsigned char> J = shaded(b, 1.2, fallOff, deg * M_PI / 180.0, 5);
          for (int k = 0; specks && k < 2000; ++k)
            J.bitmap[pixel(rng)] = k % 2 ? 255 : 0;
          const cv::Mat grey(int(J.getHeight()), int(J.getWidth()), CV_8UC1, J.bitmap);
          const vpMorphGreyClasses::Histogram h = vpMorphGreyClasses::histogram(J.bitmap, J.getSize());
          const vpMorphGreyClasses classes(grey, vpMorphGreyClasses::otsu(h, long(J.getSize())));
          const bool flat = classes.threshold(grey.cols, grey.rows) == classes.threshold(0, 0) &&
                            classes.threshold(grey.cols, 0) == classes.threshold(0, 0);
          shadedViews += flat ? 0 : 1;
          for (int u : {0, grey.cols - 1})
            for (int v : {0, grey.rows - 1})
              beyondLimit += classes.threshold(u, v) > 255.0 ? 1 : 0;
          cv::Mat dst(grey.size(), CV_8UC1);
          classes.bright(grey, dst);
          // Above the plane, or at 255; never at 0. A level within rounding of the plane may go either way.
          long wrong = 0;
          for (int v = 0; v < grey.rows; ++v)
            for (int u = 0; u < grey.cols; ++u) {
              const int g = grey.at<unsigned char>(v, u);
              const double t = classes.threshold(u, v);
              if (std::fabs(g - t) < 1e-3)
                continue;
              const bool expected = g == 255 || (g != 0 && g > t);
              wrong += (dst.at<unsigned char>(v, u) == 255) != expected;
            }
          INFO("fall-off " << fallOff << " toward " << deg << " deg" << (specks ? ", specks" : ""));
          CHECK(wrong == 0);
        }
  CHECK(shadedViews >= 16); // the shading was fitted (not Otsu's single level)
  CHECK(beyondLimit > 0);
}

namespace
{
// A zigzag band 8 px wide and 340 px long: a thin part, about 1 % of a 640 x 480 view.
Poly zigzagBand()
{
  Poly band;
  const double xs[] = {160, 240, 320, 400, 480};
  const double ys[] = {260, 200, 260, 200, 260};
  for (int k = 0; k < 5; ++k) {
    band.x.push_back(xs[k]);
    band.y.push_back(ys[k] - 4);
  }
  for (int k = 4; k >= 0; --k) {
    band.x.push_back(xs[k]);
    band.y.push_back(ys[k] + 4);
  }
  return band;
}
} // namespace

TEST_CASE("extractor: a thin object under a light that clips one side of the view is not split off with the plane's "
          "dark side",
          "[extract][region][light]")
{
  // A zigzag band 8 px wide (about 1 % of the view) on the plane (210), the object at 40, under the gradient set's
  // gain: the plane's bright side clips at 255 and its darkest corner falls to 40 % of the centre's level (fall-off
  // 0.6). Otsu's split then falls on the plane's ramp, and the two classes fitted from there meet across the ramp (a
  // local minimum of the within-class deviation), the object a speck of the dark side.
  const cv::Mat b = blurred(render({zigzagBand()}, 40, 210), 1.0);
  auto view = [&](double fallOff, double angle) {
    return vpMorphContourExtractor().extract(shaded(b, 1.3, fallOff, angle, 11));
  };
  const vpMorphContour even = view(0.0, 0.0);
  REQUIRE(even.hasRegion());
  for (double fallOff : {0.3, 0.45, 0.6})
    for (int deg = -180; deg < 180; deg += 30) {
      const vpMorphContour c = view(fallOff, deg * M_PI / 180.0);
      INFO("fall-off " << fallOff << " toward " << deg << " deg: polygon area " << c.area() / even.area()
                       << " of the evenly lit view's, region area " << c.regionArea() / even.regionArea());
      // The band alone, not the plane's dark side (25 to 35 times its area). Its edge may move by a few tenths of a
      // pixel: the dark class's level is the mean of its samples, most of them mixed by the edge on a band this thin.
      CHECK(std::fabs(c.area() / even.area() - 1.0) < 0.1);
    }
}

TEST_CASE("extractor: a floor of its own level beyond the plane's edge is not read as a light falling off",
          "[extract][region][light]")
{
  // A view of the benchmark's plane-edge set (a development fork, the tag masked): the plane, a darker floor beyond
  // its edge and the fork, evenly lit. Three levels: a shading fitted to two classes bends a threshold through them and
  // cuts bands across the floor and the plane (the fork one with the floor's band), and it lowers the within-class
  // deviation, but not by what its two parameters cost. Otsu's split stands.
  vpImage<unsigned char> I;
  vpImageIo::read(I, (std::filesystem::path(__FILE__).parent_path() / "data" / "plane-edge-view.png").string());
  const vpImage<unsigned char> M = vpMorphContourExtractor().objectMask(I);
  const int t = vpMorphContourExtractor::otsuThreshold(I);
  long agree = 0;
  for (unsigned int k = 0; k < I.getSize(); ++k)
    agree += (M.bitmap[k] == 255) == (I.bitmap[k] <= t);
  // The object is the dark class, or the light one (the polarity rule): either way the mask is Otsu's split.
  CHECK((agree == long(I.getSize()) || agree == 0));
}

TEST_CASE("extractor: a background just under the sensor's limit, its noise clipped, does not grow the region",
          "[extract][region]")
{
  // The bench's noise set lifts the background to 252 (gain 1.1, offset 22) under noise 5: a third of its pixels
  // reach 255, the level itself does not. Edge weights read against the background's median then counted a sliver
  // of background as object all round (a hammer 0.2-0.6 % too large, 1.9 mm of depth at the end of a servo); here
  // the region's edge moved by 0.02 px. Measured as that move: the area change over the perimeter.
  const Poly p = testPolygon(300, 250, 0.4);
  const double perimeter = vpMorphContour(p.x, p.y).perimeter();
  const int seeds = 6;
  for (double blur : {0.0, 0.3})
    for (int background : {252, 253}) {
      // The object at 66, the background at \e background, blurred, then noise of std sigma, rounded and clipped.
      auto area = [&](double sigma, unsigned int seed) {
        vpImage<unsigned char> I = render({p}, 66, 200);
        cv::Mat m(static_cast<int>(I.getHeight()), static_cast<int>(I.getWidth()), CV_8UC1, I.bitmap), b = m.clone();
        if (blur > 0.0)
          cv::GaussianBlur(m, b, cv::Size(0, 0), blur);
        std::mt19937 rng(seed);
        std::normal_distribution<double> noise(0.0, 1.0);
        long atLimit = 0;
        for (unsigned int k = 0; k < I.getSize(); ++k) {
          const double v = 66.0 + (b.data[k] - 66.0) * (background - 66.0) / (200.0 - 66.0) + sigma * noise(rng);
          I.bitmap[k] = cv::saturate_cast<unsigned char>(v);
          atLimit += I.bitmap[k] == 255;
        }
        if (sigma > 0.0)
          CHECK(atLimit > long(I.getSize() / 5)); // the noise does reach the limit
        return vpMorphContourExtractor().extract(I).regionArea();
      };
      double noisy = 0.0;
      for (int s = 0; s < seeds; ++s)
        noisy += area(5.0, unsigned(s)) / seeds;
      const double move = (noisy - area(0.0, 0)) / perimeter;
      std::printf("[region] blur %.1f, background at %d under noise 5: the edge moved by %+.4f px\n", blur, background,
                  move);
      CHECK(std::fabs(move) < 0.006);
    }
}

TEST_CASE("extractor: the edge outline lies on the object's edge to a few hundredths of a pixel", "[extract][outline]")
{
  // The anti-aliased test polygon at several angles and sub-pixel shifts, clean, noisy and blurred with a clipped
  // background. Points within 2 px of a vertex are left out: at a corner the edge is cut (the same way in every view
  // of the object). The renderer rounds the vertices to its 8x grid (the truth here) and fills inclusively: its
  // polygons are about 1/16 px too large all round, so the mean signed distance (outward positive) is checked apart
  // from the spread about it, which is what moves from one view to the next.
  double worstMean[3] = {0, 0, 0}, worstSpread[3] = {0, 0, 0};
  std::size_t fewest = SIZE_MAX;
  for (double th : {0.0, 0.3, 1.1, 2.5})
    for (double shift : {0.0, 0.375})
      for (int kind = 0; kind < 3; ++kind) {
        const Poly drawn = testPolygon(300 + shift, 250 + shift, th);
        vpImage<unsigned char> I = render({drawn}, 40, 210, kind == 1 ? 5.0 : 0.0, 3);
        Poly p; // the polygon the renderer fills: its vertices on its 1/8 px grid
        for (std::size_t v = 0; v < drawn.x.size(); ++v) {
          p.x.push_back((cvRound((drawn.x[v] + 0.5) * 8 - 0.5) + 0.5) / 8 - 0.5);
          p.y.push_back((cvRound((drawn.y[v] + 0.5) * 8 - 0.5) + 0.5) / 8 - 0.5);
        }
        if (kind == 2) { // blurred, background lifted to the sensor's limit
          const cv::Mat b = blurred(I, 1.2);
          for (unsigned int k = 0; k < I.getSize(); ++k)
            I.bitmap[k] = cv::saturate_cast<unsigned char>(1.3 * b.data[k] + 13.0);
        }
        const vpMorphContour c = vpMorphContourExtractor().extract(I);
        REQUIRE(c.hasOutline());
        const vpMorphContour &o = c.outline();
        CHECK(o.units() == vpMorphContour::PIXEL);
        CHECK(!o.hasOutline());
        fewest = std::min(fewest, o.size());
        std::vector<cv::Point2f> truth;
        for (std::size_t v = 0; v < p.x.size(); ++v)
          truth.emplace_back(float(p.x[v]), float(p.y[v]));
        std::vector<double> d;
        for (std::size_t k = 0; k < o.size(); ++k) {
          double nearVertex = 1e9;
          for (std::size_t v = 0; v < p.x.size(); ++v)
            nearVertex = std::min(nearVertex, std::hypot(o.x(k) - p.x[v], o.y(k) - p.y[v]));
          if (nearVertex < 2.0)
            continue;
          const bool inside = cv::pointPolygonTest(truth, cv::Point2f(float(o.x(k)), float(o.y(k))), false) > 0;
          d.push_back((inside ? -1.0 : 1.0) * distToOutline(p.x, p.y, o.x(k), o.y(k)));
        }
        REQUIRE(d.size() > 500);
        double mean = 0, s2 = 0;
        for (double v : d)
          mean += v / d.size();
        for (double v : d)
          s2 += (v - mean) * (v - mean) / d.size();
        worstMean[kind] = std::max(worstMean[kind], std::fabs(mean - 1.0 / 16));
        worstSpread[kind] = std::max(worstSpread[kind], std::sqrt(s2));
      }
  std::printf("[outline] distance to the true edge (the renderer's 1/16 px taken off): mean, then spread: clean %.3f, "
              "%.3f px; noise 5 %.3f, %.3f px; blurred and clipped %.3f, %.3f px; at least %zu points\n",
              worstMean[0], worstSpread[0], worstMean[1], worstSpread[1], worstMean[2], worstSpread[2], fewest);
  CHECK(worstMean[0] < 0.02);
  CHECK(worstSpread[0] < 0.03);
  CHECK(worstMean[1] < 0.03);
  CHECK(worstSpread[1] < 0.1); // 5 grey levels on a 170 step: 0.03 per pixel weight, 7 weights summed
  // Clipped: the level crossing, at the level about which the edge is antisymmetric (see the area test above): 0.06 px
  // out (at the level read at the gradient peaks, 10 grey levels off here, 0.15 px).
  CHECK(worstMean[2] < 0.1);
  CHECK(worstSpread[2] < 0.05);
  CHECK(fewest > 800); // about a point per boundary pixel (the polygon's perimeter is about 1100 px)
}

TEST_CASE("extractor: the edge outline's blur is the image's, unknown where a level is clipped", "[extract][outline]")
{
  // Blurs add in variance: the measured blur of an image blurred by s is sqrt(s^2 + b0^2), b0 the sharp render's own
  // (its pixels' area, 1/12 px^2, and the anti-aliasing), with noise too. Beyond 1.5 px the 7 pixels across the edge
  // lose the profile's tails: the blur is read low, never high.
  const Poly p = testPolygon(300, 250, 0.4);
  const double b0 = vpMorphContourExtractor().extract(render({p}, 40, 210)).outlineBlur();
  INFO("sharp render's blur " << b0 << " px");
  CHECK(b0 > 0.25);
  CHECK(b0 < 0.4);
  for (double noise : {0.0, 4.0})
    for (double s : {0.8, 1.2, 1.5, 2.5}) {
      vpImage<unsigned char> I = render({p}, 40, 210, 0.0, 5);
      const cv::Mat b = blurred(I, s);
      std::mt19937 rng(7);
      std::normal_distribution<double> n(0.0, noise > 0.0 ? noise : 1.0);
      for (unsigned int k = 0; k < I.getSize(); ++k)
        I.bitmap[k] = cv::saturate_cast<unsigned char>(b.data[k] + (noise > 0.0 ? n(rng) : 0.0));
      const vpMorphContour c = vpMorphContourExtractor().extract(I);
      REQUIRE(c.hasOutline());
      INFO("blur " << s << ", noise " << noise << ": measured " << c.outlineBlur() << " px");
      if (s <= 1.5) {
        CHECK(c.outlineBlur() == Approx(std::hypot(s, b0)).margin(0.1));
      } else {
        CHECK(c.outlineBlur() < std::hypot(s, b0));
        CHECK(c.outlineBlur() > 0.75 * std::hypot(s, b0));
      }
    }
  // A background lifted beyond the sensor's limit: the step's contrast is not seen, its blur unknown.
  vpImage<unsigned char> I = render({p}, 40, 210);
  const cv::Mat b = blurred(I, 1.2);
  for (unsigned int k = 0; k < I.getSize(); ++k)
    I.bitmap[k] = cv::saturate_cast<unsigned char>(1.3 * b.data[k] + 13.0);
  const vpMorphContour clipped = vpMorphContourExtractor().extract(I);
  REQUIRE(clipped.hasOutline());
  CHECK(clipped.outlineBlur() == 0.0);
}

TEST_CASE("extractor: a wire thinner than the region's band keeps its edge and blur, blurred and shaded",
          "[extract][outline][thin]")
{
  // A wavy wire 4.5 px wide: no pixel of it lies 3 px deep, so its own pixels are all edge, their levels between the
  // object's and the background's, the more so the wider the blur. Its edge is checked as the polygon's is above (the
  // renderer's 1/16 px taken off), away from its two flat ends.
  const double width = 4.5;
  Poly p, lower;
  for (int k = 0; k <= 120; ++k) {
    const double t = k / 120.0, x = 170.0 + 300.0 * t, y = 240.0 + 60.0 * std::sin(3.0 * M_PI * t);
    const double dy = 60.0 * 3.0 * M_PI * std::cos(3.0 * M_PI * t) / 300.0, n = std::hypot(1.0, dy);
    p.x.push_back(x + 0.5 * width * dy / n);
    p.y.push_back(y - 0.5 * width / n);
    lower.x.push_back(x - 0.5 * width * dy / n);
    lower.y.push_back(y + 0.5 * width / n);
  }
  const std::size_t ends[] = {0, p.x.size() - 1, p.x.size(), 2 * p.x.size() - 1};
  p.x.insert(p.x.end(), lower.x.rbegin(), lower.x.rend());
  p.y.insert(p.y.end(), lower.y.rbegin(), lower.y.rend());
  std::vector<cv::Point2f> truth;
  for (std::size_t v = 0; v < p.x.size(); ++v)
    truth.emplace_back(float(p.x[v]), float(p.y[v]));
  const double b0 = vpMorphContourExtractor().extract(render({testPolygon(300, 250, 0.4)}, 40, 210)).outlineBlur();
  for (double fallOff : {0.0, 0.3})
    for (double s : {0.8, 1.2, 1.5}) {
      const vpMorphContour c =
          vpMorphContourExtractor().extract(shaded(blurred(render({p}, 40, 210), s), 1.0, fallOff, 0.7, 11));
      REQUIRE(c.hasOutline());
      const vpMorphContour &o = c.outline();
      // Each half's mean apart, that of the lighter and of the darker side of the light's fall-off.
      double mean[2] = {0.0, 0.0};
      std::size_t n[2] = {0, 0};
      for (std::size_t k = 0; k < o.size(); ++k) {
        bool nearEnd = false;
        for (std::size_t v : ends)
          nearEnd = nearEnd || std::hypot(o.x(k) - p.x[v], o.y(k) - p.y[v]) < 3.0;
        if (nearEnd)
          continue;
        const bool inside = cv::pointPolygonTest(truth, cv::Point2f(float(o.x(k)), float(o.y(k))), false) > 0;
        const int half = (o.x(k) - 319.5) * std::cos(0.7) + (o.y(k) - 239.5) * std::sin(0.7) > 0.0;
        mean[half] += (inside ? -1.0 : 1.0) * distToOutline(p.x, p.y, o.x(k), o.y(k)); // outward positive
        ++n[half];
      }
      REQUIRE(n[0] > 250);
      REQUIRE(n[1] > 250);
      mean[0] /= double(n[0]);
      mean[1] /= double(n[1]);
      INFO("blur " << s << " px, fall-off " << fallOff << ": mean signed distance to the edge " << mean[0] << " and "
                   << mean[1] << " px (darker and lighter half), blur read " << c.outlineBlur() << " px (the image's "
                   << std::hypot(s, b0) << ")");
      CHECK(std::fabs(mean[0] - 1.0 / 16) < 0.1);
      CHECK(std::fabs(mean[1] - 1.0 / 16) < 0.1);
      CHECK(c.outlineBlur() == Approx(std::hypot(s, b0)).margin(0.15));
    }
}
