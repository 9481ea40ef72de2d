/*
  \file vpMorphOverlay.h
  \brief Internal to the morph_vs module (not installed): one drawing code for two surfaces, a display (vpDisplay,
  what display() draws) and an image (vpImageDraw and vpFont, what draw() burns in without a window).
*/
#ifndef VP_MORPH_OVERLAY_H
#define VP_MORPH_OVERLAY_H

#include <algorithm>
#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColor.h>
#include <visp3/core/vpDisplay.h>
#include <visp3/core/vpFont.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImageDraw.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/core/vpRect.h>
#include <visp3/morph/vpMorphContour.h>
#include <visp3/morph/vpMorphDrawing.h>

//! The few primitives the morph overlays are made of.
class vpMorphOverlay
{
public:
  virtual ~vpMorphOverlay() = default;
  virtual void polygon(const std::vector<vpImagePoint> &ips, const vpColor &color, unsigned int thickness) = 0;
  virtual void line(const vpImagePoint &a, const vpImagePoint &b, const vpColor &color, unsigned int thickness) = 0;
  virtual void cross(const vpImagePoint &p, unsigned int size, const vpColor &color, unsigned int thickness) = 0;
  //! Lines of text on a filled band in the top-left corner of the image (see textBand()).
  virtual void text(const std::vector<std::string> &lines, const vpColor &color, const vpColor &band) = 0;

  /*!
    The band the status text is written on: from (kBandMargin, kBandMargin), kLineHeight per line plus one, and
    kCharWidth per character of the longest line plus two. Sized for the widest of the fonts that write it (X11's
    fixed font, 6 x 13; OpenCV's Hershey plain at 0.8, about 8 pixels a character; vpFont's monospace at 14).
  */
  static vpRect textBand(const std::vector<std::string> &lines)
  {
    std::size_t chars = 0;
    for (const std::string &l : lines)
      chars = std::max(chars, l.size());
    return vpRect(kBandMargin, kBandMargin, static_cast<double>((chars + 2) * kCharWidth),
                  static_cast<double>((lines.size() + 1) * kLineHeight));
  }
  static constexpr unsigned int kBandMargin = 4, kLineHeight = 16, kCharWidth = 8;

  //! A contour (normalised or in pixels) as pixel points.
  static std::vector<vpImagePoint> pixels(const vpMorphContour &c, const vpCameraParameters &cam)
  {
    return c.units() == vpMorphContour::PIXEL ? c.points() : c.toPixels(cam).points();
  }
};

//! On the display attached to \e I (nothing happens without one).
template <typename T> class vpMorphDisplayOverlay : public vpMorphOverlay
{
public:
  explicit vpMorphDisplayOverlay(const vpImage<T> &I) : m_I(I) {}
  void polygon(const std::vector<vpImagePoint> &ips, const vpColor &color, unsigned int thickness) override
  {
    vpDisplay::displayPolygon(m_I, ips, color, thickness);
  }
  void line(const vpImagePoint &a, const vpImagePoint &b, const vpColor &color, unsigned int thickness) override
  {
    vpDisplay::displayLine(m_I, a, b, color, thickness);
  }
  void cross(const vpImagePoint &p, unsigned int size, const vpColor &color, unsigned int thickness) override
  {
    vpDisplay::displayCross(m_I, p, size, color, thickness);
  }
  void text(const std::vector<std::string> &lines, const vpColor &color, const vpColor &band) override
  {
    const vpRect r = textBand(lines);
    vpDisplay::displayRectangle(m_I, r, band, true);
    // X11 writes from the baseline, OpenCV from the top: a line's baseline a line height below its top leaves
    // either inside the band.
    for (std::size_t k = 0; k < lines.size(); ++k)
      vpDisplay::displayText(m_I, vpImagePoint(r.getTop() + kLineHeight * (k + 1) - 3, r.getLeft() + kCharWidth),
                             lines[k], color);
  }

private:
  const vpImage<T> &m_I;
};

//! Burnt into the pixels of \e I (no display needed), the lines clipped by vpMorphDrawing.
class vpMorphImageOverlay : public vpMorphOverlay
{
public:
  explicit vpMorphImageOverlay(vpImage<vpRGBa> &I) : m_I(I) {}
  void polygon(const std::vector<vpImagePoint> &ips, const vpColor &color, unsigned int thickness) override
  {
    vpMorphDrawing::drawPolygon(m_I, ips, color, thickness);
  }
  void line(const vpImagePoint &a, const vpImagePoint &b, const vpColor &color, unsigned int thickness) override
  {
    vpMorphDrawing::drawLine(m_I, a, b, color, thickness);
  }
  void cross(const vpImagePoint &p, unsigned int size, const vpColor &color, unsigned int thickness) override
  {
    const double h = size / 2.0;
    vpMorphDrawing::drawLine(m_I, p - vpImagePoint(h, 0), p + vpImagePoint(h, 0), color, thickness);
    vpMorphDrawing::drawLine(m_I, p - vpImagePoint(0, h), p + vpImagePoint(0, h), color, thickness);
  }
  void text(const std::vector<std::string> &lines, const vpColor &color, const vpColor &band) override
  {
    const vpRect r = textBand(lines);
    vpImageDraw::drawRectangle(m_I, r, band, true);
    const vpFont font(14, vpFont::GENERIC_MONOSPACE);
    for (std::size_t k = 0; k < lines.size(); ++k)
      font.drawText(m_I, lines[k],
                    vpImagePoint(r.getTop() + kLineHeight * k + kLineHeight / 2, r.getLeft() + kCharWidth), color);
  }

private:
  vpImage<vpRGBa> &m_I;
};

#endif
