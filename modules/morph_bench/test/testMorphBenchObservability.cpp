// vpMorphBenchObservability on shapes whose answer is known: the symmetry of a disc, a square, an equilateral
// triangle and rectangles, a nearly square rectangle tallied apart, a thin bar whose tilt the outline cannot bound.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include <visp3/core/vpMath.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_bench/vpMorphBenchObservability.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>

namespace
{
const vpCameraParameters kCam = vpMorphPlanarScene::defaultCamera();
const vpHomogeneousMatrix kGoal(0, 0, 0.5, 0, 0, 0);

//! A 640 x 480 view of a shape (inside(x, y) in pixels from the principal point), anti-aliased by 8 x 8 samples a
//! pixel, extracted as the bench extracts it.
template <typename Inside> vpMorphContour view(Inside inside)
{
  vpImage<unsigned char> I(480, 640, 210);
  for (unsigned int i = 0; i < 480; ++i)
    for (unsigned int j = 0; j < 640; ++j) {
      int n = 0;
      for (int a = 0; a < 8; ++a)
        for (int b = 0; b < 8; ++b)
          n += inside(j + (b + 0.5) / 8 - 0.5 - 320.0, i + (a + 0.5) / 8 - 0.5 - 240.0) ? 1 : 0; // pixel centres
      I[i][j] = static_cast<unsigned char>(std::lround(210 - 170 * n / 64.0));
    }
  return vpMorphContourExtractor().extract(I);
}

vpMorphContour rectangle(double w, double h, double turnDeg = 17)
{
  const double c = std::cos(vpMath::rad(turnDeg)), s = std::sin(vpMath::rad(turnDeg));
  return view([=](double x, double y) {
    const double u = c * x + s * y, v = -s * x + c * y;
    return std::fabs(u) < w / 2 && std::fabs(v) < h / 2;
  });
}

vpMorphContour triangle(double side)
{
  const double r = side / std::sqrt(3.0); // circumradius
  return view([=](double x, double y) {
    for (int k = 0; k < 3; ++k) { // inside the three edges, turned by 10 deg
      const double a = vpMath::rad(10 + 120 * k + 180);
      if (x * std::cos(a) + y * std::sin(a) > r / 2)
        return false;
    }
    return true;
  });
}
} // namespace

TEST_CASE("observability: a disc's symmetry is continuous, its pose otherwise bounded", "[bench][observability]")
{
  const vpMorphBenchObservability o(view([](double x, double y) { return std::hypot(x, y) < 120; }), kCam, kGoal);
  INFO("bounds with the tilt: " << 1000 * o.translationBound(true) << " mm, depth " << 1000 * o.depthBound(true)
                                << " mm, tilt " << vpMath::deg(o.tiltBound(true)) << " deg");
  CHECK(o.symmetryOrder() == 0);
  CHECK_FALSE(o.nearlySymmetric());
  CHECK(o.observable(false));
  // Tilted a little, a circle stays a circle moved aside (its ellipse is second order): the tilt is not bounded.
  CHECK(o.reason(true) == "translation");
  CHECK(o.rotationBound(false) == 0.0); // the turn about its normal is not estimated
  // Scored modulo its symmetry: a pose turned about the disc's centre is the desired one.
  const vpHomogeneousMatrix turned = kGoal * vpHomogeneousMatrix(0, 0, 0, 0, 0, vpMath::rad(70));
  const vpHomogeneousMatrix nearest = o.nearestDesiredPose(turned);
  CHECK((nearest.inverse() * turned).getTranslationVector().frobeniusNorm() < 1e-5);
  CHECK(vpThetaUVector((nearest.inverse() * turned).getRotationMatrix()).getTheta() < 1e-6);
}

