#pragma once
// Parameters, declared once. A stage binds each parameter to the field that holds it, in one
// line (name, field, doc, then range and unit); the field's initial value is the default.
// Validation, `medax describe`, the resolved config and the docs tables all come from that
// binding, and the pipeline writes each validated value straight into its field:
//
//   void declare(ParamBinder& p) override {
//     p.add("theta", options_.theta, "Angle condition (paper: pi/8)").range(0, kPi / 2).in_unit("rad");
//     p.add("inner", options_.inner, {{"auto", Inner::Auto}, {"mesh", Inner::Mesh}}, "which facets");
//     p.add("oracle", oracle_, "durix_epsilon", "the significance test");
//   }
#include <medax/role.hpp>

#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace medax {

class Stage;
struct StageRef;

enum class ParamType { Bool, Int, Real, String, Choice, Stage };
std::string_view to_string(ParamType type);

/// A parameter value. Int is 64-bit; a Stage value is a nested, configured stage.
using ParamValue = std::variant<bool, long long, double, std::string, std::shared_ptr<StageRef>>;

/// Declaration of one parameter: what `medax describe`, validation and the docs tables show.
/// A stage does not build these by hand: ParamBinder makes one per bound field.
struct ParamSpec {
  std::string name;
  ParamType type = ParamType::Real;
  ParamValue default_value;
  std::optional<double> min, max;  ///< inclusive bounds for Int and Real
  std::string unit;
  std::string doc;
  std::vector<std::string> choices;  ///< for Choice
  Role stage_role = Role::Significance;  ///< for Stage: the role the nested stage must have

  ParamSpec& range(double lo, double hi) { min = lo; max = hi; return *this; }
  ParamSpec& at_least(double lo) { min = lo; return *this; }
  ParamSpec& in_unit(std::string u) { unit = std::move(u); return *this; }

  /// Human-readable default ("0.01", "true", "mode", "durix_epsilon").
  std::string default_text() const;
  /// Human-readable range ("[0, 1]", "≥ 0", "one of a|b"), empty when unconstrained.
  std::string range_text() const;
};

/// Resolved parameter values of a stage, by name: what the pipeline validated and what
/// `config.resolved.yaml` records. Stages never read these: their bound fields hold the values.
class ParamSet {
 public:
  bool boolean(const std::string& name) const;
  long long integer(const std::string& name) const;
  double real(const std::string& name) const;  ///< also reads Int values
  const std::string& text(const std::string& name) const;  ///< String and Choice
  const StageRef& stage_ref(const std::string& name) const;

  bool has(const std::string& name) const { return values_.count(name) != 0; }
  void set(const std::string& name, ParamValue v) { values_[name] = std::move(v); }
  const ParamValue& at(const std::string& name) const;
  const std::map<std::string, ParamValue>& all() const { return values_; }

 private:
  std::map<std::string, ParamValue> values_;
};

/// A nested stage given as a parameter: which plugin, its resolved parameters, and the instance.
struct StageRef {
  std::string plugin;
  ParamSet params;
  std::shared_ptr<Stage> instance;
};

/// The field a Stage-typed parameter is bound to: the nested stage, typed by its role or class.
template <typename StageT>
class StageSlot {
 public:
  bool empty() const { return !ref_; }
  /// The nested stage, or nullptr when the slot is empty or holds a stage of another kind.
  StageT* find() const { return ref_ ? dynamic_cast<StageT*>(ref_->instance.get()) : nullptr; }
  StageT& get() const;
  StageT* operator->() const { return &get(); }
  const std::string& plugin() const;
  /// Puts a stage in the slot (the pipeline does this; tests may too).
  void set(std::shared_ptr<StageRef> ref) { ref_ = std::move(ref); }
  void set(std::shared_ptr<StageT> stage, std::string plugin = {});

 private:
  std::shared_ptr<StageRef> ref_;
};

/// Binds a stage's parameters to its fields (see the top of this file).
class ParamBinder {
 public:
  /// A bool, a whole number (any integer type), a real or a free string.
  template <typename T>
  ParamSpec& add(std::string name, T& field, std::string doc);
  /// A choice among named values, stored as `T` (an enum, usually).
  template <typename T>
  ParamSpec& add(std::string name, T& field, std::vector<std::pair<std::string, T>> choices, std::string doc);
  /// A choice among strings, stored as the string itself.
  ParamSpec& add(std::string name, std::string& field, std::vector<std::string> choices, std::string doc);
  /// A nested stage of StageT's role; `default_plugin` is used (with its defaults) when not given.
  template <typename StageT>
  ParamSpec& add(std::string name, StageSlot<StageT>& slot, std::string default_plugin, std::string doc);

