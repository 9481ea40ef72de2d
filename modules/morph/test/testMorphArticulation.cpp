// Tests of vpMorphArticulation (an articulated template: two parts about a pin) and of articulated templates in
// vpMorphDatabase, on the pliers that vispmorph-make-data draws: the two arms alone (data/joints), the closed pliers
// (the template) and the opened ones (the deformed variant, arms turned 16 deg each way).
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <opencv2/imgproc.hpp>

#include <visp3/core/vpMath.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphArticulation.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphJointFile.h>
#include <visp3/morph/vpMorphRigidTransform.h>

namespace
{
const std::string kData = VISPMORPH_DATA_DIR;
const vpImagePoint kPin(240, 320); // the pliers' pin in the drawings (v, u), the centre of seen()
const double kOpened = 32.0;       // deg: the deformed variant's opening (part 1 against part 0)

vpImage<unsigned char> read(const std::string &file)
{
  vpImage<unsigned char> I;
  vpImageIo::read(I, kData + file);
  return I;
}

// The drawing turned by theta (deg) and scaled by s about the image centre (the pin), then as the taught views: 10 deg
// and 0.93 pixel a texel, resampled bilinearly as a camera parallel to the plane sees it (grey edges, which the
// extractor measures to a fraction of a pixel; not the drawings' binary texels).
vpMorphContour seen(const std::string &file, double theta, double s)
{
  theta += 10.0;
  s *= 0.93;
  const vpImage<unsigned char> I = read(file);
  const cv::Mat src(static_cast<int>(I.getHeight()), static_cast<int>(I.getWidth()), CV_8UC1,
                    const_cast<unsigned char *>(I.bitmap));
  cv::Mat dst;
  cv::warpAffine(src, dst, cv::getRotationMatrix2D(cv::Point2f(320.f, 240.f), theta, s), src.size(), cv::INTER_LINEAR,
                 cv::BORDER_CONSTANT, cv::Scalar(255));
  vpImage<unsigned char> J(I.getHeight(), I.getWidth());
  for (int r = 0; r < dst.rows; ++r)
    std::copy(dst.ptr<unsigned char>(r), dst.ptr<unsigned char>(r) + dst.cols, J[static_cast<unsigned int>(r)]);
  return vpMorphContourExtractor().extract(J);
}

vpMorphArticulation pliers()
{
  return vpMorphArticulation(seen("/joints/pliers-part0.png", 0.0, 1.0), seen("/joints/pliers-part1.png", 0.0, 1.0),
                             kPin, vpMath::rad(-8.0), vpMath::rad(60.0));
}
} // namespace

TEST_CASE("vpMorphArticulation: the pose at the taught opening is the taught view", "[articulation]")
{
  const vpMorphArticulation a = pliers();
  const vpMorphContour taught = seen("/objects/pliers.png", 0.0, 1.0);
  for (unsigned int k : {0u, 1u}) {
    const vpMorphContour p = a.pose(0.0, k);
    REQUIRE(p.hasRegion());
    REQUIRE(p.hasOutline());
    double px, py, tx, ty;
    p.regionCentroid(px, py);
    taught.regionCentroid(tx, ty);
    CHECK(p.regionArea() / taught.regionArea() == Approx(1.0).epsilon(0.003));
    CHECK(std::hypot(px - tx, py - ty) < 0.05);
    // Edge for edge: the taught view lies on the pose within a few hundredths of a pixel.
    const vpMorphRigidTransform T =
        vpMorphRigidTransform::refineOnOutline(taught.outline(), p.outline(), vpMorphRigidTransform(), true, 0.02);
    CHECK(std::fabs(T.theta()) < vpMath::rad(0.02));
    CHECK(T.scale() == Approx(1.0).epsilon(0.001));
  }
}

