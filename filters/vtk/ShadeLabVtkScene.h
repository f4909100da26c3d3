#ifndef ShadeLabVtkScene_h
#define ShadeLabVtkScene_h
// A scene built from VTK's own rendering objects, for the VtkOpenGL2 model: what VTK 9.1's
// OpenGL2 renderer would compute for these lights, this property and this camera.
#include "ShadeLabFiltersModule.h"

#include "Scene.h"

class vtkCamera;
class vtkLightCollection;
class vtkProperty;

namespace shadelab
{
/// Lights that are switched off are left out; with none switched on, VTK's renderer creates
/// a white headlight, and so does this (as on the render that creates it). Light i of the
/// collection is named "light<i>". Positional lights get minDistance 0 (VTK's exact
/// attenuation) unless their constant attenuation coefficient is 0, where the 0.01 default
/// keeps d = 0 finite.
///
/// Assumed, as VTK's defaults: the renderer's LightFollowCamera and AutomaticLightCreation
/// are on, no UserLightTransform, and the actor is a lit surface with Gouraud or Phong
/// interpolation, no scalar colouring, no backface property and no PBR.
SHADELABFILTERS_EXPORT Scene sceneFromVtk(vtkLightCollection* lights, vtkProperty* property, vtkCamera* camera);
}

#endif
