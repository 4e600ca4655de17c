#include <medax/params.hpp>

#include <fmt/format.h>

#include <algorithm>
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
std::string number_text(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{}", v);
}
}  // namespace

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
long long ParamSet::integer(const std::string& name) const { return typed<long long>(*this, name, "int"); }
double ParamSet::real(const std::string& name) const {
  if (const long long* i = std::get_if<long long>(&at(name))) return static_cast<double>(*i);
  return typed<double>(*this, name, "real");
}
const std::string& ParamSet::text(const std::string& name) const { return typed<std::string>(*this, name, "string"); }
const StageRef& ParamSet::stage_ref(const std::string& name) const {
  const auto& ref = typed<std::shared_ptr<StageRef>>(*this, name, "stage");
  if (!ref) throw std::runtime_error("parameter '" + name + "' has no stage");
  return *ref;
}

ParamSpec& ParamBinder::bind(ParamSpec spec, Writer write) {
  if (writers_.count(spec.name))
    throw std::logic_error(fmt::format("parameter '{}' is declared twice", spec.name));
  writers_.emplace(spec.name, std::move(write));
  specs_.push_back(std::move(spec));
  return specs_.back();
}

ParamSpec& ParamBinder::add(std::string name, std::string& field, std::vector<std::string> choices,
                            std::string doc) {
  ParamSpec spec;
  spec.name = std::move(name);
  spec.type = ParamType::Choice;
  spec.doc = std::move(doc);
  if (std::find(choices.begin(), choices.end(), field) == choices.end())
    throw std::logic_error(fmt::format("parameter '{}': default '{}' is not one of its choices", spec.name, field));
  spec.default_value = field;
  spec.choices = choices;
  return bind(std::move(spec), [&field, choices = std::move(choices)](const ParamValue& v) {
    const std::string& text = std::get<std::string>(v);
    if (std::find(choices.begin(), choices.end(), text) == choices.end()) detail::throw_not_a_choice(text);
    field = text;
  });
}

void ParamBinder::apply(const ParamSet& values) const {
  for (const auto& [name, value] : values.all()) {
    auto it = writers_.find(name);
    if (it == writers_.end()) throw std::logic_error(fmt::format("no parameter named '{}'", name));
    it->second(value);
  }
}

namespace detail {
void throw_empty_slot() { throw std::logic_error("a stage parameter was used before a stage was given to it"); }
void throw_wrong_stage(const std::string& plugin) {
  throw std::invalid_argument(fmt::format("stage '{}' is not of the kind this parameter needs", plugin));
}
void throw_not_a_choice(const std::string& text) {
  throw std::invalid_argument(fmt::format("'{}' is not one of the parameter's choices", text));
}
}  // namespace detail

}  // namespace medax
