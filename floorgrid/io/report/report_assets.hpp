#pragma once

#include <string_view>

namespace floorgrid::io {

// report.html's scripts and style sheets, embedded at build time
// (cmake/embed_report_assets.cmake): the chart library uPlot (MIT, (c) Leon Sorokin) from the
// npm package pinned by report/package-lock.json, and the page's own report/page.{js,css}.

/// uPlot's minified script (`dist/uPlot.iife.min.js`): defines the global `uPlot`.
std::string_view uplot_js();
/// uPlot's minified style sheet (`dist/uPlot.min.css`).
std::string_view uplot_css();
/// The page's script (report/page.js): draws the charts from the page's embedded data.
std::string_view report_page_js();
/// The page's style sheet (report/page.css).
std::string_view report_page_css();

}  // namespace floorgrid::io
