// Tests of vpMorphOutlineBlur: a sharp outline laid at a blur is the outline of the blurred image, the blur carried by
// the contour through its operations and files.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <thread>
#include <vector>

#include <opencv2/imgproc.hpp>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphOutlineBlur.h>
#include <visp3/morph/vpMorphRigidCheck.h>
#include <visp3/morph/vpMorphRigidShape.h>
#include <visp3/morph/vpMorphRigidTransform.h>

#include "testMorphImages.h"

namespace
{
// A six-lobed star (about 180 px across) whose edge is a saw of 150 teeth 1.6 px deep: a detail finer than a blur.
vpMorphTest::Poly serratedStar(double cx, double cy)
{
  vpMorphTest::Poly p;
  const int teeth = 150;
  for (int k = 0; k < 2 * teeth; ++k) {
    const double t = 2.0 * M_PI * k / (2 * teeth);
    const double r = 75.0 * (1.0 + 0.25 * std::cos(6.0 * t)) + (k % 2 == 0 ? 1.6 : 0.0);
    p.x.push_back(cx + r * std::cos(t));
    p.y.push_back(cy + r * std::sin(t));
  }
  return p;
}

// The same star without its saw: each tooth's tip and root averaged, the look-alike a blur makes of it.
vpMorphTest::Poly smoothStar(double cx, double cy)
{
  vpMorphTest::Poly p;
  const int teeth = 150;
  for (int k = 0; k < 2 * teeth; ++k) {
    const double t = 2.0 * M_PI * k / (2 * teeth);
    const double r = 75.0 * (1.0 + 0.25 * std::cos(6.0 * t)) + 0.8;
    p.x.push_back(cx + r * std::cos(t));
    p.y.push_back(cy + r * std::sin(t));
  }
  return p;
}

// Root mean square distance of \e a's outline points to \e b's outline (its segments).
double rmsDistance(const vpMorphContour &a, const vpMorphContour &b)
{
  double s2 = 0.0;
  const vpMorphContour &o = a.outline();
  for (std::size_t k = 0; k < o.size(); ++k) {
    const double d = vpMorphTest::distToOutline(b.outline().xs(), b.outline().ys(), o.x(k), o.y(k));
    s2 += d * d;
  }
  return std::sqrt(s2 / double(o.size()));
}

// The image of \e p blurred by \e s px (none for 0), its object extracted.
vpMorphContour seen(const vpMorphTest::Poly &p, double s)
{
  vpImage<unsigned char> I = vpMorphTest::render({p}, 40, 210);
  if (s > 0.0) {
    const cv::Mat b = vpMorphTest::blurred(I, s);
    std::copy(b.data, b.data + I.getSize(), I.bitmap);
  }
  return vpMorphContourExtractor().extract(I);
}

// \e sharp's outline laid at \e view's blur: the variance the view's blur adds, less the pixel's the laying adds.
vpMorphContour laidAtBlurOf(const vpMorphContour &sharp, const vpMorphContour &view)
{
  REQUIRE(view.outlineBlur() > vpMorphOutlineBlur::leastBlur(sharp));
  return vpMorphOutlineBlur::blurredTo(sharp, view.outlineBlur());
}
} // namespace

