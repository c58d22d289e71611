// Loads a BVH through an installed legwork and prints the body's size.
#include <legwork/core/measure.hpp>
#include <legwork/io/bvh.hpp>

#include <cstdio>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer FILE.bvh\n");
    return 2;
  }
  try {
    auto motion = legwork::io::load_bvh(argv[1]);
    auto body = legwork::measure_body(motion.skeleton);
    std::printf("%d joints, %d frames, %.2f m tall\n", motion.joint_count(), motion.frame_count(), body.standing_height);
  } catch (const legwork::Error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
