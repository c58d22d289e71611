// BVH reader: a hand-written tokenizer (the format is tiny) with precise
// errors, and a motion-section parser built on std::from_chars so that no
// value allocates.
#include <legwork/core/fk.hpp>
#include <legwork/core/measure.hpp>
#include <legwork/io/bvh.hpp>
#include <legwork/io/text.hpp>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cmath>
#include <sstream>
#include <unordered_set>

namespace legwork::io {

namespace {

class Lexer {
 public:
  Lexer(std::string_view text, std::string_view source) : text_(text), source_(source) {}

  [[noreturn]] void fail(const std::string& what, int line = -1) const {
    std::ostringstream os;
    os << source_ << ":" << (line < 0 ? line_ : line) << ": " << what;
    throw Error(os.str());
  }

  // Next whitespace-separated token; empty at end of input.
  std::string_view next() {
    skip_space();
    const std::size_t start = pos_;
    while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }
  std::string_view peek() {
    const std::size_t p = pos_;
    const int l = line_;
    auto t = next();
    pos_ = p;
    line_ = l;
    return t;
  }
  void expect(std::string_view want, std::string_view context) {
    auto t = next();
    if (t != want)
      fail("expected '" + std::string(want) + "' " + std::string(context) + ", found " + describe(t));
  }
  double number(std::string_view what) {
    auto t = next();
    double v = 0;
    if (!parse_double(t, v)) {
      if (!out_of_range(t)) fail("expected a number for " + std::string(what) + ", found " + describe(t));
      v = HUGE_VAL;
    }
    if (!std::isfinite(v)) fail(std::string(what) + " is not finite or out of range ('" + std::string(t) + "')");
    return v;
  }
  int line() const { return line_; }
  std::size_t pos() const { return pos_; }
  void set_pos(std::size_t p, int line) { pos_ = p, line_ = line; }
  std::string_view text() const { return text_; }

  static std::string describe(std::string_view t) {
    return t.empty() ? std::string("end of file") : "'" + printable(t.substr(0, 40)) + "'";
  }
  // Binary input (a .glb given as .bvh) must not put control bytes in messages.
  static std::string printable(std::string_view t) { return printable_text(t, t.size()); }
  static std::string describe_number(double v) {
    std::ostringstream os;
    os << v;
    return os.str();
  }
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }
  // A well-formed number that does not fit a double (1e999).
  static bool out_of_range(std::string_view t) {
    double v;
    const char* b = t.data();
    const char* e = b + t.size();
    if (b != e && *b == '+') ++b;
    auto [ptr, ec] = std::from_chars(b, e, v);
    return ec == std::errc::result_out_of_range && ptr == e;
  }
  static bool parse_double(std::string_view t, double& v) {
    if (t.empty()) return false;
    const char* b = t.data();
    const char* e = b + t.size();
    if (*b == '+' && b + 1 < e && b[1] != '-') ++b;  // from_chars rejects a leading '+'
    auto [ptr, ec] = std::from_chars(b, e, v);
    return ec == std::errc() && ptr == e;
  }

