// The C++ API doing what examples/c/main.c does through the C API, writing
// the same CSV, so CTest can check that the two are identical byte for byte.
#include <legwork/accent/accent.hpp>
#include <legwork/core/fk.hpp>
#include <legwork/io/bvh.hpp>

#include <cstdio>

int main(int argc, char** argv) {
  using namespace legwork;
  if (argc != 4) {
    std::fprintf(stderr, "usage: capi_reference DATABASE.lwdb TRIAL.bvh OUT.csv\n");
    return 2;
  }
  try {
    const accent::Database db = accent::load_database(argv[1]);
    io::BvhReadOptions o;
    o.drop_first_frame = true;
    const auto frames = tracker_frames_from_motion(io::load_bvh(argv[2], o), 90.0);
    accent::Settings settings;
    settings.user_height = 1.7;
    const accent::Model model = accent::make_model(db, settings);
    accent::State state(model);
    Pose pose(model.skeleton());
    std::vector<Transform> world(static_cast<std::size_t>(model.skeleton().joint_count()));
    std::FILE* out = std::fopen(argv[3], "w");
    if (!out) throw Error(std::string("cannot write ") + argv[3]);
    for (std::size_t f = 0; f < frames.size(); ++f) {
      const UpdateStatus s = accent::update(model, frames[f], state, pose.ref());
      forward_kinematics(model.skeleton(), pose, world);
      for (int j = 0; j < pose.joint_count(); ++j) {
        const Quat& q = pose.rotations[static_cast<std::size_t>(j)];
        const Vec3& p = world[static_cast<std::size_t>(j)].translation;
        std::fprintf(out, "%zu,%s,%d,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", f, status_name(s), j, q.w(), q.x(), q.y(), q.z(),
                     p.x(), p.y(), p.z());
      }
    }
    std::fclose(out);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "capi_reference: %s\n", e.what());
    return 1;
  }
  return 0;
}
