// Any silhouette as a bench object (vpMorphSilhouetteLayout), its rough-edged and bent variants
// (vpMorphBendGenerator), and the scene's tag placed where it fits in a view.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

#include <visp3/core/vpMath.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_sim/vpMorphBendGenerator.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>
#include <visp3/morph_sim/vpMorphSilhouetteLayout.h>

namespace
{
//! A w x h image of value \e bg with an ellipse of value \e fg (semi-axes a, b), and a 2-pixel speck in a corner.
vpImage<unsigned char> ellipse(unsigned int w, unsigned int h, double a, double b, unsigned char fg, unsigned char bg)
{
  vpImage<unsigned char> I(h, w, bg);
  for (unsigned int i = 0; i < h; ++i)
    for (unsigned int j = 0; j < w; ++j)
      if (std::pow((j - 0.5 * w) / a, 2) + std::pow((i - 0.5 * h) / b, 2) < 1.0)
        I[i][j] = fg;
  I[1][1] = I[1][2] = fg;
  return I;
}

//! Share of the object (coverage) and its bounding box in a black-on-white image.
double coverage(const vpImage<unsigned char> &I, unsigned int &width, unsigned int &height, unsigned int &grey)
{
  double sum = 0.0;
  unsigned int x0 = I.getWidth(), x1 = 0, y0 = I.getHeight(), y1 = 0;
  grey = 0;
  for (unsigned int i = 0; i < I.getHeight(); ++i)
    for (unsigned int j = 0; j < I.getWidth(); ++j) {
      const double c = 1.0 - I[i][j] / 255.0;
      sum += c;
      grey += (I[i][j] > 0 && I[i][j] < 255) ? 1 : 0;
      if (c > 0.5) {
        x0 = std::min(x0, j);
        x1 = std::max(x1, j);
        y0 = std::min(y0, i);
        y1 = std::max(y1, i);
      }
    }
  width = x1 - x0 + 1;
  height = y1 - y0 + 1;
  return sum;
}

//! Spread (px) of the distance of a contour's edge outline to its centroid: 0 for a perfect circle.
double radiusSpread(const vpImage<unsigned char> &I)
{
  const vpMorphContour c = vpMorphContourExtractor().extract(I).outline();
  double cx = 0, cy = 0, s = 0, s2 = 0;
  for (std::size_t k = 0; k < c.size(); ++k) {
    cx += c.x(k);
    cy += c.y(k);
  }
  cx /= c.size();
  cy /= c.size();
  for (std::size_t k = 0; k < c.size(); ++k) {
    const double r = std::hypot(c.x(k) - cx, c.y(k) - cy);
    s += r;
    s2 += r * r;
  }
  const double m = s / c.size();
  return std::sqrt(std::max(0.0, s2 / c.size() - m * m));
}
} // namespace

TEST_CASE("a silhouette of either polarity and any size is laid out alike", "[morph_sim][layout]")
{
  // White on black (MPEG-7's polarity) and black on white, at two sizes: the same object, 300 px long, centred.
  const vpMorphSilhouetteLayout a(ellipse(400, 300, 150, 60, 255, 0));
  const vpMorphSilhouetteLayout b(ellipse(800, 600, 300, 120, 0, 255));
  for (const vpMorphSilhouetteLayout *l : {&a, &b}) {
    const vpImage<unsigned char> &I = l->image();
    CHECK(I.getWidth() == 316);
    CHECK(I.getHeight() == 316);
    unsigned int w = 0, h = 0, grey = 0;
    const double area = coverage(I, w, h, grey);
    CHECK(std::abs(static_cast<int>(w) - 300) <= 1);
    CHECK(std::abs(static_cast<int>(h) - 120) <= 1);
    CHECK(area == Approx(M_PI * 150 * 60).epsilon(0.01)); // the speck is gone, the ellipse kept
    CHECK(grey > 300);                                    // anti-aliased edges
    CHECK(I[158][158] == 0);
    CHECK(I[0][0] == 255);
  }
  CHECK(a.scale() == Approx(1.0).epsilon(0.01));
  CHECK(b.scale() == Approx(0.5).epsilon(0.01));
}

