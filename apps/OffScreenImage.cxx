#include "OffScreenImage.h"

#include "vtkNew.h"
#include "vtkRenderWindow.h"
#include "vtkWindowToImageFilter.h"

namespace shadelab::app
{
vtkSmartPointer<vtkImageData> renderOffScreen(vtkRenderer* renderer, int width, int height)
{
  vtkNew<vtkRenderWindow> window;
  window->SetOffScreenRendering(1);
  window->SetMultiSamples(0);
  window->SetSize(width, height);
  window->AddRenderer(renderer);
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
