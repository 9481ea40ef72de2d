#include <visp3/morph_sim/vpMorphPlanarScene.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <sstream>

#include <opencv2/imgproc.hpp>

#include <visp3/core/vpException.h>
#include <visp3/core/vpImageConvert.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_sim/vpMorphTagTexture.h>
#include <visp3/robot/vpImageSimulator.h>

namespace
{
const unsigned int kTagCell = 10; // tag texture: 10 x 10 cells of 10 px
const double kBackground = 210, kObject = 40, kOccluder = 170, kFloor = 70;
const vpRGBa kBackgroundRGB(215, 210, 195), kObjectRGB(25, 45, 120), kOccluderRGB(190, 165, 125), kFloorRGB(70, 60, 50);
const double kFloorExtent = 0.6; // m: the floor beyond the plane's edge, as seen from about 0.5 m

void badParameter(const std::string &msg) { throw vpMorphException(vpMorphException::badParameterError, msg); }

bool isFinite(double v) { return std::isfinite(v); }

vpPoint planePoint(double x, double y)
{
  vpPoint p;
  p.setWorldCoordinates(x, y, 0.0);
  return p;
}

// Dense samples (every step metres) along the closed polygon (x, y).
void densify(const std::vector<double> &x, const std::vector<double> &y, double step, std::vector<double> &sx,
             std::vector<double> &sy)
{
  sx.clear();
  sy.clear();
  const size_t n = x.size();
  for (size_t k = 0; k < n; ++k) {
    const size_t l = (k + 1) % n;
    const double dx = x[l] - x[k], dy = y[l] - y[k];
    const int m = std::max(1, static_cast<int>(std::ceil(std::hypot(dx, dy) / step)));
    for (int i = 0; i < m; ++i) {
      sx.push_back(x[k] + dx * i / m);
      sy.push_back(y[k] + dy * i / m);
    }
  }
}

// Even-odd point-in-polygon test.
bool inside(const std::vector<double> &x, const std::vector<double> &y, double px, double py)
{
  bool in = false;
  for (size_t i = 0, j = x.size() - 1; i < x.size(); j = i++)
    if ((y[i] > py) != (y[j] > py) && px < (x[j] - x[i]) * (py - y[i]) / (y[j] - y[i]) + x[i])
      in = !in;
  return in;
}

struct TagCandidate
{
  double x, y, distance; // centre in the object frame, its distance to the object's centre (m)
};

/*!
  For each of \e directions directions around the object's centre (ox, oy), the nearest centre (1 mm steps) at which a
  tag texture of half side \e half lies 1 cm clear of the outline (x, y) (no outline sample within 1 cm of the
  square, the centre outside the object); directions where none is found within reach give none.
*/
std::vector<TagCandidate> tagCandidates(const std::vector<double> &x, const std::vector<double> &y, double ox,
                                        double oy, double radius, double half, int directions)
{
  std::vector<double> sx, sy;
  densify(x, y, 0.001, sx, sy);
  std::vector<TagCandidate> out;
  for (int k = 0; k < directions; ++k) {
    const double a = k * 2.0 * M_PI / directions;
    for (double d = 0.0; d < radius + 3 * half + 0.02; d += 0.001) {
      const double tx = ox + d * std::cos(a), ty = oy + d * std::sin(a);
      bool clear = !inside(x, y, tx, ty);
      for (size_t i = 0; i < sx.size() && clear; ++i)
        clear = std::max(std::fabs(sx[i] - tx), std::fabs(sy[i] - ty)) > half + 0.01;
      if (clear) {
        out.push_back({tx, ty, d});
        break;
      }
    }
  }
  return out;
}

bool finitePose(const vpHomogeneousMatrix &M)
{
  for (unsigned int i = 0; i < 4; ++i)
    for (unsigned int j = 0; j < 4; ++j)
      if (!std::isfinite(M[i][j]))
        return false;
  return M.isAnHomogeneousMatrix();
}

unsigned char clip(double v) { return static_cast<unsigned char>(std::min(255.0, std::max(0.0, std::round(v)))); }

// Texture of the given patch kind in grey levels or colour.
template <typename T> T level(double grey, const vpRGBa &rgb);
template <> unsigned char level<unsigned char>(double grey, const vpRGBa &) { return clip(grey); }
template <> vpRGBa level<vpRGBa>(double, const vpRGBa &rgb) { return rgb; }

template <typename T> T mix(double a, const T &dark, const T &light); // a = 1 dark, 0 light
template <> unsigned char mix<unsigned char>(double a, const unsigned char &d, const unsigned char &l)
{
  return clip(l + (static_cast<double>(d) - l) * a);
}
template <> vpRGBa mix<vpRGBa>(double a, const vpRGBa &d, const vpRGBa &l)
{
  return vpRGBa(clip(l.R + (static_cast<double>(d.R) - l.R) * a), clip(l.G + (static_cast<double>(d.G) - l.G) * a),
                clip(l.B + (static_cast<double>(d.B) - l.B) * a), 255);
}

template <typename T> vpImage<T> recolour(const vpImage<unsigned char> &src)
{
  const T dark = level<T>(kObject, kObjectRGB), light = level<T>(kBackground, kBackgroundRGB);
  vpImage<T> out(src.getHeight(), src.getWidth());
  for (unsigned int k = 0; k < src.getSize(); ++k)
    out.bitmap[k] = mix<T>(1.0 - src.bitmap[k] / 255.0, dark, light);
  return out;
}

template <typename T> void applyFaults(vpImage<T> &I, const vpMorphPlanarScene::Faults &f, unsigned int frame);

template <typename T>
void photometric(vpImage<T> &I, const vpMorphPlanarScene::Faults &f, unsigned int frame, int cvType,
                 unsigned int channels)
{
  cv::Mat m(static_cast<int>(I.getHeight()), static_cast<int>(I.getWidth()), cvType, static_cast<void *>(I.bitmap));
  if (f.blurSigma > 0.0) {
    cv::Mat b;
    cv::GaussianBlur(m, b, cv::Size(0, 0), f.blurSigma, f.blurSigma, cv::BORDER_REPLICATE);
    b.copyTo(m);
  }
  if (f.gain == 1.0 && f.offset == 0.0 && f.noiseSigma <= 0.0 && f.gradient == 0.0)
    return;
  std::mt19937 rng(static_cast<std::mt19937::result_type>(f.seed * 2654435761u + frame * 40503u + 12345u));
  std::normal_distribution<double> noise(0.0, f.noiseSigma > 0.0 ? f.noiseSigma : 1.0);
  unsigned char *p = reinterpret_cast<unsigned char *>(I.bitmap);
  const size_t n = static_cast<size_t>(I.getSize()) * (cvType == CV_8UC1 ? 1 : 4);
  const unsigned int w = I.getWidth();
  const double gx = std::cos(f.gradientAngle), gy = std::sin(f.gradientAngle);
  const double cx = 0.5 * (w - 1.0), cy = 0.5 * (I.getHeight() - 1.0), halfDiagonal = std::hypot(cx, cy) + 1e-9;
  for (size_t k = 0; k < n; ++k) {
    if (channels == 4 && (k % 4) == 3)
      continue; // alpha
    double gain = f.gain;
    if (f.gradient != 0.0) {
      const size_t pixel = k / channels;
      gain *= 1.0 + f.gradient * ((pixel % w - cx) * gx + (pixel / w - cy) * gy) / halfDiagonal;
    }
    double v = gain * p[k] + f.offset;
    if (f.noiseSigma > 0.0)
      v += noise(rng);
    p[k] = clip(v);
  }
}

template <>
void applyFaults<unsigned char>(vpImage<unsigned char> &I, const vpMorphPlanarScene::Faults &f, unsigned int frame)
{
  photometric(I, f, frame, CV_8UC1, 1);
}
template <> void applyFaults<vpRGBa>(vpImage<vpRGBa> &I, const vpMorphPlanarScene::Faults &f, unsigned int frame)
{
  photometric(I, f, frame, CV_8UC4, 4);
}
} // namespace

