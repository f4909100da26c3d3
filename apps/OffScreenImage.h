#pragma once
// Renders a renderer's scene off screen and reads back the pixels, as drawn (no
// anti-aliasing, so every pixel is one fragment's colour).
#include "vtkImageData.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"

#include <initializer_list>

namespace shadelab::app
{
/// RGB, 8 bits per channel, origin at the lower left. Needs an X display (Xvfb will do).
vtkSmartPointer<vtkImageData> renderOffScreen(vtkRenderer* renderer, int width, int height);
/// The same for renderers that share the window, each in its own viewport.
vtkSmartPointer<vtkImageData> renderOffScreen(std::initializer_list<vtkRenderer*> renderers, int width, int height);

/// Throws UserError (MeshFiles.h) when there is no X display to render with: without one,
/// VTK 9.1's X window aborts the process.
void requireDisplay();
}