TEST_CASE("vpMorphArticulation: the opening of a view, whatever its similarity", "[articulation]")
{
  const vpMorphArticulation a = pliers();
  vpMorphMatcher matcher;
  for (const auto &v : {std::make_pair(0.0, 1.0), std::make_pair(70.0, 0.8), std::make_pair(-150.0, 1.1)}) {
    const vpMorphContour view = seen("/objects/pliers-deformed.png", v.first, v.second);
    double overlap = 0.0;
    const double opening = a.estimate(view, &overlap);
    INFO("view turned " << v.first << " deg, scaled " << v.second << ": opening " << vpMath::deg(opening) << " deg");
    // The arms are drawn on the texel grid at other angles than in the closed pliers: within 0.15 deg.
    CHECK(std::fabs(vpMath::deg(opening) - kOpened) < 0.15);
    CHECK(overlap > 0.9); // of polygons
    // The goal lays the view by a similarity of the view's scale (the texels resampled at another scale: within
    // 0.3 %), the part that needs the smaller turn kept.
    unsigned int fixed = 2;
    const vpMorphContour goal = a.poseFor(view, opening, &fixed);
    REQUIRE(fixed < 2);
    // The template's view for it: the same goal, at the same opening.
    vpMorphTemplate t("pliers", seen("/objects/pliers.png", 0.0, 1.0));
    t.setArticulation(a);
    double o2 = 0.0;
    unsigned int fixed2 = 2;
    CHECK(t.viewFor(view, &o2, &fixed2).xs() == goal.xs());
    CHECK(o2 == opening);
    CHECK(fixed2 == fixed);
    const vpMorphRigidTransform T = vpMorphRigidTransform::refineOnOutline(
        view.outline(), goal.outline(),
        vpMorphRigidTransform::fitLeastSquares(view, goal, matcher.match(view, goal), true,
                                               vpMorphRigidTransform::TUKEY, 30, 0.5),
        true, 0.05);
    CHECK(T.scale() == Approx(1.0 / v.second).epsilon(0.003));
    CHECK(vpMorphArticulation::fitOverlap(view, goal, matcher) > 0.9);
    auto turn = [&](const vpMorphContour &g) {
      return std::fabs(vpMorphRigidTransform::fitLeastSquares(view, g, matcher.match(view, g), true,
                                                              vpMorphRigidTransform::TUKEY, 30, 0.5)
                           .theta());
    };
    CHECK(turn(goal) <= turn(a.pose(opening, 1 - fixed)));
  }
  // The closed pliers: no opening, and the template's view for them is its taught view itself.
  const vpMorphContour closed = seen("/objects/pliers.png", 35.0, 0.9);
  CHECK(std::fabs(vpMath::deg(a.estimate(closed))) < 0.15);
  vpMorphTemplate t("pliers", seen("/objects/pliers.png", 0.0, 1.0));
  t.setArticulation(a);
  double o = 1.0;
  CHECK(t.viewFor(closed, &o).xs() == t.contour().xs());
  CHECK(o == 0.0);
}

TEST_CASE("vpMorphArticulation: bad input", "[articulation]")
{
  const vpMorphContour part = seen("/joints/pliers-part0.png", 0.0, 1.0);
  CHECK_THROWS_AS(vpMorphArticulation(vpMorphContour(), part, kPin, -0.1, 0.1), vpMorphException);
  CHECK_THROWS_AS(vpMorphArticulation(part, part.toNormalized(vpCameraParameters(800, 800, 320, 240)), kPin, -0.1, 0.1),
                  vpMorphException);
  CHECK_THROWS_AS(vpMorphArticulation(part, part, vpImagePoint(NAN, 3), -0.1, 0.1), vpMorphException);
  CHECK_THROWS_AS(vpMorphArticulation(part, part, kPin, 0.1, 0.2), vpMorphException);  // 0 out of the range
  CHECK_THROWS_AS(vpMorphArticulation(part, part, kPin, -4.0, 0.2), vpMorphException); // beyond a half turn
  CHECK_THROWS_AS(vpMorphArticulation(part, part, kPin, -0.1, NAN), vpMorphException);
  const vpMorphArticulation a = pliers();
  CHECK_THROWS_AS(a.pose(vpMath::rad(61.0)), vpMorphException);
  CHECK_THROWS_AS(a.pose(0.0, 2), vpMorphException);
  CHECK_THROWS_AS(a.part(2), vpMorphException);
  CHECK_THROWS_AS(a.estimate(vpMorphContour()), vpMorphException);
  CHECK_THROWS_AS(vpMorphArticulation().pose(0.0), vpMorphException);
  CHECK_THROWS_AS(vpMorphArticulation().estimate(part), vpMorphException);
  vpMorphTemplate t("pliers", part.toNormalized(vpCameraParameters(800, 800, 320, 240)));
  CHECK_THROWS_AS(t.setArticulation(a), vpMorphException); // parts in pixels, template normalised
}