 private:
  void skip_space() {
    while (pos_ < text_.size() && is_space(text_[pos_])) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }
  std::string_view text_, source_;
  std::size_t pos_ = 0;
  int line_ = 1;
};

bool parse_channel(std::string_view t, Channel& c) {
  static constexpr std::pair<std::string_view, Channel> names[] = {
      {"Xposition", Channel::Xposition}, {"Yposition", Channel::Yposition}, {"Zposition", Channel::Zposition},
      {"Xrotation", Channel::Xrotation}, {"Yrotation", Channel::Yrotation}, {"Zrotation", Channel::Zrotation}};
  for (auto [n, ch] : names)
    if (t == n) return c = ch, true;
  return false;
}

bool is_rotation(Channel c) { return c >= Channel::Xrotation; }
int axis_of(Channel c) { return is_rotation(c) ? static_cast<int>(c) - 3 : static_cast<int>(c); }

// sin and cos of an angle in degrees. Reduction is done in degrees (exact for
// the angles BVH files hold) and the polynomials are Taylor series to the
// 15th/16th power on [-45, 45] degrees (truncation error < 1e-16), so this
// matches libm to about an ulp at a fraction of the cost: motion parsing is
// mostly trigonometry otherwise.
inline void sincos_degrees(double deg, double& s, double& c) {
  if (!(std::abs(deg) < 1e12)) [[unlikely]] {  // beyond the exact reduction range
    s = std::sin(deg2rad(deg));
    c = std::cos(deg2rad(deg));
    return;
  }
  // Nearest quadrant by truncation (a conversion instruction, not a libm call).
  const auto quadrant = static_cast<long long>(deg * (1.0 / 90.0) + (deg >= 0 ? 0.5 : -0.5));
  const double x = deg2rad(deg - 90.0 * static_cast<double>(quadrant));
  const double x2 = x * x;
  const double sx =
      x * (1 + x2 * (-1.0 / 6 + x2 * (1.0 / 120 + x2 * (-1.0 / 5040 + x2 * (1.0 / 362880 + x2 * (-1.0 / 39916800 +
          x2 * (1.0 / 6227020800 + x2 * (-1.0 / 1307674368000))))))));
  const double cx =
      1 + x2 * (-1.0 / 2 + x2 * (1.0 / 24 + x2 * (-1.0 / 720 + x2 * (1.0 / 40320 + x2 * (-1.0 / 3628800 +
          x2 * (1.0 / 479001600 + x2 * (-1.0 / 87178291200 + x2 * (1.0 / 20922789888000))))))));
  switch (quadrant & 3) {
    case 0: s = sx, c = cx; break;
    case 1: s = cx, c = -sx; break;
    case 2: s = -sx, c = -cx; break;
    default: s = -cx, c = sx; break;
  }
}

// Rotation by `degrees` about coordinate axis 0/1/2 (same as AngleAxis, without the general path).
Quat axis_rotation(int axis, double degrees) {
  double s, c;
  sincos_degrees(0.5 * degrees, s, c);
  Quat q(c, 0.0, 0.0, 0.0);
  q.vec()[axis] = s;
  return q;
}

// q * axis_rotation(axis, degrees), using the zeros of the axis rotation.
Quat rotate_about_axis(const Quat& q, int axis, double degrees) {
  double s, c;
  sincos_degrees(0.5 * degrees, s, c);
  const double w = q.w(), x = q.x(), y = q.y(), z = q.z();
  switch (axis) {
    case 0: return Quat(w * c - x * s, x * c + w * s, y * c + z * s, z * c - y * s);
    case 1: return Quat(w * c - y * s, x * c - z * s, y * c + w * s, z * c + x * s);
    default: return Quat(w * c - z * s, x * c + y * s, y * c - x * s, z * c + w * s);
  }
}

// Fast path for the plain decimals BVH files are made of ("-12.3456"): up to
// 19 digits with a value below 2^53 and at most 22 decimals is exactly
// m / 10^k, one correctly rounded division (Clinger's fast path), so the
// result equals std::from_chars'. Returns the end of the number, or nullptr
// to hand the token to from_chars (exponents, long mantissas, junk).
const char* parse_plain_decimal(const char* b, const char* e, double& v) {
  static constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                      1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  const char* p = b;
  bool negative = false;
  if (p < e && (*p == '-' || *p == '+')) negative = *p++ == '-';
  std::uint64_t m = 0;
  int digits = 0, decimals = 0;
  while (p < e && *p >= '0' && *p <= '9') m = m * 10 + static_cast<unsigned>(*p++ - '0'), ++digits;
  if (p < e && *p == '.') {
    ++p;
    while (p < e && *p >= '0' && *p <= '9') m = m * 10 + static_cast<unsigned>(*p++ - '0'), ++digits, ++decimals;
  }
  if (digits == 0 || digits > 19 || decimals > 22 || m > (std::uint64_t{1} << 53)) return nullptr;
  if (p < e && !Lexer::is_space(*p)) return nullptr;
  const double mag = static_cast<double>(m) / kPow10[decimals];
  v = negative ? -mag : mag;
  return p;
}

// The hierarchy being read; `seen` indexes the joint names (views into the
// text) so duplicate checks stay linear in the joint count.
struct Hierarchy {
  Skeleton skel;
  std::vector<JointChannels> channels;
  std::unordered_set<std::string_view> seen;
};

void parse_joint_body(Lexer& lx, Hierarchy& h, int joint, int depth);

// Lengths (offsets, position channels) beyond this many file units are not a
// body in any unit (1000 km in millimetres); unbounded, they overflow FK to Inf.
constexpr double kMaxFileLength = 1e9;

// Deeper nesting than this is not a body (and would overflow the stack).
constexpr int kMaxJointDepth = 256;

bool is_keyword(std::string_view t) {
  return t == "JOINT" || t == "End" || t == "OFFSET" || t == "CHANNELS" || t == "{" || t == "}" || t == "MOTION" ||
         t == "ROOT";
}

void parse_joint(Lexer& lx, Hierarchy& h, int parent, int depth) {
  if (depth > kMaxJointDepth) lx.fail("joints nested more than " + std::to_string(kMaxJointDepth) + " deep");
  auto name = lx.next();
  if (name.empty() || is_keyword(name)) lx.fail("expected a joint name after JOINT/ROOT, found " + Lexer::describe(name));
  // Names go into JSON and glTF output, which need UTF-8.
  if (!is_valid_utf8(name)) lx.fail("joint name " + Lexer::describe(name) + " is not UTF-8 text (save the file as UTF-8)");
  if (!h.seen.insert(name).second) lx.fail("duplicate joint name '" + std::string(name) + "'");
  int j = h.skel.add_joint(std::string(name), parent, Vec3::Zero());
  h.channels.emplace_back();
  lx.expect("{", "after joint '" + std::string(name) + "'");
  parse_joint_body(lx, h, j, depth);
}

void parse_joint_body(Lexer& lx, Hierarchy& h, int j, int depth) {
  Skeleton& skel = h.skel;
  const std::string jname = skel.names[static_cast<std::size_t>(j)];
  bool have_offset = false, have_channels = false;
  for (;;) {
    auto t = lx.next();
    const int line = lx.line();  // the line of t
    if (t == "OFFSET") {
      Vec3 o;
      for (int k = 0; k < 3; ++k) o[k] = lx.number("OFFSET of joint '" + jname + "'");
      if (o.cwiseAbs().maxCoeff() > kMaxFileLength)
        lx.fail("OFFSET of joint '" + jname + "' is beyond " + Lexer::describe_number(kMaxFileLength) + " file units");
      skel.rest_offsets[static_cast<std::size_t>(j)] = o;
      have_offset = true;
    } else if (t == "CHANNELS") {
      auto count_tok = lx.next();
      double cnt = 0;
      if (!Lexer::parse_double(count_tok, cnt) || cnt < 0 || cnt > 6 || cnt != std::floor(cnt))
        lx.fail("CHANNELS of joint '" + jname + "' needs a count from 0 to 6, found " + Lexer::describe(count_tok));
      auto& jc = h.channels[static_cast<std::size_t>(j)].channels;
      for (int k = 0; k < static_cast<int>(cnt); ++k) {
        auto ct = lx.next();
        Channel c;
        if (!parse_channel(ct, c) && (ct.empty() || is_keyword(ct)))
          lx.fail("CHANNELS of joint '" + jname + "' declares " + std::to_string(static_cast<int>(cnt)) +
                  " channels but lists " + std::to_string(k) + " (found " + Lexer::describe(ct) + ")", line);
        if (!parse_channel(ct, c))
          lx.fail("unknown channel " + Lexer::describe(ct) + " for joint '" + jname +
                  "' (expected Xposition, Yposition, Zposition, Xrotation, Yrotation or Zrotation)");
        for (Channel prev : jc)
          if (prev == c) lx.fail("channel " + std::string(ct) + " repeated for joint '" + jname + "'");
        jc.push_back(c);
      }
      have_channels = true;
    } else if (t == "JOINT") {
      parse_joint(lx, h, j, depth + 1);
    } else if (t == "End") {
      auto site = lx.next();
      if (site != "Site") lx.fail("expected 'Site' after 'End', found " + Lexer::describe(site));
      lx.expect("{", "after End Site of joint '" + jname + "'");
      lx.expect("OFFSET", "in End Site of joint '" + jname + "'");
      Vec3 o;
      for (int k = 0; k < 3; ++k) o[k] = lx.number("End Site OFFSET of joint '" + jname + "'");
      if (o.cwiseAbs().maxCoeff() > kMaxFileLength)
        lx.fail("End Site OFFSET of joint '" + jname + "' is beyond " + Lexer::describe_number(kMaxFileLength) +
                " file units");
      lx.expect("}", "closing End Site of joint '" + jname + "'");
      skel.end_sites[static_cast<std::size_t>(j)] = o;
      skel.has_end_site[static_cast<std::size_t>(j)] = 1;
    } else if (t == "}") {
      if (!have_offset) lx.fail("joint '" + jname + "' has no OFFSET", line);
      if (!have_channels) lx.fail("joint '" + jname + "' has no CHANNELS", line);
      return;
    } else if (Channel extra; parse_channel(t, extra)) {
      lx.fail("CHANNELS of joint '" + jname + "' lists more channels than its count (extra '" + std::string(t) + "')", line);
    } else if (t.empty() || t == "MOTION") {
      lx.fail("missing '}' closing joint '" + jname + "' (found " + Lexer::describe(t) + ")", line);
    } else {
      lx.fail("unexpected " + Lexer::describe(t) + " in joint '" + jname +
              "' (expected OFFSET, CHANNELS, JOINT, End Site or '}')", line);
    }
  }
}

// "Frames:" may be written "Frames:" or "Frames :"; "Frame Time:" likewise.
void expect_label(Lexer& lx, std::initializer_list<std::string_view> words, const std::string& label) {
  for (auto w : words) {
    auto t = lx.next();
    std::string_view want = w;
    if (t == want) continue;
    if (t.size() == want.size() + 1 && t.substr(0, want.size()) == want && t.back() == ':' ) continue;
    if (t == std::string(want) + ":") continue;
    lx.fail("missing '" + label + "' line (found " + Lexer::describe(t) + ")");
  }
  if (lx.peek() == ":") lx.next();
}

}  // namespace

