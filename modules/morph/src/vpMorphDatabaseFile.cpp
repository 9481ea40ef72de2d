#include <visp3/morph/vpMorphDatabase.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include <nlohmann/json.hpp>

#include <visp3/core/vpImage.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphException.h>

// vpMorphDatabase's files (JSON: toJson(), save(), load(), fromJson()) and image folders (fromImages()).

namespace fs = std::filesystem;
using nlohmann::json;

namespace
{
constexpr double kInf = std::numeric_limits<double>::infinity();
const char *kFormat = "vispmorph-template-database";
constexpr int kVersion = 1;
// How the calibration's look-alikes were sought: lists sought otherwise (a shortlist) may miss some, and are sought
// anew.
const char *kLookAlikesOf = "every pair";

vpMorphException ioError(const std::string &msg) { return vpMorphException(vpMorphException::ioError, msg); }
json poseToJson(const vpHomogeneousMatrix &M)
{
  json a = json::array();
  for (unsigned int i = 0; i < 4; ++i)
    for (unsigned int j = 0; j < 4; ++j)
      a.push_back(M[i][j]);
  return a;
}

template <typename T> T field(const json &j, const char *key, const std::string &where)
{
  if (!j.is_object() || !j.contains(key))
    throw ioError("vpMorphDatabase: " + where + " has no \"" + key + "\" field");
  try {
    return j.at(key).get<T>();
  } catch (const json::exception &e) {
    throw ioError("vpMorphDatabase: " + where + ": field \"" + key + "\" has the wrong type (" + e.what() + ")");
  }
}

// JSON has no infinity: +inf (no other template) is written as null.
json finiteOrNull(const std::vector<double> &v)
{
  json a = json::array();
  for (double x : v)
    a.push_back(std::isfinite(x) ? json(x) : json(nullptr));
  return a;
}

std::vector<double> numbersOrInf(const json &cal, const char *key)
{
  if (!cal.contains(key) || !cal[key].is_array())
    throw ioError(std::string("vpMorphDatabase: \"calibration\" has no \"") + key + "\" array");
  std::vector<double> v;
  for (const json &x : cal[key]) {
    if (x.is_null())
      v.push_back(kInf);
    else if (x.is_number() && x.get<double>() >= 0.0)
      v.push_back(x.get<double>());
    else
      throw ioError(std::string("vpMorphDatabase: \"calibration\": \"") + key + "\" must hold numbers >= 0");
  }
  return v;
}

// The calibration's "look_alikes": per template, its look-alikes' indices and transforms.
std::vector<std::vector<vpMorphDatabase::LookAlike>> lookAlikesFromJson(const json &a, std::size_t size)
{
  const std::string bad = "vpMorphDatabase: \"calibration\": \"look_alikes\" must hold, per template, a list of "
                          "{index, theta, tx, ty, scale, cx, cy}";
  if (!a.is_array() || a.size() != size)
    throw ioError(bad);
  std::vector<std::vector<vpMorphDatabase::LookAlike>> lists;
  for (const json &list : a) {
    if (!list.is_array())
      throw ioError(bad);
    lists.emplace_back();
    for (const json &o : list) {
      double v[6];
      const char *keys[6] = {"theta", "tx", "ty", "scale", "cx", "cy"};
      for (int k = 0; k < 6; ++k) {
        if (!o.is_object() || !o.contains(keys[k]) || !o[keys[k]].is_number())
          throw ioError(bad);
        v[k] = o[keys[k]].get<double>();
      }
      if (!o.contains("index") || !o["index"].is_number_unsigned() || o["index"].get<std::size_t>() >= size)
        throw ioError(bad);
      try {
        lists.back().push_back(vpMorphDatabase::LookAlike{o["index"].get<std::size_t>(),
                                                          vpMorphRigidTransform(v[0], v[1], v[2], v[3], v[4], v[5])});
      } catch (const vpException &) { // not finite, or a scale <= 0
        throw ioError(bad);
      }
    }
  }
  return lists;
}

//! A contour's fields of a template object: units, vertices, and the measured region and outline when present.
void contourToJson(const vpMorphContour &c, json &o)
{
  o["units"] = c.units() == vpMorphContour::PIXEL ? "pixel" : "normalized";
  o["x"] = c.xs();
  o["y"] = c.ys();
  if (c.hasRegion()) {
    double cx, cy, mu20, mu11, mu02;
    c.regionCentroid(cx, cy);
    c.regionMoments(mu20, mu11, mu02);
    o["region"] = {{"area", c.regionArea()}, {"cx", cx}, {"cy", cy}, {"mu20", mu20}, {"mu11", mu11}, {"mu02", mu02}};
  }
  if (c.hasOutline()) { // the measured edge, for the out-of-plane estimate of vpServoMorph, and its blur
    o["outline"] = {{"x", c.outline().xs()}, {"y", c.outline().ys()}};
    if (c.outlineBlur() > 0.0)
      o["outline"]["blur"] = c.outlineBlur();
  }
}

//! Runs \e f, the errors of what it builds reported as a malformed file at \e where.
template <typename F> void asFileError(const std::string &where, F f)
{
  try {
    f();
  } catch (const vpMorphException &e) {
    if (e.getCode() == vpMorphException::ioError)
      throw;
    throw ioError("vpMorphDatabase: " + where + ": " + e.getStringMessage());
  }
}

//! The contour written by contourToJson(); \e where names it in the errors.
vpMorphContour contourFromJson(const json &o, const std::string &where)
{
  const std::string units = field<std::string>(o, "units", where);
  if (units != "pixel" && units != "normalized")
    throw ioError("vpMorphDatabase: " + where + ": units must be \"pixel\" or \"normalized\"");
  const std::vector<double> x = field<std::vector<double>>(o, "x", where);
  const std::vector<double> y = field<std::vector<double>>(o, "y", where);
  vpMorphContour c;
  try {
    c = vpMorphContour(x, y, units == "pixel" ? vpMorphContour::PIXEL : vpMorphContour::NORMALIZED);
  } catch (const vpException &e) {
    throw ioError("vpMorphDatabase: " + where + ": invalid contour: " + e.getStringMessage());
  }
  if (o.contains("region")) { // optional: the region measured on the template image
    const json &r = o["region"];
    if (!r.is_object())
      throw ioError("vpMorphDatabase: " + where + ": \"region\" must be an object {area, cx, cy, mu20, mu11, mu02}");
    const std::string w = where + " \"region\"";
    asFileError(w, [&] {
      c.setRegion(field<double>(r, "area", w), field<double>(r, "cx", w), field<double>(r, "cy", w),
                  field<double>(r, "mu20", w), field<double>(r, "mu11", w), field<double>(r, "mu02", w));
    });
  }
  if (o.contains("outline")) { // optional: the edge measured on the template image
    const json &e = o["outline"];
    if (!e.is_object())
      throw ioError("vpMorphDatabase: " + where + ": \"outline\" must be an object {x, y[, blur]}");
    const std::string w = where + " \"outline\"";
    asFileError(w, [&] {
      c.setOutline(
          vpMorphContour(field<std::vector<double>>(e, "x", w), field<std::vector<double>>(e, "y", w), c.units()),
          e.contains("blur") ? field<double>(e, "blur", w) : 0.0);
    });
  }
  return c;
}

bool isImageFile(const fs::path &p)
{
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char ch) { return static_cast<char>(std::tolower(ch)); });
  return e == ".png" || e == ".jpg" || e == ".jpeg" || e == ".pgm" || e == ".ppm" || e == ".bmp" || e == ".tif" ||
         e == ".tiff";
}
} // namespace

