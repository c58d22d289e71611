#pragma once
// Plausibility limits shared by the runtimes and the server.

namespace legwork {

// Plausible standing heights of a user (metres) for the runtimes that scale
// an avatar to one: outside this range a typo or a wrong unit is far more
// likely than a user (0.1 m made every accentuation frame unmatched).
inline constexpr double kMinUserHeight = 0.5;
inline constexpr double kMaxUserHeight = 2.5;

}  // namespace legwork