namespace
{
// Reads a template image; \e what names it in the errors (notFoundError when missing, ioError when unreadable).
void readImage(const std::string &path, const std::string &what, vpImage<unsigned char> &I)
{
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw vpMorphException(vpMorphException::notFoundError, what + " not found: '" + path + "'");
  try {
    vpImageIo::read(I, path);
  } catch (const vpException &e) {
    throw vpMorphException(vpMorphException::ioError, what + " '" + path + "' cannot be read: " + e.getStringMessage());
  }
}
} // namespace

vpMorphPlanarScene::vpMorphPlanarScene(const std::string &objectImage, double objectSize, int tagId, double tagSize)
  : m_path(objectImage), m_objectSize(objectSize), m_tagSize(tagSize), m_tagId(tagId), m_cam(defaultCamera())
{
  if (!isFinite(objectSize) || objectSize <= 0.0 || !isFinite(tagSize) || tagSize <= 0.0) {
    std::ostringstream os;
    os << "vpMorphPlanarScene: object and tag sizes must be positive and finite (object " << objectSize << " m, tag "
       << tagSize << " m)";
    badParameter(os.str());
  }
  readImage(objectImage, "vpMorphPlanarScene: object image", m_texture);
  m_tag = vpMorphTagTexture::create(tagId, kTagCell);          // checks the id
  m_texContour = vpMorphContourExtractor().extract(m_texture); // throws badImageError without object
  textureFrame(m_texContour, m_objectSize, m_texCx, m_texCy, m_metresPerTexel);
  updateLayout();
}

