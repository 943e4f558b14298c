// Log-log SVG plots (LogLogSvg.h).
#include "LogLogSvg.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace trace_cli {

namespace {

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

std::string escape(const std::string& s) {
  std::string r;
  for (char c : s) {
    if (c == '<')
      r += "&lt;";
    else if (c == '>')
      r += "&gt;";
    else if (c == '&')
      r += "&amp;";
    else
      r += c;
  }
  return r;
}

// "1", "10", "0.01", "1e+06": a decade's label.
std::string decade_label(int e) {
  if (e >= -3 && e <= 5) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.*f", e < 0 ? -e : 0, std::pow(10.0, e));
    return buf;
  }
  return "1e" + std::to_string(e);
}

std::string marker(int kind, double x, double y, const std::string& color, bool hollow) {
  const std::string fill = hollow ? "fill=\"#ffffff\"" : "fill=\"" + color + "\"";
  const std::string stroke = " stroke=\"" + color + "\" stroke-width=\"1.2\"";
  const double r = 3.2;
  switch (kind) {
    case 0:
      return "<circle cx=\"" + num(x) + "\" cy=\"" + num(y) + "\" r=\"" + num(r) + "\" " + fill +
             stroke + "/>";
    case 1:
      return "<rect x=\"" + num(x - r) + "\" y=\"" + num(y - r) + "\" width=\"" + num(2 * r) +
             "\" height=\"" + num(2 * r) + "\" " + fill + stroke + "/>";
    case 2:
      return "<path d=\"M" + num(x) + "," + num(y - 1.3 * r) + " L" + num(x - 1.2 * r) + "," +
             num(y + 0.8 * r) + " L" + num(x + 1.2 * r) + "," + num(y + 0.8 * r) + " z\" " + fill +
             stroke + "/>";
    case 3:
      return "<path d=\"M" + num(x) + "," + num(y - 1.3 * r) + " L" + num(x + 1.3 * r) + "," +
             num(y) + " L" + num(x) + "," + num(y + 1.3 * r) + " L" + num(x - 1.3 * r) + "," +
             num(y) + " z\" " + fill + stroke + "/>";
    default:
      return "";
  }
}

}  // namespace

