#include "gl_common.hpp"

#include <cstdio>
#include <stdexcept>
#include <vector>

#include "gl_renderer.hpp"

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

GLuint link_program(const std::string& vertex_source, const std::string& geometry_source,
                    const std::string& fragment_source, const char* name) {
    std::vector<GLuint> shaders;
    try {
        shaders.push_back(compile_shader(GL_VERTEX_SHADER, vertex_source, "vertex shader"));
        if (!geometry_source.empty()) shaders.push_back(compile_shader(GL_GEOMETRY_SHADER, geometry_source, name));
        shaders.push_back(compile_shader(GL_FRAGMENT_SHADER, fragment_source, name));
    } catch (...) {
        for (const GLuint shader : shaders) glDeleteShader(shader);
        throw;
    }
    const GLuint program = glCreateProgram();
    for (const GLuint shader : shaders) glAttachShader(program, shader);
    glLinkProgram(program);
    for (const GLuint shader : shaders) glDeleteShader(shader);  // flagged; freed with the program
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

GLuint link_program(const std::string& vertex_source, const std::string& fragment_source, const char* name) {
    return link_program(vertex_source, std::string(), fragment_source, name);
}

std::vector<float> GlReferenceRenderer::evaluate_glsl(const std::string& expression, const std::vector<float>& inputs) {
    const GLsizei n = GLsizei(inputs.size());
    if (n == 0) return {};
    GLint max_size = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    if (n > max_size) fail("evaluate_glsl: more inputs than GL_MAX_TEXTURE_SIZE");
    // x from a 1-row R32F texture (texelFetch: no filtering), the result into another.
    GLuint textures[2] = {0, 0}, fbo = 0, vao = 0;
    glGenTextures(2, textures);
    glBindTexture(GL_TEXTURE_2D, textures[0]);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, n, 1, 0, GL_RED, GL_FLOAT, inputs.data());
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);  // complete without mipmaps
    glBindTexture(GL_TEXTURE_2D, textures[1]);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, n, 1, 0, GL_RED, GL_FLOAT, nullptr);
    glGenFramebuffers(1, &fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, textures[1], 0);
    const GLuint program = link_program(
        "#version 330 core\nvoid main() {\n    vec2 p[3] = vec2[3](vec2(-1, -1), vec2(3, -1), vec2(-1, 3));\n"
        "    gl_Position = vec4(p[gl_VertexID], 0.0, 1.0);\n}\n",
        "#version 330 core\nout float result;\nuniform sampler2D inputs;\nvoid main() {\n"
        "    float x = texelFetch(inputs, ivec2(gl_FragCoord.xy), 0).r;\n    result = " + expression + ";\n}\n",
        "evaluate_glsl");
    glUseProgram(program);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, textures[0]);
    glUniform1i(glGetUniformLocation(program, "inputs"), 0);
    glGenVertexArrays(1, &vao);
    glBindVertexArray(vao);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glViewport(0, 0, n, 1);
    glDrawArrays(GL_TRIANGLES, 0, 3);
    std::vector<float> out(inputs.size());
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, n, 1, GL_RED, GL_FLOAT, out.data());
    glBindVertexArray(0);
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(program);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteTextures(2, textures);
    check_gl("evaluate_glsl");
    return out;
}

}  // namespace tessera::gl_reference