void vpMorphPlanarScene::textureFrame(const vpMorphContour &c, double objectSize, double &cx, double &cy,
                                      double &metresPerTexel)
{
  c.centroid(cx, cy);
  const auto [xmin, xmax] = std::minmax_element(c.xs().begin(), c.xs().end());
  const auto [ymin, ymax] = std::minmax_element(c.ys().begin(), c.ys().end());
  metresPerTexel = objectSize / std::max(*xmax - *xmin, *ymax - *ymin);
}

void vpMorphPlanarScene::setReferenceImage(const std::string &referenceImage, ReferencePlacement placement)
{
  vpImage<unsigned char> ref;
  readImage(referenceImage, "vpMorphPlanarScene::setReferenceImage: reference image", ref);
  if (ref.getWidth() != m_texture.getWidth() || ref.getHeight() != m_texture.getHeight())
    badParameter("vpMorphPlanarScene::setReferenceImage: '" + referenceImage +
                 "' is not of the object image's size: the two must share one texture frame");
  const vpMorphContour refContour = vpMorphContourExtractor().extract(ref);
  textureFrame(refContour, m_objectSize, m_texCx, m_texCy, m_metresPerTexel);
  m_texAlign = vpMorphRigidTransform();
  m_texAlternatives.clear();
  if (placement == BEST_OVERLAP) {
    // Starts every 2.5 deg over +-20 deg on the polygons (a local maximum wherever a part lies on the template's),
    // then the best refined on the edge outlines, to a thousandth of a texel.
    const vpMorphRigidTransform coarse =
        vpMorphRigidTransform::fitOnOverlap(m_texContour, refContour, vpMorphRigidTransform(), vpMath::rad(20.0), 17);
    m_texAlign = vpMorphRigidTransform::refineOnOverlap(m_texContour.outline(), refContour.outline(), coarse, 400);
  }
  updateLayout();
}

void vpMorphPlanarScene::setReferenceAlignment(const vpMorphRigidTransform &align,
                                               const std::vector<vpMorphRigidTransform> &alternatives)
{
  m_texAlign = align;
  m_texAlternatives = alternatives;
  updateLayout();
}

void vpMorphPlanarScene::setObjectPlacement(double x, double y, double theta)
{
  if (!isFinite(x) || !isFinite(y) || !isFinite(theta))
    badParameter("vpMorphPlanarScene::setObjectPlacement: NaN or infinite placement");
  m_objX = x;
  m_objY = y;
  m_objTheta = theta;
  updateLayout();
}

void vpMorphPlanarScene::setTagPlacement(double x, double y)
{
  if (!isFinite(x) || !isFinite(y))
    badParameter("vpMorphPlanarScene::setTagPlacement: NaN or infinite placement");
  m_tagAuto = false;
  m_tagX = x;
  m_tagY = y;
  updateLayout();
}

void vpMorphPlanarScene::setTagSize(double tagSize)
{
  if (!isFinite(tagSize) || tagSize <= 0.0)
    badParameter("vpMorphPlanarScene::setTagSize: the tag size must be finite and > 0");
  m_tagSize = tagSize;
  updateLayout();
}

