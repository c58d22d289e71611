// Database: the serialized block, its validation, mmap loading and KD-trees.
#include "database_impl.hpp"

#include <legwork/core/skeleton.hpp>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string_view>
#include <system_error>
#include <thread>
#include <type_traits>
#include <fcntl.h>
#include <fstream>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

// XXH3-64 (Debian libxxhash-dev): the file checksum runs at 20-40 GB/s
// instead of the ~1 GB/s of a serial FNV multiply chain. On x86-64 the
// library's runtime dispatch picks its AVX2/AVX-512 kernel (twice the
// baseline SSE2 speed on the project machine).
#define XXH_STATIC_LINKING_ONLY
#include <xxhash.h>
#if defined(__x86_64__) && __has_include(<xxh_x86dispatch.h>)
#define XXH_DISPATCH_DISABLE_REPLACE
#include <xxh_x86dispatch.h>
#define LEGWORK_XXH3_UPDATE XXH3_64bits_update_dispatch
#else
#define LEGWORK_XXH3_UPDATE XXH3_64bits_update
#endif

namespace legwork::accent {
namespace {

using json = nlohmann::json;

std::size_t align64(std::size_t n) { return (n + 63) & ~static_cast<std::size_t>(63); }

// The feature space section (version 8): scale, then projection, as doubles.
constexpr std::size_t kSpaceValues = kRawDim + kDim * kDim;

json vec3_json(const Vec3& v) { return json::array({v.x(), v.y(), v.z()}); }

json meta_json(const DatabaseMeta& p) {
  json j;
  const Skeleton& s = p.skeleton;
  json sk;
  sk["names"] = s.names;
  sk["parents"] = s.parents;
  json off = json::array(), ends = json::array();
  for (int i = 0; i < s.joint_count(); ++i) {
    off.push_back(vec3_json(s.rest_offsets[static_cast<std::size_t>(i)]));
    ends.push_back(s.has_end_site[static_cast<std::size_t>(i)] ? vec3_json(s.end_sites[static_cast<std::size_t>(i)]) : json(nullptr));
  }
  sk["rest_offsets_m"] = off;
  sk["end_sites_m"] = ends;
  j["skeleton"] = sk;
  j["height_m"] = p.height;
  j["build"] = {{"fps", p.settings.fps},
                {"hop", p.settings.hop},
                {"correlation_threshold", p.settings.correlation_threshold},
                {"speeds", p.settings.speeds},
                {"mirrored", p.settings.mirrored}};
  j["features"] = {{"window", kWindow},
                   {"stride", kStride},
                   {"raw_layout", "p0..p8 (xyz, head-relative m), v1..v8 (m/s), a2..a8 (m/s^2)"},
                   {"fps", p.space.fps},
                   {"group_weight", p.space.group_weight}};  // scale and projection: a binary section
  j["typical_distance"] = p.typical_distance;
  j["travel_scale"] = p.travel_scale;
  j["classes"] = p.classes;
  json ranges = json::array();
  for (auto [a, b] : p.ranges) ranges.push_back({a, b});
  j["class_ranges"] = ranges;
  json trials = json::array();
  for (const auto& t : p.trials)
    trials.push_back({{"file", t.file}, {"class", t.cls}, {"subject", t.subject}, {"trial", t.trial}, {"correlation", t.correlation}});
  j["trials"] = trials;
  return j;
}

[[noreturn]] void fail(const std::string& source, const std::string& what) {
  throw Error("accent database '" + source + "': " + what);
}

// The metadata JSON read field by field: every error names the field
// ("metadata field 'build.fps': expected a number, found string") and never
// echoes the JSON library's text (which quotes raw bytes of the file).
class MetaReader {
 public:
  explicit MetaReader(const std::string& source) : source_(source) {}
  const json& at(const json& obj, const std::string& path, const char* key) const {
    const std::string field = path.empty() ? key : path + "." + key;
    if (!obj.is_object()) fail(source_, "metadata field '" + path + "': expected an object, found " + obj.type_name());
    const auto it = obj.find(key);
    if (it == obj.end()) fail(source_, "metadata field '" + field + "' is missing; rebuild the database");
    return *it;
  }
  const json& array(const json& obj, const std::string& path, const char* key) const {
    const json& a = at(obj, path, key);
    if (!a.is_array())
      fail(source_, "metadata field '" + (path.empty() ? key : path + "." + key) + "': expected an array, found " + a.type_name());
    return a;
  }
  const json& at(const json& arr, const std::string& path, std::size_t i) const {
    if (!arr.is_array() || i >= arr.size())
      fail(source_, "metadata field '" + path + "': expected an array of at least " + std::to_string(i + 1) + " items");
    return arr[i];
  }
  template <class T>
  T get(const json& obj, const std::string& path, const char* key) const {
    return as<T>(at(obj, path, key), path.empty() ? key : path + "." + key);
  }
  template <class T>
  T as(const json& v, const std::string& field) const {
    static_assert(!std::is_integral_v<T> || std::is_same_v<T, bool>, "whole numbers: integer() (a float-to-int cast of 1e300 is undefined)");
    try {
      return v.get<T>();
    } catch (const json::exception&) {
      fail(source_, "metadata field '" + field + "': " + expected<T>() + ", found " + v.type_name() +
                        "; rebuild the database");
    }
  }
  int integer(const json& v, const std::string& field) const {
    if (!v.is_number_integer())
      fail(source_, "metadata field '" + field + "': expected a whole number, found " + v.type_name() + "; rebuild the database");
    const bool fits = v.is_number_unsigned() ? v.get<std::uint64_t>() <= 0x7fffffffu
                                             : v.get<std::int64_t>() >= -0x7fffffff - 1 && v.get<std::int64_t>() <= 0x7fffffff;
    if (!fits) fail(source_, "metadata field '" + field + "': " + v.dump() + " is out of range");
    return static_cast<int>(v.get<std::int64_t>());
  }
  int integer(const json& obj, const std::string& path, const char* key) const {
    return integer(at(obj, path, key), path.empty() ? key : path + "." + key);
  }
  std::vector<int> integers(const json& v, const std::string& field) const {
    if (!v.is_array()) fail(source_, "metadata field '" + field + "': expected an array, found " + v.type_name());
    std::vector<int> out;
    for (std::size_t i = 0; i < v.size(); ++i) out.push_back(integer(v[i], field + "[" + std::to_string(i) + "]"));
    return out;
  }
  Vec3 vec3(const json& v, const std::string& field) const {
    const auto a = as<std::vector<double>>(v, field);
    if (a.size() != 3) fail(source_, "metadata field '" + field + "': expected [x, y, z]");
    return {a[0], a[1], a[2]};
  }

