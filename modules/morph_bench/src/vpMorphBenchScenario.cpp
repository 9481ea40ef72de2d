#include <visp3/morph_bench/vpMorphBenchScenario.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <sstream>

#include <visp3/core/vpMath.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphRigidTransform.h>

#include "vpMorphBenchJoint.h"

namespace
{
const double kDesiredDepth = 0.5;    // m, the protocol's desired distance to the plane
const double kMaxTranslation = 0.08; // m, planar start offset
const double kViewMargin = 10.0;     // px, object and tag fully in view at the start

struct ObjectPose
{
  const char *name;
  double tx, ty, thetaDeg; // desired in-plane offset (m) and rotation (deg) of the object in the camera frame
};
// Each taught view differs: offsets of a few centimetres and rotations spread over the circle.
const ObjectPose kObjects[] = {{"pliers", 0.010, 0.000, 20},         {"wedge", -0.010, 0.005, -30},
                               {"key", 0.000, -0.010, 45},           {"hammer", 0.015, 0.010, 90},
                               {"screwdriver", -0.015, -0.005, -60}, {"wrench", 0.005, 0.015, 150}};

bool fileExists(const std::string &path) { return std::ifstream(path).good(); }

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
} // namespace

vpMorphPlanarScene vpMorphBenchScenario::scene() const
{
  vpMorphPlanarScene scene(objectImage);
  if (objectImage != templateImage && !jointFile.empty()) {
    // An articulated object: laid by either part on the template's, undoing the turn its drawing gave that part.
    const vpMorphBenchJoint joint = vpMorphBenchJoint::read(jointFile);
    scene.setReferenceImage(templateImage, vpMorphPlanarScene::SHARED_FRAME);
    const double pu = joint.joint.pivot().get_u(), pv = joint.joint.pivot().get_v();
    const vpMorphRigidTransform part0(-vpMath::rad(joint.deformedTurnDeg[0]), 0.0, 0.0, 1.0, pu, pv);
    const vpMorphRigidTransform part1(-vpMath::rad(joint.deformedTurnDeg[1]), 0.0, 0.0, 1.0, pu, pv);
    scene.setReferenceAlignment(part0, {part1});
  } else if (objectImage != templateImage)
    scene.setReferenceImage(templateImage, vpMorphPlanarScene::BEST_OVERLAP);
  scene.setFaults(faults);
  return scene;
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
  os << set << "#" << index << " " << object << " rot " << startRotationDeg << " deg, trans " << startTranslationMm
     << " mm";
  if (startTiltDeg != 0 || startDepthChange != 0)
    os << ", tilt " << startTiltDeg << " deg, depth " << 100 * startDepthChange << " %";
  if (faults.noiseSigma > 0)
    os << ", noise " << faults.noiseSigma;
  if (faults.occludedShare > 0)
    os << ", occluded " << 100 * faults.occludedShare << " %";
  if (focalScaleX != 1 || focalScaleY != 1)
    os << ", focal x" << focalScaleX << "/x" << focalScaleY;
  for (const vpMorphBenchEvent &e : events)
    os << ", " << e.describe();
  return os.str();
}

std::vector<std::string> vpMorphBenchScenario::setNames()
{
  // New sets go at the end: a set's place seeds its starts (generate()).
  return {"planar", "planar-hard", "6dof", "calib", "noise", "occlusion", "deformable", "faults", "calib-no-tilt"};
}

std::vector<std::string> vpMorphBenchScenario::objectNames()
{
  std::vector<std::string> names;
  for (const ObjectPose &o : kObjects)
    names.push_back(o.name);
  return names;
}

vpHomogeneousMatrix vpMorphBenchScenario::desiredPose(const std::string &object)
{
  for (const ObjectPose &o : kObjects)
    if (object == o.name)
      return vpHomogeneousMatrix(o.tx, o.ty, kDesiredDepth, 0, 0, vpMath::rad(o.thetaDeg));
  throw vpMorphException(vpMorphException::notFoundError, "vpMorphBenchScenario: unknown object '" + object + "'");
}

