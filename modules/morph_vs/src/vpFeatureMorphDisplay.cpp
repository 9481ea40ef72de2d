// vpFeatureMorph: what display() and draw() show (the contour and its centroid), on a display or into an image.
#include <visp3/morph_vs/vpFeatureMorph.h>

#include <visp3/core/vpMeterPixelConversion.h>

#include "vpMorphOverlay.h"

namespace
{
// Half-size of the centroid's cross (pixels), as ViSP's point features draw theirs.
constexpr unsigned int kCrossSize = 12;

void drawFeature(const vpFeatureMorph &s, vpMorphOverlay &o, const vpCameraParameters &cam, const vpColor &color,
                 unsigned int thickness)
{
  if (!s.isBuilt())
    return;
  o.polygon(vpMorphOverlay::pixels(s.contour(), cam), color, thickness);
  vpImagePoint g;
  vpMeterPixelConversion::convertPoint(cam, s.get_xg(), s.get_yg(), g);
  o.cross(g, kCrossSize, color, thickness);
}
} // namespace

void vpFeatureMorph::display(const vpCameraParameters &cam, const vpImage<unsigned char> &I, const vpColor &color,
                             unsigned int thickness) const
{
  vpMorphDisplayOverlay<unsigned char> o(I);
  drawFeature(*this, o, cam, color, thickness);
}

void vpFeatureMorph::display(const vpCameraParameters &cam, const vpImage<vpRGBa> &I, const vpColor &color,
                             unsigned int thickness) const
{
  vpMorphDisplayOverlay<vpRGBa> o(I);
  drawFeature(*this, o, cam, color, thickness);
}

void vpFeatureMorph::draw(const vpCameraParameters &cam, vpImage<vpRGBa> &I, const vpColor &color,
                          unsigned int thickness) const
{
  vpMorphImageOverlay o(I);
  drawFeature(*this, o, cam, color, thickness);
}
