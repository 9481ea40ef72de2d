/*!
  \file vispmorph-make-data.cpp
  \brief Generates the project's object silhouettes reproducibly from polygons defined in code.

  Usage: vispmorph-make-data OUTDIR
         vispmorph-make-data --layout SRC_DIR|LIST OUT_DIR [--size PX]   (any silhouettes laid out as bench objects)

  Writes OUTDIR/objects/<name>.png and OUTDIR/objects/<name>-deformed.png for the six tool-like objects of the
  paper's experiments (key, pliers, wedge, wrench, screwdriver, hammer), and two demo views
  OUTDIR/demo/key-view.png and OUTDIR/demo/pliers-view.png; and the pliers' two arms drawn alone with their pin
  (OUTDIR/joints/pliers-part{0,1}.png and pliers.json: an articulated template, vpMorphArticulation). Images are
  640x480, white background, black object (about 200-300 px long), binary but for the opened pliers, whose arms are
  the closed ones' drawings turned (grey edges). Every shape is a union of polygons built here, so the data can be
  regenerated bit for bit; each image is checked by extracting its contour with vpMorphContourExtractor.
*/
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include <opencv2/imgproc.hpp>

#include <visp3/core/vpImage.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/morph/vpMorphContourExtractor.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_bench/vpMorphBenchObjectSet.h>
#include <visp3/morph_sim/vpMorphSilhouetteLayout.h>

