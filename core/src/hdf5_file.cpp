#include "demcal/core/hdf5_file.hpp"

#include <hdf5.h>

#include <sys/stat.h>

#include "demcal/core/error.hpp"

namespace demcal::h5 {
namespace {

// HDF5 prints its own error stack by default; we report through Error instead.
void silence_hdf5() {
  static bool done = [] {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    return true;
  }();
  (void)done;
}

bool file_exists(const std::string& path) {
  struct stat info;
  return ::stat(path.c_str(), &info) == 0;
}

// H5Lexists fails on a path whose parent is missing, so test it prefix by prefix.
bool path_exists(hid_t location, const std::string& path) {
  std::string prefix = (!path.empty() && path.front() == '/') ? "/" : "";
  std::size_t start = prefix.size();
  while (start < path.size()) {
    std::size_t slash = path.find('/', start);
    if (slash == std::string::npos) slash = path.size();
    std::string piece = path.substr(start, slash - start);
    start = slash + 1;
    if (piece.empty()) continue;
    prefix += (prefix.empty() || prefix.back() == '/' ? "" : "/") + piece;
    if (H5Lexists(location, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
  }
  return true;
}

herr_t collect_attribute_name(hid_t, const char* name, const H5A_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->push_back(name);
  return 0;
}

}  // namespace

Handle& Handle::operator=(Handle&& other) noexcept {
  if (this != &other) {
    this->~Handle();
    id_ = other.id_;
    kind_ = other.kind_;
    other.id_ = -1;
  }
  return *this;
}

Handle::~Handle() {
  if (id_ < 0) return;
  switch (kind_) {
    case Kind::File: H5Fclose(id_); break;
    case Kind::Group: H5Gclose(id_); break;
    case Kind::Dataset: H5Dclose(id_); break;
    case Kind::Dataspace: H5Sclose(id_); break;
    case Kind::Attribute: H5Aclose(id_); break;
    case Kind::Datatype: H5Tclose(id_); break;
    case Kind::Plist: H5Pclose(id_); break;
  }
  id_ = -1;
}

File::File(const std::string& path, Mode mode) : path_(path) {
  silence_hdf5();
  hid_t id = -1;
  switch (mode) {
    case Mode::ReadOnly:
      if (!file_exists(path)) throw Error(path + ": no such HDF5 file");
      id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
      break;
    case Mode::ReadWrite:
      if (!file_exists(path)) throw Error(path + ": no such HDF5 file");
      id = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
      break;
    case Mode::Truncate:
      id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
      break;
    case Mode::OpenOrCreate:
      id = file_exists(path) ? H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT)
                             : H5Fcreate(path.c_str(), H5F_ACC_EXCL, H5P_DEFAULT, H5P_DEFAULT);
      break;
  }
  if (id < 0) throw Error(path + ": cannot open as HDF5 (not an HDF5 file, or no permission)");
  handle_ = Handle(id, Handle::Kind::File);
}

bool File::exists(const std::string& name) const { return path_exists(id(), name); }

Group File::group(const std::string& name, bool create) const {
  if (exists(name)) {
    hid_t g = H5Gopen2(id(), name.c_str(), H5P_DEFAULT);
    if (g < 0) throw Error(path_ + ": " + name + " exists but is not a group");
    return Group(Handle(g, Handle::Kind::Group), path_, name);
  }
  if (!create) throw Error(path_ + ": no group " + name);
  Handle plist(H5Pcreate(H5P_LINK_CREATE), Handle::Kind::Plist);
  H5Pset_create_intermediate_group(plist.id(), 1);
  hid_t g = H5Gcreate2(id(), name.c_str(), plist.id(), H5P_DEFAULT, H5P_DEFAULT);
  if (g < 0) throw Error(path_ + ": cannot create group " + name);
  return Group(Handle(g, Handle::Kind::Group), path_, name);
}

void File::remove(const std::string& name) const {
  if (!exists(name)) return;
  if (H5Ldelete(id(), name.c_str(), H5P_DEFAULT) < 0) throw Error(path_ + ": cannot delete " + name);
}

void File::flush() const {
  if (H5Fflush(id(), H5F_SCOPE_GLOBAL) < 0) throw Error(path_ + ": flush failed");
}

std::string Group::where(const std::string& child) const {
  return file_path_ + ": " + name_ + (name_.empty() || name_.back() == '/' ? "" : "/") + child;
}

bool Group::has(const std::string& name) const { return H5Lexists(id(), name.c_str(), H5P_DEFAULT) > 0; }

std::vector<std::string> Group::children() const {
  std::vector<std::string> names;
  H5G_info_t info;
  if (H5Gget_info(id(), &info) < 0) throw Error(where("") + ": cannot list group");
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    ssize_t size = H5Lget_name_by_idx(id(), ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (size < 0) throw Error(where("") + ": cannot read member name");
    std::string name(static_cast<std::size_t>(size) + 1, '\0');
    H5Lget_name_by_idx(id(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(), H5P_DEFAULT);
    name.resize(static_cast<std::size_t>(size));
    names.push_back(name);
  }
  return names;
}

namespace {

void write_raw(hid_t group, const std::string& name, hid_t memtype, hid_t filetype, const void* data,
               const std::vector<hsize_t>& dims, const std::string& where) {
  if (H5Lexists(group, name.c_str(), H5P_DEFAULT) > 0) H5Ldelete(group, name.c_str(), H5P_DEFAULT);
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), Handle::Kind::Dataspace);
  Handle set(H5Dcreate2(group, name.c_str(), filetype, space.id(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
             Handle::Kind::Dataset);
  if (!set.valid()) throw Error(where + ": cannot create dataset");
  bool empty = false;
  for (hsize_t d : dims) empty = empty || d == 0;
  if (!empty && H5Dwrite(set.id(), memtype, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    throw Error(where + ": cannot write dataset");
}

Handle open_dataset(hid_t group, const std::string& name, const std::string& where, std::vector<hsize_t>& dims) {
  if (H5Lexists(group, name.c_str(), H5P_DEFAULT) <= 0) throw Error(where + ": no such dataset");
  Handle set(H5Dopen2(group, name.c_str(), H5P_DEFAULT), Handle::Kind::Dataset);
  if (!set.valid()) throw Error(where + ": not a dataset");
  Handle space(H5Dget_space(set.id()), Handle::Kind::Dataspace);
  int rank = H5Sget_simple_extent_ndims(space.id());
  if (rank < 0) throw Error(where + ": cannot read shape");
  dims.assign(static_cast<std::size_t>(rank), 0);
  H5Sget_simple_extent_dims(space.id(), dims.data(), nullptr);
  return set;
}

}  // namespace

void Group::write(const std::string& name, const std::vector<double>& values) const {
  write_raw(id(), name, H5T_NATIVE_DOUBLE, H5T_IEEE_F64LE, values.data(), {values.size()}, where(name));
}

void Group::write(const std::string& name, const std::vector<std::int64_t>& values) const {
  write_raw(id(), name, H5T_NATIVE_INT64, H5T_STD_I64LE, values.data(), {values.size()}, where(name));
}

std::vector<double> Group::read_doubles(const std::string& name) const {
  std::vector<hsize_t> dims;
  Handle set = open_dataset(id(), name, where(name), dims);
  if (dims.size() != 1) throw Error(where(name) + ": expected a 1D dataset");
  std::vector<double> values(dims[0]);
  if (!values.empty() && H5Dread(set.id(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
    throw Error(where(name) + ": cannot read as doubles");
  return values;
}

std::vector<std::int64_t> Group::read_integers(const std::string& name) const {
  std::vector<hsize_t> dims;
  Handle set = open_dataset(id(), name, where(name), dims);
  if (dims.size() != 1) throw Error(where(name) + ": expected a 1D dataset");
  // HDF5 would convert 1.5 to 1 without a word: integers must be stored as integers.
  Handle type(H5Dget_type(set.id()), Handle::Kind::Datatype);
  if (H5Tget_class(type.id()) != H5T_INTEGER) throw Error(where(name) + ": expected integers");
  std::vector<std::int64_t> values(dims[0]);
  if (!values.empty() && H5Dread(set.id(), H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()) < 0)
    throw Error(where(name) + ": cannot read as integers");
  return values;
}

namespace {

void replace_attribute(hid_t object, const std::string& name) {
  if (H5Aexists(object, name.c_str()) > 0) H5Adelete(object, name.c_str());
}

void write_scalar_attribute(hid_t object, const std::string& name, hid_t filetype, hid_t memtype,
                            const void* value, const std::string& where) {
  replace_attribute(object, name);
  Handle space(H5Screate(H5S_SCALAR), Handle::Kind::Dataspace);
  Handle attribute(H5Acreate2(object, name.c_str(), filetype, space.id(), H5P_DEFAULT, H5P_DEFAULT),
                   Handle::Kind::Attribute);
  if (!attribute.valid() || H5Awrite(attribute.id(), memtype, value) < 0)
    throw Error(where + ": cannot write attribute " + name);
}

Handle open_attribute(hid_t object, const std::string& name, const std::string& where) {
  if (H5Aexists(object, name.c_str()) <= 0) throw Error(where + ": no attribute " + name);
  Handle attribute(H5Aopen(object, name.c_str(), H5P_DEFAULT), Handle::Kind::Attribute);
  if (!attribute.valid()) throw Error(where + ": cannot open attribute " + name);
  return attribute;
}

}  // namespace

void Group::set_attribute(const std::string& name, const std::string& value) const {
  Handle type(H5Tcopy(H5T_C_S1), Handle::Kind::Datatype);
  H5Tset_size(type.id(), value.empty() ? 1 : value.size());
  H5Tset_strpad(type.id(), H5T_STR_NULLPAD);
  H5Tset_cset(type.id(), H5T_CSET_UTF8);
  std::string padded = value.empty() ? std::string(1, '\0') : value;
  write_scalar_attribute(id(), name, type.id(), type.id(), padded.data(), where(""));
}

void Group::set_attribute(const std::string& name, double value) const {
  write_scalar_attribute(id(), name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value, where(""));
}

void Group::set_attribute(const std::string& name, std::int64_t value) const {
  write_scalar_attribute(id(), name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value, where(""));
}

bool Group::has_attribute(const std::string& name) const { return H5Aexists(id(), name.c_str()) > 0; }

std::string Group::string_attribute(const std::string& name) const {
  Handle attribute = open_attribute(id(), name, where(""));
  Handle type(H5Aget_type(attribute.id()), Handle::Kind::Datatype);
  if (H5Tget_class(type.id()) != H5T_STRING) throw Error(where("") + ": attribute " + name + " is not a string");
  if (H5Tis_variable_str(type.id()) > 0) {
    char* text = nullptr;
    if (H5Aread(attribute.id(), type.id(), &text) < 0) throw Error(where("") + ": cannot read attribute " + name);
    std::string value = text ? text : "";
    H5free_memory(text);
    return value;
  }
  std::size_t size = H5Tget_size(type.id());
  std::string value(size, '\0');
  if (H5Aread(attribute.id(), type.id(), value.data()) < 0) throw Error(where("") + ": cannot read attribute " + name);
  value.resize(value.find('\0') == std::string::npos ? size : value.find('\0'));
  return value;
}

double Group::double_attribute(const std::string& name) const {
  Handle attribute = open_attribute(id(), name, where(""));
  double value = 0;
  if (H5Aread(attribute.id(), H5T_NATIVE_DOUBLE, &value) < 0)
    throw Error(where("") + ": attribute " + name + " is not a number");
  return value;
}

std::int64_t Group::integer_attribute(const std::string& name) const {
  Handle attribute = open_attribute(id(), name, where(""));
  std::int64_t value = 0;
  if (H5Aread(attribute.id(), H5T_NATIVE_INT64, &value) < 0)
    throw Error(where("") + ": attribute " + name + " is not an integer");
  return value;
}

std::vector<std::string> Group::attribute_names() const {
  std::vector<std::string> names;
  hsize_t index = 0;
  if (H5Aiterate2(id(), H5_INDEX_NAME, H5_ITER_INC, &index, collect_attribute_name, &names) < 0)
    throw Error(where("") + ": cannot list attributes");
  return names;
}

}  // namespace demcal::h5