 private:
  template <class T>
  static std::string expected() {
    if constexpr (std::is_same_v<T, bool>) return "expected true or false";
    else if constexpr (std::is_same_v<T, std::string>) return "expected a string";
    else if constexpr (std::is_arithmetic_v<T>) return "expected a number";
    else return "expected an array of the right length and type";
  }
  const std::string& source_;
};

Skeleton parse_skeleton(const MetaReader& r, const json& sk, const std::string& source) {
  const auto names = r.get<std::vector<std::string>>(sk, "skeleton", "names");
  const auto parents = r.integers(r.at(sk, "skeleton", "parents"), "skeleton.parents");
  const json& offsets = r.array(sk, "skeleton", "rest_offsets_m");
  const json& ends = r.array(sk, "skeleton", "end_sites_m");
  if (parents.size() != names.size() || offsets.size() != names.size() || ends.size() != names.size())
    fail(source, "metadata field 'skeleton': names, parents, rest_offsets_m and end_sites_m have different lengths");
  std::vector<Vec3> offset(names.size()), end(names.size());
  for (std::size_t i = 0; i < names.size(); ++i) {
    const std::string at = "[" + std::to_string(i) + "]";
    offset[i] = r.vec3(offsets[i], "skeleton.rest_offsets_m" + at);
    if (!ends[i].is_null()) end[i] = r.vec3(ends[i], "skeleton.end_sites_m" + at);
  }
  try {
    Skeleton s;
    for (std::size_t i = 0; i < names.size(); ++i) {
      s.add_joint(names[i], parents[i], offset[i]);
      s.end_sites[i] = end[i];
      s.has_end_site[i] = ends[i].is_null() ? 0 : 1;
    }
    s.validate();
    resolve_roles(s);
    return s;
  } catch (const Error& e) {
    fail(source, std::string("metadata field 'skeleton': ") + e.what());
  }
}

void parse_meta(DatabaseMeta& m, const std::string& text, const std::string& source) {
  const json j = json::parse(text, nullptr, false);
  if (j.is_discarded()) fail(source, "metadata is not valid JSON; rebuild the database");
  const MetaReader r(source);
  m.skeleton = parse_skeleton(r, r.at(j, "", "skeleton"), source);
  m.height = r.get<double>(j, "", "height_m");
  const json& b = r.at(j, "", "build");
  m.settings.fps = r.get<double>(b, "build", "fps");
  m.settings.hop = r.integer(b, "build", "hop");
  m.settings.correlation_threshold = r.get<double>(b, "build", "correlation_threshold");
  m.settings.speeds = r.get<std::vector<double>>(b, "build", "speeds");
  m.settings.mirrored = r.get<bool>(b, "build", "mirrored");
  const json& f = r.at(j, "", "features");
  if (r.integer(f, "features", "window") != kWindow) fail(source, "window size differs from this build's " + std::to_string(kWindow));
  if (r.integer(f, "features", "stride") != kStride) fail(source, "window stride differs from this build's " + std::to_string(kStride));
  m.space.fps = r.get<double>(f, "features", "fps");
  m.space.group_weight = r.get<std::array<double, 3>>(f, "features", "group_weight");
  m.typical_distance = r.get<double>(j, "", "typical_distance");
  m.travel_scale = r.get<Travel>(j, "", "travel_scale");
  m.classes = r.get<std::vector<std::string>>(j, "", "classes");
  m.ranges.clear();
  const json& ranges = r.array(j, "", "class_ranges");
  for (std::size_t i = 0; i < ranges.size(); ++i) {
    const auto ab = r.integers(r.at(ranges, "class_ranges", i), "class_ranges[" + std::to_string(i) + "]");
    if (ab.size() != 2) fail(source, "metadata field 'class_ranges[" + std::to_string(i) + "]': expected [first, end]");
    m.ranges.emplace_back(ab[0], ab[1]);
  }
  m.trials.clear();
  const json& trials = r.array(j, "", "trials");
  for (std::size_t i = 0; i < trials.size(); ++i) {
    const std::string at = "trials[" + std::to_string(i) + "]";
    const json& t = r.at(trials, "trials", i);
    m.trials.push_back({r.get<std::string>(t, at, "file"), r.get<std::string>(t, at, "class"), r.integer(t, at, "subject"),
                        r.integer(t, at, "trial"), r.get<double>(t, at, "correlation")});
  }
  if (m.ranges.size() != m.classes.size()) fail(source, "class ranges do not match the class list");
}

template <class T>
const T* section(const Database::Impl& d, std::uint64_t offset, std::uint64_t count, const std::string& source,
                 const char* what) {
  const std::uint64_t bytes = count * sizeof(T);
  if (offset % alignof(T) != 0 || offset > d.size || bytes > d.size - offset)
    fail(source, std::string("section '") + what + "' lies outside the file (truncated?)");
  return reinterpret_cast<const T*>(d.base + offset);
}

void validate_meta(const DatabaseMeta& m, const std::string& source);
void scan_contents(const Database::Impl& d, const std::string& source);
void open_row_order(Database::Impl& d, const std::string& source, bool verify);
std::uint64_t checksum_and_scan(const Database::Impl& d, bool& contents_ok);
void build_trees(Database::Impl& d, int leaf_size);

// Maps the pages of [offset, offset + bytes) of a mapped file in one call
// (instead of one fault per page as they are first read); a hint only.
void prefault(const Database::Impl& d, std::uint64_t offset, std::uint64_t bytes) {
#ifdef MADV_POPULATE_READ
  if (!d.map || offset >= d.size) return;
  const std::uint64_t page = 4096, start = offset & ~(page - 1);
  const std::uint64_t end = std::min<std::uint64_t>(d.size, offset + std::min<std::uint64_t>(bytes, d.size - offset));
  (void)::madvise(static_cast<char*>(d.map) + start, end - start, MADV_POPULATE_READ);
#else
  (void)d, (void)offset, (void)bytes;
#endif
}

// Validates the block in d.base/d.size and fills the views; with `index`,
// also the stored search index (rebuilt when another nanoflann wrote it).
void open_block(Database::Impl& d, const std::string& source, bool verify, bool index) {
  if (d.size < sizeof(FileHeader)) fail(source, "file is " + std::to_string(d.size) + " bytes, shorter than the header (truncated or not a database)");
  std::memcpy(&d.header, d.base, sizeof(FileHeader));
  const FileHeader& h = d.header;
  if (std::memcmp(h.magic, kMagic, sizeof(kMagic)) != 0) fail(source, "not a legwork accent database (bad magic)");
  if (h.endian != kEndianTag) fail(source, "written on a machine of other endianness");
  if (h.version != kFormatVersion)
    fail(source, "format version " + std::to_string(h.version) + ", but this legwork reads version " +
                     std::to_string(kFormatVersion) + "; rebuild it with 'legwork accent build'");
  if (h.file_bytes != d.size)
    fail(source, "header says " + std::to_string(h.file_bytes) + " bytes but the file has " + std::to_string(d.size) +
                     (d.size < h.file_bytes ? " (truncated)" : " (trailing data)"));
  if (h.feature_dim != static_cast<std::uint32_t>(kDim) || h.window != static_cast<std::uint32_t>(kWindow))
    fail(source, "feature layout (" + std::to_string(h.feature_dim) + " dims, window " + std::to_string(h.window) +
                     ") differs from this build's");
  bool contents_ok = true;
  if (verify) {
    prefault(d, 0, d.size);  // every byte is read
    const std::uint64_t sum = checksum_and_scan(d, contents_ok);
    if (sum != h.checksum) fail(source, "checksum mismatch: the file is corrupted");
  }
  const char* meta = reinterpret_cast<const char*>(section<char>(d, h.meta_offset, h.meta_bytes, source, "metadata"));
  parse_meta(d.meta, std::string(meta, h.meta_bytes), source);
  const double* space = section<double>(d, h.space_offset, kSpaceValues, source, "feature space");
  std::memcpy(d.meta.space.scale.data(), space, sizeof d.meta.space.scale);
  std::memcpy(d.meta.space.projection.data(), space + kRawDim, sizeof d.meta.space.projection);
  if (static_cast<std::uint32_t>(d.meta.skeleton.joint_count()) != h.joint_count) fail(source, "joint count disagrees with the skeleton");
  if (d.meta.classes.size() != h.class_count) fail(source, "class count disagrees with the class list");
  for (auto [a, b] : d.meta.ranges)
    if (a < 0 || b < a || static_cast<std::uint32_t>(b) > h.window_count) fail(source, "class range outside the windows");
  for (int hand = 0; hand < 2; ++hand)
    d.features[hand] = section<Feature>(d, h.feature_offset[hand], h.window_count, source, "features");
  d.align = section<AlignXZ>(d, h.align_offset, h.window_count, source, "alignment");
  d.sources = section<WindowSource>(d, h.source_offset, h.window_count, source, "sources");
  d.poses = section<float>(d, h.pose_offset, std::uint64_t{h.pose_count} * h.joint_count * 4, source, "poses");
  d.head_up = section<float>(d, h.head_up_offset, std::uint64_t{h.pose_count} * 3, source, "head up axes");
  d.contacts = section<std::uint8_t>(d, h.contact_offset, std::uint64_t{h.pose_count} * 2, source, "foot contacts");
  d.travel = section<Travel>(d, h.travel_offset, h.window_count, source, "head travel");
  if (!verify) prefault(d, h.source_offset, std::uint64_t{h.window_count} * sizeof(WindowSource));
  validate_meta(d.meta, source);
  const std::size_t speeds = d.meta.settings.speeds.size();
  for (std::uint32_t w = 0; w < h.window_count; ++w)
    if (d.sources[w].pose >= h.pose_count || d.sources[w].trial >= d.meta.trials.size() || d.sources[w].cls >= h.class_count ||
        d.sources[w].speed >= speeds)
      fail(source, "window " + std::to_string(w) + " refers to a missing pose, trial, class or speed");
  open_row_order(d, source, verify);
  if (!contents_ok) scan_contents(d, source);  // names what the fast scan flagged
  const std::byte* section_at = section<std::byte>(d, h.index_offset, h.index_bytes, source, "search index");
  if (index && !verify) prefault(d, h.index_offset, h.index_bytes);
  if (index && !load_index(d, {section_at, h.index_bytes}, source)) build_trees(d, kIndexLeafSize);
}

// The window of each stored feature row and the row of each window (version
// 7), per hand: inverse permutations that keep every row inside its tree's
// window range (a class's, or all of them in a one-class database), so a class
// mask still selects the right rows. One pass over the windows checks both:
// every window's row lies in the window's range and holds that window back
// (so no two windows share a row, and every row is some window's).
void open_row_order(Database::Impl& d, const std::string& source, bool verify) {
  const std::uint32_t n = d.header.window_count;
  const auto* order = section<std::uint32_t>(d, d.header.order_offset, 4 * std::uint64_t{n}, source, "row order");
  if (!verify) prefault(d, d.header.order_offset, 4 * std::uint64_t{n} * sizeof(std::uint32_t));
  // The window range of each tree: its class's when the trees are per class.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> spans;
  if (d.meta.ranges.size() <= 1) spans.push_back({0, n});
  else
    for (auto [a, b] : d.meta.ranges) spans.push_back({static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b)});
  // Every window is checked once: the ranges must tile the windows in order.
  std::uint32_t next = 0;
  for (auto [a, b] : spans) {
    if (a != next) fail(source, "class window ranges do not follow each other (a class starts at window " + std::to_string(a) +
                                    ", expected " + std::to_string(next) + ")");
    next = b;
  }
  if (next != n) fail(source, "class window ranges end at window " + std::to_string(next) + " of " + std::to_string(n));
  for (int hand = 0; hand < 2; ++hand) {
    const std::uint32_t* window_of_row = order + std::size_t{n} * static_cast<std::size_t>(hand);
    const std::uint32_t* row_of_window = order + std::size_t{n} * static_cast<std::size_t>(2 + hand);
    for (auto [a, b] : spans) {
      std::uint32_t bad = 0;  // branch-free over the class; named below when set
      for (std::uint32_t w = a; w < b; ++w) {
        const std::uint32_t r = row_of_window[w];
        const bool inside = r - a < b - a;
        bad |= static_cast<std::uint32_t>(!inside) | (window_of_row[inside ? r : a] ^ w);
      }
      if (bad == 0) continue;
      for (std::uint32_t w = a; w < b; ++w) {
        const std::uint32_t r = row_of_window[w];
        if (r < a || r >= b || window_of_row[r] != w)
          fail(source, std::string(hand ? "right" : "left") + "-hand row order: window " + std::to_string(w) + "'s row " +
                           std::to_string(r) + (r < a || r >= b ? " is outside its class's rows"
                                                                 : " holds window " + std::to_string(window_of_row[r])) +
                           "; rebuild the database");
      }
    }
    d.window_of_row[hand] = window_of_row;
    d.row_of_window[hand] = row_of_window;
  }
}

// Contents beyond the checksum: a checksum-valid file can still hold values
// that make every result wrong while reporting 'matched'. Metadata is always
// checked; with the checksum pass (which reads every byte anyway) every pose
// is a finite unit quaternion, every feature, alignment point and head axis is
// finite and every contact 0 or 1: checksum_and_scan tests that per chunk
// while the chunk is in cache, and scan_contents names the first offender.
void validate_meta(const DatabaseMeta& m, const std::string& source) {
  auto positive = [&](double v, double max, const char* what) {
    if (!(v > 0 && v <= max))
      fail(source, std::string(what) + " is " + std::to_string(v) + ", expected a finite value in (0, " +
                       std::to_string(max) + "]; rebuild the database");
  };
  positive(m.settings.fps, 10000, "build fps");
  positive(m.space.fps, 10000, "feature fps");
  positive(m.height, 10, "height_m");
  positive(m.typical_distance, 1e6, "typical_distance");
  // The engine plays a candidate forward at speeds[window's speed] / hop
  // samples a database frame (accent.cpp, align_matches).
  if (m.settings.hop < 1 || m.settings.hop > 10000)
    fail(source, "build hop is " + std::to_string(m.settings.hop) + ", expected a whole number from 1 to 10000; rebuild the database");
  if (m.settings.speeds.empty() || m.settings.speeds.size() > 256)
    fail(source, "build speeds list has " + std::to_string(m.settings.speeds.size()) +
                     " factors, expected 1 to 256; rebuild the database");
  for (double v : m.settings.speeds) positive(v, 100, "a build speed factor");
  for (double v : m.space.scale)
    if (!std::isfinite(v)) fail(source, "feature scale is not finite");
  for (double v : m.space.projection)
    if (!std::isfinite(v)) fail(source, "feature projection is not finite");
  for (float v : m.travel_scale)
    if (!(v > 0 && v <= 1e6f)) fail(source, "travel_scale is " + std::to_string(v) + ", expected a finite value in (0, 1e6]; rebuild the database");
}

void scan_contents(const Database::Impl& d, const std::string& source) {
  const DatabaseMeta& m = d.meta;
  const std::uint32_t joints = d.header.joint_count;
  for (std::uint32_t p = 0; p < d.header.pose_count; ++p)
    for (std::uint32_t j = 0; j < joints; ++j) {
      const float* q = d.poses + (std::size_t{p} * joints + j) * 4;
      const double norm2 = double{q[0]} * q[0] + double{q[1]} * q[1] + double{q[2]} * q[2] + double{q[3]} * q[3];
      if (!(std::abs(norm2 - 1.0) < 1e-3))
        fail(source, "pose " + std::to_string(p) + " joint '" + m.skeleton.names[j] +
                         "' is not a finite unit quaternion; rebuild the database");
    }
  for (std::uint32_t p = 0; p < 3 * d.header.pose_count; ++p)
    if (!std::isfinite(d.head_up[p])) fail(source, "head axis of pose " + std::to_string(p / 3) + " is not finite");
  for (std::uint32_t p = 0; p < 2 * d.header.pose_count; ++p)
    if (d.contacts[p] > 1) fail(source, "foot contact of pose " + std::to_string(p / 2) + " is neither 0 nor 1");
  for (int hand = 0; hand < 2; ++hand)
    for (std::uint32_t w = 0; w < d.header.window_count; ++w)
      for (float v : d.features[hand][w])
        if (!std::isfinite(v))
          fail(source, "feature of window " + std::to_string(d.window_of_row[hand][w]) + " is not finite");
  for (std::uint32_t w = 0; w < d.header.window_count; ++w)
    for (float v : d.align[w])
      if (!std::isfinite(v)) fail(source, "alignment point of window " + std::to_string(w) + " is not finite");
  for (std::uint32_t w = 0; w < d.header.window_count; ++w)
    for (float v : d.travel[w])
      if (!std::isfinite(v)) fail(source, "head travel of window " + std::to_string(w) + " is not finite");
}

// The data sections the checksum pass also scans, by element kind. Only
// sections that lie inside the file are listed (one that does not is refused
// by name after the checksum).
enum class Scan { Finite, UnitQuat, Bits01 };
struct ScanRange {
  std::uint64_t begin, end;
  Scan kind;
};

std::size_t scan_ranges(const Database::Impl& d, std::array<ScanRange, 7>& out) {
  const FileHeader& h = d.header;
  const std::uint64_t w = h.window_count, p = h.pose_count;
  const ScanRange all[7] = {{h.feature_offset[0], w * sizeof(Feature), Scan::Finite},
                            {h.feature_offset[1], w * sizeof(Feature), Scan::Finite},
                            {h.align_offset, w * sizeof(AlignXZ), Scan::Finite},
                            {h.pose_offset, p * h.joint_count * 16, Scan::UnitQuat},
                            {h.head_up_offset, p * 12, Scan::Finite},
                            {h.contact_offset, p * 2, Scan::Bits01},
                            {h.travel_offset, w * sizeof(Travel), Scan::Finite}};
  std::size_t n = 0;
  for (const ScanRange& r : all)  // `end` holds the byte count here
    if (r.begin % 4 == 0 && r.begin <= d.size && r.end <= d.size - r.begin) out[n++] = {r.begin, r.begin + r.end, r.kind};
  return n;
}

// True when every element starting in [from, to) of range r is valid. Written
// without early exits so the compiler vectorizes it; conservative (a float
// norm test slightly tighter than scan_contents' double one).
// AVX-512 / AVX2 copies chosen at load time (glibc ifunc): 2-4x the lanes of
// the SSE2 baseline, so the scan keeps up with the hash. Not under the
// sanitizers: the ifunc resolver runs while the program is being relocated,
// before their runtimes start, and ThreadSanitizer's instrumented resolver
// crashes there.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_THREAD__) && \
    !defined(__SANITIZE_ADDRESS__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
bool scan_chunk(const std::byte* base, const ScanRange& r, std::uint64_t from, std::uint64_t to) {
  const std::uint64_t step = r.kind == Scan::UnitQuat ? 16 : r.kind == Scan::Finite ? 4 : 1;
  const std::uint64_t a = std::max(from, r.begin), b = std::min(to, r.end);
  if (a >= b) return true;
  const std::uint64_t first = r.begin + (a - r.begin + step - 1) / step * step;
  const std::uint64_t count = first < b ? (std::min(b + step - 1, r.end) - first) / step : 0;
  const std::byte* at = base + first;
  std::uint32_t bad = 0;
  if (r.kind == Scan::Bits01) {
    const auto* c = reinterpret_cast<const std::uint8_t*>(at);
    for (std::uint64_t i = 0; i < count; ++i) bad |= c[i] & 0xfeu;
  } else if (r.kind == Scan::Finite) {
    const auto* u = reinterpret_cast<const std::uint32_t*>(at);
    for (std::uint64_t i = 0; i < count; ++i) bad |= static_cast<std::uint32_t>((u[i] & 0x7f800000u) == 0x7f800000u);
  } else {
    const auto* q = reinterpret_cast<const float*>(at);
    for (std::uint64_t i = 0; i < count; ++i) {
      const float n2 = q[4 * i] * q[4 * i] + q[4 * i + 1] * q[4 * i + 1] + q[4 * i + 2] * q[4 * i + 2] + q[4 * i + 3] * q[4 * i + 3];
      bad |= static_cast<std::uint32_t>(!(std::fabs(n2 - 1.0f) < 0.999e-3f));
    }
  }
  return bad == 0;
}

// The checksum (format 9) is XXH3-64 of the two XXH3-64 digests of the block's
// halves, [0, mid) with the header's checksum field zeroed and [mid, size), so
// a load can hash the halves on two cores: one XXH3 pass over a 46 MB file is
// bound by one core's memory bandwidth at 4-6 ms (docs/accent.md, "Database
// format 9").
std::uint64_t checksum_middle(std::uint64_t size) { return std::max<std::uint64_t>(sizeof(FileHeader), size / 2); }
std::uint64_t combine_halves(std::uint64_t first, std::uint64_t second) {
  const std::uint64_t both[2] = {first, second};  // the file is little-endian (the header's endian tag)
  return XXH3_64bits(both, sizeof both);
}

// XXH3-64 of base[from, to) (the zeroed header first when from is 0) and,
// chunk by chunk while the chunk is in cache, the content scan of the ranges;
// ok = false when anything looked wrong.
std::uint64_t hash_and_scan(const Database::Impl& d, std::span<const ScanRange> ranges, std::uint64_t from,
                            std::uint64_t to, bool& ok) {
  XXH3_state_t state;
  XXH3_64bits_reset(&state);
  if (from == 0) {
    FileHeader zeroed = d.header;
    zeroed.checksum = 0;
    LEGWORK_XXH3_UPDATE(&state, &zeroed, sizeof zeroed);
    from = sizeof(FileHeader);
  }
  constexpr std::uint64_t kChunk = 128 * 1024;
  ok = true;
  for (std::uint64_t at = from; at < to; at += kChunk) {
    const std::uint64_t end = std::min<std::uint64_t>(to, at + kChunk);
    LEGWORK_XXH3_UPDATE(&state, d.base + at, end - at);
    for (const ScanRange& r : ranges) ok = scan_chunk(d.base, r, at, end) && ok;
  }
  return XXH3_64bits_digest(&state);
}

// Files at least this large hash their second half on another thread (starting
// one costs tens of microseconds; hashing a megabyte about a hundred).
constexpr std::uint64_t kParallelChecksumBytes = 1u << 20;

// The checksum of the block (as block_checksum) with the content scan;
// contents_ok = false when anything looked wrong.
std::uint64_t checksum_and_scan(const Database::Impl& d, bool& contents_ok) {
  std::array<ScanRange, 7> ranges{};
  const std::span<const ScanRange> scan(ranges.data(), scan_ranges(d, ranges));
  const std::uint64_t mid = checksum_middle(d.size);
  bool ok_first = true, ok_second = true;
  std::uint64_t second = 0;
  std::thread helper;
  if (d.size >= kParallelChecksumBytes) {
    try {
      helper = std::thread([&] { second = hash_and_scan(d, scan, mid, d.size, ok_second); });
    } catch (const std::system_error&) {  // no thread to be had: hash both halves here
    }
  }
  const std::uint64_t first = hash_and_scan(d, scan, 0, mid, ok_first);
  if (helper.joinable())
    helper.join();
  else
    second = hash_and_scan(d, scan, mid, d.size, ok_second);
  contents_ok = ok_first && ok_second;
  return combine_halves(first, second);
}

// Builds the KD-trees from the features (files of another nanoflann node
// layout, or another leaf size asked for).
void build_trees(Database::Impl& d, int leaf_size) {
  d.index.clear();
  d.index.resize(d.meta.classes.size());
  d.all = ClassIndex{};
  d.leaf_size = leaf_size;
  d.indexed = true;
  const auto params = nanoflann::KDTreeSingleIndexAdaptorParams(static_cast<std::size_t>(leaf_size));
  if (d.meta.classes.size() <= 1) {  // one class: its trees cover every window
    for (int hand = 0; hand < 2; ++hand) {
      d.all.cloud[hand] = {reinterpret_cast<const float*>(d.features[hand]), d.header.window_count};
      if (d.header.window_count) d.all.tree[hand] = std::make_unique<KdTree>(kTreeDim, d.all.cloud[hand], params);
    }
    return;
  }
  for (std::size_t c = 0; c < d.meta.classes.size(); ++c) {
    const auto [a, b] = d.meta.ranges[c];
    for (int hand = 0; hand < 2; ++hand) {
      auto& ci = d.index[c];
      ci.cloud[hand] = {reinterpret_cast<const float*>(d.features[hand] + a), static_cast<std::size_t>(b - a)};
      if (b > a) ci.tree[hand] = std::make_unique<KdTree>(kTreeDim, ci.cloud[hand], params);
    }
  }
}

}  // namespace

std::uint64_t block_checksum(std::span<const std::byte> block) {
  // Catches truncation, bit flips and overwrites (not an integrity seal
  // against tampering). Format 9: the XXH3-64 of the XXH3-64s of the block's
  // halves, the header's checksum field zeroed (checksum_and_scan); versions
  // 4-8 hashed the block in one pass, version 3 used a serial FNV-1a.
  if (block.size() < sizeof(FileHeader)) return XXH3_64bits(block.data(), block.size());
  const std::uint64_t mid = checksum_middle(block.size());
  XXH3_state_t state;
  XXH3_64bits_reset(&state);
  FileHeader zeroed;
  std::memcpy(&zeroed, block.data(), sizeof zeroed);
  zeroed.checksum = 0;
  LEGWORK_XXH3_UPDATE(&state, &zeroed, sizeof zeroed);
  LEGWORK_XXH3_UPDATE(&state, block.data() + sizeof zeroed, mid - sizeof zeroed);
  const std::uint64_t first = XXH3_64bits_digest(&state);
  XXH3_64bits_reset(&state);
  LEGWORK_XXH3_UPDATE(&state, block.data() + mid, block.size() - mid);
  return combine_halves(first, XXH3_64bits_digest(&state));
}

std::vector<std::byte> serialize_block(const BlockParts& p) {
  const std::string meta = meta_json(p.meta).dump();
  const std::size_t nw = p.sources.size();
  const std::size_t nj = static_cast<std::size_t>(p.meta.skeleton.joint_count());
  const std::size_t np = nj ? p.poses.size() / (nj * 4) : 0;
  FileHeader h{};
  std::memcpy(h.magic, kMagic, sizeof(kMagic));
  h.version = kFormatVersion;
  h.endian = kEndianTag;
  h.window_count = static_cast<std::uint32_t>(nw);
  h.pose_count = static_cast<std::uint32_t>(np);
  h.joint_count = static_cast<std::uint32_t>(nj);
  h.class_count = static_cast<std::uint32_t>(p.meta.classes.size());
  h.feature_dim = kDim;
  h.window = kWindow;
  std::size_t at = align64(sizeof(FileHeader));
  auto place = [&at](std::size_t bytes) {
    const std::size_t o = at;
    at = align64(at + bytes);
    return o;
  };
  h.meta_offset = place(meta.size());
  h.meta_bytes = meta.size();
  h.space_offset = place(kSpaceValues * sizeof(double));
  for (int hand = 0; hand < 2; ++hand) h.feature_offset[hand] = place(nw * sizeof(Feature));
  h.align_offset = place(nw * sizeof(AlignXZ));
  h.source_offset = place(nw * sizeof(WindowSource));
  h.pose_offset = place(p.poses.size() * sizeof(float));
  h.head_up_offset = place(p.head_up.size() * sizeof(float));
  h.contact_offset = place(p.contacts.size());
  h.travel_offset = place(nw * sizeof(Travel));
  // The rows are stored in their trees' leaf order (version 7).
  std::array<std::vector<Feature>, 2> rows{p.features[0], p.features[1]};
  std::array<std::vector<std::uint32_t>, 2> window_of_row;
  const std::vector<std::byte> index =
      serialize_index({rows[0].data(), rows[1].data()}, nw, p.meta.ranges, window_of_row);
  h.order_offset = place(4 * nw * sizeof(std::uint32_t));
  h.index_offset = place(index.size());
  h.index_bytes = index.size();
  h.file_bytes = at;
  std::vector<std::byte> block(at);
  auto put = [&block](std::size_t off, const void* src, std::size_t bytes) {
    if (bytes) std::memcpy(block.data() + off, src, bytes);
  };
  put(h.meta_offset, meta.data(), meta.size());
  put(h.space_offset, p.meta.space.scale.data(), sizeof p.meta.space.scale);
  put(h.space_offset + sizeof p.meta.space.scale, p.meta.space.projection.data(), sizeof p.meta.space.projection);
  for (int hand = 0; hand < 2; ++hand) {
    put(h.feature_offset[hand], rows[hand].data(), nw * sizeof(Feature));
    put(h.order_offset + hand * nw * sizeof(std::uint32_t), window_of_row[hand].data(), nw * sizeof(std::uint32_t));
    std::vector<std::uint32_t> row_of_window(nw);
    for (std::size_t r = 0; r < nw; ++r) row_of_window[window_of_row[hand][r]] = static_cast<std::uint32_t>(r);
    put(h.order_offset + (2 + hand) * nw * sizeof(std::uint32_t), row_of_window.data(), nw * sizeof(std::uint32_t));
  }
  put(h.align_offset, p.align.data(), nw * sizeof(AlignXZ));
  put(h.source_offset, p.sources.data(), nw * sizeof(WindowSource));
  put(h.pose_offset, p.poses.data(), p.poses.size() * sizeof(float));
  put(h.head_up_offset, p.head_up.data(), p.head_up.size() * sizeof(float));
  put(h.contact_offset, p.contacts.data(), p.contacts.size());
  put(h.travel_offset, p.travel.data(), nw * sizeof(Travel));
  put(h.index_offset, index.data(), index.size());
  put(0, &h, sizeof(h));
  h.checksum = block_checksum(block);
  put(0, &h, sizeof(h));
  return block;
}

Database::Impl::~Impl() {
  if (map) munmap(map, map_bytes);
}

Database::Database() : impl_(std::make_unique<Impl>()) {}
Database::~Database() = default;
Database::Database(Database&&) noexcept = default;
Database& Database::operator=(Database&&) noexcept = default;

int Database::window_count() const { return static_cast<int>(impl_->header.window_count); }
int Database::pose_count() const { return static_cast<int>(impl_->header.pose_count); }
int Database::class_count() const { return static_cast<int>(impl_->meta.classes.size()); }
const Skeleton& Database::skeleton() const { return impl_->meta.skeleton; }
double Database::height() const { return impl_->meta.height; }
const BuildSettings& Database::settings() const { return impl_->meta.settings; }
const FeatureSpace& Database::feature_space() const { return impl_->meta.space; }
double Database::typical_distance() const { return impl_->meta.typical_distance; }
const std::vector<std::string>& Database::classes() const { return impl_->meta.classes; }
const std::vector<TrialInfo>& Database::trials() const { return impl_->meta.trials; }
int Database::find_class(const std::string& name) const {
  for (std::size_t c = 0; c < impl_->meta.classes.size(); ++c)
    if (impl_->meta.classes[c] == name) return static_cast<int>(c);
  return -1;
}
std::pair<int, int> Database::class_range(int c) const { return impl_->meta.ranges[static_cast<std::size_t>(c)]; }
const Feature& Database::feature(int hand, int window) const {
  return impl_->features[hand][impl_->row_of_window[hand][window]];
}
const AlignXZ& Database::align(int window) const { return impl_->align[window]; }
const WindowSource& Database::source(int window) const { return impl_->sources[window]; }
std::span<const float> Database::pose_rotations(int pose) const {
  const std::size_t n = static_cast<std::size_t>(joint_count()) * 4;
  return {impl_->poses + static_cast<std::size_t>(pose) * n, n};
}
Vec3 Database::head_up(int pose) const {
  const float* u = impl_->head_up + static_cast<std::ptrdiff_t>(pose) * 3;
  return {u[0], u[1], u[2]};
}
std::array<bool, 2> Database::contact(int pose) const {
  const std::uint8_t* c = impl_->contacts + static_cast<std::ptrdiff_t>(pose) * 2;
  return {c[0] != 0, c[1] != 0};
}
const Travel& Database::travel(int window) const { return impl_->travel[window]; }
const Travel& Database::travel_scale() const { return impl_->meta.travel_scale; }
void Database::pose_rotation(int pose, std::span<Quat> out) const {
  const auto r = pose_rotations(pose);
  for (std::size_t j = 0; j < out.size(); ++j) out[j] = Quat(r[4 * j], r[4 * j + 1], r[4 * j + 2], r[4 * j + 3]);
}
std::span<const std::byte> Database::bytes() const { return {impl_->base, impl_->size}; }
bool Database::is_mapped() const { return impl_->map != nullptr; }
bool Database::has_index() const { return impl_->indexed; }

void Database::build_index(int leaf_size) {
  if (has_index() && impl_->leaf_size == leaf_size) return;  // stored in the block
  build_trees(*impl_, leaf_size);
}

Database Database::from_bytes(std::vector<std::byte> block, const std::string& source) {
  Database db;
  db.impl_->owned = std::move(block);
  db.impl_->base = db.impl_->owned.data();
  db.impl_->size = db.impl_->owned.size();
  open_block(*db.impl_, source, true, true);
  return db;
}

Database load_database(const std::string& path, const LoadOptions& opt) {
  Database db;
  Database::Impl& d = *db.impl_;
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) fail(path, std::string("cannot open: ") + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    ::close(fd);
    fail(path, std::string("cannot stat: ") + std::strerror(errno));
  }
  const auto bytes = static_cast<std::size_t>(st.st_size);
  if (bytes == 0) {
    ::close(fd);
    fail(path, "file is empty");
  }
  if (opt.use_mmap) {
    void* m = ::mmap(nullptr, bytes, PROT_READ, MAP_PRIVATE, fd, 0);
    ::close(fd);
    if (m == MAP_FAILED) fail(path, std::string("mmap failed: ") + std::strerror(errno));
    d.map = m;
    d.map_bytes = bytes;
    d.base = static_cast<const std::byte*>(m);
  } else {
    d.owned.resize(bytes);
    const auto got = ::read(fd, d.owned.data(), bytes);
    ::close(fd);
    if (got != static_cast<ssize_t>(bytes)) fail(path, "short read");
    d.base = d.owned.data();
  }
  d.size = bytes;
  open_block(d, path, opt.verify_checksum, opt.build_index);
  return db;
}