std::string loglog_svg(const std::string& title, const std::vector<SvgPanel>& panels) {
  const double pw = 630, ph = 460;  // a panel
  const double top = 30;            // the title above the panels
  const double left = 70, plot_w = 360, plot_top = 30, plot_h = 370;
  std::ostringstream s;
  const double width = pw * static_cast<double>(panels.size()), height = top + ph;
  s << "<?xml version=\"1.0\" encoding=\"utf-8\" standalone=\"no\"?>\n"
    << "<svg viewBox=\"0 0 " << num(width) << " " << num(height)
    << "\" xmlns=\"http://www.w3.org/2000/svg\" font-family=\"sans\" font-size=\"11\">\n"
    << "<title>" << escape(title) << "</title>\n"
    << "<rect x=\"0\" y=\"0\" width=\"" << num(width) << "\" height=\"" << num(height)
    << "\" fill=\"#ffffff\"/>\n"
    << "<text x=\"" << num(width / 2) << "\" y=\"20\" text-anchor=\"middle\" font-size=\"13\">"
    << escape(title) << "</text>\n";
  for (size_t pi = 0; pi < panels.size(); ++pi) {
    const SvgPanel& p = panels[pi];
    const double ox = pw * static_cast<double>(pi) + left, oy = top + plot_top;
    // The data's range, widened to whole decades.
    double x0 = std::numeric_limits<double>::infinity(), x1 = 0, y0 = x0, y1 = 0;
    for (const SvgSeries& se : p.series)
      for (auto [x, y] : se.points)
        if (x > 0 && y > 0) {
          x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
        }
    for (const auto& h : p.hlines) y0 = std::min(y0, h.first), y1 = std::max(y1, h.first);
    if (!(x1 > 0) || !(y1 > 0)) continue;
    const int ex0 = static_cast<int>(std::floor(std::log10(x0))),
              ex1 = std::max(ex0 + 1, static_cast<int>(std::ceil(std::log10(x1))));
    const int ey0 = static_cast<int>(std::floor(std::log10(y0))),
              ey1 = std::max(ey0 + 1, static_cast<int>(std::ceil(std::log10(y1))));
    auto X = [&](double x) { return ox + plot_w * (std::log10(x) - ex0) / (ex1 - ex0); };
    auto Y = [&](double y) { return oy + plot_h * (1.0 - (std::log10(y) - ey0) / (ey1 - ey0)); };
    s << "<g>\n<text x=\"" << num(ox + plot_w / 2) << "\" y=\"" << num(oy - 10)
      << "\" text-anchor=\"middle\">" << escape(p.title) << "</text>\n";
    // Grid: decades solid grey, 2..9 light.
    for (int e = ex0; e <= ex1; ++e)
      for (int m = 1; m <= (e < ex1 ? 9 : 1); ++m) {
        const double x = X(m * std::pow(10.0, e));
        s << "<line x1=\"" << num(x) << "\" y1=\"" << num(oy) << "\" x2=\"" << num(x) << "\" y2=\""
          << num(oy + plot_h) << "\" stroke=\"" << (m == 1 ? "#b0b0b0" : "#e4e4e4")
          << "\" stroke-width=\"0.5\"/>\n";
        if (m == 1)
          s << "<text x=\"" << num(x) << "\" y=\"" << num(oy + plot_h + 15)
            << "\" text-anchor=\"middle\">" << decade_label(e) << "</text>\n";
      }
    for (int e = ey0; e <= ey1; ++e)
      for (int m = 1; m <= (e < ey1 ? 9 : 1); ++m) {
        const double y = Y(m * std::pow(10.0, e));
        s << "<line x1=\"" << num(ox) << "\" y1=\"" << num(y) << "\" x2=\"" << num(ox + plot_w)
          << "\" y2=\"" << num(y) << "\" stroke=\"" << (m == 1 ? "#b0b0b0" : "#e4e4e4")
          << "\" stroke-width=\"0.5\"/>\n";
        if (m == 1)
          s << "<text x=\"" << num(ox - 6) << "\" y=\"" << num(y + 4) << "\" text-anchor=\"end\">"
            << decade_label(e) << "</text>\n";
      }
    s << "<rect x=\"" << num(ox) << "\" y=\"" << num(oy) << "\" width=\"" << num(plot_w)
      << "\" height=\"" << num(plot_h) << "\" fill=\"none\" stroke=\"#000000\"/>\n"
      << "<text x=\"" << num(ox + plot_w / 2) << "\" y=\"" << num(oy + plot_h + 34)
      << "\" text-anchor=\"middle\">" << escape(p.xlabel) << "</text>\n"
      << "<text transform=\"translate(" << num(ox - 48) << "," << num(oy + plot_h / 2)
      << ") rotate(-90)\" text-anchor=\"middle\">" << escape(p.ylabel) << "</text>\n";
    for (const auto& [y, label] : p.hlines) {
      s << "<line x1=\"" << num(ox) << "\" y1=\"" << num(Y(y)) << "\" x2=\"" << num(ox + plot_w)
        << "\" y2=\"" << num(Y(y)) << "\" stroke=\"#606060\" stroke-dasharray=\"2,3\"/>\n"
        << "<text x=\"" << num(ox + plot_w - 4) << "\" y=\"" << num(Y(y) - 4)
        << "\" text-anchor=\"end\" fill=\"#606060\">" << escape(label) << "</text>\n";
    }
    // The series, clipped to the plot.
    s << "<clipPath id=\"clip" << pi << "\"><rect x=\"" << num(ox) << "\" y=\"" << num(oy)
      << "\" width=\"" << num(plot_w) << "\" height=\"" << num(plot_h) << "\"/></clipPath>\n"
      << "<g clip-path=\"url(#clip" << pi << ")\">\n";
    for (const SvgSeries& se : p.series) {
      if (se.points.empty()) continue;
      s << "<polyline fill=\"none\" stroke=\"" << se.color << "\" stroke-width=\"1.3\""
        << (se.dash.empty() ? "" : " stroke-dasharray=\"" + se.dash + "\"") << " points=\"";
      for (auto [x, y] : se.points) s << num(X(x)) << "," << num(Y(y)) << " ";
      s << "\"/>\n";
      for (auto [x, y] : se.points) s << marker(se.marker, X(x), Y(y), se.color, se.hollow) << "\n";
    }
    s << "</g>\n";
    // The legend, right of the plot.
    double ly = oy + 8;
    const double lx = ox + plot_w + 14;
    for (const SvgSeries& se : p.series) {
      if (se.label.empty()) continue;
      s << "<line x1=\"" << num(lx) << "\" y1=\"" << num(ly) << "\" x2=\"" << num(lx + 28)
        << "\" y2=\"" << num(ly) << "\" stroke=\"" << se.color << "\" stroke-width=\"1.3\""
        << (se.dash.empty() ? "" : " stroke-dasharray=\"" + se.dash + "\"") << "/>\n"
        << marker(se.marker, lx + 14, ly, se.color, se.hollow) << "\n"
        << "<text x=\"" << num(lx + 34) << "\" y=\"" << num(ly + 4) << "\">" << escape(se.label)
        << "</text>\n";
      ly += 16;
    }
    s << "</g>\n";
  }
  s << "</svg>\n";
  return s.str();
}

}  // namespace trace_cli