bool vpMorphPlanarScene::placeTagInView(const vpHomogeneousMatrix &cMo, const std::vector<double> &tagSizes,
                                        double margin)
{
  if (!finitePose(cMo) || !isFinite(margin))
    badParameter("vpMorphPlanarScene::placeTagInView: invalid cMo or margin");
  for (double size : tagSizes)
    if (!isFinite(size) || size <= 0.0)
      badParameter("vpMorphPlanarScene::placeTagInView: tag sizes must be finite and > 0");
  std::vector<double> x, y;
  double radius = 0.0;
  for (const vpPoint &p : objectContour3D()) {
    x.push_back(p.get_oX());
    y.push_back(p.get_oY());
    radius = std::max(radius, std::hypot(p.get_oX() - m_objX, p.get_oY() - m_objY));
  }
  for (double size : tagSizes) {
    const double half = vpMorphTagTexture::textureSideForTagSize(size, kTagCell) / 2;
    const TagCandidate *best = nullptr;
    const std::vector<TagCandidate> candidates = tagCandidates(x, y, m_objX, m_objY, radius, half, 24);
    for (const TagCandidate &c : candidates) {
      const std::vector<vpPoint> square = {planePoint(c.x - half, c.y - half), planePoint(c.x + half, c.y - half),
                                           planePoint(c.x + half, c.y + half), planePoint(c.x - half, c.y + half)};
      bool in = true;
      for (vpPoint p : square) {
        p.track(cMo);
        double u = 0.0, v = 0.0;
        vpMeterPixelConversion::convertPoint(m_cam, p.get_x(), p.get_y(), u, v);
        in = in && p.get_Z() > 0.0 && u >= margin && v >= margin && u <= m_width - 1.0 - margin &&
             v <= m_height - 1.0 - margin;
      }
      if (in && (!best || c.distance < best->distance - 1e-9))
        best = &c;
    }
    if (best) {
      m_tagSize = size;
      m_tagAuto = false;
      m_tagX = best->x;
      m_tagY = best->y;
      updateLayout();
      return true;
    }
  }
  return false;
}

std::vector<vpPoint> vpMorphPlanarScene::tagTextureCorners3D() const
{
  const double h = vpMorphTagTexture::textureSideForTagSize(m_tagSize, kTagCell) / 2;
  return {planePoint(m_tagX - h, m_tagY - h), planePoint(m_tagX + h, m_tagY - h), planePoint(m_tagX + h, m_tagY + h),
          planePoint(m_tagX - h, m_tagY + h)};
}

double vpMorphPlanarScene::objectArea() const
{
  const std::vector<vpPoint> P = objectContour3D();
  double a = 0.0;
  for (std::size_t i = 0, j = P.size() - 1; i < P.size(); j = i++)
    a += P[j].get_oX() * P[i].get_oY() - P[i].get_oX() * P[j].get_oY();
  return 0.5 * std::fabs(a);
}

void vpMorphPlanarScene::setFaults(const Faults &f)
{
  std::ostringstream os;
  if (!isFinite(f.noiseSigma) || f.noiseSigma < 0.0 || !isFinite(f.blurSigma) || f.blurSigma < 0.0 ||
      f.blurSigma > 20.0)
    os << "noise and blur sigmas must be finite, >= 0 (blur <= 20 px): noise " << f.noiseSigma << ", blur "
       << f.blurSigma;
  else if (!isFinite(f.gain) || f.gain <= 0.0 || !isFinite(f.offset))
    os << "gain must be positive and offset finite: gain " << f.gain << ", offset " << f.offset;
  else if (!isFinite(f.occludedShare) || f.occludedShare < 0.0 || f.occludedShare > 0.9)
    os << "occluded share must be in [0, 0.9], got " << f.occludedShare;
  else if (!isFinite(f.occluderPosition) || f.occluderPosition < 0.0 || f.occluderPosition >= 1.0)
    os << "occluder position must be in [0, 1), got " << f.occluderPosition;
  else if (f.distractors > 20)
    os << "at most 20 distractors, got " << f.distractors;
  else if (!isFinite(f.gradient) || f.gradient < 0.0 || f.gradient > 0.9 || !isFinite(f.gradientAngle))
    os << "the gradient must be in [0, 0.9] with a finite angle, got " << f.gradient;
  else if (!isFinite(f.planeEdgeX) || !isFinite(f.planeEdgeY) || !isFinite(f.planeEdgeAngle))
    os << "the plane's edge must be finite";
  else if (!isFinite(f.largeDistractorArea) || f.largeDistractorArea < 0.0 || f.largeDistractorArea > 0.1 ||
           !isFinite(f.largeDistractorAspect) || f.largeDistractorAspect < 1.0 || f.largeDistractorAspect > 10.0 ||
           !isFinite(f.largeDistractorX) || !isFinite(f.largeDistractorY) || !isFinite(f.largeDistractorAngle))
    os << "the large distractor needs an area in [0, 0.1] m^2, an aspect in [1, 10] and a finite placement";
  if (!os.str().empty())
    badParameter("vpMorphPlanarScene::setFaults: " + os.str());
  m_faults = f;
  updateLayout();
}