std::vector<vpMorphBenchScenario> vpMorphBenchScenario::generate(const std::string &set, unsigned int count,
                                                                 unsigned int seed, const std::string &dataDir)
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

  // One scene per object (and per deformed variant), only to check that a start shows object and tag.
  std::map<std::string, std::unique_ptr<vpMorphPlanarScene>> scenes;
  auto sceneOf = [&](const vpMorphBenchScenario &sc) -> const vpMorphPlanarScene & {
    auto &s = scenes[sc.objectImage];
    if (!s) {
      for (const std::string &image : {sc.objectImage, sc.templateImage})
        if (!fileExists(image))
          throw vpMorphException(vpMorphException::notFoundError,
                                 "vpMorphBenchScenario::generate: missing object image " + image);
      vpMorphBenchScenario plain; // the geometry only: faults do not move the object or the tag
      plain.objectImage = sc.objectImage;
      plain.templateImage = sc.templateImage;
      plain.jointFile = sc.jointFile;
      s.reset(new vpMorphPlanarScene(plain.scene()));
    }
    return *s;
  };

  // calib-no-tilt draws calib's starts and errors (the same seeds), then drops the hand-eye tilt.
  const bool calib = set == "calib" || set == "calib-no-tilt";
  const std::string seedSet = calib ? "calib" : set;
  const unsigned int setIndex = static_cast<unsigned int>(std::find(sets.begin(), sets.end(), seedSet) - sets.begin());
  const std::vector<std::string> objects = objectNames();
  std::vector<vpMorphBenchScenario> out;
  for (unsigned int i = 0; i < count; ++i) {
    vpMorphBenchScenario sc;
    sc.set = set;
    sc.index = i;
    // Scenario seed: a function of (set seed, set, index) only, so that a scenario is replayed alone.
    std::seed_seq seq{seed, setIndex, i};
    std::vector<unsigned int> words(1);
    seq.generate(words.begin(), words.end());
    sc.seed = words[0];
    std::mt19937 rng(sc.seed);
    auto uni = [&rng](double a, double b) { return std::uniform_real_distribution<double>(a, b)(rng); };

    // faults: the kinds in turn (index % 5), the objects in turn per round of kinds, so every kind meets them all.
    sc.object = objects[(set == "faults" ? i / 5 + i % 5 : i) % objects.size()];
    sc.templateImage = dataDir + "/objects/" + sc.object + ".png";
    sc.objectImage = set == "deformable" ? dataDir + "/objects/" + sc.object + "-deformed.png" : sc.templateImage;
    sc.jointFile = vpMorphBenchJoint::file(dataDir, sc.object);
    sc.cdMo = desiredPose(sc.object);
    sc.faults.seed = sc.seed;

    // Faults and calibration errors first (they do not depend on the start).
    if (calib) {
      sc.focalScaleX = uni(0.8, 1.2);
      sc.focalScaleY = uni(0.8, 1.2);
      sc.principalShiftU = uni(-16, 16);
      sc.principalShiftV = uni(-16, 16);
      const double dt = uni(0, 0.02), dr = vpMath::rad(uni(0, 10));
      const double az = uni(-M_PI, M_PI), el = std::asin(uni(-1, 1));
      const double az2 = uni(-M_PI, M_PI), el2 = std::asin(uni(-1, 1));
      const vpTranslationVector t(dt * std::cos(el) * std::cos(az), dt * std::cos(el) * std::sin(az),
                                  dt * std::sin(el));
      const double tilt = set == "calib-no-tilt" ? 0.0 : 1.0; // the rotation about the optical axis only
      const vpThetaUVector tu(tilt * dr * std::cos(el2) * std::cos(az2), tilt * dr * std::cos(el2) * std::sin(az2),
                              dr * std::sin(el2));
      sc.eMcError = vpHomogeneousMatrix(t, tu);
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
      e.kind = static_cast<vpMorphBenchEvent::Kind>(i % 5);
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
        for (const std::string &o : objects)
          if (o != sc.object)
            others.push_back(o);
        e.wrongTemplate = others[std::min<std::size_t>(others.size() - 1, std::size_t(uni(0, 1) * others.size()))];
        break;
      }
      }
      sc.events.push_back(e);
    }

    const vpMorphPlanarScene &scene = sceneOf(sc);
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
      if (scene.objectInView(cMo, kViewMargin) && scene.tagInView(cMo, kViewMargin)) {
        ok = true;
        sc.cdMc = cdMc;
        sc.startRotationDeg = rot;
        sc.startTranslationMm = 1000 * r;
        sc.startTiltDeg = tilt;
        sc.startDepthChange = depth;
      }
    }
    if (!ok)
      throw vpMorphException(vpMorphException::badParameterError,
                             "vpMorphBenchScenario::generate: no start with object and tag in view for " + sc.object);
    out.push_back(sc);
  }
  return out;
}
