//! \example tutorial-paper-interleaved.cpp
//! The paper's Figure 5: the views seen by the eye-in-hand camera during the alignment of the pliers (start 100 deg
//! and 45 mm away), interleaved with the virtual images of the morph that guided it. Each virtual image (the
//! sub-goal contour, orange on white) is followed by the real view at the move where it was reached, with that
//! sub-goal drawn over it; the arrow means "reached within the thresholds". The start view and the final view
//! have black borders. Writes fig5-interleaved.png in --out DIR. Exits with failure unless the alignment
//! converged (paper::aligned()).
#include <cstdio>
#include <memory>
#include <sstream>

#include <visp3/core/vpFont.h>
#include <visp3/core/vpImageTools.h>

#include "tutorial-paper-common.h"

namespace
{
//! One tile of the figure: a picture (full camera resolution) and its caption.
struct Tile
{
  vpImage<vpRGBa> image;
  std::string caption;
  bool border;
};

//! The tiles in rows of \e columns, scaled to tileW x tileH, an arrow from each virtual tile to its real one.
vpImage<vpRGBa> grid(const std::vector<Tile> &tiles, unsigned int columns, unsigned int tileW, unsigned int tileH)
{
  const unsigned int gap = 24, rows = static_cast<unsigned int>((tiles.size() + columns - 1) / columns);
  vpImage<vpRGBa> G(rows * (tileH + gap) + gap, columns * (tileW + gap) + gap, vpRGBa(255, 255, 255));
  const vpFont font(14, vpFont::GENERIC_MONOSPACE);
  for (std::size_t k = 0; k < tiles.size(); ++k) {
    const unsigned int top = gap + static_cast<unsigned int>(k / columns) * (tileH + gap);
    const unsigned int left = gap + static_cast<unsigned int>(k % columns) * (tileW + gap);
    vpImage<vpRGBa> small;
    vpImageTools::resize(tiles[k].image, small, tileW, tileH, vpImageTools::INTERPOLATION_AREA);
    G.insert(small, vpImagePoint(top, left));
    const vpRect r(left - 1, top - 1, tileW + 2, tileH + 2);
    vpImageDraw::drawRectangle(G, r, tiles[k].border ? vpColor::black : vpColor::lightGray, false,
                               tiles[k].border ? 4 : 1);
    font.drawText(G, tiles[k].caption, vpImagePoint(top + 4, left + 6), vpColor::black);
    // Virtual tile (odd index) -> its real view (next tile, same row): an arrow in the gap.
    if (k % 2 == 1 && k + 1 < tiles.size() && (k + 1) % columns != 0) {
      const double v = top + tileH / 2.0;
      vpImageDraw::drawArrow(G, vpImagePoint(v, left + tileW + 2), vpImagePoint(v, left + tileW + gap - 2),
                             vpColor::red, 6, 6, 2);
    }
  }
  return G;
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

    paper::Bench bench("pliers");
    if (!bench.start(vpHomogeneousMatrix(0.036, 0.027, 0, 0, 0, vpMath::rad(100)))) {
      std::cerr << "start pose out of reach" << std::endl;
      return EXIT_FAILURE;
    }
    vpServoMorph servo;
    paper::setUpController(servo, bench.robot, bench.scene.camera(), bench.storedView, bench.cdMo[2][3],
                           paper::Bench::dt);
    tutorial::ServoWindows watch(viewer, bench.scene.imageWidth(), bench.scene.imageHeight(),
                                 bench.scene.objectContour3D(), bench.scene.tagCorners3D(), bench.cdMo,
                                 "Viper850 camera"); // windows, when a display is available

    std::vector<Tile> tiles;
    vpImage<unsigned char> I;
    paper::PoseError e;
    //! [Loop]
    unsigned int move = 0;
    for (; move < 200; ++move) {
      const vpMorphContour seen = bench.look(I);
      if (move == 0)
        tiles.push_back({paper::withContour(I, vpMorphContour(), vpColor::orange), "start", true});
      const std::size_t before = servo.getSubGoalIndex();
      const vpColVector ve = servo.computeControlLaw(seen);
      watch.show(I, servo, move, bench.robot.get_cMo());
      // The sub-goals reached at this move: each virtual image, then the real view that reached it.
      const std::size_t reached =
          servo.getStatus() == vpServoMorph::CONVERGED ? servo.getSubGoals().size() : servo.getSubGoalIndex();
      for (std::size_t k = before; k < reached; ++k) {
        const vpMorphContour &goal = servo.getSubGoals()[k];
        vpImage<unsigned char> blank(I.getHeight(), I.getWidth(), 255);
        std::ostringstream v, r;
        v << "virtual " << k + 1;
        r << "real, move " << move;
        tiles.push_back({paper::withContour(blank, goal, vpColor::orange), v.str(), false});
        tiles.push_back({paper::withContour(I, goal, vpColor::orange), r.str(), k + 1 == servo.getSubGoals().size()});
      }
      e = bench.error();
      if (!paper::running(servo) || watch.stopped())
        break;
      bench.move(ve);
    }
    //! [Loop]

    //! [Figure]
    vpMorphDrawing::write(grid(tiles, 6, 256, 192), out + "/fig5-interleaved.png");
    //! [Figure]
    std::printf("pliers, 100 deg and 45 mm, Viper850: %s after %u moves, %zu virtual images, %zu tiles\n",
                vpServoMorph::statusName(servo.getStatus()), move, servo.getSubGoals().size(), tiles.size());
    std::printf("final pose error (simulator truth): %.3f deg, %.3f mm in the image plane, %.3f mm in depth\n", e.deg,
                e.inPlaneMm, e.depthMm);
    std::printf("wrote %s/fig5-interleaved.png\n", out.c_str());
    const bool ok = paper::aligned(servo, e);
    std::printf("%s\n", ok ? "aligned" : "NOT aligned");
    watch.end(servo);
    return ok ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cerr << "error: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
}
