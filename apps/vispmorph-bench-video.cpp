#include "vispmorph-bench-video.h"

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>

#include <visp3/core/vpImageConvert.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpXmlParserCamera.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/io/vpVideoWriter.h>
#include <visp3/morph/vpMorphDrawing.h>
#include <visp3/morph/vpMorphException.h>
#include <visp3/morph_sim/vpMorphTagPoseEstimator.h>
#include <visp3/morph_vs/vpFeatureMorph.h>
#include <visp3/morph_vs/vpServoMorph.h>

namespace fs = std::filesystem;

namespace
{
// One run's files: the frames as recorded, the overlays and their video.
class Recorder
{
public:
  Recorder(const std::string &dir, const vpMorphBenchScenario &sc, const std::string &controller, double fps)
    : m_dir(dir), m_sc(sc), m_controller(controller), m_fps(fps)
  {
    fs::create_directories(dir + "/frames");
    fs::create_directories(dir + "/overlay");
  }
  ~Recorder()
  {
    for (vpVideoWriter *w : {m_frames.get(), m_overlays.get()})
      if (w)
        w->close();
  }
  unsigned int frames() const { return m_count; }

  void operator()(const vpMorphBench::Frame &f)
  {
    char name[64];
    std::snprintf(name, sizeof name, "/frames/frame-%04u.png", m_count);
    vpImageIo::write(f.image, m_dir + name);
    vpImage<vpRGBa> O;
    vpImageConvert::convert(f.image, O);
    draw(f, O);
    std::snprintf(name, sizeof name, "/overlay/overlay-%04u.png", m_count);
    vpImageIo::write(O, m_dir + name);
    vpImage<vpRGBa> F;
    vpImageConvert::convert(f.image, F);
    save(m_frames, "/frames.avi", F);
    save(m_overlays, "/overlay.avi", O);
    ++m_count;
  }

private:
  // A frame of the video \e file (MJPG, opened at the first frame).
  void save(std::unique_ptr<vpVideoWriter> &w, const char *file, vpImage<vpRGBa> &I) const
  {
    if (!w) {
      w.reset(new vpVideoWriter);
      w->setFileName(m_dir + file);
      const char *c = "MJPG"; // OpenCV's four-character code, its characters' bytes low first
      w->setCodec(c[0] | (c[1] << 8) | (c[2] << 16) | (c[3] << 24));
      w->setFramerate(m_fps);
      w->open(I);
    }
    w->saveFrame(I);
  }
  // The controller's state (VISPMorph's: the servo's or its features'), then the run's caption at the bottom.
  void draw(const vpMorphBench::Frame &f, vpImage<vpRGBa> &O) const
  {
    if (const vpServoMorph *servo = f.controller.servo()) {
      servo->draw(O, vpColor::red, vpColor::orange, vpColor::green, 2);
    } else {
      const std::pair<const vpFeatureMorph *, const vpFeatureMorph *> s = f.controller.features();
      const vpCameraParameters cam = m_sc.estimatedCamera(m_sc.camera);
      if (s.second && s.second->isBuilt())
        s.second->draw(cam, O, vpColor::green, 3);
      if (s.first && s.first->isBuilt())
        s.first->draw(cam, O, vpColor::red, 1);
    }
    double t = 0, r = 0;
    vpMorphTagPoseEstimator::poseDifference(m_sc.cdMo, f.cMo, t, r);
    const std::string state = f.command.stop ? "  stop: " + f.command.reason : f.command.converged ? "  converged" : "";
    char line[160];
    std::snprintf(line, sizeof line, "period %u  truth: %.1f mm, %.2f deg%s", f.iteration, 1000 * t, vpMath::deg(r),
                  state.c_str());
    const std::vector<std::string> caption = {
        m_sc.set + " #" + std::to_string(m_sc.index) + "  " + m_sc.object + "  " + m_controller, line};
    vpMorphDrawing::drawTextBand(
        O, caption, vpImagePoint(O.getHeight() - 4 - vpMorphDrawing::textBand(caption, vpImagePoint()).getHeight(), 4),
        vpColor::white);
  }

  std::string m_dir;
  vpMorphBenchScenario m_sc;
  std::string m_controller;
  double m_fps;
  std::unique_ptr<vpVideoWriter> m_frames, m_overlays;
  unsigned int m_count = 0;
};
} // namespace

int recordRuns(const vpMorphBench &bench, const std::vector<vpMorphBenchScenario> &scenarios,
               const std::vector<std::string> &controllers, const std::string &out)
{
  for (const vpMorphBenchScenario &sc : scenarios)
    for (const std::string &c : controllers) {
      const std::string dir = out + "/video/" + sc.set + "-" + std::to_string(sc.index) + "-" + c;
      fs::remove_all(dir);
      unsigned int frames = 0;
      vpMorphBenchResult r;
      {
        Recorder rec(dir, sc, c, 1.0 / bench.settings().samplingTime);
        r = bench.run(sc, c, [&rec](const vpMorphBench::Frame &f) { rec(f); });
        frames = rec.frames();
      }
      // What vispmorph-replay needs: the templates the run recognised from, and the camera that took the frames.
      bench.database(sc.variant, sc.set).save(dir + "/db.json");
      vpXmlParserCamera xml;
      if (xml.save(sc.camera, dir + "/camera.xml", "bench", sc.width, sc.height) != vpXmlParserCamera::SEQUENCE_OK)
        throw vpMorphException(vpMorphException::ioError, "cannot write " + dir + "/camera.xml");
      std::cout << sc.set << " #" << sc.index << " " << sc.object << " " << c << ": "
                << (r.success ? "success" : r.failure) << " (" << r.iterations << " it), " << frames << " frames in "
                << dir << "/\n  replay: vispmorph-replay '" << dir << "/frames/frame-%04d.png' --db " << dir
                << "/db.json --camera-xml " << dir << "/camera.xml --camera-name bench --mask-tags --out " << dir
                << "/replay" << std::endl;
    }
  return 0;
}
