// Scratch: dumps per-frame wip Info + true depths of every walk (CSV) for depth analysis.
#include <legwork/eval/wip.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/wip/offline/run.hpp>
#include <cstdio>
#include <filesystem>
#include <algorithm>
using namespace legwork;
int main(int argc, char** argv) {
  std::string dir = argc > 1 ? argv[1] : "/work/shared/data/cmu/bvh/walking";
  std::vector<std::string> files;
  for (auto& e : std::filesystem::directory_iterator(dir)) if (e.path().extension() == ".bvh") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  std::printf("trial,subject,turning,leg,t,walking,lead,since,stride,apexL,apexR,cL,cR,hL,hR,vL,vR,pL,pR,zL,zR,px,pz,hd,turn\n");
  for (auto& file : files) {
    io::BvhReadOptions o; o.drop_first_frame = true;
    Motion m = io::read_bvh(file, o).motion;
    std::string name = std::filesystem::path(file).stem().string();
    wip::Settings s; s.mapping.depth = wip::DepthMapping::Document;
    auto model = wip::make_model(m.skeleton, s);
    wip::RunOptions ro; ro.calibrate = false; ro.keep_poses = false;
    auto frames = wip::run_wip(model, tracker_frames_from_motion(m, s.signal.rate), ro).frames;
    auto truth = eval::true_depths(m, s.signal.rate);
    bool turning = truth.heading_range_deg > eval::kTurningDegrees;
    size_t n = std::min(frames.size(), truth.time.size());
    for (size_t i = 0; i < n; ++i) {
      auto& f = frames[i];
      std::printf("%s,%s,%d,%.5f,%.4f,%d,%d,%.4f,%.4f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%d,%d,%.5f,%.5f,%.4f,%.4f,%.5f,%.5f\n", name.c_str(),
        eval::subject_of(name).c_str(), turning, model.leg_length(), f.time, f.walking, f.lead, std::min(f.since_strike, 99.0), f.stride_period,
        f.apex_estimate[0], f.apex_estimate[1], f.cycle[0], f.cycle[1], f.h[0], f.h[1], f.v[0], f.v[1], (int)f.phase[0], (int)f.phase[1],
        truth.z[0][i], truth.z[1][i], truth.pelvis[i].x(), truth.pelvis[i].z(), f.heading, f.turn_rate);
    }
  }
}
