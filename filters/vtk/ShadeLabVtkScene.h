#ifndef ShadeLabVtkScene_h
#define ShadeLabVtkScene_h
// A scene built from VTK's own rendering objects, for the VtkOpenGL2 model (or VtkPbr for a
// property with PBR interpolation): what VTK 9.1's OpenGL2 renderer would compute for these
// lights, this property and this camera.
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
/// keeps d = 0 finite. A property with PBR interpolation gives the vtk_pbr model; with a
/// positional light among the lights, its directional ones become unattenuated point lights at
/// their positions (a headlight at the camera, as also when it is the lone light), as VTK's PBR
/// shader treats them. A coat, anisotropy or textures throw std::invalid_argument. The
/// property's material is the scene's (Scene::materialGiven): a mesh's own materials (a glTF
/// file's parts) do not replace it.
///
/// Assumed, as VTK's defaults: the renderer's LightFollowCamera and AutomaticLightCreation
/// are on, no UserLightTransform, no image-based lighting, and the actor is a lit surface with
/// no scalar colouring, no textures and no backface property.
SHADELABFILTERS_EXPORT Scene sceneFromVtk(vtkLightCollection* lights, vtkProperty* property, vtkCamera* camera);
}

#endif
