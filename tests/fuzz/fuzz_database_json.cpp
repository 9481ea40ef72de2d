/*!
  \file fuzz_database_json.cpp
  \brief Fuzz target: the template database loader (vpMorphDatabase::fromJson, what load() parses) on arbitrary
  text.

  A vpException (malformed, truncated, wrong version, invalid contour, duplicate name...) is a correct outcome;
  an escaping std::exception or a crash is a finding. A database that loads must be usable: it writes itself
  back (toJson()) into text that loads again to the same templates and minimum support, and it recognises its first
  template's contour as a template at distance >= 0 (finite), whose outline that contour shows a share of.
*/
#include <cmath>
#include <cstdint>
#include <string>

#include <visp3/core/vpException.h>
#include <visp3/morph/vpMorphDatabase.h>

#include "vpFuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  const std::string text(reinterpret_cast<const char *>(data), size);
  vpMorphDatabase db;
  try {
    db = vpMorphDatabase::fromJson(text, false, "");
  } catch (const vpException &) {
    return 0; // refused with a clear message
  }
  const std::string again = db.toJson();
  vpMorphDatabase db2;
  try {
    db2 = vpMorphDatabase::fromJson(again, false, "");
  } catch (const vpException &e) {
    std::fprintf(stderr, "%s\n", e.getMessage());
    VP_FUZZ_CHECK(false, "a database that loads writes text that loads again");
  }
  VP_FUZZ_CHECK(db2.size() == db.size(), "a saved database keeps its templates");
  VP_FUZZ_CHECK(db2.minimumSupport() == db.minimumSupport(), "a saved database keeps its minimum support");
  for (std::size_t k = 0; k < db.size(); ++k) {
    VP_FUZZ_CHECK(db2[k].name() == db[k].name(), "a saved database keeps its names");
    VP_FUZZ_CHECK(db2[k].contour().xs() == db[k].contour().xs() && db2[k].contour().ys() == db[k].contour().ys(),
                  "a saved database keeps its contours");
  }
  if (db.empty())
    return 0;
  try {
    const vpMorphRecognition r = db.recognize(db[0].contour());
    VP_FUZZ_CHECK(r.index < db.size(), "recognition names a template");
    VP_FUZZ_CHECK(std::isfinite(r.distance) && r.distance >= 0.0, "the recognised distance is finite and >= 0");
    const double s = db.support(db[0].contour(), 0);
    VP_FUZZ_CHECK(s >= 0.0 && s <= 1.0, "the support of a template's own contour is a share");
  } catch (const vpException &) {
    // a stored contour the distance model refuses (e.g. a normalised contour with pixel templates)
  }
  return 0;
}
