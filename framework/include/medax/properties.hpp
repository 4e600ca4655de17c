#pragma once
// Named per-element properties, in the spirit of OpenMesh's dynamic properties: each name maps
// to one value per element. Ordered by name so that output files are deterministic. Each column
// remembers the value it was created with, which fills the rows of elements added later.
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace medax {

using Index = std::uint32_t;  // as in geometry.hpp

enum class Element { Vertex, Edge, Face };

/// In a row selection (PropertyMap::select), a new row set to the column's initial value.
inline constexpr Index kFreshRow = static_cast<Index>(-1);

/// A typed handle to one column: which elements, which name, and how its values scale with
/// length. T is double (a field) or int (a label). Declare it once
/// (`inline const Property<double> kEt{Element::Vertex, "et", 1};`) and use it everywhere,
/// instead of repeating the string.
template <typename T>
struct Property {
  Element element;
  std::string name;
  /// The field scales as length^k: 1 for a distance (a radius, a burn time), 2 for an area, 0 for
  /// angles, ratios, counts and labels. Outputs written in the input's frame scale it by s^k, as
  /// they map the geometry back (MedialComplex::transform).
  int length_power = 0;
};

template <typename T>
class PropertyMap {
 public:
  using Column = std::vector<T>;

  /// Adds (or replaces) a property with `size` values set to `init`, scaling as length^length_power
  /// (see Property); returns it for filling.
  Column& add(const std::string& name, std::size_t size, T init = T{}, int length_power = 0) {
    inits_[name] = init;
    powers_[name] = length_power;
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
  /// k when the column scales as length^k (0 when unknown, e.g. a column read from a file).
  int length_power(const std::string& name) const {
    auto it = powers_.find(name);
    return it == powers_.end() ? 0 : it->second;
  }
  void erase(const std::string& name) {
    columns_.erase(name);
    inits_.erase(name);
    powers_.erase(name);
  }
  void clear() {
    columns_.clear();
    inits_.clear();
    powers_.clear();
  }
  bool empty() const { return columns_.empty(); }
  const std::map<std::string, Column>& all() const { return columns_; }
  std::map<std::string, Column>& all() { return columns_; }

  /// Appends one row to every column, set to the column's initial value.
  void grow() {
    for (auto& [name, column] : columns_) column.push_back(initial(name));
  }
  /// Rebuilds every column from `rows`: row k becomes old row rows[k], or the column's initial
  /// value where rows[k] is kFreshRow.
  void select(const std::vector<Index>& rows) {
    for (auto& [name, column] : columns_) {
      Column next;
      next.reserve(rows.size());
      for (Index i : rows) next.push_back(i == kFreshRow ? initial(name) : column[i]);
      column = std::move(next);
    }
  }

 private:
  T initial(const std::string& name) const {
    auto it = inits_.find(name);
    return it == inits_.end() ? T{} : it->second;
  }

  std::map<std::string, Column> columns_;
  std::map<std::string, T> inits_;
  std::map<std::string, int> powers_;
};

/// Scalar fields (significance, distances) and integer labels (sheet id, path type) of one
/// element kind.
struct ElementProperties {
  PropertyMap<double> fields;
  PropertyMap<int> labels;

  void grow() {
    fields.grow();
    labels.grow();
  }
  void select(const std::vector<Index>& keep) {
    fields.select(keep);
    labels.select(keep);
  }
  bool empty() const { return fields.empty() && labels.empty(); }
  template <typename T>
  PropertyMap<T>& map() {
    if constexpr (std::is_same_v<T, double>) return fields;
    else return labels;
  }
  template <typename T>
  const PropertyMap<T>& map() const {
    if constexpr (std::is_same_v<T, double>) return fields;
    else return labels;
  }
};

}  // namespace medax
