// Shared by the tutorials: ViSP's -c / -d flags, a window when one can open (vpDisplayX, else vpDisplayOpenCV on a
// Wayland session, else none, said once), vpPlot windows, and --save-display FILE, which saves what the windows show
// (vpDisplay::getImage) and what the display test is to find in it. Header-only, tutorial code, not a library.
#ifndef TUTORIAL_DISPLAY_H
#define TUTORIAL_DISPLAY_H

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <visp3/core/vpColor.h>
#include <visp3/core/vpConfig.h>
#include <visp3/core/vpDisplay.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpRect.h>
#include <visp3/core/vpTime.h>
#include <visp3/gui/vpDisplayOpenCV.h>
#include <visp3/gui/vpDisplayX.h>
#include <visp3/gui/vpPlot.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphDrawing.h>

namespace tutorial
{
/*!
  The windows of a tutorial. Options (taken out of the command line, the others left to the tutorial):
  - -d: no window (what ctest passes); -c: click-free (never waits for a click; the demo passes it);
  - --save-display FILE: at save(), each window's picture as it is shown, FILE for the first one and FILE-<tag>.png
    for the others, and FILE with the extension .json listing what the display test checks in them
    (tutorial-display-check).
  A window opens with vpDisplayX when an X display is reachable; else with vpDisplayOpenCV on a Wayland session (an
  OpenCV window aborts the program when no display server answers, so it is not tried otherwise); else the tutorial
  runs headless and says so once. A window that cannot open never fails the tutorial.
*/
class Viewer
{
public:
  Viewer(int argc, char **argv, std::vector<std::string> &rest)
  {
    for (int i = 1; i < argc; ++i) {
      if (!std::strcmp(argv[i], "-d"))
        m_display = false;
      else if (!std::strcmp(argv[i], "-c"))
        m_click = false;
      else if (!std::strcmp(argv[i], "--save-display") && i + 1 < argc)
        m_save = argv[++i];
      else
        rest.push_back(argv[i]);
    }
  }
  //! The options, for a tutorial's usage line.
  static const char *options() { return "[-c] [-d] [--save-display FILE]"; }
  /*!
    True when at most \e most arguments are left in \e rest for the tutorial, none of them an option; else (--help,
    an unknown option, too many arguments) prints the usage (\e more: the tutorial's own arguments) and returns false.
  */
  static bool accepts(const std::vector<std::string> &rest, std::size_t most, const char *program,
                      const std::string &more = "")
  {
    bool option = false;
    for (const std::string &a : rest)
      option = option || (a.size() > 1 && a[0] == '-');
    if (rest.size() <= most && !option)
      return true;
    std::cout << "Usage: " << program << " " << (more.empty() ? "" : more + " ") << options() << std::endl;
    return false;
  }

  bool clickFree() const { return !m_click; }
  //! True once a window is open.
  bool on() const { return !m_windows.empty(); }

  /*!
    A window showing \e I at (x, y), its picture saved as \e tag (the first window's tag is not used: it is FILE).
    False, headless, with -d or when no window can open.
  */
  template <typename T> bool open(vpImage<T> &I, int x, int y, const std::string &title, const std::string &tag)
  {
    if (!m_display || m_failed)
      return false;
    const char *server = std::getenv("DISPLAY"), *wayland = std::getenv("WAYLAND_DISPLAY");
    std::string why = "no X display (DISPLAY is not set)";
#if defined(VISP_HAVE_X11)
    if (server && *server) {
      if (tryOpen(std::unique_ptr<vpDisplay>(new vpDisplayX), I, x, y, title, tag, why))
        return true;
      why = std::string("the X display ") + server + " did not open (" + why + ")";
    }
#endif
#if defined(VISP_HAVE_OPENCV)
    if (wayland && *wayland && tryOpen(std::unique_ptr<vpDisplay>(new vpDisplayOpenCV), I, x, y, title, tag, why))
      return true;
#endif
    headless(why);
    return false;
  }

  /*!
    A vpPlot window of \e graphs graphs (vpPlot opens its own display), or nullptr when no window is open: call after
    open(), and test the pointer.
  */
  vpPlot *plot(unsigned int graphs, unsigned int height, unsigned int width, int x, int y, const std::string &title,
               const std::string &tag)
  {
    if (!on())
      return nullptr;
    try {
      std::unique_ptr<vpPlot> p(new vpPlot(graphs, height, width, x, y, title));
      vpPlot *raw = p.get();
      m_windows.push_back({tag, nullptr, std::move(p), [raw](vpImage<vpRGBa> &O) { vpDisplay::getImage(raw->I, O); }});
      return raw;
    } catch (const vpException &e) {
      std::cout << "no plot: " << e.getStringMessage() << std::endl;
      return nullptr;
    }
  }

  //! Lets a window show a frame for at least \e ms milliseconds since the last call (nothing without a window).
  void pace(double ms)
  {
    if (!on())
      return;
    vpTime::wait(m_last, ms);
    m_last = vpTime::measureTimeMs();
  }

  //! A click in window \e I (not waited for): the user asks to stop.
  template <typename T> bool clicked(const vpImage<T> &I) const { return on() && vpDisplay::getClick(I, false); }

  //! ViSP's end: "A click to quit" written in \e I and a click waited for, unless -c or headless.
  template <typename T> void waitClick(const vpImage<T> &I) const
  {
    if (!on() || !m_click)
      return;
    vpDisplay::displayText(I, static_cast<int>(I.getHeight()) - 12, 10, "A click to quit...", vpColor::red);
    vpDisplay::flush(I);
    vpDisplay::getClick(I);
  }

