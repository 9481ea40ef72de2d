// Tests of vpMorphPartRecognizer: a rigid part named by the RIGID stage (whole or under a card), a bent one by the
// database's own distance, look-alikes the view cannot tell apart rejected whatever the distance says, the candidates
// of one image, and bad input.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphPartRecognizer.h>

#include "testMorphImages.h"

namespace
{
using vpMorphTest::extract;

// \e m turned by \e deg and scaled by \e scale about the image centre, blurred and noisy (std 3), extracted.
vpMorphContour view(const cv::Mat &m, double deg, double scale, unsigned int seed, bool joined = false)
{
  return extract(vpMorphTest::warp(m, vpMorphTest::similarity(m, deg, scale, 0, 0), 3, seed), joined);
}

const char *kTools[] = {"key", "pliers", "wedge", "wrench", "screwdriver", "hammer"};

// The six tools' taught views, in a database of the default (deformation-tolerant) distance, calibrated.
const vpMorphDatabase &tools()
{
  static const vpMorphDatabase db = [] {
    vpMorphDatabase d;
    for (const char *name : kTools)
      d.add(vpMorphTemplate(name, extract(vpMorphTest::readObject(name))));
    d.calibrate(0);
    return d;
  }();
  return db;
}
} // namespace

TEST_CASE("part recognizer: a rigid view is named by the rigid stage, a bent one by the database's distance",
          "[recognizer]")
{
  const vpMorphPartRecognizer recognizer(tools());
  REQUIRE(recognizer.getRigidDatabase().distance().model() == vpMorphShapeDistance::RIGID);
  REQUIRE(recognizer.getRigidDatabase().size() == tools().size());
  for (std::size_t k = 0; k < tools().size(); ++k)
    CHECK(recognizer.getRigidDatabase()[k].name() == tools()[k].name()); // the answers index the database given
  unsigned int seed = 10;
  for (const char *name : {"key", "wrench", "screwdriver", "hammer"}) {
    const cv::Mat whole = vpMorphTest::readObject(name);
    const cv::Mat bent = vpMorphTest::readObject(std::string(name) + "-deformed");
    for (const double deg : {35.0, 160.0}) {
      vpMorphPartRecognizer::Stage stage;
      const vpMorphRecognition r = recognizer.recognize(view(whole, deg, 0.95, ++seed), &stage);
      CAPTURE(name, deg, tools()[r.index].name(), r.distance);
      CHECK(stage == vpMorphPartRecognizer::RIGID_STAGE);
      CHECK((r.accepted && tools()[r.index].name() == name));
      CHECK_FALSE(r.ambiguous);
      // The bent view fits no template rigidly: the database's distance names it, as the database alone does.
      const vpMorphContour b = view(bent, deg, 1.0, ++seed);
      const vpMorphRecognition rb = recognizer.recognize(b, &stage), alone = tools().recognize(b),
                               rigid = recognizer.getRigidDatabase().recognize(b);
      CAPTURE(tools()[rb.index].name(), rigid.support);
      CHECK_FALSE(rigid.accepted);
      CHECK_FALSE(rigid.ambiguous);
      CHECK(stage == vpMorphPartRecognizer::DISTANCE_STAGE);
      CHECK((rb.accepted && tools()[rb.index].name() == name));
      CHECK((rb.index == alone.index && rb.accepted == alone.accepted && rb.distance == alone.distance));
    }
  }
}

TEST_CASE("part recognizer: a view under a card is named by the rigid stage", "[recognizer]")
{
  const vpMorphPartRecognizer recognizer(tools());
  unsigned int seed = 40;
  for (const char *name : kTools)
    for (const double where : {0.1, 0.6}) {
      const cv::Mat hidden = vpMorphTest::squareOccluder(vpMorphTest::readObject(name), where, 0.2);
      vpMorphPartRecognizer::Stage stage;
      const vpMorphRecognition r = recognizer.recognize(view(hidden, 20.0 + 300.0 * where, 1.05, ++seed, true), &stage);
      CAPTURE(name, where, tools()[r.index].name(), r.support);
      CHECK(stage == vpMorphPartRecognizer::RIGID_STAGE);
      CHECK((r.accepted && tools()[r.index].name() == name));
    }
}

