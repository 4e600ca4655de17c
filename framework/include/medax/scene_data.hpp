#pragma once
// Typed data that flows between stages. A stage publishes a named payload (an Erosion
// Thickness burn, a sheet graph, MSD primitives); a later stage reads it by the same key. The
// key names its type and the stage that makes it, so a missing payload is an error that says
// which stage to put first. A key with a writer also puts the payload into the run folder.
//
//   inline const medax::DataKey<BurnResult> kBurn{"et.burn", "erosion_thickness"};
//   ctx.data().publish(kBurn, std::move(burn), ctx.stage_id());   // in erosion_thickness
//   const BurnResult& burn = ctx.data().get(kBurn);                 // in et_skeleton
//
// Payloads are immutable once published and shared between copies of the scene, so copying a
// scene (the runner does, per stage) copies no payload.
#include <functional>
#include <iosfwd>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <typeindex>
#include <vector>

namespace medax {

/// Names a payload of type T. `producer` is the stage (plugin name) that publishes it.
template <typename T>
struct DataKey {
  std::string name;
  std::string producer;
  /// When set, the run folder gets `<publishing stage id>_<file>` written by `write`.
  std::string file;
  std::function<void(const T&, std::ostream&)> write;
};

/// Thrown when a stage reads a payload no earlier stage published.
struct MissingData : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

class SceneData {
 public:
  /// Publishes (or replaces) the payload under `key`; `publisher` is the publishing stage's id.
  template <typename T>
  void publish(const DataKey<T>& key, T value, const std::string& publisher);
  /// The payload under `key`, or nullptr when there is none.
  template <typename T>
  const T* find(const DataKey<T>& key) const;
  /// The payload under `key`; throws MissingData naming the stage that should have made it.
  template <typename T>
  const T& get(const DataKey<T>& key) const;
  /// The id of the stage that published `name` (empty when none did).
  std::string publisher(const std::string& name) const;
  void erase(const std::string& name) { entries_.erase(name); }

  /// A payload that goes into the run folder: its file name and how to write it.
  struct Output {
    std::string file;
    std::function<void(std::ostream&)> write;
  };
  /// Every payload whose key has a writer, ordered by name.
  std::vector<Output> outputs() const;

 private:
  struct Entry {
    std::shared_ptr<const void> value;
    std::type_index type;
    std::string publisher;
    Output output;  // file empty when the key has no writer
  };
  const Entry* entry(const std::string& name, std::type_index type) const;
  [[noreturn]] static void throw_missing(const std::string& name, const std::string& producer);

  std::map<std::string, Entry> entries_;
};

template <typename T>
void SceneData::publish(const DataKey<T>& key, T value, const std::string& publisher) {
  auto shared = std::make_shared<const T>(std::move(value));
  Output output;
  if (key.write) {
    output.file = publisher + "_" + key.file;
    output.write = [shared, write = key.write](std::ostream& out) { write(*shared, out); };
  }
  entries_.insert_or_assign(key.name, Entry{shared, typeid(T), publisher, std::move(output)});
}

template <typename T>
const T* SceneData::find(const DataKey<T>& key) const {
  const Entry* e = entry(key.name, typeid(T));
  return e ? static_cast<const T*>(e->value.get()) : nullptr;
}

template <typename T>
const T& SceneData::get(const DataKey<T>& key) const {
  if (const T* value = find(key)) return *value;
  throw_missing(key.name, key.producer);
}

}  // namespace medax