TEST_CASE("database: an articulated template recognises its opened views and is saved with them", "[database]")
{
  vpMorphDatabase rigid;
  for (const std::string name : {"key", "pliers", "wedge", "wrench", "screwdriver", "hammer"})
    rigid.add(vpMorphTemplate(name, seen("/objects/" + name + ".png", 0.0, 1.0)));
  vpMorphDatabase db;
  for (std::size_t k = 0; k < rigid.size(); ++k) {
    vpMorphTemplate t = rigid[k];
    if (t.name() == "pliers")
      t.setArticulation(pliers());
    db.add(t);
  }
  rigid.calibrate(1);
  db.calibrate(1);
  for (const auto &v : {std::make_pair(40.0, 0.9), std::make_pair(-100.0, 1.0)}) {
    const vpMorphContour opened = seen("/objects/pliers-deformed.png", v.first, v.second);
    // Rigid, the opened pliers are no known tool: a hammer by the distance, rejected.
    const vpMorphRecognition r0 = rigid.recognize(opened);
    CHECK_FALSE((r0.accepted && rigid[r0.index].name() == "pliers"));
    // Articulated: the pliers, at the pose nearest their opening (poses every 4 deg).
    const vpMorphRecognition r = db.recognize(opened);
    CHECK(db[r.index].name() == "pliers");
    CHECK(r.accepted);
    CHECK(std::fabs(vpMath::deg(r.articulation) - kOpened) <= 2.0);
    CHECK(db.accepts(opened, r.index));
    CHECK(db.support(opened, r.index) > 0.9);
    // The other tools are recognised as before.
    const vpMorphContour key = seen("/objects/key.png", v.first, v.second);
    CHECK(db[db.recognize(key).index].name() == "key");
    CHECK(db.recognize(key).articulation == 0.0);
  }

  const std::filesystem::path file = std::filesystem::current_path() / "db-articulated.json";
  db.save(file.string());
  const vpMorphDatabase back = vpMorphDatabase::load(file.string());
  const vpMorphTemplate &t = back["pliers"];
  REQUIRE(t.isArticulated());
  CHECK(t.articulation().pivot() == kPin);
  CHECK(t.articulation().minAngle() == db["pliers"].articulation().minAngle());
  CHECK(t.articulation().maxAngle() == db["pliers"].articulation().maxAngle());
  for (unsigned int k : {0u, 1u}) {
    CHECK(t.articulation().part(k).xs() == db["pliers"].articulation().part(k).xs());
    CHECK(t.articulation().part(k).outline().xs() == db["pliers"].articulation().part(k).outline().xs());
    CHECK(t.articulation().part(k).regionArea() == db["pliers"].articulation().part(k).regionArea());
  }
  CHECK_FALSE(back["key"].isArticulated());
  const vpMorphContour opened = seen("/objects/pliers-deformed.png", 15.0, 1.0);
  CHECK(back.recognize(opened).articulation == db.recognize(opened).articulation);
  CHECK(back.recognize(opened).distance == db.recognize(opened).distance);
  // A malformed articulation is a malformed file.
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const std::string key : {"\"pivot\"", "\"range\""}) {
    std::string bad = text;
    bad.replace(bad.find(key), key.size(), "\"nothing\"");
    try {
      (void)vpMorphDatabase::fromJson(bad);
      FAIL("no error without " << key);
    } catch (const vpMorphException &e) {
      CHECK(e.getCode() == vpMorphException::ioError);
      CHECK(e.getStringMessage().find("articulation") != std::string::npos);
    }
  }
  std::filesystem::remove(file);
}

