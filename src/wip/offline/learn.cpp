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
  std::vector<double> depths;
  for (std::size_t i = 0; i < n; ++i) {
    const Info& fr = frames[i];
    if (!fr.walking || fr.lead < 0 || fr.time < settle) continue;
    for (int f = 0; f < 2; ++f) {
      const double z = truth[f][i];
      if (!std::isfinite(z) || !std::isfinite(fr.cycle[f])) continue;
      out.push_back({fr.cycle[f], fr.cycle[1 - f], fr.lead == f ? 1 : 0, fr.since_strike,
                     0.5 * (fr.apex_estimate[0] + fr.apex_estimate[1]), 1 / fr.stride_period, z / leg_length, 0,
                     fr.turn_rate});
      depths.push_back(z / leg_length);
    }
  }
  if (depths.size() < 2) return {};
  std::sort(depths.begin(), depths.end());
  auto at = [&](double p) { return depths[static_cast<std::size_t>(p * static_cast<double>(depths.size() - 1))]; };
  const double amplitude = 0.5 * (at(0.95) - at(0.05));
  if (!(amplitude > 1e-3)) return {};  // the feet never moved apart: nothing to learn
  for (auto& s : out) s.amplitude = amplitude;
  return out;
}

namespace {

constexpr int kN = LearnedMapping::kNodes, kS = LearnedMapping::kSinceNodes;

// Empty nodes (no weight) take the value of the nearest filled node of the
// same lead slice (distance in grid steps over since, own, other).
void fill_empty(LearnedMapping& m, const std::vector<double>& weight) {
  constexpr double kMin = 1e-3;
  LearnedMapping filled = m;
  for (int l = 0; l < 2; ++l)
    for (int k = 0; k < kS; ++k)
      for (int i = 0; i < kN; ++i)
        for (int j = 0; j < kN; ++j) {
          if (weight[LearnedMapping::index(l, k, i, j)] >= kMin) continue;
          int best = -1;
          for (int c = 0; c < kS; ++c)
            for (int a = 0; a < kN; ++a)
              for (int b = 0; b < kN; ++b) {
                const int d = (c - k) * (c - k) + (a - i) * (a - i) + (b - j) * (b - j);
                if (weight[LearnedMapping::index(l, c, a, b)] >= kMin && (best < 0 || d < best))
                  best = d, filled.at(l, k, i, j) = m.at(l, c, a, b);
              }
          if (best < 0)
            throw Error("learned walking-in-place mapping: no training frame with lead foot " + std::to_string(l));
        }
  m.shape = filled.shape;
}

// Amplitude = intercept + slope * apex + cadence_slope * cadence, least
// squares over the frames (centred normal equations, 2 x 2).
void fit_amplitude(std::span<const LearnSample> samples, LearnedMapping& m) {
  const double n = static_cast<double>(samples.size());
  double sa = 0, sc = 0, sz = 0;
  m.amplitude_min = m.amplitude_max = samples[0].amplitude;
  for (const auto& s : samples) {
    sa += s.apex, sc += s.cadence, sz += s.amplitude;
    m.amplitude_min = std::min(m.amplitude_min, s.amplitude);
    m.amplitude_max = std::max(m.amplitude_max, s.amplitude);
  }
  m.apex_mean = sa / n;
  m.cadence_mean = sc / n;
  const double z_mean = sz / n;
  double aa = 0, ac = 0, cc = 0, az = 0, cz = 0;
  for (const auto& s : samples) {
    const double a = s.apex - m.apex_mean, c = s.cadence - m.cadence_mean, z = s.amplitude - z_mean;
    aa += a * a, ac += a * c, cc += c * c, az += a * z, cz += c * z;
  }
  const double det = aa * cc - ac * ac;
  m.amplitude_slope = m.cadence_slope = 0;
  if (det > 1e-12 * std::max(1.0, aa * cc)) {
    m.amplitude_slope = (az * cc - cz * ac) / det;
    m.cadence_slope = (cz * aa - az * ac) / det;
  } else if (aa > 1e-12) {
    m.amplitude_slope = az / aa;
  }
  m.amplitude_intercept = z_mean - m.amplitude_slope * m.apex_mean - m.cadence_slope * m.cadence_mean;
}

// Turning gain: the true depth against the table's prediction p and p * the
// clamped turn rate, least squares without a constant (2 x 2 normal
// equations); no turn term when the frames do not determine it.
void fit_turn_gain(std::span<const LearnSample> samples, LearnedMapping& m) {
  m.turn_intercept = 1.0;
  m.turn_slope = 0.0;
  double pp = 0, pr = 0, rr = 0, pz = 0, rz = 0;
  for (const auto& s : samples) {
    const double p = m.amplitude(s.apex, s.cadence) * m.lookup(s.own, s.other, s.lead ? 1 : 0, s.since);
    const double r = p * std::clamp(std::isfinite(s.turn) ? s.turn : 0.0, 0.0, LearnedMapping::kMaxTurnRate);
    pp += p * p, pr += p * r, rr += r * r, pz += p * s.z, rz += r * s.z;
  }
  const double det = pp * rr - pr * pr;
  if (!(det > 1e-9 * std::max(1e-300, pp * rr))) return;
  const double a = (pz * rr - rz * pr) / det, b = (rz * pp - pz * pr) / det;
  // An intercept outside [0, kMaxTurnGain] (what the reader accepts) would write a
  // table no one can read: then no turn term.
  if (std::isfinite(a) && std::isfinite(b) && a >= 0 && a <= LearnedMapping::kMaxTurnGain) m.turn_intercept = a, m.turn_slope = b;
}

}  // namespace

