// Tests of the template database (vpMorphTemplate, vpMorphDatabase): building from a folder, access by index and
// name, JSON save and load round trip, atomic save, and clear errors on malformed, truncated and wrong-version
// files, missing images, duplicate and unknown names.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphException.h>

namespace fs = std::filesystem;

namespace
{
std::string objectsDir() { return std::string(VISPMORPH_DATA_DIR) + "/objects"; }

// A fresh scratch directory under the test's working directory.
fs::path scratch(const std::string &name)
{
  const fs::path p = fs::current_path() / ("db-" + name);
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

std::string readText(const fs::path &p)
{
  std::ifstream f(p);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

void writeText(const fs::path &p, const std::string &s) { std::ofstream(p) << s; }

// The error code and message of what \e f throws.
template <typename F> std::pair<int, std::string> errorOf(F f)
{
  try {
    f();
  } catch (const vpMorphException &e) {
    return {e.getCode(), e.getStringMessage()};
  }
  return {0, ""};
}

vpMorphContour square(double s = 10.0) { return vpMorphContour({0, s, s, 0}, {0, 0, s, s}); }

// One database of the twelve generated images (the six tools and their deformed variants), built once.
const vpMorphDatabase &folderDatabase()
{
  static const vpMorphDatabase db = vpMorphDatabase::fromImages(objectsDir());
  return db;
}
} // namespace

TEST_CASE("database: built from a folder of images in one call", "[database]")
{
  std::size_t calls = 0;
  const vpMorphDatabase db =
      vpMorphDatabase::fromImages(objectsDir(), vpMorphShapeDistance(), [&](std::size_t, std::size_t) { ++calls; });
  REQUIRE(db.size() == 12);
  CHECK(calls >= 2);
  CHECK(db.isCalibrated());
  CHECK(std::isfinite(db.threshold(0)));
  CHECK(db[0].name() == "hammer"); // sorted by file name
  CHECK(db.find("key") != vpMorphRecognition::npos);
  CHECK(db["key"].name() == "key");
  CHECK(db["key"].imagePath() == objectsDir() + "/key.png");
  CHECK(db.find("nothing") == vpMorphRecognition::npos);
  CHECK(db["wrench-deformed"].contour().size() >= 3);
  // Each template recognises itself, at distance 0.
  for (std::size_t k = 0; k < db.size(); ++k) {
    const vpMorphRecognition r = db.recognize(db[k].contour());
    CHECK(r.index == k);
    CHECK(r.distance == Approx(0.0).margin(1e-12));
    CHECK(r.accepted);
  }
}

TEST_CASE("database: JSON round trip keeps every field", "[database]")
{
  vpMorphDatabase db = folderDatabase();
  vpMorphTemplate t("square", square(), "");
  t.setPlanarPose(0.01, -0.02, 0.5, 0.3);
  t.setMetadata("grasp", "centre");
  t.setMetadata("part", "A-12");
  db.add(t);
  db.calibrate();
  db.setMinimumSupport(0.8);
  const fs::path dir = scratch("roundtrip");
  const fs::path file = dir / "db.json";
  db.save(file.string());
  const std::string text = readText(file);
  CHECK(text.find("\"format\": \"vispmorph-template-database\"") != std::string::npos);
  CHECK(text.find("\"version\": 1") != std::string::npos);
  CHECK(text.find("\"image\": \"../") != std::string::npos); // relative to the file's directory
  // No temporary file is left behind.
  std::size_t files = 0;
  for (const auto &e : fs::directory_iterator(dir))
    files += e.is_regular_file();
  CHECK(files == 1);

  const vpMorphDatabase back = vpMorphDatabase::load(file.string());
  REQUIRE(back.size() == db.size());
  for (std::size_t k = 0; k < db.size(); ++k)
    CHECK(back.threshold(k) == db.threshold(k));
  CHECK(back.withinDistances() == db.withinDistances());
  CHECK(back.betweenDistances() == db.betweenDistances());
  CHECK(back.isCalibrated());
  CHECK(back.minimumSupport() == 0.8);
  CHECK(back.distance().name() == db.distance().name());
  for (std::size_t k = 0; k < db.size(); ++k) {
    CHECK(back[k].name() == db[k].name());
    // Saved relative to the file, resolved back on load.
    if (!db[k].imagePath().empty())
      CHECK(fs::equivalent(back[k].imagePath(), db[k].imagePath()));
    CHECK(back[k].contour().xs() == db[k].contour().xs());
    CHECK(back[k].contour().ys() == db[k].contour().ys());
    // The region measured on the template image (templates built from images) travels with the contour.
    REQUIRE(back[k].contour().hasRegion() == db[k].contour().hasRegion());
    if (db[k].contour().hasRegion()) {
      double a20, a11, a02, b20, b11, b02;
      db[k].contour().regionMoments(a20, a11, a02);
      back[k].contour().regionMoments(b20, b11, b02);
      CHECK(back[k].contour().regionArea() == db[k].contour().regionArea());
      CHECK(b20 == a20);
      CHECK(b11 == a11);
      CHECK(b02 == a02);
    }
    // So does the measured edge outline.
    REQUIRE(back[k].contour().hasOutline() == db[k].contour().hasOutline());
    CHECK(back[k].contour().outline().xs() == db[k].contour().outline().xs());
    CHECK(back[k].contour().outline().ys() == db[k].contour().outline().ys());
    CHECK(back[k].metadata() == db[k].metadata());
  }
  CHECK(db["pliers"].contour().hasRegion());
  CHECK(db["pliers"].contour().hasOutline());
  CHECK_FALSE(back["square"].contour().hasRegion());
  const vpMorphTemplate &s = back["square"];
  CHECK(s.metadata("grasp") == "centre");
  CHECK(s.metadata("absent", "none") == "none");
  CHECK(s.cdMo()[2][3] == Approx(0.5));
  CHECK(s.cdMo()[0][3] == Approx(0.01));
  CHECK(std::atan2(s.cdMo()[1][0], s.cdMo()[0][0]) == Approx(0.3));
  // The same recognition after the round trip.
  const vpMorphRecognition a = db.recognize(db["pliers-deformed"].contour().transformed(1, 2, 3));
  const vpMorphRecognition b = back.recognize(db["pliers-deformed"].contour().transformed(1, 2, 3));
  CHECK(a.index == b.index);
  CHECK(a.distance == b.distance);

  // Saving over an existing file replaces it.
  db.remove("square");
  db.save(file.string());
  CHECK(vpMorphDatabase::load(file.string()).size() == 12);
  // A resampling model is saved with its settings.
  db.setDistance(vpMorphShapeDistance(vpMorphShapeDistance::MULTISCALE));
  db.setMinimumSupport(std::numeric_limits<double>::infinity()); // the distance alone: written as null
  db.save(file.string());
  CHECK(readText(file).find("\"support\": null") != std::string::npos);
  db.setSupportFloor(0.4);
  db.save(file.string());
  const vpMorphDatabase m = vpMorphDatabase::load(file.string());
  CHECK(std::isinf(m.minimumSupport()));
  CHECK(m.supportFloor() == 0.4);
  CHECK(m.distance().name() == "multiscale");
  CHECK(m.distance().scales() == db.distance().scales());
  CHECK(m.distance().points() == db.distance().points());
  CHECK_FALSE(m.isCalibrated());
  // So is the height model, with the same answers.
  vpMorphShapeDistance height(vpMorphShapeDistance::HEIGHT);
  vpMorphHeightFunction h = height.heightFunction();
  h.setPoints(120, 24);
  h.setSkipCost(0.25);
  h.setCandidateStarts(3);
  height.setHeightFunction(h);
  db.setDistance(height);
  db.save(file.string());
  const vpMorphDatabase hb = vpMorphDatabase::load(file.string());
  CHECK(hb.distance().name() == "height");
  CHECK(hb.distance().heightFunction().getPoints() == 120);
  CHECK(hb.distance().heightFunction().getSegments() == 24);
  CHECK(hb.distance().heightFunction().getSkipCost() == 0.25);
  CHECK(hb.distance().heightFunction().getCandidateStarts() == 3);
  const vpMorphContour q = db["wrench"].contour().transformed(1, 2, 3, 0.8);
  const vpMorphRecognition ra = db.recognize(q), rb = hb.recognize(q);
  CHECK(ra.index == db.find("wrench"));
  CHECK(ra.index == rb.index);
  CHECK(ra.distance == rb.distance);
}

TEST_CASE("database: bad files give clear errors", "[database]")
{
  const fs::path dir = scratch("bad");
  const fs::path good = dir / "good.json";
  folderDatabase().save(good.string());
  const std::string text = readText(good);
  auto loadText = [&](const std::string &s) {
    const fs::path p = dir / "x.json";
    writeText(p, s);
    return errorOf([&] { vpMorphDatabase::load(p.string()); });
  };
  // The good file with the first \e what replaced by \e with.
  auto edited = [&](const std::string &what, const std::string &with) {
    std::string t = text;
    t.replace(t.find(what), what.size(), with);
    return t;
  };
  auto expectIo = [](const std::pair<int, std::string> &e, const std::string &words) {
    CAPTURE(e.second);
    CHECK(e.first == vpMorphException::ioError);
    CHECK(e.second.find(words) != std::string::npos);
  };
  expectIo(loadText(text.substr(0, text.size() / 2)), "truncated");
  expectIo(loadText("{ not json"), "malformed");
  expectIo(loadText("[1, 2]"), "not a JSON object");
  expectIo(loadText("{\"format\": \"something-else\", \"version\": 1}"), "not a template database");
  expectIo(loadText(edited("\"version\": 1", "\"version\": 2")), "unsupported version 2");
  expectIo(loadText(edited("\"templates\"", "\"templatez\"")), "templates");
  expectIo(loadText(edited("\"x\": [", "\"x\": [\"a\",")), "wrong type");
  REQUIRE(text.find("\"region\": {") != std::string::npos);
  expectIo(loadText(edited("\"region\": {", "\"region\": 3, \"was\": {")), "\"region\" must be an object");
  REQUIRE(text.find("\"outline\": {") != std::string::npos);
  expectIo(loadText(edited("\"outline\": {", "\"outline\": [], \"was\": {")), "\"outline\" must be an object");
  std::string shortOutline = text;
  const std::size_t ox = shortOutline.find("\"x\": [", shortOutline.find("\"outline\": {"));
  shortOutline.replace(ox, 6, "\"x\": [1, 2], \"z\": [");
  expectIo(loadText(shortOutline), "\"outline\"");
  expectIo(loadText(edited("\"outline\": {", "\"outline\": {\"blur\": -0.5, ")), "the blur must be finite and >= 0");
  expectIo(loadText(edited("\"outline\": {", "\"outline\": {\"blur\": \"sharp\", ")), "wrong type");
  expectIo(loadText(edited("\"area\": ", "\"area\": -")), "finite positive area");
  REQUIRE(text.find("\"support\": 0.75") != std::string::npos);
  for (const char *bad : {"1.5", "0", "\"high\""}) {
    expectIo(loadText(edited("\"support\": 0.75", std::string("\"support\": ") + bad)),
             "support must be a number in (0, 1] or null");
  }
  REQUIRE(text.find("\"support_floor\": 0.5") != std::string::npos);
  for (const char *bad : {"1.5", "-0.1", "null", "\"low\""}) {
    expectIo(loadText(edited("\"support_floor\": 0.5", std::string("\"support_floor\": ") + bad)),
             "support_floor must be a number in [0, 1]");
  }
  // The height model's settings: missing, or points its segments do not divide.
  {
    vpMorphDatabase h = folderDatabase();
    h.setDistance(vpMorphShapeDistance(vpMorphShapeDistance::HEIGHT));
    h.save(good.string());
    const std::string ht = readText(good);
    const std::string segments = "\"segments\": 20";
    REQUIRE(ht.find(segments) != std::string::npos);
    std::string noSegments = ht;
    noSegments.replace(noSegments.find(segments), segments.size(), "\"segmentz\": 20");
    expectIo(loadText(noSegments), "segments");
    std::string badSegments = ht;
    badSegments.replace(badSegments.find(segments), segments.size(), "\"segments\": 7");
    expectIo(loadText(badSegments), "invalid \"distance\"");
  }
  // Files written before the support (or its floor) existed have the defaults.
  std::string noSupport = text;
  noSupport.replace(noSupport.find("\"support\": 0.75"), 15, "\"supporx\": 0.75");
  noSupport.replace(noSupport.find("\"support_floor\": 0.5"), 20, "\"supporx_floor\": 0.5");
  {
    const fs::path p = dir / "old.json";
    writeText(p, noSupport);
    CHECK(vpMorphDatabase::load(p.string()).minimumSupport() == 0.75);
    CHECK(vpMorphDatabase::load(p.string()).supportFloor() == 0.5);
  }
  // RIGID's look-alikes: malformed ones refused; a calibrated file written before they were kept finds them again.
  {
    vpMorphDatabase r = folderDatabase();
    r.setDistance(vpMorphShapeDistance(vpMorphShapeDistance::RIGID));
    r.calibrate(0);
    r.save(good.string());
    const std::string rt = readText(good);
    REQUIRE(rt.find("\"look_alikes\": [") != std::string::npos);
    REQUIRE(rt.find("\"index\": ") != std::string::npos); // one at least
    auto rigidEdited = [&](const std::string &what, const std::string &with) {
      std::string t = rt;
      t.replace(t.find(what), what.size(), with);
      return t;
    };
    for (const auto &bad :
         {std::make_pair("\"index\": ", "\"index\": 1000"), std::make_pair("\"index\": ", "\"index\": -"),
          std::make_pair("\"scale\": ", "\"scale\": -"), std::make_pair("\"theta\": ", "\"theta\": \"up\", \"was\": "),
          std::make_pair("\"look_alikes\": [", "\"look_alikes\": [[], ")})
      expectIo(loadText(rigidEdited(bad.first, bad.second)), "\"look_alikes\" must hold");
    auto sameLookAlikes = [&r](const vpMorphDatabase &back) {
      for (std::size_t k = 0; k < r.size(); ++k) {
        REQUIRE(back.lookAlikes(k).size() == r.lookAlikes(k).size());
        for (std::size_t i = 0; i < r.lookAlikes(k).size(); ++i) {
          CHECK(back.lookAlikes(k)[i].index == r.lookAlikes(k)[i].index);
          CHECK(back.lookAlikes(k)[i].transform.theta() == r.lookAlikes(k)[i].transform.theta());
        }
      }
    };
    const fs::path p = dir / "old-rigid.json";
    writeText(p, rigidEdited("\"look_alikes\"", "\"look_alikez\""));
    sameLookAlikes(vpMorphDatabase::load(p.string()));
    // Lists sought among a shortlist (a file without "look_alikes_of", one list edited) are sought anew; lists
    // sought among every pair are read as they are.
    std::size_t first = 0;
    while (first < r.size() && r.lookAlikes(first).empty())
      ++first;
    REQUIRE(first < r.size());
    REQUIRE(r.lookAlikes(first)[0].transform.theta() != 0.5);
    const std::string edited = rigidEdited("\"theta\": ", "\"theta\": 0.5, \"was\": ");
    writeText(p, edited);
    CHECK(vpMorphDatabase::load(p.string()).lookAlikes(first)[0].transform.theta() == 0.5);
    std::string shortlisted = edited;
    shortlisted.replace(shortlisted.find("\"look_alikes_of\""), 16, "\"look_alikes_ox\"");
    writeText(p, shortlisted);
    sameLookAlikes(vpMorphDatabase::load(p.string()));
  }
  expectIo(errorOf([&] { vpMorphDatabase::load((dir / "absent.json").string()); }), "cannot open");
  // Found by fuzz_database_json: a number beyond double made the JSON parser throw out_of_range, which escaped
  // as a nlohmann exception instead of a vpMorphException (regressions/database_json/).
  expectIo(loadText("[\n 44440000000000000000000e000000000000000000000000395, 0.05]"), "malformed");
  std::string hugeX = text;
  hugeX.replace(hugeX.find("\"x\": ["), 6, "\"x\": [1e400,");
  expectIo(loadText(hugeX), "malformed");

  // A template whose image disappeared.
  vpMorphDatabase db;
  db.add(vpMorphTemplate("gone", square(), (dir / "gone.png").string()));
  db.save((dir / "gone.json").string());
  expectIo(errorOf([&] { vpMorphDatabase::load((dir / "gone.json").string()); }), "not found");
  CHECK(vpMorphDatabase::load((dir / "gone.json").string(), false).size() == 1);

  // Duplicate names in a file.
  std::string dup = text;
  const std::size_t a = dup.find("\"name\": \"hammer-deformed\"");
  REQUIRE(a != std::string::npos);
  dup.replace(a, 25, "\"name\": \"hammer\"");
  const auto e = loadText(dup);
  CHECK(e.first == vpMorphException::badParameterError);
  CHECK(e.second.find("duplicate template name 'hammer'") != std::string::npos);
}

TEST_CASE("database: names, indices and folders", "[database]")
{
  vpMorphDatabase db;
  db.add(vpMorphTemplate("a", square()));
  auto e = errorOf([&] { db.add(vpMorphTemplate("a", square(5))); });
  CHECK(e.first == vpMorphException::badParameterError);
  CHECK(e.second.find("duplicate") != std::string::npos);
  CHECK(errorOf([&] { (void)db["b"]; }).first == vpMorphException::notFoundError);
  CHECK(errorOf([&] { (void)db[3]; }).first == vpMorphException::notFoundError);
  CHECK(errorOf([&] { db.remove("b"); }).first == vpMorphException::notFoundError);
  CHECK(errorOf([] { vpMorphTemplate("", square()); }).first == vpMorphException::badParameterError);
  CHECK(errorOf([] { vpMorphTemplate("x", vpMorphContour()); }).first == vpMorphException::badParameterError);
  // One template: calibrated from itself alone.
  db.calibrate();
  CHECK(db.isCalibrated());
  CHECK(std::isinf(db.betweenDistances()[0]));
  CHECK(db.recognize(square(3)).margin == 1.0);
  // A manual threshold survives a round trip; +inf between distances too.
  db.setThreshold(0.5);
  const fs::path one = scratch("one") / "one.json";
  db.save(one.string());
  const vpMorphDatabase back = vpMorphDatabase::load(one.string());
  CHECK(back.isThresholdManual());
  CHECK(back.threshold(0) == 0.5);
  CHECK(std::isinf(back.betweenDistances()[0]));
  CHECK(db.recognize(square(3)).secondIndex == vpMorphRecognition::npos);

  CHECK(errorOf([] { vpMorphDatabase::fromImages("/nonexistent-dir"); }).first == vpMorphException::ioError);
  const fs::path emptyDir = scratch("empty");
  CHECK(errorOf([&] { vpMorphDatabase::fromImages(emptyDir.string()); }).first == vpMorphException::ioError);
  // Two images with the same name.
  const fs::path twice = scratch("twice");
  fs::copy_file(objectsDir() + "/key.png", twice / "key.png");
  fs::copy_file(objectsDir() + "/key.png", twice / "key.pgm");
  e = errorOf([&] { vpMorphDatabase::fromImages(twice.string()); });
  CHECK(e.first == vpMorphException::badParameterError);
  CHECK(e.second.find("two images named 'key'") != std::string::npos);
  // An unreadable image.
  const fs::path broken = scratch("broken");
  writeText(broken / "junk.png", "not a png");
  CHECK(errorOf([&] { vpMorphDatabase::fromImages(broken.string()); }).first == vpMorphException::ioError);
  // A file where the directory should be: save fails cleanly.
  CHECK(errorOf([&] { db.save("/nonexistent-dir/db.json"); }).first == vpMorphException::ioError);
}