TEST_CASE("vpMorphJointFile: the pliers' joint file gives their articulation", "[articulation][joint]")
{
  const vpMorphJointFile j = vpMorphJointFile::read(kData + "/joints/pliers.json");
  CHECK(j.part(0) == kData + "/joints/pliers-part0.png");
  CHECK(j.part(1) == kData + "/joints/pliers-part1.png");
  CHECK(j.pivot() == kPin);
  CHECK(j.minAngle() == Approx(vpMath::rad(-8.0)));
  CHECK(j.maxAngle() == Approx(vpMath::rad(60.0)));
  // Made from the drawings themselves (the template's frame): the opened drawing's opening.
  const vpMorphArticulation a = j.articulation();
  CHECK(a.pivot() == kPin);
  CHECK(a.part(0).hasOutline());
  const vpMorphContour opened = vpMorphContourExtractor().extract(read("/objects/pliers-deformed.png"));
  CHECK(std::fabs(vpMath::deg(a.estimate(opened)) - kOpened) < 0.5);
  // At the taught opening the parts make the closed drawing (the drawings' binary edges put a pose's region 1 %
  // larger: measured edges of binary texels, drawn again).
  const vpMorphContour closed = vpMorphContourExtractor().extract(read("/objects/pliers.png"));
  vpMorphMatcher matcher;
  const double iou = vpMorphArticulation::fitOverlap(closed, a.pose(0.0), matcher);
  CAPTURE(iou, a.pose(0.0).regionArea() / closed.regionArea());
  CHECK(iou > 0.97);
  CHECK(vpMorphArticulation::fitOverlap(closed, a.pose(vpMath::rad(kOpened)), matcher) < 0.8);
  // Paths: relative to the base directory, absolute ones kept.
  const std::string text = "{\"parts\": [\"a.png\", \"/x/b.png\"], \"pivot\": [1.5, 2], \"range_deg\": [0, 30]}";
  const vpMorphJointFile t = vpMorphJointFile::fromJson(text, "/base");
  CHECK(t.part(0) == "/base/a.png");
  CHECK(t.part(1) == "/x/b.png");
  CHECK(t.pivot() == vpImagePoint(2, 1.5));
  CHECK(vpMorphJointFile::fromJson(text).part(0) == "a.png");
  CHECK_THROWS_AS(t.part(2), vpMorphException);
}

TEST_CASE("vpMorphJointFile: bad files are clear errors", "[articulation][joint]")
{
  namespace fs = std::filesystem;
  for (const std::string text :
       {"", "not json", "[1, 2]", "{\"parts\": [\"a.png\"], \"pivot\": [1, 2], \"range_deg\": [-8, 60]}",
        "{\"parts\": [\"a.png\", \"\"], \"pivot\": [1, 2], \"range_deg\": [-8, 60]}",
        "{\"parts\": [\"a.png\", \"b.png\"], \"range_deg\": [-8, 60]}",
        "{\"parts\": [\"a.png\", \"b.png\"], \"pivot\": [1], \"range_deg\": [-8, 60]}",
        "{\"parts\": [\"a.png\", \"b.png\"], \"pivot\": [1, \"2\"], \"range_deg\": [-8, 60]}",
        "{\"parts\": [\"a.png\", \"b.png\"], \"pivot\": [1, 1e999], \"range_deg\": [-8, 60]}",
        "{\"parts\": [\"a.png\", \"b.png\"], \"pivot\": [1, 2], \"range_deg\": [5, 60]}",
        "{\"parts\": [\"a.png\", \"b.png\"], \"pivot\": [1, 2], \"range_deg\": [-8, 180]}",
        "{\"parts\": [\"a.png\", \"b.png\"], \"pivot\": [1, 2], \"range_deg\": [-8, 60, 70]}"}) {
    try {
      (void)vpMorphJointFile::fromJson(text);
      FAIL("no error for '" << text << "'");
    } catch (const vpMorphException &e) {
      CHECK(e.getCode() == vpMorphException::ioError);
      CHECK(e.getStringMessage().find("malformed joint file") != std::string::npos);
    }
  }
  CHECK_THROWS_AS(vpMorphJointFile::read("/nonexistent/joint.json"), vpMorphException);
  // Part images that are missing, or show no object: errors that name the image.
  const fs::path dir = fs::current_path() / "joint-file-test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  vpImage<unsigned char> blank(120, 160, 255);
  vpImageIo::write(blank, (dir / "blank.png").string());
  for (const auto &c : {std::make_pair(std::string("missing.png"), vpMorphException::ioError),
                        std::make_pair(std::string("blank.png"), vpMorphException::badImageError)}) {
    std::ofstream(dir / "j.json") << "{\"parts\": [\"" << c.first << "\", \"" << c.first
                                  << "\"], \"pivot\": [1, 2], \"range_deg\": [-8, 60]}";
    const vpMorphJointFile j = vpMorphJointFile::read((dir / "j.json").string());
    try {
      (void)j.articulation();
      FAIL("no error for " << c.first);
    } catch (const vpMorphException &e) {
      CHECK(e.getCode() == c.second);
      CHECK(e.getStringMessage().find(c.first) != std::string::npos);
    }
  }
  fs::remove_all(dir);
}

