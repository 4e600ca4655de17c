#include <medax/scene_data.hpp>

#include <fmt/format.h>

namespace medax {

const SceneData::Entry* SceneData::entry(const std::string& name, std::type_index type) const {
  auto it = entries_.find(name);
  if (it == entries_.end()) return nullptr;
  if (it->second.type != type)
    throw std::logic_error(fmt::format("scene data '{}' (from stage '{}') is not of the type asked for", name,
                                       it->second.publisher));
  return &it->second;
}

void SceneData::throw_missing(const std::string& name, const std::string& producer) {
  throw MissingData(fmt::format("needs '{}', which no earlier stage made: put a `{}` stage before this one", name,
                                producer));
}

std::string SceneData::publisher(const std::string& name) const {
  auto it = entries_.find(name);
  return it == entries_.end() ? std::string() : it->second.publisher;
}

std::vector<SceneData::Output> SceneData::outputs() const {
  std::vector<Output> out;
  for (const auto& [name, e] : entries_)
    if (!e.output.file.empty()) out.push_back(e.output);
  return out;
}

}  // namespace medax
