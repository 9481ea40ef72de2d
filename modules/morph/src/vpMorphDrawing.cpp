#include <visp3/morph/vpMorphDrawing.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <sstream>

#include <visp3/core/vpDisplay.h>
#include <visp3/core/vpFont.h>
#include <visp3/core/vpImageDraw.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphException.h>

const vpColor vpMorphDrawing::rigidColor(30, 90, 220);
const vpColor vpMorphDrawing::deformationColor(235, 120, 0);
const vpColor vpMorphDrawing::inputColor(175, 175, 175);

namespace
{
template <typename T>
vpRect displayBand(const vpImage<T> &I, const std::vector<std::string> &lines, const vpImagePoint &topLeft,
                   const vpColor &color)
{
  const vpRect band = vpMorphDrawing::textBand(lines, topLeft);
  vpDisplay::displayRectangle(I, band, vpColor::black, true);
  // X11 writes from the baseline, OpenCV from the top: a baseline 13 pixels below a line's top leaves either inside
  // the band.
  for (std::size_t k = 0; k < lines.size(); ++k)
    vpDisplay::displayText(I, vpImagePoint(band.getTop() + 16.0 * (k + 1) - 3, band.getLeft() + 8), lines[k], color);
  return band;
}

// Paints a rectangular frame of the given thickness inside the tile [top, top+size) x [left, left+size).
void tileBorder(vpImage<vpRGBa> &I, unsigned int top, unsigned int left, unsigned int size, unsigned int thickness,
                const vpRGBa &c)
{
  for (unsigned int r = top; r < top + size; ++r)
    for (unsigned int q = left; q < left + size; ++q) {
      const unsigned int dr = std::min(r - top, top + size - 1 - r), dq = std::min(q - left, left + size - 1 - q);
      if (std::min(dr, dq) < thickness)
        I[r][q] = c;
    }
}
} // namespace

vpImage<vpRGBa> vpMorphDrawing::sequenceStrip(const vpMorphContour &input, const std::vector<vpMorphContour> &frames,
                                              unsigned int tileSize, unsigned int columns, std::size_t rigidFrames)
{
  if (frames.empty())
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphDrawing::sequenceStrip: no frames to draw");
  if (tileSize < 32) {
    std::ostringstream os;
    os << "vpMorphDrawing::sequenceStrip: tileSize must be >= 32 pixels (got " << tileSize << ")";
    throw vpMorphException(vpMorphException::badParameterError, os.str());
  }
  if (input.empty())
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphDrawing::sequenceStrip: empty input contour");
  for (std::size_t k = 0; k < frames.size(); ++k)
    if (frames[k].empty()) {
      std::ostringstream os;
      os << "vpMorphDrawing::sequenceStrip: frame " << k << " is empty";
      throw vpMorphException(vpMorphException::badParameterError, os.str());
    }

  const std::size_t N = frames.size();
  std::size_t cols = columns;
  if (cols == 0) {
    const std::size_t rows = (N + 7) / 8;
    cols = (N + rows - 1) / rows;
  }
  cols = std::min(cols, N);
  const std::size_t rows = (N + cols - 1) / cols;

  // One scale and offset for every tile, fitted to the union bounding box.
  double xmin = std::numeric_limits<double>::infinity(), ymin = xmin, xmax = -xmin, ymax = -xmin;
  auto grow = [&](const vpMorphContour &c) {
    for (std::size_t k = 0; k < c.size(); ++k) {
      xmin = std::min(xmin, c.x(k));
      xmax = std::max(xmax, c.x(k));
      ymin = std::min(ymin, c.y(k));
      ymax = std::max(ymax, c.y(k));
    }
  };
  grow(input);
  for (const vpMorphContour &f : frames)
    grow(f);
  const double margin = std::max(8.0, tileSize / 10.0);
  const double extent = std::max(std::max(xmax - xmin, ymax - ymin), 1e-12);
  const double scale = (tileSize - 2.0 * margin) / extent;
  const double ox = 0.5 * tileSize - scale * 0.5 * (xmin + xmax);
  const double oy = 0.5 * tileSize - scale * 0.5 * (ymin + ymax);

  vpImage<vpRGBa> I(static_cast<unsigned int>(rows * tileSize), static_cast<unsigned int>(cols * tileSize),
                    vpRGBa(255, 255, 255));
  std::unique_ptr<vpFont> font;
  try {
    font.reset(new vpFont(std::max(10u, tileSize / 14), vpFont::GENERIC_MONOSPACE));
  } catch (...) {
    font.reset(); // numbers are optional
  }

  auto toTile = [&](const vpMorphContour &c, unsigned int top, unsigned int left) {
    std::vector<vpImagePoint> p;
    p.reserve(c.size());
    for (std::size_t k = 0; k < c.size(); ++k)
      p.emplace_back(top + oy + scale * c.y(k), left + ox + scale * c.x(k));
    return p;
  };

  for (std::size_t k = 0; k < N; ++k) {
    const unsigned int top = static_cast<unsigned int>((k / cols) * tileSize);
    const unsigned int left = static_cast<unsigned int>((k % cols) * tileSize);
    const bool endTile = (k == 0 || k + 1 == N);
    tileBorder(I, top, left, tileSize, endTile ? 3 : 1, endTile ? vpRGBa(0, 0, 0) : vpRGBa(220, 220, 220));
    vpImageDraw::drawPolygon(I, toTile(input, top, left), inputColor, 1, true);
    const vpColor &col = k < rigidFrames ? rigidColor : deformationColor;
    vpImageDraw::drawPolygon(I, toTile(frames[k], top, left), col, 2, true);
    if (font) {
      std::ostringstream os;
      os << k;
      font->drawText(I, os.str(), vpImagePoint(top + 6, left + 8), vpColor::black);
    }
  }
  return I;
}

