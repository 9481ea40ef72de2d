/*!
  \file vispmorph-replay.cpp
  \brief Replays a recorded image sequence through recognition and vpFeatureMorph: the path from a real camera's
  recording to the library.

  \code
  vispmorph-replay SEQUENCE --db DB.json --out DIR (--intrinsics PX PY U0 V0 | --camera-xml FILE --camera-name NAME)
                   [--depth Z] [--object NAME] [--mask-tags] [--video FILE] [--fps F]
  \endcode
  SEQUENCE is what vpVideoReader reads: a numbered image sequence ("frames/frame-%04d.png") or a video file. Each
  frame: the AprilTags (36h11) painted out with --mask-tags (a scene's tag is a larger dark region than most objects),
  the largest object's contour extracted (vpMorphTagPoseEstimator::silhouette, the bench's own pipeline), recognised
  against the template database until a template accepts it (or the template --object from the first frame with an
  object), then the feature vpFeatureMorph s of the contour (depth from the area ratio to the taught view) against
  s* of the template's view at the taught depth (--depth, else the template's cdMo), and its error s - s*.
  Writes in DIR:
  - features.csv: per frame, the status (ok, no-object, not-recognised), the template and its distance, the depth,
    s = (xg, yg, theta, sigma) and s - s*;
  - overlay-NNNN.png: the frame with s* (green, wide), the correspondence (cyan), s (red) and the values as text;
  - with --video FILE, the overlays as a video through vpVideoWriter (.avi: MJPG, .mp4: mp4v; or a %04d.png pattern).
  A frame without the object, or not recognised, is said on its overlay and in the CSV; the replay goes on.
  Exit status: 0 when the sequence was replayed, 1 on an error (unreadable sequence or database, unknown object,
  no frame with the object), 2 on bad arguments.
*/
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImageConvert.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/core/vpXmlParserCamera.h>
#include <visp3/detection/vpDetectorAprilTag.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/io/vpVideoReader.h>
#include <visp3/io/vpVideoWriter.h>
#include <visp3/morph/vpMorphDatabase.h>
#include <visp3/morph/vpMorphDrawing.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_sim/vpMorphTagPoseEstimator.h>
#include <visp3/morph_vs/vpFeatureMorph.h>

