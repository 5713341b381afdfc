#pragma once
// Contact models behind one interface and a registry by name, in the manner
// of LAMMPS pair styles: a new model is one file plus one line in
// src/builtin_models.cpp. The world assigns a model to each pair of material
// groups (mortar-mortar, mortar-aggregate, disk-wall ...).
//
// A model computes the forces of a contiguous range of pairs in one call, so
// the virtual call happens once per model and step, not once per contact.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "demcal/dem/bodies.hpp"
#include "demcal/dem/contacts.hpp"
#include "demcal/dem/walls.hpp"

namespace demcal {
class Rng;
}

namespace demcal::dem {

struct StepContext {
  double dt_s = 0;
  double time_s = 0;
  double thickness_m = 1;
  std::vector<BreakEvent>* breaks = nullptr;  // where bond breaks are logged
};

// The two sides of a pair when it enters the neighbour list.
struct PairInfo {
  double radius_i = 0, radius_j = 0;  // radius_j = 0 for a wall
  std::uint8_t group_i = 0, group_j = 0;
  bool wall = false;
  double overlap = 0;  // current overlap (negative: a gap), set when a bond is installed
};

class ContactModel {
 public:
  virtual ~ContactModel() = default;
  virtual std::string name() const = 0;

  // Sets the constants of pair k (stiffness, friction) when it enters the list.
  virtual void initialise(ContactSet& c, std::size_t k, const PairInfo& pair, double thickness_m) const = 0;
  // Installs a bond on pair k (material genesis); false when the model has none.
  virtual bool install_bond(ContactSet& c, std::size_t k, const PairInfo& pair, double thickness_m, Rng& rng) const;

  // Adds the forces of disk pairs [begin, end) to the bodies.
  virtual void disk_forces(ContactSet& c, std::size_t begin, std::size_t end, Bodies& b,
                           const StepContext& step) const = 0;
  // Adds the forces of disk-wall pairs [begin, end) to the disks and walls.
  virtual void wall_forces(ContactSet& c, std::size_t begin, std::size_t end, Bodies& b, std::vector<Wall>& walls,
                           const StepContext& step) const = 0;

  // Translational and rotational stiffness pair k adds to a disk whose
  // contact lies `arm_m` from its centre (for the critical time step).
  virtual void stiffness(const ContactSet& c, std::size_t k, double arm_m, double& translational_n_m,
                         double& rotational_nm_rad) const;
  // Normal stiffness of a contact between two disks of radius r, for a disk
  // that has no neighbour yet (time step bound).
  virtual double normal_stiffness_estimate(double radius_m, double thickness_m) const = 0;
};

using ContactModelFactory =
    std::function<std::unique_ptr<ContactModel>(const nlohmann::json& parameters, const std::string& where)>;

class ContactModelRegistry {
 public:
  static ContactModelRegistry& instance();  // holds the built-in models
  void add(const std::string& name, ContactModelFactory factory);
  // Throws an Error naming the known models when `name` is unknown.
  std::unique_ptr<ContactModel> create(const std::string& name, const nlohmann::json& parameters,
                                       const std::string& where) const;
  std::vector<std::string> names() const;

 private:
  std::vector<std::pair<std::string, ContactModelFactory>> factories_;
};

}  // namespace demcal::dem
