// Tests of the contour value type: geometry (area, centroid, orientation, perimeter, turning angles),
// resampling, transforms and unit conversions.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphException.h>

namespace
{
// Axis-aligned rectangle w x h with its lower-left corner at (x0, y0), counter-clockwise in (x, y).
vpMorphContour rectangle(double x0, double y0, double w, double h)
{
  return vpMorphContour({x0, x0 + w, x0 + w, x0}, {y0, y0, y0 + h, y0 + h});
}
} // namespace

TEST_CASE("contour area, centroid, perimeter and orientation", "[contour]")
{
  const vpMorphContour r = rectangle(10, 20, 40, 10);
  CHECK(r.size() == 4);
  CHECK(r.signedArea() == Approx(400));
  CHECK(r.isCounterClockwise());
  CHECK(r.reversed().signedArea() == Approx(-400));
  CHECK(r.area() == Approx(400));
  CHECK(r.perimeter() == Approx(100));
  double cx, cy;
  r.centroid(cx, cy);
  CHECK(cx == Approx(30));
  CHECK(cy == Approx(25));
  // Elongated along x, then rotated by 30 deg: the principal axis follows.
  CHECK(r.orientation() == Approx(0.0).margin(1e-12));
  CHECK(r.transformed(M_PI / 6, 0, 0).orientation() == Approx(M_PI / 6));
  CHECK(r.transformed(-2.0, 0, 0).orientation() == Approx(-2.0 + M_PI));
  // Centroid of an L shape (not the vertex mean).
  const vpMorphContour L({0, 2, 2, 1, 1, 0}, {0, 0, 1, 1, 3, 3});
  L.centroid(cx, cy);
  CHECK(L.area() == Approx(4));
  // Two 2x1 rectangles: [0,2]x[0,1] (centroid (1, 0.5)) and [0,1]x[1,3] (centroid (0.5, 2)).
  CHECK(cx == Approx((2 * 1.0 + 2 * 0.5) / 4));
  CHECK(cy == Approx((2 * 0.5 + 2 * 2.0) / 4));
}

TEST_CASE("contour edges and turning angles", "[contour]")
{
  const vpMorphContour r = rectangle(0, 0, 4, 3);
  CHECK(r.edgeLength(0) == Approx(3)); // from vertex 3 (0, 3) to vertex 0 (0, 0)
  CHECK(r.edgeLength(1) == Approx(4));
  double sum = 0;
  for (std::size_t k = 0; k < r.size(); ++k) {
    CHECK(r.turningAngle(k) == Approx(M_PI / 2));
    sum += r.turningAngle(k);
  }
  CHECK(sum == Approx(2 * M_PI));
  const vpMorphContour rev = r.reversed();
  for (std::size_t k = 0; k < rev.size(); ++k)
    CHECK(rev.turningAngle(k) == Approx(-M_PI / 2));
}

TEST_CASE("contour start, reversal, mirror and transforms", "[contour]")
{
  const vpMorphContour c({0, 10, 12, 3}, {0, 1, 8, 6});
  const vpMorphContour s = c.rotatedStart(2);
  CHECK(s.x(0) == c.x(2));
  CHECK(s.y(1) == c.y(3));
  CHECK(s.x(2) == c.x(0));
  const vpMorphContour rv = c.reversed();
  CHECK(rv.x(0) == c.x(0));
  CHECK(rv.x(1) == c.x(3));
  CHECK(c.counterClockwise().isCounterClockwise());
  CHECK(rv.counterClockwise().isCounterClockwise());
  const vpMorphContour mi = c.mirrored();
  CHECK(mi.area() == Approx(c.area()));
  CHECK(mi.signedArea() * c.signedArea() > 0);
  // Similarity about the centroid: area scales by s^2, centroid moves by t, perimeter by s.
  double cx, cy, tx, ty;
  c.centroid(cx, cy);
  const vpMorphContour t = c.transformed(0.7, 5, -3, 2.0);
  t.centroid(tx, ty);
  CHECK(tx == Approx(cx + 5));
  CHECK(ty == Approx(cy - 3));
  CHECK(t.area() == Approx(4 * c.area()));
  CHECK(t.perimeter() == Approx(2 * c.perimeter()));
  // Normalised: centroid at the origin, unit perimeter.
  const vpMorphContour n = c.normalized();
  n.centroid(tx, ty);
  CHECK(tx == Approx(0).margin(1e-12));
  CHECK(ty == Approx(0).margin(1e-12));
  CHECK(n.perimeter() == Approx(1));
}

