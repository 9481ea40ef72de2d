// vpMorphBenchScenario to and from JSON: every field, numbers to the bit (nlohmann writes doubles with 17 digits).
#include <visp3/morph_bench/vpMorphBenchScenario.h>

#include <nlohmann/json.hpp>

#include <visp3/morph/vpMorphException.h>

namespace
{
using json = nlohmann::json;

json matrix(const vpHomogeneousMatrix &M)
{
  json a = json::array();
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 4; ++j)
      a.push_back(M[i][j]);
  return a;
}

vpHomogeneousMatrix matrix(const json &a)
{
  if (!a.is_array() || a.size() != 12)
    throw vpMorphException(vpMorphException::ioError, "vpMorphBenchScenario::fromJson: a pose needs 12 numbers");
  vpHomogeneousMatrix M;
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 4; ++j)
      M[i][j] = a[4 * i + j].get<double>();
  return M;
}

std::string relative(const std::string &path, const std::string &base)
{
  if (base.empty() || path.compare(0, base.size() + 1, base + "/") != 0)
    return path;
  return path.substr(base.size() + 1);
}

std::string absolute(const std::string &path, const std::string &base)
{
  if (base.empty() || path.empty() || path[0] == '/')
    return path;
  return base + "/" + path;
}

json toObject(const vpMorphBenchScenario &s, const std::string &base)
{
  const vpMorphPlanarScene::Faults &f = s.faults;
  json j;
  j["set"] = s.set;
  j["index"] = s.index;
  j["seed"] = s.seed;
  j["set_seed"] = s.setSeed;
  j["object"] = s.object;
  j["object_image"] = relative(s.objectImage, base);
  j["template_image"] = relative(s.templateImage, base);
  j["variant"] = s.variant;
  j["joint_file"] = relative(s.jointFile, base);
  j["truth"] = static_cast<int>(s.truth);
  j["setup"] = s.setup;
  j["cdMo"] = matrix(s.cdMo);
  j["cdMc"] = matrix(s.cdMc);
  j["start"] = {s.startRotationDeg, s.startTranslationMm, s.startTiltDeg, s.startDepthChange};
  j["faults"] = {{"noise", f.noiseSigma},
                 {"blur", f.blurSigma},
                 {"gain", f.gain},
                 {"offset", f.offset},
                 {"occluded_share", f.occludedShare},
                 {"occluder_position", f.occluderPosition},
                 {"distractors", f.distractors},
                 {"seed", f.seed},
                 {"object_hidden", f.objectHidden},
                 {"gradient", {f.gradient, f.gradientAngle}},
                 {"plane_edge", {f.planeEdge ? 1.0 : 0.0, f.planeEdgeX, f.planeEdgeY, f.planeEdgeAngle}},
                 {"large_distractor",
                  {f.largeDistractorArea, f.largeDistractorAspect, f.largeDistractorX, f.largeDistractorY,
                   f.largeDistractorAngle}}};
  j["camera"] = {s.camera.get_px(), s.camera.get_py(), s.camera.get_u0(), s.camera.get_v0()};
  j["image"] = {s.width, s.height};
  j["tag"] = {{"size", s.tagSize}, {"x", s.tagX}, {"y", s.tagY}, {"auto", s.tagAuto}};
  j["calibration"] = {s.focalScaleX, s.focalScaleY, s.principalShiftU, s.principalShiftV};
  j["eMc_error"] = matrix(s.eMcError);
  j["eMc_tolerance"] = {s.eMcRotationTolerance, s.eMcTranslationTolerance};
  j["events"] = json::array();
  for (const vpMorphBenchEvent &e : s.events)
    j["events"].push_back({{"kind", vpMorphBenchEvent::kindName(e.kind)},
                           {"iteration", e.iteration},
                           {"frames", e.frames},
                           {"occluded_share", e.occludedShare},
                           {"occluder_position", e.occluderPosition},
                           {"cMcp", matrix(e.cMcp)},
                           {"wrong_template", e.wrongTemplate}});
  return j;
}

