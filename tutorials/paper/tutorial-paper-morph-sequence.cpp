//! \example tutorial-paper-morph-sequence.cpp
//! The paper's Figures 1 and 4: contour morph sequences, from contours extracted from rendered camera images.
//! Figure 1: the key seen turned by 120 deg, and deformed (data/objects/key-deformed.png), morphed into the stored
//! view of the key: rotational rectification (blue frames), then rectification of the deformation (orange).
//! Figure 4: the pliers seen turned by 150 deg and shifted, morphed into their stored view.
//! Writes fig1-key-morph.png and fig4-pliers-morph.png in --out DIR; the first and last tiles (initial and final
//! pose) have black borders. With a display, shows each input view with its morph drawn over it: the virtual images
//! (rigid blue, deformation orange) from the contour seen (red) to the stored view (green). Exits with failure unless
//! each sequence ends on the stored view.
#include <cstdio>

#include "tutorial-paper-common.h"

namespace
{
//! The contour seen by the camera at cdMc (relative to the desired pose) in a scene of \e object, and its image.
vpMorphContour view(const std::string &object, const vpHomogeneousMatrix &cdMc, vpImage<unsigned char> &I)
{
  const vpMorphPlanarScene scene(std::string(VISPMORPH_DATA_DIR) + "/objects/" + object + ".png");
  return paper::observe(scene, scene.tagPoseEstimator(), cdMc.inverse() * paper::desiredPose(), I);
}
} // namespace

int main(int argc, char **argv)
{
  std::string out;
  std::vector<std::string> args;
  tutorial::Viewer viewer(argc, argv, args);
  try {
    if (!paper::parseArgs(argv[0], args, out))
      return EXIT_FAILURE;
    vpImage<unsigned char> I(480, 640, 255), Istored;
    viewer.open(I, 0, 0, "Morph: seen (red), virtual images (rigid blue, deformation orange), stored view (green)",
                "morph");
    const vpHomogeneousMatrix here; // the desired pose itself
    const struct
    {
      const char *file, *input, *stored;
      vpHomogeneousMatrix cdMc;
    } figures[] = {
        {"fig1-key-morph.png", "key-deformed", "key", vpHomogeneousMatrix(0, 0, 0, 0, 0, vpMath::rad(120))},
        {"fig4-pliers-morph.png", "pliers", "pliers", vpHomogeneousMatrix(0.03, 0.02, 0, 0, 0, vpMath::rad(150))}};
    bool ok = true;
    std::vector<std::string> caption;
    vpMorphContour target;
    for (const auto &f : figures) {
      //! [Morph]
      const vpMorphContour input = view(f.input, f.cdMc, I), stored = view(f.stored, here, Istored);
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

      //! [Display]
      // The morph over the input view: every virtual image, from the contour seen to the stored view.
      char line[120];
      std::snprintf(line, sizeof line, "D_morph %.3f, rigid part %.1f deg, %zu virtual images", morph.distance(),
                    vpMath::deg(morph.rigidTransform().theta()), n);
      caption = {std::string(f.input) + " -> " + f.stored, line};
      vpDisplay::display(I);
      vpDisplay::displayPolygon(I, stored.points(), vpColor::green, 4);
      for (std::size_t k = 0; k < seq.size(); ++k)
        vpDisplay::displayPolygon(I, seq[k].points(),
                                  k < morph.rigidFrameCount(n) ? vpMorphDrawing::rigidColor
                                                               : vpMorphDrawing::deformationColor);
      vpDisplay::displayPolygon(I, input.points(), vpColor::red, 2);
      tutorial::Viewer::caption(I, caption);
      vpDisplay::flush(I);
      //! [Display]
      if (&f != &figures[1])
        viewer.waitClick(I);
      target = stored;
    }
    std::printf("wrote %s/fig1-key-morph.png, fig4-pliers-morph.png\n", out.c_str());
    viewer.expectContour("morph", "stored view", target.points(), vpColor::green);
    viewer.expectText("morph", "caption", tutorial::Viewer::captionBand(caption), vpColor::white, caption);
    viewer.save();
    viewer.waitClick(I);
    return ok ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cerr << "error: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
}
