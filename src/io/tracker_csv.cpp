// Tracker CSV: time plus named xyz (and optional quaternion) columns.
// A small hand-written reader: the format is fixed and the errors must point
// at the exact cell (file:line:column), which generic CSV readers do not do.
#include <legwork/core/stats.hpp>
#include <legwork/io/text.hpp>
#include <legwork/io/tracker_csv.hpp>

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

namespace legwork::io {

namespace {

// Column suffixes in their canonical order: position, then orientation.
constexpr std::string_view kSuffixes[] = {"_x", "_y", "_z", "_qw", "_qx", "_qy", "_qz"};
constexpr int kSuffixCount = 7;

struct Cell {
  std::string_view text;  // trimmed
  int column = 1;         // 1-based character column of the cell's start
};

struct Failure {
  std::string_view source;
  [[noreturn]] void at(int line, int column, const std::string& what) const {
    throw Error(std::string(source) + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + what);
  }
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

void split_cells(std::string_view line, std::vector<Cell>& cells) {
  cells.clear();
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    const std::string_view raw = line.substr(start, comma == std::string_view::npos ? line.npos : comma - start);
    std::size_t lead = 0;
    while (lead < raw.size() && (raw[lead] == ' ' || raw[lead] == '\t')) ++lead;
    cells.push_back({trim(raw), static_cast<int>(start + lead) + 1});
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
}

bool iequals(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  return true;
}

// A number, NaN for a dropped sample (empty or "nan"), nullopt if not a number.
std::optional<double> parse_cell(std::string_view t) {
  if (t.empty() || iequals(t, "nan") || iequals(t, "-nan")) return kNaN;
  const char* b = t.data();
  const char* e = b + t.size();
  if (*b == '+' && b + 1 < e && b[1] != '-') ++b;
  double v = 0;
  auto [ptr, ec] = std::from_chars(b, e, v);
  if (ec != std::errc() || ptr != e || std::isinf(v)) return std::nullopt;
  return v;
}

// Header column: which point and which component (index into kSuffixes).
struct ColumnRole {
  int point = -1;
  int component = -1;
};

struct Header {
  std::vector<ColumnRole> columns;  // per cell; column 0 is time
  std::vector<std::array<int, kSuffixCount>> cell_of;  // per point: cell index per component, -1 if absent
};

Header parse_header(const std::vector<Cell>& cells, TrackerTable& table, const Failure& fail) {
  Header h;
  bool has_time = false;
  for (const Cell& c : cells) has_time = has_time || c.text == "time";
  if (!has_time) fail.at(1, 1, "missing 'time' column (the header must start with 'time')");
  if (cells[0].text != "time") fail.at(1, cells[0].column, "the first column must be 'time', found '" + printable_text(cells[0].text, 40) + "'");
  h.columns.resize(cells.size());
  std::map<std::string, int, std::less<>> index;
  for (std::size_t i = 1; i < cells.size(); ++i) {
    const Cell& c = cells[i];
    int comp = -1;
    std::string_view name;
    for (int k = 0; k < kSuffixCount; ++k) {
      const auto suf = kSuffixes[k];
      if (c.text.size() > suf.size() && c.text.substr(c.text.size() - suf.size()) == suf) {
        comp = k;
        name = c.text.substr(0, c.text.size() - suf.size());
      }
    }
    if (c.text == "time") fail.at(1, c.column, "column 'time' appears twice");
    if (comp < 0)
      fail.at(1, c.column, "column '" + printable_text(c.text, 40) +
                               "' is not '<point>_x/_y/_z' or '<point>_qw/_qx/_qy/_qz'");
    auto it = index.find(name);
    if (it == index.end()) {
      it = index.emplace(std::string(name), static_cast<int>(table.points.size())).first;
      table.points.push_back({});
      table.points.back().name = std::string(name);
      h.cell_of.emplace_back();
      h.cell_of.back().fill(-1);
    }
    auto& slot = h.cell_of[static_cast<std::size_t>(it->second)][static_cast<std::size_t>(comp)];
    if (slot >= 0) fail.at(1, c.column, "column '" + printable_text(c.text, 40) + "' appears twice");
    slot = static_cast<int>(i);
    h.columns[i] = {it->second, comp};
  }
  // Every point needs a full xyz triple; an orientation needs all four parts.
  for (std::size_t p = 0; p < table.points.size(); ++p) {
    const auto& slots = h.cell_of[p];
    const std::string& name = table.points[p].name;
    int first_col = -1;
    for (int s : slots)
      if (s >= 0 && (first_col < 0 || s < first_col)) first_col = s;
    const int col = cells[static_cast<std::size_t>(first_col)].column;
    for (int k = 0; k < 3; ++k)
      if (slots[static_cast<std::size_t>(k)] < 0)
        fail.at(1, col, "incomplete xyz triple: point '" + name + "' has no '" + name + std::string(kSuffixes[k]) + "' column");
    int quat_parts = 0;
    for (int k = 3; k < kSuffixCount; ++k) quat_parts += slots[static_cast<std::size_t>(k)] >= 0;
    if (quat_parts != 0 && quat_parts != 4)
      fail.at(1, col, "incomplete orientation: point '" + name + "' needs all of _qw, _qx, _qy, _qz (has " +
                          std::to_string(quat_parts) + ")");
    table.points[p].has_rotation = quat_parts == 4;
  }
  return h;
}

void append_number(std::string& out, double v) {
  if (!std::isfinite(v)) return;  // an empty cell marks a dropped sample
  char buf[64];
  auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, ptr);
}

}  // namespace

bool TrackerTable::has(std::string_view name) const {
  for (const auto& p : points)
    if (p.name == name) return true;
  return false;
}

const TrackedPoint& TrackerTable::point(std::string_view name) const {
  for (const auto& p : points)
    if (p.name == name) return p;
  std::string names;
  for (const auto& p : points) names += (names.empty() ? "" : ", ") + p.name;
  throw Error("tracker table has no point '" + std::string(name) + "' (it has: " + (names.empty() ? "none" : names) + ")");
}

TrackerTable parse_tracker_csv(std::string_view text, std::string_view source) {
  text = text_body(text, source);  // UTF-16 is named; a UTF-8 byte-order mark is skipped
  const Failure fail{source};
  TrackerTable table;
  std::vector<Cell> cells;
  std::optional<Header> header;
  std::vector<double> row;
  int line_no = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t nl = text.find('\n', pos);
    const std::string_view line = text.substr(pos, nl == std::string_view::npos ? text.npos : nl - pos);
    pos = nl == std::string_view::npos ? text.size() : nl + 1;
    ++line_no;
    if (trim(line).empty()) continue;  // blank lines (e.g. a trailing one) carry nothing
    split_cells(line, cells);
    if (!header) {
      if (line_no != 1) fail.at(line_no, 1, "the header must be on line 1 (found blank lines before it)");
      header = parse_header(cells, table, fail);
      continue;
    }
    if (cells.size() != header->columns.size())
      fail.at(line_no, cells.size() > header->columns.size() ? cells[header->columns.size()].column : static_cast<int>(line.size()) + 1,
              "wrong cell count: the row has " + std::to_string(cells.size()) + " cells, the header has " +
                  std::to_string(header->columns.size()));
    row.resize(cells.size());
    for (std::size_t i = 0; i < cells.size(); ++i) {
      auto v = parse_cell(cells[i].text);
      if (!v)
        fail.at(line_no, cells[i].column, "cell '" + printable_text(cells[i].text, 40) + "' in column " +
                                              std::to_string(i + 1) + " is not a number");
      row[i] = *v;
    }
    if (std::isnan(row[0])) fail.at(line_no, cells[0].column, "the time cell is empty or NaN; every row needs a time");
    if (!table.time.empty() && !(row[0] > table.time.back()))
      fail.at(line_no, cells[0].column, "time " + printable_text(cells[0].text, 40) + " is not after the previous row's time (times must increase strictly)");
    table.time.push_back(row[0]);
    for (std::size_t p = 0; p < table.points.size(); ++p) {
      TrackedPoint& pt = table.points[p];
      const auto& slot = header->cell_of[p];
      auto at = [&](int k) { return row[static_cast<std::size_t>(slot[static_cast<std::size_t>(k)])]; };
      Vec3 pos3(at(0), at(1), at(2));
      Quat q = Quat::Identity();
      bool ok = pos3.allFinite();
      if (pt.has_rotation) {
        q = Quat(at(3), at(4), at(5), at(6));
        const double norm = q.norm();
        if (q.coeffs().allFinite() && norm < 1e-9)
          fail.at(line_no, cells[static_cast<std::size_t>(slot[3])].column, "orientation of '" + pt.name + "' is a zero quaternion");
        ok = ok && q.coeffs().allFinite();
        if (ok) q.normalize();
      }
      // A partly filled sample is dropped as a whole: downstream code trusts valid == 1.
      if (!ok) {
        pos3.setConstant(kNaN);
        q.coeffs().setConstant(kNaN);
      }
      pt.position.push_back(pos3);
      if (pt.has_rotation) pt.rotation.push_back(q);
      pt.valid.push_back(ok ? 1 : 0);
    }
  }
  if (!header) fail.at(1, 1, "empty file: expected a header line starting with 'time'");
  return table;
}

