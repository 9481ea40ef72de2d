/*!
  \file fuzz_contour_extraction.cpp
  \brief Fuzz target: vpMorphContourExtractor (Otsu, polarity, boundary tracing, polygonal approximation) on
  arbitrary grey-level and colour images.

  Input: width and height bytes (0 to 63: the extractor must reject images smaller than 3x3 with an exception),
  a mode byte (bit 0: colour image; bits 1-2: each byte painted over a 1x1, 2x2, 3x3 or 4x4 block, so that large
  flat regions and long boundaries are easy to reach), then the pixels (reused cyclically when short; an empty
  pixel list gives a uniform image). A vpException is a correct outcome; anything else must satisfy the
  invariants of vpMorphContourExtractor.h (polygon: at least 3 finite vertices inside the image, positive signed
  area, simple; boundary: a closed 8-connected chain of pixel centres; mask: 0 or 255, image-sized).
*/
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include <visp3/core/vpException.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImageConvert.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphContourExtractor.h>

#include "vpFuzzInput.h"

namespace
{
void checkPolygon(const vpMorphContour &c, unsigned int w, unsigned int h)
{
  VP_FUZZ_CHECK(c.size() >= 3, "an extracted polygon has at least 3 vertices");
  VP_FUZZ_CHECK(c.units() == vpMorphContour::PIXEL, "extracted polygons are in pixels");
  for (std::size_t k = 0; k < c.size(); ++k) {
    VP_FUZZ_CHECK(std::isfinite(c.x(k)) && std::isfinite(c.y(k)), "vertices are finite");
    VP_FUZZ_CHECK(c.x(k) >= 0.0 && c.x(k) <= w - 1.0 && c.y(k) >= 0.0 && c.y(k) <= h - 1.0,
                  "vertices are pixel centres of the image");
  }
  VP_FUZZ_CHECK(c.signedArea() > 0.0, "polygons are counter-clockwise in (x, y)");
  VP_FUZZ_CHECK(c.isSimple(), "polygons are simple");
}

void checkChain(const std::vector<vpImagePoint> &chain, unsigned int w, unsigned int h)
{
  VP_FUZZ_CHECK(!chain.empty(), "a boundary has pixels");
  for (std::size_t k = 0; k < chain.size(); ++k) {
    const vpImagePoint &p = chain[k], &q = chain[(k + 1) % chain.size()];
    VP_FUZZ_CHECK(p.get_u() >= 0 && p.get_u() <= w - 1.0 && p.get_v() >= 0 && p.get_v() <= h - 1.0,
                  "boundary pixels are in the image");
    VP_FUZZ_CHECK(std::fabs(p.get_u() - q.get_u()) <= 1.0 && std::fabs(p.get_v() - q.get_v()) <= 1.0,
                  "boundaries are closed 8-connected chains");
  }
}

template <typename Pixel> void run(const vpImage<Pixel> &I, const vpImage<unsigned char> &grey)
{
  const vpMorphContourExtractor extractor;
  const unsigned int w = I.getWidth(), h = I.getHeight();
  std::vector<vpMorphContour> all;
  try {
    all = extractor.extractAll(I);
  } catch (const vpException &) {
    all.clear(); // bad image (uniform, too small, no object): a correct outcome
  }
  for (const vpMorphContour &c : all)
    checkPolygon(c, w, h);
  if (!all.empty()) {
    const vpMorphContour largest = extractor.extract(I);
    VP_FUZZ_CHECK(largest.xs() == all.front().xs() && largest.ys() == all.front().ys(),
                  "extract() is the first of extractAll()");
    // The pieces joined across their gaps: a valid polygon in the image, never smaller than the largest alone
    // by more than its digitisation (the bridges and pieces only add).
    const vpMorphContour joined = extractor.extractJoined(I);
    checkPolygon(joined, w, h);
    VP_FUZZ_CHECK(joined.area() >= largest.area() - largest.perimeter(), "a joined outline holds the largest piece");
    // Followed from its own outline (traced in a window about it when it is small in the image): valid, in the image.
    try {
      checkPolygon(extractor.extractJoined(I, largest), w, h);
    } catch (const vpException &) {
    }
  }
  try {
    for (const std::vector<vpImagePoint> &chain : extractor.boundaries(I))
      checkChain(chain, w, h);
  } catch (const vpException &) {
  }
  try {
    const vpImage<unsigned char> mask = extractor.objectMask(grey);
    VP_FUZZ_CHECK(mask.getWidth() == w && mask.getHeight() == h, "the mask has the image's size");
    for (unsigned int k = 0; k < mask.getSize(); ++k)
      VP_FUZZ_CHECK(mask.bitmap[k] == 0 || mask.bitmap[k] == 255, "the mask is binary");
  } catch (const vpException &) {
  }
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  vpFuzzInput in(data, size);
  const unsigned int w0 = in.byte() % 64, h0 = in.byte() % 64;
  const uint8_t mode = in.byte();
  const unsigned int block = 1 + ((mode >> 1) & 3);
  const unsigned int w = w0 * block, h = h0 * block;
  const bool colour = (mode & 1) != 0;
  const std::size_t channels = colour ? 3 : 1;
  const std::string px = in.rest();
  auto at = [&](std::size_t k) -> unsigned char {
    return px.empty() ? 128 : static_cast<unsigned char>(px[k % px.size()]);
  };

  vpImage<unsigned char> grey(h, w, 0);
  vpImage<vpRGBa> rgb(h, w);
  for (unsigned int v = 0; v < h; ++v)
    for (unsigned int u = 0; u < w; ++u) {
      const std::size_t k = channels * ((v / block) * w0 + u / block);
      grey[v][u] = at(k);
      rgb[v][u] = vpRGBa(at(k), at(k + 1), at(k + 2), 255);
    }
  if (colour) {
    vpImage<unsigned char> g;
    vpImageConvert::convert(rgb, g);
    run(rgb, g);
  } else {
    run(grey, grey);
  }
  return 0;
}
