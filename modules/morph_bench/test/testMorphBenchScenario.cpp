// Tests of the benchmark's scenario sets (vpMorphBenchScenario): reproducible from the seed and independent of the
// other objects, each set within the protocol's ranges, every start showing the object and the tag, the scene looks
// on the planar starts, set-up failures instead of aborts, a replay to the bit, clear errors for bad input.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_bench/vpMorphBench.h>
#include <visp3/morph_bench/vpMorphBenchScenario.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>

namespace
{
const std::string kData = VISPMORPH_DATA_DIR;

//! The six tools at the desired poses of the set seed (derived images under the test's working folder).
const vpMorphBenchObjectSet &tools()
{
  static const vpMorphBenchObjectSet t = vpMorphBenchObjectSet::tools(kData, "bench-scenarios");
  return t;
}

//! A black disc on white, 280 of its 300 px across, written to \e path: a compact object (15 cm in a scene).
void writeDisc(const std::string &path)
{
  vpImage<unsigned char> disc(300, 300, 255);
  for (unsigned int i = 0; i < 300; ++i)
    for (unsigned int j = 0; j < 300; ++j)
      if (std::hypot(i - 149.5, j - 149.5) < 140)
        disc[i][j] = 0;
  vpImageIo::write(disc, path);
}

bool samePose(const vpHomogeneousMatrix &a, const vpHomogeneousMatrix &b)
{
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 4; ++j)
      if (a[i][j] != b[i][j])
        return false;
  return true;
}
} // namespace

TEST_CASE("bench scenarios are reproducible from their seed and differ across seeds", "[bench]")
{
  const auto a = vpMorphBenchScenario::generate("calib", 6, 107, tools());
  const auto b = vpMorphBenchScenario::generate("calib", 6, 107, tools());
  const auto c = vpMorphBenchScenario::generate("calib", 6, 108, tools());
  REQUIRE(a.size() == 6);
  unsigned int differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK(a[i].seed == b[i].seed);
    CHECK(a[i].setSeed == 107);
    CHECK(samePose(a[i].cdMc, b[i].cdMc));
    CHECK(samePose(a[i].cdMo, b[i].cdMo));
    CHECK(a[i].focalScaleX == b[i].focalScaleX);
    CHECK(samePose(a[i].eMcError, b[i].eMcError));
    differ += samePose(a[i].cdMc, c[i].cdMc) ? 0 : 1;
  }
  CHECK(differ == a.size());
  // A scenario does not depend on how many are drawn: the first of 2 is the first of 6.
  const auto d = vpMorphBenchScenario::generate("calib", 2, 107, tools());
  CHECK(samePose(d[0].cdMc, a[0].cdMc));
  CHECK(samePose(d[1].cdMc, a[1].cdMc));
}

TEST_CASE("bench scenarios of an object do not depend on the other objects", "[bench]")
{
  // Start k of an object is drawn from (seed, set, name, k): with two objects the pliers' second start is index 2,
  // with three it is index 3, and it is the same start.
  const std::string o = kData + "/objects/";
  const vpMorphBenchObjectSet two =
      vpMorphBenchObjectSet::images({{o + "pliers.png", "pliers"}, {o + "key.png", "key"}}, "bench-two", 104);
  const vpMorphBenchObjectSet three = vpMorphBenchObjectSet::images(
      {{o + "pliers.png", "pliers"}, {o + "wedge.png", "wedge"}, {o + "key.png", "key"}}, "bench-three", 104);
  for (const std::string set : {"planar", "occlusion", "calib-wide"}) {
    const auto a = vpMorphBenchScenario::generate(set, 4, 104, two);
    const auto b = vpMorphBenchScenario::generate(set, 6, 104, three);
    REQUIRE(a[2].object == "pliers");
    REQUIRE(b[3].object == "pliers");
    CHECK(a[2].seed == b[3].seed);
    CHECK(samePose(a[2].cdMc, b[3].cdMc));
    CHECK(samePose(a[2].cdMo, b[3].cdMo));
    CHECK(samePose(a[2].eMcError, b[3].eMcError));
    CHECK(a[2].faults.occludedShare == b[3].faults.occludedShare);
    CHECK(a[2].tagX == b[3].tagX);
    // And the key's first start (index 1 and index 2).
    CHECK(samePose(a[1].cdMc, b[2].cdMc));
  }
}