TEST_CASE("a low-resolution silhouette is laid out with smooth edges, and roughened on demand", "[morph_sim][layout]")
{
  // A disc drawn with 24 px across, laid out at 300 px: the source's staircase becomes chords; roughened to 24 px
  // across, the staircase is back.
  const vpMorphSilhouetteLayout small(ellipse(32, 32, 12, 12, 0, 255));
  const double smooth = radiusSpread(small.image());
  const double rough = radiusSpread(vpMorphSilhouetteLayout::roughened(small.image(), 24));
  INFO("outline radius spread: laid out " << smooth << " px, roughened " << rough << " px");
  CHECK(smooth < 0.25 * small.scale()); // a quarter of a source pixel: the chords of its staircase
  CHECK(rough > 4.0 * smooth);
  CHECK_THROWS_AS(vpMorphSilhouetteLayout::roughened(small.image(), 2), vpMorphException);
  CHECK_THROWS_AS(vpMorphSilhouetteLayout::roughened(small.image(), 400), vpMorphException);
}

TEST_CASE("a variant of an object is laid out in its template's frame", "[morph_sim][layout]")
{
  const vpImage<unsigned char> src = ellipse(400, 300, 150, 60, 0, 255);
  vpImage<unsigned char> shorter = src;
  for (unsigned int i = 0; i < 300; ++i)
    for (unsigned int j = 300; j < 400; ++j)
      shorter[i][j] = 255; // the right end cut off
  const vpMorphSilhouetteLayout layout(src);
  const vpImage<unsigned char> cut = layout.apply(shorter);
  // Where both have the object, they agree: the same scale and offset.
  unsigned int differ = 0;
  for (unsigned int i = 0; i < cut.getHeight(); ++i)
    for (unsigned int j = 0; j < 200; ++j)
      differ += cut[i][j] != layout.image()[i][j] ? 1 : 0;
  CHECK(differ == 0);
  CHECK_THROWS_AS(layout.apply(vpImage<unsigned char>(10, 10, 0)), vpMorphException);
}

TEST_CASE("bad silhouettes are clear errors", "[morph_sim][layout]")
{
  CHECK_THROWS_AS(vpMorphSilhouetteLayout(vpImage<unsigned char>()), vpMorphException);
  CHECK_THROWS_AS(vpMorphSilhouetteLayout(vpImage<unsigned char>(50, 50, 128)), vpMorphException);
  CHECK_THROWS_AS(vpMorphSilhouetteLayout(ellipse(100, 100, 30, 30, 0, 255), 4), vpMorphException);
  try {
    vpMorphSilhouetteLayout::read("/nonexistent/apple.png");
    FAIL("no error");
  } catch (const vpMorphException &e) {
    CHECK(e.getCode() == vpMorphException::notFoundError);
  }
  {
    std::ofstream("layout-not-an-image.png") << "not an image";
  }
  CHECK_THROWS_AS(vpMorphSilhouetteLayout::read("layout-not-an-image.png"), vpMorphException);
}

TEST_CASE("a bent variant keeps at least 60 % undeformed, exactly, and is seeded", "[morph_sim][layout]")
{
  const vpMorphSilhouetteLayout layout(ellipse(400, 300, 180, 40, 0, 255));
  const vpImage<unsigned char> &I = layout.image();
  unsigned int w = 0, h = 0, grey = 0;
  const double area = coverage(I, w, h, grey);
  for (unsigned int seed : {1u, 2u, 3u, 4u}) {
    const vpMorphBendGenerator::Bend b = vpMorphBendGenerator::generate(I, seed);
    INFO("seed " << seed << ": share " << b.undeformedShare << ", angle " << b.angleDeg);
    CHECK(b.undeformedShare >= 0.6);
    CHECK(b.undeformedShare <= 0.81);
    CHECK(std::fabs(b.angleDeg) >= 2.5); // halved at most twice for room
    CHECK(std::fabs(b.angleDeg) <= 25.0);
    // The bend keeps the area (a turn of each slice), to the resampling.
    CHECK(coverage(b.image, w, h, grey) == Approx(area).epsilon(0.01));
    // The undeformed part's pixels are the template's, away from the pivot.
    unsigned int same = 0, part = 0;
    for (unsigned int k = 0; k < I.getSize(); ++k)
      if (b.undeformedMask.bitmap[k] == 0) {
        ++part;
        same += b.image.bitmap[k] == I.bitmap[k] ? 1 : 0;
      }
    CHECK(same > 0.95 * part);
    const vpMorphBendGenerator::Bend again = vpMorphBendGenerator::generate(I, seed);
    CHECK(again.angleDeg == b.angleDeg);
    CHECK(std::equal(again.image.bitmap, again.image.bitmap + again.image.getSize(), b.image.bitmap));
  }
  CHECK(vpMorphBendGenerator::generate(I, 1).angleDeg != vpMorphBendGenerator::generate(I, 2).angleDeg);
  CHECK_THROWS_AS(vpMorphBendGenerator::generate(vpImage<unsigned char>(50, 50, 255), 1), vpMorphException);
}

