#include "medial_json.hpp"

#include <fmt/format.h>
#include <gmp.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace medax::msd {
namespace {

using nlohmann::json;

/// Where a problem is, for messages: "vertices[3] (id 17)".
struct Where {
  std::string list;
  std::size_t entry = 0;
  long long id = -1;
  std::string text() const {
    return id >= 0 ? fmt::format("{}[{}] (id {})", list, entry, id) : fmt::format("{}[{}]", list, entry);
  }
};

class Reader {
 public:
  explicit Reader(std::string name) : name_(std::move(name)) {}
  MedialComplex read(const json& root);

 private:
  [[noreturn]] void fail(const Where& where, const std::string& reason) const {
    throw std::runtime_error(fmt::format("{}: {}: {}; expected the authors' medial JSON (input-ma.json)", name_,
                                         where.text(), reason));
  }
  const json& list(const json& root, const std::string& key) const;
  /// An entry [id, {...}]: its id and object.
  std::pair<long long, const json*> entry(const json& item, Where& where) const;
  double coordinate(const json& value, const Where& where) const;
  Index vertex_index(const json& id, const Where& where) const;
  template <std::size_t N>
  std::array<Index, N> corners(const json& object, Where& where) const;

  std::string name_;
  std::map<long long, Index> index_of_id_;
};

const json& Reader::list(const json& root, const std::string& key) const {
  if (!root.is_object()) fail({"top level", 0}, "not a JSON object");
  const auto it = root.find(key);
  if (it == root.end() || !it->is_array()) fail({key, 0}, fmt::format("no \"{}\" list", key));
  return *it;
}

std::pair<long long, const json*> Reader::entry(const json& item, Where& where) const {
  if (!item.is_array() || item.size() != 2 || !item[0].is_number_integer() || !item[1].is_object())
    fail(where, "an entry must be [id, {...}]");
  where.id = item[0].get<long long>();
  return {where.id, &item[1]};
}

double Reader::coordinate(const json& value, const Where& where) const {
  if (value.is_number()) return value.get<double>();
  std::string text;
  if (value.is_string()) {
    text = value.get<std::string>();
  } else if (value.is_array()) {  // character codes of the string, padded with zeros
    for (const json& c : value) {
      if (!c.is_number_integer() || c.get<long long>() < 0 || c.get<long long>() > 127)
        fail(where, "a coordinate given as characters holds a non-character");
      if (c.get<long long>() == 0) break;
      text.push_back(static_cast<char>(c.get<long long>()));
    }
  } else {
    fail(where, "a coordinate must be a number, a string or an array of characters");
  }
  mpq_t q;
  mpq_init(q);
  const bool exact = mpq_set_str(q, text.c_str(), 10) == 0 && mpz_sgn(mpq_denref(q)) != 0;
  double result = 0;
  if (exact) {
    mpq_canonicalize(q);
    result = mpq_get_d(q);
  }
  mpq_clear(q);
  if (exact) return result;
  std::istringstream decimal(text);
  decimal >> result;
  if (decimal.fail() || !decimal.eof() || !std::isfinite(result))
    fail(where, fmt::format("coordinate \"{}\" is no number", text));
  return result;
}

Index Reader::vertex_index(const json& id, const Where& where) const {
  if (!id.is_number_integer()) fail(where, "a vertex id in \"vidx\" is not an integer");
  const auto it = index_of_id_.find(id.get<long long>());
  if (it == index_of_id_.end()) fail(where, fmt::format("vertex id {} is not in \"vertices\"", id.get<long long>()));
  return it->second;
}

template <std::size_t N>
std::array<Index, N> Reader::corners(const json& object, Where& where) const {
  const auto it = object.find("vidx");
  if (it == object.end() || !it->is_array() || it->size() != N)
    fail(where, fmt::format("\"vidx\" must list {} vertex ids", N));
  std::array<Index, N> ids{};
  for (std::size_t k = 0; k < N; ++k) ids[k] = vertex_index((*it)[k], where);
  for (std::size_t k = 0; k < N; ++k)
    for (std::size_t l = k + 1; l < N; ++l)
      if (ids[k] == ids[l]) fail(where, "an element repeats a vertex");
  return ids;
}

MedialComplex Reader::read(const json& root) {
  MedialComplex medial;
  const json& vertices = list(root, "vertices");
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    Where where{"vertices", k};
    const auto [id, object] = entry(vertices[k], where);
    const auto pos = object->find("pos");
    if (pos == object->end() || !pos->is_array() || pos->size() != 3) fail(where, "\"pos\" must hold 3 coordinates");
    Vec3 p;
    for (int c = 0; c < 3; ++c) p[c] = coordinate((*pos)[c], where);
    if (!index_of_id_.emplace(id, static_cast<Index>(medial.num_vertices())).second)
      fail(where, "vertex id listed twice");
    medial.add_vertex(p, 0.0);
  }
  const json& edges = list(root, "edges");
  for (std::size_t k = 0; k < edges.size(); ++k) {
    Where where{"edges", k};
    const auto ids = corners<2>(*entry(edges[k], where).second, where);
    medial.add_edge(ids[0], ids[1]);
  }
  const json& triangles = list(root, "triangles");
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    Where where{"triangles", k};
    const auto ids = corners<3>(*entry(triangles[k], where).second, where);
    medial.add_face(ids[0], ids[1], ids[2]);
  }
  if (medial.num_vertices() == 0) fail({"vertices", 0}, "the medial mesh has no vertex");
  return medial;
}

}  // namespace

MedialComplex parse_medial_json(const std::string& text, const std::string& name) {
  json root;
  try {
    root = json::parse(text);
  } catch (const json::parse_error& e) {
    throw std::runtime_error(fmt::format("{}: byte {}: not valid JSON ({})", name, e.byte, e.what()));
  }
  return Reader(name).read(root);
}

MedialComplex read_medial_json(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot open the medial JSON file", file.string()));
  std::ostringstream text;
  text << in.rdbuf();
  return parse_medial_json(text.str(), file.string());
}

}  // namespace medax::msd