  //! Lines of text in \e color on a black band at the top-left of \e I (where vpServoMorph writes its status).
  template <typename T>
  static void caption(const vpImage<T> &I, const std::vector<std::string> &lines, const vpColor &color = vpColor::white)
  {
    vpMorphDrawing::displayTextBand(I, lines, vpImagePoint(4, 4), color);
  }
  //! The caption's band.
  static vpRect captionBand(const std::vector<std::string> &lines)
  {
    return vpMorphDrawing::textBand(lines, vpImagePoint(4, 4));
  }

  // What the display test checks in the saved pictures (tutorial-display-check), window by window (by tag).
  //! At least 90 % of the pixels along \e points (a closed polygon, pixels) have \e color within 1 px.
  void expectContour(const std::string &tag, const std::string &name, const std::vector<vpImagePoint> &points,
                     const vpColor &color)
  {
    nlohmann::json pts = nlohmann::json::array();
    for (const vpImagePoint &p : points)
      pts.push_back({p.get_u(), p.get_v()});
    checks(tag)["contours"].push_back({{"name", name}, {"color", rgb(color)}, {"points", pts}, {"min_share", 0.9}});
  }
  //! Text in \e color drawn inside \e box: at least 4 pixels of it per character of \e lines (spaces aside).
  void expectText(const std::string &tag, const std::string &name, const vpRect &box, const vpColor &color,
                  const std::vector<std::string> &lines)
  {
    std::size_t chars = 0;
    for (const std::string &l : lines)
      for (char c : l)
        chars += c != ' ';
    checks(tag)["texts"].push_back({{"name", name},
                                    {"color", rgb(color)},
                                    {"box", {box.getLeft(), box.getTop(), box.getWidth(), box.getHeight()}},
                                    {"min_pixels", 4 * chars}});
  }
  //! A plot whose curves are drawn in \e colors: at least 100 pixels of them, in at least two of the colours.
  void expectCurves(const std::string &tag, const std::string &name, const std::vector<vpColor> &colors)
  {
    nlohmann::json cs = nlohmann::json::array();
    for (const vpColor &c : colors)
      cs.push_back(rgb(c));
    checks(tag)["curves"].push_back({{"name", name}, {"colors", cs}, {"min_pixels", 100}, {"min_colors", 2}});
  }

  /*!
    With --save-display: writes every window's picture and the checks. Without a window (headless, -d) nothing can be
    saved: says so and returns false; the display test then fails on the missing picture.
  */
  bool save()
  {
    if (m_save.empty())
      return true;
    if (!on()) {
      std::cout << "--save-display " << m_save << ": no window is open, nothing saved" << std::endl;
      return false;
    }
    const std::string dir = vpIoTools::getParent(m_save), stem = vpIoTools::getNameWE(m_save);
    const std::string base = dir.empty() ? stem : dir + "/" + stem;
    if (!dir.empty())
      vpIoTools::makeDirectory(dir);
    nlohmann::json out = {{"windows", nlohmann::json::array()}};
    for (std::size_t k = 0; k < m_windows.size(); ++k) {
      Window &w = m_windows[k];
      const std::string file = k == 0 ? m_save : base + "-" + w.tag + ".png";
      vpImage<vpRGBa> O;
      w.grab(O);
      vpImageIo::write(O, file);
      nlohmann::json j = m_checks.count(w.tag) ? m_checks[w.tag] : nlohmann::json::object();
      j["tag"] = w.tag;
      j["file"] = vpIoTools::getName(file);
      out["windows"].push_back(j);
      std::cout << "saved the window \"" << w.tag << "\" to " << file << std::endl;
    }
    std::ofstream f(base + ".json");
    f << out.dump(1) << "\n";
    if (!f) {
      std::cout << "cannot write " << base << ".json" << std::endl;
      return false;
    }
    return true;
  }

private:
  struct Window
  {
    std::string tag;
    std::unique_ptr<vpDisplay> display;
    std::unique_ptr<vpPlot> plot;
    std::function<void(vpImage<vpRGBa> &)> grab;
  };

  template <typename T>
  bool tryOpen(std::unique_ptr<vpDisplay> d, vpImage<T> &I, int x, int y, const std::string &title,
               const std::string &tag, std::string &why)
  {
    try {
      d->init(I, x, y, title);
    } catch (const vpException &e) {
      why = e.getStringMessage();
      return false;
    }
    vpImage<T> *image = &I;
    m_windows.push_back({tag, std::move(d), nullptr, [image](vpImage<vpRGBa> &O) { vpDisplay::getImage(*image, O); }});
    return true;
  }
  void headless(const std::string &why)
  {
    if (!m_failed)
      std::cout << "headless: " << why << "; nothing is displayed" << std::endl;
    m_failed = true;
  }
  nlohmann::json &checks(const std::string &tag)
  {
    nlohmann::json &j = m_checks[tag];
    if (j.is_null())
      j = {{"contours", nlohmann::json::array()},
           {"texts", nlohmann::json::array()},
           {"curves", nlohmann::json::array()}};
    return j;
  }
  static nlohmann::json rgb(const vpColor &c) { return {c.R, c.G, c.B}; }

  bool m_display = true, m_click = true, m_failed = false;
  std::string m_save;
  std::vector<Window> m_windows;
  std::map<std::string, nlohmann::json> m_checks;
  double m_last = 0.0;
};
} // namespace tutorial

#endif
