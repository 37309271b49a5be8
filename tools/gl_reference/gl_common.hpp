// What the peer renderer's parts share: GL errors as exceptions, shader building.
// Internal to tools/gl_reference.
#pragma once

#include <string>

#define GL_GLEXT_PROTOTYPES 1  // glvnd's libOpenGL exports every core entry point: no loader needed
#include <GL/glcorearb.h>

namespace tessera::gl_reference {

// Throws std::runtime_error("OpenGL reference: " + what).
[[noreturn]] void fail(const std::string& what);
// Throws, naming `where`, if glGetError reports an error.
void check_gl(const char* where);
// Compiles and links; a compile or link failure throws with the driver's log.
GLuint link_program(const std::string& vertex_source, const std::string& fragment_source, const char* name);
// The same with a geometry shader between them.
GLuint link_program(const std::string& vertex_source, const std::string& geometry_source,
                    const std::string& fragment_source, const char* name);

}  // namespace tessera::gl_reference