void vpMorphPlanarScene::setCamera(const vpCameraParameters &cam, unsigned int width, unsigned int height)
{
  if (!(cam.get_px() > 0.0) || !(cam.get_py() > 0.0) || !isFinite(cam.get_u0()) || !isFinite(cam.get_v0()) ||
      width < 8 || height < 8 || width > 10000 || height > 10000)
    badParameter(
        "vpMorphPlanarScene::setCamera: positive focal lengths and an image of 8..10000 pixels per side needed");
  m_cam = cam;
  m_width = width;
  m_height = height;
}

std::vector<vpPoint> vpMorphPlanarScene::objectContour3D() const
{
  std::vector<vpPoint> P;
  for (size_t k = 0; k < m_texContour.size(); ++k)
    P.push_back(texelOnPlane(m_texContour.x(k), m_texContour.y(k)));
  return P;
}

std::vector<vpHomogeneousMatrix> vpMorphPlanarScene::alternativePlacements() const
{
  std::vector<vpHomogeneousMatrix> out;
  for (const vpMorphRigidTransform &A : m_texAlternatives)
    out.push_back(placementOf(A));
  return out;
}

vpHomogeneousMatrix vpMorphPlanarScene::placementOf(const vpMorphRigidTransform &A) const
{
  // W maps the object laid by m_texAlign onto the object laid by A, in the object frame: two texels fix the in-plane
  // rotation and translation.
  const double ax = m_texCx, ay = m_texCy, bx = m_texCx + 100.0, by = m_texCy;
  const vpPoint p1a = texelOnPlane(ax, ay), p1b = texelOnPlane(bx, by);
  const vpPoint p2a = texelOnPlane(ax, ay, A), p2b = texelOnPlane(bx, by, A);
  const double angle = std::atan2(p2b.get_oY() - p2a.get_oY(), p2b.get_oX() - p2a.get_oX()) -
                       std::atan2(p1b.get_oY() - p1a.get_oY(), p1b.get_oX() - p1a.get_oX());
  const double c = std::cos(angle), s = std::sin(angle);
  return vpHomogeneousMatrix(p2a.get_oX() - (c * p1a.get_oX() - s * p1a.get_oY()),
                             p2a.get_oY() - (s * p1a.get_oX() + c * p1a.get_oY()), 0.0, 0.0, 0.0, angle);
}

vpPoint vpMorphPlanarScene::texelOnPlane(double tx, double ty) const { return texelOnPlane(tx, ty, m_texAlign); }

vpPoint vpMorphPlanarScene::texelOnPlane(double tx, double ty, const vpMorphRigidTransform &align) const
{
  double ax, ay;
  align.apply(tx, ty, ax, ay);
  const double c = std::cos(m_objTheta), s = std::sin(m_objTheta), p = m_metresPerTexel;
  const double lx = (ax - m_texCx) * p, ly = (ay - m_texCy) * p;
  return planePoint(m_objX + c * lx - s * ly, m_objY + s * lx + c * ly);
}

vpImagePoint vpMorphPlanarScene::projectedTexel(double tx, double ty, const vpHomogeneousMatrix &cMo) const
{
  if (!finitePose(cMo) || !isFinite(tx) || !isFinite(ty))
    badParameter("vpMorphPlanarScene::projectedTexel: NaN or infinite texel or pose");
  vpPoint P = texelOnPlane(tx, ty);
  P.track(cMo);
  if (P.get_Z() <= 0.0)
    badParameter("vpMorphPlanarScene::projectedTexel: the texel is behind the camera");
  double u = 0.0, v = 0.0;
  vpMeterPixelConversion::convertPoint(m_cam, P.get_x(), P.get_y(), u, v);
  return vpImagePoint(v, u);
}

vpMorphContour vpMorphPlanarScene::projectedContour(const vpHomogeneousMatrix &cMo) const
{
  if (!finitePose(cMo))
    badParameter("vpMorphPlanarScene::projectedContour: cMo is not a valid homogeneous matrix (NaN?)");
  std::vector<double> u, v;
  for (vpPoint P : objectContour3D()) {
    P.track(cMo);
    if (P.get_Z() <= 0.0)
      badParameter("vpMorphPlanarScene::projectedContour: the object is behind the camera");
    double uu = 0.0, vv = 0.0;
    vpMeterPixelConversion::convertPoint(m_cam, P.get_x(), P.get_y(), uu, vv);
    u.push_back(uu);
    v.push_back(vv);
  }
  return vpMorphContour(u, v, vpMorphContour::PIXEL);
}

