// One table for a whole sweep (results.csv, results.md) and its plots (gnuplot, PNG + SVG).
#include <medax/io.hpp>
#include <medax/kernel/sweep.hpp>

#include <fmt/format.h>
#include "json_file.hpp"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <set>

namespace medax {

namespace fs = std::filesystem;

namespace {

using Row = std::map<std::string, std::string>;

std::string number(double v) { return fmt::format("{}", v); }

Row job_row(const SweepJob& job, const fs::path& dir) {
  Row row{{"job", job.name}, {"input", job.input.stem().string()}};
  for (const auto& [key, value] : job.assignment) row[key] = value;
  const nlohmann::json status = detail::read_json_file(dir / "status.json");
  row["status"] = status.is_object() ? status.value("status", "unknown") : "not run";
  if (status.is_object() && status.contains("error")) row["error"] = status["error"].get<std::string>();
  const nlohmann::json metrics = detail::read_json_file(dir / "metrics.json");
  if (metrics.is_object())
    for (const auto& [stage, values] : metrics.items())
      for (const auto& [name, value] : values.items())
        row[stage + "." + name] = value.is_number() ? number(value.get<double>()) : "";
  const nlohmann::json timings = detail::read_json_file(dir / "timings.json");
  if (timings.is_object()) {
    double peak = 0;
    for (const auto& stage : timings.value("stages", nlohmann::json::array())) {
      row["time." + stage.value("id", std::string("?"))] = number(stage.value("seconds", 0.0));
      peak = std::max(peak, stage.value("peak_memory_mib", 0.0));
    }
    row["time.total"] = number(timings.value("total_seconds", 0.0));
    row["peak_memory_mib"] = number(peak);
  }
  return row;
}

/// Fixed columns first, then the swept keys, metrics, and times, each group sorted.
std::vector<std::string> columns_of(const std::vector<Row>& rows, const SweepConfig& config) {
  std::vector<std::string> columns{"job", "input"};
  for (const SweepAxis& axis : config.axes) columns.push_back(axis.key);
  columns.insert(columns.end(), {"status", "error"});
  std::set<std::string> metrics, times;
  for (const Row& row : rows)
    for (const auto& [key, value] : row) {
      if (std::find(columns.begin(), columns.end(), key) != columns.end()) continue;
      (key.rfind("time.", 0) == 0 || key == "peak_memory_mib" ? times : metrics).insert(key);
    }
  columns.insert(columns.end(), metrics.begin(), metrics.end());
  columns.insert(columns.end(), times.begin(), times.end());
  return columns;
}

std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string quoted = "\"";
  for (char c : s) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

std::string md_field(std::string s) {
  for (std::size_t p = 0; (p = s.find('|', p)) != std::string::npos; p += 2) s.replace(p, 1, "\\|");
  return s;
}

bool is_number(const std::string& s) {
  char* end = nullptr;
  std::strtod(s.c_str(), &end);
  return !s.empty() && end == s.c_str() + s.size();
}

/// When `plots:` is absent: every numeric swept parameter and the element count against every
/// Hausdorff-type error column (the curves the VMAS and MSD papers draw).
std::vector<PlotSpec> default_plots(const SweepConfig& config, const std::vector<std::string>& columns) {
  std::vector<std::string> errors, counts;
  for (const std::string& c : columns) {
    if (c.size() >= 13 && c.compare(c.size() - 13, 13, "hausdorff_pct") == 0) errors.push_back(c);
    if (c.size() >= 9 && c.compare(c.size() - 9, 9, ".vertices") == 0) counts.push_back(c);
  }
  std::vector<PlotSpec> plots;
  for (const std::string& y : errors) {
    for (const SweepAxis& axis : config.axes) {
      const bool numeric = std::all_of(axis.values.begin(), axis.values.end(), is_number);
      if (numeric && axis.values.size() > 1) plots.push_back({axis.key, y, "input"});
    }
    for (const std::string& x : counts) {
      PlotSpec scatter{x, y, "input"};
      scatter.points_only = true;  // one point per job, across meshes: no curve to draw
      plots.push_back(scatter);
    }
  }
  return plots;
}

/// Why no row gives a point for `column` (empty when some row does): no such column, or text only.
std::string unplottable(const std::string& column, const std::vector<Row>& rows,
                        const std::vector<std::string>& columns) {
  if (std::find(columns.begin(), columns.end(), column) == columns.end())
    return fmt::format("results.csv has no column '{}'", column);
  for (const Row& row : rows) {
    const auto it = row.find(column);
    if (it != row.end() && is_number(it->second)) return {};
  }
  return fmt::format("'{}' holds no numbers (a text column can be a plot's `series:`)", column);
}

void draw(const PlotSpec& plot, const std::vector<Row>& rows, const std::vector<std::string>& columns,
          const fs::path& plot_dir) {
  std::map<std::string, std::vector<std::pair<double, double>>> series;
  for (const Row& row : rows) {
    const auto x = row.find(plot.x), y = row.find(plot.y);
    if (x == row.end() || y == row.end() || !is_number(x->second) || !is_number(y->second)) continue;
    const auto s = row.find(plot.series);
    series[s == row.end() ? "all" : s->second].emplace_back(std::stod(x->second), std::stod(y->second));
  }
  if (series.empty()) {
    std::string why = unplottable(plot.x, rows, columns);
    if (why.empty()) why = unplottable(plot.y, rows, columns);
    if (why.empty()) why = "no row has numbers in both columns";
    fmt::print(stderr, "warning: plot of {} against {} not drawn: {}\n", plot.y, plot.x, why);
    return;
  }
  fs::create_directories(plot_dir);
  const std::string stem = fmt::format("{}_vs_{}", plot.y, plot.x);
  std::string plot_command = "plot ";
  std::size_t k = 0;
  for (auto& curve : series) {  // not a structured binding: C++17 lambdas cannot capture one
    const std::string& name = curve.first;
    std::vector<std::pair<double, double>>& points = curve.second;
    std::sort(points.begin(), points.end());
    const fs::path data = plot_dir / fmt::format("{}.{}.dat", stem, k);
    write_file_atomic(data, [&](std::ostream& out) {
      for (const auto& [x, y] : points) out << fmt::format("{} {}\n", x, y);
    });
    plot_command += fmt::format("{}'{}' using 1:2 with {} title '{}'", k ? ", " : "", data.string(),
                                plot.points_only ? "points pointsize 1.5" : "linespoints", name);
    ++k;
  }
  const fs::path script = plot_dir / (stem + ".gp");
  write_file_atomic(script, [&](std::ostream& out) {
    out << "set grid\nset key outside right\n";
    out << fmt::format("set xlabel '{}'\nset ylabel '{}'\n", plot.x, plot.y);
    if (plot.log_x) out << "set logscale x\n";
    if (plot.log_y) out << "set logscale y\n";
    // noenhanced: column names like recon.hausdorff_pct are text, not subscripts.
    for (const char* terminal : {"pngcairo noenhanced size 900,600", "svg noenhanced size 900,600"}) {
      const std::string ext = std::string(terminal).rfind("svg", 0) == 0 ? "svg" : "png";
      out << fmt::format("set terminal {}\nset output '{}'\n{}\n", terminal, (plot_dir / (stem + "." + ext)).string(),
                         plot_command);
    }
  });
  const std::string command = fmt::format("gnuplot '{}' 2>'{}'", script.string(), (plot_dir / (stem + ".log")).string());
  if (std::system(command.c_str()) != 0)
    fmt::print(stderr, "warning: gnuplot could not draw {} (is gnuplot installed? see {}.log)\n", stem,
               (plot_dir / stem).string());
}

}  // namespace

std::size_t write_sweep_results(const SweepConfig& config, const std::vector<SweepJob>& jobs, const fs::path& out_dir) {
  std::vector<Row> rows;
  for (const SweepJob& job : jobs) rows.push_back(job_row(job, out_dir / "jobs" / job.name));
  const std::vector<std::string> columns = columns_of(rows, config);
  const auto cell = [](const Row& row, const std::string& c) {
    const auto it = row.find(c);
    return it == row.end() ? std::string() : it->second;
  };
  write_file_atomic(out_dir / "results.csv", [&](std::ostream& out) {
    for (std::size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << csv_field(columns[i]);
    out << '\n';
    for (const Row& row : rows) {
      for (std::size_t i = 0; i < columns.size(); ++i) out << (i ? "," : "") << csv_field(cell(row, columns[i]));
      out << '\n';
    }
  });
  std::vector<std::string> shown = columns;
  if (!config.table_columns.empty()) {
    shown = {"job", "input", "status"};
    shown.insert(shown.end(), config.table_columns.begin(), config.table_columns.end());
  }
  write_file_atomic(out_dir / "results.md", [&](std::ostream& out) {
    out << fmt::format("# {}\n\n{} jobs from `{}`.\n\n", config.name, rows.size(), config.file.filename().string());
    out << "|";
    for (const std::string& c : shown) out << ' ' << md_field(c) << " |";
    out << "\n|";
    for (std::size_t i = 0; i < shown.size(); ++i) out << "---|";
    out << '\n';
    for (const Row& row : rows) {
      out << "|";
      for (const std::string& c : shown) out << ' ' << md_field(cell(row, c)) << " |";
      out << '\n';
    }
  });
  const std::vector<PlotSpec> plots = config.plots.empty() ? default_plots(config, columns) : config.plots;
  fs::remove_all(out_dir / "plots");  // plots of entries removed from `plots:` must not linger
  for (const PlotSpec& plot : plots) draw(plot, rows, columns, out_dir / "plots");
  return rows.size();
}

}  // namespace medax