LearnedMapping build_learned_mapping(std::span<const LearnSample> samples, int min_samples) {
  if (static_cast<int>(samples.size()) < min_samples || samples.empty())
    throw Error("learned walking-in-place mapping: " + std::to_string(samples.size()) +
                " training frames while walking (need at least " + std::to_string(min_samples) + ")");
  LearnedMapping m;
  std::vector<double> weight(m.shape.size(), 0.0);
  for (const auto& s : samples) {
    int i, j, k;
    double a, b, c;
    locate_cycle(s.own, i, a);
    locate_cycle(s.other, j, b);
    locate_since(s.since, k, c);
    for (int dk = 0; dk < 2; ++dk)
      for (int di = 0; di < 2; ++di)
        for (int dj = 0; dj < 2; ++dj) {
          const double w = (dk ? c : 1 - c) * (di ? a : 1 - a) * (dj ? b : 1 - b);
          const std::size_t n = LearnedMapping::index(s.lead ? 1 : 0, k + dk, i + di, j + dj);
          weight[n] += w;
          m.shape[n] += w * s.z / s.amplitude;
        }
  }
  for (std::size_t k = 0; k < weight.size(); ++k) m.shape[k] = weight[k] > 0 ? m.shape[k] / weight[k] : 0;
  fill_empty(m, weight);
  fit_amplitude(samples, m);
  fit_turn_gain(samples, m);
  m.samples = static_cast<int>(samples.size());
  return m;
}

