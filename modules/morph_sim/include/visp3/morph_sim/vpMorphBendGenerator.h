/*!
  \file vpMorphBendGenerator.h
  \brief A bent variant of a laid-out object: the part beyond a pivot bent smoothly, the rest untouched.
*/
#ifndef VP_MORPH_BEND_GENERATOR_H
#define VP_MORPH_BEND_GENERATOR_H

#include <visp3/core/vpImage.h>

/*!
  \class vpMorphBendGenerator
  \ingroup group_morph_sim
  \brief Generates a seeded bent variant of an object image (black on white, as vpMorphSilhouetteLayout lays it out)
  for the benchmark's deformable set, and the mask of its undeformed part.

  The bend, in the object's principal axes (x along the long axis, from the area centroid):
  - one end (drawn by the seed) is bent; the pivot x0 is where the area beyond it is a share q of the whole, q drawn
    in [0.2, 0.4], so the undeformed part is at least 60 % of the area;
  - a point at distance u = |x| - |x0| beyond the pivot turns about the pivot by theta min(1, u / L), L the part's
    length beyond the pivot: a smooth bend, its angle growing along the part (an arc of radius L / theta);
  - |theta| is drawn in [10, 25] deg (either sign), capped at 0.8 L / w (w the part's largest half-width beyond the
    pivot) so that no point of it turns back across the pivot, and halved until the bent part stays in the canvas.
  The outline (holes included) is mapped at 4 x the image's resolution, filled and averaged down (anti-aliased). The
  undeformed part keeps its pixels exactly: the variant and its template share one frame, in which the undeformed
  part's pose is the template's (vpMorphPlanarScene::SHARED_FRAME).

  \code
  const vpMorphBendGenerator::Bend b = vpMorphBendGenerator::generate(layout.image(), seed);
  vpImageIo::write(b.image, "objects/apple-7-deformed.png");
  vpImageIo::write(b.undeformedMask, "objects/apple-7-deformed-mask.png");
  \endcode
  \sa vpMorphSilhouetteLayout, \ref page_benchmarks
*/
class vpMorphBendGenerator
{
public:
  //! A bent variant and its undeformed part.
  struct Bend
  {
    vpImage<unsigned char> image;          //!< the bent object, black on white, the input's size
    vpImage<unsigned char> undeformedMask; //!< the undeformed part alone, black on white
    double undeformedShare = 0;            //!< its share of the object's area, >= 0.6
    double angleDeg = 0;                   //!< theta, signed
  };
  /*!
    The bent variant of \e object (black on white, as laid out), drawn by \e seed (see the class description).
    \throw vpMorphException::badImageError for an image without object, or whose bend finds no room in the canvas.
  */
  static Bend generate(const vpImage<unsigned char> &object, unsigned int seed);
};

#endif
