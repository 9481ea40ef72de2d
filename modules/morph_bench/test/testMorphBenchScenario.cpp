// Tests of the benchmark's scenario sets (vpMorphBenchScenario): reproducible from the seed, each set within the
// protocol's ranges, every start showing the object and the tag, clear errors for bad input.
#include <catch2/catch.hpp>

#include <cmath>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_bench/vpMorphBenchScenario.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>

namespace
{
const std::string kData = VISPMORPH_DATA_DIR;

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
  const auto a = vpMorphBenchScenario::generate("calib", 6, 7, kData);
  const auto b = vpMorphBenchScenario::generate("calib", 6, 7, kData);
  const auto c = vpMorphBenchScenario::generate("calib", 6, 8, kData);
  REQUIRE(a.size() == 6);
  unsigned int differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK(a[i].seed == b[i].seed);
    CHECK(samePose(a[i].cdMc, b[i].cdMc));
    CHECK(a[i].focalScaleX == b[i].focalScaleX);
    CHECK(samePose(a[i].eMcError, b[i].eMcError));
    differ += samePose(a[i].cdMc, c[i].cdMc) ? 0 : 1;
  }
  CHECK(differ == a.size());
  // A scenario does not depend on how many are drawn: the first of 2 is the first of 6.
  const auto d = vpMorphBenchScenario::generate("calib", 2, 7, kData);
  CHECK(samePose(d[0].cdMc, a[0].cdMc));
  CHECK(samePose(d[1].cdMc, a[1].cdMc));
}

TEST_CASE("calib-no-tilt draws calib's starts and errors, the hand-eye rotation error about the optical axis only",
          "[bench]")
{
  const auto calib = vpMorphBenchScenario::generate("calib", 8, 3, kData);
  const auto noTilt = vpMorphBenchScenario::generate("calib-no-tilt", 8, 3, kData);
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

TEST_CASE("bench scenario sets follow the protocol's ranges and show object and tag at the start", "[bench]")
{
  for (const std::string &set : vpMorphBenchScenario::setNames()) {
    const auto scs = vpMorphBenchScenario::generate(set, 12, 3, kData);
    REQUIRE(scs.size() == 12);
    for (const vpMorphBenchScenario &s : scs) {
      INFO(s.describe());
      CHECK(s.set == set);
      CHECK(std::fabs(s.startRotationDeg) <= 180.0);
      CHECK(s.startTranslationMm <= 80.0 + 1e-9);
      // The start shows the object and the tag (the object seen is the deformed one for "deformable").
      const vpMorphPlanarScene scene = s.scene();
      const vpHomogeneousMatrix cMo = s.cdMc.inverse() * s.cdMo;
      CHECK(scene.objectInView(cMo, 10));
      CHECK(scene.tagInView(cMo, 10));
      // The desired pose: optical axis normal to the plane at 0.5 m.
      CHECK(s.cdMo[2][3] == Approx(0.5));
      CHECK(std::fabs(s.cdMo[2][2] - 1.0) < 1e-12);
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
      } else {
        CHECK(s.focalScaleX == 1.0);
        CHECK(samePose(s.eMcError, vpHomogeneousMatrix()));
      }
      if (set == "noise")
        CHECK(s.faults.noiseSigma >= 1.0);
      else
        CHECK(s.faults.noiseSigma == 0.0);
      if (set == "occlusion")
        CHECK((s.faults.occludedShare >= 0.05 && s.faults.occludedShare <= 0.2));
      CHECK((s.objectImage != s.templateImage) == (set == "deformable"));
      CHECK(s.events.empty() == (set != "faults")); // timed faults only in their set
    }
  }
}

TEST_CASE("bench scenario bad input gives clear errors", "[bench]")
{
  CHECK_THROWS_AS(vpMorphBenchScenario::generate("bogus", 3, 1, kData), vpMorphException);
  CHECK_THROWS_AS(vpMorphBenchScenario::generate("planar", 0, 1, kData), vpMorphException);
  CHECK_THROWS_AS(vpMorphBenchScenario::generate("planar", 2, 1, "/nonexistent"), vpMorphException);
  CHECK_THROWS_AS(vpMorphBenchScenario::desiredPose("spoon"), vpMorphException);
  try {
    vpMorphBenchScenario::generate("bogus", 3, 1, kData);
  } catch (const vpMorphException &e) {
    CHECK(e.getStringMessage().find("unknown set 'bogus'") != std::string::npos);
  }
}
