/*!
  \file vpMorphOutlineBlur.h
  \brief The measured outline of a contour as a more blurred image of it would show it.
*/
#ifndef VP_MORPH_OUTLINE_BLUR_H
#define VP_MORPH_OUTLINE_BLUR_H

#include <visp3/morph/vpMorphContour.h>

/*!
  \class vpMorphOutlineBlur
  \ingroup group_morph
  \brief Blurs a measured outline: the edge vpMorphContourExtractor would measure on an image of the same object
  blurred by a Gaussian of \e sigma more.

  A blur rounds every detail of an edge finer than itself (the teeth of a serrated edge, a sharp corner), and the
  measured outline follows: two outlines of one object, measured at different blurs, differ by more than their noise
  along such details. Comparing them at one blur removes that difference. The outline is filled, integrated over the
  pixels (as a camera's pixel integrates the light over its area), blurred by \e sigma and measured again by
  vpMorphContourExtractor, so that both outlines come from one measurement. The result's blur (outlineBlur()) is the one
  measured on that image: the outline's own, the pixel's area again and \e sigma.

  Why not a curve smoothing along the arc length: a serrated outline is longer than the edge a blur leaves of it, so
  the same sigma along the arc smooths it by much less than the image's blur does.

  \code
  // A goal sharper than the view, laid at the view's blur before the two are compared (pixels, one scale).
  if (view.outlineBlur() >= vpMorphOutlineBlur::leastBlur(goal))
    goal = vpMorphOutlineBlur::blurredTo(goal, view.outlineBlur());
  \endcode
*/
class vpMorphOutlineBlur
{
public:
  /*!
    \e contour (PIXEL units, with a measured outline) with its outline replaced by the one an image of its region
    blurred by \e sigma (pixels) more shows; polygon and region unchanged. \e sigma = 0 still integrates the pixels
    once more (pixelVariance()).
    \throw vpMorphException::badParameterError on a negative or non-finite sigma, NORMALIZED units or no outline;
    badContourError when the blurred image shows no outline (an object thinner than the blur everywhere).
  */
  static vpMorphContour blurred(const vpMorphContour &contour, double sigma);
  /*!
    \e contour laid at an outline blur of \e blur (pixels, as vpMorphContour::outlineBlur() measures it): blurred() by
    the Gaussian whose variance, with its outline's and the pixel's, makes up blur^2.
    \throw vpMorphException::badParameterError when \e blur is below leastBlur(); as blurred() otherwise.
  */
  static vpMorphContour blurredTo(const vpMorphContour &contour, double blur);
  //! The least outline blur that laying \e contour gives (pixels): its own and the pixel's area, in quadrature.
  static double leastBlur(const vpMorphContour &contour);
  //! The variance a pixel's area adds to an edge's spread (px^2): a box one pixel wide, 1/12.
  static double pixelVariance() { return 1.0 / 12.0; }
};

#endif