vpMorphDatabase vpMorphDatabase::fromImages(const std::string &dir, const vpMorphShapeDistance &distance,
                                            const Progress &progress)
{
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw ioError("vpMorphDatabase::fromImages: '" + dir + "' is not a readable directory");
  std::vector<fs::path> files;
  for (const auto &e : fs::directory_iterator(dir, ec))
    if (e.is_regular_file() && isImageFile(e.path()))
      files.push_back(e.path());
  if (ec)
    throw ioError("vpMorphDatabase::fromImages: cannot list '" + dir + "': " + ec.message());
  if (files.empty())
    throw ioError("vpMorphDatabase::fromImages: no image (png, jpg, pgm, ppm, bmp, tif) in '" + dir + "'");
  std::sort(files.begin(), files.end(), [](const fs::path &a, const fs::path &b) {
    return a.stem() < b.stem() || (a.stem() == b.stem() && a.filename() < b.filename());
  });
  for (std::size_t k = 1; k < files.size(); ++k)
    if (files[k].stem() == files[k - 1].stem())
      throw vpMorphException(vpMorphException::badParameterError,
                             "vpMorphDatabase::fromImages: two images named '" + files[k].stem().string() + "' (" +
                                 files[k - 1].filename().string() + ", " + files[k].filename().string() + ")");
  std::vector<vpMorphContour> contours(files.size());
  distance.parallelFor(
      files.size(), 0,
      [&](std::size_t k, vpMorphMatcher &) {
        vpImage<unsigned char> I;
        try {
          vpImageIo::read(I, files[k].string());
        } catch (const vpException &e) {
          throw ioError("vpMorphDatabase::fromImages: cannot read image '" + files[k].string() +
                        "': " + e.getStringMessage());
        }
        try {
          contours[k] = vpMorphContourExtractor().extract(I);
        } catch (const vpException &e) {
          throw vpMorphException(vpMorphException::badImageError,
                                 "vpMorphDatabase::fromImages: '" + files[k].string() + "': " + e.getStringMessage());
        }
      },
      progress);
  vpMorphDatabase db(distance);
  for (std::size_t k = 0; k < files.size(); ++k)
    db.add(vpMorphTemplate(files[k].stem().string(), contours[k], files[k].string()));
  db.calibrate(0, progress);
  return db;
}