  const std::deque<ParamSpec>& specs() const { return specs_; }
  /// Writes every value of `values` into its field; names not bound here are an error (the
  /// pipeline has already refused them, so this is a programming error).
  void apply(const ParamSet& values) const;

 private:
  using Writer = std::function<void(const ParamValue&)>;
  ParamSpec& bind(ParamSpec spec, Writer write);

  std::deque<ParamSpec> specs_;  // a deque: chained range()/in_unit() keep their reference
  std::map<std::string, Writer> writers_;
};

/// The name of a choice value, for messages and `describe` (throws when `value` is not listed).
template <typename T>
const std::string& choice_name(const std::vector<std::pair<std::string, T>>& choices, const T& value) {
  for (const auto& [name, v] : choices)
    if (v == value) return name;
  throw std::logic_error("a choice parameter's default is not one of its choices");
}

// ---- implementation ----------------------------------------------------------------------------

namespace detail {
[[noreturn]] void throw_empty_slot();
[[noreturn]] void throw_wrong_stage(const std::string& plugin);
[[noreturn]] void throw_not_a_choice(const std::string& text);
template <typename T>
ParamType param_type_of() {
  if constexpr (std::is_same_v<T, bool>) return ParamType::Bool;
  else if constexpr (std::is_integral_v<T>) return ParamType::Int;
  else if constexpr (std::is_floating_point_v<T>) return ParamType::Real;
  else {
    static_assert(std::is_same_v<T, std::string>, "a parameter is a bool, an integer, a real or a string");
    return ParamType::String;
  }
}
}  // namespace detail

template <typename StageT>
StageT& StageSlot<StageT>::get() const {
  if (!ref_ || !ref_->instance) detail::throw_empty_slot();
  StageT* typed = find();
  if (!typed) detail::throw_wrong_stage(ref_->plugin);
  return *typed;
}

template <typename StageT>
const std::string& StageSlot<StageT>::plugin() const {
  if (!ref_) detail::throw_empty_slot();
  return ref_->plugin;
}

template <typename StageT>
void StageSlot<StageT>::set(std::shared_ptr<StageT> stage, std::string plugin) {
  auto ref = std::make_shared<StageRef>();
  ref->plugin = std::move(plugin);
  ref->instance = std::move(stage);
  ref_ = std::move(ref);
}

template <typename T>
ParamSpec& ParamBinder::add(std::string name, T& field, std::string doc) {
  ParamSpec spec;
  spec.name = std::move(name);
  spec.type = detail::param_type_of<T>();
  spec.doc = std::move(doc);
  if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, std::string>) spec.default_value = field;
  else if constexpr (std::is_integral_v<T>) spec.default_value = static_cast<long long>(field);
  else spec.default_value = static_cast<double>(field);
  return bind(std::move(spec), [&field](const ParamValue& v) {
    if constexpr (std::is_same_v<T, bool> || std::is_same_v<T, std::string>) field = std::get<T>(v);
    else if constexpr (std::is_integral_v<T>) field = static_cast<T>(std::get<long long>(v));
    else if (const auto* i = std::get_if<long long>(&v)) field = static_cast<T>(*i);
    else field = static_cast<T>(std::get<double>(v));
  });
}

template <typename T>
ParamSpec& ParamBinder::add(std::string name, T& field, std::vector<std::pair<std::string, T>> choices,
                            std::string doc) {
  ParamSpec spec;
  spec.name = std::move(name);
  spec.type = ParamType::Choice;
  spec.doc = std::move(doc);
  spec.default_value = choice_name(choices, field);
  for (const auto& choice : choices) spec.choices.push_back(choice.first);
  return bind(std::move(spec), [&field, choices = std::move(choices)](const ParamValue& v) {
    const std::string& text = std::get<std::string>(v);
    for (const auto& [name, value] : choices)
      if (name == text) {
        field = value;
        return;
      }
    detail::throw_not_a_choice(text);
  });
}

template <typename StageT>
ParamSpec& ParamBinder::add(std::string name, StageSlot<StageT>& slot, std::string default_plugin,
                            std::string doc) {
  ParamSpec spec;
  spec.name = std::move(name);
  spec.type = ParamType::Stage;
  spec.doc = std::move(doc);
  spec.default_value = std::move(default_plugin);
  spec.stage_role = StageT::kRole;
  return bind(std::move(spec),
              [&slot](const ParamValue& v) { slot.set(std::get<std::shared_ptr<StageRef>>(v)); });
}

}  // namespace medax