TEST_CASE("vpMorphOutlineBlur: a sharp outline laid at an image's blur is that image's outline", "[outline_blur]")
{
  const vpMorphTest::Poly star = serratedStar(320.3, 240.6);
  const vpMorphContour sharp = seen(star, 0.0);
  REQUIRE(sharp.hasOutline());
  for (double s : {1.0, 1.5, 2.0}) {
    const vpMorphContour view = seen(star, s);
    REQUIRE(view.hasOutline());
    const vpMorphContour laid = laidAtBlurOf(sharp, view);
    const double before = rmsDistance(view, sharp), after = rmsDistance(view, laid);
    INFO("image blur " << s << " px: measured " << view.outlineBlur() << " px, the sharp outline's "
                       << sharp.outlineBlur() << " px, laid at " << laid.outlineBlur() << " px; view to sharp outline "
                       << before << " px rms, to the laid one " << after << " px rms");
    CHECK(before > 0.15);
    CHECK(after < (s <= 1.5 ? 0.05 : 0.1)); // a tenth of a pixel: the outline fit's floor
    if (s <= 1.5) // where the extractor reads blurs to 0.1 px (beyond, low: the laid blur lower still)
      CHECK(laid.outlineBlur() == Approx(view.outlineBlur()).margin(0.1));
    // The polygon and region are the contour's own.
    CHECK(laid.xs() == sharp.xs());
    CHECK(laid.regionArea() == sharp.regionArea());
  }
}

TEST_CASE("vpMorphOutlineBlur: a polygon's sides and corners are laid where the blurred image has them",
          "[outline_blur]")
{
  // Straight sides do not move under a blur, corners are rounded: both as on the blurred image, whatever the blur.
  const vpMorphTest::Poly p = vpMorphTest::testPolygon(320.3, 240.6, 0.4);
  const vpMorphContour sharp = seen(p, 0.0);
  for (double s : {1.0, 1.5, 2.0}) {
    const vpMorphContour view = seen(p, s);
    const vpMorphContour laid = laidAtBlurOf(sharp, view);
    const double before = rmsDistance(view, sharp), after = rmsDistance(view, laid);
    INFO("image blur " << s << " px: view to the sharp outline " << before << " px rms, to the laid one " << after);
    CHECK(after < (s <= 1.5 ? 0.05 : 0.1));
    CHECK(after < before);
  }
}

TEST_CASE("vpMorphOutlineBlur: the blur follows the contour through its units, similarities and files",
          "[outline_blur]")
{
  const vpMorphContour c = seen(serratedStar(320, 240), 1.2);
  REQUIRE(c.outlineBlur() > 1.0);
  const vpCameraParameters cam(800, 800, 320, 240);
  const vpMorphContour n = c.toNormalized(cam);
  CHECK(n.outlineBlur() == Approx(c.outlineBlur() / 800.0));
  CHECK(n.toPixels(cam).outlineBlur() == Approx(c.outlineBlur()));
  CHECK(vpMorphRigidTransform(0.3, 5.0, -2.0, 2.0).apply(c).outlineBlur() == Approx(2.0 * c.outlineBlur()));
  CHECK(c.transformed(0.3, 1.0, 1.0, 0.5).outlineBlur() == Approx(0.5 * c.outlineBlur()));
  CHECK(c.resampled(64).outlineBlur() == c.outlineBlur());
  vpMorphDatabase db;
  db.add(vpMorphTemplate("star", c));
  const std::string file = "outline-blur-db.json";
  db.save(file);
  const vpMorphDatabase back = vpMorphDatabase::load(file, false);
  std::filesystem::remove(file);
  CHECK(back["star"].contour().outlineBlur() == Approx(c.outlineBlur()));
  vpMorphContour bad(c);
  CHECK_THROWS_AS(bad.setOutline(c.outline(), -1.0), vpMorphException);
  CHECK_THROWS_AS(bad.setOutline(c.outline(), NAN), vpMorphException);
}

