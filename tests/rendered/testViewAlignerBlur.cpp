// vpMorphViewAligner on rendered views of a serrated, nearly six-fold star: blurred more than the taught one (an edge's
// detail finer than the blur is rounded off in the view, not in the template, and the two are compared at one blur),
// and aligned without a start from any turn (the correspondence may start a lobe off).
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <string>

#include <visp3/core/vpImage.h>
#include <visp3/core/vpMath.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph_sim/vpMorphPlanarScene.h>
#include <visp3/morph_sim/vpMorphTagPoseEstimator.h>
#include <visp3/morph_vs/vpMorphViewAligner.h>

#include "testRenderedView.h"

namespace
{
using vpMorphRenderedTest::view;

// A six-lobed star, its lobes of unequal sizes (no symmetry), whose edge is a saw of 240 teeth (5 % of its radius deep,
// about 2 px in the views): a silhouette drawn at 512 x 512, dark on white, anti-aliased (4 x 4 samples a pixel).
std::string serratedStar()
{
  const int n = 512, teeth = 240, S = 4;
  vpImage<unsigned char> I(n, n, 255);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      int inside = 0;
      for (int a = 0; a < S; ++a)
        for (int b = 0; b < S; ++b) {
          const double x = j + (b + 0.5) / S - 0.5 * n, y = i + (a + 0.5) / S - 0.5 * n;
          const double t = std::atan2(y, x), saw = std::fabs(std::remainder(t * teeth / (2.0 * M_PI), 1.0));
          inside += std::hypot(x, y) <
                            170.0 * (1.0 + 0.25 * std::cos(6.0 * t) + 0.08 * std::cos(t) + 0.05 * std::sin(2.0 * t)) *
                                (1.0 + 0.05 * saw)
                        ? 1
                        : 0;
        }
      I[i][j] = static_cast<unsigned char>(std::lround(255.0 * (1.0 - double(inside) / (S * S))));
    }
  const std::string path = "serrated-star.png";
  vpImageIo::write(I, path);
  return path;
}

} // namespace

TEST_CASE("A view blurred more than the taught one is explained, its size and turn unbiased",
          "[rendered][aligner][blur]")
{
  const std::string image = serratedStar();
  const vpHomogeneousMatrix cdMo(0.01, -0.005, 0.55, 0, 0, vpMath::rad(25));
  const vpMorphPlanarScene taughtScene(image);
  const vpMorphContour taught = view(taughtScene, cdMo, 0);
  REQUIRE(taught.hasOutline());
  for (double blur : {1.0, 1.5, 2.0}) {
    vpMorphPlanarScene scene(image);
    vpMorphPlanarScene::Faults f;
    f.blurSigma = blur;
    f.noiseSigma = 4.0;
    f.seed = 5;
    scene.setFaults(f);
    double worstScale = 0.0, worstTurn = 0.0, worstSigma = 0.0;
    for (int deg = 0; deg < 360; deg += 45) {
      const vpMorphContour c = view(scene, cdMo, deg);
      vpMorphViewAligner aligner;
      aligner.setCameraParameters(scene.camera());
      aligner.setGoal(taught);
      // Started 2 deg off, as a servo's last period starts the next (a nearly six-fold star is not the test here).
      aligner.setStart(vpMorphRigidTransform(vpMath::rad(deg + 2), 0.0, 0.0));
      const vpMorphViewAlignment a = aligner.align(c);
      INFO("blur " << blur << " px at " << deg << " deg: view blur " << c.outlineBlur() << " px, template's "
                   << taught.outlineBlur() << " px; sigma " << a.sigmaPx << " px, scale " << a.transform.scale());
      REQUIRE(a.explained());
      CHECK(a.model == vpMorphViewAlignment::RIGID);
      worstSigma = std::max(worstSigma, a.sigmaPx);
      worstScale = std::max(worstScale, std::fabs(a.transform.scale() - 1.0));
      worstTurn = std::max(worstTurn, std::fabs(std::remainder(a.transform.theta() - vpMath::rad(deg), 2.0 * M_PI)));
    }
    INFO("blur " << blur << " px: worst sigma " << worstSigma << " px, size " << worstScale << ", turn "
                 << vpMath::deg(worstTurn) << " deg");
    CHECK(worstSigma < 0.15);  // the fit's floor (0.1 px) and the noise's share
    CHECK(worstScale < 0.001); // 0.5 mm of depth at 0.5 m
    CHECK(worstTurn < vpMath::rad(0.1));
  }
}

TEST_CASE("A nearly six-fold star is aligned without a start from any turn", "[rendered][aligner][search]")
{
  const std::string image = serratedStar();
  const vpHomogeneousMatrix cdMo(0.01, -0.005, 0.55, 0, 0, vpMath::rad(25));
  const vpMorphPlanarScene scene(image);
  const vpMorphContour taught = view(scene, cdMo, 0);
  double worstTurn = 0.0;
  for (int deg = 15; deg < 360; deg += 30) {
    const vpMorphViewAlignment a = vpMorphRenderedTest::alignCold(scene, taught, view(scene, cdMo, deg));
    INFO("at " << deg << " deg: sigma " << a.sigmaPx << " px, turn " << vpMath::deg(a.transform.theta()) << " deg");
    REQUIRE(a.explained());
    worstTurn = std::max(worstTurn, std::fabs(std::remainder(a.transform.theta() - vpMath::rad(deg), 2.0 * M_PI)));
  }
  INFO("worst turn error " << vpMath::deg(worstTurn) << " deg");
  CHECK(worstTurn < vpMath::rad(0.1));
}
