#pragma once
// Private: the serialized block layout and the in-memory view of a Database.
#include <legwork/accent/database.hpp>

#include <nanoflann.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#ifndef LEGWORK_ACCENT_TREE_DIM
#define LEGWORK_ACCENT_TREE_DIM 5
#endif

namespace legwork::accent {

inline constexpr std::uint32_t kEndianTag = 0x01020304u;

// Fixed header at offset 0 (little-endian; 160 bytes).
struct FileHeader {
  char magic[8];
  std::uint32_t version;
  std::uint32_t endian;
  std::uint64_t file_bytes;
  std::uint64_t checksum;  // hash of the whole block with this field zeroed
  std::uint32_t window_count, pose_count, joint_count, class_count;
  std::uint32_t feature_dim, window;
  std::uint64_t meta_offset, meta_bytes;       // JSON: skeleton, normalisation, classes, trials
  std::uint64_t feature_offset[2];             // float[window_count][kDim] per hand
  std::uint64_t align_offset;                  // AlignXZ[window_count]
  std::uint64_t source_offset;                 // WindowSource[window_count]
  std::uint64_t pose_offset;                   // float[pose_count][joint_count][4]
  std::uint64_t head_up_offset;                // float[pose_count][3]: the head's up axis, model space
  std::uint64_t contact_offset;                // uint8[pose_count][2]: foot in contact (left, right), 0/1
  std::uint64_t index_offset, index_bytes;     // the stored KD-trees (since version 3; layout in database_index.cpp)
  std::uint64_t travel_offset;                 // Travel[window_count]: the performer's head travel (since version 5)
  std::uint64_t order_offset;                  // u32[2][window_count] the window of each stored feature row, then
                                               // u32[2][window_count] the row of each window, per hand (since
                                               // version 7: rows in their trees' leaf order)
  std::uint64_t space_offset;                  // f64 scale[kRawDim], then f64 projection[kDim * kDim]: the
                                               // feature space's numbers (since version 8; in the JSON before)
};
static_assert(sizeof(FileHeader) == 168);

std::uint64_t block_checksum(std::span<const std::byte> block);

// The KD-trees index only the first kTreeDim projected dimensions (the
// principal ones). Distances over a prefix never exceed the full distance, so
// the trees prune with lower bounds and the search stays exact (search.cpp).
inline constexpr int kTreeDim = LEGWORK_ACCENT_TREE_DIM;

// nanoflann reads the mapped features in place through this adaptor.
struct FeatureCloud {
  const float* data = nullptr;
  std::size_t count = 0;
  std::size_t kdtree_get_point_count() const { return count; }
  float kdtree_get_pt(std::size_t i, std::size_t d) const { return data[i * kDim + d]; }
  template <class Box>
  bool kdtree_get_bbox(Box&) const { return false; }
};
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, FeatureCloud>, FeatureCloud,
                                                    kTreeDim, std::uint32_t>;

struct ClassIndex {
  std::array<FeatureCloud, 2> cloud;
  std::array<std::unique_ptr<KdTree>, 2> tree;
};

// The stored index (database_index.cpp). Trees in order: per class (left,
// right hand); a one-class database has one pair over every window (in `all`).
// (Version 3 also stored a whole-database pair beside the class trees: it
// doubled the index and its load time; searches over several classes now
// walk their class trees with one shared result set.) Each tree is nanoflann's own serialization (saveIndex) of a tree
// over kTreeDim dimensions with leaves of kIndexLeafSize points.
inline constexpr int kIndexLeafSize = 16;
// Serializes the trees over `features` (per hand, window-major) and the class
// ranges. Since version 7 each tree's rows are reordered in place into the
// tree's leaf order (a leaf's rows lie in one run of memory and the stored
// permutation is the identity); window_of_row[hand][row] receives the window
// each row holds. Rows never leave their class's range.
std::vector<std::byte> serialize_index(const std::array<Feature*, 2>& features, std::size_t windows,
                                       const std::vector<std::pair<int, int>>& ranges,
                                       std::array<std::vector<std::uint32_t>, 2>& window_of_row);
// Validates the section (sizes, counts, every node and point index; declared
// sizes are never trusted) and fills d.all / d.index from it. Returns false,
// leaving no trees, when the section was written by another nanoflann node
// layout (the caller rebuilds); throws legwork::Error naming `source` when it
// is malformed.
bool load_index(Database::Impl& d, std::span<const std::byte> section, const std::string& source);

// What the block's JSON metadata section holds; shared by the builder's parts
// and the opened database.
struct DatabaseMeta {
  Skeleton skeleton;
  double height = 0;
  BuildSettings settings;
  FeatureSpace space;
  double typical_distance = 1;
  Travel travel_scale{1, 1, 1, 1};  // 1 / standard deviation of each travel term over the windows
  std::vector<std::string> classes;
  std::vector<std::pair<int, int>> ranges;
  std::vector<TrialInfo> trials;
};

struct Database::Impl {
  std::vector<std::byte> owned;  // in-memory block (empty when mapped)
  void* map = nullptr;
  std::size_t map_bytes = 0;
  const std::byte* base = nullptr;
  std::size_t size = 0;
  FileHeader header{};

  DatabaseMeta meta;

  // Feature rows per hand in storage order (version 7: each tree's leaf
  // order); the search reads rows, everything else windows.
  const Feature* features[2] = {nullptr, nullptr};
  const std::uint32_t* window_of_row[2] = {nullptr, nullptr};  // storage row -> window
  const std::uint32_t* row_of_window[2] = {nullptr, nullptr};  // window -> storage row
  const AlignXZ* align = nullptr;
  const WindowSource* sources = nullptr;
  const float* poses = nullptr;
  const float* head_up = nullptr;
  const std::uint8_t* contacts = nullptr;
  const Travel* travel = nullptr;

  std::vector<ClassIndex> index;  // per class when there is more than one class
  ClassIndex all;                 // a one-class database's trees (over every window)
  int leaf_size = kIndexLeafSize; // of the trees above
  bool indexed = false;           // the trees above are built or loaded

  ~Impl();
};

// Serializes the parts into a block (used by the builder).
struct BlockParts {
  DatabaseMeta meta;
  std::vector<Feature> features[2];
  std::vector<AlignXZ> align;
  std::vector<WindowSource> sources;
  std::vector<float> poses;  // pose_count * joint_count * 4
  std::vector<float> head_up;  // pose_count * 3
  std::vector<std::uint8_t> contacts;  // pose_count * 2
  std::vector<Travel> travel;          // window_count
};
std::vector<std::byte> serialize_block(const BlockParts& parts);

}  // namespace legwork::accent