TEST_CASE("vpMorphOutlineBlur: bad input is a clear error", "[outline_blur][bad]")
{
  const vpMorphContour c = seen(serratedStar(320, 240), 0.0);
  CHECK_THROWS_AS(vpMorphOutlineBlur::blurred(c, -1.0), vpMorphException);
  CHECK_THROWS_AS(vpMorphOutlineBlur::blurred(c, INFINITY), vpMorphException);
  CHECK_THROWS_AS(vpMorphOutlineBlur::blurred(c.toNormalized(vpCameraParameters(800, 800, 320, 240)), 1.0),
                  vpMorphException);
  CHECK_THROWS_AS(vpMorphOutlineBlur::blurred(vpMorphContour(c.xs(), c.ys()), 1.0), vpMorphException); // no outline
  // blurredTo(): a blur below what laying gives (the outline's own and the pixel's), or not finite.
  const double least = vpMorphOutlineBlur::leastBlur(c);
  CHECK(least == Approx(std::sqrt(c.outlineBlur() * c.outlineBlur() + vpMorphOutlineBlur::pixelVariance())));
  CHECK_THROWS_AS(vpMorphOutlineBlur::blurredTo(c, 0.9 * least), vpMorphException);
  CHECK_THROWS_AS(vpMorphOutlineBlur::blurredTo(c, NAN), vpMorphException);
  CHECK_THROWS_AS(vpMorphOutlineBlur::blurredTo(c, INFINITY), vpMorphException);
  CHECK(vpMorphOutlineBlur::blurredTo(c, least).outline().xs() == vpMorphOutlineBlur::blurred(c, 0.0).outline().xs());
  // A speck under a blur seven times its size: a uniform image (under a grey level of contrast), nothing to measure.
  vpMorphTest::Poly speck;
  speck.x = {300, 306, 306, 300};
  speck.y = {200, 200, 206, 206};
  const vpMorphContour small = seen(speck, 0.0);
  REQUIRE(small.hasOutline());
  CHECK_THROWS_AS(vpMorphOutlineBlur::blurred(small, 40.0), vpMorphException);
}

TEST_CASE("vpMorphRigidShape::atBlur: a ladder of blurs, each rung laid once and shared", "[outline_blur][rigid]")
{
  const vpMorphContour sharp = seen(serratedStar(320.3, 240.6), 0.0);
  const vpMorphRigidShape t(sharp);
  const double own = sharp.outlineBlur(), rung = vpMorphRigidShape::blurRung();
  CHECK(&t.atBlur(own) == &t);
  CHECK(&t.atBlur(0.0) == &t);
  CHECK(&t.atBlur(NAN) == &t);
  // One rung for the blurs nearest it, its blur as measured on the image it stands for.
  const vpMorphRigidShape &r4 = t.atBlur(4.0 * rung - 0.2 * rung);
  REQUIRE(&r4 != &t);
  CHECK(&t.atBlur(4.0 * rung + 0.2 * rung) == &r4);
  CHECK(&t.atBlur(5.0 * rung - 0.2 * rung) != &r4);
  // The extractor reads a blur of 2 px up to 0.2 px low; the polygon and region are the contour's own.
  CHECK(r4.contour().outlineBlur() == Approx(4.0 * rung).margin(0.25));
  CHECK(r4.contour().xs() == sharp.xs());
  // The copies share the ladder.
  const vpMorphRigidShape copy = t;
  CHECK(&copy.atBlur(4.0 * rung) == &r4);
  // Threads asking for one new rung get the same one.
  const vpMorphRigidShape *got[2] = {nullptr, nullptr};
  std::thread a([&] { got[0] = &t.atBlur(3.0 * rung); });
  std::thread b([&] { got[1] = &copy.atBlur(3.0 * rung); });
  a.join();
  b.join();
  CHECK(got[0] == got[1]);
  CHECK(got[0] != &t);
  // Nothing to lay: no measured outline, NORMALIZED units; a part the blur erases is compared as it is.
  const vpMorphRigidShape polygon(vpMorphContour(sharp.xs(), sharp.ys()));
  CHECK(&polygon.atBlur(3.0) == &polygon);
  const vpMorphRigidShape normalized(sharp.toNormalized(vpCameraParameters(800, 800, 320, 240)));
  CHECK(&normalized.atBlur(3.0) == &normalized);
  vpMorphTest::Poly speck;
  speck.x = {300, 306, 306, 300};
  speck.y = {200, 200, 206, 206};
  const vpMorphRigidShape small(seen(speck, 0.0));
  CHECK(&small.atBlur(80.0) == &small);
  CHECK_THROWS_AS(vpMorphRigidShape().atBlur(1.0), vpMorphException);
}

