// The articulated pliers in the bench: the template taught with its two arms, the opened pliers laid by either arm,
// recognised at their opening, and aligned by vpServoMorph and by vpFeatureMorph in a stock vpServo.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <visp3/core/vpMath.h>
#include <visp3/morph/vpMorphArticulation.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_bench/vpMorphBench.h>
#include <visp3/morph_bench/vpMorphBenchScenario.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>
#include <visp3/morph_vs/vpServoMorph.h>

namespace
{
const std::string kData = VISPMORPH_DATA_DIR;

const vpMorphBench &bench()
{
  static const vpMorphBench b(kData, vpMorphBench::Settings());
  return b;
}
} // namespace

TEST_CASE("bench: the pliers' template is taught with its two arms", "[bench][articulation]")
{
  const vpMorphTemplate &t = bench().database()["pliers"];
  REQUIRE(t.isArticulated());
  CHECK_FALSE(bench().database()["key"].isArticulated());
  const vpMorphArticulation &a = t.articulation();
  // The camera at the desired pose is parallel to the plane: the drawing's range, not mirrored.
  CHECK(vpMath::deg(a.minAngle()) == Approx(-8.0));
  CHECK(vpMath::deg(a.maxAngle()) == Approx(60.0));
  // Posed at the taught opening, the arms make the taught view.
  for (unsigned int k : {0u, 1u}) {
    const vpMorphContour p = a.pose(0.0, k);
    double px, py, tx, ty;
    p.regionCentroid(px, py);
    t.contour().regionCentroid(tx, ty);
    CHECK(p.regionArea() / t.contour().regionArea() == Approx(1.0).epsilon(0.003));
    CHECK(std::hypot(px - tx, py - ty) < 0.05);
  }
}

TEST_CASE("bench: the opened pliers are laid by either arm and recognised at their opening", "[bench][articulation]")
{
  const std::vector<vpMorphBenchScenario> scs = vpMorphBenchScenario::generate("deformable", 20, 1, kData);
  for (std::size_t k : {0, 6, 12, 18}) {
    REQUIRE(scs[k].object == "pliers");
    const vpMorphPlanarScene scene = scs[k].scene();
    const std::vector<vpHomogeneousMatrix> alt = scene.alternativePlacements();
    REQUIRE(alt.size() == 1);
    // The other arm's placement turns the object by the opening about the pin, which stays where it is.
    CHECK(std::fabs(vpMath::deg(std::atan2(alt[0][1][0], alt[0][0][0]))) == Approx(32.0).margin(1e-6));
    const vpImagePoint pin = scene.projectedTexel(320, 240, scs[k].cdMo);
    CHECK(vpImagePoint::distance(pin, scene.projectedTexel(320, 240, scs[k].cdMo * alt[0])) < 1e-6);
    const vpMorphRecognition r = bench().recognizeStart(scs[k]);
    CHECK(bench().database()[r.index].name() == "pliers");
    CHECK(r.accepted);
    CHECK(std::fabs(vpMath::deg(r.articulation) - 32.0) <= 2.0);
  }
  // A rigid object has one best placement.
  CHECK(scs[1].scene().alternativePlacements().empty());
}

TEST_CASE("bench: vpServoMorph and vpFeatureMorph align opened pliers by either arm", "[bench][articulation]")
{
  // Before the articulated template these views were rejected by recognition (and, given the closed template,
  // vpServoMorph stopped on them: DEFORMATION_UNRESOLVED).
  const std::vector<vpMorphBenchScenario> seed1 = vpMorphBenchScenario::generate("deformable", 10, 1, kData);
  const std::vector<vpMorphBenchScenario> seed3 = vpMorphBenchScenario::generate("deformable", 20, 3, kData);
  const std::vector<std::pair<const vpMorphBenchScenario *, std::string>> runs{
      {&seed1[0], "morph"}, {&seed1[6], "morph"}, {&seed3[12], "morph"}, {&seed1[0], "morph-vpservo"}};
  for (const auto &run : runs) {
    const vpMorphBenchResult r = bench().run(*run.first, run.second);
    std::printf("[articulated] opened pliers, start %u (scenario seed %u), %s: %s, goal %u (arm), %.3f mm %.3f deg, %u "
                "periods\n",
                run.first->index, run.first->seed, run.second.c_str(), r.success ? "success" : r.failure.c_str(),
                r.goal, 1000 * r.finalTranslation, vpMath::deg(r.finalRotation), r.iterations);
    CHECK(r.success);
    CHECK(r.recognized == "pliers");
    // The error curve is against the same goal as the final error.
    REQUIRE_FALSE(r.curveTranslation.empty());
    CHECK(r.curveTranslation.back() == Approx(r.finalTranslation));
    CHECK(r.curveRotation.back() == Approx(r.finalRotation));
  }
}

