#pragma once
// A small RAII layer over the HDF5 C API: files, groups, 1D datasets of
// doubles/integers/strings and scalar attributes. Every failure throws an
// Error that names the file and the object.
#include <cstdint>
#include <string>
#include <vector>

namespace demcal::h5 {

using hid = std::int64_t;  // hid_t without pulling hdf5.h into every header

// Owns one HDF5 identifier and closes it with the right H5*close.
class Handle {
 public:
  enum class Kind { File, Group, Dataset, Dataspace, Attribute, Datatype, Plist };
  Handle() = default;
  Handle(hid id, Kind kind) : id_(id), kind_(kind) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  Handle(Handle&& other) noexcept { *this = std::move(other); }
  Handle& operator=(Handle&& other) noexcept;
  ~Handle();
  hid id() const { return id_; }
  bool valid() const { return id_ >= 0; }

 private:
  hid id_ = -1;
  Kind kind_ = Kind::File;
};

enum class Mode { ReadOnly, ReadWrite, Truncate, OpenOrCreate };

class Group;

class File {
 public:
  File(const std::string& path, Mode mode);
  const std::string& path() const { return path_; }
  hid id() const { return handle_.id(); }
  // Opens a group ("/a/b"); `create` makes it and any missing parents.
  Group group(const std::string& name, bool create) const;
  bool exists(const std::string& name) const;
  void remove(const std::string& name) const;
  void flush() const;

 private:
  std::string path_;
  Handle handle_;
};

class Group {
 public:
  Group(Handle handle, std::string file_path, std::string name)
      : handle_(std::move(handle)), file_path_(std::move(file_path)), name_(std::move(name)) {}
  hid id() const { return handle_.id(); }
  const std::string& name() const { return name_; }

  bool has(const std::string& name) const;
  std::vector<std::string> children() const;

  void write(const std::string& name, const std::vector<double>& values) const;
  void write(const std::string& name, const std::vector<std::int64_t>& values) const;
  std::vector<double> read_doubles(const std::string& name) const;
  std::vector<std::int64_t> read_integers(const std::string& name) const;

  void set_attribute(const std::string& name, const std::string& value) const;
  void set_attribute(const std::string& name, double value) const;
  void set_attribute(const std::string& name, std::int64_t value) const;
  bool has_attribute(const std::string& name) const;
  std::string string_attribute(const std::string& name) const;
  double double_attribute(const std::string& name) const;
  std::int64_t integer_attribute(const std::string& name) const;
  std::vector<std::string> attribute_names() const;

 private:
  std::string where(const std::string& child) const;
  Handle handle_;
  std::string file_path_;
  std::string name_;
};

}  // namespace demcal::h5