TEST_CASE("bench desired poses come from the seed and the name, the object and the tag in the taught view", "[bench]")
{
  std::set<long> rotations;
  for (const std::string &name : vpMorphBenchScenario::objectNames()) {
    const vpHomogeneousMatrix a = vpMorphBenchScenario::desiredPose(100, name);
    CHECK(samePose(a, vpMorphBenchScenario::desiredPose(100, name)));
    CHECK_FALSE(samePose(a, vpMorphBenchScenario::desiredPose(101, name)));
    CHECK(a[2][3] == Approx(0.5));
    CHECK(std::fabs(a[2][2] - 1.0) < 1e-12); // optical axis normal to the plane
    CHECK(std::hypot(a[0][3], a[1][3]) <= 0.02 + 1e-12);
    rotations.insert(std::lround(vpMath::deg(std::atan2(a[1][0], a[0][0]))));
  }
  CHECK(rotations.size() == 6);
  // The taught view of each scenario shows object and tag, the tag the largest that fits.
  for (const vpMorphBenchScenario &s : vpMorphBenchScenario::generate("planar", 6, 100, tools())) {
    INFO(s.describe());
    REQUIRE(s.setup.empty());
    const vpMorphPlanarScene scene = s.scene();
    CHECK(scene.objectInView(s.cdMo, 10));
    CHECK(scene.tagInView(s.cdMo, 10));
    CHECK(s.tagSize == Approx(0.08));
  }
}

TEST_CASE("bench: an object that leaves the tag no room is a set-up failure, not an abort", "[bench][loop]")
{
  // A 15 cm disc seen from 0.3 m fills the image but for 4.5 cm on either side: no tag of 4 cm or more (5 cm with its
  // quiet zone, 1 cm from the object) fits there.
  writeDisc("bench-disc.png");
  vpMorphPlanarScene scene("bench-disc.png");
  const vpHomogeneousMatrix near(0, 0, 0.3, 0, 0, 0);
  CHECK(vpMorphBenchScenario::stage(scene, near) == "tag-fits-nowhere");
  CHECK(vpMorphBenchScenario::stage(scene, vpHomogeneousMatrix(0, 0, 0.1, 0, 0, 0)) == "object-not-in-view-at-goal");
  CHECK(vpMorphBenchScenario::stage(scene, vpHomogeneousMatrix(0, 0, 0.5, 0, 0, 0)).empty());
  // Its runs fail "setup" with the reason, for every controller; the bench does not throw.
  vpMorphBenchScenario s = vpMorphBenchScenario::generate("planar", 1, 100, tools())[0];
  s.setup = "tag-fits-nowhere";
  vpMorphBench::Settings st;
  st.maxIterations = 5;
  const vpMorphBench bench(tools(), 100, st);
  for (const std::string c : {"morph", "pbvs"}) {
    const vpMorphBenchResult r = bench.run(s, c);
    CHECK(r.failure == "setup");
    CHECK(r.setup == "tag-fits-nowhere");
    CHECK(r.iterations == 0);
    CHECK_FALSE(r.success);
  }
}

