#include "report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>

#include "scene_io/atomic_file.h"

namespace trs_bench {

namespace {

/// The CPU backend's passes, in the order they run; the table shows these, the CSV any others too.
const std::vector<std::string> kKnownPasses = {"counting", "rounding", "scan", "distribution",
                                               "realization"};

template <class... Args>
std::string format(const char* pattern, Args... args) {
  char buffer[128];
  std::snprintf(buffer, sizeof buffer, pattern, args...);
  return buffer;
}

std::string format_target(double target) {
  const double exponent = std::log10(target);
  if (target >= 1 && exponent == std::round(exponent)) return format("1e%d", int(exponent));
  return format("%.3g", target);
}

/// Milliseconds with about four significant digits, whatever the magnitude.
std::string format_ms(double ms) {
  if (ms < 10) return format("%.3f", ms);
  if (ms < 1000) return format("%.1f", ms);
  return format("%.0f", ms);
}

std::optional<double> pass_ms(const Measurement& m, const std::string& name) {
  for (const auto& pass : m.pass_medians)
    if (lightsampler::to_string(pass.pass) == name) return pass.ms;
  return std::nullopt;
}

struct Column {
  const char* header;
  int width;
};

const std::vector<Column> kColumns = {
    {"mesh", -6},    {"tris", 8},     {"map", -6},     {"engine", -10}, {"method", -6},
    {"scan", -9},    {"target", 6},   {"samples", 10}, {"accept", 7},
    {"count ms", 9}, {"round ms", 9}, {"scan ms", 9},  {"distr ms", 9},
    {"real ms", 9},  {"total ms", 9}, {"Msmp/s", 8},   {"runs", 4},     {"x floor", 7},
    {"variant", 0}};

/// One table line: cells padded to their column (negative width: left-aligned); cells past the
/// end of `cells` are left out, so a skipped case can end with a free-text note.
std::string table_line(const std::vector<std::string>& cells) {
  std::string line;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const int width = i < kColumns.size() ? kColumns[i].width : 0;
    line += format(width < 0 ? "%-*s" : "%*s", std::abs(width), cells[i].c_str());
    if (i + 1 < cells.size()) line += ' ';
  }
  return line;
}

std::vector<std::string> table_cells(const CaseResult& r) {
  std::vector<std::string> cells = {r.mesh,   std::to_string(r.triangles), r.map, r.engine,
                                    r.method, r.scan, format_target(r.target)};
  if (!r.measured) {
    cells.push_back(format("skipped (est. %.1f s per frame)", r.estimate_ms * 1e-3));
    return cells;
  }
  const Measurement& m = *r.measured;
  cells.push_back(format("%.0f", m.samples));
  cells.push_back(m.realized() ? format("%.3g%%", 100 * m.acceptance()) : "-");
  for (const auto& name : kKnownPasses) {
    const auto ms = pass_ms(m, name);
    cells.push_back(ms ? format_ms(*ms) : "-");
  }
  cells.push_back(format_ms(m.total_ms));
  cells.push_back(m.realized() ? format("%.3g", m.samples_per_s() * 1e-6) : "-");
  cells.push_back(std::to_string(m.runs));
  cells.push_back(r.floor_ms ? format("%.3g", m.total_ms / *r.floor_ms) : "-");
  // The ablation, or the overlap formula where it is what the rows compare.
  cells.push_back(!r.variant.empty() ? r.variant : r.experiment == "overlap" ? r.overlap : "");
  return cells;
}

std::string csv_quote(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

/// A square map's width, as the column always said; WxH for a map from a file that is not square.
std::string map_size_cell(const CaseResult& r) {
  if (r.map_width == r.map_height) return std::to_string(r.map_width);
  return std::to_string(r.map_width) + "x" + std::to_string(r.map_height);
}

/// Pass names of all results: the known ones first, then any others in the order they appear.
std::vector<std::string> csv_pass_columns(const std::vector<CaseResult>& results) {
  std::vector<std::string> names = kKnownPasses;
  for (const auto& r : results)
    if (r.measured)
      for (const auto& pass : r.measured->pass_medians)
        if (std::find(names.begin(), names.end(), lightsampler::to_string(pass.pass)) == names.end())
          names.push_back(lightsampler::to_string(pass.pass));
  return names;
}

std::string csv_text(const std::vector<CaseResult>& results) {
  const auto passes = csv_pass_columns(results);
  std::string text =
      "experiment,mesh,triangles,map,map_size,method,scan,target,status,runs,samples,candidates,"
      "acceptance,exhausted";
  for (const auto& name : passes) text += "," + name + "_ms";
  text += ",total_ms,wall_ms,samples_per_s,threads,backend,engine,device,estimate_ms,refine,floor_ms,floor_multiple,"
          "setup_ms,setup_bytes,overlap,variant,coverage\n";
  for (const auto& r : results) {
    text += r.experiment + "," + csv_quote(r.mesh) + "," + std::to_string(r.triangles) + "," +
            csv_quote(r.map) + "," + map_size_cell(r) + "," + r.method + "," + r.scan + "," +
            format("%.9g", r.target) + "," + (r.measured ? "ok" : "skipped");
    if (r.measured) {
      const Measurement& m = *r.measured;
      text += format(",%d,%.9g,%.9g,", m.runs, m.samples, m.candidates);
      text += (m.realized() ? format("%.6g", m.acceptance()) : "") +
              format(",%llu", static_cast<unsigned long long>(m.exhausted));
      for (const auto& name : passes) {
        const auto ms = pass_ms(m, name);
        text += ms ? format(",%.6g", *ms) : ",";
      }
      text += format(",%.6g,%.6g,", m.total_ms, m.wall_ms);
      text += m.realized() ? format("%.6g", m.samples_per_s()) : "";
    } else {
      text += std::string(5 + passes.size() + 3, ',');
    }
    text += format(",%u,", r.threads) + csv_quote(r.backend) + ',' + csv_quote(r.engine) + ',' +
            csv_quote(r.device) + ',';
    text += (r.measured ? "" : format("%.6g", r.estimate_ms)) + format(",%g,", r.refine);
    text += r.floor_ms ? format("%.6g,", *r.floor_ms) : ",";
    text += r.floor_ms && r.measured ? format("%.6g,", r.measured->total_ms / *r.floor_ms) : ",";
    text += r.measured && r.measured->setup_bytes ? format("%.6g,%llu,", r.measured->setup_ms,
                                                           static_cast<unsigned long long>(r.measured->setup_bytes))
                                                  : ",,";
    text += csv_quote(r.overlap) + ',' + csv_quote(r.variant) + ',';
    text += r.experiment == "floor" ? "\n" : format("%.9g\n", r.coverage);
  }
  return text;
}

}  // namespace

Recorder::Recorder(std::ostream& table, std::filesystem::path csv)
    : table_(table), csv_(std::move(csv)) {}

void Recorder::begin_section(const std::string& title) {
  std::vector<std::string> headers;
  for (const auto& column : kColumns) headers.push_back(column.header);
  table_ << "\n" << title << "\n" << table_line(headers) << std::endl;
}

void Recorder::add(CaseResult result) {
  table_ << table_line(table_cells(result)) << std::endl;
  results_.push_back(std::move(result));
  if (!csv_.empty()) write_csv();
}

void Recorder::write_csv() const {
  trs::AtomicFile file(csv_);
  file.write(csv_text(results_));
  file.commit();
}

void print_speedups(std::ostream& out, const std::vector<CaseResult>& results) {
  const auto time_ms = [](const CaseResult& r) {
    return r.measured ? r.measured->total_ms : r.estimate_ms;
  };
  bool header = false;
  for (const auto& trs : results) {
    if (trs.experiment != "sampling" || trs.method != "trs" || !trs.measured) continue;
    const auto rs = std::find_if(results.begin(), results.end(), [&](const CaseResult& r) {
      return r.experiment == "sampling" && r.method == "rs" && r.backend == trs.backend && r.mesh == trs.mesh &&
             r.triangles == trs.triangles && r.map == trs.map && r.target == trs.target;
    });
    if (rs == results.end()) continue;
    if (!header) {
      out << "\nTRS speed-up over plain rejection sampling (total frame time; ~ marks an "
             "extrapolated rejection time)\n"
          << format("%-6s %8s %-6s %-10s %6s %10s %12s %9s", "mesh", "tris", "map", "engine", "target",
                    "trs ms", "rs ms", "speed-up")
          << "\n";
      header = true;
    }
    const char* mark = rs->measured ? "" : "~";
    out << format("%-6s %8llu %-6s %-10s %6s %10s %12s %9s", trs.mesh.c_str(),
                  static_cast<unsigned long long>(trs.triangles), trs.map.c_str(), trs.engine.c_str(),
                  format_target(trs.target).c_str(), format_ms(time_ms(trs)).c_str(),
                  format("%s%s", mark, format_ms(time_ms(*rs)).c_str()).c_str(),
                  format("%s%.3gx", mark, time_ms(*rs) / time_ms(trs)).c_str())
        << "\n";
  }
}

}  // namespace trs_bench
