#include "ui/gl/gl_util.hpp"

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>

namespace sonarsim::ui::gl {
namespace {

GLuint compile(GLenum type, const char* src) {
    const GLuint s = glCreateShader(type);
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetShaderInfoLog(s, sizeof log, nullptr, log);
        glDeleteShader(s);
        throw std::runtime_error(std::string("OpenGL shader does not compile: ") + log);
    }
    return s;
}

} // namespace

GLuint compile_program(const char* vs, const char* fs) {
    const GLuint v = compile(GL_VERTEX_SHADER, vs), f = compile(GL_FRAGMENT_SHADER, fs);
    const GLuint p = glCreateProgram();
    glAttachShader(p, v);
    glAttachShader(p, f);
    glLinkProgram(p);
    glDeleteShader(v);
    glDeleteShader(f);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[2048] = {};
        glGetProgramInfoLog(p, sizeof log, nullptr, log);
        glDeleteProgram(p);
        throw std::runtime_error(std::string("OpenGL program does not link: ") + log);
    }
    return p;
}

VertexBuffer::VertexBuffer() {
    glGenVertexArrays(1, &vao_);
    glGenBuffers(1, &vbo_);
    glBindVertexArray(vao_);
    glBindBuffer(GL_ARRAY_BUFFER, vbo_);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                          reinterpret_cast<void*>(offsetof(Vertex, position)));
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                          reinterpret_cast<void*>(offsetof(Vertex, normal)));
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, sizeof(Vertex),
                          reinterpret_cast<void*>(offsetof(Vertex, color)));
    glBindVertexArray(0);
}

VertexBuffer::~VertexBuffer() {
    glDeleteBuffers(1, &vbo_);
    glDeleteVertexArrays(1, &vao_);
}

void VertexBuffer::upload(const std::vector<Vertex>& v) {
    glBindBuffer(GL_ARRAY_BUFFER, vbo_);
    const size_t bytes = v.size() * sizeof(Vertex);
    if (bytes > capacity_) {
        glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(bytes), v.data(), GL_DYNAMIC_DRAW);
        capacity_ = bytes;
    } else if (bytes > 0) {
        glBufferSubData(GL_ARRAY_BUFFER, 0, GLsizeiptr(bytes), v.data());
    }
    count_ = GLsizei(v.size());
}

void VertexBuffer::draw(GLenum mode) const {
    if (count_ == 0) return;
    glBindVertexArray(vao_);
    glDrawArrays(mode, 0, count_);
    glBindVertexArray(0);
}

void VertexBuffer::draw_range(GLenum mode, GLint first, GLsizei count) const {
    if (count <= 0 || first + count > count_) return;
    glBindVertexArray(vao_);
    glDrawArrays(mode, first, count);
    glBindVertexArray(0);
}

Framebuffer::Framebuffer(int w, int h) : w_(w), h_(h) {
    glGenFramebuffers(1, &fbo_);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
    glGenRenderbuffers(1, &color_);
    glBindRenderbuffer(GL_RENDERBUFFER, color_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, color_);
    glGenRenderbuffers(1, &depth_);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        throw std::runtime_error("OpenGL framebuffer incomplete (status " + std::to_string(status) + ")");
    }
}

Framebuffer::~Framebuffer() {
    glDeleteRenderbuffers(1, &depth_);
    glDeleteRenderbuffers(1, &color_);
    glDeleteFramebuffers(1, &fbo_);
}

void Framebuffer::bind() const {
    glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
}

Texture::Texture() {
    glGenTextures(1, &tex_);
    glBindTexture(GL_TEXTURE_2D, tex_);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

Texture::~Texture() {
    glDeleteTextures(1, &tex_);
}

void Texture::upload(const Image8& img) {
    glBindTexture(GL_TEXTURE_2D, tex_);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    const GLenum fmt = img.channels == 1 ? GL_RED : img.channels == 4 ? GL_RGBA : GL_RGB;
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, img.width, img.height, 0, fmt, GL_UNSIGNED_BYTE,
                 img.pixels.data());
    if (img.channels == 1) {
        const GLint swizzle[4] = {GL_RED, GL_RED, GL_RED, GL_ONE};
        glTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_RGBA, swizzle);
    } else {
        const GLint swizzle[4] = {GL_RED, GL_GREEN, GL_BLUE, img.channels == 4 ? GL_ALPHA : GL_ONE};
        glTexParameteriv(GL_TEXTURE_2D, GL_TEXTURE_SWIZZLE_RGBA, swizzle);
    }
    w_ = img.width, h_ = img.height;
}

Image8 read_pixels_rgb(int x, int y, int w, int h) {
    Image8 img;
    img.width = w, img.height = h, img.channels = 3;
    std::vector<std::uint8_t> raw(size_t(w) * h * 3);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(x, y, w, h, GL_RGB, GL_UNSIGNED_BYTE, raw.data());
    img.pixels.resize(raw.size());
    const size_t row = size_t(w) * 3;
    for (int r = 0; r < h; ++r)
        std::copy_n(raw.begin() + long(size_t(h - 1 - r) * row), row,
                    img.pixels.begin() + long(size_t(r) * row));
    return img;
}

} // namespace sonarsim::ui::gl
