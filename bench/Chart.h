#pragma once
// Scatter and line charts drawn with VTK's own charts (vtkChartXY), off screen to PNG.
#include <array>
#include <string>
#include <vector>

namespace shadelab::app
{
struct ChartSeries
{
  std::string name; // in the legend
  std::vector<double> x, y;
  bool line = false; // points joined by lines, or points alone
  std::array<unsigned char, 3> color{ 0, 0, 0 };
  bool markers = false; // with line: a marker at each point too
  bool dashed = false;  // with line
  bool wide = false;    // a wide band, to mark the points of the series drawn over it
};

struct ChartSpec
{
  std::string title, xTitle, yTitle;
  bool logX = false, logY = false;
  bool legendOutside = false;      // beside the plot, for series that fill every corner of it
  std::vector<ChartSeries> series; // drawn in this order
};

/// The Pareto front of the points (cost, error), those that no other point beats in both,
/// as a black line in order of cost, for a log error axis: points with error 0 are left out.
ChartSeries paretoFront(const std::vector<double>& cost, const std::vector<double>& error);

/// Draws the chart to a PNG, writing through a temporary file. Needs an X display (run under
/// xvfb-run on a headless machine). Throws UserError.
void writeChartPng(const ChartSpec& chart, const std::string& pngFile);
}
