#include <medax/context.hpp>

#include <iostream>

namespace medax {

Context::~Context() = default;

BasicContext::BasicContext(std::uint64_t seed, bool verbose, std::string stage_id)
    : seed_(seed), verbose_(verbose), rng_(seed), stage_id_(std::move(stage_id)) {}

void BasicContext::info(std::string_view message) {
  if (verbose_) std::cerr << message << '\n';
}
void BasicContext::warn(std::string_view message) { std::cerr << "warning: " << message << '\n'; }

}  // namespace medax
