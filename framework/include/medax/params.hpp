#pragma once
// Typed parameter declarations. A stage declares its parameters once (name, type, default,
// range, unit, doc); validation, `medax describe`, the resolved config and the docs all come
// from that one declaration.
#include <medax/role.hpp>

#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

namespace medax {

class Stage;
struct StageRef;

enum class ParamType { Bool, Int, Real, String, Choice, Stage };
std::string_view to_string(ParamType type);

/// A parameter value. Int is 64-bit; a Stage value is a nested, configured stage.
using ParamValue = std::variant<bool, long long, double, std::string, std::shared_ptr<StageRef>>;

/// Declaration of one parameter.
struct ParamSpec {
  std::string name;
  ParamType type = ParamType::Real;
  ParamValue default_value;
  std::optional<double> min, max;  ///< inclusive bounds for Int and Real
  std::string unit;
  std::string doc;
  std::vector<std::string> choices;  ///< for Choice
  Role stage_role = Role::Significance;  ///< for Stage: the role the nested stage must have

  static ParamSpec boolean(std::string name, bool def, std::string doc);
  static ParamSpec integer(std::string name, long long def, std::string doc);
  static ParamSpec real(std::string name, double def, std::string doc);
  static ParamSpec text(std::string name, std::string def, std::string doc);
  static ParamSpec choice(std::string name, std::string def, std::vector<std::string> choices,
                          std::string doc);
  /// A nested stage of `role`; `default_plugin` is used (with its defaults) when not given.
  static ParamSpec stage(std::string name, Role role, std::string default_plugin, std::string doc);

  ParamSpec&& range(double lo, double hi) && { min = lo; max = hi; return std::move(*this); }
  ParamSpec&& at_least(double lo) && { min = lo; return std::move(*this); }
  ParamSpec&& in_unit(std::string u) && { unit = std::move(u); return std::move(*this); }

  /// Human-readable default ("0.01", "true", "mode", "durix_epsilon").
  std::string default_text() const;
  /// Human-readable range ("[0, 1]", "≥ 0", "one of a|b"), empty when unconstrained.
  std::string range_text() const;
};

/// Resolved parameter values of a stage: every declared parameter present, validated.
class ParamSet {
 public:
  bool boolean(const std::string& name) const;
  long long integer(const std::string& name) const;
  double real(const std::string& name) const;  ///< also reads Int values
  const std::string& text(const std::string& name) const;  ///< String and Choice
  /// The nested stage given for a Stage parameter, cast to its role interface.
  template <typename StageT>
  StageT& stage(const std::string& name) const;
  const StageRef& stage_ref(const std::string& name) const;

  bool has(const std::string& name) const { return values_.count(name) != 0; }
  void set(const std::string& name, ParamValue v) { values_[name] = std::move(v); }
  const ParamValue& at(const std::string& name) const;
  const std::map<std::string, ParamValue>& all() const { return values_; }

 private:
  std::map<std::string, ParamValue> values_;
};

/// Every non-stage parameter at its default: for calling a stage directly (tests, scripts).
/// Stage-typed parameters are left out; set them with ParamSet::set.
ParamSet default_params(const std::vector<ParamSpec>& specs);

/// A nested stage given as a parameter: which plugin, its resolved parameters, and the instance.
struct StageRef {
  std::string plugin;
  ParamSet params;
  std::shared_ptr<Stage> instance;
};

template <typename StageT>
StageT& ParamSet::stage(const std::string& name) const {
  const StageRef& ref = stage_ref(name);
  auto* typed = dynamic_cast<StageT*>(ref.instance.get());
  if (!typed) throw std::runtime_error("parameter '" + name + "': stage '" + ref.plugin +
                                       "' does not have the required role");
  return *typed;
}

}  // namespace medax