TEST_CASE("bench: vpServoMorph takes a posed target's depth from its edges", "[bench][articulation]")
{
  // Held-out deformable, seed 2 start 0: the opened pliers laid by arm 0, which the servo keeps still. The target
  // posed at 32 deg has its region drawn from its arms' outlines: with the depth from its area, the run ended
  // 0.83 mm and 0.39 deg off (held out on the camera: 1.03-1.13 mm, failures, with the drawing made by OpenCV's
  // warp). From the edges it ends 0.17 mm and 0.21 deg off.
  const vpMorphBenchScenario sc = vpMorphBenchScenario::generate("deformable", 20, 2, kData)[0];
  REQUIRE(sc.object == "pliers");
  const vpMorphBenchResult r = bench().run(sc, "morph");
  std::printf("[articulated] opened pliers, seed 2 start 0, morph: %s, goal %u (arm), %.3f mm %.3f deg\n",
              r.success ? "success" : r.failure.c_str(), r.goal, 1000 * r.finalTranslation,
              vpMath::deg(r.finalRotation));
  CHECK(r.success);
  CHECK(r.goal == 0);
  CHECK(r.finalTranslation < 0.0005);
}

TEST_CASE("bench: a malformed joint file is a clear error", "[bench][articulation]")
{
  namespace fs = std::filesystem;
  const fs::path dir = fs::current_path() / "joint-data";
  fs::remove_all(dir);
  fs::create_directories(dir / "joints");
  fs::create_directory_symlink(fs::path(kData) / "objects", dir / "objects");
  for (const std::string text : {"{\"parts\": [\"a.png\"]", "{\"parts\": [\"a.png\"], \"pivot\": [1, 2]}",
                                 "{\"parts\": [\"a.png\", \"b.png\"], \"pivot\": [1, 2], \"range_deg\": [-8, 60], "
                                 "\"deformed_turns_deg\": [1]}"}) {
    std::ofstream(dir / "joints" / "pliers.json") << text;
    try {
      const vpMorphBench b(dir.string(), vpMorphBench::Settings());
      FAIL("no error for " << text);
    } catch (const vpMorphException &e) {
      CHECK(e.getCode() == vpMorphException::ioError);
      CHECK(e.getStringMessage().find("malformed joint file") != std::string::npos);
    }
  }
  // Parts that are not there: the scene's own error names the image.
  std::ofstream(dir / "joints" / "pliers.json") << "{\"parts\": [\"a.png\", \"b.png\"], \"pivot\": [320, 240], "
                                                   "\"range_deg\": [-8, 60], \"deformed_turns_deg\": [-16, 16]}";
  CHECK_THROWS_AS(vpMorphBench(dir.string(), vpMorphBench::Settings()), vpMorphException);
  fs::remove_all(dir);
}

TEST_CASE("bench: vpServoMorph poses an articulated target at the opening the view shows", "[bench][articulation]")
{
  const vpMorphTemplate &t = bench().database()["pliers"];
  const vpMorphBenchScenario sc = vpMorphBenchScenario::generate("deformable", 1, 1, kData)[0];
  REQUIRE(sc.object == "pliers");
  vpMorphContour view;
  bench().recognizeStart(sc, &view);
  REQUIRE_FALSE(view.empty());
  vpServoMorph servo;
  servo.setCameraParameters(vpMorphPlanarScene::defaultCamera());
  servo.setTarget(t);
  CHECK(servo.targetOpening() == 0.0); // not posed before the first view
  servo.computeControlLaw(view);
  CHECK(std::fabs(vpMath::deg(servo.targetOpening()) - 32.0) < 0.2);
  CHECK(servo.targetFixedPart() < 2);
  // A rigid target (a contour) forgets the articulation.
  servo.setTarget(t.contour(), 0.5);
  servo.computeControlLaw(view);
  CHECK(servo.targetOpening() == 0.0);
}
