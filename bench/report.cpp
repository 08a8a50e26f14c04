#include "report.h"

#include <cmath>
#include <cstdio>
#include <sstream>

namespace crestline::bench {
namespace {

std::string seconds_cell(double s) {
  if (std::isnan(s)) return "-";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3f", s);
  return buffer;
}

std::string json_string(const char* text) {
  std::string out = "\"";
  for (const char* c = text; *c; ++c) {
    if (*c == '"' || *c == '\\') out += '\\';
    if (static_cast<unsigned char>(*c) < 0x20) continue;
    out += *c;
  }
  return out + "\"";
}

std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", v);
  return buffer;
}

// The stage whose progress call ended the longest gap ("end": run() returned).
const char* gap_stage_name(int stage) {
  return stage >= 0 && stage < kStages ? stage_name(static_cast<Stage>(stage)) : "end";
}

double bytes_per_triangle(const MeshResult& r) {
  return r.triangles && r.peak_rss >= r.input_rss ? double(r.peak_rss - r.input_rss) / double(r.triangles) : NAN;
}

}  // namespace

void print_table(const std::vector<MeshResult>& results) {
  std::vector<std::string> header = {"mesh", "triangles", "read", "repair", "topology"};
  for (int s = 0; s < kStages; ++s) header.push_back(stage_name(static_cast<Stage>(s)));
  header.push_back("write");
  for (const char* h : {"total", "cpu", "re-thr", "re-smooth", "cancel wait", "peak MB", "B/tri", "iterations"})
    header.push_back(h);

  std::vector<std::vector<std::string>> rows;
  for (const MeshResult& r : results) {
    std::vector<std::string> row = {r.name, std::to_string(r.triangles)};
    if (r.error[0]) {
      row.push_back(std::string("error: ") + r.error);
      rows.push_back(row);
      continue;
    }
    for (double s : {r.read, r.repair, r.topology}) row.push_back(seconds_cell(s));
    for (double s : r.stages) row.push_back(seconds_cell(s));
    row.push_back(seconds_cell(r.write));
    for (double s : {r.total, r.cpu, r.rethreshold, r.resmooth}) row.push_back(seconds_cell(s));
    row.push_back(seconds_cell(r.longest_gap) + " " + gap_stage_name(r.gap_stage));
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.0f", r.peak_rss / 1048576.0);
    row.push_back(buffer);
    std::snprintf(buffer, sizeof buffer, "%.0f", bytes_per_triangle(r));
    row.push_back(buffer);
    row.push_back(std::to_string(r.smoothing_iterations));
    rows.push_back(row);
  }
  std::vector<size_t> width(header.size());
  for (size_t c = 0; c < header.size(); ++c) {
    width[c] = header[c].size();
    for (const auto& row : rows)
      if (c < row.size() && row.size() == header.size()) width[c] = std::max(width[c], row[c].size());
  }
  auto print_row = [&](const std::vector<std::string>& row) {
    std::string line = "|";
    for (size_t c = 0; c < row.size(); ++c) {
      const std::string& cell = row[c];
      const size_t pad = c < width.size() && width[c] > cell.size() ? width[c] - cell.size() : 0;
      line += " " + (c == 0 ? cell + std::string(pad, ' ') : std::string(pad, ' ') + cell) + " |";
    }
    std::printf("%s\n", line.c_str());
  };
  print_row(header);
  std::string rule = "|";
  for (size_t c = 0; c < header.size(); ++c)
    rule += (c == 0 ? ":" : "") + std::string(width[c] + 1, '-') + (c == 0 ? "|" : ":|");
  std::printf("%s\n", rule.c_str());
  for (const auto& row : rows) print_row(row);
}

std::string to_json(const std::vector<MeshResult>& results, const BenchSettings& settings) {
  std::ostringstream out;
  const PipelineOptions& p = settings.pipeline;
  out << "{\n  \"runner\": \"native\",\n  \"runs\": " << settings.runs << ",\n  \"threads\": " << settings.threads
      << ",\n  \"options\": {\"smoothing_steps\": " << p.smoothing.steps
      << ", \"smoothing_time_step\": " << json_number(p.smoothing.time_step)
      << ", \"fairing_bound\": " << json_number(p.fairing.hausdorff_bound)
      << ", \"fairing_iterations\": " << p.fairing.iterations << "},\n  \"meshes\": [";
  for (size_t i = 0; i < results.size(); ++i) {
    const MeshResult& r = results[i];
    out << (i ? "," : "") << "\n    {\"name\": " << json_string(r.name) << ", \"source\": " << json_string(r.source)
        << ", \"soup\": " << json_string(r.soup_file);
    if (r.error[0]) {
      out << ", \"error\": " << json_string(r.error) << "}";
      continue;
    }
    out << ", \"vertices\": " << r.vertices << ", \"triangles\": " << r.triangles << ", \"runs\": " << r.runs
        << ",\n     \"seconds\": {\"read\": " << json_number(r.read) << ", \"repair\": " << json_number(r.repair)
        << ", \"topology\": " << json_number(r.topology);
    for (int s = 0; s < kStages; ++s)
      out << ", \"" << stage_name(static_cast<Stage>(s)) << "\": " << json_number(r.stages[s]);
    out << ", \"write\": " << json_number(r.write) << ", \"total\": " << json_number(r.total)
        << ", \"total_cpu\": " << json_number(r.cpu) << ", \"rethreshold\": " << json_number(r.rethreshold)
        << ", \"resmooth\": " << json_number(r.resmooth) << ", \"longest_progress_gap\": " << json_number(r.longest_gap)
        << "}, \"longest_progress_gap_before\": " << json_string(gap_stage_name(r.gap_stage))
        << ",\n     \"input_rss_bytes\": " << r.input_rss << ", \"peak_rss_bytes\": " << r.peak_rss
        << ", \"peak_bytes_per_triangle_above_input\": " << json_number(bytes_per_triangle(r))
        << ", \"smoothing_iterations\": " << r.smoothing_iterations << ",\n     \"lines\": {\"ridges\": " << r.ridges
        << ", \"valleys\": " << r.valleys << ", \"ridge_length\": " << json_number(r.ridge_length)
        << ", \"valley_length\": " << json_number(r.valley_length) << "}}";
  }
  out << "\n  ]\n}\n";
  return out.str();
}

}  // namespace crestline::bench
