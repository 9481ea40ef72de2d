// vpMorphOutlineFit: the robust outline fit of the servo's measurement, on dense synthetic outlines whose answer is
// known (a similarity, a part hidden, a part bent, an outline grown all round).
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphOutlineFit.h>

namespace
{
// A dense closed outline (a point every pixel or so) of an asymmetric blob: radius r(t) with a few lobes, about 200 px
// across, counter-clockwise in (x, y).
vpMorphContour blob(double noise = 0.0, unsigned int seed = 1)
{
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, noise > 0.0 ? noise : 1.0);
  std::vector<double> x, y;
  const int n = 700;
  for (int k = 0; k < n; ++k) {
    const double t = 2.0 * M_PI * k / n;
    const double r = 100.0 + 25.0 * std::cos(2.0 * t) + 12.0 * std::sin(3.0 * t + 0.4) + 6.0 * std::cos(5.0 * t + 1.0);
    const double e = noise > 0.0 ? g(rng) : 0.0; // along the radius: an edge point's error is across the edge
    x.push_back(320.0 + (r + e) * std::cos(t));
    y.push_back(240.0 + (r + e) * std::sin(t));
  }
  return vpMorphContour(x, y);
}

// The outline with its points from angle a0 to a1 (about its centre (320, 240)) bent: turned by \e turn about the
// point at a0 (a limb turned away), or cut: replaced by the chord between the two ends (an occluder's edge).
vpMorphContour bent(const vpMorphContour &c, double a0, double a1, double turn)
{
  std::vector<double> x(c.xs()), y(c.ys());
  double px = 0.0, py = 0.0;
  bool pivot = false;
  for (std::size_t k = 0; k < c.size(); ++k) {
    const double a = std::atan2(c.y(k) - 240.0, c.x(k) - 320.0);
    if (a < a0 || a > a1)
      continue;
    if (!pivot) {
      px = c.x(k);
      py = c.y(k);
      pivot = true;
    }
    const double dx = c.x(k) - px, dy = c.y(k) - py;
    x[k] = px + std::cos(turn) * dx - std::sin(turn) * dy;
    y[k] = py + std::sin(turn) * dx + std::cos(turn) * dy;
  }
  return vpMorphContour(x, y);
}

vpMorphContour cut(const vpMorphContour &c, double a0, double a1)
{
  std::vector<double> x, y;
  bool chord = false;
  for (std::size_t k = 0; k < c.size(); ++k) {
    const double a = std::atan2(c.y(k) - 240.0, c.x(k) - 320.0);
    if (a >= a0 && a <= a1) {
      chord = true; // the hidden stretch: the polygon goes straight across it (the occluder's edge)
      continue;
    }
    x.push_back(c.x(k));
    y.push_back(c.y(k));
  }
  REQUIRE(chord);
  return vpMorphContour(x, y);
}

double poseError(const vpMorphRigidTransform &T, const vpMorphRigidTransform &truth, const vpMorphContour &c)
{
  double e = 0.0;
  for (std::size_t k = 0; k < c.size(); k += 7) {
    double x0, y0, x1, y1;
    T.apply(c.x(k), c.y(k), x0, y0);
    truth.apply(c.x(k), c.y(k), x1, y1);
    e = std::max(e, std::hypot(x1 - x0, y1 - y0));
  }
  return e;
}
} // namespace

