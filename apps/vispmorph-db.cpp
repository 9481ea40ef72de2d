/*!
  \file vispmorph-db.cpp
  \brief Template databases from the command line: build one from a folder of images, inspect it, recognise.

  \code
  vispmorph-db build DIR --out db.json [--model rigid|multiscale|paper|polygon|height] [--threshold T] [--joints JDIR]
  vispmorph-db info db.json
  vispmorph-db recognize db.json IMAGE... [--json] [--exhaustive] [--min-support S|off]
  \endcode
  build: one template per image of DIR (named after the file), the largest object of each, calibrated
  acceptance thresholds (vpMorphDatabase::calibrate()), saved atomically; progress on stderr. --joints: each
  JDIR/NAME.json (vpMorphJointFile) articulates template NAME (a joint file naming no template is an error).
  info: templates, vertex counts, calibration (within, nearest other template, threshold), articulations.
  recognize: per image, the template (and the opening a view of an articulated one was recognised at), its distance
  (the default rigid model: the exact check's cost) and, for a D_morph model, its threshold, the share of its outline
  shown (vpMorphDatabase::support()), the runner-up (the distance's choice when the support re-ranked them), the
  margin, and ACCEPTED or REJECTED (vpMorphDatabase's rule for the model: rigid, by the check; D_morph, by the
  distance or by the support); with several images, how many were accepted (for D_morph, each way).
  --min-support replaces the database's minimum support for this query (off: with D_morph, the distance alone).
  Exit status: 0 on success (also when objects are rejected), 1 on an error (with several images, after recognising
  all the others), 2 on bad arguments.
*/
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <visp3/core/vpImage.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpTime.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphJointFile.h>

