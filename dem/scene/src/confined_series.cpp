#include "demcal/dem/confined_series.hpp"

#include "demcal/core/error.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/dem/loading_monitor.hpp"
#include "demcal/dem/strength_envelope.hpp"

namespace demcal::dem {

std::vector<OutputSpec> confined_series_outputs(const std::vector<double>& confinements_pa,
                                                const std::string& confining_wall, const std::string& lateral_gauge,
                                                OutputRange nu_range) {
  std::vector<OutputSpec> out;
  for (std::size_t k = 0; k < confinements_pa.size(); ++k) {
    const std::string n = std::to_string(k + 1),
                      at = " at confinement " + n + " (" + format_double(confinements_pa[k] / 1e6) + " MPa)";
    out.push_back({"q_peak_MPa_" + n, "MPa", "peak deviatoric stress sigma_1 - sigma_3" + at, true, kNonNegative});
    out.push_back({"sigma_1_peak_MPa_" + n, "MPa", "axial stress at the peak" + at, true, kNonNegative});
    out.push_back({"sigma_3_peak_MPa_" + n, "MPa",
                   "confining stress " + confining_wall + " measured at the peak (the servo's, not the nominal one)" + at,
                   true, kNonNegative});
    out.push_back({"E_GPa_" + n, "GPa", "tangent d q / d eps_ax where q first reaches half its peak" + at, true,
                   kNonNegative});
    out.push_back({"nu_" + n, "1", "tangent d eps_lat / d eps_ax over the same window as E (" + lateral_gauge + ")" + at,
                   true, nu_range});
    out.push_back({"peak_strain_" + n, "1", "axial strain at the peak" + at, true, kNonNegative});
    out.push_back({"cracks_tension_" + n, "1", "bonds broken in tension" + at, true, kNonNegative});
    out.push_back({"cracks_shear_" + n, "1", "bonds broken in shear" + at, true, kNonNegative});
    out.push_back({"cracks_confining_" + n, "1", "bonds broken while the confinement was applied" + at, true, kNonNegative});
    out.push_back({"reached_strain_limit_" + n, "1",
                   "1 when loading.strain_limit ended the test before the post-peak stop" + at, false, kFlag});
  }
  if (confinements_pa.size() >= 2) {
    out.push_back({"c_MPa", "MPa", "Mohr-Coulomb cohesion sigma_c / (2 sqrt(N_phi)) of the least-squares line "
                                   "sigma_1 = sigma_c + N_phi sigma_3 through the peaks", true, kNonNegative});
    out.push_back({"phi_deg", "deg", "Mohr-Coulomb friction angle, asin((N_phi - 1) / (N_phi + 1))", true,
                   kAcuteAngleDeg});
    out.push_back({"mc_sigma_c_MPa", "MPa", "the envelope's intercept sigma_c (its uniaxial strength)", true,
                   kNonNegative});
    out.push_back({"mc_r2", "1", "coefficient of determination of the envelope's line", true, kAtMostOne});
    out.push_back({"hb_m_i", "1", "Hoek-Brown m_i of intact rock: the slope of (sigma_1 - sigma_3)^2 on sigma_3 "
                                  "over sigma_c (Hoek & Brown 1997); missing when that line has no positive "
                                  "intercept (ended_by says so)", false, kNonNegative});
    out.push_back({"hb_sigma_c_MPa", "MPa", "Hoek-Brown sigma_c: the square root of that line's intercept", false,
                   kNonNegative});
    out.push_back({"hb_r2", "1", "coefficient of determination of the Hoek-Brown line", false, kAtMostOne});
  }
  return out;
}

void add_confined_values(TestResult& result) {
  try {
    for (const auto& [name, value] : ucs_macro_values(result.curve)) result.macro[name] = value;
  } catch (const Error& e) {
    result.ok = false;
    result.reason = e.what();
    return;
  }
  std::size_t peak = 0;
  for (std::size_t k = 1; k < result.curve.size(); ++k)
    if (result.curve[k].stress_pa > result.curve[peak].stress_pa) peak = k;
  result.macro["sigma_1_peak_MPa"] = (result.curve[peak].stress_pa + result.curve[peak].confining_stress_pa) / 1e6;
  result.macro["sigma_3_peak_MPa"] = result.curve[peak].confining_stress_pa / 1e6;
  if (result.ended_by == "strain_limit") result.macro["reached_strain_limit"] = 1;
}

void add_confinement_outputs(const TestResult& one, const std::string& n, TestResult& series) {
  series.macro["q_peak_MPa_" + n] = one.macro.at("sigma_u_MPa");
  for (const char* name : {"sigma_1_peak_MPa", "sigma_3_peak_MPa", "E_GPa", "nu", "peak_strain", "cracks_tension",
                           "cracks_shear", "cracks_confining"})
    series.macro[std::string(name) + "_" + n] = one.macro.at(name);
  if (one.macro.count("reached_strain_limit")) series.macro["reached_strain_limit_" + n] = 1;
}

bool add_envelopes(const std::vector<double>& sigma_3_pa, const std::vector<double>& sigma_1_pa, TestResult& series) {
  try {
    const MohrCoulombFit fit = fit_mohr_coulomb(sigma_3_pa, sigma_1_pa);
    series.macro["c_MPa"] = fit.c_pa / 1e6;
    series.macro["phi_deg"] = fit.phi_deg;
    series.macro["mc_sigma_c_MPa"] = fit.sigma_c_pa / 1e6;
    series.macro["mc_r2"] = fit.r2;
  } catch (const Error& e) {
    series.reason = e.what();
    return false;
  }
  // Hoek-Brown is an extra reading of the same peaks: where its line has no
  // positive intercept the Mohr-Coulomb outputs still stand, and ended_by
  // says why the hb_ outputs are missing.
  try {
    const HoekBrownFit hb = fit_hoek_brown(sigma_3_pa, sigma_1_pa);
    series.macro["hb_m_i"] = hb.m_i;
    series.macro["hb_sigma_c_MPa"] = hb.sigma_c_pa / 1e6;
    series.macro["hb_r2"] = hb.r2;
  } catch (const Error& e) {
    series.ended_by += std::string("; no Hoek-Brown envelope: ") + e.what();
  }
  return true;
}

}  // namespace demcal::dem
