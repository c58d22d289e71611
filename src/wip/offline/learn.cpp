#include <legwork/wip/offline/learn.hpp>

#include <legwork/core/types.hpp>
#include <legwork/io/text.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace legwork::wip {

std::vector<LearnSample> learning_samples(std::span<const Info> frames, std::span<const double> true_left,
                                          std::span<const double> true_right, double leg_length, double settle) {
  std::vector<LearnSample> out;
  const std::span<const double> truth[2] = {true_left, true_right};
  const std::size_t n = std::min({frames.size(), true_left.size(), true_right.size()});
  for (std::size_t i = 0; i < n; ++i) {
    const Info& fr = frames[i];
    if (!fr.walking || fr.lead < 0 || fr.time < settle) continue;
    for (int f = 0; f < 2; ++f) {
      const double z = truth[f][i];
      if (!std::isfinite(z) || !std::isfinite(fr.cycle[f])) continue;
      out.push_back({fr.cycle[f], fr.cycle[1 - f], fr.lead == f ? 1 : 0,
                     0.5 * (fr.apex_estimate[0] + fr.apex_estimate[1]), z / leg_length});
    }
  }
  return out;
}

namespace {

constexpr int kN = LearnedMapping::kNodes;

// Node index and fraction of a coordinate in [0, 2] (as the lookup does).
void locate(double c, int& i, double& t) {
  const double x = std::clamp(c, 0.0, 2.0) * (kN - 1) / 2.0;
  i = std::min(static_cast<int>(x), kN - 2);
  t = x - i;
}

// Empty nodes (no weight) take the value of the nearest filled node of the same slice.
void fill_empty(LearnedMapping& m, const std::vector<double>& weight) {
  auto w = [&](int l, int i, int j) { return weight[static_cast<std::size_t>((l * kN + i) * kN + j)]; };
  constexpr double kMin = 1e-3;
  LearnedMapping filled = m;
  for (int l = 0; l < 2; ++l)
    for (int i = 0; i < kN; ++i)
      for (int j = 0; j < kN; ++j) {
        if (w(l, i, j) >= kMin) continue;
        int best = -1;
        double best_value = 0;
        for (int a = 0; a < kN; ++a)
          for (int b = 0; b < kN; ++b) {
            const int d = (a - i) * (a - i) + (b - j) * (b - j);
            if (w(l, a, b) >= kMin && (best < 0 || d < best)) best = d, best_value = m.at(l, a, b);
          }
        if (best < 0) throw Error("learned walking-in-place mapping: no training frame with lead foot " + std::to_string(l));
        filled.at(l, i, j) = best_value;
      }
  m.depth = filled.depth;
}

}  // namespace

LearnedMapping build_learned_mapping(std::span<const LearnSample> samples, int min_samples) {
  if (static_cast<int>(samples.size()) < min_samples)
    throw Error("learned walking-in-place mapping: " + std::to_string(samples.size()) +
                " training frames while walking (need at least " + std::to_string(min_samples) + ")");
  LearnedMapping m;
  std::vector<double> weight(m.depth.size(), 0.0);
  for (const auto& s : samples) {
    int i, j;
    double a, b;
    locate(s.own, i, a);
    locate(s.other, j, b);
    const double w[2][2] = {{(1 - a) * (1 - b), (1 - a) * b}, {a * (1 - b), a * b}};
    for (int di = 0; di < 2; ++di)
      for (int dj = 0; dj < 2; ++dj) {
        const auto k = static_cast<std::size_t>(((s.lead ? 1 : 0) * kN + i + di) * kN + j + dj);
        weight[k] += w[di][dj];
        m.depth[k] += w[di][dj] * s.z;
      }
  }
  for (std::size_t k = 0; k < weight.size(); ++k) m.depth[k] = weight[k] > 0 ? m.depth[k] / weight[k] : 0;
  fill_empty(m, weight);
  // Gain: z = t (1 + slope (apex - apex_mean)), least squares in slope.
  double apex_sum = 0;
  for (const auto& s : samples) apex_sum += s.apex;
  m.apex_mean = apex_sum / static_cast<double>(samples.size());
  double num = 0, den = 0;
  for (const auto& s : samples) {
    const double t = m.lookup(s.own, s.other, s.lead);
    const double x = t * (s.apex - m.apex_mean);
    num += (s.z - t) * x;
    den += x * x;
  }
  m.gain_slope = den > 1e-12 ? num / den : 0;
  m.samples = static_cast<int>(samples.size());
  return m;
}

