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
  //! Lines of text in \e color on a black band in the top-left corner of the image (vpMorphDrawing::textBand()).
  virtual void text(const std::vector<std::string> &lines, const vpColor &color) = 0;
  static constexpr unsigned int kBandMargin = 4;

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
  void text(const std::vector<std::string> &lines, const vpColor &color) override
  {
    vpMorphDrawing::displayTextBand(m_I, lines, vpImagePoint(kBandMargin, kBandMargin), color);
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
  void text(const std::vector<std::string> &lines, const vpColor &color) override
  {
    vpMorphDrawing::drawTextBand(m_I, lines, vpImagePoint(kBandMargin, kBandMargin), color);
  }

private:
  vpImage<vpRGBa> &m_I;
};

#endif
