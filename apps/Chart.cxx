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
#include "vtkPlot.h"
#include "vtkRenderer.h"
#include "vtkTable.h"
#include "vtkTextProperty.h"

#include <algorithm>
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
  chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);
  for (const auto& [axis, title, log] : { std::tuple{ vtkAxis::BOTTOM, spec.xTitle, spec.logX },
         std::tuple{ vtkAxis::LEFT, spec.yTitle, spec.logY } })
  {
    chart->GetAxis(axis)->SetTitle(title);
    chart->GetAxis(axis)->SetLogScale(log);
  }
  std::vector<vtkSmartPointer<vtkTable>> tables;
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
      }
    }
    table->AddColumn(x);
    table->AddColumn(y);
    tables.push_back(table);
    vtkPlot* plot = chart->AddPlot(series.line ? vtkChart::LINE : vtkChart::POINTS);
    plot->SetInputData(table, 0, 1);
    plot->SetColor(series.color[0], series.color[1], series.color[2], 255);
    plot->SetWidth(series.line ? 2.0f : 6.0f);
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