namespace
{
void usage(std::ostream &os)
{
  os << "Usage: vispmorph-db build DIR --out db.json [--model rigid|multiscale|paper|polygon|height] [--threshold T]\n"
        "                         [--joints JDIR]\n"
        "       vispmorph-db info db.json\n"
        "       vispmorph-db recognize db.json IMAGE... [--json] [--exhaustive] [--min-support S|off]\n"
        "  build      one template per image of DIR, calibrated, written atomically to db.json; JDIR/NAME.json\n"
        "             (parts' images, pivot, range_deg) articulates template NAME\n"
        "  info       templates and calibration of a database\n"
        "  recognize  the template of the largest object of each IMAGE, accepted or rejected (--min-support: the\n"
        "             least share of the template's outline it shows; off: with a D_morph model, the distance alone)\n";
}

struct Args
{
  std::string verb, out, model = vpMorphDatabase().distance().name(), joints;
  std::vector<std::string> positional;
  double threshold = 0.0;
  double minSupport = 0.0; // 0: the database's; +inf: off
  bool json = false, exhaustive = false;
};

bool parse(int argc, char **argv, Args &a)
{
  if (argc < 2) {
    std::cerr << "vispmorph-db: a verb is needed (build, info, recognize)\n";
    return false;
  }
  a.verb = argv[1];
  if (a.verb == "--help" || a.verb == "-h") {
    usage(std::cout);
    std::exit(0);
  }
  if (a.verb != "build" && a.verb != "info" && a.verb != "recognize") {
    std::cerr << "vispmorph-db: unknown verb '" << a.verb << "'\n";
    return false;
  }
  for (int k = 2; k < argc; ++k) {
    const std::string s = argv[k];
    if (s == "--json") {
      a.json = true;
    } else if (s == "--exhaustive") {
      a.exhaustive = true;
    } else if (s == "--out" || s == "--model" || s == "--threshold" || s == "--min-support" || s == "--joints") {
      if (k + 1 >= argc) {
        std::cerr << "vispmorph-db: " << s << " needs a value\n";
        return false;
      }
      const std::string v = argv[++k];
      if (s == "--out") {
        a.out = v;
      } else if (s == "--joints") {
        a.joints = v;
      } else if (s == "--model") {
        a.model = v;
      } else if (s == "--min-support") {
        char *end = nullptr;
        a.minSupport = v == "off" ? std::numeric_limits<double>::infinity() : std::strtod(v.c_str(), &end);
        if (v != "off" && (v.empty() || *end != '\0' || !(a.minSupport > 0.0 && a.minSupport <= 1.0))) {
          std::cerr << "vispmorph-db: --min-support needs a number in (0, 1] or off (got '" << v << "')\n";
          return false;
        }
      } else {
        char *end = nullptr;
        a.threshold = std::strtod(v.c_str(), &end);
        if (v.empty() || *end != '\0' || !(a.threshold > 0.0) || !std::isfinite(a.threshold)) {
          std::cerr << "vispmorph-db: --threshold needs a positive number (got '" << v << "')\n";
          return false;
        }
      }
    } else if (!s.empty() && s[0] == '-') {
      std::cerr << "vispmorph-db: unknown option '" << s << "'\n";
      return false;
    } else {
      a.positional.push_back(s);
    }
  }
  const std::size_t need = a.verb == "recognize" ? 2 : 1;
  if (a.verb == "recognize" ? a.positional.size() < need : a.positional.size() != need) {
    std::cerr << "vispmorph-db " << a.verb << ": expected " << (a.verb == "recognize" ? "at least " : "") << need
              << " argument(s), got " << a.positional.size() << "\n";
    return false;
  }
  if (a.minSupport > 0.0 && a.verb != "recognize") {
    std::cerr << "vispmorph-db: --min-support is an option of recognize\n";
    return false;
  }
  if (!a.joints.empty() && a.verb != "build") {
    std::cerr << "vispmorph-db: --joints is an option of build\n";
    return false;
  }
  if (a.verb == "build" && a.out.empty()) {
    std::cerr << "vispmorph-db build: --out db.json is required\n";
    return false;
  }
  return true;
}

void progress(std::size_t done, std::size_t total)
{
  std::cerr << "\r  " << done << "/" << total << (done >= total ? "\n" : "") << std::flush;
}

/*!
  Articulates the templates of \e db that a joint file of \e dir names (NAME.json, sorted); returns how many.
  \throw vpMorphException::ioError on an unreadable directory or file, notFoundError on a joint file that names no
  template (a misspelt file would otherwise leave its tool rigid without a word).
*/
std::size_t articulate(vpMorphDatabase &db, const std::string &dir)
{
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->path().extension() == ".json")
      files.push_back(it->path());
  if (ec)
    throw vpMorphException(vpMorphException::ioError, "cannot read joint directory '" + dir + "': " + ec.message());
  std::sort(files.begin(), files.end());
  for (const fs::path &f : files) {
    const std::string name = f.stem().string();
    if (db.find(name) == vpMorphRecognition::npos)
      throw vpMorphException(vpMorphException::notFoundError,
                             "joint file '" + f.string() + "' names no template of the database ('" + name + "')");
    std::cerr << "articulating " << name << " (" << f.string() << ")\n";
    db.setArticulation(name, vpMorphJointFile::read(f.string()).articulation());
  }
  return files.size();
}

//! A template's articulation as its range ("-8..60"), "-" when rigid.
std::string joint(const vpMorphTemplate &t)
{
  if (!t.isArticulated())
    return "-";
  std::ostringstream os;
  os << std::fixed << std::setprecision(0) << vpMath::deg(t.articulation().minAngle()) << ".."
     << vpMath::deg(t.articulation().maxAngle());
  return os.str();
}

std::string fmt(double x, int decimals = 4)
{
  if (!std::isfinite(x))
    return "-";
  std::ostringstream os;
  os << std::fixed << std::setprecision(decimals) << x;
  return os.str();
}
} // namespace