namespace
{
void usage(std::ostream &os)
{
  os << "Usage: vispmorph-replay SEQUENCE --db DB.json --out DIR (--intrinsics PX PY U0 V0 | --camera-xml FILE\n"
        "                        --camera-name NAME) [--depth Z] [--object NAME] [--mask-tags] [--video FILE] [--fps "
        "F]\n"
        "  SEQUENCE           a numbered image sequence (frames/frame-%04d.png) or a video file (vpVideoReader)\n"
        "  --db FILE          template database (vispmorph-db build, or the one vispmorph-bench --video writes)\n"
        "  --out DIR          features.csv and overlay-NNNN.png\n"
        "  --intrinsics ...   the camera's px py u0 v0 (pixels)\n"
        "  --camera-xml FILE  ViSP camera file (vpXmlParserCamera), with --camera-name NAME\n"
        "  --depth Z          the taught depth (m); default the template's desired pose cdMo\n"
        "  --object NAME      the template to servo to (default: recognised in the first frames)\n"
        "  --mask-tags        paint out AprilTags (36h11) before extracting the object\n"
        "  --video FILE       also write the overlays as a video (.avi, .mp4) or a %04d.png sequence\n"
        "  --fps F            the video's frame rate (default 10)\n";
}

struct Options
{
  std::string sequence, db, out, xml, cameraName, object, video;
  double px = 0, py = 0, u0 = 0, v0 = 0, depth = 0, fps = 10;
  bool intrinsics = false, maskTags = false;
};

bool number(const char *s, double &v)
{
  char *end = nullptr;
  v = std::strtod(s, &end);
  return end != s && *end == '\0' && std::isfinite(v);
}

// Returns false (after printing why) when the arguments are not usable.
bool parse(int argc, char **argv, Options &o)
{
  // Options with a text value, options with a number > 0.
  const std::map<std::string, std::string Options::*> texts = {
      {"--db", &Options::db},          {"--out", &Options::out},
      {"--camera-xml", &Options::xml}, {"--camera-name", &Options::cameraName},
      {"--object", &Options::object},  {"--video", &Options::video}};
  const std::map<std::string, double Options::*> numbers = {{"--depth", &Options::depth}, {"--fps", &Options::fps}};
  for (int k = 1; k < argc; ++k) {
    const std::string s = argv[k];
    auto value = [&](std::string &v) {
      if (k + 1 >= argc) {
        std::cerr << "vispmorph-replay: " << s << " needs a value\n";
        return false;
      }
      v = argv[++k];
      return true;
    };
    auto positive = [&](double &v) {
      std::string t;
      if (!value(t))
        return false;
      if (!number(t.c_str(), v) || v <= 0) {
        std::cerr << "vispmorph-replay: " << s << " needs a number > 0, not '" << t << "'\n";
        return false;
      }
      return true;
    };
    if (s == "--help" || s == "-h") {
      usage(std::cout);
      std::exit(0);
    } else if (texts.count(s)) {
      if (!value(o.*texts.at(s)))
        return false;
    } else if (numbers.count(s)) {
      if (!positive(o.*numbers.at(s)))
        return false;
    } else if (s == "--intrinsics") {
      o.intrinsics = true;
      for (double *v : {&o.px, &o.py, &o.u0, &o.v0}) {
        if (k + 1 >= argc || !number(argv[k + 1], *v)) {
          std::cerr << "vispmorph-replay: --intrinsics needs 4 numbers: px py u0 v0\n";
          return false;
        }
        ++k;
      }
      if (o.px <= 0 || o.py <= 0) {
        std::cerr << "vispmorph-replay: --intrinsics: px and py must be > 0\n";
        return false;
      }
    } else if (s == "--mask-tags") {
      o.maskTags = true;
    } else if (!s.empty() && s[0] == '-') {
      std::cerr << "vispmorph-replay: unknown option '" << s << "'\n";
      return false;
    } else if (o.sequence.empty()) {
      o.sequence = s;
    } else {
      std::cerr << "vispmorph-replay: one sequence only ('" << o.sequence << "', then '" << s << "')\n";
      return false;
    }
  }
  if (o.sequence.empty() || o.db.empty() || o.out.empty()) {
    std::cerr << "vispmorph-replay: needs a SEQUENCE, --db and --out\n";
    return false;
  }
  if (o.intrinsics == !o.xml.empty()) {
    std::cerr << "vispmorph-replay: give the camera either by --intrinsics or by --camera-xml (with --camera-name)\n";
    return false;
  }
  if (!o.xml.empty() && o.cameraName.empty()) {
    std::cerr << "vispmorph-replay: --camera-xml needs --camera-name\n";
    return false;
  }
  return true;
}

vpCameraParameters camera(const Options &o, unsigned int width, unsigned int height)
{
  if (o.intrinsics)
    return vpCameraParameters(o.px, o.py, o.u0, o.v0);
  vpXmlParserCamera parser;
  vpCameraParameters cam;
  if (parser.parse(cam, o.xml, o.cameraName, vpCameraParameters::perspectiveProjWithoutDistortion, width, height) !=
      vpXmlParserCamera::SEQUENCE_OK)
    throw vpMorphException(vpMorphException::ioError, "cannot read camera '" + o.cameraName + "' (" +
                                                          std::to_string(width) + "x" + std::to_string(height) +
                                                          ", without distortion) from " + o.xml);
  return cam;
}

// The codec vpVideoWriter gives OpenCV for a video file, from its extension (an image pattern needs none): OpenCV's
// four-character code, its characters' bytes low first.
int codecFor(const std::string &file)
{
  const char *c = vpIoTools::getFileExtension(file) == ".mp4" ? "mp4v" : "MJPG";
  return c[0] | (c[1] << 8) | (c[2] << 16) | (c[3] << 24);
}

// The alignment from s to s* (a line from a vertex of s to where the measured similarity lays it), in pixels.
void drawAlignment(vpImage<vpRGBa> &O, const vpFeatureMorph &s, const vpCameraParameters &cam)
{
  for (const auto &l : s.getAlignment().lines(s.contour(), cam))
    vpMorphDrawing::drawLine(O, l.first, l.second, vpColor::cyan);
}

std::string fmt(const char *format, double a, double b = 0, double c = 0, double d = 0)
{
  char line[200];
  std::snprintf(line, sizeof line, format, a, b, c, d);
  return line;
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
    //! [Open]
    vpVideoReader reader;
    vpImage<unsigned char> I;
    try {
      reader.setFileName(o.sequence);
      reader.open(I);
    } catch (const vpException &e) {
      throw vpMorphException(vpMorphException::ioError,
                             "cannot read the sequence '" + o.sequence + "': " + e.getStringMessage());
    }
    const vpCameraParameters cam = camera(o, I.getWidth(), I.getHeight());
    const vpMorphDatabase db = vpMorphDatabase::load(o.db, false);
    if (db.empty())
      throw vpMorphException(vpMorphException::badParameterError, "the database " + o.db + " has no template");
    std::size_t chosen = vpMorphRecognition::npos;
    if (!o.object.empty() && (chosen = db.find(o.object)) == vpMorphRecognition::npos)
      throw vpMorphException(vpMorphException::notFoundError, "no template '" + o.object + "' in " + o.db);
    //! [Open]

    vpIoTools::makeDirectory(o.out);
    std::ofstream csv(o.out + "/features.csv");
    if (!csv)
      throw vpMorphException(vpMorphException::ioError, "cannot write " + o.out + "/features.csv");
    csv << "frame,status,object,distance,threshold,Z,xg,yg,theta,sigma,e_xg,e_yg,e_theta,e_sigma,vertices\n";
    vpVideoWriter writer;
    vpDetectorAprilTag tags(vpDetectorAprilTag::TAG_36h11);
    vpFeatureMorph s, sd;
    vpMorphContour goal;
    double Zd = o.depth, distance = 0, threshold = 0;
    unsigned int frames = 0, withObject = 0;
    long recognisedAt = 0;
    vpColVector e;
    std::string nearest;
    while (!reader.end()) { // open() read the first frame without moving on: acquire() gives it again
      reader.acquire(I);
      const long index = reader.getFrameIndex();
      ++frames;

      //! [Frame]
      // The bench's pipeline: the tags painted out, the largest object's contour (empty when there is none).
      vpImage<unsigned char> J = I; // the frame as recorded stays for the overlay
      if (o.maskTags && tags.detect(J))
        for (std::size_t t = 0; t < tags.getNbObjects(); ++t)
          vpMorphTagPoseEstimator::maskTag(J, tags.getPolygon(t));
      const vpMorphContour c = vpMorphTagPoseEstimator::silhouette(J, {});
      std::string status = "ok";
      if (c.empty()) {
        status = "no-object";
      } else if (goal.empty()) {
        // The template: the one named, else the first one the database accepts.
        const vpMorphRecognition r = db.recognize(c);
        if (chosen == vpMorphRecognition::npos && r.accepted)
          chosen = r.index;
        if (chosen != vpMorphRecognition::npos) {
          distance = chosen == r.index ? r.distance : std::nan("");
          threshold = r.threshold;
          goal = db[chosen].viewFor(c);
          if (o.depth <= 0)
            Zd = db[chosen].cdMo()[2][3];
          if (!(Zd > 0))
            throw vpMorphException(vpMorphException::badParameterError,
                                   "template '" + db[chosen].name() + "' has no desired pose: give --depth");
          sd.buildFrom(goal, cam, Zd);
          recognisedAt = index;
        } else {
          status = "not-recognised";
          nearest = db[r.index].name();
          distance = r.distance;
          threshold = r.threshold;
        }
      }
      if (status == "ok") {
        ++withObject;
        // A first depth from the area ratio to the taught view, then the one the alignment's scale gives (a plane
        // parallel to the image; vpFeatureMorph's depth): only the interaction matrix and Z depend on it, not e.
        s.buildFrom(c, cam, Zd * std::sqrt(goal.area() / c.area()));
        e = s.error(sd);
        if (s.getAlignment().explained())
          s.buildFrom(c, cam, Zd * s.getAlignment().transform.scale());
      }
      //! [Frame]

      vpImage<vpRGBa> O;
      vpImageConvert::convert(I, O);
      std::vector<std::string> text = {fmt("frame %.0f", index)};
      csv << index << "," << status << ",";
      if (status == "ok") {
        sd.draw(cam, O, vpColor::green, 3);
        drawAlignment(O, s, cam);
        s.draw(cam, O, vpColor::red, 1);
        text[0] += "  " + db[chosen].name() + fmt("  Z %.3f m", s.get_Z());
        text.push_back(
            fmt("s: xg %.4f yg %.4f theta %.4f sigma %.4f", s.get_xg(), s.get_yg(), s.get_theta(), s.get_sigma()));
        text.push_back(fmt("s - s*: %.4f %.4f %.4f %.4f", e[0], e[1], e[2], e[3]));
        csv << db[chosen].name() << "," << distance << "," << threshold << "," << s.get_Z() << "," << s.get_xg() << ","
            << s.get_yg() << "," << s.get_theta() << "," << s.get_sigma() << "," << e[0] << "," << e[1] << "," << e[2]
            << "," << e[3] << "," << c.size() << "\n";
      } else {
        const bool none = status == "no-object";
        text[0] += none ? "  no object in the image"
                        : "  not recognised: closest " + nearest +
                              fmt(", distance %.3f > threshold %.3f", distance, threshold);
        csv << (none ? "" : nearest) << "," << (none ? "" : std::to_string(distance)) << ","
            << (none ? "" : std::to_string(threshold)) << ",,,,,,,,,," << c.size() << "\n";
      }
      vpMorphDrawing::drawTextBand(O, text, vpImagePoint(4, 4)); // as vpServoMorph::draw() writes its status
      char name[64];
      std::snprintf(name, sizeof name, "/overlay-%04ld.png", index);
      vpImageIo::write(O, o.out + name);
      if (!o.video.empty()) {
        if (frames == 1) {
          writer.setFileName(o.video);
          writer.setCodec(codecFor(o.video));
          writer.setFramerate(o.fps);
          writer.open(O);
        }
        writer.saveFrame(O);
      }
    }
    if (!o.video.empty())
      writer.close();

    std::printf("%s: %u frames, %u with the object", o.sequence.c_str(), frames, withObject);
    if (chosen != vpMorphRecognition::npos)
      std::printf(", %s from frame %ld (taught depth %.3f m)", db[chosen].name().c_str(), recognisedAt, Zd);
    std::printf("\n");
    if (withObject > 0)
      std::printf("last frame: s - s* = (%.5f, %.5f, %.5f, %.5f), depth %.4f m\n", e[0], e[1], e[2], e[3], s.get_Z());
    std::printf("wrote %s/features.csv, %s/overlay-*.png%s%s\n", o.out.c_str(), o.out.c_str(),
                o.video.empty() ? "" : ", ", o.video.c_str());
    if (withObject == 0) {
      std::cerr << "vispmorph-replay: no frame showed a recognised object\n";
      return 1;
    }
    return 0;
  } catch (const vpException &e) {
    std::cerr << "vispmorph-replay: " << e.getStringMessage() << std::endl;
    return 1;
  }
}