namespace
{
struct P
{
  double x, y;
};
using Poly = std::vector<P>;
using Shape = std::vector<Poly>; // union of filled polygons; a polygon marked as hole is drawn in white
struct Part
{
  Poly poly;
  bool hole;
};
using Parts = std::vector<Part>;

const double kPi = 3.14159265358979323846;

Poly rect(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

// Regular polygon approximating a circle arc from a0 to a1 (radians), n segments.
Poly arc(double cx, double cy, double r, double a0, double a1, int n)
{
  Poly p;
  for (int k = 0; k <= n; ++k) {
    const double a = a0 + (a1 - a0) * k / n;
    p.push_back({cx + r * std::cos(a), cy + r * std::sin(a)});
  }
  return p;
}

Poly circle(double cx, double cy, double r, int n = 32)
{
  Poly p = arc(cx, cy, r, 0, 2 * kPi, n);
  p.pop_back();
  return p;
}

P rotate(const P &p, double a, double cx = 0, double cy = 0)
{
  const double c = std::cos(a), s = std::sin(a);
  return {cx + c * (p.x - cx) - s * (p.y - cy), cy + s * (p.x - cx) + c * (p.y - cy)};
}

// Smooth bend: points beyond x0 turn about (x0, 0) by an angle growing linearly to \e total at x0 + len.
Parts bend(Parts parts, double x0, double len, double total)
{
  for (Part &pt : parts)
    for (P &p : pt.poly)
      if (p.x > x0)
        p = rotate(p, total * std::min(1.0, (p.x - x0) / len), x0, 0);
  return parts;
}

// Key: round bow with a hole, a blade, teeth along the lower edge. Deformed: the blade is bent by 12 deg.
Parts key(bool deformed)
{
  Parts k;
  k.push_back({circle(-85, 0, 45), false});
  k.push_back({circle(-100, 0, 14, 20), true});
  Poly blade{{-50, -13}, {120, -13}, {135, 0}, {120, 10}};
  // teeth: (x, depth) from the tip back towards the bow
  const double teeth[][2] = {{112, 22}, {100, 16}, {88, 28}, {76, 18}, {64, 26}, {52, 14}, {40, 10}};
  for (const auto &t : teeth)
    blade.push_back({t[0], 10 + t[1] * 0.9}), blade.push_back({t[0] - 6, 10});
  blade.push_back({-50, 10});
  k.push_back({blade, false});
  return deformed ? bend(k, -30, 160, 12 * kPi / 180) : k;
}

// One arm of the pliers (side -1 or +1: jaw + handle) turned by side * half about the pivot, with the pivot's
// rivet: the rigid part of the articulated template (vpMorphArticulation).
Parts pliersArm(double side, double half)
{
  // Arm in its own frame: jaw towards +x on one side of the axis, handle towards -x on the other side.
  Poly jaw{{-8, 0}, {10, -14 * side}, {70, -12 * side}, {100, -3 * side}, {100, 1 * side}, {10, 3 * side}};
  Poly handle{{8, 0}, {-15, 10 * side}, {-150, 26 * side}, {-158, 20 * side}, {-155, 10 * side}, {-20, -3 * side}};
  Parts out;
  for (Poly *p : {&jaw, &handle}) {
    for (P &q : *p)
      q = rotate(q, side * half);
    out.push_back({*p, false});
  }
  return out;
}

Parts rivet() { return {{circle(0, 0, 17, 24), false}, {circle(0, 0, 5, 12), true}}; }

const double kPliersClosedHalf = 4.0, kPliersOpenedHalf = 20.0; // deg: half the angle between the jaws

// Pliers: two crossed arms (jaw + handle) about a pivot, closed (jaws 8 deg apart). The deformed variant, opened
// wider, is openedPliers(): the arms' own drawings turned.
Parts pliers(bool)
{
  const double half = kPliersClosedHalf * kPi / 180;
  Parts out;
  for (double side : {-1.0, 1.0})
    for (const Part &p : pliersArm(side, half))
      out.push_back(p);
  for (const Part &p : rivet())
    out.push_back(p);
  return out;
}

// The closed pliers' two arms, each with the rivet, drawn alone in the template's frame.
Parts pliersPart(int k)
{
  Parts out = pliersArm(k == 0 ? -1.0 : 1.0, kPliersClosedHalf * kPi / 180);
  for (const Part &p : rivet())
    out.push_back(p);
  return out;
}

// Wedge (door stop): a long thin triangle with a finger notch. Deformed: the top face sags by 10 px.
Parts wedge(bool deformed)
{
  Poly w{{-120, 40}, {-120, -30}, {-90, -36}};
  const double sag = deformed ? 10.0 : 0.0;
  for (int k = 1; k <= 10; ++k) {
    const double t = k / 10.0, x = -90 + 220 * t;
    w.push_back({x, -36 + 34 * t + sag * 4 * t * (1 - t)});
  }
  w.push_back({130, 40});
  // finger notch in the base
  w.push_back({-40, 40});
  w.push_back({-55, 28});
  w.push_back({-75, 28});
  w.push_back({-90, 40});
  return {{w, false}};
}

// Open-end wrench with a ring at the other end. Deformed: the handle is bent by 15 deg.
Parts wrench(bool deformed)
{
  Parts w;
  w.push_back({{{-95, -11}, {75, -13}, {75, 13}, {-95, 11}}, false});
  // open end: a disc with a slot facing +x
  Poly head = arc(100, 0, 36, 0.45, 2 * kPi - 0.45, 28);
  head.push_back({106, -14}); // parallel-sided slot
  head.push_back({106, 14});
  w.push_back({head, false});
  w.push_back({circle(-115, 0, 28), false});
  w.push_back({circle(-115, 0, 14, 12), true});
  return deformed ? bend(w, -60, 120, -15 * kPi / 180) : w;
}

// Screwdriver: ribbed handle, ferrule, shaft and flat tip. Deformed: the shaft is bent by 10 deg.
Parts screwdriver(bool deformed)
{
  Parts s;
  Poly handle{{-140, -14}, {-130, -22}};
  for (int k = 0; k < 5; ++k) { // ribs on the upper edge
    const double x = -120 + 20 * k;
    handle.push_back({x, -22});
    handle.push_back({x + 4, -19});
    handle.push_back({x + 8, -22});
  }
  handle.push_back({-20, -22});
  handle.push_back({-10, -12});
  handle.push_back({-10, 12});
  handle.push_back({-20, 22});
  handle.push_back({-130, 22});
  handle.push_back({-140, 14});
  s.push_back({handle, false});
  s.push_back({rect(-12, -8, 5, 8), false});
  s.push_back({{{0, -4}, {110, -4}, {128, -2}, {128, 2}, {110, 4}, {0, 4}}, false});
  return deformed ? bend(s, 5, 120, 10 * kPi / 180) : s;
}

// Claw hammer: handle, head, curved claw. Deformed: the handle is bent by 12 deg.
Parts hammer(bool deformed)
{
  Parts h;
  h.push_back({{{-140, -10}, {70, -13}, {70, 13}, {-140, 12}}, false});
  // head: striking face below, claw above (along -y), centred on x = 85
  Poly head{{65, 70}, {105, 70}, {105, 55}, {100, 20}, {100, -20}};
  // claw: curving back towards -x while going up, ending in a split tip
  const Poly outer = arc(40, -20, 60, 0.0, -1.45, 10);
  for (const P &p : outer)
    head.push_back(p);
  head.push_back({38, -82});
  const Poly inner = arc(40, -20, 45, -1.5, -0.2, 10);
  for (const P &p : inner)
    head.push_back(p);
  head.push_back({70, -12});
  head.push_back({65, 20});
  head.push_back({60, 55});
  h.push_back({head, false});
  // the head stays straight; the handle bends towards its free end (-x)
  if (!deformed)
    return h;
  for (P &p : h[0].poly)
    if (p.x < 40)
      p = rotate(p, 12 * kPi / 180 * std::min(1.0, (40 - p.x) / 180), 40, 0);
  return h;
}

// Renders parts scaled by s, rotated by theta (radians, counter-clockwise in the (u, v) axes) about the
// object origin, which lands at image point (u0, v0).
vpImage<unsigned char> render(const Parts &parts, double u0, double v0, double theta = 0.0, double s = 1.0)
{
  const int W = 640, H = 480, shift = 4; // sub-pixel vertex positions: 1/16 px
  cv::Mat img(H, W, CV_8UC1, cv::Scalar(255));
  for (bool holes : {false, true})
    for (const Part &pt : parts) {
      if (pt.hole != holes)
        continue;
      std::vector<cv::Point> q;
      for (const P &p : pt.poly) {
        const P r = rotate({p.x * s, p.y * s}, theta);
        q.emplace_back(cvRound((u0 + r.x) * (1 << shift)), cvRound((v0 + r.y) * (1 << shift)));
      }
      cv::fillPoly(img, std::vector<std::vector<cv::Point>>{q}, cv::Scalar(holes ? 255 : 0), cv::LINE_8, shift);
    }
  vpImage<unsigned char> I(H, W);
  for (int r = 0; r < H; ++r)
    for (int c = 0; c < W; ++c)
      I[static_cast<unsigned int>(r)][static_cast<unsigned int>(c)] = img.at<unsigned char>(r, c);
  return I;
}

/*
  The pliers opened wider (jaws 40 deg apart): each arm's drawing (pliersPart()) turned about the pivot (u0, v0) by
  +-(kPliersOpenedHalf - kPliersClosedHalf), its texels resampled bilinearly, and the two laid over each other (the
  darker texel). Why not the arms' polygons drawn again at the new angle: a binary texel grid cuts a turned polygon
  elsewhere, and an arm's two drawings differed by up to half a texel at its tips, 0.2 % of its length, the depth of
  a millimetre at 0.5 m between the opened pliers and their template posed at the same opening. A real pliers opens
  with the same arms.
*/
vpImage<unsigned char> openedPliers(double u0, double v0)
{
  const double turn = (kPliersOpenedHalf - kPliersClosedHalf) * kPi / 180;
  vpImage<unsigned char> out;
  for (int k : {0, 1}) {
    const vpImage<unsigned char> arm = render(pliersPart(k), u0, v0);
    if (k == 0)
      out.resize(arm.getHeight(), arm.getWidth(), 255);
    // Each output texel reads the arm where the turn brings it from (the inverse turn), bilinearly.
    const double a = k == 0 ? -turn : turn, c = std::cos(a), s = std::sin(a);
    const int W = static_cast<int>(arm.getWidth()), H = static_cast<int>(arm.getHeight());
    auto at = [&](int x, int y) { return x < 0 || y < 0 || x >= W || y >= H ? 255.0 : double(arm[y][x]); };
    for (int v = 0; v < H; ++v)
      for (int u = 0; u < W; ++u) {
        const double x = u0 + c * (u - u0) + s * (v - v0), y = v0 - s * (u - u0) + c * (v - v0);
        const int x0 = static_cast<int>(std::floor(x)), y0 = static_cast<int>(std::floor(y));
        const double fx = x - x0, fy = y - y0;
        const double g = (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
                         fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
        unsigned char &o = out[static_cast<unsigned int>(v)][static_cast<unsigned int>(u)];
        o = std::min(o, static_cast<unsigned char>(std::lround(g)));
      }
  }
  return out;
}

bool save(const vpImage<unsigned char> &I, const std::filesystem::path &file)
{
  vpImageIo::write(I, file.string());
  try {
    const vpMorphContour c = vpMorphContourExtractor().extract(I);
    double umin = 1e9, umax = -1e9, vmin = 1e9, vmax = -1e9;
    for (std::size_t k = 0; k < c.size(); ++k) {
      umin = std::min(umin, c.x(k));
      umax = std::max(umax, c.x(k));
      vmin = std::min(vmin, c.y(k));
      vmax = std::max(vmax, c.y(k));
    }
    std::cout << file.string() << ": " << c.size() << " vertices, bounding box " << umax - umin << " x " << vmax - vmin
              << " px" << std::endl;
    return true;
  } catch (const vpException &e) {
    std::cerr << file.string() << ": contour extraction failed: " << e.getMessage() << std::endl;
    return false;
  }
}
} // namespace

/*
  --layout SRC OUT [--size PX]: every silhouette of folder (or list file) SRC laid out as a bench object in OUT/NAME.png
  (vpMorphSilhouetteLayout: either polarity and any size in, black on white, PX across, centred, anti-aliased out),
  its NAME-deformed.png and NAME-deformed-mask.png, when beside it, in its frame. An image that cannot be laid out
  is named with its reason and skipped; the exit status is 1 if any was.
*/
int layout(int argc, char **argv)
{
  std::string src, out;
  unsigned long size = 300;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--size" && i + 1 < argc) {
      char *end = nullptr;
      size = std::strtoul(argv[++i], &end, 10);
      if (*end != '\0' || size < 16 || size > 4000) {
        std::cerr << "vispmorph-make-data: --size needs an integer in 16..4000\n";
        return 2;
      }
    } else if (src.empty())
      src = a;
    else if (out.empty())
      out = a;
    else {
      std::cerr << "Usage: vispmorph-make-data --layout SRC_DIR|LIST OUT_DIR [--size PX]\n";
      return 2;
    }
  }
  if (src.empty() || out.empty()) {
    std::cerr << "Usage: vispmorph-make-data --layout SRC_DIR|LIST OUT_DIR [--size PX]\n";
    return 2;
  }
  try {
    std::filesystem::create_directories(out);
    bool ok = true;
    unsigned int done = 0;
    for (const vpMorphBenchObjectSet::Source &s : vpMorphBenchObjectSet::listImages(src)) {
      try {
        const vpMorphSilhouetteLayout l(vpMorphSilhouetteLayout::read(s.path), static_cast<unsigned int>(size));
        vpImageIo::write(l.image(), out + "/" + s.name + ".png");
        const std::filesystem::path p(s.path);
        for (const std::string variant : {"-deformed", "-deformed-mask"}) {
          const std::filesystem::path v = p.parent_path() / (p.stem().string() + variant + p.extension().string());
          if (std::filesystem::is_regular_file(v))
            vpImageIo::write(l.apply(vpMorphSilhouetteLayout::read(v.string())), out + "/" + s.name + variant + ".png");
        }
        ++done;
      } catch (const vpException &e) {
        std::cerr << "vispmorph-make-data: skipped " << s.path << ": " << e.getStringMessage() << std::endl;
        ok = false;
      }
    }
    std::cout << done << " objects laid out in " << out << std::endl;
    return ok ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cerr << "vispmorph-make-data: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
}

int main(int argc, char **argv)
{
  if (argc >= 2 && std::string(argv[1]) == "--layout")
    return layout(argc, argv);
  if (argc != 2 || std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help") {
    std::cerr << "Usage: " << argv[0] << " OUTDIR\n"
              << "Writes OUTDIR/objects/<name>[-deformed].png, OUTDIR/demo/{key,pliers}-view.png and OUTDIR/joints/.\n"
              << "       " << argv[0] << " --layout SRC_DIR|LIST OUT_DIR [--size PX]\n"
              << "Lays out any silhouettes (either polarity, any size) as bench objects: OUT_DIR/<name>.png, black on\n"
              << "white, PX (default 300) across, centred, anti-aliased; <name>-deformed[-mask].png beside one in its "
                 "frame.\n";
    return argc == 2 ? EXIT_SUCCESS : EXIT_FAILURE;
  }
  const std::filesystem::path out(argv[1]);
  try {
    std::filesystem::create_directories(out / "objects");
    std::filesystem::create_directories(out / "demo");
    const std::vector<std::pair<std::string, std::function<Parts(bool)>>> objects{
        {"key", key},       {"pliers", pliers},           {"wedge", wedge},
        {"wrench", wrench}, {"screwdriver", screwdriver}, {"hammer", hammer}};
    bool ok = true;
    for (const auto &o : objects) {
      ok &= save(render(o.second(false), 320, 240), out / "objects" / (o.first + ".png"));
      ok &= save(o.first == "pliers" ? openedPliers(320, 240) : render(o.second(true), 320, 240),
                 out / "objects" / (o.first + "-deformed.png"));
    }
    // The pliers' joint: part 1 (side +1) turns counter-clockwise in the image axes when the jaws open; from
    // closed (jaws touching: -2 x 4 deg) to wide open. In the deformed variant each arm turned by 16 deg.
    std::filesystem::create_directories(out / "joints");
    for (int k : {0, 1})
      ok &= save(render(pliersPart(k), 320, 240), out / "joints" / ("pliers-part" + std::to_string(k) + ".png"));
    {
      std::ofstream f(out / "joints" / "pliers.json");
      const double turn = kPliersOpenedHalf - kPliersClosedHalf; // each arm's, in the deformed variant
      f << "{\n  \"parts\": [\"pliers-part0.png\", \"pliers-part1.png\"],\n  \"pivot\": [320, 240],\n"
        << "  \"range_deg\": [" << -2 * kPliersClosedHalf << ", 60],\n  \"deformed_turns_deg\": [" << -turn << ", "
        << turn << "]\n}\n";
      ok &= static_cast<bool>(f);
    }
    ok &= save(render(key(false), 350, 220, 140 * kPi / 180), out / "demo" / "key-view.png");
    ok &= save(render(pliers(false), 290, 255, -100 * kPi / 180, 0.9), out / "demo" / "pliers-view.png");
    return ok ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const std::exception &e) {
    std::cerr << "Error: " << e.what() << std::endl;
    return EXIT_FAILURE;
  }
}