vpImage<vpRGBa> vpMorphDrawing::sequenceStrip(const vpMorph &morph, std::size_t n, unsigned int tileSize,
                                              unsigned int columns)
{
  return sequenceStrip(morph.input(), morph.sequenceWithInput(n), tileSize, columns, 1 + morph.rigidFrameCount(n));
}

void vpMorphDrawing::write(const vpImage<vpRGBa> &image, const std::string &pngPath)
{
  if (pngPath.empty())
    throw vpMorphException(vpMorphException::ioError, "vpMorphDrawing::write: empty file name");
  const std::filesystem::path path(pngPath);
  std::error_code ec;
  if (path.has_parent_path()) {
    std::filesystem::create_directories(path.parent_path(), ec);
    if (ec)
      throw vpMorphException(vpMorphException::ioError, "vpMorphDrawing::write: cannot create directory " +
                                                            path.parent_path().string() + ": " + ec.message());
  }
  if (std::filesystem::is_directory(path, ec))
    throw vpMorphException(vpMorphException::ioError, "vpMorphDrawing::write: " + pngPath + " is a directory");
  // vpImageIo does not always report a failed write: remove the old file so that success can be checked.
  std::filesystem::remove(path, ec);
  try {
    vpImageIo::write(image, pngPath);
  } catch (const vpException &e) {
    throw vpMorphException(vpMorphException::ioError,
                           "vpMorphDrawing::write: cannot write " + pngPath + ": " + e.getStringMessage());
  }
  if (!std::filesystem::is_regular_file(path, ec) || std::filesystem::file_size(path, ec) == 0)
    throw vpMorphException(vpMorphException::ioError, "vpMorphDrawing::write: " + pngPath + " was not written");
}

void vpMorphDrawing::drawLine(vpImage<vpRGBa> &I, const vpImagePoint &a, const vpImagePoint &b, const vpColor &color,
                              unsigned int thickness)
{
  const double u0 = a.get_u(), v0 = a.get_v(), du = b.get_u() - u0, dv = b.get_v() - v0;
  if (I.getWidth() == 0 || I.getHeight() == 0 || !std::isfinite(u0) || !std::isfinite(v0) || !std::isfinite(du) ||
      !std::isfinite(dv))
    return;
  // Liang-Barsky: the part of u0 + t du, v0 + t dv, t in [0, 1], inside [0, W-1] x [0, H-1].
  const double W = I.getWidth() - 1.0, H = I.getHeight() - 1.0;
  const double p[4] = {-du, du, -dv, dv}, q[4] = {u0, W - u0, v0, H - v0};
  double t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 4; ++k) {
    if (p[k] == 0.0) {
      if (q[k] < 0.0)
        return; // parallel to this border and outside it
      continue;
    }
    const double r = q[k] / p[k];
    if (p[k] < 0.0)
      t0 = std::max(t0, r);
    else
      t1 = std::min(t1, r);
  }
  if (t0 > t1)
    return;
  auto inside = [&](double t) {
    return vpImagePoint(std::min(std::max(v0 + t * dv, 0.0), H), std::min(std::max(u0 + t * du, 0.0), W));
  };
  vpImageDraw::drawLine(I, inside(t0), inside(t1), color, thickness);
}

void vpMorphDrawing::drawPolygon(vpImage<vpRGBa> &I, const std::vector<vpImagePoint> &points, const vpColor &color,
                                 unsigned int thickness)
{
  for (std::size_t k = 0; k < points.size() && points.size() > 1; ++k)
    drawLine(I, points[k], points[(k + 1) % points.size()], color, thickness);
}

vpRect vpMorphDrawing::textBand(const std::vector<std::string> &lines, const vpImagePoint &topLeft)
{
  std::size_t chars = 0;
  for (const std::string &l : lines)
    chars = std::max(chars, l.size());
  return vpRect(topLeft.get_u(), topLeft.get_v(), 8.0 * (chars + 2), 16.0 * (lines.size() + 1));
}

vpRect vpMorphDrawing::drawTextBand(vpImage<vpRGBa> &I, const std::vector<std::string> &lines,
                                    const vpImagePoint &topLeft, const vpColor &color)
{
  const vpRect band = textBand(lines, topLeft);
  // Filled here, within the image (vpImageDraw's rectangle goes through its line drawing).
  const int u0 = std::max(0, static_cast<int>(band.getLeft())), v0 = std::max(0, static_cast<int>(band.getTop()));
  const int u1 = std::min(static_cast<int>(I.getWidth()), static_cast<int>(band.getRight()) + 1);
  const int v1 = std::min(static_cast<int>(I.getHeight()), static_cast<int>(band.getBottom()) + 1);
  for (int v = v0; v < v1; ++v)
    for (int u = u0; u < u1; ++u)
      I[static_cast<unsigned int>(v)][static_cast<unsigned int>(u)] = vpRGBa(0, 0, 0);
  const vpFont font(14, vpFont::GENERIC_MONOSPACE);
  for (std::size_t k = 0; k < lines.size(); ++k)
    font.drawText(I, lines[k], vpImagePoint(band.getTop() + 16.0 * k + 8, band.getLeft() + 8), color);
  return band;
}

vpRect vpMorphDrawing::displayTextBand(const vpImage<unsigned char> &I, const std::vector<std::string> &lines,
                                       const vpImagePoint &topLeft, const vpColor &color)
{
  return displayBand(I, lines, topLeft, color);
}

vpRect vpMorphDrawing::displayTextBand(const vpImage<vpRGBa> &I, const std::vector<std::string> &lines,
                                       const vpImagePoint &topLeft, const vpColor &color)
{
  return displayBand(I, lines, topLeft, color);
}
