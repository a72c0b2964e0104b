#include "floorgrid/io/report/report_sections.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "floorgrid/io/files/base64.hpp"
#include "floorgrid/io/report/report_format.hpp"

namespace floorgrid::io {

namespace {

using nlohmann::json;

std::string section(const std::string& id, const std::string& title, const std::string& lead,
                    const std::string& body) {
  return fmt::format("<section id=\"{}\">\n<h2>{}</h2>\n<p class=\"lead\">{}</p>\n{}</section>\n",
                     id, html_escape(title), lead, body);
}

double number_or(const json& j, double fallback) {
  return j.is_number() ? j.get<double>() : fallback;
}

std::string text_of(const json& j) {
  if (j.is_string())
    return j.get<std::string>();
  if (j.is_null())
    return "n/a";
  return j.dump();
}

/// The error a model is ranked by: against the truth when there is one, else cross-validated.
double ranking_error(const json& model, bool has_truth) {
  const double inf = std::numeric_limits<double>::infinity();
  return number_or(has_truth ? json_at(model, {"mean_error_m"}) : json_at(model, {"cv_error_m"}),
                   inf);
}

std::string image_tag(const ReportImage& image, const std::string& alt) {
  return fmt::format("<img src=\"data:image/png;base64,{}\" alt=\"{}\">", base64_encode(image.png),
                     html_escape(alt));
}

const ReportImage* find_image(const ReportInputs& in, const std::string& path) {
  for (const ReportImage& image : in.images) {
    if (image.path == path)
      return &image;
  }
  return nullptr;
}

std::string model_label(const ReportContext& c, const std::string& name) {
  if (name == "auto" && !c.chosen.empty())
    return fmt::format("auto <span class=\"muted\">(= {})</span>", html_escape(c.chosen));
  std::string label = html_escape(name);
  if (name == c.chosen)
    label += " <span class=\"badge\">chosen</span>";
  return label;
}

/// Why auto chose its model, from model-auto.json's fit details (cv_table).
std::string why_chosen(const ReportContext& c) {
  const json& details = json_at(c.inputs.auto_model, {"fit", "details"});
  const json& table = json_at(details, {"cv_table"});
  if (c.chosen.empty())
    return "<p>No model was chosen (auto could not be fitted).</p>\n";
  if (!table.is_object() || table.empty()) {
    return fmt::format(
        "<p><b>{}</b> was chosen by <code>auto</code>: the lowest cross-validated error on the "
        "pairs (model-auto.json, with the details, is not in this folder).</p>\n",
        html_escape(c.chosen));
  }
  const bool paired = table.begin()->contains("paired_rms_m");
  const char* score_key = paired ? "paired_rms_m" : "mean_error_m";
  std::string lowest;
  double lowest_score = std::numeric_limits<double>::infinity();
  for (const auto& [name, row] : table.items()) {
    const double s = number_or(json_at(row, {score_key}), std::numeric_limits<double>::infinity());
    if (s < lowest_score) {
      lowest_score = s;
      lowest = name;
    }
  }
  std::string why;
  const std::string kind = text_of(json_at(details, {"cv_kind"}));
  if (paired) {
    why = fmt::format(
        "<code>auto</code> held out stretches of the run ({} folds) and predicted each from the "
        "rest, pair by pair. ",
        html_escape(text_of(json_at(details, {"folds"}))));
    if (lowest == c.chosen) {
      why += fmt::format("<b>{}</b> had the lowest held-out rms error, {}.", html_escape(c.chosen),
                         format_metres(lowest_score));
    } else {
      why += fmt::format(
          "<b>{}</b> had the lowest held-out rms error ({}); <b>{}</b> ({}) was chosen as an "
          "earlier, simpler candidate within one standard error of it: a difference the pairs' "
          "noise could make.",
          html_escape(lowest), format_metres(lowest_score), html_escape(c.chosen),
          format_metres(json_at(table, {c.chosen.c_str(), "paired_rms_m"})));
    }
  } else {
    why = fmt::format(
        "<code>auto</code> cross-validated every candidate ({} folds, {}); <b>{}</b> had the "
        "lowest mean held-out error, {}.",
        html_escape(text_of(json_at(details, {"folds"}))), html_escape(kind), html_escape(c.chosen),
        format_metres(json_at(table, {c.chosen.c_str(), "mean_error_m"})));
  }
  std::vector<std::string> names;
  for (const auto& [name, row] : table.items())
    names.push_back(name);
  std::stable_sort(names.begin(), names.end(), [&](const std::string& a, const std::string& b) {
    const double inf = std::numeric_limits<double>::infinity();
    return number_or(json_at(table[a], {score_key}), inf) <
           number_or(json_at(table[b], {score_key}), inf);
  });
  std::string rows;
  for (const std::string& name : names) {
    const json& row = table[name];
    rows += fmt::format(
        "<tr{}><td>{}</td><td>{}</td><td>{}</td>{}<td>{}</td></tr>\n",
        name == c.chosen ? " class=\"chosen\"" : "", html_escape(name),
        format_metres(json_at(row, {"mean_error_m"})),
        format_metres(json_at(row, {"median_error_m"})),
        paired ? fmt::format("<td>{}</td>", format_metres(json_at(row, {"paired_rms_m"}))) : "",
        html_escape(text_of(json_at(row, {"failed_folds"}))));
  }
  return fmt::format(
      "<h3>Why {}</h3>\n<p>{}</p>\n<table class=\"numbers\">\n<thead><tr><th>candidate</th>"
      "<th>held-out mean</th><th>held-out median</th>{}<th>failed folds</th></tr></thead>\n"
      "<tbody>\n{}</tbody>\n</table>\n",
      html_escape(c.chosen), why, paired ? "<th>held-out rms (compared)</th>" : "", rows);
}

/// Where the pairs came from: "run", "maps" (the maps alone) or "both" (metrics.json
/// pairs.source; "run" when a folder predates it).
std::string pair_source(const ReportContext& c) {
  const json& source = json_at(c.metrics(), {"pairs", "source"});
  return source.is_string() ? source.get<std::string>() : "run";
}

/// The maps-only alignment (metrics.json maps_only): the global registration, the bending, the
/// fitness and its verdict.
std::string maps_alignment_body(const json& m) {
  const json& r = json_at(m, {"registration"});
  const bool accepted = json_at(m, {"accepted"}) == json(true);
  const double turn = number_or(json_at(r, {"theta_deg"}), NAN);
  std::string body = fmt::format(
      "<p>The gridmap was registered on the plan as a whole: plan scale <b>{}</b> (plan metres "
      "per world metre {}), turned <b>{:.1f}&deg;</b>, score {:.2f} ({} of its walls on the "
      "plan's, {} of the plan's walls in space it saw free){}; the best other answer scored "
      "{:.2f}. Then it was bent onto the plan's walls in {} stages of a displacement lattice, "
      "coarse to fine: of its {} wall points, <b>{}</b> ended within reach of a plan wall and "
      "became the pairs (median {} from it).</p>\n",
      format_ratio(json(1.0 / number_or(json_at(r, {"scale"}), NAN))),
      format_ratio(json_at(r, {"scale"})), turn, number_or(json_at(r, {"score"}), NAN),
      format_percent(json_at(r, {"on_walls"})), format_percent(json_at(r, {"in_free_space"})),
      json_at(r, {"correlation"}) == json(true) ? ", found by a 2-D correlation search" : "",
      number_or(json_at(r, {"runner_up_score"}), NAN), format_count(json_at(m, {"stages"})),
      format_count(json_at(m, {"points"})), format_count(json_at(m, {"pairs"})),
      format_metres(json_at(m, {"median_distance_m"})));
  // A bar the folder states ("" for an older folder without it).
  const auto bar = [&](const char* key, const char* text) {
    const json& value = json_at(m, {key});
    return value.is_number() ? fmt::format(fmt::runtime(text), value.get<double>()) : std::string();
  };
  body += fmt::format(
      "<p class=\"{}\">Fitness of the bent gridmap: <b>{:.2f}</b>{}; {} of its walls on the "
      "plan's{}, {} of the plan's walls in space it saw free. Ambiguity {:.2f}{}: how well the "
      "best other place the registration found fits, bent too, against this one (1: as well). "
      "{}.</p>\n",
      accepted ? "" : "warning", number_or(json_at(m, {"fitness"}), NAN),
      bar("min_fitness", ", at least {:.2f} needed"), format_percent(json_at(m, {"on_walls"})),
      bar("min_on_walls", " (at least {:.2f} needed)"),
      format_percent(json_at(m, {"in_free_space"})), number_or(json_at(m, {"ambiguity"}), NAN),
      bar("max_ambiguity", " (below {:.2f} needed)"),
      accepted ? "Accepted" : "Not accepted: " + html_escape(text_of(json_at(m, {"diagnosis"}))));
  body +=
      fmt::format("<p class=\"muted\">Took {} (the registration {}).</p>\n",
                  format_seconds(json_at(m, {"seconds"})), format_seconds(json_at(r, {"seconds"})));
  return body;
}

std::string card(const std::string& title, const std::string& value, const std::string& note) {
  return fmt::format(
      "<div class=\"card\"><div class=\"card-title\">{}</div><div class=\"card-value\">{}</div>"
      "<div class=\"card-note\">{}</div></div>\n",
      title, value, note);
}

}  // namespace

const json& json_at(const json& j, std::initializer_list<const char*> path) {
  static const json null_value = nullptr;
  const json* at = &j;
  for (const char* key : path) {
    if (!at->is_object())
      return null_value;
    const auto found = at->find(key);
    if (found == at->end())
      return null_value;
    at = &*found;
  }
  return *at;
}

ReportContext report_context(const ReportInputs& inputs) {
  ReportContext c{inputs, {}, false, {}, scan_track(inputs.scans_csv)};
  const json& chosen = json_at(inputs.metrics, {"chosen_model"});
  if (chosen.is_string())
    c.chosen = chosen.get<std::string>();
  const json& models = json_at(inputs.metrics, {"models"});
  if (models.is_object()) {
    for (const auto& [name, m] : models.items()) {
      c.models.push_back(name);
      c.has_truth = c.has_truth || json_at(m, {"mean_error_m"}).is_number();
    }
  }
  // Best first; the chosen model leads its ties (auto equals it).
  std::stable_sort(c.models.begin(), c.models.end(),
                   [&](const std::string& a, const std::string& b) {
                     const double ea = ranking_error(models[a], c.has_truth);
                     const double eb = ranking_error(models[b], c.has_truth);
                     if (ea != eb)
                       return ea < eb;
                     return (a == c.chosen) > (b == c.chosen);
                   });
  return c;
}

std::string summary_section(const ReportContext& c) {
  const json& m = c.metrics();
  const json& chosen = json_at(m, {"models", c.chosen.c_str()});
  std::string cards;
  cards += card("Chosen model", c.chosen.empty() ? "none" : html_escape(c.chosen),
                "picked by <code>auto</code>; <a href=\"#models\">why</a>");
  if (c.has_truth) {
    cards += card(
        "Mean error vs truth", format_metres(json_at(chosen, {"mean_error_m"})),
        fmt::format("median {}, 95% under {}", format_metres(json_at(chosen, {"median_error_m"})),
                    format_metres(json_at(chosen, {"p95_error_m"}))));
  }
  cards += card(
      "Cross-validated error", format_metres(json_at(chosen, {"cv_error_m"})),
      fmt::format("on held-out pairs ({})", html_escape(text_of(json_at(chosen, {"cv_kind"})))));
  const std::string source = pair_source(c);
  const json& maps = json_at(m, {"maps_only"});
  const json& fallback = json_at(m, {"pairs", "fallback"});
  if (source == "maps") {
    cards += card("Pairs", format_count(json_at(m, {"pairs", "count"})),
                  fallback.is_string()
                      ? std::string("from the maps alone: <b>the run's were not used</b> "
                                    "(<a href=\"#pairs\">why</a>)")
                      : std::string("from the maps alone: gridmap walls on the plan's"));
  } else {
    cards += card("Pairs", format_count(json_at(m, {"pairs", "count"})),
                  fmt::format("from {} scans{}", format_count(json_at(m, {"pairs", "scans"})),
                              source == "both" ? " and the maps" : ""));
    cards += card("Converged", format_percent(json_at(m, {"pairs", "converged_fraction"})),
                  "of the scans, both filters sure");
  }
  if (maps.is_object()) {
    cards += card("Maps fitness", fmt::format("{:.2f}", number_or(json_at(maps, {"fitness"}), NAN)),
                  json_at(maps, {"accepted"}) == json(true)
                      ? "the bent gridmap on the plan: accepted"
                      : "the bent gridmap on the plan: <b>not accepted</b>");
  }
  const bool estimated = json_at(m, {"plan_scale_estimated"}) == json(true);
  cards += card("Plan scale", format_ratio(json_at(m, {"plan_scale"})),
                !estimated         ? std::string("given")
                : source == "maps" ? std::string("estimated from the maps")
                                   : fmt::format("&plusmn; {}, estimated from the run",
                                                 format_ratio(json_at(m, {"plan_scale_std"}))));
  const json& match = json_at(m, {"plan_match"});
  if (match.is_object()) {
    cards += card("Plan match", fmt::format("{:.2f}", number_or(match["score"], NAN)),
                  fmt::format("{} of the gridmap's walls on the plan's",
                              format_percent(json_at(match, {"on_walls"}))));
  }
  std::string notes;
  for (const std::string& name : c.models) {
    const json& failure = json_at(m, {"models", name.c_str(), "failure"});
    if (failure.is_string()) {
      notes += fmt::format("<p class=\"warning\">{} could not be fitted: {}</p>\n",
                           html_escape(name), html_escape(failure.get<std::string>()));
    }
  }
  return section("summary", "Summary",
                 "The model to use and how far off it is; the pairs it was learnt from.",
                 "<div class=\"cards\">\n" + cards + "</div>\n" + notes);
}

std::string models_section(const ReportContext& c) {
  const json& models = json_at(c.metrics(), {"models"});
  std::string head = "<th>model</th>";
  if (c.has_truth)
    head += "<th>mean error</th><th>median</th><th>95th pct.</th>";
  head +=
      "<th>cross-validated</th><th>median to walls</th><th>round trip max</th><th>pairs "
      "used</th><th>fit time</th>";
  std::string rows;
  for (const std::string& name : c.models) {
    const json& r = models[name];
    std::string cells = fmt::format("<td>{}</td>", model_label(c, name));
    if (r.contains("failure")) {
      rows += fmt::format("<tr class=\"failed\">{}<td colspan=\"{}\">failed: {}</td></tr>\n", cells,
                          c.has_truth ? 8 : 5, html_escape(text_of(r["failure"])));
      continue;
    }
    if (c.has_truth) {
      cells += fmt::format("<td>{}</td><td>{}</td><td>{}</td>",
                           format_metres(json_at(r, {"mean_error_m"})),
                           format_metres(json_at(r, {"median_error_m"})),
                           format_metres(json_at(r, {"p95_error_m"})));
    }
    cells += fmt::format("<td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>",
                         format_metres(json_at(r, {"cv_error_m"})),
                         format_metres(json_at(r, {"wall_distance_median_m"})),
                         format_metres(json_at(r, {"back_and_forth", "max_m"})),
                         format_count(json_at(r, {"pairs_used"})),
                         format_seconds(json_at(r, {"fit_seconds"})));
    rows += fmt::format("<tr{}>{}</tr>\n", name == c.chosen ? " class=\"chosen\"" : "", cells);
  }
  const std::string lead =
      c.has_truth ? "Every model, best first by its mean error against the truth over the domain; "
                    "the chosen one is marked."
                  : "Every model, best first by its cross-validated error (no truth in this "
                    "dataset); the chosen one is marked.";
  return section("models", "Models", lead,
                 "<table class=\"numbers\">\n<thead><tr>" + head + "</tr></thead>\n<tbody>\n" +
                     rows + "</tbody>\n</table>\n" +
                     "<p class=\"muted\">Median to walls: how far the gridmap's walls lie from the "
                     "plan's mapped through the model (no truth needed). Round trip: the largest "
                     "drift of a point mapped there and back 100 times.</p>\n" +
                     why_chosen(c));
}

std::string histogram_section(const ReportContext& c) {
  if (!c.has_truth) {
    return section("histograms", "Error histograms",
                   "The share of the domain's points per error bin, per model.",
                   "<p class=\"muted\">No truth in this dataset: no errors to count.</p>\n");
  }
  std::string head = "<th>error</th>";
  std::vector<std::string> names;
  for (const std::string& name : c.models) {
    if (name != "auto" &&
        json_at(c.metrics(), {"models", name.c_str(), "error_histogram"}).is_array()) {
      names.push_back(name);
      head += fmt::format("<th>{}</th>", html_escape(name));
    }
  }
  std::string rows;
  for (int bin = 0; bin <= 20; ++bin) {
    rows += bin < 20
                ? fmt::format("<tr><td>{:.2f}&ndash;{:.2f} m</td>", 0.05 * bin, 0.05 * (bin + 1))
                : std::string("<tr><td>1.0 m and more</td>");
    for (const std::string& name : names) {
      const json& h = json_at(c.metrics(), {"models", name.c_str(), "error_histogram"});
      rows +=
          fmt::format("<td>{}</td>", static_cast<std::size_t>(bin) < h.size() ? format_count(h[bin])
                                                                              : std::string("n/a"));
    }
    rows += "</tr>\n";
  }
  return section(
      "histograms", "Error histograms",
      "How the error against the truth spreads over the domain's points: mass near zero is "
      "good, mass in the last bin (1.0 m and more) is where a model fails. Click a legend entry "
      "to hide a model.",
      "<div class=\"chart\" id=\"chart-histogram\"></div>\n<p class=\"muted\">The same "
      "counts added up: the share of points within each error (higher is better).</p>\n"
      "<div class=\"chart\" id=\"chart-cumulative\"></div>\n<details><summary>Points per bin"
      "</summary>\n<table class=\"numbers\">\n<thead><tr>" +
          head + "</tr></thead>\n<tbody>\n" + rows + "</tbody>\n</table>\n</details>\n");
}

namespace {

/// What the wall slide did to the pairs (metrics.json pairs.wall_slide), or "" without one.
std::string wall_slide_paragraph(const json& slide) {
  if (!slide.is_object() || !json_at(slide, {"noise_along_m"}).is_number())
    return "";
  const std::string noise =
      fmt::format("their noise between visits is {} along their gridmap walls and {} across",
                  format_metres(json_at(slide, {"noise_along_m"})),
                  format_metres(json_at(slide, {"noise_across_m"})));
  if (!json_at(slide, {"applied"}).is_boolean() || !json_at(slide, {"applied"}).get<bool>())
    return "<p>The pairs were not slid along their walls: " + noise +
           ", not clearly more along (see README, &ldquo;Pairs slid along their "
           "walls&rdquo;).</p>\n";
  std::string p = fmt::format(
      "<p>Before the models were fitted, the {} pairs on a straight gridmap wall were slid along "
      "it, never across, to a smooth fit of all pairs ({}): median {}, 95% under {}.",
      format_count(json_at(slide, {"pairs_on_walls"})), noise,
      format_metres(json_at(slide, {"median_slide_m"})),
      format_metres(json_at(slide, {"p95_slide_m"})));
  if (json_at(slide, {"localized_error_median_m"}).is_number())
    p += fmt::format(" The filters' own pairs had a median error of {} against the truth.",
                     format_metres(json_at(slide, {"localized_error_median_m"})));
  return p +
         " The models' cross-validated error and std_m come from the filters' own pairs "
         "(pairs-localized.csv).</p>\n";
}

}  // namespace

/// How the run's pairs compared with the maps' alignment, when both were there.
std::string agreement_paragraph(const json& a) {
  if (!a.is_object())
    return {};
  const json& drawn = json_at(a, {"run_scale_at_drawn_walls"});
  // scale_tolerance is a difference of scales: shown as a share of the maps' scale.
  const json& maps_scale = json_at(a, {"maps_scale"});
  const json& tolerance = json_at(a, {"scale_tolerance"});
  const json relative =
      tolerance.is_number() && maps_scale.is_number() && maps_scale.get<double>() > 0.0
          ? json(tolerance.get<double>() / maps_scale.get<double>())
          : json(nullptr);
  return fmt::format(
      "<p>The run's pairs against the maps' bent map: <b>{}</b> (median distance {}, 90% under "
      "{}, tolerance {}; plan scale {} from the run{}, {} from the maps, tolerance {}).</p>\n",
      a.value("agree", false) ? "they agree" : "they disagree",
      format_metres(json_at(a, {"median_m"})), format_metres(json_at(a, {"p90_m"})),
      format_metres(json_at(a, {"tolerance_m"})), format_ratio(json_at(a, {"run_scale"})),
      drawn.is_number()
          ? fmt::format(" ({} without the walls' faces, on the drawn walls)", format_ratio(drawn))
          : std::string(),
      format_ratio(maps_scale), format_percent(relative));
}

/// What the bias every pair shares, added to every model's std_m, was measured from.
std::string shared_bias_paragraph(const json& b) {
  const json& from = json_at(b, {"from"});
  const double faces = number_or(json_at(b, {"faces_m"}), 0.0);
  if (!from.is_string() || (from == json("none") && !(faces > 0.0)))
    return {};
  const std::string f = from.get<std::string>();
  std::vector<std::string> parts;
  if (f == "agreement") {
    parts.push_back(format_metres(json_at(b, {"sources_m"})) +
                    " from where the run's pairs and the maps' alignment lie apart (averaged "
                    "over the pairs of each place)");
  } else if (f == "maps") {
    parts.push_back(format_metres(json_at(b, {"sources_m"})) +
                    " from the maps' bent map: its scale spread over the pairs' extent");
  } else if (f == "option") {
    parts.push_back("set by the options (align.models.mapping.uncertainty.shared_std)");
  }
  if (faces > 0.0) {
    parts.push_back(format_metres(json(faces)) +
                    " for the outer walls' faces off the drawn strokes, which neither source "
                    "took out");
  }
  std::string listed;
  for (std::size_t i = 0; i < parts.size(); ++i)
    listed += (i == 0 ? "" : i + 1 == parts.size() ? " and " : ", ") + parts[i];
  return fmt::format(
      "<p>Every model's std_m includes a bias all pairs share, which their cross-validation "
      "cannot see: <b>{}</b>: {}.</p>\n",
      format_metres(json_at(b, {"std_m"})), listed);
}

/// The maps' pairs among the pairs: those that filled where the run did not reach, or all of
/// them under --pairs-from both.
json maps_pairs_added(const ReportContext& c) {
  const json& filled = json_at(c.metrics(), {"sources", "filled_pairs"});
  if (filled.is_number() && json_at(c.metrics(), {"sources", "chosen"}) == json("run")) {
    return filled;
  }
  return json_at(c.metrics(), {"maps_only", "pairs"});
}

std::string pairs_section(const ReportContext& c) {
  const json& pairs = json_at(c.metrics(), {"pairs"});
  const std::string source = pair_source(c);
  std::string body =
      source == "maps"
          ? fmt::format(
                "<p><b>{}</b> pairs from the maps alone: gridmap wall points and the plan "
                "wall surfaces they were bent onto (see <a "
                "href=\"#localization\">Alignment from the maps</a>).",
                format_count(json_at(pairs, {"count"})))
          : fmt::format(
                "<p><b>{}</b> pairs from <b>{}</b> scans, made in {} converged periods{}.",
                format_count(json_at(pairs, {"count"})), format_count(json_at(pairs, {"scans"})),
                format_count(json_at(pairs, {"converged_periods"})),
                source == "both"
                    ? fmt::format(", and {} from the maps alone", format_count(maps_pairs_added(c)))
                    : "");
  const json& fallback = json_at(pairs, {"fallback"});
  if (fallback.is_string()) {
    body += fmt::format(" <b>The run's pairs were not used:</b> {}.",
                        html_escape(fallback.get<std::string>()));
  }
  if (json_at(pairs, {"error_median_m"}).is_number()) {
    body += fmt::format(" Their error against the truth: median {}, mean {}, 95% under {}.",
                        format_metres(json_at(pairs, {"error_median_m"})),
                        format_metres(json_at(pairs, {"error_mean_m"})),
                        format_metres(json_at(pairs, {"error_p95_m"})));
  }
  if (json_at(pairs, {"noise_rms_m"}).is_number()) {
    body += fmt::format(" Their own noise, between visits to one place: {} rms.",
                        format_metres(json_at(pairs, {"noise_rms_m"})));
  }
  body += "</p>\n";
  body += wall_slide_paragraph(json_at(pairs, {"wall_slide"}));
  body += agreement_paragraph(json_at(c.metrics(), {"sources", "agreement"}));
  body += shared_bias_paragraph(json_at(c.metrics(), {"shared_bias"}));
  const json& rejected = json_at(pairs, {"rejected"});
  if (rejected.is_object() && !rejected.empty()) {
    double total = number_or(json_at(pairs, {"count"}), 0.0);
    for (const auto& [reason, count] : rejected.items())
      total += number_or(count, 0.0);
    std::vector<std::pair<std::string, json>> reasons;
    for (const auto& [reason, count] : rejected.items())
      reasons.emplace_back(reason, count);
    std::stable_sort(reasons.begin(), reasons.end(), [](const auto& a, const auto& b) {
      return number_or(a.second, 0.0) > number_or(b.second, 0.0);
    });
    std::string rows;
    for (const auto& [reason, count] : reasons) {
      const double share = total > 0 ? number_or(count, 0.0) / total : 0.0;
      rows += fmt::format(
          "<tr><td>{}</td><td>{}</td><td class=\"bar-cell\"><span class=\"bar\" "
          "style=\"width:{:.1f}%\"></span> {}</td></tr>\n",
          html_escape(reason), format_count(count), 100.0 * share, format_percent(json(share)));
    }
    body +=
        "<table class=\"numbers\">\n<thead><tr><th>endpoints dropped because</th><th>count</th>"
        "<th>share of all endpoints</th></tr></thead>\n<tbody>\n" +
        rows + "</tbody>\n</table>\n";
  }
  if (const ReportImage* image = find_image(c.inputs, "overlays/pairs.png")) {
    body += "<figure>" + image_tag(*image, "the pairs' gridmap endpoints on the gridmap") +
            "<figcaption>The pairs' gridmap endpoints (blue) on the gridmap: walls without blue "
            "were not paired, and the models only guess there.</figcaption></figure>\n";
  }
  return section("pairs", "Reference pairs",
                 "Where the models learnt from: the laser endpoints seen from both filters' poses, "
                 "and why the others were dropped.",
                 body);
}

std::string localization_section(const ReportContext& c) {
  const json& maps = json_at(c.metrics(), {"maps_only"});
  if (pair_source(c) == "maps") {
    return section("localization", "Alignment from the maps",
                   "No robot run: the gridmap was placed on the plan and bent onto its walls, and "
                   "the fitness says whether to trust it.",
                   maps.is_object() ? maps_alignment_body(maps)
                                    : "<p class=\"muted\">No maps_only in metrics.json.</p>\n");
  }
  const json& l = json_at(c.metrics(), {"localization"});
  std::string body = fmt::format(
      "<p>Both filters converged on <b>{}</b> of the scans. The gridmap filter first converged "
      "at scan {}, the plan filter at scan {}; the longest stretch without pairs was {} scans.",
      format_percent(json_at(c.metrics(), {"pairs", "converged_fraction"})),
      html_escape(text_of(json_at(l, {"grid_start_scan"}))),
      html_escape(text_of(json_at(l, {"plan_start_scan"}))),
      html_escape(text_of(json_at(l, {"longest_gap_scans"}))));
  const json& restarts = json_at(l, {"grid_restarts"});
  if (restarts.is_object()) {
    body += fmt::format(
        " Gridmap filter restarts: {} near its last pose, {} global, {} from the plan filter.",
        html_escape(text_of(json_at(restarts, {"near"}))),
        html_escape(text_of(json_at(restarts, {"global"}))),
        html_escape(text_of(json_at(restarts, {"from_plan"}))));
  }
  body += "</p>\n";
  const json& list = json_at(l, {"notes"});
  if (list.is_array() && !list.empty()) {
    body += "<details><summary>What the localization did</summary>\n<ul class=\"notes\">\n";
    for (const json& note : list)
      body += fmt::format("<li>{}</li>\n", html_escape(text_of(note)));
    body += "</ul>\n</details>\n";
  }
  if (c.track.scans > 0) {
    body +=
        "<div class=\"chart\" id=\"chart-localization\"></div>\n"
        "<div class=\"chart\" id=\"chart-scan-pairs\"></div>\n";
    body += fmt::format(
        "<p class=\"muted\">From scans.csv: {} scans{}; the gridmap filter was converged on {}, "
        "the plan filter on {}, and {} made pairs.</p>\n",
        format_count(c.track.scans),
        c.track.bucket > 1
            ? fmt::format(", drawn {} to a point (a bar where at least half of them were)",
                          c.track.bucket)
            : "",
        format_count(c.track.grid_converged), format_count(c.track.plan_converged),
        format_count(c.track.with_pairs));
  } else {
    body += "<p class=\"muted\">No scans.csv in this folder: no scan-by-scan chart.</p>\n";
  }
  if (maps.is_object())
    body += "<h3>Alignment from the maps</h3>\n" + maps_alignment_body(maps);
  return section("localization", "Localization over time",
                 "Scan by scan, whether each filter knew where the robot was: pairs are made only "
                 "where both bars are present.",
                 body);
}

std::string heatmaps_section(const ReportContext& c) {
  std::string figures;
  for (const ReportImage& image : c.inputs.images) {
    if (!image.path.starts_with("heatmaps/"))
      continue;
    const std::string file = image.path.substr(9);
    std::string caption = file;
    if (file.starts_with("heat-") && file.ends_with(".png"))
      caption = "error against the truth, " + file.substr(5, file.size() - 9);
    else if (file.starts_with("std-") && file.ends_with(".png"))
      caption = "predicted std_m, " + file.substr(4, file.size() - 8);
    figures += "<figure class=\"zoomable\">" + image_tag(image, caption) + "<figcaption>" +
               html_escape(caption) + "</figcaption></figure>\n";
  }
  if (figures.empty()) {
    return section("heatmaps", "Heat maps", "Where over the building each model is off.",
                   "<p class=\"muted\">No heat maps in this folder (heatmaps/*.png).</p>\n");
  }
  return section("heatmaps", "Heat maps",
                 "Where over the building each model is off (error against the truth) and how "
                 "sure it says it is (std_m). Click a picture to enlarge it.",
                 "<div class=\"gallery\">\n" + figures + "</div>\n");
}

std::string overlays_section(const ReportContext& c) {
  std::string figures;
  // The chosen model first, then the others best first.
  std::vector<std::string> order;
  if (!c.chosen.empty())
    order.push_back(c.chosen);
  for (const std::string& name : c.models) {
    if (name != c.chosen && name != "auto")
      order.push_back(name);
  }
  for (const std::string& name : order) {
    const ReportImage* image = find_image(c.inputs, "overlays/overlay-" + name + ".png");
    if (!image)
      continue;
    const std::string caption = name + (name == c.chosen ? " (chosen)" : "");
    figures += fmt::format("<figure class=\"zoomable{}\">", name == c.chosen ? " wide" : "") +
               image_tag(*image, "the plan's walls through " + name + " on the gridmap") +
               "<figcaption>" + html_escape(caption) + "</figcaption></figure>\n";
  }
  if (figures.empty()) {
    return section("overlays", "Overlays", "The plan's walls drawn through each model.",
                   "<p class=\"muted\">No overlays in this folder.</p>\n");
  }
  return section("overlays", "Overlays",
                 "The plan's walls through each model (red) and through the truth when known "
                 "(green) on the gridmap (black walls): red on black is a good fit. Click a "
                 "picture to enlarge it.",
                 "<div class=\"gallery\">\n" + figures + "</div>\n");
}

std::string back_and_forth_section(const ReportContext& c) {
  std::string rows;
  for (const std::string& name : c.models) {
    const json& b = json_at(c.metrics(), {"models", name.c_str(), "back_and_forth"});
    if (!b.is_object())
      continue;
    rows += fmt::format(
        "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
        html_escape(name), format_metres(json_at(b, {"min_m"})),
        format_metres(json_at(b, {"mean_m"})), format_metres(json_at(b, {"max_m"})),
        format_count(json_at(b, {"points"})), format_count(json_at(b, {"not_invertible"})));
  }
  return section(
      "back-and-forth", "Back and forth",
      "Each domain point mapped plan to grid and back 100 times: the drift should be far below "
      "a millimetre (the thesis's separate reverse models drifted metres). Not invertible: "
      "points whose grid point has more than one plan point, where the map folds over (or, for "
      "lc, jumps between triangles); the inverse says so instead of returning another point, "
      "and they are not in the drift.",
      "<table class=\"numbers\">\n<thead><tr><th>model</th><th>min drift</th><th>mean</th>"
      "<th>max</th><th>points</th><th>not invertible</th></tr></thead>\n<tbody>\n" +
          rows + "</tbody>\n</table>\n");
}

std::string timings_section(const ReportContext& c) {
  const json& t = json_at(c.metrics(), {"timings_s"});
  if (!t.is_object())
    return section("timings", "Timings", "Wall-clock time of each stage.", "<p>n/a</p>\n");
  double total = 0.0, longest = 0.0;
  for (const auto& [stage, seconds] : t.items()) {
    total += number_or(seconds, 0.0);
    longest = std::max(longest, number_or(seconds, 0.0));
  }
  std::string rows;
  // The stages in the order the job runs them (metrics.json's object is sorted by name).
  std::vector<std::string> stages = {"load",  "global_localization", "scale_search", "localize",
                                     "pairs", "maps_alignment",      "fit",          "evaluate",
                                     "write"};
  for (const auto& [stage, seconds] : t.items()) {
    if (std::find(stages.begin(), stages.end(), stage) == stages.end())
      stages.push_back(stage);
  }
  for (const std::string& stage : stages) {
    const json& seconds = json_at(t, {stage.c_str()});
    if (!seconds.is_number())
      continue;
    rows += fmt::format(
        "<tr><td>{}</td><td>{}</td><td class=\"bar-cell\"><span class=\"bar\" "
        "style=\"width:{:.1f}%\"></span></td></tr>\n",
        html_escape(stage), format_seconds(seconds),
        longest > 0 ? 100.0 * seconds.get<double>() / longest : 0.0);
  }
  rows += fmt::format("<tr class=\"total\"><td>total</td><td>{}</td><td></td></tr>\n",
                      format_seconds(total));
  return section("timings", "Timings",
                 "Wall-clock time of each stage of the job (localize includes the pairs' making; "
                 "fit is every model, cross-validation included).",
                 "<table class=\"numbers\">\n<thead><tr><th>stage</th><th>time</th><th></th></tr>"
                 "</thead>\n<tbody>\n" +
                     rows + "</tbody>\n</table>\n");
}

std::string dataset_section(const ReportContext& c) {
  const json& m = c.metrics();
  std::string rows;
  const auto row = [&](const std::string& what, const std::string& value) {
    rows += fmt::format("<tr><th>{}</th><td>{}</td></tr>\n", what, value);
  };
  row("dataset", html_escape(text_of(json_at(m, {"dataset"}))));
  row("scans in the run", format_count(json_at(m, {"pairs", "scans"})));
  const json& units = json_at(m, {"floorplan_units"});
  if (units.is_object()) {
    row("plan units", fmt::format("{} ({} confidence, from the {}): {}",
                                  html_escape(text_of(json_at(units, {"unit"}))),
                                  html_escape(text_of(json_at(units, {"confidence"}))),
                                  html_escape(text_of(json_at(units, {"source"}))),
                                  html_escape(text_of(json_at(units, {"reason"})))));
  }
  row("plan scale",
      format_ratio(json_at(m, {"plan_scale"})) +
          (json_at(m, {"plan_scale_estimated"}) == json(true)
               ? " &plusmn; " + format_ratio(json_at(m, {"plan_scale_std"})) + " (estimated)"
               : std::string(" (given)")));
  row("evaluation domain",
      fmt::format("{}, {} points", html_escape(text_of(json_at(m, {"domain", "kind"}))),
                  format_count(json_at(m, {"domain", "points"}))));
  const json& start_plan = json_at(m, {"localization", "start_plan"});
  const json& start_grid = json_at(m, {"localization", "start_grid"});
  if (start_plan.is_array() && start_plan.size() == 3 && start_grid.is_array() &&
      start_grid.size() == 3) {
    row("start pose", fmt::format("plan ({}, {}, {:.3f} rad), grid ({}, {}, {:.3f} rad)",
                                  format_metres(start_plan[0]), format_metres(start_plan[1]),
                                  number_or(start_plan[2], NAN), format_metres(start_grid[0]),
                                  format_metres(start_grid[1]), number_or(start_grid[2], NAN)));
  }
  if (!c.inputs.exports.empty()) {
    std::string files;
    for (const std::string& file : c.inputs.exports)
      files += "<code>" + html_escape(file) + "</code> ";
    row("exports/", files);
  }
  return section("dataset", "Dataset", "What was aligned, and the files beside this report.",
                 "<table class=\"facts\">\n" + rows + "</table>\n");
}

json chart_data(const ReportContext& c) {
  json data;
  data["chosen"] = c.chosen;
  json histograms = json::object();
  for (const std::string& name : c.models) {
    const json& h = json_at(c.metrics(), {"models", name.c_str(), "error_histogram"});
    if (name != "auto" && h.is_array())
      histograms[name] = h;
  }
  data["histograms"] = histograms;
  data["models"] = c.models;
  data["scans"] = c.track.chart;
  return data;
}

}  // namespace floorgrid::io
