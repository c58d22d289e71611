#pragma once
// The accentuation motion database: a read-only, flat, memory-mappable block.
//
// Built offline (builder.hpp) and either kept in memory or written to a
// versioned binary file (layout in docs/accent.md) that loads by mmap in
// milliseconds. Windows are grouped by activity class (contiguous ranges), so
// a session can restrict matching to some classes. Per window: the projected
// left- and right-hand features (features.hpp), both hands' x/z over the window
// for rotation alignment, and the candidate pose (the window's last frame:
// local joint rotations on the database skeleton) with its source.
//
// Thread safety: a Database is immutable after construction (and after
// build_index()); any number of Accentuators may read it concurrently.
#include <legwork/accent/features.hpp>
#include <legwork/core/motion.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace legwork::accent {

// 2: per-pose foot contacts; 3: the KD-tree search index is stored in the file;
// 4: the checksum is XXH3-64 (was a serial FNV-1a);
// 5: per-window head travel (Travel) and its spread. 6: feature windows of
// kWindow samples kStride apart (features.hpp; the stride is stored in the
// metadata and checked). 7: each hand's feature rows stored in its KD-trees'
// leaf order, with the window of each row and the row of each window beside
// them. 8: the feature scale and projection as a binary section of doubles
// (bit for bit) instead of 17-digit JSON numbers, which were 16 KB of the 18 KB
// of metadata and three quarters of the fuzz target's time. 9: the checksum is
// the XXH3-64 of the two halves' XXH3-64s, so a load hashes them on two cores.
// Older files are refused with a "rebuild" message.
inline constexpr std::uint32_t kFormatVersion = 9;
// The first 8 bytes of every database file.
inline constexpr char kMagic[8] = {'L', 'W', 'A', 'C', 'C', 'E', 'N', 'T'};

// The performer's travel at a window's end, from the head trajectory (the
// user's is measured the same way from the headset): horizontal head speed
// over the last kTravelShort and kTravelLong seconds (m/s), vertical head
// velocity over the last kTravelVertical seconds (m/s, up positive) and head
// height over standing body height. Speeds are in database space (the user's
// divided by the user/database height ratio) and, for a time-scaled window,
// at the played speed.
inline constexpr int kTravelDim = 4;
using Travel = std::array<float, kTravelDim>;
inline constexpr double kTravelShort = 0.2, kTravelLong = 0.6, kTravelVertical = 0.1;

// Where a window came from (for reports and leave-one-out checks).
struct WindowSource {
  std::uint32_t pose = 0;   // index into the pose table (shared by speed variants)
  std::uint32_t trial = 0;  // index into Database::trials()
  std::uint32_t frame = 0;  // last frame of the window, at the database rate (T-pose dropped)
  std::uint16_t cls = 0;    // index into Database::classes()
  std::uint8_t speed = 0;   // index into BuildSettings::speeds (0 = original speed)
  std::uint8_t mirrored = 0;
};
static_assert(sizeof(WindowSource) == 16);

struct TrialInfo {
  std::string file, cls;
  int subject = 0, trial = 0;
  double correlation = 0;  // hand-foot Pearson |r| (see builder.hpp)
};

// Build parameters recorded in the database (for reports and reproducibility).
struct BuildSettings {
  double fps = 90.0;
  int hop = 4;  // samples between window ends
  double correlation_threshold = 0.1;
  std::vector<double> speeds{1.0};  // time-scale factors; speeds[0] = 1
  bool mirrored = false;
};

class Database {
 public:
  Database();
  ~Database();
  Database(Database&&) noexcept;
  Database& operator=(Database&&) noexcept;

  // Sizes.
  int window_count() const;
  int pose_count() const;
  int class_count() const;
  int joint_count() const { return skeleton().joint_count(); }

  // The database skeleton (roles resolved), its standing height (metres) and
  // build parameters.
  const Skeleton& skeleton() const;
  double height() const;
  const BuildSettings& settings() const;
  const FeatureSpace& feature_space() const;
  // Median distance from a window to its nearest window of another trial
  // (projected feature units): the scale for relative distance thresholds.
  double typical_distance() const;

  const std::vector<std::string>& classes() const;
  const std::vector<TrialInfo>& trials() const;
  // Index of a class by name, or -1.
  int find_class(const std::string& name) const;
  // Windows [first, last) of class c.
  std::pair<int, int> class_range(int c) const;

  // Per-window data (spans into the mapped block). hand: 0 = left, 1 = right.
  const Feature& feature(int hand, int window) const;
  const AlignXZ& align(int window) const;
  const WindowSource& source(int window) const;
  // Candidate pose rotations (joint_count quaternions, float w,x,y,z).
  std::span<const float> pose_rotations(int pose) const;
  void pose_rotation(int pose, std::span<Quat> out) const;
  // The head joint's up axis in the candidate pose (model space, unit): how
  // upright the performer's head was (a swimmer's is near horizontal).
  Vec3 head_up(int pose) const;
  // Whether the performer's left [0] and right [1] foot was planted on the
  // floor in the candidate pose (detected from foot height and speed at build
  // time; never while the head was far from upright, e.g. swimming).
  std::array<bool, 2> contact(int pose) const;
  // The performer's head travel at the end of a window (Travel above), and
  // 1 / its standard deviation per term over the database (the scale the
  // engine's travel distance uses).
  const Travel& travel(int window) const;
  const Travel& travel_scale() const;

  // Serialized block (what save() writes; in memory or mapped).
  std::span<const std::byte> bytes() const;
  bool is_mapped() const;

  // KD-trees per class and hand (nanoflann) for the Exact and Fast search
  // modes. A database from the builder or a file already has them (they are
  // stored in the block); this rebuilds them only when missing or when
  // another leaf size is asked for. Not thread-safe; call before sharing.
  void build_index(int leaf_size = 16);
  bool has_index() const;

  struct Impl;
  const Impl& impl() const { return *impl_; }

  // From a serialized block (validates it; throws legwork::Error naming `source`).
  static Database from_bytes(std::vector<std::byte> block, const std::string& source);

 private:
  friend Database load_database(const std::string&, const struct LoadOptions&);
  std::unique_ptr<Impl> impl_;
};

struct LoadOptions {
  bool verify_checksum = true;  // hash (XXH3-64) and scan the whole file (a few ms per 50 MB)
  bool build_index = true;      // KD-trees for the Exact/Fast search modes (read from the file's index section)
  bool use_mmap = true;         // false: read into memory
};
// Maps a database file. Throws legwork::Error naming the file when it is
// missing, truncated, corrupted (checksum), of another format version or not
// a legwork accent database at all.
Database load_database(const std::string& path, const LoadOptions& opt = {});
// Writes db.bytes() to path (throws legwork::Error on I/O failure).
void save_database(const std::string& path, const Database& db);

}  // namespace legwork::accent