namespace
{
bool pointsInView(const std::vector<vpPoint> &P, const vpHomogeneousMatrix &cMo, const vpCameraParameters &cam,
                  unsigned int width, unsigned int height, double margin)
{
  if (!finitePose(cMo) || !std::isfinite(margin))
    badParameter("vpMorphPlanarScene: in-view test needs a valid cMo and a finite margin");
  for (vpPoint p : P) {
    p.track(cMo);
    if (p.get_Z() <= 0.0)
      return false;
    double u = 0.0, v = 0.0;
    vpMeterPixelConversion::convertPoint(cam, p.get_x(), p.get_y(), u, v);
    if (u < margin || v < margin || u > width - 1.0 - margin || v > height - 1.0 - margin)
      return false;
  }
  return true;
}
} // namespace

bool vpMorphPlanarScene::objectInView(const vpHomogeneousMatrix &cMo, double margin) const
{
  return pointsInView(objectContour3D(), cMo, m_cam, m_width, m_height, margin);
}

bool vpMorphPlanarScene::tagInView(const vpHomogeneousMatrix &cMo, double margin) const
{
  return pointsInView(tagCorners3D(), cMo, m_cam, m_width, m_height, margin);
}

vpHomogeneousMatrix vpMorphPlanarScene::oMt() const { return vpHomogeneousMatrix(m_tagX, m_tagY, 0.0, 0.0, 0.0, 0.0); }

std::vector<vpPoint> vpMorphPlanarScene::tagCorners3D() const
{
  // vpDetectorAprilTag's order with z along the viewing direction: (-,+), (+,+), (+,-), (-,-) in tag coordinates.
  const double h = m_tagSize / 2;
  return {planePoint(m_tagX - h, m_tagY + h), planePoint(m_tagX + h, m_tagY + h), planePoint(m_tagX + h, m_tagY - h),
          planePoint(m_tagX - h, m_tagY - h)};
}

std::vector<vpImagePoint> vpMorphPlanarScene::projectedTagCorners(const vpHomogeneousMatrix &cMo) const
{
  if (!finitePose(cMo))
    badParameter("vpMorphPlanarScene::projectedTagCorners: cMo is not a valid homogeneous matrix (NaN?)");
  std::vector<vpImagePoint> ips;
  for (vpPoint P : tagCorners3D()) {
    P.track(cMo);
    vpImagePoint ip;
    vpMeterPixelConversion::convertPoint(m_cam, P.get_x(), P.get_y(), ip);
    ips.push_back(ip);
  }
  return ips;
}

vpMorphTagPoseEstimator vpMorphPlanarScene::tagPoseEstimator() const
{
  return vpMorphTagPoseEstimator(m_tagId, m_tagSize, oMt(), m_cam);
}

vpMorphContour vpMorphPlanarScene::silhouette(const vpHomogeneousMatrix &cMo) const
{
  vpImage<unsigned char> I;
  render(cMo, I);
  std::vector<vpImagePoint> corners;
  if (tagInView(cMo)) {
    vpHomogeneousMatrix cMo_tag;
    if (!tagPoseEstimator().estimate(I, cMo_tag, &corners))
      throw vpMorphException(vpMorphException::badImageError,
                             "vpMorphPlanarScene::silhouette: the tag of '" + m_path + "' is in view but not found");
  }
  const vpMorphContour c = vpMorphTagPoseEstimator::silhouette(I, corners);
  if (c.empty())
    throw vpMorphException(vpMorphException::badImageError,
                           "vpMorphPlanarScene::silhouette: no object seen in the view of '" + m_path + "'");
  return c;
}

vpMorphArticulation vpMorphPlanarScene::articulation(const vpMorphJointFile &joint,
                                                     const vpHomogeneousMatrix &cMo) const
{
  vpMorphContour c[2];
  for (unsigned int k = 0; k < 2; ++k) {
    vpMorphPlanarScene part(joint.part(k), m_objectSize, m_tagId, m_tagSize);
    part.setReferenceImage(m_path, SHARED_FRAME); // the object's texture frame, not the part's own
    part.setObjectPlacement(m_objX, m_objY, m_objTheta);
    if (!m_tagAuto)
      part.setTagPlacement(m_tagX, m_tagY);
    part.setCamera(m_cam, m_width, m_height);
    c[k] = part.silhouette(cMo);
  }
  // The range is drawn in the texture's axes; the camera may see them mirrored.
  const double pu = joint.pivot().get_u(), pv = joint.pivot().get_v();
  const vpImagePoint o = projectedTexel(pu, pv, cMo);
  const vpImagePoint ex = projectedTexel(pu + 1.0, pv, cMo), ey = projectedTexel(pu, pv + 1.0, cMo);
  const double cross =
      (ex.get_u() - o.get_u()) * (ey.get_v() - o.get_v()) - (ex.get_v() - o.get_v()) * (ey.get_u() - o.get_u());
  const double lo = joint.minAngle(), hi = joint.maxAngle();
  return cross > 0.0 ? vpMorphArticulation(c[0], c[1], o, lo, hi) : vpMorphArticulation(c[0], c[1], o, -hi, -lo);
}