TEST_CASE("contour resampling by arc length", "[contour]")
{
  const vpMorphContour r = rectangle(0, 0, 30, 10); // perimeter 80
  const vpMorphContour s = r.resampled(8);          // one vertex every 10
  REQUIRE(s.size() == 8);
  CHECK(s.perimeter() == Approx(80));
  CHECK(s.x(0) == Approx(0));
  CHECK(s.y(0) == Approx(0));
  CHECK(s.x(1) == Approx(10));
  CHECK(s.x(3) == Approx(30));
  CHECK(s.y(4) == Approx(10));
  CHECK(s.x(4) == Approx(30));
  CHECK(s.area() == Approx(r.area()));
  const vpMorphContour dense = r.resampled(400);
  CHECK(dense.size() == 400);
  CHECK(dense.perimeter() == Approx(80).epsilon(1e-9));
}

TEST_CASE("contour unit conversions with the camera intrinsics", "[contour]")
{
  const vpCameraParameters cam(800, 800, 320, 240);
  const vpMorphContour p({320, 400, 320}, {240, 240, 320});
  const vpMorphContour n = p.toNormalized(cam);
  CHECK(n.units() == vpMorphContour::NORMALIZED);
  CHECK(n.x(1) == Approx(0.1));
  CHECK(n.y(2) == Approx(0.1));
  const vpMorphContour back = n.toPixels(cam);
  CHECK(back.units() == vpMorphContour::PIXEL);
  for (std::size_t k = 0; k < 3; ++k) {
    CHECK(back.x(k) == Approx(p.x(k)));
    CHECK(back.y(k) == Approx(p.y(k)));
  }
  REQUIRE_THROWS_AS(n.toNormalized(cam), vpMorphException);
  REQUIRE_THROWS_AS(p.toPixels(cam), vpMorphException);
  // vpImagePoint convention: u = x (column), v = y (row).
  CHECK(p.point(1).get_u() == Approx(400));
  CHECK(p.point(2).get_v() == Approx(320));
  const vpMorphContour fromPoints(p.points());
  CHECK(fromPoints.x(1) == Approx(400));
}

