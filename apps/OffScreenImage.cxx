#include "OffScreenImage.h"

#include "MeshFiles.h"

#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkWindowToImageFilter.h"

#include <cstdlib>

namespace shadelab::app
{
void requireDisplay()
{
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
  {
    throw UserError("no X display to render with: run the command under xvfb-run -a (package xvfb)");
  }
}

vtkSmartPointer<vtkImageData> renderOffScreen(vtkRenderer* renderer, int width, int height)
{
  return renderOffScreen({ renderer }, width, height);
}

vtkSmartPointer<vtkImageData> renderOffScreen(std::initializer_list<vtkRenderer*> renderers, int width, int height)
{
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(width, height);
  for (vtkRenderer* renderer : renderers)
  {
    window->AddRenderer(renderer);
  }
  window->Render();
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(grab->GetOutput());
  return image;
}
}
