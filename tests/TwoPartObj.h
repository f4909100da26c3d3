#pragma once
// An OBJ file of two parts and its MTL file, for the tests of meshes with their own materials.
#include <string>

namespace shadelab::testing
{
/// Two flat parts in the plane z = 0, normals +z: "red" a unit square at x in [-2, -1], and
/// "tex" a grid of 4 x 2 vertices, one at each texel's centre of the 4 x 2 texture, at x >= 0.
inline const char* const twoPartObj = R"(mtllib parts.mtl
v -2 0 0
v -1 0 0
v -1 1 0
v -2 1 0
v 0 0 0
v 1 0 0
v 2 0 0
v 3 0 0
v 0 1 0
v 1 1 0
v 2 1 0
v 3 1 0
vt 0.125 0.25
vt 0.375 0.25
vt 0.625 0.25
vt 0.875 0.25
vt 0.125 0.75
vt 0.375 0.75
vt 0.625 0.75
vt 0.875 0.75
vn 0 0 1
usemtl red
f 1/1/1 2/2/1 3/6/1
f 1/1/1 3/6/1 4/5/1
usemtl tex
f 5/1/1 6/2/1 10/6/1
f 5/1/1 10/6/1 9/5/1
f 6/2/1 7/3/1 11/7/1
f 6/2/1 11/7/1 10/6/1
f 7/3/1 8/4/1 12/8/1
f 7/3/1 12/8/1 11/7/1
)";

inline const char* const partsMtl = R"(newmtl red
Ka 0.1 0 0
Kd 0.7 0.2 0.1
Ks 0.5 0.5 0.5
Ns 20
newmtl tex
Ka 0 0.1 0
Kd 0.9 0.8 0.6
Ks 0.2 0.2 0.2
Ns 64
map_Kd texture.png
)";

}
