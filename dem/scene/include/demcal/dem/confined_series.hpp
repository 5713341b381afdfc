#pragma once
// What a confined series shares in either dimension (the 2D biaxial, the 3D
// triaxial): its outputs, numbered per confinement, the numbered values one
// confinement's test adds to the series, and the envelopes through the peaks.
#include <string>
#include <vector>

#include "demcal/dem/lab_test.hpp"
#include "demcal/dem/test_result.hpp"

namespace demcal::dem {

// The outputs of a series at `confinements_pa`: per confinement k, q_peak_MPa_k,
// sigma_1_peak_MPa_k, sigma_3_peak_MPa_k, E_GPa_k, nu_k, peak_strain_k, cracks
// by mode and while confining, reached_strain_limit_k; with two or more, the
// Mohr-Coulomb (c_MPa, phi_deg, mc_sigma_c_MPa, mc_r2) and Hoek-Brown (hb_m_i,
// hb_sigma_c_MPa, hb_r2) envelopes. `confining_wall` names what measures
// sigma_3 ("the side walls"), `lateral_gauge` what nu's lateral strain comes
// from ("side walls").
std::vector<OutputSpec> confined_series_outputs(const std::vector<double>& confinements_pa,
                                                const std::string& confining_wall, const std::string& lateral_gauge,
                                                OutputRange nu_range);

// One confined test's values from its curve (the deviator q against the axial
// strain): the compression test's (ucs_macro_values: sigma_u is q's peak, E,
// nu, ...), sigma_1 and sigma_3 at the peak, and reached_strain_limit; on a
// curve too short to evaluate, ok false and the reason.
void add_confined_values(TestResult& result);

// Adds confinement `n`'s numbered values (from its test's sigma_u_MPa, E_GPa,
// nu, ...) to the series.
void add_confinement_outputs(const TestResult& one, const std::string& n, TestResult& series);

// The Mohr-Coulomb and Hoek-Brown envelopes through the peaks (Pa) into the
// series' outputs; false with series.reason set when Mohr-Coulomb fails. A
// missing Hoek-Brown envelope is said in series.ended_by.
bool add_envelopes(const std::vector<double>& sigma_3_pa, const std::vector<double>& sigma_1_pa, TestResult& series);

}  // namespace demcal::dem
