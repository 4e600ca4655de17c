#include <medax/params.hpp>

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace medax {

std::string_view to_string(ParamType type) {
  switch (type) {
    case ParamType::Bool: return "bool";
    case ParamType::Int: return "int";
    case ParamType::Real: return "real";
    case ParamType::String: return "string";
    case ParamType::Choice: return "choice";
    case ParamType::Stage: return "stage";
  }
  return "unknown";
}

namespace {
ParamSpec make(std::string name, ParamType type, ParamValue def, std::string doc) {
  ParamSpec s;
  s.name = std::move(name);
  s.type = type;
  s.default_value = std::move(def);
  s.doc = std::move(doc);
  return s;
}

std::string number_text(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{}", v);
}
}  // namespace

ParamSpec ParamSpec::boolean(std::string name, bool def, std::string doc) {
  return make(std::move(name), ParamType::Bool, def, std::move(doc));
}
ParamSpec ParamSpec::integer(std::string name, long long def, std::string doc) {
  return make(std::move(name), ParamType::Int, def, std::move(doc));
}
ParamSpec ParamSpec::real(std::string name, double def, std::string doc) {
  return make(std::move(name), ParamType::Real, def, std::move(doc));
}
ParamSpec ParamSpec::text(std::string name, std::string def, std::string doc) {
  return make(std::move(name), ParamType::String, std::move(def), std::move(doc));
}
ParamSpec ParamSpec::choice(std::string name, std::string def, std::vector<std::string> choices,
                            std::string doc) {
  ParamSpec s = make(std::move(name), ParamType::Choice, std::move(def), std::move(doc));
  s.choices = std::move(choices);
  return s;
}
ParamSpec ParamSpec::stage(std::string name, Role role, std::string default_plugin,
                           std::string doc) {
  ParamSpec s = make(std::move(name), ParamType::Stage, std::move(default_plugin), std::move(doc));
  s.stage_role = role;
  return s;
}

std::string ParamSpec::default_text() const {
  return std::visit(
      [](const auto& v) -> std::string {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, bool>) return v ? "true" : "false";
        else if constexpr (std::is_same_v<T, long long>) return std::to_string(v);
        else if constexpr (std::is_same_v<T, double>) return number_text(v);
        else if constexpr (std::is_same_v<T, std::string>) return v;
        else return v ? v->plugin : std::string("none");
      },
      default_value);
}

std::string ParamSpec::range_text() const {
  if (type == ParamType::Choice) {
    std::string out = "one of ";
    for (std::size_t i = 0; i < choices.size(); ++i) out += (i ? "|" : "") + choices[i];
    return out;
  }
  if (type == ParamType::Stage) return std::string("a ") + std::string(to_string(stage_role)) + " stage";
  if (min && max) return fmt::format("[{}, {}]", number_text(*min), number_text(*max));
  if (min) return fmt::format(">= {}", number_text(*min));
  if (max) return fmt::format("<= {}", number_text(*max));
  return {};
}

const ParamValue& ParamSet::at(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end()) throw std::out_of_range("no parameter named '" + name + "'");
  return it->second;
}

namespace {
template <typename T>
const T& typed(const ParamSet& set, const std::string& name, const char* type) {
  const ParamValue& v = set.at(name);
  if (const T* p = std::get_if<T>(&v)) return *p;
  throw std::runtime_error(fmt::format("parameter '{}' is not of type {}", name, type));
}
}  // namespace

bool ParamSet::boolean(const std::string& name) const { return typed<bool>(*this, name, "bool"); }
long long ParamSet::integer(const std::string& name) const {
  return typed<long long>(*this, name, "int");
}
double ParamSet::real(const std::string& name) const {
  const ParamValue& v = at(name);
  if (const long long* i = std::get_if<long long>(&v)) return static_cast<double>(*i);
  return typed<double>(*this, name, "real");
}
const std::string& ParamSet::text(const std::string& name) const {
  return typed<std::string>(*this, name, "string");
}
const StageRef& ParamSet::stage_ref(const std::string& name) const {
  const auto& ref = typed<std::shared_ptr<StageRef>>(*this, name, "stage");
  if (!ref) throw std::runtime_error("parameter '" + name + "' has no stage");
  return *ref;
}

ParamSet default_params(const std::vector<ParamSpec>& specs) {
  ParamSet set;
  for (const ParamSpec& spec : specs)
    if (spec.type != ParamType::Stage) set.set(spec.name, spec.default_value);
  return set;
}

}  // namespace medax
