#include "edits.hpp"

#include <algorithm>
#include <cctype>
#include <sstream>
#include <stdexcept>

namespace medax::vmas {

namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

[[noreturn]] void fail(const std::string& edit, const std::string& why) {
  throw std::invalid_argument("edit '" + edit + "': " + why +
                              " (expected `split|remove|add X Y Z [after K|end]`)");
}

Edit parse_one(const std::string& raw) {
  std::string text = raw;
  for (char& c : text)
    if (c == ',' || c == '[' || c == ']' || c == '(' || c == ')') c = ' ';
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  Edit e;
  e.text = trim(raw);
  if (words.empty()) fail(raw, "empty edit");
  std::string op = words[0];
  std::transform(op.begin(), op.end(), op.begin(), [](unsigned char c) { return std::tolower(c); });
  if (op == "split") e.op = EditOp::Split;
  else if (op == "remove" || op == "delete") e.op = EditOp::Remove;
  else if (op == "add") e.op = EditOp::Add;
  else fail(e.text, "unknown operation '" + words[0] + "'");
  if (words.size() < 4) fail(e.text, "needs three coordinates");
  for (int i = 0; i < 3; ++i) {
    try {
      std::size_t used = 0;
      e.point[i] = std::stod(words[1 + i], &used);
      if (used != words[1 + i].size()) throw std::invalid_argument("trailing");
    } catch (const std::exception&) {
      fail(e.text, "'" + words[1 + i] + "' is not a number");
    }
  }
  if (words.size() == 4) return e;
  if (words.size() != 6 || (words[4] != "after" && words[4] != "at")) fail(e.text, "unexpected '" + words[4] + "'");
  if (words[5] == "end") return e;
  try {
    std::size_t used = 0;
    const long k = std::stol(words[5], &used);
    if (used != words[5].size() || k < 0) throw std::invalid_argument("bad");
    e.after = static_cast<int>(k);
  } catch (const std::exception&) {
    fail(e.text, "'after' takes a number of iterations ≥ 0 or 'end', not '" + words[5] + "'");
  }
  return e;
}

}  // namespace

std::vector<Edit> parse_edits(const std::string& script) {
  std::vector<Edit> edits;
  std::string item;
  const auto flush = [&] {
    std::string s = item;
    item.clear();
    if (const auto hash = s.find('#'); hash != std::string::npos) s.erase(hash);
    s = trim(s);
    if (!s.empty() && s[0] == '-' && (s.size() == 1 || std::isspace(static_cast<unsigned char>(s[1])))) s = trim(s.substr(1));
    if (!s.empty()) edits.push_back(parse_one(s));
  };
  for (char c : script) {
    if (c == ';' || c == '\n') flush();
    else item += c;
  }
  flush();
  std::stable_sort(edits.begin(), edits.end(), [](const Edit& a, const Edit& b) {
    const long ka = a.after == Edit::kEnd ? std::numeric_limits<long>::max() : a.after;
    const long kb = b.after == Edit::kEnd ? std::numeric_limits<long>::max() : b.after;
    return ka < kb;
  });
  return edits;
}

std::string apply_edit(VmasSolver& solver, const Edit& edit, const Vec3& point) {
  std::ostringstream log;
  log << "edit '" << edit.text << "' after iteration " << solver.iterations() << ": ";
  switch (edit.op) {
    case EditOp::Split: {
      const SphereId target = solver.nearest_sphere(point);
      const SphereId added = solver.split_sphere(target);
      log << "split sphere " << target << " -> new sphere " << added;
      break;
    }
    case EditOp::Remove: {
      const SphereId target = solver.nearest_sphere(point);
      solver.remove_sphere(target);
      log << "removed sphere " << target;
      break;
    }
    case EditOp::Add: {
      const Index v = solver.input().nearest_vertex(point - solver.input().origin);
      const SphereId added = solver.add_sphere(v);
      log << "added sphere " << added << " at vertex " << v;
      break;
    }
  }
  log << "; " << solver.size() << " spheres";
  return log.str();
}

}  // namespace medax::vmas
