// Tests of what vpServoMorph and vpFeatureMorph draw: on a display (a recording vpDisplay, no window) and burnt into
// an image (draw()), checked on the pixels as a person would see them.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/morph_vs/vpFeatureMorph.h>
#include <visp3/morph_vs/vpServoMorph.h>

#include "testMorphVsRecordingDisplay.h"
#include "testMorphVsScene.h"

using namespace vpMorphVsTest;

namespace
{
bool hasColor(const vpImage<vpRGBa> &I, int u, int v, const vpColor &c)
{
  if (u < 0 || v < 0 || u >= static_cast<int>(I.getWidth()) || v >= static_cast<int>(I.getHeight()))
    return false;
  const vpRGBa &p = I[static_cast<unsigned int>(v)][static_cast<unsigned int>(u)];
  return p.R == c.R && p.G == c.G && p.B == c.B;
}

// Share of the pixels of polygon \e c's edges (sampled every half pixel) with colour \e col within 1 pixel.
double coverage(const vpImage<vpRGBa> &I, const vpMorphContour &c, const vpColor &col)
{
  std::size_t n = 0, hit = 0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const std::size_t j = (i + 1) % c.size();
    const double len = std::hypot(c.x(j) - c.x(i), c.y(j) - c.y(i));
    const int steps = std::max(1, static_cast<int>(std::ceil(2 * len)));
    for (int s = 0; s < steps; ++s) {
      const double t = static_cast<double>(s) / steps;
      const int u = static_cast<int>(std::lround(c.x(i) + t * (c.x(j) - c.x(i))));
      const int v = static_cast<int>(std::lround(c.y(i) + t * (c.y(j) - c.y(i))));
      bool found = false;
      for (int dv = -1; dv <= 1 && !found; ++dv)
        for (int du = -1; du <= 1 && !found; ++du)
          found = hasColor(I, u + du, v + dv, col);
      ++n;
      hit += found;
    }
  }
  return n ? static_cast<double>(hit) / n : 0.0;
}

std::size_t countColor(const vpImage<vpRGBa> &I, const vpColor &col, unsigned int top = 0, unsigned int bottom = 0)
{
  std::size_t n = 0;
  bottom = bottom ? bottom : I.getHeight();
  for (unsigned int v = top; v < bottom; ++v)
    for (unsigned int u = 0; u < I.getWidth(); ++u)
      n += hasColor(I, static_cast<int>(u), static_cast<int>(v), col);
  return n;
}

// What servo.display() draws on an image with a recording display.
RecordingDisplay recorded(const vpServoMorph &servo)
{
  vpImage<unsigned char> I(480, 640, 255);
  RecordingDisplay rec;
  rec.attach(I);
  servo.display(I);
  RecordingDisplay::detach(I);
  return rec;
}

const vpHomogeneousMatrix cdMo = planarPose(20, 0.01, 0.0);
} // namespace

TEST_CASE("vpServoMorph::draw() burns the target, sub-goal, correspondence, contour and status into an image",
          "[servo][display]")
{
  vpServoMorph servo;
  servo.setTarget(projectPixels(cdMo), depth(cdMo));
  servo.getPlanner().setSubGoalCount(6);
  const vpMorphContour start = projectPixels(planarPose(20 + 120, 0.05, -0.03));
  servo.computeControlLaw(start);
  REQUIRE(servo.getStatus() == vpServoMorph::MOVING);

  vpImage<vpRGBa> I(480, 640, vpRGBa(255, 255, 255));
  servo.draw(I);
  // The target underneath, wider than the rest: it keeps its colour along its whole outline (9 edges, the
  // correspondence lines crossing it here and there).
  CHECK(coverage(I, servo.getTargetContour(), vpColor::green) > 0.9);
  CHECK(coverage(I, start, vpColor::red) > 0.9);
  CHECK(coverage(I, servo.getSubGoals()[0], vpColor::orange) > 0.8);
  CHECK(countColor(I, vpColor::cyan) > 50);
  // The status: yellow text on the black band, two lines (status and sub-goal, residuals).
  const std::vector<std::string> text = servo.statusText();
  REQUIRE(text.size() == 2);
  CHECK(text[0] == "moving  sub-goal 1/6  (rigid)");
  CHECK(text[1].rfind("residual ", 0) == 0);
  const std::size_t yellow = countColor(I, vpColor::yellow, 0, 60), black = countColor(I, vpColor::black, 0, 60);
  CHECK(yellow > 5 * (text[0].size() + text[1].size()) / 2); // glyphs drawn, not a blob or nothing
  CHECK(black > yellow);
  CHECK(countColor(I, vpColor::yellow, 60) == 0);
}