// Written to a temporary file in the same folder, then renamed over `path`:
// a process that has the old file mapped keeps its (unlinked) pages instead of
// dying with SIGBUS on a file truncated under it, and a failed write never
// leaves a half-written database behind.
void save_database(const std::string& path, const Database& db) {
  std::string tmp = path + ".tmp-XXXXXX";
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) throw Error("cannot write accent database '" + path + "': " + std::strerror(errno));
  auto failed = [&](const char* what) {
    const std::string reason = std::strerror(errno);
    ::close(fd);
    ::unlink(tmp.c_str());
    throw Error(std::string(what) + " accent database '" + path + "': " + reason);
  };
  const auto b = db.bytes();
  const auto* data = reinterpret_cast<const char*>(b.data());
  for (std::size_t done = 0; done < b.size();) {
    const ssize_t n = ::write(fd, data + done, b.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) failed("write failed for");
    done += static_cast<std::size_t>(n);
  }
  // mkstemp makes the file private (0600); a database is shared data.
  if (::fchmod(fd, 0644) != 0 || ::fsync(fd) != 0) failed("cannot finish");
  if (::close(fd) != 0) {
    ::unlink(tmp.c_str());
    throw Error("cannot finish accent database '" + path + "': " + std::strerror(errno));
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw Error("cannot write accent database '" + path + "': " + reason);
  }
}

}  // namespace legwork::accent
