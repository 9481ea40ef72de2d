#include <visp3/morph_sim/vpMorphPlanarScene.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include <visp3/core/vpException.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_sim/vpMorphTagTexture.h>

#include "vpMorphPlanarSceneShared.h"

using namespace vpMorphPlanarSceneShared;

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
  else if (!isFinite(f.largeDistractorArea) || f.largeDistractorArea < 0.0 ||
           f.largeDistractorArea > maxDistractorArea() || !isFinite(f.largeDistractorAspect) ||
           f.largeDistractorAspect < 1.0 || f.largeDistractorAspect > 10.0 || !isFinite(f.largeDistractorX) ||
           !isFinite(f.largeDistractorY) || !isFinite(f.largeDistractorAngle))
    os << "the large distractor needs an area in [0, " << maxDistractorArea()
       << "] m^2, an aspect in [1, 10] and a finite placement";
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