TEST_CASE("vpMorphOutlineFit recovers a similarity, and its covariance predicts the scatter under noise",
          "[morph][outline_fit]")
{
  const vpMorphContour goal = blob();
  const vpMorphRigidTransform truth(0.7, 12.0, -8.0, 1.05, 320.0, 240.0);
  std::vector<double> dth, dls;
  double predictedTheta = 0.0, predictedScale = 0.0;
  for (unsigned int trial = 0; trial < 40; ++trial) {
    const vpMorphContour view = truth.inverse().apply(blob(0.1, 100 + trial));
    vpMorphOutlineFit fit(goal);
    const vpMorphRigidTransform start = vpMorphRigidTransform(0.03, 3.0, -2.0, 1.01, 320.0, 240.0) * truth;
    const vpMorphRigidTransform T = fit.fit(view, start);
    CHECK(poseError(T, truth, view) < 0.1);
    CHECK(fit.getInlierShare() > 0.95);
    CHECK(fit.getOutsideShare() == 0.0);
    CHECK(fit.getInsideShare() == 0.0);
    CHECK(fit.getSigma() > 0.04); // the view's 0.1 px of radial noise, seen across the edges
    CHECK(fit.getSigma() < 0.12);
    dth.push_back(std::remainder(T.theta() - truth.theta(), 2.0 * M_PI));
    dls.push_back(std::log(T.scale() / truth.scale()));
    predictedTheta += std::sqrt(fit.getCovariance()[0][0]) / 40.0;
    predictedScale += std::sqrt(fit.getCovariance()[3][3]) / 40.0;
  }
  double sdTheta = 0.0, sdScale = 0.0;
  for (std::size_t k = 0; k < dth.size(); ++k) {
    sdTheta += dth[k] * dth[k] / dth.size();
    sdScale += dls[k] * dls[k] / dls.size();
  }
  sdTheta = std::sqrt(sdTheta);
  sdScale = std::sqrt(sdScale);
  INFO("rotation sd " << sdTheta << " predicted " << predictedTheta << "; log-scale sd " << sdScale << " predicted "
                      << predictedScale);
  CHECK(sdTheta < 3.0 * predictedTheta);
  CHECK(sdTheta > predictedTheta / 3.0);
  CHECK(sdScale < 3.0 * predictedScale);
  CHECK(sdScale > predictedScale / 3.0);
}

TEST_CASE("vpMorphOutlineFit lays a view with a part hidden by the part it shows", "[morph][outline_fit]")
{
  const vpMorphContour goal = blob();
  const vpMorphRigidTransform truth(-2.0, -20.0, 15.0, 0.95, 320.0, 240.0);
  const vpMorphContour view = truth.inverse().apply(cut(blob(0.05, 3), 0.3, 1.1)); // about an eighth hidden
  vpMorphOutlineFit fit(goal);
  const vpMorphRigidTransform T = fit.fit(view, vpMorphRigidTransform(0.04, 4.0, 3.0, 1.02, 320.0, 240.0) * truth);
  CHECK(poseError(T, truth, view) < 0.05);
  CHECK(fit.getInsideShare() > 0.02); // the chord lies inside the goal
  CHECK(fit.getOutsideShare() == 0.0);
  CHECK(fit.getGoalCoverage() < 0.95); // the goal's hidden stretch has nothing on it
}

TEST_CASE("vpMorphOutlineFit's search finds the part a bend did not move, from a start in another basin",
          "[morph][outline_fit]")
{
  const vpMorphContour goal = blob();
  const vpMorphRigidTransform truth(2.5, 10.0, 5.0, 1.0, 320.0, 240.0);
  const vpMorphContour view = truth.inverse().apply(bent(blob(0.05, 4), -0.4, 0.9, 0.25));
  vpMorphOutlineFit fit(goal);
  // Started half a turn off: no local refinement gets back from there.
  const vpMorphRigidTransform wrong = vpMorphRigidTransform(M_PI - 0.1, 0.0, 0.0, 1.0, 320.0, 240.0) * truth;
  const vpMorphRigidTransform T = fit.search(view, wrong);
  INFO("error " << poseError(T, truth, view) << " px");
  CHECK(poseError(T, truth, view) < 0.1);
  CHECK(fit.getOutsideShare() > 0.05); // the limb sticks out
  CHECK(fit.getInlierShare() > 0.6);
  // fit() alone from there lands elsewhere, with a far larger residual scale.
  vpMorphOutlineFit local(goal);
  local.fit(view, wrong);
  CHECK(local.getSigma() > 10.0 * fit.getSigma());
}

