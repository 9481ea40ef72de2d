/*
  The fixture of morph_bench's tests: the six tools at the taught poses they had during development and the starts
  the tests pin (test/data/development-starts.json, every field to the bit: the servo was shaped on all of them, none
  is held out), benches on them, and starts made by hand.
*/
#ifndef TEST_MORPH_BENCH_FIXTURE_H
#define TEST_MORPH_BENCH_FIXTURE_H

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include <visp3/core/vpMath.h>
#include <visp3/morph_bench/vpMorphBench.h>

namespace fixture
{
inline const std::string &data()
{
  static const std::string d = VISPMORPH_DATA_DIR;
  return d;
}

inline const nlohmann::json &file()
{
  static const nlohmann::json j = [] {
    std::ifstream f(std::filesystem::path(__FILE__).parent_path() / "data" / "development-starts.json");
    return nlohmann::json::parse(f);
  }();
  return j;
}

//! The six tools at their development taught poses (derived images under the test's working folder).
inline const vpMorphBenchObjectSet &tools()
{
  static const vpMorphBenchObjectSet t = [] {
    vpMorphBenchObjectSet s = vpMorphBenchObjectSet::tools(data(), "bench-fixture");
    for (const auto &p : file().at("desired_poses").items()) {
      vpHomogeneousMatrix M;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 4; ++j)
          M[i][j] = p.value().at(4 * i + j).get<double>();
      s.setDesiredPose(p.key(), M);
    }
    return s;
  }();
  return t;
}

//! The desired pose of one of the six tools.
inline vpHomogeneousMatrix desiredPose(const std::string &object) { return tools()[object].desiredPose; }

//! A pinned start, by its key in the file ("set/object/rotation in deg").
inline vpMorphBenchScenario start(const std::string &key)
{
  return vpMorphBenchScenario::fromJson(file().at("starts").at(key).dump(), data());
}

//! A bench on the six tools with \e settings (its databases are taught on first use).
inline std::unique_ptr<vpMorphBench> makeBench(const vpMorphBench::Settings &settings = vpMorphBench::Settings())
{
  return std::unique_ptr<vpMorphBench>(new vpMorphBench(tools(), 100, settings));
}

//! The bench with the default settings on \e robot, built once per test process.
inline const vpMorphBench &bench(vpMorphSimRobot::Kind robot = vpMorphSimRobot::FREE_CAMERA)
{
  static std::map<vpMorphSimRobot::Kind, std::unique_ptr<vpMorphBench>> benches;
  std::unique_ptr<vpMorphBench> &b = benches[robot];
  if (!b) {
    vpMorphBench::Settings st;
    st.robot = robot;
    b = makeBench(st);
  }
  return *b;
}

//! A planar start made by hand: \e object turned by rotDeg and moved by (tx, ty) m from its desired pose.
inline vpMorphBenchScenario planarStart(const std::string &object, double rotDeg, double tx, double ty)
{
  vpMorphBenchScenario s;
  s.set = "planar";
  s.object = object;
  s.objectImage = s.templateImage = tools()[object].image;
  s.cdMo = desiredPose(object);
  s.cdMc = vpHomogeneousMatrix(tx, ty, 0, 0, 0, vpMath::rad(rotDeg));
  s.startRotationDeg = rotDeg;
  s.startTranslationMm = 1000 * std::hypot(tx, ty);
  return s;
}
} // namespace fixture

#endif