TEST_CASE("calib-no-tilt draws calib's starts and errors, the hand-eye rotation error about the optical axis only",
          "[bench]")
{
  const auto calib = vpMorphBenchScenario::generate("calib", 8, 103, tools());
  const auto noTilt = vpMorphBenchScenario::generate("calib-no-tilt", 8, 103, tools());
  REQUIRE(noTilt.size() == calib.size());
  unsigned int tilted = 0;
  for (std::size_t i = 0; i < calib.size(); ++i) {
    CHECK(noTilt[i].set == "calib-no-tilt");
    CHECK(noTilt[i].seed == calib[i].seed);
    CHECK(noTilt[i].object == calib[i].object);
    CHECK(samePose(noTilt[i].cdMc, calib[i].cdMc));
    CHECK(noTilt[i].focalScaleX == calib[i].focalScaleX);
    CHECK(noTilt[i].principalShiftV == calib[i].principalShiftV);
    const vpTranslationVector t = noTilt[i].eMcError.getTranslationVector(),
                              tc = calib[i].eMcError.getTranslationVector();
    CHECK((t - tc).frobeniusNorm() == 0.0);
    const vpThetaUVector tu(noTilt[i].eMcError.getRotationMatrix()), tuc(calib[i].eMcError.getRotationMatrix());
    CHECK(std::hypot(tu[0], tu[1]) < 1e-12);
    CHECK(tu[2] == Approx(tuc[2]).margin(1e-12));
    tilted += std::hypot(tuc[0], tuc[1]) > vpMath::rad(1) ? 1 : 0;
  }
  CHECK(tilted > 0); // calib's own errors do tilt the camera on the hand
}

TEST_CASE("the scene looks and the resolutions are the planar starts rendered otherwise", "[bench]")
{
  const auto planar = vpMorphBenchScenario::generate("planar", 6, 105, tools());
  for (const std::string set :
       {"saturated", "low-contrast", "rough", "gradient", "plane-edge", "large-distractor", "res-1280", "res-320"}) {
    const auto look = vpMorphBenchScenario::generate(set, 6, 105, tools());
    for (std::size_t i = 0; i < look.size(); ++i) {
      INFO(look[i].describe());
      CHECK(look[i].object == planar[i].object);
      CHECK(look[i].seed == planar[i].seed);
      if (!look[i].setup.empty()) {
        CHECK((set == "large-distractor" && look[i].setup == "no-room-for-distractor"));
        continue;
      }
      CHECK(samePose(look[i].cdMc, planar[i].cdMc));
      CHECK(samePose(look[i].cdMo, planar[i].cdMo));
      const vpMorphPlanarScene::Faults &f = look[i].faults;
      if (set == "saturated") {
        CHECK(f.gain >= 1.3);
        CHECK(210 * f.gain + f.offset >= 265.0 - 1e-9); // the plane clipped by at least 10 levels
      } else if (set == "low-contrast") {
        CHECK(170 * f.gain >= 15.0 - 1e-9);
        CHECK(170 * f.gain <= 40.0 + 1e-9);
        CHECK(f.noiseSigma >= 0.5);
      } else if (set == "gradient") {
        CHECK(f.gradient >= 0.3);
        CHECK(f.gradient <= 0.6);
      } else if (set == "rough") {
        CHECK(look[i].variant == "rough");
        CHECK(look[i].objectImage == look[i].templateImage);
        CHECK(look[i].objectImage != planar[i].objectImage);
      } else if (set == "plane-edge") {
        CHECK(f.planeEdge);
      } else if (set == "large-distractor") {
        const vpMorphPlanarScene scene = look[i].scene();
        CHECK(f.largeDistractorArea >= 1.2 * scene.objectArea() - 1e-12);
        CHECK(scene.distractorCorners3D().size() == 1);
      } else {
        CHECK(look[i].width == (set == "res-1280" ? 1280u : 320u));
        CHECK(look[i].camera.get_px() == look[i].width * 1.25);
        // The same start seen at another resolution: object and tag in view, the tag placed alike.
        CHECK(look[i].tagX == Approx(planar[i].tagX).margin(1e-9));
      }
    }
  }
}

