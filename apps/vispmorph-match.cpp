/*!
  \file vispmorph-match.cpp
  \brief Morph one object image into another: D_morph, correspondence, rigid transform, morph sequence picture.

  \code
  vispmorph-match A.png B.png [--exact] [--json] [--sequence N --out strip.png]
  \endcode
  Extracts the largest object contour of each image (no parameter), computes the minimal-work cyclic
  correspondence (fast exact search, or the brute-force reference with --exact), and prints the morph distance
  (scale normalised, as for recognition), the vertex counts, the starting pair, the similarity from A to B
  (robust least squares over the correspondence) and the timings. --json prints the same as one JSON object.
  --sequence N writes the picture of the N intermediate contours (rigid frames, then deformation frames).
  Exit status: 0 on success, 1 on an error (unreadable image, no object, ...), 2 on bad arguments.
*/
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <string>

#include <nlohmann/json.hpp>

#include <visp3/core/vpImage.h>
#include <visp3/core/vpTime.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorph.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphDrawing.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph/vpMorphMatcher.h>

namespace
{
void usage(std::ostream &os)
{
  os << "Usage: vispmorph-match A.png B.png [--exact] [--json] [--sequence N --out strip.png]\n"
        "  Morph the largest object of image A into the largest object of image B.\n"
        "  --exact         use the brute-force reference search instead of the fast exact one\n"
        "  --json          print one JSON object instead of text\n"
        "  --sequence N    number of intermediate contours to draw (N >= 1), with --out\n"
        "  --out FILE      PNG file for the morph sequence picture\n";
}

struct Options
{
  std::string a, b, out;
  bool exact = false, json = false;
  long sequence = 0;
};

// Returns false (after printing why) when the arguments are not usable.
bool parse(int argc, char **argv, Options &o)
{
  for (int k = 1; k < argc; ++k) {
    const std::string s = argv[k];
    if (s == "--help" || s == "-h") {
      usage(std::cout);
      std::exit(0);
    } else if (s == "--exact") {
      o.exact = true;
    } else if (s == "--json") {
      o.json = true;
    } else if (s == "--sequence" || s == "--out") {
      if (k + 1 >= argc) {
        std::cerr << "vispmorph-match: " << s << " needs a value\n";
        return false;
      }
      const std::string v = argv[++k];
      if (s == "--out") {
        o.out = v;
      } else {
        char *end = nullptr;
        o.sequence = std::strtol(v.c_str(), &end, 10);
        if (v.empty() || *end != '\0' || o.sequence < 1 || o.sequence > 1000) {
          std::cerr << "vispmorph-match: --sequence needs an integer in [1, 1000] (got '" << v << "')\n";
          return false;
        }
      }
    } else if (!s.empty() && s[0] == '-') {
      std::cerr << "vispmorph-match: unknown option '" << s << "'\n";
      return false;
    } else if (o.a.empty()) {
      o.a = s;
    } else if (o.b.empty()) {
      o.b = s;
    } else {
      std::cerr << "vispmorph-match: too many images ('" << s << "')\n";
      return false;
    }
  }
  if (o.b.empty()) {
    std::cerr << "vispmorph-match: two images are needed\n";
    return false;
  }
  if ((o.sequence > 0) != !o.out.empty()) {
    std::cerr << "vispmorph-match: --sequence and --out go together\n";
    return false;
  }
  return true;
}

vpMorphContour load(const std::string &path, double &ms)
{
  vpImage<unsigned char> I;
  try {
    vpImageIo::read(I, path);
  } catch (const vpException &e) {
    throw vpMorphException(vpMorphException::ioError, "cannot read image '" + path + "': " + e.getStringMessage());
  }
  const double t0 = vpTime::measureTimeMs();
  vpMorphContour c = vpMorphContourExtractor().extract(I);
  ms = vpTime::measureTimeMs() - t0;
  return c;
}
} // namespace

int main(int argc, char **argv)
{
  Options o;
  if (!parse(argc, argv, o)) {
    usage(std::cerr);
    return 2;
  }
  try {
    double msA = 0, msB = 0;
    const vpMorphContour A = load(o.a, msA), B = load(o.b, msB);

    vpMorphMatcher matcher;
    const double t0 = vpTime::measureTimeMs();
    const vpMorphCorrespondence corr = o.exact ? matcher.matchBruteForce(A, B) : matcher.match(A, B);
    const double msMatch = vpTime::measureTimeMs() - t0;
    const vpMorph morph(A, B, corr);
    const vpMorphRigidTransform &T = morph.rigidTransform();

    if (o.sequence > 0)
      vpMorphDrawing::write(vpMorphDrawing::sequenceStrip(morph, static_cast<std::size_t>(o.sequence)), o.out);

    if (o.json) {
      nlohmann::json j;
      j["input"] = {{"image", o.a}, {"vertices", A.size()}, {"extraction_ms", msA}};
      j["target"] = {{"image", o.b}, {"vertices", B.size()}, {"extraction_ms", msB}};
      j["search"] = o.exact ? "brute-force" : "fast-exact";
      j["d_morph"] = corr.work();
      j["stretching_work"] = corr.stretchingWork();
      j["bending_work"] = corr.bendingWork();
      j["correspondence_pairs"] = corr.size();
      j["starting_pair"] = {corr.start().first, corr.start().second};
      j["rigid"] = {{"rotation_deg", T.theta() * 180.0 / M_PI},
                    {"translation_px", {T.tx(), T.ty()}},
                    {"scale", T.scale()},
                    {"centre_px", {T.cx(), T.cy()}}};
      j["match_ms"] = msMatch;
      if (o.sequence > 0)
        j["sequence"] = {{"frames", o.sequence}, {"picture", o.out}};
      std::cout << j.dump(2) << std::endl;
    } else {
      std::cout << std::fixed << std::setprecision(4) << "input   " << o.a << ": " << A.size() << " vertices ("
                << std::setprecision(1) << msA << " ms)\n"
                << "target  " << o.b << ": " << B.size() << " vertices (" << msB << " ms)\n"
                << std::setprecision(5) << "D_morph " << corr.work() << " (stretching " << corr.stretchingWork()
                << ", bending " << corr.bendingWork() << "), " << (o.exact ? "brute-force" : "fast exact")
                << " search in " << std::setprecision(3) << msMatch << " ms\n"
                << "pairs   " << corr.size() << ", starting pair (" << corr.start().first << ", " << corr.start().second
                << ")\n"
                << std::setprecision(2) << "rigid   rotation " << T.theta() * 180.0 / M_PI << " deg, translation ("
                << T.tx() << ", " << T.ty() << ") px, scale " << std::setprecision(4) << T.scale() << "\n";
      if (o.sequence > 0)
        std::cout << "picture " << o.out << " (" << o.sequence << " intermediate contours)\n";
    }
  } catch (const vpException &e) {
    std::cerr << "vispmorph-match: " << e.getStringMessage() << std::endl;
    return 1;
  }
  return 0;
}
