#pragma once
// Checks of a mesh file's own claims before any reader trusts them: what a PLY header
// declares against the bytes the file has, an OBJ's face indices against the vertices it
// lists. A lie there is what crashes or stalls VTK's readers, or makes them read out of
// bounds without a sign; found here, it gets a message that says what is wrong.
#include <cstdint>
#include <string>

namespace shadelab::app
{
/// What is wrong with the file, or "" when nothing was found (a file that passes may still be
/// refused by its reader). extension is lower case, with its dot; fileSize in bytes.
std::string fileProblem(const std::string& fileName, const std::string& extension, std::uintmax_t fileSize);

/// The same for a PLY file's header; header is the file's text from its start.
std::string plyHeaderProblem(const std::string& text, std::uintmax_t fileSize);

/// The same for an OBJ file's text: every face index refers to a vertex, texture coordinate
/// or normal listed before it.
std::string objIndexProblem(const std::string& text);
}