Quat euler_to_quat(const Channel* order, const double* degrees, int n) {
  Quat q = Quat::Identity();
  for (int k = 0; k < n; ++k) q = q * axis_rotation(axis_of(order[k]), degrees[k]);
  return q;
}

namespace {

// Frame times outside this range are not motion capture (and 1e300 s makes
// every derived sample count overflow).
constexpr double kMinFrameTime = 1e-4, kMaxFrameTime = 10.0;

// What precedes the motion lines.
struct Header {
  Hierarchy h;
  double declared = 0;  // the 'Frames:' value
  int frames_line = 0;
  double frame_time = 0;
};

void parse_header(Lexer& lx, Header& hd) {
  if (auto t = lx.next(); t != "HIERARCHY")
    lx.fail("expected 'HIERARCHY' at the start of a BVH file, found " + Lexer::describe(t));
  if (auto t = lx.next(); t != "ROOT") {
    if (t == "MOTION" || t.empty()) lx.fail("empty hierarchy: expected 'ROOT' after HIERARCHY, found " + Lexer::describe(t));
    lx.fail("expected 'ROOT' after HIERARCHY, found " + Lexer::describe(t));
  }
  parse_joint(lx, hd.h, -1, 0);
  if (auto t = lx.next(); t != "MOTION") {
    if (t == "ROOT") lx.fail("more than one ROOT; legwork reads single-root BVH files");
    lx.fail("expected 'MOTION' after the hierarchy, found " + Lexer::describe(t));
  }
  expect_label(lx, {"Frames"}, "Frames:");
  hd.frames_line = lx.line();
  auto ft = lx.next();
  if (!Lexer::parse_double(ft, hd.declared) || hd.declared < 0 || hd.declared != std::floor(hd.declared) ||
      hd.declared > 1e8)
    lx.fail("'Frames:' needs a whole number from 0 to 100000000, found " + Lexer::describe(ft), hd.frames_line);
  expect_label(lx, {"Frame", "Time"}, "Frame Time:");
  hd.frame_time = lx.number("Frame Time");
  if (!(hd.frame_time > 0) || !std::isfinite(1.0 / hd.frame_time))
    lx.fail("'Frame Time:' must be a positive number of seconds, found " + std::to_string(hd.frame_time));
  if (hd.frame_time < kMinFrameTime || hd.frame_time > kMaxFrameTime) {
    std::ostringstream os;
    os << "'Frame Time: " << hd.frame_time << "' is outside " << kMinFrameTime << " to " << kMaxFrameTime
       << " seconds (" << 1 / kMaxFrameTime << " to " << 1 / kMinFrameTime << " frames per second)";
    lx.fail(os.str());
  }
}

// Channels flattened: joint j's are flat[first[j] .. first[j + 1]).
struct FlatChannels {
  std::vector<Channel> flat;
  std::vector<int> first;
  int total() const { return static_cast<int>(flat.size()); }
};

FlatChannels flatten(const std::vector<JointChannels>& channels) {
  FlatChannels fc;
  fc.first.assign(channels.size() + 1, 0);
  for (std::size_t j = 0; j < channels.size(); ++j) {
    fc.flat.insert(fc.flat.end(), channels[j].channels.begin(), channels[j].channels.end());
    fc.first[j + 1] = fc.total();
  }
  return fc;
}

// One motion line's values, parsed in place into v.
struct LineValues {
  int count = 0;
  bool blank = true, all_zero = true;
};

// Parses the values of the line starting at t[p] (up to '\n' or the end);
// p ends on that '\n'. Every value must be a finite number.
LineValues read_line(const Lexer& lx, std::string_view t, std::size_t& p, int line, std::vector<double>& v) {
  const int total = static_cast<int>(v.size());
  LineValues lv;
  while (p < t.size() && t[p] != '\n') {
    char c = t[p];
    if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') { ++p; continue; }
    lv.blank = false;
    const char* b = t.data() + p;
    const char* e = t.data() + t.size();
    double val;
    const char* ptr = parse_plain_decimal(b, e, val);
    std::errc ec{};
    if (!ptr) {  // exponents, long mantissas, junk: the general parser decides
      if (*b == '+' && b + 1 < e && b[1] != '-') ++b;
      const auto r = std::from_chars(b, e, val);
      ptr = r.ptr;
      ec = r.ec;
    }
    auto token = [&] {
      std::size_t q = p;
      while (q < t.size() && !Lexer::is_space(t[q])) ++q;
      return Lexer::printable(t.substr(p, std::min<std::size_t>(q - p, 40)));
    };
    const std::string which = "motion line value " + std::to_string(lv.count + 1);
    if (lv.count >= total)
      lx.fail("motion line has more than the " + std::to_string(total) + " values the hierarchy declares (extra '" +
                  token() + "')", line);
    if (ec == std::errc::result_out_of_range && (ptr == e || Lexer::is_space(*ptr)))
      lx.fail(which + " is out of range: '" + token() + "'", line);
    if (ec != std::errc() || (ptr < e && !Lexer::is_space(*ptr))) lx.fail(which + " is not a number: '" + token() + "'", line);
    if (!std::isfinite(val)) lx.fail(which + " is not finite (NaN or Inf): '" + token() + "'", line);
    v[static_cast<std::size_t>(lv.count)] = val;
    lv.all_zero = lv.all_zero && val == 0.0;
    ++lv.count;
    p = static_cast<std::size_t>(ptr - t.data());
  }
  return lv;
}

// A pose from one line's channel values (degrees; positions in file units).
// Returns the 0-based index of a position value beyond kMaxFileLength, or -1.
int store_pose(const FlatChannels& fc, const Skeleton& skel, double scale, const double* val, PoseRef pose) {
  int absurd = -1;
  const int n = skel.joint_count();
  for (int j = 0; j < n; ++j) {
    const auto ju = static_cast<std::size_t>(j);
    Vec3 tr = skel.rest_offsets[ju];
    Quat q = Quat::Identity();
    for (int k = fc.first[ju]; k < fc.first[ju + 1]; ++k) {
      const Channel c = fc.flat[static_cast<std::size_t>(k)];
      if (is_rotation(c)) q = rotate_about_axis(q, axis_of(c), val[k]);
      else {
        tr[axis_of(c)] = val[k] * scale;  // position channels replace the OFFSET
        if (std::abs(val[k]) > kMaxFileLength) absurd = k;
      }
    }
    pose.rotations[ju] = q;
    pose.translations[ju] = tr;
  }
  return absurd;
}

// Frames that are all zeros (a CMU export glitch) take the nearest real
// frame's pose; the dropped T-pose is never a source. Returns the count.
int repair_zero_frames(Motion& m, const std::vector<unsigned char>& zero) {
  const int count = m.frame_count();
  std::vector<int> before(static_cast<std::size_t>(count), -1), after(static_cast<std::size_t>(count), -1);
  for (int f = 0, last = -1; f < count; ++f) {
    before[static_cast<std::size_t>(f)] = last;
    if (!zero[static_cast<std::size_t>(f)]) last = f;
  }
  for (int f = count - 1, next = -1; f >= 0; --f) {
    after[static_cast<std::size_t>(f)] = next;
    if (!zero[static_cast<std::size_t>(f)]) next = f;
  }
  int repaired = 0;
  for (int f = 0; f < count; ++f) {
    const auto fu = static_cast<std::size_t>(f);
    if (!zero[fu]) continue;
    const int b = before[fu], a = after[fu];
    const int best = b < 0 ? a : a < 0 ? b : (f - b < a - f ? b : a);  // ties go to the later frame
    if (best < 0) continue;  // every frame is zero: nothing to repair from
    m.set_frame(f, m.frame(best));  // sources are unrepaired real frames
    ++repaired;
  }
  return repaired;
}

// Frames the motion can hold, bounded before anything is allocated. Every
// value takes at least two characters, so the text bounds the line count (a
// bogus 'Frames:' fails after counting, it never reserves gigabytes). Joints
// without channels cost pose memory but no motion text, so the joint poses
// (frames x joints) are bounded by the file's size too: 2^21 + 8 per byte
// (a real file needs well under one per byte), and never more than 2^26.
int frame_capacity(const Lexer& lx, const Header& hd, int total, std::size_t motion_bytes) {
  const int n = hd.h.skel.joint_count();
  const std::size_t max_lines = total > 0 ? motion_bytes / (2 * static_cast<std::size_t>(total)) + 1 : 0;
  const int capacity = static_cast<int>(std::min(static_cast<std::size_t>(hd.declared), max_lines));
  const double limit = std::min(static_cast<double>(1 << 26), static_cast<double>(1 << 21) + 8.0 * lx.text().size());
  if (static_cast<double>(capacity) * n > limit)
    lx.fail(std::to_string(capacity) + " frames x " + std::to_string(n) + " joints is more than legwork reads from a " +
                std::to_string(lx.text().size()) + "-byte file (" + std::to_string(static_cast<long long>(limit)) +
                " joint poses)",
            hd.frames_line);
  return capacity;
}

}  // namespace

