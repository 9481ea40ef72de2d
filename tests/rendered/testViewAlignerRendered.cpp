// vpMorphViewAligner on rendered views: the measured size of one object does not drift with its in-plane rotation or
// with the rendering (the depth the servo stops at depends on it: 0.4 % of size is 2 mm at 0.5 m).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

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

// The object image with rough edges, as a silhouette drawn from a source at a quarter of the resolution: each 4 x 4
// block takes the level of its top-left pixel.
std::string roughTexture(const std::string &name)
{
  vpImage<unsigned char> I;
  vpImageIo::read(I, std::string(VISPMORPH_DATA_DIR) + "/objects/" + name + ".png");
  for (unsigned int i = 0; i < I.getHeight(); ++i)
    for (unsigned int j = 0; j < I.getWidth(); ++j)
      I[i][j] = I[i - i % 4][j - j % 4];
  const std::string path = "rough-" + name + ".png";
  vpImageIo::write(I, path);
  return path;
}

struct Look
{
  const char *name;
  double gain, offset, noise;
  bool rough;
  double gradient = 0.0; // the light's fall-off across the image (vpMorphPlanarScene::Faults::gradient), at 30 deg
};

} // namespace

TEST_CASE("The measured size of an object agrees within 0.4 % between views at one depth, at any in-plane rotation, "
          "whatever the rendering",
          "[rendered][aligner][depth]")
{
  // Saturated: gain 6 clips both levels, the edge pixels' shares crushed; low contrast: 26 grey levels between object
  // and plane, with noise; rough: a silhouette drawn from a source at a quarter of the resolution; uneven light: the
  // light falls off by 45 % from the image's centre to its corners (the plane's far corner dark as the object).
  const Look looks[] = {{"plain", 1.0, 0.0, 0.0, false},
                        {"saturated", 6.0, -650.0, 0.0, false},
                        {"low contrast", 0.15, 120.0, 1.0, false},
                        {"rough edges", 1.0, 0.0, 0.0, true},
                        {"uneven light", 1.0, 0.0, 1.0, false, 0.45}};
  const vpHomogeneousMatrix cdMo(0.01, -0.005, 0.5, 0, 0, vpMath::rad(25));
  for (const std::string name : {"key", "screwdriver", "wrench"}) {
    const std::string image = std::string(VISPMORPH_DATA_DIR) + "/objects/" + name + ".png";
    const vpMorphPlanarScene taughtScene(image);
    const vpMorphContour taught = view(taughtScene, cdMo, 0);
    for (const Look &look : looks) {
      vpMorphPlanarScene scene(look.rough ? roughTexture(name) : image);
      vpMorphPlanarScene::Faults f;
      f.gain = look.gain;
      f.offset = look.offset;
      f.noiseSigma = look.noise;
      f.gradient = look.gradient;
      f.gradientAngle = vpMath::rad(30);
      f.seed = 11;
      scene.setFaults(f);
      // The taught view of this rendering, and, for a lighting, the same views against the plain taught one (a lighting
      // that differs between teaching and servoing grows or shrinks the edges all round, which is not a depth). A
      // rough silhouette is another outline than the smooth one, not another lighting of it.
      const vpMorphContour own = view(scene, cdMo, 0);
      double lo = 1.0, hi = 1.0, worstToPlain = 0.0, worstRotation = 0.0;
      for (int deg = 30; deg < 360; deg += 30) {
        const vpMorphContour c = view(scene, cdMo, deg);
        vpMorphViewAligner aligner;
        aligner.setCameraParameters(scene.camera());
        aligner.setGoal(own);
        const vpMorphViewAlignment a = aligner.align(c);
        INFO(name << ", " << look.name << " at " << deg << " deg: sigma " << a.sigmaPx << " px, overlap "
                  << a.overlapShare << ", scale " << a.transform.scale());
        REQUIRE(a.explained());
        lo = std::min(lo, a.transform.scale());
        hi = std::max(hi, a.transform.scale());
        worstRotation =
            std::max(worstRotation, std::fabs(std::remainder(a.transform.theta() - vpMath::rad(deg), 2.0 * M_PI)));
        if (look.rough)
          continue;
        aligner.setGoal(taught);
        const vpMorphViewAlignment p = aligner.align(c);
        INFO(name << ", " << look.name << " at " << deg << " deg against the plain view: sigma " << p.sigmaPx
                  << " px, overlap " << p.overlapShare << ", offset " << p.edgeOffsetPx << " px, scale "
                  << p.transform.scale());
        REQUIRE(p.explained());
        worstToPlain = std::max(worstToPlain, std::fabs(p.transform.scale() - 1.0));
      }
      INFO(name << ", " << look.name << ": sizes " << lo << " .. " << hi << ", to the plain taught view "
                << worstToPlain << ", rotation " << vpMath::deg(worstRotation) << " deg");
      CHECK(hi / lo - 1.0 < 0.004);
      CHECK(worstToPlain < 0.004);
      CHECK(worstRotation < vpMath::rad(0.1));
    }
  }
}
