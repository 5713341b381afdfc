#pragma once
// An earthquake record as the input of a dynamic test: the ground
// acceleration read from a text file, integrated into the particle velocity
// an input boundary sends (trapezoid rule), with a baseline correction that
// leaves the ground at rest when the record ends. A viscous input boundary
// (Lysmer and Kuhlemeyer) takes a velocity, not an acceleration: its dashpot
// acts on v - 2 v_wave.
#include <string>
#include <vector>

namespace demcal::dem {

// How the file lists the record: "values" (accelerations only, in order, any
// number per line, at a time step given in the scene: the PEER / Peknold
// layout) or "time_value" (two numbers per line, time and acceleration, at an
// even time step).
enum class RecordFormat { values, time_value };

// How the velocity is corrected: none, or by the constant acceleration offset
// v(T) / T that brings the integrated velocity back to zero at the record's
// end T (a linear baseline on the velocity, zero at both ends), so the input
// leaves the model neither moving nor drifting.
enum class Baseline { none, end_at_rest };

struct GroundMotion {
  double dt_s = 0;
  std::vector<double> acceleration_m_s2;  // corrected
  std::vector<double> velocity_m_s;       // v(0) = 0
  double baseline_offset_m_s2 = 0;        // what the correction subtracted from every acceleration
  double duration_s() const { return dt_s * static_cast<double>(velocity_m_s.size() - 1); }
  // Linear between samples; 0 before 0 and after the record.
  double velocity_at(double t_s) const;
  double peak_speed_m_s() const;
  double peak_acceleration_m_s2() const;
};

// Reads the accelerations of `path` (lines starting with '#' and blank lines
// skipped). `time_step_s` is used with RecordFormat::values and checked
// against the file's own with time_value. Throws an Error naming the file and
// line for a value that is not a number, a time_value line without exactly
// two numbers, or an uneven time step; `where` names the scene section
// ("s.json: earthquake") for a file that cannot be read or a missing step.
std::vector<double> read_acceleration_record(const std::string& path, RecordFormat format, double& time_step_s,
                                             const std::string& where);

// The first `duration_s` of `acceleration` (all of it when <= 0) times
// `scale_to_m_s2`, integrated, baseline-corrected.
GroundMotion ground_motion(const std::vector<double>& acceleration, double time_step_s, double scale_to_m_s2,
                           double duration_s, Baseline baseline);

}  // namespace demcal::dem
