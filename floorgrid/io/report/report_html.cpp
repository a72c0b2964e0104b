#include "floorgrid/io/report/report_html.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "floorgrid/core/error.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/report/report_assets.hpp"
#include "floorgrid/io/report/report_format.hpp"
#include "floorgrid/io/report/report_sections.hpp"

namespace floorgrid::io {

namespace {

namespace fs = std::filesystem;

nlohmann::json read_json(const fs::path& path) {
  const std::string text = read_whole_file(path);
  nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded())
    throw InputError("not valid JSON", path.string(), 0, "");
  return j;
}

/// The PNG files of `folder`/`sub`, by name.
void add_images(const fs::path& folder, const std::string& sub, std::vector<ReportImage>& images) {
  std::error_code error;
  if (!fs::is_directory(folder / sub, error))
    return;
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder / sub, error)) {
    if (entry.is_regular_file(error) && entry.path().extension() == ".png")
      names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  for (const std::string& name : names)
    images.push_back({sub + "/" + name, read_whole_file(folder / sub / name)});
}

/// JSON safe inside a <script> element: "</" would end the element.
std::string script_json(const nlohmann::json& j) {
  std::string text = j.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    out += text[i];
    if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/')
      out += '\\';
  }
  return out;
}

std::string navigation() {
  static const char* const kLinks[][2] = {
      {"summary", "Summary"},           {"models", "Models"},
      {"histograms", "Histograms"},     {"pairs", "Pairs"},
      {"localization", "Localization"}, {"heatmaps", "Heat maps"},
      {"overlays", "Overlays"},         {"back-and-forth", "Back and forth"},
      {"timings", "Timings"},           {"dataset", "Dataset"}};
  std::string nav = "<nav>";
  for (const auto& link : kLinks)
    nav += fmt::format("<a href=\"#{}\">{}</a>", link[0], link[1]);
  return nav + "</nav>\n";
}

}  // namespace

ReportInputs read_report_inputs(const fs::path& folder) {
  ReportInputs in;
  in.metrics = read_json(folder / "metrics.json");
  std::error_code error;
  if (fs::is_regular_file(folder / "model-auto.json", error))
    in.auto_model = read_json(folder / "model-auto.json");
  if (fs::is_regular_file(folder / "scans.csv", error))
    in.scans_csv = read_whole_file(folder / "scans.csv");
  add_images(folder, "overlays", in.images);
  add_images(folder, "heatmaps", in.images);
  if (fs::is_directory(folder / "exports", error)) {
    for (const fs::directory_entry& entry : fs::directory_iterator(folder / "exports", error)) {
      if (entry.is_regular_file(error))
        in.exports.push_back(entry.path().filename().string());
    }
    std::sort(in.exports.begin(), in.exports.end());
  }
  return in;
}

std::string render_report_html(const ReportInputs& inputs) {
  const ReportContext c = report_context(inputs);
  const std::string dataset = json_at(inputs.metrics, {"dataset"}).is_string()
                                  ? inputs.metrics["dataset"].get<std::string>()
                                  : std::string("(unnamed)");
  std::string page;
  page.reserve(1 << 20);
  page += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  page += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  // Nothing may leave the file: no network, whatever a string in the data says.
  page +=
      "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; img-src data:; "
      "style-src 'unsafe-inline'; script-src 'unsafe-inline'\">\n";
  page += fmt::format("<title>floorgrid report: {}</title>\n", html_escape(dataset));
  page += "<style>\n";
  page += uplot_css();
  page += "\n";
  page += report_page_css();
  page += "</style>\n</head>\n<body>\n<header>\n";
  page += fmt::format("<h1>Floorplan to gridmap: <span class=\"dataset\">{}</span></h1>\n",
                      html_escape(dataset));
  page += navigation();
  page += "</header>\n<main>\n";
  page += summary_section(c);
  page += models_section(c);
  page += histogram_section(c);
  page += pairs_section(c);
  page += localization_section(c);
  page += heatmaps_section(c);
  page += overlays_section(c);
  page += back_and_forth_section(c);
  page += timings_section(c);
  page += dataset_section(c);
  page +=
      "</main>\n<footer>\n<p>Written by floorgrid from the files beside it (metrics.json, "
      "model-auto.json, scans.csv, overlays/, heatmaps/). Charts drawn with uPlot (MIT "
      "License, &copy; Leon Sorokin, https://github.com/leeoniya/uPlot), inlined: this page "
      "needs no network.</p>\n</footer>\n";
  page += "<script type=\"application/json\" id=\"report-data\">" + script_json(chart_data(c)) +
          "</script>\n";
  page += "<script>\n";
  page += uplot_js();
  page += "\n</script>\n<script>\n";
  page += report_page_js();
  page += "</script>\n</body>\n</html>\n";
  return page;
}

fs::path write_report_html(const fs::path& folder) {
  const fs::path path = folder / "report.html";
  write_file_atomically(path, render_report_html(read_report_inputs(folder)));
  return path;
}

}  // namespace floorgrid::io
