#pragma once
// A slope section for 2D dynamic runs (Ma et al. 2022's rockfill slope): a
// bedrock of large disks below a surface profile, and layers (zones) of
// smaller disks above it, each bounded below by what lies under it and above
// by its own top profile. Made as PFC users make one: each part is packed by
// radius expansion in boxes (genesis.hpp, cached per box and seed) and the
// disks not wholly inside its region are deleted; a zone's disks that would overlap a
// disk of the part below are deleted too, so the parts meet without
// interpenetrating and the test's gravity settling closes the gaps.
#include <cstdint>
#include <string>
#include <vector>

namespace demcal::dem {

// A profile y(x) through points of strictly increasing x (one that turns
// back on itself is refused); linear between them, and only defined between
// its first and last x.
struct Profile {
  std::vector<double> x, y;
  double at(double x_m) const;  // x_m clamped to the profile's range
  double min_y(double from_x_m, double to_x_m) const;
  double max_y(double from_x_m, double to_x_m) const;
  bool covers(double x_m) const { return !x.empty() && x_m >= x.front() && x_m <= x.back(); }
  // Area between the profile and y = `base_y` over its range (where above it), m^2.
  double area_above(double base_y_m) const;
  // An Error "<where>: ..." when fewer than 2 points, x not strictly increasing or a value not finite.
  void validate(const std::string& where) const;
};

// The disks of one part (the bedrock or a zone), packed by radius expansion.
struct SlopePart {
  std::string name;
  double radius_min_m = 1, radius_max_m = 1, porosity = 0.16, density_kg_m3 = 2600;
};

struct SlopeZone {
  SlopePart part;
  Profile top;  // the zone lies between what is under it and this profile, over its x range
};

struct SlopeSpec {
  double width_m = 0, height_m = 0, thickness_m = 1;
  SlopePart bedrock;
  Profile bedrock_surface;  // spans 0 .. width_m
  std::vector<SlopeZone> zones;  // bottom-up: each lies on the bedrock and the zones before it
  double column_width_m = 50;    // a zone is packed in boxes this wide, so a thin layer is not packed in a tall box
  std::uint64_t seed = 1;
  // An Error "<where>.<field>: ..." on anything out of range (profiles outside the model, a zone with no room).
  void validate(const std::string& where) const;
  // The top of what lies under zone `z` at x: the bedrock's surface, raised by the tops of the zones before z
  // that cover x. With z = zones.size(), the material's surface.
  double top_below_zone(std::size_t z, double x_m) const;
  double surface_at(double x_m) const { return top_below_zone(zones.size(), x_m); }
};

struct SlopeSpecimen {
  std::vector<double> x, y, radius;
  std::vector<std::uint8_t> part;  // 0: bedrock; k + 1: zone k
  std::vector<std::string> part_names;
  std::vector<double> part_density_kg_m3;
  std::vector<double> part_porosity;  // the porosity its boxes were packed to
  std::vector<double> part_area_m2;  // the region each part fills
  std::vector<std::size_t> part_disks;
  double width_m = 0, height_m = 0, thickness_m = 1;
  SlopeSpec geometry;  // what it was built from
  std::size_t size() const { return x.size(); }
};

// Packs (or loads from `cache_dir`, empty: no cache) every part's boxes and cuts them to the slope.
SlopeSpecimen build_slope_specimen(const SlopeSpec& spec, const std::string& cache_dir);

}  // namespace demcal::dem
