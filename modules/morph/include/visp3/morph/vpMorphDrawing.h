/*!
  \file vpMorphDrawing.h
  \brief Headless pictures of morph sequences (PNG), like the paper's Figures 1 and 4.
*/
#ifndef VP_MORPH_DRAWING_H
#define VP_MORPH_DRAWING_H

#include <cstddef>
#include <string>
#include <vector>

#include <visp3/core/vpColor.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/core/vpRect.h>
#include <visp3/morph/vpMorph.h>
#include <visp3/morph/vpMorphContour.h>

/*!
  \class vpMorphDrawing
  \ingroup group_morph
  \brief Draws morph sequences into images without a display (vpImageDraw), for reports and tests.

  All tiles share one scale and offset, fitted to the union bounding box of every frame and the input,
  so that the motion from tile to tile is visible (per-tile fitting would hide translation and scale).
  The input is drawn as a thin grey outline in every tile as a reference; each frame is drawn in colour,
  rigid frames in blue and deformation frames in orange; the first and last tiles (initial and final pose)
  get a black border, as in the paper. Frame numbers use ViSP's built-in monospace vpFont.
  The y axis points down, as in images (pixel contours are drawn where they are in the image).

  \code
  vpMorph morph(input, target);
  vpMorphDrawing::write(vpMorphDrawing::sequenceStrip(morph, 10), "out/morph.png"); // the paper's Figure 1 layout
  \endcode
  \sa vpMorph
*/
class vpMorphDrawing
{
public:
  //! Colour of rigid-rectification frames.
  static const vpColor rigidColor;
  //! Colour of deformation frames.
  static const vpColor deformationColor;
  //! Colour of the input outline drawn in every tile.
  static const vpColor inputColor;

  /*!
    One tile per frame, tileSize x tileSize pixels, in \e columns columns (0: automatic, at most 8 per row,
    rows balanced). frames[k] for k < \e rigidFrames are drawn in rigidColor, the others in deformationColor.
    \throw vpMorphException::badParameterError if frames is empty, tileSize < 32, or a contour is empty.
  */
  static vpImage<vpRGBa> sequenceStrip(const vpMorphContour &input, const std::vector<vpMorphContour> &frames,
                                       unsigned int tileSize = 200, unsigned int columns = 0,
                                       std::size_t rigidFrames = 0);
  /*!
    The paper's figure for a morph: morph.sequenceWithInput(n), i.e. the input (initial pose) in the first
    tile, then the rigid frames, then the deformation frames, ending on the target (final pose).
  */
  static vpImage<vpRGBa> sequenceStrip(const vpMorph &morph, std::size_t n, unsigned int tileSize = 200,
                                       unsigned int columns = 0);

  /*!
    The segment from \e a to \e b drawn into \e I (vpImageDraw), clipped to the image first: ViSP 3.5's own clipping
    writes outside the image for some segments that cross its border (a segfault on random segments). Nothing is
    drawn for a segment outside the image or with a non-finite end.
  */
  static void drawLine(vpImage<vpRGBa> &I, const vpImagePoint &a, const vpImagePoint &b, const vpColor &color,
                       unsigned int thickness = 1);
  //! A closed polygon, each edge by drawLine().
  static void drawPolygon(vpImage<vpRGBa> &I, const std::vector<vpImagePoint> &points, const vpColor &color,
                          unsigned int thickness = 1);

  /*!
    The band that lines of text are written on from \e topLeft: 16 pixels a line and 8 a character, with a line and
    two characters of margin (the widest of the fonts that write them: vpFont's monospace at 14 pixels, X11's fixed
    6 x 13, OpenCV's Hershey plain at 0.8).
  */
  static vpRect textBand(const std::vector<std::string> &lines, const vpImagePoint &topLeft);
  //! Lines of text in \e color on their black textBand() (vpFont's monospace), clipped to the image; returns the band.
  static vpRect drawTextBand(vpImage<vpRGBa> &I, const std::vector<std::string> &lines, const vpImagePoint &topLeft,
                             const vpColor &color = vpColor::yellow);
  //! The same on the display attached to \e I (vpDisplay: no-op without one), in the display's font.
  static vpRect displayTextBand(const vpImage<unsigned char> &I, const std::vector<std::string> &lines,
                                const vpImagePoint &topLeft, const vpColor &color = vpColor::yellow);
  //! Same on a colour image's display.
  static vpRect displayTextBand(const vpImage<vpRGBa> &I, const std::vector<std::string> &lines,
                                const vpImagePoint &topLeft, const vpColor &color = vpColor::yellow);

  /*!
    Writes \e image as PNG (format from the extension, as vpImageIo does), creating parent directories.
    \throw vpMorphException::ioError if a directory cannot be created or the file cannot be written.
  */
  static void write(const vpImage<vpRGBa> &image, const std::string &pngPath);
};

#endif