TEST_CASE("vpMorphOutlineFit takes an outline grown all round for an edge offset, not a depth", "[morph][outline_fit]")
{
  const vpMorphContour goal = blob();
  // The view's outline 0.15 px out all round (a clipped lighting), seen at the goal's pose.
  std::vector<double> x, y;
  for (std::size_t k = 0; k < goal.size(); ++k) {
    const std::size_t a = (k + goal.size() - 1) % goal.size(), b = (k + 1) % goal.size();
    const double tx = goal.x(b) - goal.x(a), ty = goal.y(b) - goal.y(a), l = std::hypot(tx, ty);
    x.push_back(goal.x(k) + 0.15 * ty / l); // the right normal of a counter-clockwise outline points out
    y.push_back(goal.y(k) - 0.15 * tx / l);
  }
  const vpMorphContour view(x, y);
  vpMorphOutlineFit fit(goal);
  const vpMorphRigidTransform T = fit.fit(view, vpMorphRigidTransform());
  CHECK(T.scale() == Approx(1.0).margin(2e-4));
  CHECK(fit.getOffset() == Approx(0.15).margin(0.02));
  vpMorphOutlineFit plain(goal);
  plain.setEdgeOffset(false);
  const vpMorphRigidTransform Tp = plain.fit(view, vpMorphRigidTransform());
  CHECK(std::fabs(Tp.scale() - 1.0) > 5e-4); // without the offset the band is taken for scale
}

namespace
{
// The blob with a part sticking out at angle \e a: a neck \e neck wide and \e length long, ending in a disc of
// radius \e knob (0: a round cap as wide as the neck), in place of the outline's points across the neck's base.
vpMorphContour withPart(const vpMorphContour &c, double a, double neck, double length, double knob)
{
  std::size_t k0 = 0;
  for (std::size_t k = 0; k < c.size(); ++k)
    if (std::fabs(std::remainder(std::atan2(c.y(k) - 240.0, c.x(k) - 320.0) - a, 2 * M_PI)) <
        std::fabs(std::remainder(std::atan2(c.y(k0) - 240.0, c.x(k0) - 320.0) - a, 2 * M_PI)))
      k0 = k;
  const double px = c.x(k0), py = c.y(k0);
  const double tx = c.x((k0 + 1) % c.size()) - c.x((k0 + c.size() - 1) % c.size()),
               ty = c.y((k0 + 1) % c.size()) - c.y((k0 + c.size() - 1) % c.size()), tn = std::hypot(tx, ty);
  const double ux = tx / tn, uy = ty / tn, nx = uy, ny = -ux; // along the outline, and out of the blob (CCW)
  std::vector<double> x, y;
  bool done = false;
  for (std::size_t k = 0; k < c.size(); ++k) {
    const double along = (c.x(k) - px) * ux + (c.y(k) - py) * uy;
    if (std::fabs(along) <= 0.5 * neck + 0.5 && std::hypot(c.x(k) - px, c.y(k) - py) < neck + 1.0) {
      if (done)
        continue;
      done = true;
      const double r = knob > 0.0 ? knob : 0.5 * neck;
      const double stem = knob > 0.0 ? length : length - r;
      for (double s = 0.0; s < stem; s += 0.5) // out along one side
        x.push_back(px - 0.5 * neck * ux + s * nx), y.push_back(py - 0.5 * neck * uy + s * ny);
      const double cx = px + (stem + (knob > 0.0 ? std::sqrt(r * r - 0.25 * neck * neck) : 0.0)) * nx,
                   cy = py + (stem + (knob > 0.0 ? std::sqrt(r * r - 0.25 * neck * neck) : 0.0)) * ny;
      const double b0 = std::atan2(py - 0.5 * neck * uy + stem * ny - cy, px - 0.5 * neck * ux + stem * nx - cx);
      const double b1 = std::atan2(py + 0.5 * neck * uy + stem * ny - cy, px + 0.5 * neck * ux + stem * nx - cx);
      double sweep = std::remainder(b1 - b0, 2 * M_PI); // round the end, through the tip
      if (sweep > 0.0)
        sweep -= 2 * M_PI;
      const int steps = std::max(4, static_cast<int>(std::fabs(sweep) * r / 0.5));
      for (int i = 0; i <= steps; ++i)
        x.push_back(cx + r * std::cos(b0 + sweep * i / steps)), y.push_back(cy + r * std::sin(b0 + sweep * i / steps));
      for (double s = stem - 0.5; s > 0.0; s -= 0.5) // and back along the other
        x.push_back(px + 0.5 * neck * ux + s * nx), y.push_back(py + 0.5 * neck * uy + s * ny);
      continue;
    }
    x.push_back(c.x(k));
    y.push_back(c.y(k));
  }
  return vpMorphContour(x, y);
}
} // namespace

