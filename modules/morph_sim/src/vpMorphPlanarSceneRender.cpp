// vpMorphPlanarScene's images: the patches drawn by vpImageSimulator, the photometric faults, and what is extracted
// from a rendered view (silhouette, articulation).
#include <visp3/morph_sim/vpMorphPlanarScene.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <type_traits>

#include <opencv2/imgproc.hpp>

#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_sim/vpMorphTagTexture.h>
#include <visp3/robot/vpImageSimulator.h>

#include "vpMorphPlanarSceneShared.h"

using namespace vpMorphPlanarSceneShared;

namespace
{
const double kBackground = 210, kObject = 40, kOccluder = 170, kFloor = 70;
const vpRGBa kBackgroundRGB(215, 210, 195), kObjectRGB(25, 45, 120), kOccluderRGB(190, 165, 125), kFloorRGB(70, 60, 50);
const double kFloorExtent = 0.6; // m: the floor beyond the plane's edge, as seen from about 0.5 m

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

unsigned int vpMorphPlanarScene::supersampling(const vpHomogeneousMatrix &cMo) const
{
  if (!finitePose(cMo))
    badParameter("vpMorphPlanarScene::supersampling: cMo is not a valid homogeneous matrix (NaN?)");
  if (m_faults.objectHidden)
    return 1;
  // Texels a pixel, the most over the texture's corners and centre in front of the camera: the inverse of the
  // shortest image step of one texel along either texture axis.
  const double W = m_texture.getWidth() - 1.0, H = m_texture.getHeight() - 1.0;
  const double at[5][2] = {{0, 0}, {W, 0}, {W, H}, {0, H}, {W / 2, H / 2}};
  double texels = 0.0;
  for (const auto &t : at) {
    vpPoint p[3] = {texelOnPlane(t[0], t[1]), texelOnPlane(t[0] + 1, t[1]), texelOnPlane(t[0], t[1] + 1)};
    double u[3], v[3];
    bool front = true;
    for (int k = 0; k < 3; ++k) {
      p[k].track(cMo);
      front = front && p[k].get_Z() > 0.0;
      vpMeterPixelConversion::convertPoint(m_cam, p[k].get_x(), p[k].get_y(), u[k], v[k]);
    }
    if (front)
      texels =
          std::max(texels, 1.0 / std::min(std::hypot(u[1] - u[0], v[1] - v[0]), std::hypot(u[2] - u[0], v[2] - v[0])));
  }
  return static_cast<unsigned int>(std::min<double>(maxSupersampling(), std::max(1.0, std::ceil(texels / 2.0))));
}

template <typename T>
void vpMorphPlanarScene::renderT(const vpHomogeneousMatrix &cMo, vpImage<T> &I, unsigned int frame) const
{
  if (!finitePose(cMo))
    badParameter("vpMorphPlanarScene::render: cMo is not a valid homogeneous matrix (NaN?)");
  const T background = level<T>(kBackground, kBackgroundRGB);
  I.resize(m_height, m_width, background);
  // K x K sub-pixels a pixel: sub-pixel s of pixel u is centred at u - 1/2 + (s + 1/2) / K, the K-times finer
  // camera's pixel K u + s, so its principal point is K u0 + (K - 1) / 2.
  const unsigned int K = supersampling(cMo);
  vpImage<T> fine;
  if (K > 1)
    fine.resize(m_height * K, m_width * K, background);
  vpImage<T> &canvas = K > 1 ? fine : I;
  const vpCameraParameters cam =
      K > 1 ? vpCameraParameters(K * m_cam.get_px(), K * m_cam.get_py(), K * m_cam.get_u0() + (K - 1) / 2.0,
                                 K * m_cam.get_v0() + (K - 1) / 2.0)
            : m_cam;
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
    sim.getImage(canvas, cam); // paints only where the patch is seen, over what is already there (coplanar: in order)
  }
  if (K > 1) {
    const int type = std::is_same<T, unsigned char>::value ? CV_8UC1 : CV_8UC4;
    const cv::Mat from(static_cast<int>(fine.getHeight()), static_cast<int>(fine.getWidth()), type,
                       static_cast<void *>(fine.bitmap));
    cv::Mat to(static_cast<int>(m_height), static_cast<int>(m_width), type, static_cast<void *>(I.bitmap));
    cv::resize(from, to, to.size(), 0, 0, cv::INTER_AREA); // the mean of each K x K block
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