TEST_CASE("observability: a square, an equilateral triangle and a 1.2 rectangle have their k-fold symmetries",
          "[bench][observability]")
{
  struct Case
  {
    const char *what;
    vpMorphContour contour;
    unsigned int order;
  };
  for (const Case &c :
       {Case{"square", rectangle(200, 200), 4}, Case{"triangle", triangle(240), 3},
        Case{"rectangle 1.2", rectangle(240, 200), 2}, Case{"rectangle 1.001", rectangle(240.24, 240), 4}}) {
    const vpMorphBenchObservability o(c.contour, kCam, kGoal);
    INFO(c.what << ": order " << o.symmetryOrder() << ", nearest other turn " << vpMath::deg(o.nearTurn()) << " deg at "
                << o.nearResidualPx() << " px RMS; bounds " << 1000 * o.translationBound(true) << " mm, "
                << 1000 * o.depthBound(true) << " mm, " << vpMath::deg(o.rotationBound(true)) << " deg, "
                << vpMath::deg(o.tiltBound(true)) << " deg");
    CHECK(o.symmetryOrder() == c.order);
    CHECK_FALSE(o.nearlySymmetric());
    CHECK(o.observable(false));
    CHECK(o.observable(true));
    // Its symmetric placements turn the object by multiples of 360 / k about its centre, which stays in place.
    REQUIRE(o.symmetricPlacements().size() == c.order - 1);
    for (std::size_t j = 0; j < o.symmetricPlacements().size(); ++j) {
      const vpHomogeneousMatrix &W = o.symmetricPlacements()[j];
      CHECK(std::fabs(std::remainder(std::atan2(W[1][0], W[0][0]) - 2 * M_PI * (j + 1) / c.order, 2 * M_PI)) <
            vpMath::rad(0.1));
      CHECK(std::hypot(W[0][3], W[1][3]) < 1e-4); // the centre at the object frame's origin here
    }
  }
}

TEST_CASE("observability: a rectangle a few tenths of a pixel off square is nearly symmetric, tallied apart",
          "[bench][observability]")
{
  // 240.72 x 240 px: turned a quarter turn it lies on itself within 0.36 px, between the noise (0.2 px) and the
  // views' slowly varying offsets (0.5 px).
  const vpMorphBenchObservability o(rectangle(240.72, 240), kCam, kGoal);
  INFO("order " << o.symmetryOrder() << ", quarter turn at " << o.nearResidualPx() << " px RMS");
  CHECK(o.symmetryOrder() == 2);
  CHECK(o.nearlySymmetric());
  CHECK(std::fabs(std::fabs(std::remainder(o.nearTurn(), M_PI)) - M_PI / 2) < vpMath::rad(1));
  CHECK_FALSE(o.observable(false));
  CHECK(o.reason(false) == "nearly-symmetric");
}

TEST_CASE("observability: a thin bar's tilt cannot be bounded, its planar pose can", "[bench][observability]")
{
  // 240 x 4 px: 15 cm by 2.5 mm at 0.5 m. A tilt about its long axis moves its edges by thousandths of a pixel.
  const vpMorphBenchObservability o(rectangle(240, 4, 30), kCam, kGoal);
  INFO("bounds: " << 1000 * o.translationBound(true) << " mm, depth " << 1000 * o.depthBound(true) << " mm, tilt "
                  << vpMath::deg(o.tiltBound(true)) << " deg");
  CHECK(o.symmetryOrder() == 2);
  CHECK(o.observable(false));
  CHECK_FALSE(o.observable(true));
  CHECK(o.reason(true) == "tilt");
  // A small disc (12 px across: 7.5 mm) bounds its depth no better than 1 mm.
  const vpMorphBenchObservability small(view([](double x, double y) { return std::hypot(x, y) < 6; }), kCam, kGoal);
  CHECK(small.reason(false) == "depth");
  CHECK_THROWS_AS(vpMorphBenchObservability(vpMorphContour({0, 1, 1}, {0, 0, 1}), kCam, kGoal), vpMorphException);
  CHECK_THROWS_AS(vpMorphBenchObservability(rectangle(240, 200), kCam, kGoal, -1.0), vpMorphException);
}