TEST_CASE("the tag is placed where it fits in the view, smaller if it must", "[morph_sim][layout]")
{
  vpImageIo::write(ellipse(400, 300, 180, 40, 0, 255), "layout-bar.png");
  vpMorphPlanarScene scene("layout-bar.png");
  const std::vector<double> sizes = {0.08, 0.06, 0.05, 0.04};
  // At 0.5 m, the bar turned by 30 deg and moved aside: an 8 cm tag finds a side in view.
  const vpHomogeneousMatrix cMo(0.05, 0.02, 0.5, 0, 0, vpMath::rad(30));
  REQUIRE(scene.placeTagInView(cMo, sizes));
  CHECK(scene.tagSize() == Approx(0.08));
  CHECK(scene.tagInView(cMo, 10));
  CHECK(scene.objectInView(cMo, 10));
  // From 0.33 m the bar fills the width: only a smaller tag fits, above or below it.
  const vpHomogeneousMatrix near(0, 0, 0.33, 0, 0, 0);
  REQUIRE(scene.placeTagInView(near, sizes));
  CHECK(scene.tagSize() < 0.08);
  CHECK(scene.tagInView(near, 10));
  // From 0.2 m nothing fits; the tag is left where it was.
  const double x = scene.tagX(), y = scene.tagY(), size = scene.tagSize();
  CHECK_FALSE(scene.placeTagInView(vpHomogeneousMatrix(0, 0, 0.2, 0, 0, 0), sizes));
  CHECK(scene.tagX() == x);
  CHECK(scene.tagY() == y);
  CHECK(scene.tagSize() == size);
  CHECK_THROWS_AS(scene.placeTagInView(cMo, {0.08, -1.0}), vpMorphException);
}

TEST_CASE("the scene's looks: a gradient, the plane's edge, a large distractor", "[morph_sim][faults]")
{
  vpImageIo::write(ellipse(400, 300, 180, 40, 0, 255), "layout-bar.png");
  vpMorphPlanarScene scene("layout-bar.png");
  const vpHomogeneousMatrix cMo(0, 0, 0.5, 0, 0, 0);
  vpImage<unsigned char> plain, I;
  scene.render(cMo, plain);
  // Gradient along +x: the plane brighter on the right, darker on the left, unchanged in the middle.
  vpMorphPlanarScene::Faults f;
  f.gradient = 0.5;
  scene.setFaults(f);
  scene.render(cMo, I);
  CHECK(I[240][5] < plain[240][5] - 60);
  CHECK(I[10][320] == Approx(plain[10][320]).margin(2));
  CHECK(I[240][634] == 255); // 210 x 1.5 clipped
  // The plane's edge 12 cm to the right: the floor (70) beyond it, the plane before it.
  f = vpMorphPlanarScene::Faults();
  f.planeEdge = true;
  f.planeEdgeX = 0.12;
  f.planeEdgeAngle = 0.0;
  scene.setFaults(f);
  scene.render(cMo, I);
  CHECK(I[240][620] == 70);
  CHECK(I[240][500] == plain[240][500]);
  // A distractor of 60 cm^2 right of the object, its long side along y: dark, drawn there (the tag above).
  scene.setTagPlacement(0.0, -0.12);
  f = vpMorphPlanarScene::Faults();
  f.largeDistractorArea = 0.006;
  f.largeDistractorX = 0.16;
  f.largeDistractorAngle = M_PI / 2;
  scene.setFaults(f);
  REQUIRE(scene.distractorCorners3D().size() == 1);
  scene.render(cMo, I);
  CHECK(I[240][576] == 40);
  CHECK(I[240 - 60][576] == 40);
  CHECK(I[240][500] == plain[240][500]);
  CHECK(scene.objectArea() == Approx(M_PI * 0.075 * 0.075 * 40 / 180).epsilon(0.02));
  f.largeDistractorAspect = 0.5;
  CHECK_THROWS_AS(scene.setFaults(f), vpMorphException);
  f = vpMorphPlanarScene::Faults();
  f.gradient = 2.0;
  CHECK_THROWS_AS(scene.setFaults(f), vpMorphException);
}