BvhFile parse_bvh(std::string_view text, std::string_view source, const BvhReadOptions& opt) {
  Lexer lx(text_body(text, source), source);
  BvhFile out;
  Header hd;
  parse_header(lx, hd);
  Skeleton& skel = hd.h.skel;
  out.channels = std::move(hd.h.channels);
  const FlatChannels fc = flatten(out.channels);
  const int total = fc.total();

  // Units come from the rest pose alone, so the motion can be converted as it is read.
  double scale = opt.scale;
  if (scale <= 0) {
    resolve_roles(skel);
    double h = measure_body(skel).standing_height;
    scale = guess_unit_scale(h, &out.report.scale_reason);
    if (scale == 0) throw Error(std::string(source) + ": " + out.report.scale_reason);
  } else {
    out.report.scale_reason = "given scale x" + std::to_string(scale);
  }
  out.report.scale = scale;
  skel.scale(scale);

  // Motion lines: skip to the end of the Frame Time line.
  std::string_view t = lx.text();
  std::size_t p = lx.pos();
  int line = lx.line();
  while (p < t.size() && t[p] != '\n') {
    if (!Lexer::is_space(t[p])) lx.fail("unexpected text after Frame Time value");
    ++p;
  }
  const int capacity = frame_capacity(lx, hd, total, t.size() - p);
  // Lines are parsed straight into the motion's poses. With drop_first_frame,
  // line 0 (the CMU T-pose) goes to a side pose and is only kept if it turns
  // out to be the only frame.
  const int skip = opt.drop_first_frame ? 1 : 0;
  Motion m(skel, 1.0 / hd.frame_time, std::max(capacity - skip, 0));
  Pose line0(skel);
  std::vector<unsigned char> zero(static_cast<std::size_t>(std::max(capacity - skip, 0)), 0);
  bool line0_zero = false;
  std::vector<double> v(static_cast<std::size_t>(total));
  int frames = 0;
  while (p < t.size()) {
    ++p;  // past '\n'
    ++line;
    const LineValues lv = read_line(lx, t, p, line, v);
    if (lv.blank) continue;
    if (lv.count < total)
      lx.fail("motion line has " + std::to_string(lv.count) + " values, the hierarchy declares " +
                  std::to_string(total) + " channels", line);
    if (frames < capacity) {  // lines past 'Frames:' are checked, not kept
      const int absurd = frames < skip ? store_pose(fc, m.skeleton, scale, v.data(), line0.ref())
                                       : store_pose(fc, m.skeleton, scale, v.data(), m.frame(frames - skip));
      if (absurd >= 0)
        lx.fail("motion line value " + std::to_string(absurd + 1) + " is a position beyond " +
                    Lexer::describe_number(kMaxFileLength) + " file units", line);
      if (frames < skip) line0_zero = lv.all_zero;
      else zero[static_cast<std::size_t>(frames - skip)] = lv.all_zero ? 1 : 0;
    }
    ++frames;
  }
  const int declared = static_cast<int>(hd.declared);
  if (frames != declared) {
    std::ostringstream os;
    os << "'Frames: " << declared << "' but the file has " << frames << " motion lines";
    if (opt.strict_frame_count || frames < declared) lx.fail(os.str(), hd.frames_line);
    out.report.warnings.push_back(os.str() + "; using the " + std::to_string(declared) + " declared frames");
    frames = declared;
  }
  if (frames == 0) lx.fail("the file has no motion frames", hd.frames_line);
  out.report.declared_frames = declared;
  if (skip == 1 && frames == 1) {  // nothing to drop: keep the only frame
    m.resize(1);
    m.set_frame(0, line0);
    zero.assign(1, line0_zero ? 1 : 0);
  }
  out.report.dropped_first_frame = skip == 1 && frames > 1;
  if (opt.repair_zero_frames && total > 0) out.report.repaired_zero_frames = repair_zero_frames(m, zero);
  if (opt.resolve_roles) out.report.missing_roles = resolve_roles(m.skeleton);
  out.motion = std::move(m);
  return out;
}

BvhFile read_bvh(const std::string& path, const BvhReadOptions& opt) {
  return parse_bvh(read_text_file(path), path, opt);
}

Motion load_bvh(const std::string& path, const BvhReadOptions& opt) { return read_bvh(path, opt).motion; }

}  // namespace legwork::io
