#include "gl_common.hpp"

#include <cstdio>
#include <stdexcept>

namespace tessera::gl_reference {

void fail(const std::string& what) { throw std::runtime_error("OpenGL reference: " + what); }

namespace {

GLuint compile_shader(GLenum type, const std::string& source, const char* name) {
    const GLuint shader = glCreateShader(type);
    const char* text = source.c_str();
    glShaderSource(shader, 1, &text, nullptr);
    glCompileShader(shader);
    GLint ok = GL_FALSE, log_length = 0;
    glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &log_length);
    std::string log(std::size_t(log_length > 0 ? log_length : 0), '\0');
    if (log_length > 0) glGetShaderInfoLog(shader, log_length, nullptr, log.data());
    if (!ok) {
        glDeleteShader(shader);
        fail(std::string(name) + " failed to compile:\n" + log.c_str());
    }
    return shader;
}

}  // namespace

void check_gl(const char* where) {
    const GLenum err = glGetError();
    if (err != GL_NO_ERROR) {
        char buf[16];
        std::snprintf(buf, sizeof buf, "0x%04x", unsigned(err));
        fail(std::string(where) + ": GL error " + buf);
    }
}

GLuint link_program(const std::string& vertex_source, const std::string& fragment_source, const char* name) {
    const GLuint vs = compile_shader(GL_VERTEX_SHADER, vertex_source, "vertex shader");
    GLuint fs = 0;
    try {
        fs = compile_shader(GL_FRAGMENT_SHADER, fragment_source, name);
    } catch (...) {
        glDeleteShader(vs);
        throw;
    }
    const GLuint program = glCreateProgram();
    glAttachShader(program, vs);
    glAttachShader(program, fs);
    glLinkProgram(program);
    glDeleteShader(vs);  // flagged; freed with the program
    glDeleteShader(fs);
    GLint ok = GL_FALSE, log_length = 0;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &log_length);
    if (!ok) {
        std::string log(std::size_t(log_length > 0 ? log_length : 0), '\0');
        if (log_length > 0) glGetProgramInfoLog(program, log_length, nullptr, log.data());
        glDeleteProgram(program);
        fail(std::string(name) + " program failed to link:\n" + log.c_str());
    }
    return program;
}

}  // namespace tessera::gl_reference
