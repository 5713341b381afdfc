#include "demcal/dem3d/heap_section_fit.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "demcal/core/error.hpp"

namespace demcal::dem3d {

HeapSectionFit fit_heap_sections(const std::vector<double>& x, const std::vector<double>& y,
                                 const std::vector<double>& z, const std::vector<double>& r, double base_z_m,
                                 const HeapSectionOptions& options) {
  if (options.sections < 1) throw Error("fit_heap_sections: needs at least one section");
  if (!(options.slab_width_m > 0)) throw Error("fit_heap_sections: the slab width must be positive");
  HeapSectionFit fit;
  double sum = 0, sum2 = 0;
  for (std::size_t k = 0; k < options.sections; ++k) {
    const double phi = M_PI * static_cast<double>(k) / static_cast<double>(options.sections);
    const double c = std::cos(phi), s = std::sin(phi);
    std::vector<double> along, height, radius;
    for (std::size_t i = 0; i < x.size(); ++i)
      if (std::abs(-x[i] * s + y[i] * c) <= 0.5 * options.slab_width_m) {
        along.push_back(x[i] * c + y[i] * s);
        height.push_back(z[i]);
        radius.push_back(r[i]);
      }
    dem::ReposeFit section;
    try {
      section = dem::fit_angle_of_repose(along, height, radius, base_z_m, options.profile);
    } catch (const Error& e) {
      throw Error("the section at azimuth " + std::to_string(static_cast<int>(std::lround(phi * 180 / M_PI))) +
                  " deg: " + e.what());
    }
    for (double a : {section.left_deg, section.right_deg}) {
      fit.flank_deg.push_back(a);
      sum += a;
      sum2 += a * a;
    }
    fit.height_m = std::max(fit.height_m, section.height_m);
    fit.sections.push_back(std::move(section));
  }
  const double n = static_cast<double>(fit.flank_deg.size());
  fit.mean_deg = sum / n;
  fit.sd_deg = n > 1 ? std::sqrt(std::max(0.0, (sum2 - n * fit.mean_deg * fit.mean_deg) / (n - 1))) : 0.0;
  return fit;
}

}  // namespace demcal::dem3d