TrackerTable read_tracker_csv(const std::string& path) { return parse_tracker_csv(read_text_file(path), path); }

std::string format_tracker_csv(const TrackerTable& t) {
  const std::size_t n = t.time.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(t.time[i])) throw Error("format_tracker_csv: time " + std::to_string(i) + " is not finite");
    if (i > 0 && !(t.time[i] > t.time[i - 1]))
      throw Error("format_tracker_csv: time is not strictly increasing at sample " + std::to_string(i));
  }
  std::string out = "time";
  for (const auto& p : t.points) {
    if (p.position.size() != n || p.valid.size() != n || (p.has_rotation && p.rotation.size() != n))
      throw Error("format_tracker_csv: point '" + p.name + "' does not have one sample per time (" +
                  std::to_string(n) + ")");
    if (p.name.empty() || p.name.find_first_of(",\n\r") != std::string::npos)
      throw Error("format_tracker_csv: point name '" + p.name + "' is empty or contains a comma or line break");
    for (int k = 0; k < (p.has_rotation ? kSuffixCount : 3); ++k) out += "," + p.name + std::string(kSuffixes[k]);
  }
  out += '\n';
  for (std::size_t i = 0; i < n; ++i) {
    append_number(out, t.time[i]);
    for (const auto& p : t.points) {
      const bool ok = p.valid[i] != 0;
      for (int k = 0; k < 3; ++k) out += ',', append_number(out, ok ? p.position[i][k] : kNaN);
      if (p.has_rotation) {
        const Quat& q = p.rotation[i];
        for (double v : {q.w(), q.x(), q.y(), q.z()}) out += ',', append_number(out, ok ? v : kNaN);
      }
    }
    out += '\n';
  }
  return out;
}

void write_tracker_csv(const std::string& path, const TrackerTable& t) { write_text_file(path, format_tracker_csv(t)); }

}  // namespace legwork::io
