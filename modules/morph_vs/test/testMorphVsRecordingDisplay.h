// A headless vpDisplay that records the lines, crosses and text drawn on the image it is attached to, so that tests
// can check what display() methods draw without a window (vpDisplay::displayPolygon draws through displayLine).
#ifndef TEST_MORPH_VS_RECORDING_DISPLAY_H
#define TEST_MORPH_VS_RECORDING_DISPLAY_H

#include <string>
#include <vector>

#include <visp3/core/vpDisplay.h>
#include <visp3/core/vpImage.h>

namespace vpMorphVsTest
{
class RecordingDisplay : public vpDisplay
{
public:
  struct Line
  {
    vpImagePoint a, b;
    vpColor color;
  };
  struct Text
  {
    vpImagePoint position;
    std::string text;
    vpColor color;
  };
  std::vector<Line> lines;
  std::vector<vpImagePoint> crosses;
  std::vector<Text> texts;

  //! Attaches to \e I (the display is used by vpDisplay's static functions on I) until detach().
  template <typename T> void attach(vpImage<T> &I)
  {
    I.display = this;
    m_displayHasBeenInitialized = true;
  }
  template <typename T> static void detach(vpImage<T> &I) { I.display = nullptr; }
  //! Number of lines drawn in \e c.
  std::size_t count(const vpColor &c) const
  {
    std::size_t n = 0;
    for (const Line &l : lines)
      n += l.color == c;
    return n;
  }

  void displayLine(const vpImagePoint &a, const vpImagePoint &b, const vpColor &color, unsigned int) override
  {
    lines.push_back({a, b, color});
  }
  void displayDotLine(const vpImagePoint &a, const vpImagePoint &b, const vpColor &color, unsigned int) override
  {
    lines.push_back({a, b, color});
  }
  void displayCharString(const vpImagePoint &p, const char *text, const vpColor &color) override
  {
    texts.push_back({p, text, color});
  }
  void displayCross(const vpImagePoint &p, unsigned int, const vpColor &, unsigned int) override
  {
    crosses.push_back(p);
  }

  // Everything else does nothing.
  void clearDisplay(const vpColor &) override {}
  void closeDisplay() override {}
  void displayArrow(const vpImagePoint &, const vpImagePoint &, const vpColor &, unsigned int, unsigned int,
                    unsigned int) override
  {
  }
  void displayCircle(const vpImagePoint &, unsigned int, const vpColor &, bool, unsigned int) override {}
  void displayImage(const vpImage<unsigned char> &) override {}
  void displayImage(const vpImage<vpRGBa> &) override {}
  void displayImageROI(const vpImage<unsigned char> &, const vpImagePoint &, unsigned int, unsigned int) override {}
  void displayImageROI(const vpImage<vpRGBa> &, const vpImagePoint &, unsigned int, unsigned int) override {}
  void displayPoint(const vpImagePoint &, const vpColor &, unsigned int) override {}
  void displayRectangle(const vpImagePoint &, unsigned int, unsigned int, const vpColor &, bool, unsigned int) override
  {
  }
  void displayRectangle(const vpImagePoint &, const vpImagePoint &, const vpColor &, bool, unsigned int) override {}
  void displayRectangle(const vpRect &, const vpColor &, bool, unsigned int) override {}
  void flushDisplay() override {}
  void flushDisplayROI(const vpImagePoint &, unsigned int, unsigned int) override {}
  bool getClick(bool) override { return false; }
  bool getClick(vpImagePoint &, bool) override { return false; }
  bool getClick(vpImagePoint &, vpMouseButton::vpMouseButtonType &, bool) override { return false; }
  bool getClickUp(vpImagePoint &, vpMouseButton::vpMouseButtonType &, bool) override { return false; }
  bool getKeyboardEvent(bool) override { return false; }
  bool getKeyboardEvent(std::string &, bool) override { return false; }
  bool getPointerMotionEvent(vpImagePoint &) override { return false; }
  bool getPointerPosition(vpImagePoint &) override { return false; }
  unsigned int getScreenHeight() override { return 480; }
  void getScreenSize(unsigned int &w, unsigned int &h) override
  {
    w = 640;
    h = 480;
  }
  unsigned int getScreenWidth() override { return 640; }
  void init(vpImage<unsigned char> &I, int, int, const std::string &) override { attach(I); }
  void init(vpImage<vpRGBa> &I, int, int, const std::string &) override { attach(I); }
  void init(unsigned int, unsigned int, int, int, const std::string &) override {}
  void setFont(const std::string &) override {}
  void setTitle(const std::string &) override {}
  void setWindowPosition(int, int) override {}
  void getImage(vpImage<vpRGBa> &) override {}
};
} // namespace vpMorphVsTest

#endif