TEST_CASE("contour region: unset by construction, carried through similarities, unit changes and re-ordering",
          "[contour][region]")
{
  // A 40 x 20 rectangle: area 800, centroid (20, 10), central moments / area: w^2/12, 0, h^2/12.
  vpMorphContour r = rectangle(0, 0, 40, 20);
  CHECK_FALSE(r.hasRegion());
  CHECK(r.regionArea() == Approx(800)); // falls back to the polygon
  double cx, cy, m20, m11, m02;
  r.regionCentroid(cx, cy);
  CHECK(cx == Approx(20));
  r.regionMoments(m20, m11, m02);
  CHECK(m20 == Approx(1600.0 / 12));
  CHECK(m11 == Approx(0.0).margin(1e-9));
  CHECK(m02 == Approx(400.0 / 12));
  CHECK(r.reversed().orientation() == Approx(0.0).margin(1e-12)); // clockwise too
  // A measured region slightly off the polygon (as an image gives it), to tell region from polygon below.
  r.setRegion(810, 20.5, 10.25, 1600.0 / 12, 0.0, 400.0 / 12);
  REQUIRE(r.hasRegion());
  CHECK(r.regionArea() == Approx(810));

  // Similarity about the polygon's centroid: the region moves with the vertices; its axis turns with them.
  const double th = 0.7, s = 1.5;
  const vpMorphContour t = r.transformed(th, 3.0, -4.0, s);
  REQUIRE(t.hasRegion());
  CHECK(t.regionArea() == Approx(810 * s * s));
  t.regionCentroid(cx, cy);
  CHECK(cx == Approx(20 + s * (std::cos(th) * 0.5 - std::sin(th) * 0.25) + 3.0));
  CHECK(cy == Approx(10 + s * (std::sin(th) * 0.5 + std::cos(th) * 0.25) - 4.0));
  t.regionMoments(m20, m11, m02);
  CHECK(0.5 * std::atan2(2 * m11, m20 - m02) == Approx(th));
  CHECK(m20 + m02 == Approx(s * s * 2000.0 / 12)); // the trace is rotation invariant

  // Mirror: the axis orientation changes sign, the area stays.
  const vpMorphContour m = t.mirrored();
  double mm20, mm11, mm02;
  m.regionMoments(mm20, mm11, mm02);
  CHECK(m.regionArea() == Approx(t.regionArea()));
  CHECK(mm11 == Approx(-m11));

  // Re-ordering and resampling keep the same region; construction from vertices does not.
  CHECK(t.reversed().regionArea() == Approx(t.regionArea()));
  CHECK(t.rotatedStart(2).regionArea() == Approx(t.regionArea()));
  CHECK(t.resampled(12).regionArea() == Approx(t.regionArea()));
  CHECK_FALSE(vpMorphContour(t.xs(), t.ys()).hasRegion());

  // Pixels <-> normalised: area / (px py), centroid as a vertex, and back.
  const vpCameraParameters cam(800, 700, 320, 240);
  const vpMorphContour n = r.toNormalized(cam);
  CHECK(n.regionArea() == Approx(810.0 / (800 * 700)));
  n.regionCentroid(cx, cy);
  CHECK(cx == Approx((20.5 - 320) / 800));
  CHECK(cy == Approx((10.25 - 240) / 700));
  n.regionMoments(m20, m11, m02);
  CHECK(m02 == Approx(400.0 / 12 / (700.0 * 700.0)));
  const vpMorphContour back = n.toPixels(cam);
  CHECK(back.regionArea() == Approx(810));
  back.regionCentroid(cx, cy);
  CHECK(cx == Approx(20.5));
}

TEST_CASE("contour region: bad values throw", "[contour][region][bad]")
{
  vpMorphContour r = rectangle(0, 0, 4, 2);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  REQUIRE_THROWS_AS(r.setRegion(0.0, 1, 1, 1, 0, 1), vpMorphException);
  REQUIRE_THROWS_AS(r.setRegion(-2.0, 1, 1, 1, 0, 1), vpMorphException);
  REQUIRE_THROWS_AS(r.setRegion(8.0, nan, 1, 1, 0, 1), vpMorphException);
  REQUIRE_THROWS_AS(r.setRegion(8.0, 1, 1, -1, 0, 1), vpMorphException);
  REQUIRE_THROWS_AS(r.setRegion(8.0, 1, 1, 1, 2, 1), vpMorphException); // not positive semi-definite
  REQUIRE_THROWS_AS(r.setRegion(8.0, 1, 1, std::numeric_limits<double>::infinity(), 0, 1), vpMorphException);
  CHECK_FALSE(r.hasRegion());
}

// Found by fuzzing (tests/fuzz/regressions/polygon_correspondence/): two distinct vertices 1e-231 apart make an
// edge whose length underflows to 0, and coordinates beyond 1e75 make the moments (centroid, rigid fits) overflow; such
// contours used to be accepted and gave the matcher NaN step costs, whose trace-back then left its band
// (heap-buffer-overflow under ASan). They are refused at construction now, with a message saying why.
TEST_CASE("contour: coordinates too close or too large for double precision throw", "[contour][bad][fuzz]")
{
  // The L shape of the fuzz seed with its last vertex 2.6e-231 above the first one.
  REQUIRE_THROWS_WITH((vpMorphContour({0, 60, 60, 30, 30, 0}, {0, 0, 6, 6, 20, 2.586563270614692e-231})),
                      Catch::Contains("edge 0 has length 0"));
  REQUIRE_THROWS_AS((vpMorphContour({0, 40, 40, 10, 10, 0}, {0, 0, 1.8e-260, 10, 50, 50})), vpMorphException);
  // Overflow: beyond maxCoordinate().
  REQUIRE_THROWS_WITH((vpMorphContour({0, 1e300, 1e300}, {0, 0, 1e300})), Catch::Contains("beyond"));
  REQUIRE_THROWS_WITH((vpMorphContour({0, 5e153, 5e153}, {0, 0, 5e153})), Catch::Contains("beyond 1e+75"));
  REQUIRE_THROWS_WITH((vpMorphContour({0, 2e75, 2e75}, {0, 0, 1})), Catch::Contains("overflow"));
  CHECK_NOTHROW(vpMorphContour({0, 1e75, 1e75}, {0, 0, 1e75}));
  // Still accepted: tiny and large but representable polygons.
  CHECK_NOTHROW(rectangle(0, 0, 1e-100, 2e-100));
  CHECK_NOTHROW(rectangle(1e70, -1e70, 1e70, 3e70));
  CHECK(rectangle(0, 0, 1e-100, 2e-100).area() > 0);
}

