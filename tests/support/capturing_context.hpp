#pragma once
// A context for stage tests that keeps the files a stage writes (ctx.write_output) in memory.
#include <medax/context.hpp>

#include <filesystem>
#include <functional>
#include <map>
#include <sstream>
#include <string>

namespace medax::test {

class CapturingContext : public BasicContext {
 public:
  using BasicContext::BasicContext;
  std::filesystem::path write_output(const std::string& name,
                                     const std::function<void(std::ostream&)>& body) override {
    std::ostringstream out;
    body(out);
    files[name] = out.str();
    return name;
  }
  std::map<std::string, std::string> files;  ///< file name -> content
};

}  // namespace medax::test
