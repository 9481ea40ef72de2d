#include <visp3/morph_sim/vpMorphTagTexture.h>

#include <cmath>
#include <memory>
#include <sstream>

#include <visp3/morph/vpMorphException.h>

extern "C" {
#include <apriltag/apriltag.h>
#include <apriltag/common/image_u8.h>
#include <apriltag/tag36h11.h>
}

namespace
{
void checkCell(unsigned int cellPixels)
{
  if (cellPixels == 0 || cellPixels > 1000) {
    std::ostringstream os;
    os << "vpMorphTagTexture: cellPixels must be in 1..1000, got " << cellPixels;
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
}
} // namespace

vpImage<unsigned char> vpMorphTagTexture::create(int id, unsigned int cellPixels)
{
  checkCell(cellPixels);
  if (id < 0 || id > maxId()) {
    std::ostringstream os;
    os << "vpMorphTagTexture: 36h11 tag id must be in 0.." << maxId() << ", got " << id;
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  std::unique_ptr<apriltag_family_t, void (*)(apriltag_family_t *)> family(tag36h11_create(), tag36h11_destroy);
  std::unique_ptr<image_u8_t, void (*)(image_u8_t *)> tag(apriltag_to_image(family.get(), id), image_u8_destroy);
  if (!tag || tag->width != static_cast<int>(cellCount()) || tag->height != static_cast<int>(cellCount()))
    throw vpMorphException(vpMorphException::badImageError,
                           "vpMorphTagTexture: libapriltag returned an unexpected tag image");
  const unsigned int n = cellCount() * cellPixels;
  vpImage<unsigned char> I(n, n);
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = 0; j < n; ++j)
      I[i][j] = tag->buf[(i / cellPixels) * tag->stride + j / cellPixels] ? 255 : 0;
  return I;
}

double vpMorphTagTexture::tagSizeForTextureSide(double side, unsigned int cellPixels)
{
  checkCell(cellPixels);
  if (!(side > 0.0) || !std::isfinite(side)) {
    std::ostringstream os;
    os << "vpMorphTagTexture: texture side must be positive and finite, got " << side;
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  const double c = cellPixels;
  return side * borderCellCount() * c / (cellCount() * c - 1.0);
}

double vpMorphTagTexture::textureSideForTagSize(double tagSize, unsigned int cellPixels)
{
  checkCell(cellPixels);
  if (!(tagSize > 0.0) || !std::isfinite(tagSize)) {
    std::ostringstream os;
    os << "vpMorphTagTexture: tag size must be positive and finite, got " << tagSize;
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  const double c = cellPixels;
  return tagSize * (cellCount() * c - 1.0) / (borderCellCount() * c);
}
