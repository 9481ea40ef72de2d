/*!
  \file vpMorphTagTexture.h
  \brief AprilTag 36h11 textures for simulated scenes (ViSP 3.5 cannot draw tag images).
*/
#ifndef VP_MORPH_TAG_TEXTURE_H
#define VP_MORPH_TAG_TEXTURE_H

#include <visp3/core/vpImage.h>

/*!
  \class vpMorphTagTexture
  \ingroup group_morph_sim
  \brief Generates AprilTag 36h11 images with libapriltag and gives the metric sizes that make
  vpDetectorAprilTag and vpImageSimulator agree exactly.

  The tag image from libapriltag has 10 x 10 cells: a one-cell white quiet zone around an 8-cell black
  border square (the side vpDetectorAprilTag calls tagSize). Each cell is scaled up to \e cellPixels pixels
  by nearest neighbour, so the edges stay sharp.

  Why the exact sizes matter: vpImageSimulator maps texel centres 0 .. W-1 onto the texture rectangle
  (not texel edges 0 .. W), so with bilinear interpolation the black border spans 8 c / (10 c - 1) of the
  texture side, not 0.8. At 0.5 m a 1 % size error is a 5 mm depth error, larger than the ground-truth
  tolerance; tagSizeForTextureSide() and textureSideForTagSize() give the exact relation (the black square
  stays centred in the texture).

  \code
  vpImage<unsigned char> tag = vpMorphTagTexture::create(0);                // id 0, 100 x 100 px
  double side = vpMorphTagTexture::textureSideForTagSize(0.08);             // texture side for an 8 cm tag
  \endcode
  \sa vpMorphPlanarScene, vpMorphTagPoseEstimator
*/
class vpMorphTagTexture
{
public:
  //! 36h11 tag \e id (0 .. maxId()) with cells of \e cellPixels pixels; black 0, white 255.
  static vpImage<unsigned char> create(int id, unsigned int cellPixels = 10);
  //! Largest valid 36h11 id (the family has 587 codes).
  static int maxId() { return 586; }
  //! Cells per side of the whole texture (quiet zone included).
  static unsigned int cellCount() { return 10; }
  //! Cells per side of the black border square.
  static unsigned int borderCellCount() { return 8; }
  //! Black-border side (vpDetectorAprilTag tagSize) of a texture of metric side \e side rendered by vpImageSimulator.
  static double tagSizeForTextureSide(double side, unsigned int cellPixels = 10);
  //! Inverse of tagSizeForTextureSide(): the texture side to give vpImageSimulator for a wanted tag size.
  static double textureSideForTagSize(double tagSize, unsigned int cellPixels = 10);
};

#endif