std::string vpMorphDatabase::toJson() const { return toJson(std::string()); }

std::string vpMorphDatabase::toJson(const std::string &relativeTo) const
{
  json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["distance"] = json::parse(m_distance.settingsJson());
  json cal;
  cal["calibrated"] = m_calibrated;
  cal["manual"] = m_manual;
  cal["threshold"] = m_manual ? json(m_threshold) : json(nullptr);
  cal["slack"] = calibrationSlack();
  cal["within"] = finiteOrNull(m_within);
  cal["between"] = finiteOrNull(m_between);
  if (!m_lookAlikes.empty()) {
    json all = json::array();
    for (const std::vector<LookAlike> &list : m_lookAlikes) {
      json a = json::array();
      for (const LookAlike &l : list) {
        const vpMorphRigidTransform &t = l.transform;
        a.push_back(json{{"index", l.index},
                         {"theta", t.theta()},
                         {"tx", t.tx()},
                         {"ty", t.ty()},
                         {"scale", t.scale()},
                         {"cx", t.cx()},
                         {"cy", t.cy()}});
      }
      all.push_back(a);
    }
    cal["look_alikes"] = all;
    cal["look_alikes_of"] = kLookAlikesOf;
  }
  cal["support"] = std::isfinite(m_minSupport) ? json(m_minSupport) : json(nullptr);
  cal["support_floor"] = m_supportFloor;
  j["calibration"] = cal;
  json ts = json::array();
  for (const vpMorphTemplate &t : m_templates) {
    json o;
    o["name"] = t.name();
    std::string image = t.imagePath();
    if (!image.empty() && !relativeTo.empty()) {
      std::error_code ec;
      const fs::path rel = fs::absolute(image, ec).lexically_normal().lexically_relative(
          fs::absolute(relativeTo, ec).lexically_normal());
      if (!ec && !rel.empty())
        image = rel.generic_string();
    }
    o["image"] = image;
    contourToJson(t.contour(), o);
    if (t.isArticulated()) {
      const vpMorphArticulation &a = t.articulation();
      json parts = json::array();
      for (unsigned int k = 0; k < 2; ++k) {
        json pj;
        contourToJson(a.part(k), pj);
        parts.push_back(pj);
      }
      o["articulation"] = {
          {"parts", parts}, {"pivot", {a.pivot().get_u(), a.pivot().get_v()}}, {"range", {a.minAngle(), a.maxAngle()}}};
    }
    o["cdMo"] = poseToJson(t.cdMo());
    o["metadata"] = t.metadata();
    ts.push_back(o);
  }
  j["templates"] = ts;
  return j.dump(1);
}

void vpMorphDatabase::save(const std::string &path) const
{
  const fs::path target(path);
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  const std::string text = toJson(dir.string());
  // Temporary file in the same directory, so that the rename is atomic (same file system).
  std::ostringstream name;
  name << "." << target.filename().string() << ".tmp-" << std::random_device()();
  const fs::path tmp = dir / name.str();
  {
    std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
    if (!f)
      throw ioError("vpMorphDatabase::save: cannot write in '" + dir.string() + "'");
    f << text << "\n";
    f.flush();
    if (!f) {
      f.close();
      std::remove(tmp.string().c_str());
      throw ioError("vpMorphDatabase::save: write error on '" + tmp.string() + "' (disk full?)");
    }
  }
  if (std::rename(tmp.string().c_str(), path.c_str()) != 0) {
    std::remove(tmp.string().c_str());
    throw ioError("vpMorphDatabase::save: cannot rename the temporary file onto '" + path + "'");
  }
}

