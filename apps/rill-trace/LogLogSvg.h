// Log-log line plots as SVG, written by hand (no gnuplot or matplotlib needed): panels side by
// side, each with decade ticks and a grid, its series as lines with markers, dashed guide lines
// and a legend beside it. For `rill-trace noise` (NoiseBench.h); the look follows gnuplot's
// SVG terminal of the other plots in docs/ (white, sans 11, grey grid).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace trace_cli {

struct SvgSeries {
  std::string label;  // in the legend; empty: not listed
  std::string color = "#000000";
  std::string dash;  // SVG stroke-dasharray; empty: solid
  int marker = 0;    // 0 circle, 1 square, 2 triangle, 3 diamond, -1 none
  bool hollow = false;
  std::vector<std::pair<double, double>> points;  // (x, y), both > 0; none: a legend entry only
};

struct SvgPanel {
  std::string title, xlabel, ylabel;
  std::vector<SvgSeries> series;
  std::vector<std::pair<double, std::string>> hlines;  // a dotted line at y, labelled
};

// The panels side by side under `title`; each panel is 630 x 460 units.
std::string loglog_svg(const std::string& title, const std::vector<SvgPanel>& panels);

}  // namespace trace_cli
