#include <visp3/morph_bench/vpMorphBenchScenario.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <utility>

#include <opencv2/imgproc.hpp>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphRigidTransform.h>

#include "vpMorphBenchHash.h"
#include "vpMorphBenchJoint.h"
#include "vpMorphBenchPlane.h"

namespace
{
const double kDesiredDepth = 0.5;      // m, the protocol's desired distance to the plane
const double kMaxDesiredOffset = 0.02; // m, the desired in-plane offset of the object
const double kMaxTranslation = 0.08;   // m, planar start offset
const double kViewMargin = 10.0;       // px at 640 px across: object and tag fully in view
const double kClearance = 0.01;        // m: what the plane's edge and the large distractor keep from object and tag
const std::vector<double> kTagSizes = {0.08, 0.06, 0.05, 0.04}; // m, black border: the largest that fits

const char *const kLooks[] = {"saturated", "gradient", "low-contrast", "rough", "plane-edge", "large-distractor"};

bool isLook(const std::string &set) { return std::find(std::begin(kLooks), std::end(kLooks), set) != std::end(kLooks); }
bool isResolution(const std::string &set) { return set == "res-1280" || set == "res-320"; }

unsigned int setIndex(const std::string &set)
{
  const std::vector<std::string> sets = vpMorphBenchScenario::setNames();
  return static_cast<unsigned int>(std::find(sets.begin(), sets.end(), set) - sets.begin());
}

// Start camera in the desired camera frame. The camera first orbits the point of the plane on its optical axis
// (tilt about an in-plane axis of azimuth phi), then moves along its new optical axis to change the depth, then
// turns about that axis and translates parallel to the image plane.
vpHomogeneousMatrix startPose(double rotDeg, double tx, double ty, double tiltDeg, double phi, double depthChange)
{
  const vpHomogeneousMatrix toPivot(0, 0, kDesiredDepth, 0, 0, 0);
  const vpRotationMatrix tiltR(
      vpThetaUVector(std::cos(phi) * vpMath::rad(tiltDeg), std::sin(phi) * vpMath::rad(tiltDeg), 0));
  const vpHomogeneousMatrix orbit =
      toPivot * vpHomogeneousMatrix(vpTranslationVector(0, 0, 0), tiltR) * toPivot.inverse();
  const vpHomogeneousMatrix depth(0, 0, -depthChange * kDesiredDepth, 0, 0, 0);
  const vpHomogeneousMatrix planar(tx, ty, 0, 0, 0, vpMath::rad(rotDeg));
  return orbit * depth * planar;
}

bool inView(const std::vector<vpPoint> &P, const vpHomogeneousMatrix &cMo, const vpCameraParameters &cam,
            unsigned int w, unsigned int h, double margin)
{
  for (vpPoint p : P) {
    p.track(cMo);
    double u = 0.0, v = 0.0;
    vpMeterPixelConversion::convertPoint(cam, p.get_x(), p.get_y(), u, v);
    if (p.get_Z() <= 0.0 || u < margin || v < margin || u > w - 1.0 - margin || v > h - 1.0 - margin)
      return false;
  }
  return true;
}

//! Samples every \e step m along the closed polygon \e P (plane coordinates).
std::vector<std::pair<double, double>> boundary(const std::vector<vpPoint> &P, double step)
{
  std::vector<std::pair<double, double>> out;
  for (std::size_t k = 0; k < P.size(); ++k) {
    const vpPoint &a = P[k], &b = P[(k + 1) % P.size()];
    const double dx = b.get_oX() - a.get_oX(), dy = b.get_oY() - a.get_oY();
    const int m = std::max(1, static_cast<int>(std::ceil(std::hypot(dx, dy) / step)));
    for (int i = 0; i < m; ++i)
      out.emplace_back(a.get_oX() + dx * i / m, a.get_oY() + dy * i / m);
  }
  return out;
}

//! Distance from (x, y) to the rectangle (centre, half sides, angle), 0 inside.
double rectangleDistance(double x, double y, double cx, double cy, double hl, double hw, double angle)
{
  const double c = std::cos(angle), s = std::sin(angle);
  const double u = c * (x - cx) + s * (y - cy), v = -s * (x - cx) + c * (y - cy);
  return std::hypot(std::max(0.0, std::fabs(u) - hl), std::max(0.0, std::fabs(v) - hw));
}

//! Image points (px) of the plane points \e P seen from cMo.
std::vector<cv::Point2f> project(const std::vector<vpPoint> &P, const vpHomogeneousMatrix &cMo,
                                 const vpCameraParameters &cam)
{
  std::vector<cv::Point2f> uv;
  for (vpPoint p : P) {
    p.track(cMo);
    double u = 0.0, v = 0.0;
    vpMeterPixelConversion::convertPoint(cam, p.get_x(), p.get_y(), u, v);
    uv.emplace_back(static_cast<float>(u), static_cast<float>(v));
  }
  return uv;
}

//! Area (px^2) of the part of the convex plane polygon \e P (in front of the camera) inside the w x h image at cMo.
double convexAreaInView(const std::vector<vpPoint> &P, const vpHomogeneousMatrix &cMo, const vpCameraParameters &cam,
                        unsigned int w, unsigned int h)
{
  const float W = static_cast<float>(w), H = static_cast<float>(h);
  const std::vector<cv::Point2f> image = {{0.f, 0.f}, {W, 0.f}, {W, H}, {0.f, H}};
  std::vector<cv::Point2f> inside;
  return cv::intersectConvexConvex(project(P, cMo, cam), image, inside, true);
}

bool insidePolygon(const std::vector<vpPoint> &P, double x, double y)
{
  bool in = false;
  for (std::size_t i = 0, j = P.size() - 1; i < P.size(); j = i++) {
    const double xi = P[i].get_oX(), yi = P[i].get_oY(), xj = P[j].get_oX(), yj = P[j].get_oY();
    if ((yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi)
      in = !in;
  }
  return in;
}

//! The scene's geometry for one object image: the tag placed in the taught view, or why it cannot be set up.
struct Staging
{
  std::string setup;
  double tagSize = 0, tagX = 0, tagY = 0;
  std::unique_ptr<vpMorphPlanarScene> scene;
};
} // namespace

vpMorphPlanarScene vpMorphBenchScenario::scene() const
{
  vpMorphPlanarScene scene(objectImage, 0.15, 0, tagSize);
  if (objectImage != templateImage) {
    if (truth == vpMorphBenchObjectSet::TRUTH_ARTICULATED && !jointFile.empty()) {
      // Laid by either part on the template's, undoing the turn its drawing gave that part.
      const vpMorphBenchJoint joint = vpMorphBenchJoint::read(jointFile);
      scene.setReferenceImage(templateImage, vpMorphPlanarScene::SHARED_FRAME);
      const double pu = joint.joint.pivot().get_u(), pv = joint.joint.pivot().get_v();
      const vpMorphRigidTransform part0(-vpMath::rad(joint.deformedTurnDeg[0]), 0.0, 0.0, 1.0, pu, pv);
      const vpMorphRigidTransform part1(-vpMath::rad(joint.deformedTurnDeg[1]), 0.0, 0.0, 1.0, pu, pv);
      scene.setReferenceAlignment(part0, {part1});
    } else if (truth == vpMorphBenchObjectSet::TRUTH_PART) {
      scene.setReferenceImage(templateImage, vpMorphPlanarScene::SHARED_FRAME);
    } else {
      scene.setReferenceImage(templateImage, vpMorphPlanarScene::BEST_OVERLAP);
    }
  }
  scene.setCamera(camera, width, height);
  if (!tagAuto)
    scene.setTagPlacement(tagX, tagY);
  scene.setFaults(faults);
  return scene;
}

vpHomogeneousMatrix vpMorphBenchScenario::overlapPlacement() const
{
  if (objectImage == templateImage || truth != vpMorphBenchObjectSet::TRUTH_PART)
    return vpHomogeneousMatrix();
  vpMorphPlanarScene overlap(objectImage);
  overlap.setReferenceImage(templateImage, vpMorphPlanarScene::BEST_OVERLAP);
  vpMorphPlanarScene shared(objectImage);
  shared.setReferenceImage(templateImage, vpMorphPlanarScene::SHARED_FRAME);
  return shared.placementOf(overlap.referenceAlignment());
}

vpCameraParameters vpMorphBenchScenario::estimatedCamera(const vpCameraParameters &trueCam) const
{
  return vpCameraParameters(trueCam.get_px() * focalScaleX, trueCam.get_py() * focalScaleY,
                            trueCam.get_u0() + principalShiftU, trueCam.get_v0() + principalShiftV);
}

std::string vpMorphBenchScenario::describe() const
{
  std::ostringstream os;
  os.precision(4);
  os << set << "#" << index << " " << object;
  if (!setup.empty())
    return os.str() + ": not set up (" + setup + ")";
  os << " rot " << startRotationDeg << " deg, trans " << startTranslationMm << " mm";
  if (startTiltDeg != 0 || startDepthChange != 0)
    os << ", tilt " << startTiltDeg << " deg, depth " << 100 * startDepthChange << " %";
  if (faults.noiseSigma > 0)
    os << ", noise " << faults.noiseSigma;
  if (faults.gain != 1 || faults.offset != 0)
    os << ", gain " << faults.gain << " offset " << faults.offset;
  if (faults.gradient > 0)
    os << ", gradient " << faults.gradient;
  if (faults.planeEdge)
    os << ", plane edge";
  if (faults.largeDistractorArea > 0)
    os << ", distractor " << 1e4 * faults.largeDistractorArea << " cm2";
  if (faults.occludedShare > 0)
    os << ", occluded " << 100 * faults.occludedShare << " %";
  if (focalScaleX != 1 || focalScaleY != 1)
    os << ", focal x" << focalScaleX << "/x" << focalScaleY;
  if (width != 640)
    os << ", " << width << "x" << height;
  if (!tagAuto && tagSize != kTagSizes.front())
    os << ", tag " << 100 * tagSize << " cm";
  for (const vpMorphBenchEvent &e : events)
    os << ", " << e.describe();
  return os.str();
}

std::vector<std::string> vpMorphBenchScenario::setNames()
{
  // New sets go at the end: a set's place seeds its starts (generate()).
  return {"planar",     "planar-hard",      "6dof",       "calib",     "noise",        "occlusion", "deformable",
          "faults",     "calib-no-tilt",    "calib-wide", "saturated", "low-contrast", "rough",     "gradient",
          "plane-edge", "large-distractor", "res-1280",   "res-320"};
}

std::string vpMorphBenchScenario::startSet(const std::string &set)
{
  if (set == "calib-no-tilt")
    return "calib";
  if (isLook(set) || isResolution(set))
    return "planar";
  return set;
}

bool vpMorphBenchScenario::needsTilt(const std::string &set) { return set == "6dof" || set == "calib"; }

std::vector<std::string> vpMorphBenchScenario::objectNames()
{
  return {"pliers", "wedge", "key", "hammer", "screwdriver", "wrench"};
}

vpHomogeneousMatrix vpMorphBenchScenario::desiredPose(unsigned int seed, const std::string &object)
{
  std::seed_seq seq{seed, 0x44455349u /* "DESI" */, vpMorphBenchHash::low(object), vpMorphBenchHash::high(object)};
  std::vector<unsigned int> w(1);
  seq.generate(w.begin(), w.end());
  std::mt19937 rng(w[0]);
  auto uni = [&rng](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };
  const double theta = uni(-M_PI, M_PI), r = kMaxDesiredOffset * std::sqrt(uni(0, 1)), a = uni(-M_PI, M_PI);
  return vpHomogeneousMatrix(r * std::cos(a), r * std::sin(a), kDesiredDepth, 0, 0, theta);
}

double vpMorphBenchScenario::viewMargin(unsigned int width) { return kViewMargin * width / 640.0; }

std::string vpMorphBenchScenario::stage(vpMorphPlanarScene &scene, const vpHomogeneousMatrix &cdMo)
{
  const double margin = viewMargin(scene.imageWidth());
  if (!scene.objectInView(cdMo, margin))
    return "object-not-in-view-at-goal";
  if (!scene.placeTagInView(cdMo, kTagSizes, margin))
    return "tag-fits-nowhere";
  return std::string();
}

vpHomogeneousMatrix vpMorphBenchScenario::desiredPose(unsigned int seed, const vpMorphBenchObjectSet::Object &object)
{
  return object.fixedPose ? object.desiredPose : desiredPose(seed, object.name);
}

void vpMorphBenchScenario::cameraOf(const std::string &set, vpCameraParameters &cam, unsigned int &width,
                                    unsigned int &height)
{
  if (set == "res-1280") {
    cam = vpCameraParameters(1600.0, 1600.0, 640.0, 480.0);
    width = 1280;
    height = 960;
  } else if (set == "res-320") {
    cam = vpCameraParameters(400.0, 400.0, 160.0, 120.0);
    width = 320;
    height = 240;
  } else {
    cam = vpMorphPlanarScene::defaultCamera();
    width = 640;
    height = 480;
  }
}

std::vector<vpMorphBenchScenario> vpMorphBenchScenario::generate(const std::string &set, unsigned int count,
                                                                 unsigned int seed,
                                                                 const vpMorphBenchObjectSet &objects)
{
  const std::vector<std::string> sets = setNames();
  if (std::find(sets.begin(), sets.end(), set) == sets.end()) {
    std::string known;
    for (const std::string &s : sets)
      known += (known.empty() ? "" : ", ") + s;
    throw vpMorphException(vpMorphException::badParameterError,
                           "vpMorphBenchScenario::generate: unknown set '" + set + "' (" + known + ")");
  }
  if (count == 0)
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphBenchScenario::generate: count must be > 0");
  if (objects.empty())
    throw vpMorphException(vpMorphException::badParameterError, "vpMorphBenchScenario::generate: no object");

  vpCameraParameters cam;
  unsigned int width = 0, height = 0;
  cameraOf(set, cam, width, height);
  const double margin = viewMargin(width);

  // One staging per object image: the scene's geometry at the desired pose, the tag placed in the taught view.
  std::map<std::string, Staging> stagings;
  auto stage = [&](const vpMorphBenchScenario &sc) -> const Staging & {
    Staging &st = stagings[sc.objectImage + "|" + sc.templateImage];
    if (st.scene || !st.setup.empty())
      return st;
    vpMorphBenchScenario plain; // the geometry only: faults do not move the object or the tag
    plain.objectImage = sc.objectImage;
    plain.templateImage = sc.templateImage;
    plain.truth = sc.truth;
    plain.jointFile = sc.jointFile;
    plain.camera = sc.camera;
    plain.width = sc.width;
    plain.height = sc.height;
    std::unique_ptr<vpMorphPlanarScene> scene(new vpMorphPlanarScene(plain.scene()));
    st.setup = vpMorphBenchScenario::stage(*scene, sc.cdMo);
    if (st.setup.empty()) {
      st.tagSize = scene->tagSize();
      st.tagX = scene->tagX();
      st.tagY = scene->tagY();
      st.scene = std::move(scene);
    }
    return st;
  };

  const unsigned int startIndex = setIndex(startSet(set)), ownIndex = setIndex(set);
  const std::vector<vpMorphBenchObjectSet::Object> &objs = objects.objects();
  const unsigned int n = static_cast<unsigned int>(objs.size());
  std::vector<vpMorphBenchScenario> out;
  for (unsigned int i = 0; i < count; ++i) {
    const vpMorphBenchObjectSet::Object &o = objs[i % n];
    const unsigned int k = i / n;
    const unsigned int lo = vpMorphBenchHash::low(o.name), hi = vpMorphBenchHash::high(o.name);
    vpMorphBenchScenario sc;
    sc.set = set;
    sc.index = i;
    sc.setSeed = seed;
    sc.object = o.name;
    // Scenario seed: a function of (set seed, the set whose starts it draws, object, start) only.
    std::seed_seq seq{seed, startIndex, lo, hi, k};
    std::vector<unsigned int> words(1);
    seq.generate(words.begin(), words.end());
    sc.seed = words[0];
    std::mt19937 rng(sc.seed);
    auto uni = [&rng](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };

    sc.templateImage = o.image;
    sc.objectImage = o.image;
    if (set == "deformable") {
      sc.objectImage = o.deformedImage;
      sc.truth = o.truth;
      if (o.truth == vpMorphBenchObjectSet::TRUTH_ARTICULATED)
        sc.jointFile = o.jointFile;
    }
    sc.camera = cam;
    sc.width = width;
    sc.height = height;
    sc.cdMo = desiredPose(seed, o);
    sc.faults.seed = sc.seed;

    // Faults and calibration errors first (they do not depend on the start).
    if (set == "calib" || set == "calib-no-tilt") {
      // The hand-eye error is drawn within the tolerance the calibration states (and the controllers are told).
      const double rotationDeg = 10.0;
      sc.eMcRotationTolerance = vpMath::rad(rotationDeg);
      sc.eMcTranslationTolerance = 0.02;
      sc.focalScaleX = uni(0.8, 1.2);
      sc.focalScaleY = uni(0.8, 1.2);
      sc.principalShiftU = uni(-16, 16);
      sc.principalShiftV = uni(-16, 16);
      const double dt = uni(0, sc.eMcTranslationTolerance), dr = vpMath::rad(uni(0, rotationDeg));
      const double az = uni(-M_PI, M_PI), el = std::asin(uni(-1, 1));
      const double az2 = uni(-M_PI, M_PI), el2 = std::asin(uni(-1, 1));
      const vpTranslationVector t(dt * std::cos(el) * std::cos(az), dt * std::cos(el) * std::sin(az),
                                  dt * std::sin(el));
      const double tilt = set == "calib-no-tilt" ? 0.0 : 1.0; // the rotation about the optical axis only
      const vpThetaUVector tu(tilt * dr * std::cos(el2) * std::cos(az2), tilt * dr * std::cos(el2) * std::sin(az2),
                              dr * std::sin(el2));
      sc.eMcError = vpHomogeneousMatrix(t, tu);
    } else if (set == "calib-wide") {
      const double rotationDeg = 90.0; // about the optical axis, either way
      sc.eMcRotationTolerance = vpMath::rad(rotationDeg);
      sc.eMcTranslationTolerance = 0.05;
      const double f = uni(0.7, 1.3); // px and py together
      sc.focalScaleX = sc.focalScaleY = f;
      sc.principalShiftU = uni(-10, 10);
      sc.principalShiftV = uni(-10, 10);
      const double dt = uni(0, sc.eMcTranslationTolerance), az = uni(-M_PI, M_PI), el = std::asin(uni(-1, 1));
      const vpTranslationVector t(dt * std::cos(el) * std::cos(az), dt * std::cos(el) * std::sin(az),
                                  dt * std::sin(el));
      sc.eMcError = vpHomogeneousMatrix(t, vpThetaUVector(0, 0, vpMath::rad(uni(-rotationDeg, rotationDeg))));
    } else if (set == "noise") {
      sc.faults.noiseSigma = uni(1, 6);
      sc.faults.blurSigma = uni(0, 1.5);
      sc.faults.gain = uni(0.7, 1.3);
      sc.faults.offset = uni(-25, 25);
    } else if (set == "occlusion") {
      sc.faults.occludedShare = uni(0.05, 0.20);
      sc.faults.occluderPosition = uni(0, 1);
    } else if (set == "faults") {
      vpMorphBenchEvent e;
      e.kind = static_cast<vpMorphBenchEvent::Kind>((k + lo) % 5);
      e.iteration = static_cast<unsigned int>(std::floor(uni(15, 41)));
      switch (e.kind) {
      case vpMorphBenchEvent::DROPPED_FRAMES:
        e.frames = static_cast<unsigned int>(std::floor(uni(3, 9)));
        break;
      case vpMorphBenchEvent::NO_OBJECT:
        e.frames = static_cast<unsigned int>(std::floor(uni(2, 7)));
        break;
      case vpMorphBenchEvent::SUDDEN_OCCLUDER:
        e.occludedShare = uni(0.10, 0.25);
        e.occluderPosition = uni(0, 1);
        break;
      case vpMorphBenchEvent::POSE_JUMP: {
        const double a = uni(-M_PI, M_PI), r = (uni(0, 1) < 0.5 ? -1 : 1) * vpMath::rad(10);
        e.cMcp = vpHomogeneousMatrix(0.02 * std::cos(a), 0.02 * std::sin(a), 0, 0, 0, r);
        break;
      }
      case vpMorphBenchEvent::WRONG_TEMPLATE: {
        e.iteration = 0;
        std::vector<std::string> others;
        for (const vpMorphBenchObjectSet::Object &other : objs)
          if (other.name != sc.object)
            others.push_back(other.name);
        const double u = uni(0, 1);
        if (others.empty()) { // one object: nothing else to take it for
          e.kind = vpMorphBenchEvent::DROPPED_FRAMES;
          e.iteration = 15;
        } else
          e.wrongTemplate = others[std::min<std::size_t>(others.size() - 1, std::size_t(u * others.size()))];
        break;
      }
      }
      sc.events.push_back(e);
    }

    const Staging &st = stage(sc);
    if (!st.setup.empty()) {
      sc.setup = st.setup;
      out.push_back(sc);
      continue;
    }
    sc.tagAuto = false;
    sc.tagSize = st.tagSize;
    sc.tagX = st.tagX;
    sc.tagY = st.tagY;
    const vpMorphPlanarScene &scene = *st.scene;
    bool ok = false;
    for (int attempt = 0; attempt < 1000 && !ok; ++attempt) {
      double rot = set == "planar-hard" ? (uni(0, 1) < 0.5 ? -1 : 1) * uni(150, 180) : uni(-180, 180);
      const double r = kMaxTranslation * uni(0, 1), a = uni(-M_PI, M_PI);
      double tilt = 0, phi = 0, depth = 0;
      if (set == "6dof") {
        tilt = uni(0, 30);
        phi = uni(-M_PI, M_PI);
        depth = uni(-0.4, 0.4);
      }
      const vpHomogeneousMatrix cdMc = startPose(rot, r * std::cos(a), r * std::sin(a), tilt, phi, depth);
      const vpHomogeneousMatrix cMo = cdMc.inverse() * sc.cdMo;
      if (scene.objectInView(cMo, margin) && scene.tagInView(cMo, margin)) {
        ok = true;
        sc.cdMc = cdMc;
        sc.startRotationDeg = rot;
        sc.startTranslationMm = 1000 * r;
        sc.startTiltDeg = tilt;
        sc.startDepthChange = depth;
      }
    }
    if (!ok) {
      sc.setup = "no-start-in-view";
      out.push_back(sc);
      continue;
    }

    // The scene looks: their own stream, so that they share the planar set's starts.
    std::seed_seq lookSeq{seed, ownIndex, lo, hi, k, 0x4c4f4f4bu /* "LOOK" */};
    lookSeq.generate(words.begin(), words.end());
    std::mt19937 look(words[0]);
    auto draw = [&look](double a, double b) { return std::uniform_real_distribution<double>(a, b)(look); };
    const vpHomogeneousMatrix cMo = sc.cdMc.inverse() * sc.cdMo;
    if (set == "saturated") {
      sc.faults.gain = draw(1.3, 1.8);
      sc.faults.offset = 255.0 + draw(10, 60) - 210.0 * sc.faults.gain; // the plane (210) clipped
    } else if (set == "low-contrast") {
      const double contrast = draw(15, 40), mean = draw(60, 190);
      sc.faults.gain = contrast / 170.0; // object 40, plane 210
      sc.faults.offset = mean - 125.0 * sc.faults.gain;
      sc.faults.noiseSigma = draw(0.5, 1.5);
    } else if (set == "gradient") {
      sc.faults.gradient = draw(0.3, 0.6);
      sc.faults.gradientAngle = draw(-M_PI, M_PI);
    } else if (set == "rough") {
      sc.objectImage = sc.templateImage = o.roughImage;
      sc.variant = "rough";
    } else if (set == "plane-edge") {
      std::vector<vpPoint> keep = scene.objectContour3D();
      for (const vpPoint &p : scene.tagTextureCorners3D())
        keep.push_back(p);
      bool found = false;
      for (int attempt = 0; attempt < 100 && !found; ++attempt) {
        const double psi = draw(-M_PI, M_PI), gap = draw(kClearance, 3 * kClearance);
        const double nx = std::cos(psi), ny = std::sin(psi);
        double extent = -1e9;
        for (const vpPoint &p : keep)
          extent = std::max(extent, p.get_oX() * nx + p.get_oY() * ny);
        const double ex = (extent + gap) * nx, ey = (extent + gap) * ny;
        for (double t = -0.4; t <= 0.4 && !found; t += 0.005) {
          vpPoint p;
          p.setWorldCoordinates(ex - t * ny, ey + t * nx, 0.0);
          found = inView({p}, cMo, cam, width, height, margin);
        }
        if (found) {
          sc.faults.planeEdge = true;
          sc.faults.planeEdgeX = ex;
          sc.faults.planeEdgeY = ey;
          sc.faults.planeEdgeAngle = psi;
        }
      }
      if (!found)
        sc.setup = "plane-edge-not-in-view";
    } else if (set == "large-distractor") {
      // Its part in view is larger than the object in view; the rectangle may run past the image's border, as a
      // tray or a table's edge does, so that a compact object leaves room for it: its centre is drawn over the image
      // widened by half its size on every side.
      const std::vector<vpPoint> outline = scene.objectContour3D(), tag = scene.tagTextureCorners3D();
      const auto outlineSamples = boundary(outline, 0.002), tagSamples = boundary(tag, 0.002);
      const double objectPx = cv::contourArea(project(outline, cMo, cam)); // wholly in view
      const double maxArea = vpMorphPlanarScene::maxDistractorArea();
      bool found = false;
      for (int attempt = 0; attempt < 3000 && !found; ++attempt) { // the search's budget, not a tolerance
        const double share = draw(1.2, 1.6), aspect = draw(1.0, 2.0), angle = draw(-M_PI, M_PI);
        double cx = 0, cy = 0;
        const double u = draw(-0.5 * width, 1.5 * width), v = draw(-0.5 * height, 1.5 * height);
        if (!vpMorphBenchPlane::onPlane(cMo, cam, u, v, cx, cy))
          continue;
        auto halfSides = [aspect](double area) { // of the rectangle of \e area at the drawn aspect
          const double hl = 0.5 * std::sqrt(area * aspect);
          return std::make_pair(hl, 0.5 * area / (2 * hl));
        };
        auto corners = [&](double area) {
          const auto [hl, hw] = halfSides(area);
          const double c = std::cos(angle), s = std::sin(angle);
          const double du[4] = {-hl, hl, hl, -hl}, dv[4] = {-hw, -hw, hw, hw};
          std::vector<vpPoint> P(4);
          for (int q = 0; q < 4; ++q)
            P[q].setWorldCoordinates(cx + c * du[q] - s * dv[q], cy + s * du[q] + c * dv[q], 0.0);
          return P;
        };
        // The rectangles about one centre are nested, so the area in view grows with the area: bisect it.
        const double targetPx = share * objectPx;
        if (convexAreaInView(corners(maxArea), cMo, cam, width, height) < targetPx)
          continue;
        double lo = 0.0, hi = maxArea;
        for (int it = 0; it < 50; ++it) { // to about the double's precision
          const double mid = 0.5 * (lo + hi);
          (convexAreaInView(corners(mid), cMo, cam, width, height) < targetPx ? lo : hi) = mid;
        }
        const double area = hi;
        const auto [hl, hw] = halfSides(area);
        bool clear = true;
        for (const auto &p : outlineSamples)
          clear = clear && rectangleDistance(p.first, p.second, cx, cy, hl, hw, angle) > kClearance;
        for (const auto &p : tagSamples)
          clear = clear && rectangleDistance(p.first, p.second, cx, cy, hl, hw, angle) > kClearance;
        for (const auto &p : boundary(corners(area), 0.002))
          clear = clear && !insidePolygon(outline, p.first, p.second) && !insidePolygon(tag, p.first, p.second);
        if (clear) {
          found = true;
          sc.faults.largeDistractorArea = area;
          sc.faults.largeDistractorAspect = aspect;
          sc.faults.largeDistractorX = cx;
          sc.faults.largeDistractorY = cy;
          sc.faults.largeDistractorAngle = angle;
        }
      }
      if (!found)
        sc.setup = "no-room-for-distractor";
    }
    out.push_back(sc);
  }
  return out;
}