namespace
{
// The six tools' drawings as templates (the folder also holds their deformed variants), calibrated.
vpMorphDatabase sixTools()
{
  vpMorphDatabase db = vpMorphDatabase::fromImages(kData + "/objects");
  for (const std::string name : {"hammer", "key", "pliers", "screwdriver", "wedge", "wrench"})
    db.remove(name + "-deformed");
  db.calibrate(1);
  return db;
}
} // namespace

TEST_CASE("database: an articulation given to a template of a database", "[database][joint]")
{
  vpMorphDatabase db = sixTools();
  const std::vector<double> thresholds = {db.threshold(0), db.threshold(1), db.threshold(2)};
  const vpMorphContour opened = vpMorphContourExtractor().extract(read("/objects/pliers-deformed.png"));
  const vpMorphRecognition r0 = db.recognize(opened);
  CHECK_FALSE((r0.accepted && db[r0.index].name() == "pliers"));

  db.setArticulation("pliers", vpMorphJointFile::read(kData + "/joints/pliers.json").articulation());
  CHECK(db["pliers"].isArticulated());
  CHECK(db.isCalibrated()); // made on the taught views, which did not change
  CHECK(db.threshold(0) == thresholds[0]);
  CHECK(db.threshold(2) == thresholds[2]);
  const vpMorphRecognition r = db.recognize(opened);
  CHECK(db[r.index].name() == "pliers");
  CHECK(r.accepted);
  CHECK(std::fabs(vpMath::deg(r.articulation) - kOpened) <= 2.0);
  // Another distance: the same poses, prepared for it.
  vpMorphDatabase paper = db;
  paper.setDistance(vpMorphShapeDistance(vpMorphShapeDistance::PAPER));
  paper.calibrate(1);
  CHECK(paper.recognize(opened).articulation == r.articulation);
  // Rigid again.
  db.setArticulation("pliers", vpMorphArticulation());
  CHECK_FALSE(db["pliers"].isArticulated());
  CHECK(db.recognize(opened).distance == r0.distance);
  CHECK_THROWS_AS(db.setArticulation("pincers", vpMorphArticulation()), vpMorphException);
}

TEST_CASE("database: MPEG-7 shapes whose fit onto the pliers' poses collapses are rejected, not errors",
          "[database][joint][datasets]")
{
  // Found by vispmorph-db recognize over MPEG-7 with an articulated pliers: the robust similarity of each onto a pose
  // left its weight on pairs meeting one vertex of the pose (scale 0), and fitOverlap() threw.
  vpMorphDatabase db = sixTools();
  db.setArticulation("pliers", vpMorphJointFile::read(kData + "/joints/pliers.json").articulation());
  const std::string dir = std::string(VISPMORPH_DATASETS_DIR) + "/mpeg7/";
  for (const char *f : {"apple-11.png", "frog-1.png", "frog-6.png", "guitar-3.png", "turtle-7.png"}) {
    vpImage<unsigned char> I;
    try {
      vpImageIo::read(I, dir + f);
    } catch (const vpException &) {
      WARN("MPEG-7 image " << dir + f << " not found: dataset test skipped");
      return;
    }
    vpMorphRecognition r;
    CAPTURE(f);
    REQUIRE_NOTHROW(r = db.recognize(vpMorphContourExtractor().extract(I)));
    CHECK_FALSE(r.accepted);
  }
}
