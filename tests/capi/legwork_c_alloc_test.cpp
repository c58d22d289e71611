// lw_avatar_update allocates nothing, for every method (global operator new
// counted while warmed-up avatars run over a real trial).
#include <legwork/legwork.h>

#include <gtest/gtest.h>

#include "alloc_counter.hpp"

#include <string>

namespace {

std::string sample(const std::string& rel) { return std::string(LEGWORK_SOURCE_DIR) + "/data/" + rel; }

TEST(CApiAlloc, UpdateIsAllocationFreeForIkWipWalkerAndCombined) {
  lw_skeleton* skel = nullptr;
  ASSERT_EQ(lw_skeleton_load_bvh(sample("cmu/bvh/walking/07_02.bvh").c_str(), &skel), LW_OK) << lw_last_error();
  lw_frame* frames = nullptr;
  int32_t n = 0;
  ASSERT_EQ(lw_frames_from_bvh(sample("cmu/bvh/walking/07_02.bvh").c_str(), 0, 1, &frames, &n), LW_OK);
  lw_model* models[4] = {nullptr, nullptr, nullptr, nullptr};
  ASSERT_EQ(lw_model_create_ik(skel, &models[0]), LW_OK) << lw_last_error();
  ASSERT_EQ(lw_model_create_wip(skel, &models[1]), LW_OK) << lw_last_error();
  ASSERT_EQ(lw_model_create_walker(sample("walks/normal.json").c_str(), &models[2]), LW_OK) << lw_last_error();
  ASSERT_EQ(lw_model_create_combined(nullptr, nullptr, skel, &models[3]), LW_OK) << lw_last_error();
  for (lw_model* m : models) {
    lw_avatar* a = nullptr;
    ASSERT_EQ(lw_avatar_create(m, &a), LW_OK);
    if (lw_model_method(m) == LW_METHOD_WIP || lw_model_method(m) == LW_METHOD_COMBINED) {
      ASSERT_EQ(lw_avatar_set_floor(a, frames[0].devices[LW_LEFT_FOOT].position[1], frames[0].devices[LW_RIGHT_FOOT].position[1]), LW_OK);
    }
    for (int32_t i = 0; i < 10; ++i) ASSERT_GE(lw_avatar_update(a, &frames[i]), 0);
    const long allocations = legwork::alloc_count::count_allocations([&] {
      for (int32_t i = 10; i < n; ++i) lw_avatar_update(a, &frames[i]);
    });
    EXPECT_EQ(allocations, 0) << "method " << lw_model_method(m);
    lw_avatar_destroy(a);
    lw_model_destroy(m);
  }
  lw_frames_free(frames);
  lw_skeleton_destroy(skel);
}

}  // namespace