double vpMorphPlanarScene::occludedShare() const { return m_occludedShare; }
std::vector<vpPoint> vpMorphPlanarScene::occluderCorners3D() const { return m_occluder; }
std::vector<std::vector<vpPoint>> vpMorphPlanarScene::distractorCorners3D() const { return m_distractors; }

void vpMorphPlanarScene::updateLayout()
{
  const std::vector<vpPoint> P = objectContour3D();
  std::vector<double> x, y;
  double radius = 0.0; // of the outline about its centroid
  for (const vpPoint &p : P) {
    x.push_back(p.get_oX());
    y.push_back(p.get_oY());
    radius = std::max(radius, std::hypot(p.get_oX() - m_objX, p.get_oY() - m_objY));
  }
  const double tagHalf = vpMorphTagTexture::textureSideForTagSize(m_tagSize, kTagCell) / 2; // with quiet zone
  if (m_tagAuto) {
    // The nearest of 8 directions (the first found among equals).
    double best = 1e9;
    for (const TagCandidate &c : tagCandidates(x, y, m_objX, m_objY, radius, tagHalf, 8))
      if (c.distance < best - 1e-9) {
        best = c.distance;
        m_tagX = c.x;
        m_tagY = c.y;
      }
  }

  // Occluder: a square centred on the outline point at the requested arc length, grown by bisection until the
  // requested share of the densely sampled outline lies inside it.
  m_occluder.clear();
  m_occludedShare = 0.0;
  std::vector<double> sx, sy;
  densify(x, y, 0.0005, sx, sy);
  if (m_faults.occludedShare > 0.0) {
    const size_t c = std::min(sx.size() - 1, static_cast<size_t>(m_faults.occluderPosition * sx.size()));
    auto share = [&](double h) {
      size_t in = 0;
      for (size_t i = 0; i < sx.size(); ++i)
        in += (std::fabs(sx[i] - sx[c]) <= h && std::fabs(sy[i] - sy[c]) <= h) ? 1 : 0;
      return static_cast<double>(in) / sx.size();
    };
    double lo = 0.0, hi = 2.5 * radius;
    for (int it = 0; it < 40; ++it) {
      const double mid = 0.5 * (lo + hi);
      (share(mid) < m_faults.occludedShare ? lo : hi) = mid;
    }
    const double h = hi;
    m_occludedShare = share(h);
    m_occluder = {planePoint(sx[c] - h, sy[c] - h), planePoint(sx[c] + h, sy[c] - h), planePoint(sx[c] + h, sy[c] + h),
                  planePoint(sx[c] - h, sy[c] + h)};
  }

  // Distractors: small dark rectangles placed by the seeded generator, clear of the object and of the tag.
  m_distractors.clear();
  std::mt19937 rng(m_faults.seed * 7919u + 17u);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  const double keepObject = radius + 0.015, keepTag = tagHalf * std::sqrt(2.0) + 0.01;
  for (unsigned int k = 0, tries = 0; k < m_faults.distractors && tries < 10000; ++tries) {
    const double L = 0.015 + 0.02 * U(rng), W = 0.006 + 0.01 * U(rng), a = 2 * M_PI * U(rng);
    const double cx = m_objX + (U(rng) - 0.5) * 0.36, cy = m_objY + (U(rng) - 0.5) * 0.26;
    const double r = 0.5 * std::hypot(L, W);
    if (std::hypot(cx - m_objX, cy - m_objY) < keepObject + r || std::hypot(cx - m_tagX, cy - m_tagY) < keepTag + r)
      continue;
    bool overlaps = false;
    for (const auto &d : m_distractors) {
      const double dx = 0.5 * (d[0].get_oX() + d[2].get_oX()), dy = 0.5 * (d[0].get_oY() + d[2].get_oY());
      overlaps = overlaps || std::hypot(cx - dx, cy - dy) < r + 0.03;
    }
    if (overlaps)
      continue;
    const double c = std::cos(a), s = std::sin(a);
    auto corner = [&](double u, double v) { return planePoint(cx + c * u - s * v, cy + s * u + c * v); };
    m_distractors.push_back(
        {corner(-L / 2, -W / 2), corner(L / 2, -W / 2), corner(L / 2, W / 2), corner(-L / 2, W / 2)});
    ++k;
  }
  if (m_faults.largeDistractorArea > 0.0) {
    const double L = std::sqrt(m_faults.largeDistractorArea * m_faults.largeDistractorAspect);
    const double W = m_faults.largeDistractorArea / L;
    const double c = std::cos(m_faults.largeDistractorAngle), s = std::sin(m_faults.largeDistractorAngle);
    const double cx = m_faults.largeDistractorX, cy = m_faults.largeDistractorY;
    auto corner = [&](double u, double v) { return planePoint(cx + c * u - s * v, cy + s * u + c * v); };
    m_distractors.push_back(
        {corner(-L / 2, -W / 2), corner(L / 2, -W / 2), corner(L / 2, W / 2), corner(-L / 2, W / 2)});
  }
}

