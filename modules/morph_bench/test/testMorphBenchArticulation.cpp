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

#include "testMorphBenchFixture.h"

namespace
{
const std::string kData = VISPMORPH_DATA_DIR;
using fixture::bench;
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
  for (const std::string key :
       {"deformable/pliers/101", "deformable/pliers/103", "deformable/pliers/51", "deformable/pliers/-46"}) {
    const vpMorphBenchScenario sc = fixture::start(key);
    REQUIRE(sc.object == "pliers");
    const vpMorphPlanarScene scene = sc.scene();
    const std::vector<vpHomogeneousMatrix> alt = scene.alternativePlacements();
    REQUIRE(alt.size() == 1);
    // The other arm's placement turns the object by the opening about the pin, which stays where it is.
    CHECK(std::fabs(vpMath::deg(std::atan2(alt[0][1][0], alt[0][0][0]))) == Approx(32.0).margin(1e-6));
    const vpImagePoint pin = scene.projectedTexel(320, 240, sc.cdMo);
    CHECK(vpImagePoint::distance(pin, scene.projectedTexel(320, 240, sc.cdMo * alt[0])) < 1e-6);
    const vpMorphRecognition r = bench().recognizeStart(sc);
    CHECK(bench().database()[r.index].name() == "pliers");
    CHECK(r.accepted);
    CHECK(std::fabs(vpMath::deg(r.articulation) - 32.0) <= 2.0);
  }
  // A rigid object has one best placement.
  CHECK(fixture::start("deformable/key/168").scene().alternativePlacements().empty());
}

TEST_CASE("bench: vpServoMorph and vpFeatureMorph align opened pliers by either arm", "[bench][articulation][loop]")
{
  // Before the articulated template these views were rejected by recognition (and, given the closed template,
  // vpServoMorph stopped on them: DEFORMATION_UNRESOLVED).
  const std::vector<std::pair<std::string, std::string>> runs{{"deformable/pliers/101", "morph"},
                                                              {"deformable/pliers/103", "morph"},
                                                              {"deformable/pliers/70", "morph"},
                                                              {"deformable/pliers/101", "morph-vpservo"}};
  for (const auto &run : runs) {
    const vpMorphBenchResult r = bench().run(fixture::start(run.first), run.second);
    std::printf("[articulated] opened pliers, start %s, %s: %s, goal %u (arm), %.3f mm %.3f deg, %u periods\n",
                run.first.c_str(), run.second.c_str(), r.success ? "success" : r.failure.c_str(), r.goal,
                1000 * r.finalTranslation, vpMath::deg(r.finalRotation), r.iterations);
    CHECK(r.success);
    CHECK(r.recognized == "pliers");
    // The error curve is against the same goal as the final error.
    REQUIRE_FALSE(r.curveTranslation.empty());
    CHECK(r.curveTranslation.back() == Approx(r.finalTranslation));
    CHECK(r.curveRotation.back() == Approx(r.finalRotation));
  }
}

TEST_CASE("bench: vpServoMorph takes a posed target's depth from its edges", "[bench][articulation][loop]")
{
  // A development start of the opened pliers laid by arm 0, which the servo keeps still. The target posed at 32 deg
  // has its region drawn from its arms' outlines: with the depth from its area, the run ended 0.83 mm and 0.39 deg
  // off (1.03-1.13 mm on the free camera, failures, with the drawing made by OpenCV's warp). From the edges it ends
  // 0.17 mm and 0.21 deg off.
  const vpMorphBenchScenario sc = fixture::start("deformable/pliers/-108");
  REQUIRE(sc.object == "pliers");
  const vpMorphBenchResult r = bench().run(sc, "morph");
  std::printf("[articulated] opened pliers, deformable/pliers/-108, morph: %s, goal %u (arm), %.3f mm %.3f deg\n",
              r.success ? "success" : r.failure.c_str(), r.goal, 1000 * r.finalTranslation,
              vpMath::deg(r.finalRotation));
  CHECK(r.success);
  CHECK(r.goal == 0);
  CHECK(r.finalTranslation < 0.0005);
}

TEST_CASE("bench: a malformed joint file is a clear error", "[bench][articulation][loop]")
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
      vpMorphBenchObjectSet::tools(dir.string(), "bench-fixture-joints");
      FAIL("no error for " << text);
    } catch (const vpMorphException &e) {
      CHECK(e.getCode() == vpMorphException::ioError);
      CHECK(e.getStringMessage().find("malformed joint file") != std::string::npos);
    }
  }
  // Parts that are not there: the pliers cannot be taught, and its runs are set-up failures; the bench goes on.
  std::ofstream(dir / "joints" / "pliers.json") << "{\"parts\": [\"a.png\", \"b.png\"], \"pivot\": [320, 240], "
                                                   "\"range_deg\": [-8, 60], \"deformed_turns_deg\": [-16, 16]}";
  vpMorphBench::Settings st;
  st.maxIterations = 5;
  const vpMorphBench b(vpMorphBenchObjectSet::tools(dir.string(), "bench-fixture-joints"), 100, st);
  CHECK(b.database().find("pliers") == vpMorphRecognition::npos);
  CHECK(b.database().find("key") != vpMorphRecognition::npos);
  vpMorphBenchScenario sc = fixture::planarStart("pliers", 10, 0, 0);
  sc.cdMo = vpMorphBenchScenario::desiredPose(100, "pliers");
  const vpMorphBenchResult r = b.run(sc, "morph");
  CHECK(r.failure == "setup");
  CHECK(r.setup == "template-not-taught");
  fs::remove_all(dir);
}

TEST_CASE("bench: vpServoMorph poses an articulated target at the opening the view shows", "[bench][articulation]")
{
  const vpMorphTemplate &t = bench().database()["pliers"];
  const vpMorphBenchScenario sc = fixture::start("deformable/pliers/101");
  REQUIRE(sc.object == "pliers");
  vpMorphContour view;
  bench().recognizeStart(sc, &view);
  REQUIRE_FALSE(view.empty());
  vpServoMorph servo;
  servo.setCameraParameters(vpMorphPlanarScene::defaultCamera());
  servo.setTarget(t);
  CHECK(servo.getTargetOpening() == 0.0); // not posed before the first view
  servo.computeControlLaw(view);
  CHECK(std::fabs(vpMath::deg(servo.getTargetOpening()) - 32.0) < 0.2);
  CHECK(servo.getTargetFixedPart() < 2);
  // A rigid target (a contour) forgets the articulation.
  servo.setTarget(t.contour(), 0.5);
  servo.computeControlLaw(view);
  CHECK(servo.getTargetOpening() == 0.0);
}
