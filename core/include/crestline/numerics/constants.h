#pragma once
// Mathematical constants shared by the stages, spelled once (<cmath>'s M_PI
// is POSIX, not C++17).
namespace crestline {

/// π, the nearest double.
constexpr double kPi = 3.14159265358979323846;

}  // namespace crestline