TEST_CASE("the large distractor is larger in view than the object, beside a compact object too", "[bench]")
{
  // A 15 cm disc leaves no room in view for a rectangle larger than itself beside it and the tag: the rectangle runs
  // past the image's border, its part in view 1.2-1.6 times the disc's region.
  writeDisc("bench-distractor-disc.png");
  const vpMorphBenchObjectSet discs =
      vpMorphBenchObjectSet::images({{"bench-distractor-disc.png", "disc"}}, "bench-distractor", 100);
  REQUIRE(discs.size() == 1);
  for (const vpMorphBenchObjectSet *objects : {&discs, &tools()}) {
    for (const vpMorphBenchScenario &s : vpMorphBenchScenario::generate("large-distractor", 6, 107, *objects)) {
      INFO(s.describe());
      REQUIRE(s.setup.empty());
      const vpMorphPlanarScene scene = s.scene();
      const vpHomogeneousMatrix cMo = s.cdMc.inverse() * s.cdMo;
      vpImage<unsigned char> I;
      scene.render(cMo, I);
      // The object's and the tag's regions are the ones about their centres; the distractor is the largest other.
      auto centre = [&](const std::vector<vpPoint> &P) {
        vpImagePoint c;
        for (vpPoint p : P) {
          p.track(cMo);
          double u = 0, v = 0;
          vpMeterPixelConversion::convertPoint(scene.camera(), p.get_x(), p.get_y(), u, v);
          c += vpImagePoint(v, u) * (1.0 / P.size());
        }
        return c;
      };
      const vpImagePoint objectCentre = centre({vpPoint(0, 0, 0)}), tagCentre = centre(scene.tagTextureCorners3D());
      std::vector<vpMorphContour> regions = vpMorphContourExtractor().extractAll(I);
      auto nearest = [&regions](const vpImagePoint &c) {
        return std::min_element(regions.begin(), regions.end(), [&c](const auto &a, const auto &b) {
          double ax = 0, ay = 0, bx = 0, by = 0;
          a.centroid(ax, ay);
          b.centroid(bx, by);
          return std::hypot(ax - c.get_u(), ay - c.get_v()) < std::hypot(bx - c.get_u(), by - c.get_v());
        });
      };
      regions.erase(nearest(objectCentre));
      regions.erase(nearest(tagCentre));
      REQUIRE_FALSE(regions.empty());
      // The looks start fronto-parallel: the object's outline in view is its area on the plane times (px / Z)^2.
      const double objectPx = scene.objectArea() * std::pow(scene.camera().get_px() / cMo[2][3], 2);
      const double share = regions.front().regionArea() / objectPx; // regions by decreasing area
      INFO("distractor over object in view " << share);
      // The region loses up to half a pixel along the image's border: 1 % of the area at most here.
      CHECK(share >= 1.2 * 0.99);
      CHECK(share <= 1.6 * 1.01);
    }
  }
}

TEST_CASE("bench scenario sets follow the protocol's ranges and show object and tag at the start", "[bench]")
{
  for (const std::string &set : vpMorphBenchScenario::setNames()) {
    const auto scs = vpMorphBenchScenario::generate(set, 6, 103, tools());
    REQUIRE(scs.size() == 6);
    for (const vpMorphBenchScenario &s : scs) {
      INFO(s.describe());
      CHECK(s.set == set);
      if (!s.setup.empty()) {
        CHECK(set == "large-distractor"); // the only set whose draws may find no room
        continue;
      }
      CHECK(std::fabs(s.startRotationDeg) <= 180.0);
      CHECK(s.startTranslationMm <= 80.0 + 1e-9);
      // The start shows the object and the tag (the object seen is the deformed one for "deformable").
      const vpMorphPlanarScene scene = s.scene();
      const vpHomogeneousMatrix cMo = s.cdMc.inverse() * s.cdMo;
      CHECK(scene.objectInView(cMo, vpMorphBenchScenario::viewMargin(s.width)));
      CHECK(scene.tagInView(cMo, vpMorphBenchScenario::viewMargin(s.width)));
      if (set == "planar-hard")
        CHECK(std::fabs(s.startRotationDeg) >= 150.0);
      if (set == "6dof") {
        CHECK(s.startTiltDeg <= 30.0);
        CHECK(std::fabs(s.startDepthChange) <= 0.4);
      } else {
        CHECK(s.startTiltDeg == 0.0);
        CHECK(s.startDepthChange == 0.0);
        CHECK(std::fabs(s.cdMc[2][3]) < 1e-12); // same depth
      }
      if (set == "calib" || set == "calib-no-tilt") {
        CHECK(std::fabs(s.focalScaleX - 1) <= 0.2);
        CHECK(std::fabs(s.focalScaleY - 1) <= 0.2);
        CHECK(s.eMcError.getTranslationVector().frobeniusNorm() <= 0.02);
        CHECK(vpThetaUVector(s.eMcError.getRotationMatrix()).getTheta() <= vpMath::rad(10) + 1e-9);
      } else if (set == "calib-wide") {
        CHECK(s.focalScaleX == s.focalScaleY); // px and py together
        CHECK(std::fabs(s.focalScaleX - 1) <= 0.3);
        CHECK(std::fabs(s.principalShiftU) <= 10.0);
        CHECK(std::fabs(s.principalShiftV) <= 10.0);
        CHECK(s.eMcError.getTranslationVector().frobeniusNorm() <= 0.05);
        const vpThetaUVector tu(s.eMcError.getRotationMatrix());
        CHECK(std::hypot(tu[0], tu[1]) < 1e-12); // about the optical axis only
        CHECK(std::fabs(tu[2]) <= vpMath::rad(90) + 1e-9);
      } else {
        CHECK(s.focalScaleX == 1.0);
        CHECK(samePose(s.eMcError, vpHomogeneousMatrix()));
      }
      // The hand-eye error drawn lies within the tolerance the controllers are told.
      CHECK(s.eMcError.getTranslationVector().frobeniusNorm() <= s.eMcTranslationTolerance + 1e-12);
      CHECK(vpThetaUVector(s.eMcError.getRotationMatrix()).getTheta() <= s.eMcRotationTolerance + 1e-9);
      if (set == "noise")
        CHECK(s.faults.noiseSigma >= 1.0);
      else if (set != "low-contrast")
        CHECK(s.faults.noiseSigma == 0.0);
      if (set == "occlusion")
        CHECK((s.faults.occludedShare >= 0.05 && s.faults.occludedShare <= 0.2));
      CHECK((s.objectImage != s.templateImage) == (set == "deformable"));
      CHECK(s.events.empty() == (set != "faults")); // timed faults only in their set
    }
  }
}

