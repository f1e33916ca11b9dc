// Small OpenGL 3.3 core helpers (through epoxy): shader programs, vertex buffers, an offscreen framebuffer,
// RGB textures and read-back. Every function needs a current GL context.
#pragma once
#include <epoxy/gl.h>

#include "core/display/image.hpp"

#include <glm/glm.hpp>
#include <vector>

namespace sonarsim::ui::gl {

/// Compiles and links a vertex + fragment shader; throws std::runtime_error with the driver's log.
GLuint compile_program(const char* vertex_src, const char* fragment_src);

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal; ///< zero: unlit
    glm::vec4 color;
};

/// A vertex array with one interleaved buffer (attributes 0 position, 1 normal, 2 colour).
class VertexBuffer {
  public:
    VertexBuffer();
    ~VertexBuffer();
    VertexBuffer(const VertexBuffer&) = delete;
    VertexBuffer& operator=(const VertexBuffer&) = delete;
    void upload(const std::vector<Vertex>& vertices);
    void draw(GLenum mode) const;
    void draw_range(GLenum mode, GLint first, GLsizei count) const;
    bool empty() const { return count_ == 0; }

  private:
    GLuint vao_ = 0, vbo_ = 0;
    GLsizei count_ = 0;
    size_t capacity_ = 0;
};

/// RGBA8 colour + 24-bit depth offscreen target.
class Framebuffer {
  public:
    Framebuffer(int width, int height);
    ~Framebuffer();
    Framebuffer(const Framebuffer&) = delete;
    Framebuffer& operator=(const Framebuffer&) = delete;
    void bind() const;
    GLuint id() const { return fbo_; }
    int width() const { return w_; }
    int height() const { return h_; }

  private:
    GLuint fbo_ = 0, color_ = 0, depth_ = 0;
    int w_, h_;
};

/// A 2D texture holding an RGB or gray Image8 (linear filtering, clamped).
class Texture {
  public:
    Texture();
    ~Texture();
    Texture(const Texture&) = delete;
    Texture& operator=(const Texture&) = delete;
    void upload(const Image8& image);
    GLuint id() const { return tex_; }
    int width() const { return w_; }
    int height() const { return h_; }

  private:
    GLuint tex_ = 0;
    int w_ = 0, h_ = 0;
};

/// Reads an RGB rectangle of the bound read framebuffer (origin bottom-left in GL) into an image with its
/// top row first.
Image8 read_pixels_rgb(int x, int y, int width, int height);

} // namespace sonarsim::ui::gl