vpMorphBenchScenario fromObject(const json &j, const std::string &base)
{
  vpMorphBenchScenario s;
  s.set = j.at("set").get<std::string>();
  s.index = j.at("index").get<unsigned int>();
  s.seed = j.at("seed").get<unsigned int>();
  s.setSeed = j.at("set_seed").get<unsigned int>();
  s.object = j.at("object").get<std::string>();
  s.objectImage = absolute(j.at("object_image").get<std::string>(), base);
  s.templateImage = absolute(j.at("template_image").get<std::string>(), base);
  s.variant = j.at("variant").get<std::string>();
  s.jointFile = absolute(j.at("joint_file").get<std::string>(), base);
  s.truth = static_cast<vpMorphBenchObjectSet::Truth>(j.at("truth").get<int>());
  s.setup = j.at("setup").get<std::string>();
  s.cdMo = matrix(j.at("cdMo"));
  s.cdMc = matrix(j.at("cdMc"));
  const json &st = j.at("start");
  s.startRotationDeg = st.at(0).get<double>();
  s.startTranslationMm = st.at(1).get<double>();
  s.startTiltDeg = st.at(2).get<double>();
  s.startDepthChange = st.at(3).get<double>();
  const json &f = j.at("faults");
  s.faults.noiseSigma = f.at("noise").get<double>();
  s.faults.blurSigma = f.at("blur").get<double>();
  s.faults.gain = f.at("gain").get<double>();
  s.faults.offset = f.at("offset").get<double>();
  s.faults.occludedShare = f.at("occluded_share").get<double>();
  s.faults.occluderPosition = f.at("occluder_position").get<double>();
  s.faults.distractors = f.at("distractors").get<unsigned int>();
  s.faults.seed = f.at("seed").get<unsigned int>();
  s.faults.objectHidden = f.at("object_hidden").get<bool>();
  s.faults.gradient = f.at("gradient").at(0).get<double>();
  s.faults.gradientAngle = f.at("gradient").at(1).get<double>();
  s.faults.planeEdge = f.at("plane_edge").at(0).get<double>() != 0.0;
  s.faults.planeEdgeX = f.at("plane_edge").at(1).get<double>();
  s.faults.planeEdgeY = f.at("plane_edge").at(2).get<double>();
  s.faults.planeEdgeAngle = f.at("plane_edge").at(3).get<double>();
  const json &d = f.at("large_distractor");
  s.faults.largeDistractorArea = d.at(0).get<double>();
  s.faults.largeDistractorAspect = d.at(1).get<double>();
  s.faults.largeDistractorX = d.at(2).get<double>();
  s.faults.largeDistractorY = d.at(3).get<double>();
  s.faults.largeDistractorAngle = d.at(4).get<double>();
  const json &c = j.at("camera");
  s.camera =
      vpCameraParameters(c.at(0).get<double>(), c.at(1).get<double>(), c.at(2).get<double>(), c.at(3).get<double>());
  s.width = j.at("image").at(0).get<unsigned int>();
  s.height = j.at("image").at(1).get<unsigned int>();
  const json &t = j.at("tag");
  s.tagSize = t.at("size").get<double>();
  s.tagX = t.at("x").get<double>();
  s.tagY = t.at("y").get<double>();
  s.tagAuto = t.at("auto").get<bool>();
  const json &k = j.at("calibration");
  s.focalScaleX = k.at(0).get<double>();
  s.focalScaleY = k.at(1).get<double>();
  s.principalShiftU = k.at(2).get<double>();
  s.principalShiftV = k.at(3).get<double>();
  s.eMcError = matrix(j.at("eMc_error"));
  if (j.contains("eMc_tolerance")) { // a file written before the tolerance was stated: none
    s.eMcRotationTolerance = j.at("eMc_tolerance").at(0).get<double>();
    s.eMcTranslationTolerance = j.at("eMc_tolerance").at(1).get<double>();
    if (!(s.eMcRotationTolerance >= 0.0) || !(s.eMcTranslationTolerance >= 0.0))
      throw vpMorphException(vpMorphException::ioError,
                             "vpMorphBenchScenario: the hand-eye tolerance (eMc_tolerance) must be >= 0");
  }
  for (const json &e : j.at("events")) {
    vpMorphBenchEvent ev;
    ev.kind = vpMorphBenchEvent::kindFromName(e.at("kind").get<std::string>());
    ev.iteration = e.at("iteration").get<unsigned int>();
    ev.frames = e.at("frames").get<unsigned int>();
    ev.occludedShare = e.at("occluded_share").get<double>();
    ev.occluderPosition = e.at("occluder_position").get<double>();
    ev.cMcp = matrix(e.at("cMcp"));
    ev.wrongTemplate = e.at("wrong_template").get<std::string>();
    s.events.push_back(ev);
  }
  return s;
}

json parse(const std::string &text)
{
  try {
    return json::parse(text);
  } catch (const json::exception &e) {
    throw vpMorphException(vpMorphException::ioError, std::string("vpMorphBenchScenario: malformed JSON: ") + e.what());
  }
}
} // namespace

std::string vpMorphBenchScenario::toJson(const std::string &base) const { return toObject(*this, base).dump(); }

vpMorphBenchScenario vpMorphBenchScenario::fromJson(const std::string &text, const std::string &base)
{
  const json j = parse(text);
  try {
    return fromObject(j.is_array() ? j.at(0) : j, base);
  } catch (const json::exception &e) {
    throw vpMorphException(vpMorphException::ioError,
                           std::string("vpMorphBenchScenario: malformed scenario: ") + e.what());
  }
}

std::vector<vpMorphBenchScenario> vpMorphBenchScenario::listFromJson(const std::string &text, const std::string &base)
{
  const json j = parse(text);
  std::vector<vpMorphBenchScenario> out;
  try {
    if (!j.is_array())
      throw vpMorphException(vpMorphException::ioError, "vpMorphBenchScenario: a list of scenarios is a JSON array");
    for (const json &s : j)
      out.push_back(fromObject(s, base));
  } catch (const json::exception &e) {
    throw vpMorphException(vpMorphException::ioError,
                           std::string("vpMorphBenchScenario: malformed scenario: ") + e.what());
  }
  return out;
}
