#pragma once
// Named per-element properties, in the spirit of OpenMesh's dynamic properties: each name maps
// to one value per element. Ordered by name so that output files are deterministic.
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace medax {

template <typename T>
class PropertyMap {
 public:
  using Column = std::vector<T>;

  /// Adds (or replaces) a property with `size` values set to `init`; returns it for filling.
  Column& add(const std::string& name, std::size_t size, T init = T{}) {
    auto& column = columns_[name];
    column.assign(size, init);
    return column;
  }
  bool has(const std::string& name) const { return columns_.count(name) != 0; }
  const Column& get(const std::string& name) const {
    auto it = columns_.find(name);
    if (it == columns_.end()) throw std::out_of_range("no property named '" + name + "'");
    return it->second;
  }
  Column& get(const std::string& name) {
    return const_cast<Column&>(static_cast<const PropertyMap&>(*this).get(name));
  }
  void erase(const std::string& name) { columns_.erase(name); }
  void clear() { columns_.clear(); }
  bool empty() const { return columns_.empty(); }
  const std::map<std::string, Column>& all() const { return columns_; }
  std::map<std::string, Column>& all() { return columns_; }

 private:
  std::map<std::string, Column> columns_;
};

/// Scalar fields (significance, distances) and integer labels (sheet id, path type) of one
/// element kind.
struct ElementProperties {
  PropertyMap<double> fields;
  PropertyMap<int> labels;
};

}  // namespace medax
