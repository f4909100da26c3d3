#include "Chart.h"

#include "MeshFiles.h"
#include "OffScreenImage.h"

#include "vtkAxis.h"
#include "vtkChartLegend.h"
#include "vtkChartXY.h"
#include "vtkContextActor.h"
#include "vtkContextScene.h"
#include "vtkDoubleArray.h"
#include "vtkPNGWriter.h"
#include "vtkPen.h"
#include "vtkPlot.h"
#include "vtkPlotPoints.h"
#include "vtkRenderer.h"
#include "vtkTable.h"
#include "vtkTextProperty.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace shadelab::app
{
ChartSeries paretoFront(const std::vector<double>& cost, const std::vector<double>& error)
{
  std::vector<std::size_t> order(cost.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
    [&](std::size_t a, std::size_t b) { return cost[a] < cost[b] || (cost[a] == cost[b] && error[a] < error[b]); });
  ChartSeries front{ "Pareto front", {}, {}, true, { 0, 0, 0 } };
  for (const std::size_t i : order)
  {
    // An error of 0 (an exact method at a point where it has no rounding, such as x^1) has no
    // place on a log axis: a front through it would not be drawn at all.
    if (error[i] == 0)
    {
      continue;
    }
    if (front.y.empty() || error[i] < front.y.back())
    {
      front.x.push_back(cost[i]);
      front.y.push_back(error[i]);
    }
  }
  return front;
}

void writeChartPng(const ChartSpec& spec, const std::string& pngFile)
{
  vtkNew<vtkChartXY> chart;
  chart->SetTitle(spec.title);
  chart->GetTitleProperties()->SetFontSize(16);
  chart->SetShowLegend(true);
  chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);
  chart->GetLegend()->SetVerticalAlignment(spec.legendOutside ? vtkChartLegend::CENTER : vtkChartLegend::TOP);
  chart->GetLegend()->SetInline(!spec.legendOutside);
  std::vector<vtkSmartPointer<vtkTable>> tables;
  std::array<double, 2> xRange{ HUGE_VAL, -HUGE_VAL }, yRange{ HUGE_VAL, -HUGE_VAL }; // of the points drawn
  for (const ChartSeries& series : spec.series)
  {
    auto table = vtkSmartPointer<vtkTable>::New();
    vtkNew<vtkDoubleArray> x;
    x->SetName("x");
    vtkNew<vtkDoubleArray> y;
    y->SetName(series.name.c_str());
    for (std::size_t i = 0; i < series.x.size(); ++i)
    {
      // A log axis cannot show 0 or less: such points are left out of the picture (the CSV has them).
      if ((!spec.logX || series.x[i] > 0) && (!spec.logY || series.y[i] > 0))
      {
        x->InsertNextValue(series.x[i]);
        y->InsertNextValue(series.y[i]);
        xRange = { std::min(xRange[0], series.x[i]), std::max(xRange[1], series.x[i]) };
        yRange = { std::min(yRange[0], series.y[i]), std::max(yRange[1], series.y[i]) };
      }
    }
    table->AddColumn(x);
    table->AddColumn(y);
    tables.push_back(table);
    vtkPlot* plot = chart->AddPlot(series.line ? vtkChart::LINE : vtkChart::POINTS);
    plot->SetInputData(table, 0, 1);
    plot->SetColor(series.color[0], series.color[1], series.color[2], 255);
    plot->SetWidth(series.wide ? 10.0f : series.line ? 2.0f : 6.0f);
    if (series.dashed)
    {
      plot->GetPen()->SetLineType(vtkPen::DASH_LINE);
    }
    if (series.markers)
    {
      vtkPlotPoints::SafeDownCast(plot)->SetMarkerStyle(vtkPlotPoints::CIRCLE);
    }
  }
  // VTK can fit a log axis to the data exactly, cutting the markers at its ends in half.
  const bool markers = std::any_of(
    spec.series.begin(), spec.series.end(), [](const ChartSeries& series) { return !series.line || series.markers; });
  for (const auto& [axis, title, log, range] : { std::tuple{ vtkAxis::BOTTOM, spec.xTitle, spec.logX, xRange },
         std::tuple{ vtkAxis::LEFT, spec.yTitle, spec.logY, yRange } })
  {
    chart->GetAxis(axis)->SetTitle(title);
    chart->GetAxis(axis)->SetLogScale(log);
    if (log && markers && range[0] <= range[1])
    {
      chart->GetAxis(axis)->SetUnscaledRange(range[0] / 1.3, range[1] * 1.3);
      chart->GetAxis(axis)->SetBehavior(vtkAxis::FIXED);
    }
  }
  vtkNew<vtkContextActor> actor;
  actor->GetScene()->AddItem(chart);
  vtkNew<vtkRenderer> renderer;
  renderer->SetBackground(1, 1, 1);
  renderer->AddActor(actor);
  vtkSmartPointer<vtkImageData> image = renderOffScreen(renderer, 1000, 640);
  writeThroughTemporary(pngFile,
    [&](const std::string& temporary) -> std::string
    {
      vtkNew<vtkPNGWriter> writer;
      writer->SetFileName(temporary.c_str());
      writer->SetInputData(image);
      writer->Write();
      return writer->GetErrorCode() ? "the PNG could not be written" : "";
    });
}
}