TEST_CASE("vpMorphOutlineFit does not take a part finer than the pixel grid's phase for a bent one",
          "[morph][outline_fit]")
{
  // A filament, and a knob on a neck, thinner than the fine width: seen in one image and not in the next as the grid
  // moves under them; a tab wider than it is a part the goal lacks.
  const vpMorphContour goal = blob();
  const double fineWidth = vpMorphOutlineFit::fineWidth(1.0, 0.45); // a pixel, the renderer's blur
  struct Part
  {
    const char *name;
    double neck, length, knob;
    bool counted;
  };
  for (const Part &part : {Part{"filament", 1.0, 20.0, 0.0, false}, Part{"knob on a neck", 1.2, 8.0, 5.0, false},
                           Part{"tab", 8.0, 14.0, 0.0, true}}) {
    INFO(part.name);
    const vpMorphContour view = withPart(blob(), 1.0, part.neck, part.length, part.knob);
    for (const double width : {0.0, fineWidth}) {
      vpMorphOutlineFit fit(goal);
      fit.setMinimumSigma(0.1);
      fit.setFineWidth(width);
      fit.fit(view, vpMorphRigidTransform());
      INFO("fine width " << width);
      CHECK(fit.getInsideShare() == 0.0);
      CHECK((fit.getOutsideShare() > 0.0) == (part.counted || width == 0.0));
    }
  }
  vpMorphOutlineFit fit(goal);
  CHECK_THROWS_AS(fit.setFineWidth(-1.0), vpMorphException);
  CHECK_THROWS_AS(fit.setFineWidth(std::nan("")), vpMorphException);
  CHECK(fit.getFineWidth() == 0.0);
}

TEST_CASE("vpMorphOutlineFit settings and bad input", "[morph][outline_fit][bad]")
{
  CHECK_THROWS_AS(vpMorphOutlineFit(vpMorphContour()), vpMorphException);
  vpMorphOutlineFit fit(blob());
  CHECK_THROWS_AS(fit.setMinimumSigma(-1.0), vpMorphException);
  CHECK_THROWS_AS(fit.setMinimumSigma(std::nan("")), vpMorphException);
  CHECK_THROWS_AS(fit.setMaxIterations(0), vpMorphException);
  CHECK_THROWS_AS(fit.setSampleCount(4), vpMorphException);
  CHECK_THROWS_AS(fit.fit(vpMorphContour(), vpMorphRigidTransform()), vpMorphException);
  CHECK_THROWS_AS(fit.fit(blob(), vpMorphRigidTransform(), -1.0), vpMorphException);
  const vpMorphContour normalised(std::vector<double>{0.0, 0.1, 0.1}, std::vector<double>{0.0, 0.0, 0.1},
                                  vpMorphContour::NORMALIZED);
  CHECK_THROWS_AS(fit.fit(normalised, vpMorphRigidTransform()), vpMorphException);
  // The criterion that compares fits: 0 on the goal's edges, 1 far off.
  CHECK(vpMorphOutlineFit::cost(std::vector<double>{0.0, 0.0}, 1.0) == 0.0);
  CHECK(vpMorphOutlineFit::cost(std::vector<double>{100.0}, 1.0) == 1.0);
  CHECK(vpMorphOutlineFit::cost(std::vector<double>(), 1.0) == 1.0);
  // A fit of the goal on itself.
  const vpMorphRigidTransform T = fit.fit(blob(), vpMorphRigidTransform());
  CHECK(std::fabs(T.scale() - 1.0) < 1e-9);
  CHECK(fit.getResiduals().size() == 256);
}
