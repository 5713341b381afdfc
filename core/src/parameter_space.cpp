#include "demcal/core/parameter_space.hpp"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "demcal/core/error.hpp"
#include "demcal/core/json_fields.hpp"
#include "demcal/core/number_format.hpp"

namespace demcal {
namespace {

using json = nlohmann::json;

double read_number(const json& object, const std::string& key, const std::string& where) {
  if (!object.contains(key)) throw Error(where + ": missing field \"" + key + "\"");
  const json& value = object.at(key);
  if (!value.is_number()) throw Error(where + ": field \"" + key + "\" must be a number");
  double number = value.get<double>();
  if (!std::isfinite(number)) throw Error(where + ": field \"" + key + "\" must be finite");
  return number;
}

std::string read_string(const json& object, const std::string& key, const std::string& where,
                        bool required) {
  if (!object.contains(key)) {
    if (required) throw Error(where + ": missing field \"" + key + "\"");
    return "";
  }
  if (!object.at(key).is_string()) throw Error(where + ": field \"" + key + "\" must be a string");
  return object.at(key).get<std::string>();
}

bool valid_name(const std::string& name) {
  if (name.empty()) return false;
  for (char c : name) {
    bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '-';
    if (!ok) return false;
  }
  return true;
}

}  // namespace

double Parameter::from_symmetric(double coded) const {
  // A point meant to lie on a bound lies on it exactly (mid - half can miss by rounding).
  if (coded == -1.0) return low;
  if (coded == 1.0) return high;
  if (log_scale) {
    double mid = 0.5 * (std::log(low) + std::log(high));
    double half = 0.5 * (std::log(high) - std::log(low));
    return std::exp(mid + coded * half);
  }
  return 0.5 * (low + high) + coded * 0.5 * (high - low);
}

double Parameter::from_unit(double unit_value) const { return from_symmetric(2.0 * unit_value - 1.0); }

double Parameter::to_symmetric(double natural) const {
  if (log_scale) {
    double mid = 0.5 * (std::log(low) + std::log(high));
    double half = 0.5 * (std::log(high) - std::log(low));
    return (std::log(natural) - mid) / half;
  }
  return (natural - 0.5 * (low + high)) / (0.5 * (high - low));
}

ParameterSpace ParameterSpace::from_json(const json& root, const std::string& origin) {
  if (!root.is_object()) throw Error(origin + ": a parameter space must be a JSON object");
  require_known_fields(root, {"description", "fixed", "parameters", "source", "tied"}, origin);
  if (!root.contains("parameters") || !root.at("parameters").is_array())
    throw Error(origin + ": missing array \"parameters\"");

  ParameterSpace space;
  const json& list = root.at("parameters");
  for (std::size_t i = 0; i < list.size(); ++i) {
    const json& item = list[i];
    std::string where = origin + ": parameters[" + std::to_string(i) + "]";
    if (!item.is_object()) throw Error(where + ": must be an object");
    require_known_fields(item, {"high", "levels", "log_scale", "low", "name", "note", "reference", "unit"}, where);
    Parameter p;
    p.name = read_string(item, "name", where, true);
    where += " (\"" + p.name + "\")";
    p.unit = read_string(item, "unit", where, false);
    p.low = read_number(item, "low", where);
    p.high = read_number(item, "high", where);
    if (item.contains("levels")) {
      if (!item.at("levels").is_array()) throw Error(where + ": \"levels\" must be an array of numbers");
      for (const auto& level : item.at("levels")) {
        if (!level.is_number() || !std::isfinite(level.get<double>()))
          throw Error(where + ": \"levels\" must hold finite numbers");
        p.levels.push_back(level.get<double>());
      }
    }
    if (item.contains("reference")) p.reference = read_number(item, "reference", where);
    if (item.contains("log_scale")) {
      if (!item.at("log_scale").is_boolean()) throw Error(where + ": \"log_scale\" must be true or false");
      p.log_scale = item.at("log_scale").get<bool>();
    }
    space.parameters_.push_back(p);
  }

  if (root.contains("fixed")) {
    const json& fixed = root.at("fixed");
    if (!fixed.is_object()) throw Error(origin + ": \"fixed\" must be an object of name: value");
    for (auto it = fixed.begin(); it != fixed.end(); ++it) {
      if (!it.value().is_number() || !std::isfinite(it.value().get<double>()))
        throw Error(origin + ": fixed." + it.key() + " must be a finite number");
      space.fixed_[it.key()] = it.value().get<double>();
    }
  }

  if (root.contains("tied")) {
    const json& tied = root.at("tied");
    if (!tied.is_array()) throw Error(origin + ": \"tied\" must be an array");
    for (std::size_t i = 0; i < tied.size(); ++i) {
      std::string where = origin + ": tied[" + std::to_string(i) + "]";
      const json& item = tied[i];
      if (!item.is_object()) throw Error(where + ": must be an object");
      require_known_fields(item, {"factor", "name", "note", "offset", "source"}, where);
      TiedParameter t;
      t.name = read_string(item, "name", where, true);
      t.source = read_string(item, "source", where, true);
      if (item.contains("factor")) t.factor = read_number(item, "factor", where);
      if (item.contains("offset")) t.offset = read_number(item, "offset", where);
      space.tied_.push_back(t);
    }
  }
  space.validate(origin);
  return space;
}

void ParameterSpace::validate(const std::string& origin) const {
  std::set<std::string> names;
  auto claim = [&](const std::string& name, const std::string& where) {
    if (!valid_name(name))
      throw Error(where + ": name \"" + name + "\" must be non-empty and use only letters, digits, '_', '.', '-'");
    if (!names.insert(name).second) throw Error(where + ": name \"" + name + "\" is defined twice");
  };
  for (std::size_t i = 0; i < parameters_.size(); ++i) {
    const Parameter& p = parameters_[i];
    std::string where = origin + ": parameters[" + std::to_string(i) + "] (\"" + p.name + "\")";
    claim(p.name, where);
    if (!(p.low < p.high))
      throw Error(where + ": low (" + format_double(p.low) + ") must be below high (" + format_double(p.high) + ")");
    // Coding needs (high - low) / 2 and the midpoint: a range wider than double's overflows.
    if (!std::isfinite(p.high - p.low))
      throw Error(where + ": the range [" + format_double(p.low) + ", " + format_double(p.high) + "] is too wide to code");
    if (p.log_scale && p.low <= 0)
      throw Error(where + ": log_scale needs low > 0 (low is " + format_double(p.low) + ")");
    for (std::size_t k = 0; k < p.levels.size(); ++k) {
      double level = p.levels[k];
      if (level < p.low || level > p.high)
        throw Error(where + ": levels[" + std::to_string(k) + "] = " + format_double(level) + " lies outside [" +
                    format_double(p.low) + ", " + format_double(p.high) + "]");
      if (k > 0 && !(level > p.levels[k - 1]))
        throw Error(where + ": levels must be strictly increasing");
    }
    if (p.levels.size() == 1) throw Error(where + ": give at least two levels or none");
    if (p.reference && (*p.reference < p.low || *p.reference > p.high))
      throw Error(where + ": reference " + format_double(*p.reference) + " lies outside [" + format_double(p.low) +
                  ", " + format_double(p.high) + "]");
  }
  for (const auto& [name, value] : fixed_) {
    (void)value;
    claim(name, origin + ": fixed." + name);
  }
  for (std::size_t i = 0; i < tied_.size(); ++i) {
    const TiedParameter& t = tied_[i];
    std::string where = origin + ": tied[" + std::to_string(i) + "] (\"" + t.name + "\")";
    claim(t.name, where);
    bool known = contains(t.source) || fixed_.count(t.source) > 0;
    if (!known) throw Error(where + ": source \"" + t.source + "\" is neither a parameter nor a fixed value");
  }
  if (parameters_.empty()) throw Error(origin + ": \"parameters\" is empty; a space needs at least one");
}

ParameterSpace ParameterSpace::load(const std::string& path) {
  return from_json(read_json_file(path, "parameter space file"), path);
}

json ParameterSpace::to_json() const {
  json root;
  root["parameters"] = json::array();
  for (const Parameter& p : parameters_) {
    json item = {{"name", p.name}, {"unit", p.unit}, {"low", p.low}, {"high", p.high}};
    if (!p.levels.empty()) item["levels"] = p.levels;
    if (p.reference) item["reference"] = *p.reference;
    if (p.log_scale) item["log_scale"] = true;
    root["parameters"].push_back(item);
  }
  if (!fixed_.empty()) root["fixed"] = fixed_;
  if (!tied_.empty()) {
    root["tied"] = json::array();
    for (const TiedParameter& t : tied_)
      root["tied"].push_back({{"name", t.name}, {"source", t.source}, {"factor", t.factor}, {"offset", t.offset}});
  }
  return root;
}

std::size_t ParameterSpace::index_of(const std::string& name) const {
  for (std::size_t i = 0; i < parameters_.size(); ++i)
    if (parameters_[i].name == name) return i;
  std::string list;
  for (const Parameter& p : parameters_) list += (list.empty() ? "" : ", ") + p.name;
  throw Error("unknown parameter \"" + name + "\" (known: " + list + ")");
}

bool ParameterSpace::contains(const std::string& name) const {
  for (const Parameter& p : parameters_)
    if (p.name == name) return true;
  return false;
}

std::map<std::string, double> ParameterSpace::complete(const std::vector<double>& varied) const {
  if (varied.size() != parameters_.size())
    throw Error("expected " + std::to_string(parameters_.size()) + " parameter values, got " +
                std::to_string(varied.size()));
  std::map<std::string, double> values = fixed_;
  for (std::size_t i = 0; i < parameters_.size(); ++i) {
    const Parameter& p = parameters_[i];
    double v = varied[i];
    if (!std::isfinite(v)) throw Error("parameter \"" + p.name + "\" is not a finite number");
    values[p.name] = v;
  }
  for (const TiedParameter& t : tied_) values[t.name] = t.factor * values.at(t.source) + t.offset;
  return values;
}

ParameterSpace ParameterSpace::subset(const std::vector<std::string>& keep,
                                      const std::map<std::string, double>& fixed_values) const {
  ParameterSpace out;
  out.fixed_ = fixed_;
  out.tied_ = tied_;
  std::set<std::string> kept(keep.begin(), keep.end());
  for (const std::string& name : keep) out.parameters_.push_back(parameters_[index_of(name)]);
  for (const Parameter& p : parameters_) {
    if (kept.count(p.name)) continue;
    auto it = fixed_values.find(p.name);
    if (it != fixed_values.end()) {
      out.fixed_[p.name] = it->second;
    } else if (p.reference) {
      out.fixed_[p.name] = *p.reference;
    } else {
      throw Error("parameter \"" + p.name + "\" is dropped from the space but has no fixed value or reference");
    }
  }
  out.validate("subset of space");
  return out;
}

}  // namespace demcal