TEST_CASE("a scenario replays from its JSON to the bit", "[bench]")
{
  for (const std::string set : {"faults", "calib-wide", "plane-edge", "deformable"}) {
    for (const vpMorphBenchScenario &s : vpMorphBenchScenario::generate(set, 5, 106, tools())) {
      INFO(s.describe());
      const vpMorphBenchScenario r = vpMorphBenchScenario::fromJson(s.toJson(kData), kData);
      CHECK(r.toJson() == s.toJson());
      CHECK(r.describe() == s.describe());
      CHECK(samePose(r.cdMc, s.cdMc));
      CHECK(samePose(r.eMcError, s.eMcError));
    }
  }
  CHECK_THROWS_AS(vpMorphBenchScenario::fromJson("{\"set\": 3"), vpMorphException);
  CHECK_THROWS_AS(vpMorphBenchScenario::fromJson("{\"set\": \"planar\"}"), vpMorphException);
  // A negative hand-eye tolerance is no tolerance: a clear error.
  std::string text = vpMorphBenchScenario::generate("calib-wide", 1, 106, tools())[0].toJson(kData);
  const std::size_t at = text.find("\"eMc_tolerance\":[");
  REQUIRE(at != std::string::npos);
  text.insert(at + std::string("\"eMc_tolerance\":[").size(), "-");
  try {
    vpMorphBenchScenario::fromJson(text, kData);
    FAIL("a negative tolerance was read");
  } catch (const vpMorphException &e) {
    CHECK(e.getStringMessage().find("eMc_tolerance") != std::string::npos);
  }
}

TEST_CASE("bench scenario bad input gives clear errors", "[bench]")
{
  CHECK_THROWS_AS(vpMorphBenchScenario::generate("bogus", 3, 1, tools()), vpMorphException);
  CHECK_THROWS_AS(vpMorphBenchScenario::generate("planar", 0, 1, tools()), vpMorphException);
  CHECK_THROWS_AS(vpMorphBenchScenario::generate("planar", 2, 1, vpMorphBenchObjectSet()), vpMorphException);
  try {
    vpMorphBenchScenario::generate("bogus", 3, 1, tools());
  } catch (const vpMorphException &e) {
    CHECK(e.getStringMessage().find("unknown set 'bogus'") != std::string::npos);
  }
}