vpMorphDatabase vpMorphDatabase::load(const std::string &path, bool checkImages)
{
  std::ifstream f(path, std::ios::binary);
  if (!f)
    throw ioError("vpMorphDatabase::load: cannot open '" + path + "'");
  std::stringstream ss;
  ss << f.rdbuf();
  const fs::path p(path);
  try {
    return fromJson(ss.str(), checkImages, p.has_parent_path() ? p.parent_path().string() : std::string("."));
  } catch (const vpMorphException &e) {
    throw vpMorphException(e.getCode(), e.getStringMessage() + " (file '" + path + "')");
  }
}

vpMorphDatabase vpMorphDatabase::fromJson(const std::string &text, bool checkImages, const std::string &baseDir)
{
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception &e) {
    // parse_error, and also out_of_range for a number beyond double (1e400): both are a malformed file.
    throw ioError(std::string("vpMorphDatabase: not valid JSON (malformed or truncated file): ") + e.what());
  }
  if (!j.is_object())
    throw ioError("vpMorphDatabase: the file is not a JSON object");
  if (!j.contains("format") || !j["format"].is_string() || j["format"].get<std::string>() != kFormat)
    throw ioError(std::string("vpMorphDatabase: not a template database (\"format\" must be \"") + kFormat + "\")");
  if (!j.contains("version") || !j["version"].is_number_integer())
    throw ioError("vpMorphDatabase: missing or non-integer \"version\"");
  const int version = j["version"].get<int>();
  if (version != kVersion) {
    std::ostringstream os;
    os << "vpMorphDatabase: unsupported version " << version << " (this build reads version " << kVersion << ")";
    throw ioError(os.str());
  }
  const json dj = j.contains("distance") ? j["distance"] : json();
  vpMorphShapeDistance d = vpMorphShapeDistance::fromName(field<std::string>(dj, "model", "\"distance\""));
  try {
    d.setWorkModel(vpMorphWorkModel(field<double>(dj, "ks", "\"distance\""), field<double>(dj, "kb", "\"distance\""),
                                    field<double>(dj, "cs", "\"distance\"")));
    if (d.model() == vpMorphShapeDistance::HEIGHT) {
      vpMorphHeightFunction h = d.heightFunction();
      h.setPoints(field<std::size_t>(dj, "points", "\"distance\""), field<std::size_t>(dj, "segments", "\"distance\""));
      h.setSkipCost(field<double>(dj, "skip", "\"distance\""));
      h.setCandidateStarts(field<std::size_t>(dj, "starts", "\"distance\""));
      d.setHeightFunction(h);
    } else if (d.model() != vpMorphShapeDistance::POLYGON) {
      d.setPoints(field<std::size_t>(dj, "points", "\"distance\""));
      d.setScales(field<std::vector<double>>(dj, "scales", "\"distance\""));
    }
    d.setMirrors(field<bool>(dj, "mirrors", "\"distance\""));
  } catch (const vpMorphException &e) {
    if (e.getCode() == vpMorphException::ioError)
      throw;
    throw ioError("vpMorphDatabase: invalid \"distance\": " + e.getStringMessage());
  }
  vpMorphDatabase db(d);
  if (!j.contains("templates") || !j["templates"].is_array())
    throw ioError("vpMorphDatabase: no \"templates\" array");
  std::size_t k = 0;
  for (const json &o : j["templates"]) {
    std::ostringstream where;
    where << "template " << k++;
    const std::string name = field<std::string>(o, "name", where.str());
    where << " ('" << name << "')";
    const vpMorphContour c = contourFromJson(o, where.str());
    const std::vector<double> m = field<std::vector<double>>(o, "cdMo", where.str());
    if (m.size() != 16)
      throw ioError("vpMorphDatabase: " + where.str() + ": \"cdMo\" needs 16 numbers (row-major 4x4)");
    vpHomogeneousMatrix M;
    for (unsigned int r = 0; r < 4; ++r)
      for (unsigned int cc = 0; cc < 4; ++cc)
        M[r][cc] = m[4 * r + cc];
    std::string image = o.contains("image") ? field<std::string>(o, "image", where.str()) : std::string();
    if (!image.empty() && fs::path(image).is_relative() && !baseDir.empty()) {
      std::error_code ec;
      image = (fs::absolute(baseDir, ec) / image).lexically_normal().string();
    }
    if (checkImages && !image.empty()) {
      std::error_code ec;
      if (!fs::exists(image, ec))
        throw ioError("vpMorphDatabase: " + where.str() + ": image '" + image + "' not found");
    }
    vpMorphTemplate t(name, c, image, M);
    if (o.contains("articulation")) { // optional: two parts about a pin
      const json &a = o["articulation"];
      const std::string w = where.str() + " \"articulation\"";
      if (!a.is_object() || !a.contains("parts") || !a["parts"].is_array() || a["parts"].size() != 2)
        throw ioError("vpMorphDatabase: " + w + " must be an object {parts: [2 contours], pivot, range}");
      const std::vector<double> pivot = field<std::vector<double>>(a, "pivot", w);
      const std::vector<double> range = field<std::vector<double>>(a, "range", w);
      if (pivot.size() != 2 || range.size() != 2)
        throw ioError("vpMorphDatabase: " + w + ": \"pivot\" is (u, v) and \"range\" (min, max) radians");
      asFileError(w, [&] {
        t.setArticulation(vpMorphArticulation(contourFromJson(a["parts"][0], w + " part 0"),
                                              contourFromJson(a["parts"][1], w + " part 1"),
                                              vpImagePoint(pivot[1], pivot[0]), range[0], range[1]));
      });
    }
    if (o.contains("metadata"))
      t.setMetadata(field<std::map<std::string, std::string>>(o, "metadata", where.str()));
    if (db.find(name) != vpMorphRecognition::npos)
      throw vpMorphException(vpMorphException::badParameterError,
                             "vpMorphDatabase: duplicate template name '" + name + "'");
    db.add(t);
  }
  if (j.contains("calibration")) {
    const json &cal = j["calibration"];
    const std::string w = "\"calibration\"";
    const bool calibrated = field<bool>(cal, "calibrated", w);
    const bool manual = field<bool>(cal, "manual", w);
    const json &th = cal.contains("threshold") ? cal["threshold"] : json();
    if (!th.is_null() && !(th.is_number() && th.get<double>() > 0.0))
      throw ioError("vpMorphDatabase: \"calibration\": threshold must be a positive number or null");
    if (manual && th.is_null())
      throw ioError("vpMorphDatabase: \"calibration\": a manual threshold needs a value");
    db.m_within = numbersOrInf(cal, "within");
    db.m_between = numbersOrInf(cal, "between");
    if (calibrated && (db.m_within.size() != db.size() || db.m_between.size() != db.size()))
      throw ioError("vpMorphDatabase: \"calibration\" does not match the number of templates");
    db.m_calibrated = calibrated;
    db.m_manual = manual;
    db.m_threshold = manual ? th.get<double>() : kInf;
    if (cal.contains("support")) { // absent from the files written before it existed: the default
      const json &su = cal["support"];
      if (!su.is_null() && !(su.is_number() && su.get<double>() > 0.0 && su.get<double>() <= 1.0))
        throw ioError("vpMorphDatabase: \"calibration\": support must be a number in (0, 1] or null");
      db.m_minSupport = su.is_null() ? kInf : su.get<double>();
    }
    if (cal.contains("support_floor")) { // idem
      const json &fl = cal["support_floor"];
      if (!(fl.is_number() && fl.get<double>() >= 0.0 && fl.get<double>() <= 1.0))
        throw ioError("vpMorphDatabase: \"calibration\": support_floor must be a number in [0, 1]");
      db.m_supportFloor = fl.get<double>();
    }
    if (cal.contains("look_alikes"))
      db.m_lookAlikes = lookAlikesFromJson(cal["look_alikes"], db.size());
    // A file written before look-alikes were kept, or when they were sought among a shortlist: found anew.
    if (calibrated && db.m_distance.model() == vpMorphShapeDistance::RIGID &&
        !(cal.contains("look_alikes") && cal.contains("look_alikes_of") && cal["look_alikes_of"] == kLookAlikesOf))
      db.findLookAlikes(0);
  }
  return db;
}