TEST_CASE("part recognizer: look-alikes that differ only under the card are rejected, whatever the distance says",
          "[recognizer][ambiguity]")
{
  const cv::Mat key = vpMorphTest::readObject("key");
  cv::Point centre;
  const cv::Mat tabbed = vpMorphTest::withTab(key, centre);
  vpMorphDatabase db;
  db.add(vpMorphTemplate("key", extract(key)));
  db.add(vpMorphTemplate("key-tab", extract(tabbed)));
  db.calibrate(0);
  const vpMorphPartRecognizer recognizer(db);
  cv::Mat hidden = tabbed.clone();
  cv::rectangle(hidden, centre - cv::Point(28, 28), centre + cv::Point(28, 28), cv::Scalar(170), cv::FILLED);
  int aloneAccepted = 0;
  for (int k = 0; k < 4; ++k) {
    const double deg = 40.0 + 75.0 * k, scale = 0.9 + 0.05 * k;
    vpMorphPartRecognizer::Stage stage;
    const vpMorphRecognition whole = recognizer.recognize(view(tabbed, deg, scale, 300 + k), &stage);
    CHECK((whole.accepted && db[whole.index].name() == "key-tab" && stage == vpMorphPartRecognizer::RIGID_STAGE));
    const vpMorphContour c = view(hidden, deg, scale, 300 + k, true);
    const vpMorphRecognition card = recognizer.recognize(c, &stage), alone = db.recognize(c);
    CAPTURE(k, alone.accepted, db[alone.index].name());
    CHECK(card.ambiguous);
    CHECK_FALSE(card.accepted);
    CHECK(stage == vpMorphPartRecognizer::RIGID_STAGE);
    aloneAccepted += alone.accepted;
  }
  // The deformation-tolerant distance alone names one of the two for these views: the rigid stage's rejection is
  // what keeps them unnamed.
  CHECK(aloneAccepted > 0);
}

TEST_CASE("part recognizer: of one image's candidates, a rigid fit before a deformation-tolerant one", "[recognizer]")
{
  const vpMorphPartRecognizer recognizer(tools());
  cv::Mat disc(480, 640, CV_8UC1, cv::Scalar(255));
  cv::circle(disc, cv::Point(320, 240), 90, cv::Scalar(0), cv::FILLED);
  const vpMorphContour other = extract(disc);
  const vpMorphContour bent = view(vpMorphTest::readObject("wrench-deformed"), 70.0, 1.0, 60);
  const vpMorphContour key = view(vpMorphTest::readObject("key"), 110.0, 1.0, 61);
  std::size_t chosen = 99;
  vpMorphPartRecognizer::Stage stage;
  vpMorphRecognition r = recognizer.recognize({other, bent, key}, chosen, &stage);
  CHECK(chosen == 2);
  CHECK((r.accepted && tools()[r.index].name() == "key" && stage == vpMorphPartRecognizer::RIGID_STAGE));
  r = recognizer.recognize({other, bent}, chosen, &stage);
  CHECK(chosen == 1);
  CHECK((r.accepted && tools()[r.index].name() == "wrench" && stage == vpMorphPartRecognizer::DISTANCE_STAGE));
  r = recognizer.recognize({other}, chosen, &stage);
  CHECK(chosen == 0);
  CHECK_FALSE(r.accepted);
}

TEST_CASE("part recognizer: a RIGID database is its own twin, and bad input", "[recognizer][safety]")
{
  vpMorphDatabase rigid = tools();
  rigid.setDistance(vpMorphShapeDistance(vpMorphShapeDistance::RIGID));
  rigid.calibrate(0);
  const vpMorphPartRecognizer one(rigid);
  CHECK(&one.getRigidDatabase() == &one.getDatabase());
  const vpMorphContour c = view(vpMorphTest::readObject("pliers"), 250.0, 0.9, 70);
  vpMorphPartRecognizer::Stage stage;
  const vpMorphRecognition r = one.recognize(c, &stage), alone = rigid.recognize(c);
  CHECK((r.index == alone.index && r.accepted == alone.accepted && r.distance == alone.distance));
  CHECK(stage == vpMorphPartRecognizer::RIGID_STAGE);

  CHECK_THROWS_AS(vpMorphPartRecognizer(vpMorphDatabase()), vpMorphException);
  CHECK_THROWS_AS(one.recognize(vpMorphContour()), vpMorphException);
  std::size_t chosen = 0;
  CHECK_THROWS_AS(one.recognize(std::vector<vpMorphContour>(), chosen), vpMorphException);
  CHECK_THROWS_AS(one.recognize(std::vector<vpMorphContour>{c, vpMorphContour()}, chosen), vpMorphException);
  const std::size_t pliers = rigid.find("pliers");
  CHECK(one.namedAs(c, pliers) == vpMorphPartRecognizer::NAMED_TEMPLATE);
  CHECK(one.namedAs(c, rigid.find("hammer")) == vpMorphPartRecognizer::NAMED_OTHER);
  CHECK_THROWS_AS(one.namedAs(c, rigid.size()), vpMorphException);
  CHECK_THROWS_AS(one.namedAs(vpMorphContour(), pliers), vpMorphException);
}
