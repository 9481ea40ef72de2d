//! \example tutorial-paper-morph-sequence.cpp
//! The paper's Figures 1 and 4: contour morph sequences, from contours extracted from rendered camera images.
//! Figure 1: the key seen turned by 120 deg, and deformed (data/objects/key-deformed.png), morphed into the stored
//! view of the key: rotational rectification (blue frames), then rectification of the deformation (orange).
//! Figure 4: the pliers seen turned by 150 deg and shifted, morphed into their stored view.
//! Writes fig1-key-morph.png and fig4-pliers-morph.png in --out DIR; the first and last tiles (initial and final
//! pose) have black borders. Exits with failure unless each sequence ends on the stored view.
#include <cstdio>

#include "tutorial-paper-common.h"

namespace
{
//! The contour seen by the camera at cdMc (relative to the desired pose) in a scene of \e object.
vpMorphContour view(const std::string &object, const vpHomogeneousMatrix &cdMc)
{
  const vpMorphPlanarScene scene(std::string(VISPMORPH_DATA_DIR) + "/objects/" + object + ".png");
  vpImage<unsigned char> I;
  return paper::observe(scene, scene.tagPoseEstimator(), cdMc.inverse() * paper::desiredPose(), I);
}
} // namespace

int main(int argc, char **argv)
{
  std::string out;
  try {
    if (!paper::parseArgs(argc, argv, out))
      return EXIT_FAILURE;
    const vpHomogeneousMatrix here; // the desired pose itself
    const struct
    {
      const char *file, *input, *stored;
      vpHomogeneousMatrix cdMc;
    } figures[] = {
        {"fig1-key-morph.png", "key-deformed", "key", vpHomogeneousMatrix(0, 0, 0, 0, 0, vpMath::rad(120))},
        {"fig4-pliers-morph.png", "pliers", "pliers", vpHomogeneousMatrix(0.03, 0.02, 0, 0, 0, vpMath::rad(150))}};
    bool ok = true;
    for (const auto &f : figures) {
      //! [Morph]
      const vpMorphContour input = view(f.input, f.cdMc), stored = view(f.stored, here);
      const vpMorph morph(input, stored);
      const std::size_t n = 8; // virtual images, as in the servo tutorials
      vpMorphDrawing::write(vpMorphDrawing::sequenceStrip(morph, n, 160, 0), out + "/" + f.file);
      //! [Morph]
      const std::vector<vpMorphContour> seq = morph.sequence(n);
      const bool endsOnTarget = seq.back().size() == stored.size();
      std::printf("%s: %s -> %s, D_morph %.3f, rigid part %.1f deg, %zu rigid + %zu deformation frames%s\n", f.file,
                  f.input, f.stored, morph.distance(), vpMath::deg(morph.rigidTransform().theta()),
                  morph.rigidFrameCount(n), n - morph.rigidFrameCount(n), endsOnTarget ? "" : " (BAD END)");
      ok = ok && endsOnTarget;
    }
    std::printf("wrote %s/fig1-key-morph.png, fig4-pliers-morph.png\n", out.c_str());
    return ok ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cerr << "error: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
}