TEST_CASE("vpMorphRigidCheck: a blurred view of a serrated part coincides with its sharp template laid at its blur",
          "[outline_blur][rigid]")
{
  // The template sharp; the view turned, shifted, a tenth larger and blurred by 2 px: its teeth are rounded off.
  const vpMorphTest::Poly star = serratedStar(0.0, 0.0);
  vpMorphTest::Poly turned;
  for (std::size_t k = 0; k < star.x.size(); ++k) {
    const double c = std::cos(0.7), s = std::sin(0.7);
    turned.x.push_back(330.2 + 1.1 * (c * star.x[k] - s * star.y[k]));
    turned.y.push_back(236.7 + 1.1 * (s * star.x[k] + c * star.y[k]));
  }
  const vpMorphContour sharp = seen(serratedStar(320.3, 240.6), 0.0), view = seen(turned, 2.0);
  const vpMorphRigidShape t(sharp), v(view);
  const vpMorphRigidShape::Alignment a = v.alignOn(t);
  const vpMorphRigidCheck::Result r = vpMorphRigidCheck::check(v, t, a);
  // The same sharp outline declared at the view's blur (in its own pixels), so that neither is laid: its teeth stand
  // out of the view's outline by up to a tolerance, and most of the outline is off by a good part of one.
  vpMorphContour declared(sharp);
  declared.setOutline(sharp.outline(), view.outlineBlur() * a.transform.scale());
  const vpMorphRigidShape d(declared);
  REQUIRE(&d.atBlur(view.outlineBlur() * a.transform.scale()) == &d);
  REQUIRE(&v.atBlur(declared.outlineBlur() / a.transform.scale()) == &v);
  const vpMorphRigidCheck::Result n = vpMorphRigidCheck::check(v, d, a);
  INFO("view blur " << view.outlineBlur() << " px: laid at it, shares " << r.targetShare << " / " << r.inputShare
                    << ", cost " << r.cost << "; sharp, shares " << n.targetShare << " / " << n.inputShare << ", cost "
                    << n.cost);
  REQUIRE(r.fitted);
  CHECK(r.targetShare > 0.95);
  CHECK(r.inputShare > 0.95);
  CHECK(n.cost > 0.15);
  CHECK(r.cost < 0.1 * n.cost);
}

TEST_CASE("RIGID database: a blurred view of a serrated part is never named its smooth look-alike",
          "[outline_blur][rigid]")
{
  // The saw's teeth (1.6 px) show under no blur and fade under 1 and 2 px. Laid at the view's blur, the saw's template
  // coincides with the view, and the smooth one comes within the ambiguity only as the blur erases the teeth: named
  // the saw, or rejected. Compared sharp (the view's blur declared sharp, so nothing is laid), the smooth look-alike
  // is nearer the blurred views and accepted: 0.036 against 0.103 at 1 px, 0.054 against 0.200 at 2 px.
  vpMorphDatabase db(vpMorphShapeDistance(vpMorphShapeDistance::RIGID));
  db.add(vpMorphTemplate("serrated", seen(serratedStar(320.3, 240.6), 0.0)));
  db.add(vpMorphTemplate("smooth", seen(smoothStar(320.3, 240.6), 0.0)));
  for (double s : {0.0, 1.0, 2.0}) {
    const vpMorphContour view = seen(serratedStar(318.6, 243.1), s);
    for (bool prune : {true, false}) {
      const vpMorphRecognition r = db.recognize(view, prune);
      INFO("blur " << s << " px: named " << db[r.index].name() << " at " << r.distance << ", runner-up "
                   << r.secondDistance << ", accepted " << r.accepted);
      CHECK(!(r.accepted && db[r.index].name() == "smooth"));
      if (s == 0.0) {
        CHECK(db[r.index].name() == "serrated");
        CHECK(r.accepted);
      }
    }
  }
}