TEST_CASE("vpServoMorph::display() draws the same on a display, and nothing of a stale fit after a stop",
          "[servo][display]")
{
  vpServoMorph servo;
  servo.setTarget(projectPixels(cdMo), depth(cdMo));
  servo.getPlanner().setSubGoalCount(6);
  servo.computeControlLaw(projectPixels(planarPose(20 + 120, 0.05, -0.03)));
  {
    const RecordingDisplay rec = recorded(servo);
    CHECK(rec.count(vpColor::green) == 9);
    CHECK(rec.count(vpColor::orange) == 9);
    CHECK(rec.count(vpColor::red) == 9);
    CHECK(rec.count(vpColor::cyan) == servo.alignmentLines().size());
    REQUIRE(rec.texts.size() == 2);
    CHECK(rec.texts[0].text == servo.statusText()[0]);
    CHECK(rec.texts[0].color == vpColor::yellow);
    CHECK(rec.texts[1].position.get_v() > rec.texts[0].position.get_v());
  }
  // An empty view: the target and the sub-goal stay, the contour and its correspondence go, the status says why.
  servo.computeControlLaw(vpMorphContour());
  REQUIRE(servo.getStatus() == vpServoMorph::TARGET_LOST);
  {
    const RecordingDisplay rec = recorded(servo);
    CHECK(rec.count(vpColor::green) == 9);
    CHECK(rec.count(vpColor::orange) == 9);
    CHECK(rec.count(vpColor::red) == 0);
    CHECK(rec.count(vpColor::cyan) == 0);
    REQUIRE(!rec.texts.empty());
    CHECK(rec.texts[0].text.rfind("target lost", 0) == 0);
  }
  // Before any period: the target and the status only.
  vpServoMorph fresh;
  fresh.setTarget(projectPixels(cdMo), depth(cdMo));
  CHECK(fresh.statusText() == std::vector<std::string>{"not started"});
  vpImage<vpRGBa> C(480, 640, vpRGBa(255, 255, 255));
  fresh.draw(C);
  CHECK(coverage(C, fresh.getTargetContour(), vpColor::green) > 0.9);
  CHECK(countColor(C, vpColor::red) == 0);
}

TEST_CASE("vpServoMorph::draw() on a contour partly out of the image draws what is inside", "[servo][display]")
{
  vpServoMorph servo;
  servo.setTarget(projectPixels(cdMo), depth(cdMo));
  // The object's centroid 19 cm to the side at 0.5 m: 304 px right of the centre, part of it beyond the border.
  const vpMorphContour view = projectPixels(planarPose(20 + 30, 0.19, 0.0));
  double xmax = 0;
  for (std::size_t i = 0; i < view.size(); ++i)
    xmax = std::max(xmax, view.x(i));
  REQUIRE(xmax > 640);
  servo.computeControlLaw(view);
  vpImage<vpRGBa> I(480, 640, vpRGBa(255, 255, 255));
  CHECK_NOTHROW(servo.draw(I));
  CHECK(countColor(I, vpColor::red) > 100);
}

TEST_CASE("vpFeatureMorph draws its contour and a cross at its centroid", "[feature][display]")
{
  const vpCameraParameters cam = camera();
  vpFeatureMorph s;
  s.buildFrom(projectPixels(cdMo), cam, depth(cdMo));
  vpImagePoint g;
  vpMeterPixelConversion::convertPoint(cam, s.get_xg(), s.get_yg(), g);
  {
    vpImage<unsigned char> I(480, 640, 0);
    RecordingDisplay rec;
    rec.attach(I);
    s.display(cam, I, vpColor::red);
    RecordingDisplay::detach(I);
    CHECK(rec.count(vpColor::red) == 9);
    REQUIRE(rec.crosses.size() == 1);
    CHECK(rec.crosses[0].get_u() == Approx(g.get_u()));
    CHECK(rec.crosses[0].get_v() == Approx(g.get_v()));
  }
  vpImage<vpRGBa> I(480, 640, vpRGBa(255, 255, 255));
  s.draw(cam, I, vpColor::blue, 2);
  CHECK(coverage(I, projectPixels(cdMo), vpColor::blue) > 0.95);
  // An arm of the cross, 5 pixels right of the centroid (within a pixel: the line is drawn on the pixel grid).
  const int gu = static_cast<int>(std::lround(g.get_u())), gv = static_cast<int>(std::lround(g.get_v()));
  CHECK((hasColor(I, gu + 5, gv - 1, vpColor::blue) || hasColor(I, gu + 5, gv, vpColor::blue) ||
         hasColor(I, gu + 5, gv + 1, vpColor::blue)));
  vpFeatureMorph unbuilt;
  vpImage<vpRGBa> E(480, 640, vpRGBa(255, 255, 255));
  unbuilt.draw(cam, E);
  CHECK(countColor(E, vpColor::green) == 0);
}