std::vector<vpMorphPlanarScene::Patch> vpMorphPlanarScene::patches() const
{
  std::vector<Patch> out;
  // Object texture: texel (i, j) centre lands at ((j - cx) p, (i - cy) p) before placement (vpImageSimulator maps
  // texel centres 0 .. W-1 onto the rectangle).
  const double W = m_texture.getWidth() - 1.0, H = m_texture.getHeight() - 1.0;
  if (!m_faults.objectHidden)
    out.push_back({{texelOnPlane(0, 0), texelOnPlane(W, 0), texelOnPlane(W, H), texelOnPlane(0, H)}, 0});
  if (m_faults.planeEdge) {
    // The floor beyond the edge, painted over the object texture's white margin where the edge crosses it.
    const double nx = std::cos(m_faults.planeEdgeAngle), ny = std::sin(m_faults.planeEdgeAngle), F = kFloorExtent;
    const double px = m_faults.planeEdgeX, py = m_faults.planeEdgeY;
    out.push_back({{planePoint(px - F * ny, py + F * nx), planePoint(px + F * ny, py - F * nx),
                    planePoint(px + F * ny + F * nx, py - F * nx + F * ny),
                    planePoint(px - F * ny + F * nx, py + F * nx + F * ny)},
                   4});
  }
  for (const auto &d : m_distractors)
    out.push_back({d, 3});
  const double h = vpMorphTagTexture::textureSideForTagSize(m_tagSize, kTagCell) / 2;
  out.push_back({{planePoint(m_tagX - h, m_tagY - h), planePoint(m_tagX + h, m_tagY - h),
                  planePoint(m_tagX + h, m_tagY + h), planePoint(m_tagX - h, m_tagY + h)},
                 1});
  if (!m_occluder.empty())
    out.push_back({m_occluder, 2});
  return out;
}

template <typename T>
void vpMorphPlanarScene::renderT(const vpHomogeneousMatrix &cMo, vpImage<T> &I, unsigned int frame) const
{
  if (!finitePose(cMo))
    badParameter("vpMorphPlanarScene::render: cMo is not a valid homogeneous matrix (NaN?)");
  const T background = level<T>(kBackground, kBackgroundRGB);
  I.resize(m_height, m_width, background);
  const vpImage<T> object = recolour<T>(m_texture), tag = recolour<T>(m_tag);
  vpImage<T> dark(2, 2, level<T>(kObject, kObjectRGB)), occluder(2, 2, level<T>(kOccluder, kOccluderRGB)),
      floor(2, 2, level<T>(kFloor, kFloorRGB));
  const vpImageSimulator::vpColorPlan plan =
      std::is_same<T, unsigned char>::value ? vpImageSimulator::GRAY_SCALED : vpImageSimulator::COLORED;
  for (const Patch &patch : patches()) {
    vpImageSimulator sim(plan);
    sim.setInterpolationType(vpImageSimulator::BILINEAR_INTERPOLATION);
    const vpImage<T> &tex = patch.kind == 0   ? object
                            : patch.kind == 1 ? tag
                            : patch.kind == 2 ? occluder
                            : patch.kind == 4 ? floor
                                              : dark;
    sim.init(tex, patch.corners);
    sim.setCameraPosition(cMo);
    sim.getImage(I, m_cam); // paints only where the patch is seen, over what is already there (coplanar: in order)
  }
  applyFaults(I, m_faults, frame);
}

void vpMorphPlanarScene::render(const vpHomogeneousMatrix &cMo, vpImage<unsigned char> &I, unsigned int frame) const
{
  renderT(cMo, I, frame);
}

void vpMorphPlanarScene::render(const vpHomogeneousMatrix &cMo, vpImage<vpRGBa> &I, unsigned int frame) const
{
  renderT(cMo, I, frame);
}
