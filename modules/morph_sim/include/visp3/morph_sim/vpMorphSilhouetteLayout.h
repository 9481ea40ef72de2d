/*!
  \file vpMorphSilhouetteLayout.h
  \brief Any silhouette image laid out as a bench object: dark on white, sized, centred, anti-aliased.
*/
#ifndef VP_MORPH_SILHOUETTE_LAYOUT_H
#define VP_MORPH_SILHOUETTE_LAYOUT_H

#include <string>

#include <visp3/core/vpImage.h>

/*!
  \class vpMorphSilhouetteLayout
  \ingroup group_morph_sim
  \brief Lays out a silhouette image of either polarity and any size as an object image of vpMorphPlanarScene.

  The object is the largest 8-connected region of the class that does not dominate the image border (Otsu's
  threshold; the rule of vpMorphContourExtractor), holes kept, specks elsewhere dropped. It is scaled so that the
  longest side of its bounding box is objectPixels(), centred in a square canvas of objectPixels() + 2 margin()
  (room for a bend generated later, vpMorphBendGenerator), and drawn black (0) on white (255) with each pixel's grey
  level the share of it the shape covers: the shape is resampled at 4 x the output resolution (bilinear, cut at
  one half, so a low-resolution source's staircase becomes straight chords) and averaged down.

  Related images of one object (a deformed variant, the mask of its undeformed part) must share the template's
  frame: construct the layout from the template, then apply() it to the others (same size as the template's
  source), which maps them by the template's scale and offset.

  \code
  const vpMorphSilhouetteLayout layout(vpMorphSilhouetteLayout::read("mpeg7/apple-7.png"));
  vpImageIo::write(layout.image(), "objects/apple-7.png");
  \endcode
  \sa vpMorphPlanarScene, vpMorphBendGenerator
*/
class vpMorphSilhouetteLayout
{
public:
  /*!
    \param source : silhouette image, either polarity, any size.
    \param objectPixels : longest side of the laid-out object, pixels (16..4000).
    \param margin : free pixels around the object's square (0..1000).
    \throw vpMorphException::badImageError for an empty or uniform image, or one without an object region;
    badParameterError for sizes out of range.
  */
  explicit vpMorphSilhouetteLayout(const vpImage<unsigned char> &source, unsigned int objectPixels = 300,
                                   unsigned int margin = 8);

  //! The template laid out (a copy).
  const vpImage<unsigned char> &image() const { return m_image; }
  //! Longest side of the laid-out object (pixels).
  unsigned int objectPixels() const { return m_objectPixels; }
  //! Free pixels around the object's square.
  unsigned int margin() const { return m_margin; }
  //! Output pixels per source pixel.
  double scale() const { return m_scale; }
  /*!
    Another image of the same object (a deformed variant, a part's mask), source of the template's size, laid out by
    the template's scale and offset; its object is its own largest region. Parts outside the canvas are cut.
    \throw vpMorphException::badParameterError for another size; badImageError as the constructor.
  */
  vpImage<unsigned char> apply(const vpImage<unsigned char> &other) const;
  /*!
    An object image (black on white) as a low-resolution source would give it: resampled with \e lowPixels pixels
    across the longest side of the object's bounding box, cut at one half, and enlarged back by nearest neighbour,
    so its edges are staircases of (that side / lowPixels) pixels (binary, no anti-aliasing).
    \throw vpMorphException::badParameterError unless lowPixels >= 4; badImageError without object or when the
    object is not larger than lowPixels.
  */
  static vpImage<unsigned char> roughened(const vpImage<unsigned char> &image, unsigned int lowPixels);

  /*!
    Reads an image file as grey levels.
    \throw vpMorphException::notFoundError when missing, ioError when unreadable.
  */
  static vpImage<unsigned char> read(const std::string &path);

private:
  vpImage<unsigned char> m_image;
  unsigned int m_objectPixels, m_margin;
  unsigned int m_srcWidth = 0, m_srcHeight = 0;
  double m_scale = 1.0;
  double m_offsetX = 0.0, m_offsetY = 0.0; // output = source * scale + offset (pixel centres)
};

#endif