int main(int argc, char **argv)
{
  Args a;
  if (!parse(argc, argv, a)) {
    usage(std::cerr);
    return 2;
  }
  try {
    if (a.verb == "build") {
      const double t0 = vpTime::measureTimeMs();
      std::cerr << "extracting contours and calibrating\n";
      vpMorphDatabase db =
          vpMorphDatabase::fromImages(a.positional[0], vpMorphShapeDistance::fromName(a.model), progress);
      if (a.threshold > 0.0)
        db.setThreshold(a.threshold);
      std::size_t articulated = 0;
      if (!a.joints.empty())
        articulated = articulate(db, a.joints);
      db.save(a.out);
      std::cout << "wrote " << a.out << ": " << db.size() << " templates"
                << (articulated ? " (" + std::to_string(articulated) + " articulated)" : std::string()) << ", model "
                << db.distance().name() << ", " << std::fixed << std::setprecision(1)
                << (vpTime::measureTimeMs() - t0) / 1000.0 << " s\n";
    } else if (a.verb == "info") {
      const vpMorphDatabase db = vpMorphDatabase::load(a.positional[0]);
      std::cout << a.positional[0] << ": " << db.size() << " templates, model " << db.distance().name() << " ("
                << db.distance().points() << " points, kb " << db.distance().workModel().kb()
                << (db.distance().mirrors() ? ", mirrors" : "") << "), "
                << (db.isThresholdManual() ? "manual threshold"
                    : db.isCalibrated()    ? "calibrated thresholds"
                                           : "not calibrated")
                << "\n";
      std::cout << std::left << std::setw(24) << "name" << std::right << std::setw(9) << "vertices" << std::setw(10)
                << "within" << std::setw(10) << "nearest" << std::setw(11) << "threshold"
                << "  joint (deg)  image\n";
      for (std::size_t k = 0; k < db.size(); ++k) {
        const bool cal = db.isCalibrated();
        std::cout << std::left << std::setw(24) << db[k].name() << std::right << std::setw(9) << db[k].contour().size()
                  << std::setw(10) << (cal ? fmt(db.withinDistances()[k]) : "-") << std::setw(10)
                  << (cal ? fmt(db.betweenDistances()[k]) : "-") << std::setw(11) << fmt(db.threshold(k)) << "  "
                  << std::left << std::setw(11) << joint(db[k]) << "  " << std::right << db[k].imagePath() << "\n";
      }
      if (db.distance().model() == vpMorphShapeDistance::RIGID) {
        std::cout << "minimum support (share of a template's outline a view must show): " << fmt(db.minimumSupport())
                  << "; most outside it: " << fmt(vpMorphDatabase::maximumOutside())
                  << "; ambiguity (least evidence telling two acceptable templates apart): "
                  << fmt(vpMorphDatabase::ambiguity()) << "\n";
      } else {
        std::cout << "minimum support (share of a template's outline that accepts a view its distance rejects): "
                  << fmt(db.minimumSupport()) << "\n";
        std::cout << "support floor (share under which a view its distance accepts is rejected): "
                  << fmt(db.supportFloor()) << "\n";
      }
    } else {
      vpMorphDatabase db = vpMorphDatabase::load(a.positional[0]);
      if (a.minSupport > 0.0)
        db.setMinimumSupport(a.minSupport);
      nlohmann::json all = nlohmann::json::array();
      const std::size_t n = a.positional.size() - 1;
      std::size_t byDistance = 0, bySupport = 0, byCheck = 0, errors = 0;
      for (std::size_t i = 1; i <= n; ++i) {
        const std::string &path = a.positional[i];
        vpMorphRecognition r;
        double ms = 0.0;
        try {
          vpImage<unsigned char> I;
          try {
            vpImageIo::read(I, path);
          } catch (const vpException &e) {
            throw vpMorphException(vpMorphException::ioError,
                                   "cannot read image '" + path + "': " + e.getStringMessage());
          }
          const double t0 = vpTime::measureTimeMs();
          r = db.recognize(vpMorphContourExtractor().extract(I), !a.exhaustive);
          ms = vpTime::measureTimeMs() - t0;
        } catch (const vpException &e) {
          if (n == 1)
            throw;
          // One bad image among many (unreadable, no object): said, counted, and the others still recognised.
          std::cerr << "vispmorph-db: " << path << ": " << e.getStringMessage() << std::endl;
          ++errors;
          continue;
        }
        // By the support: beyond its threshold, or put in place of the distance's choice (re-ranked). RIGID accepts
        // by its check alone (counted apart).
        const bool rigid = db.distance().model() == vpMorphShapeDistance::RIGID;
        const bool supported = !rigid && r.accepted && (r.reranked || !(r.distance <= r.threshold));
        byCheck += rigid && r.accepted ? 1 : 0;
        byDistance += !rigid && r.accepted && !supported ? 1 : 0;
        bySupport += supported ? 1 : 0;
        if (a.json) {
          nlohmann::json j;
          j["image"] = path;
          j["best"] = db[r.index].name();
          j["distance"] = r.distance;
          j["threshold"] = r.threshold;
          j["support"] = std::isnan(r.support) ? nlohmann::json(nullptr) : nlohmann::json(r.support);
          j["minimum_support"] =
              std::isfinite(db.minimumSupport()) ? nlohmann::json(db.minimumSupport()) : nlohmann::json(nullptr);
          j["accepted"] = r.accepted;
          j["accepted_by"] = !r.accepted ? nlohmann::json(nullptr)
                                         : nlohmann::json(rigid       ? "rigid check"
                                                          : supported ? "support"
                                                                      : "distance");
          j["mirrored"] = r.mirrored;
          j["opening_deg"] = db[r.index].isArticulated() ? nlohmann::json(vpMath::deg(r.articulation)) : nullptr;
          j["reranked"] = r.reranked;
          j["support_floor"] = db.supportFloor();
          j["runner_up"] = r.secondIndex == vpMorphRecognition::npos ? nlohmann::json(nullptr)
                                                                     : nlohmann::json(db[r.secondIndex].name());
          j["runner_up_distance"] = std::isfinite(r.secondDistance) ? nlohmann::json(r.secondDistance) : nullptr;
          j["margin"] = r.margin;
          j["templates_evaluated"] = r.evaluated;
          j["templates"] = db.size();
          j["ms"] = ms;
          all.push_back(j);
        } else {
          std::cout << (a.positional.size() > 2 ? path + ": " : std::string())
                    << (r.accepted ? (supported ? "ACCEPTED (support) " : "ACCEPTED ") : "REJECTED ")
                    << db[r.index].name() << (r.mirrored ? " (mirrored)" : "")
                    << (r.articulation != 0.0 ? " opened " + fmt(vpMath::deg(r.articulation), 1) + " deg" : "") << ": "
                    << (rigid ? "cost " : "distance ") << fmt(r.distance);
          if (!rigid)
            std::cout << " (threshold " << fmt(r.threshold) << ")";
          if (!std::isnan(r.support))
            std::cout << ", support " << std::setprecision(2) << std::fixed << r.support << " (minimum "
                      << fmt(db.minimumSupport()) << ")";
          if (r.reranked)
            std::cout << ", re-ranked from " << db[r.secondIndex].name();
          if (!rigid && !r.accepted && r.distance <= r.threshold)
            std::cout << ", under the support floor " << fmt(db.supportFloor());
          std::cout << ", runner-up "
                    << (r.secondIndex == vpMorphRecognition::npos ? std::string("none") : db[r.secondIndex].name())
                    << " " << fmt(r.secondDistance) << ", margin " << std::setprecision(1) << std::fixed
                    << 100.0 * r.margin << " %; " << r.evaluated << " of " << db.size() << " templates matched in "
                    << ms << " ms\n";
        }
      }
      if (a.json)
        std::cout << (n == 1 ? all[0] : all).dump(2) << std::endl;
      else if (n > 1 && db.distance().model() == vpMorphShapeDistance::RIGID)
        std::cout << "accepted " << byCheck << " of " << n
                  << (errors ? " (" + std::to_string(errors) + " in error)" : std::string()) << "\n";
      else if (n > 1)
        std::cout << "accepted " << byDistance + bySupport << " of " << n << " (" << byDistance << " by the distance, "
                  << bySupport << " by the support" << (errors ? ", " + std::to_string(errors) + " in error" : "")
                  << ")\n";
      if (errors)
        return 1;
    }
  } catch (const vpException &e) {
    std::cerr << "vispmorph-db: " << e.getStringMessage() << std::endl;
    return 1;
  }
  return 0;
}