TEST_CASE("vpMorphContour: the measured edge outline follows its polygon", "[contour][outline]")
{
  const vpMorphContour square({0.0, 40.0, 40.0, 0.0}, {0.0, 0.0, 40.0, 40.0});
  CHECK(!square.hasOutline());
  CHECK(&square.outline() == &square); // none measured: the polygon itself
  const vpMorphContour dense = square.resampled(160).transformed(0.0, 0.3, -0.2);
  vpMorphContour c = square;
  c.setOutline(dense);
  REQUIRE(c.hasOutline());
  CHECK(c.outline().size() == 160);
  // Bad outlines throw and leave the contour unchanged.
  CHECK_THROWS_AS(c.setOutline(vpMorphContour()), vpMorphException);
  CHECK_THROWS_AS(c.setOutline(vpMorphContour({0.0, 1.0, 0.0}, {0.0, 0.0, 1.0})), vpMorphException);
  CHECK_THROWS_AS(c.setOutline(dense.toNormalized(vpCameraParameters(800, 800, 320, 240))), vpMorphException);
  CHECK(c.outline().size() == 160);

  // Every geometric operation moves the outline with the polygon: compare with the same operation on it alone.
  auto same = [](const vpMorphContour &a, const vpMorphContour &b) {
    REQUIRE(a.size() == b.size());
    REQUIRE(a.units() == b.units());
    double e = 0;
    for (std::size_t k = 0; k < a.size(); ++k)
      e = std::max(e, std::hypot(a.x(k) - b.x(k), a.y(k) - b.y(k)));
    return e;
  };
  const vpCameraParameters cam(800, 780, 320, 240);
  const vpMorphContour n = c.toNormalized(cam);
  REQUIRE(n.hasOutline());
  CHECK(same(n.outline(), dense.toNormalized(cam)) < 1e-12);
  CHECK(same(n.toPixels(cam).outline(), dense) < 1e-9);
  CHECK(c.resampled(30).outline().size() == 160);
  CHECK(c.reversed().hasOutline());
  CHECK(c.rotatedStart(2).hasOutline());
  // transformed() turns about the polygon's centroid: the outline turns about the same point.
  const vpMorphContour t = c.transformed(0.4, 5.0, -3.0, 1.5);
  double cx, cy;
  c.centroid(cx, cy);
  std::vector<double> x, y;
  for (std::size_t k = 0; k < dense.size(); ++k) {
    const double dx = dense.x(k) - cx, dy = dense.y(k) - cy;
    x.push_back(cx + 1.5 * (std::cos(0.4) * dx - std::sin(0.4) * dy) + 5.0);
    y.push_back(cy + 1.5 * (std::sin(0.4) * dx + std::cos(0.4) * dy) - 3.0);
  }
  CHECK(same(t.outline(), vpMorphContour(x, y)) < 1e-9);
  const vpMorphContour m = c.mirrored();
  REQUIRE(m.hasOutline());
  CHECK(m.outline().x(0) == Approx(2 * cx - dense.x(0)));
  // A copy shares the outline; changing the copy's outline leaves the original's.
  vpMorphContour d = c;
  d.setOutline(square.resampled(8));
  CHECK(c.outline().size() == 160);
  CHECK(d.outline().size() == 8);
}