std::string format_learned_mapping(const LearnedMapping& m, const std::string& source) {
  std::ostringstream o;
  o << "legwork-wip-learned-mapping 1\n";
  o << "# z / leg length of a foot by (own cycle coordinate: rows, other foot's: columns) over 0..2;\n"
       "# built by `legwork wip learn` (legwork/wip/offline/learn.hpp), not edited by hand\n";
  char b[64];
  auto num = [&](double v) {
    std::snprintf(b, sizeof b, "%.6g", v);
    return std::string(b);
  };
  o << "nodes " << LearnedMapping::kNodes << "\napex_mean " << num(m.apex_mean) << "\ngain_slope " << num(m.gain_slope)
    << "\ngain_min " << num(m.gain_min) << "\ngain_max " << num(m.gain_max) << "\nsamples " << m.samples
    << "\nsource " << source << "\n";
  for (int l = 0; l < 2; ++l) {
    o << "lead " << l << "\n";
    for (int i = 0; i < kN; ++i) {
      for (int j = 0; j < kN; ++j) o << (j ? " " : "") << num(m.at(l, i, j));
      o << "\n";
    }
  }
  return o.str();
}

namespace {

struct LineReader {
  std::istringstream in;
  std::string path, line;
  int number = 0;
  bool next() {  // skips comments and blank lines
    while (std::getline(in, line)) {
      ++number;
      if (!line.empty() && line.back() == '\r') line.pop_back();
      if (line.empty() || line[0] == '#') continue;
      return true;
    }
    return false;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw Error(path + ":" + std::to_string(number) + ": " + what);
  }
  // "key value" with a number value.
  double value(const std::string& key) {
    if (!next()) fail("file ends before '" + key + "'");
    std::istringstream ls(line);
    std::string k;
    double v = NAN;
    ls >> k >> v;
    if (k != key) fail("expected '" + key + " <number>', found '" + line + "'");
    if (ls.fail() || !std::isfinite(v)) fail("'" + key + "' is not a finite number");
    return v;
  }
};

}  // namespace

LearnedMapping parse_learned_mapping(const std::string& text, const std::string& path) {
  LineReader r{std::istringstream(text), path, "", 0};
  if (!r.next() || r.line != "legwork-wip-learned-mapping 1")
    r.fail("not a learned walking-in-place mapping (expected the header 'legwork-wip-learned-mapping 1')");
  LearnedMapping m;
  if (r.value("nodes") != kN) r.fail("'nodes' must be " + std::to_string(kN));
  m.apex_mean = r.value("apex_mean");
  m.gain_slope = r.value("gain_slope");
  m.gain_min = r.value("gain_min");
  m.gain_max = r.value("gain_max");
  if (!(m.gain_min > 0) || m.gain_max < m.gain_min) r.fail("'gain_min' must be positive and at most 'gain_max'");
  m.samples = static_cast<int>(r.value("samples"));
  if (!r.next() || r.line.rfind("source", 0) != 0) r.fail("expected 'source <text>'");
  for (int l = 0; l < 2; ++l) {
    if (r.value("lead") != l) r.fail("expected 'lead " + std::to_string(l) + "'");
    for (int i = 0; i < kN; ++i) {
      if (!r.next()) r.fail("file ends inside the lead " + std::to_string(l) + " table (row " + std::to_string(i) + ")");
      std::istringstream ls(r.line);
      for (int j = 0; j < kN; ++j) {
        double v = NAN;
        ls >> v;
        if (ls.fail() || !std::isfinite(v))
          r.fail("lead " + std::to_string(l) + " table row " + std::to_string(i) + ": column " + std::to_string(j) +
                 " is not a finite number (need " + std::to_string(kN) + " numbers)");
        m.at(l, i, j) = v;
      }
      std::string extra;
      if (ls >> extra) r.fail("lead " + std::to_string(l) + " table row " + std::to_string(i) + ": more than " +
                             std::to_string(kN) + " numbers");
    }
  }
  return m;
}

void write_learned_mapping(const std::string& path, const LearnedMapping& m, const std::string& source) {
  io::write_text_file(path, format_learned_mapping(m, source));
}

LearnedMapping read_learned_mapping(const std::string& path) {
  return parse_learned_mapping(io::read_text_file(path), path);
}

}  // namespace legwork::wip