std::string format_learned_mapping(const LearnedMapping& m, const std::string& source) {
  std::ostringstream o;
  o << "legwork-wip-learned-mapping 2\n";
  o << "# depth / walk amplitude of a foot by (own cycle coordinate: rows, other foot's: columns) over 0..2;\n"
       "# built by `legwork wip learn` (legwork/wip/offline/learn.hpp), not edited by hand\n";
  char b[64];
  auto num = [&](double v) {
    std::snprintf(b, sizeof b, "%.6g", v);
    return std::string(b);
  };
  o << "nodes " << LearnedMapping::kNodes << "\namplitude_intercept " << num(m.amplitude_intercept)
    << "\namplitude_slope " << num(m.amplitude_slope) << "\ncadence_slope " << num(m.cadence_slope)
    << "\namplitude_min " << num(m.amplitude_min) << "\namplitude_max " << num(m.amplitude_max) << "\napex_mean "
    << num(m.apex_mean) << "\ncadence_mean " << num(m.cadence_mean) << "\nturn_intercept " << num(m.turn_intercept)
    << "\nturn_slope " << num(m.turn_slope) << "\nsamples " << m.samples << "\nsource "
    << source << "\n";
  for (int l = 0; l < 2; ++l) {
    o << "lead " << l << "\n";
    for (int k = 0; k < kS; ++k) {
      o << "since " << num(LearnedMapping::kSince[static_cast<std::size_t>(k)]) << "\n";
      for (int i = 0; i < kN; ++i) {
        for (int j = 0; j < kN; ++j) o << (j ? " " : "") << num(m.at(l, k, i, j));
        o << "\n";
      }
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

// One table row: kNodes finite numbers.
void read_row(LineReader& r, LearnedMapping& m, int l, int k, int i) {
  const std::string where = "lead " + std::to_string(l) + " since node " + std::to_string(k) + " row " + std::to_string(i);
  if (!r.next()) r.fail("file ends inside the table (" + where + ")");
  std::istringstream ls(r.line);
  for (int j = 0; j < kN; ++j) {
    double v = NAN;
    ls >> v;
    if (ls.fail() || !std::isfinite(v))
      r.fail(where + ": column " + std::to_string(j) + " is not a finite number (need " + std::to_string(kN) + " numbers)");
    m.at(l, k, i, j) = v;
  }
  std::string extra;
  if (ls >> extra) r.fail(where + ": more than " + std::to_string(kN) + " numbers");
}

}  // namespace

LearnedMapping parse_learned_mapping(const std::string& text, const std::string& path) {
  LineReader r{std::istringstream(text), path, "", 0};
  // Format 2 adds the turning gain (turn_intercept, turn_slope); format 1
  // tables read as before (no turn term).
  const bool v1 = r.next() && r.line == "legwork-wip-learned-mapping 1";
  if (!v1 && r.line != "legwork-wip-learned-mapping 2")
    r.fail("not a learned walking-in-place mapping (expected the header 'legwork-wip-learned-mapping 2', or 1)");
  LearnedMapping m;
  if (r.value("nodes") != kN) r.fail("'nodes' must be " + std::to_string(kN));
  m.amplitude_intercept = r.value("amplitude_intercept");
  m.amplitude_slope = r.value("amplitude_slope");
  m.cadence_slope = r.value("cadence_slope");
  m.amplitude_min = r.value("amplitude_min");
  m.amplitude_max = r.value("amplitude_max");
  if (!(m.amplitude_min > 0) || m.amplitude_max < m.amplitude_min)
    r.fail("'amplitude_min' must be positive and at most 'amplitude_max'");
  m.apex_mean = r.value("apex_mean");
  m.cadence_mean = r.value("cadence_mean");
  if (!v1) {
    m.turn_intercept = r.value("turn_intercept");
    m.turn_slope = r.value("turn_slope");
    if (m.turn_intercept < 0 || m.turn_intercept > LearnedMapping::kMaxTurnGain)
      r.fail("'turn_intercept' must be within [0, 2] (LearnedMapping::kMaxTurnGain)");
  }
  // A count, checked before the cast (wip_table_fuzz: 2e87 overflowed the int).
  const double samples = r.value("samples");
  if (!(samples >= 0 && samples <= 1e9) || samples != std::floor(samples))
    r.fail("'samples' must be a whole number from 0 to 1000000000");
  m.samples = static_cast<int>(samples);
  if (!r.next() || r.line.rfind("source", 0) != 0) r.fail("expected 'source <text>'");
  for (int l = 0; l < 2; ++l) {
    if (r.value("lead") != l) r.fail("expected 'lead " + std::to_string(l) + "'");
    for (int k = 0; k < kS; ++k) {
      const double since = LearnedMapping::kSince[static_cast<std::size_t>(k)];
      if (std::abs(r.value("since") - since) > 1e-9) r.fail("expected 'since " + std::to_string(since) + "'");
      for (int i = 0; i < kN; ++i) read_row(r, m, l, k, i);
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
