// The display test's checker: reads the checks a tutorial wrote with --save-display (FILE.json, see
// tutorial-display.h) and verifies them on the saved pictures, as a person would see them:
// - a contour: at least min_share of the pixels along the polygon carry its overlay colour within 1 pixel;
// - a text: at least min_pixels pixels of its colour inside its box (glyphs drawn: fonts found, text not covered);
// - a plot: at least min_pixels pixels of its curves' colours, in at least min_colors of them.
// Prints the figure of every check; exit status 0 when all pass.
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <set>
#include <string>
#include <utility>

#include <nlohmann/json.hpp>

#include <visp3/core/vpException.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/io/vpImageIo.h>

namespace
{
using json = nlohmann::json;

bool sameColor(const vpRGBa &p, const json &c) { return p.R == c[0] && p.G == c[1] && p.B == c[2]; }

bool colorNear(const vpImage<vpRGBa> &I, long u, long v, const json &c)
{
  for (long dv = -1; dv <= 1; ++dv)
    for (long du = -1; du <= 1; ++du) {
      const long uu = u + du, vv = v + dv;
      if (uu >= 0 && vv >= 0 && uu < static_cast<long>(I.getWidth()) && vv < static_cast<long>(I.getHeight()) &&
          sameColor(I[static_cast<unsigned int>(vv)][static_cast<unsigned int>(uu)], c))
        return true;
    }
  return false;
}

// The pixels along a closed polygon (sampled every half pixel) inside the image, each once.
std::set<std::pair<long, long>> polygonPixels(const json &pts, unsigned int w, unsigned int h)
{
  std::set<std::pair<long, long>> px;
  const std::size_t n = pts.size();
  for (std::size_t i = 0; i < n; ++i) {
    const double u0 = pts[i][0], v0 = pts[i][1], u1 = pts[(i + 1) % n][0], v1 = pts[(i + 1) % n][1];
    const int steps = std::max(1, static_cast<int>(std::ceil(2 * std::hypot(u1 - u0, v1 - v0))));
    for (int s = 0; s < steps; ++s) {
      const double t = static_cast<double>(s) / steps;
      const long u = std::lround(u0 + t * (u1 - u0)), v = std::lround(v0 + t * (v1 - v0));
      if (u >= 0 && v >= 0 && u < static_cast<long>(w) && v < static_cast<long>(h))
        px.insert({u, v});
    }
  }
  return px;
}

bool checkContour(const vpImage<vpRGBa> &I, const json &c)
{
  const auto px = polygonPixels(c.at("points"), I.getWidth(), I.getHeight());
  std::size_t hit = 0;
  for (const auto &p : px)
    hit += colorNear(I, p.first, p.second, c.at("color"));
  const double share = px.empty() ? 0.0 : static_cast<double>(hit) / px.size();
  const bool ok = px.size() >= 50 && share >= c.at("min_share").get<double>();
  std::cout << "  contour \"" << c.at("name").get<std::string>() << "\": " << hit << " of " << px.size()
            << " pixels in its colour within 1 px (" << std::lround(1000 * share) / 10.0 << " %, needs "
            << 100 * c.at("min_share").get<double>() << " %)" << (ok ? "" : "  FAILED") << std::endl;
  return ok;
}

bool checkText(const vpImage<vpRGBa> &I, const json &t)
{
  const json &b = t.at("box");
  const long left = std::max(0L, std::lround(b[0].get<double>())), top = std::max(0L, std::lround(b[1].get<double>()));
  const long right = std::min(static_cast<long>(I.getWidth()), std::lround(b[0].get<double>() + b[2].get<double>()));
  const long bottom = std::min(static_cast<long>(I.getHeight()), std::lround(b[1].get<double>() + b[3].get<double>()));
  std::size_t n = 0;
  for (long v = top; v < bottom; ++v)
    for (long u = left; u < right; ++u)
      n += sameColor(I[static_cast<unsigned int>(v)][static_cast<unsigned int>(u)], t.at("color"));
  const std::size_t need = t.at("min_pixels");
  const bool ok = n >= need;
  std::cout << "  text \"" << t.at("name").get<std::string>() << "\": " << n
            << " pixels of its colour in its box (needs " << need << ")" << (ok ? "" : "  FAILED") << std::endl;
  return ok;
}

bool checkCurves(const vpImage<vpRGBa> &I, const json &c)
{
  std::size_t total = 0, colors = 0;
  for (const json &col : c.at("colors")) {
    std::size_t n = 0;
    for (unsigned int k = 0; k < I.getSize(); ++k)
      n += sameColor(I.bitmap[k], col);
    total += n;
    colors += n > 0;
  }
  const std::size_t needPx = c.at("min_pixels"), needColors = c.at("min_colors");
  const bool ok = total >= needPx && colors >= needColors;
  std::cout << "  plot \"" << c.at("name").get<std::string>() << "\": " << total << " pixels of its curves' colours, "
            << colors << " colours (needs " << needPx << ", " << needColors << ")" << (ok ? "" : "  FAILED")
            << std::endl;
  return ok;
}
} // namespace

int main(int argc, char **argv)
{
  if (argc != 2) {
    std::cout << "Usage: " << argv[0] << " FILE.json  (written by a tutorial's --save-display)" << std::endl;
    return EXIT_FAILURE;
  }
  try {
    std::ifstream f(argv[1]);
    if (!f) {
      std::cout << "cannot read " << argv[1] << " (was the tutorial run with --save-display, and a window open?)"
                << std::endl;
      return EXIT_FAILURE;
    }
    const json checks = json::parse(f);
    const std::string dir = vpIoTools::getParent(argv[1]);
    bool ok = true;
    std::size_t count = 0;
    for (const json &w : checks.at("windows")) {
      const std::string file = (dir.empty() ? "" : dir + "/") + w.at("file").get<std::string>();
      vpImage<vpRGBa> I;
      vpImageIo::read(I, file);
      std::cout << file << " (" << I.getWidth() << " x " << I.getHeight() << ")" << std::endl;
      for (const json &c : w.value("contours", json::array()))
        ok = checkContour(I, c) && ok, ++count;
      for (const json &t : w.value("texts", json::array()))
        ok = checkText(I, t) && ok, ++count;
      for (const json &c : w.value("curves", json::array()))
        ok = checkCurves(I, c) && ok, ++count;
    }
    if (count == 0) {
      std::cout << "no check in " << argv[1] << std::endl;
      return EXIT_FAILURE;
    }
    std::cout << (ok ? "display checks passed" : "display checks FAILED") << " (" << count << ")" << std::endl;
    return ok ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cout << "error: " << e.getStringMessage() << std::endl;
  } catch (const std::exception &e) {
    std::cout << "error: " << e.what() << std::endl;
  }
  return EXIT_FAILURE;
}
