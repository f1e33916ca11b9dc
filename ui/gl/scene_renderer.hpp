// Draws the 3D view with OpenGL 3.3 core: seafloor with a grid, object meshes with simple shading, the water
// surface (translucent, with a grid), the sonar housing and its field-of-view shell (wireframe + translucent
// faces), and the teaching overlays (the elevation arc of a hovered image pixel, the surface points that
// echoed into it and its strongest echo path, a hovered surface point).
#pragma once
#include "ui/model/camera.hpp"
#include "ui/model/framing.hpp"
#include "ui/gl/gl_util.hpp"

#include "core/geometry/mesh.hpp"
#include "core/data/scene.hpp"

#include <memory>
#include <optional>
#include <vector>

namespace sonarsim::ui {

struct ViewOverlay {
    std::vector<glm::dvec3> arc;        ///< elevation arc of the hovered pixel [world]
    std::vector<glm::vec3> echo_points; ///< traced points that echo into the hovered pixel
    /// The hovered pixel's strongest echo path (sonar, mirrors out, scatterer, mirrors back, sonar) [world]
    std::vector<glm::dvec3> echo_path;
    size_t echo_path_scatterer = 0;    ///< index of the scatterer in echo_path
    std::optional<glm::dvec3> marker;  ///< hovered surface point
    std::vector<glm::vec3> hit_points; ///< optional: every traced hit (teaching: shadows)
    std::vector<glm::dvec3> handles;   ///< where the sonar can be grabbed besides its housing
    bool sonar_hot = false;            ///< frustum under the mouse or being dragged
    /// The fields of view drawn (fields_of_view); empty: those of the scene's own pings.
    std::vector<SonarParams> fields;
    int selected_object = -1;
};

class SceneRenderer {
  public:
    /// Compiles the shaders; needs a current OpenGL 3.3 core context. Throws std::runtime_error.
    SceneRenderer();
    ~SceneRenderer();
    SceneRenderer(const SceneRenderer&) = delete;
    SceneRenderer& operator=(const SceneRenderer&) = delete;

    /// The objects' meshes in their own coordinates (object i = element i; shared meshes are uploaded once),
    /// once per change of meshes. draw() places object i by object_transform(scene.objects[i]), so moving
    /// objects needs no new upload.
    void set_meshes(const std::vector<std::shared_ptr<const TriMesh>>& meshes);

    /// Clears and draws into the viewport (x, y, w, h) of the bound framebuffer (GL: origin bottom-left).
    void draw(const SceneDesc& scene, const OrbitCamera& camera, int x, int y, int w, int h,
              const ViewOverlay& overlay);

  private:
    struct Program {
        explicit Program(bool round_points);
        ~Program();
        Program(const Program&) = delete;
        Program& operator=(const Program&) = delete;
        GLuint id = 0;
        GLint mvp = -1, model = -1, normal = -1, light = -1, point = -1, tint = -1;
    };
    void use(const Program& p, const glm::mat4& mvp, const glm::vec3& light, float point_px);
    /// Places what is drawn next (object meshes); everything else is drawn with the identity.
    void set_model(const Program& p, const glm::dmat4& model);
    /// Draws `vb` where it is visible, then again with `hidden_alpha` where surfaces hide it.
    void draw_with_hidden(const gl::VertexBuffer& vb, GLenum mode, float hidden_alpha);
    /// The water surface plane z = h around (cx, cy): translucent faces and grid (blending on, no depth
    /// writes).
    void draw_water_surface(double h, double cx, double cy, double half);
    /// The echo path: the way out wide and orange, the way back thin and pale on top.
    void draw_echo_path(const ViewOverlay& ov);

    Program surfaces_, points_;
    GLint u_tint_ = -1;                           // tint uniform of the program in use
    std::vector<size_t> mesh_first_, mesh_count_; // triangle vertex ranges per object
    std::vector<Box3> mesh_bounds_;               // local bounds per object (terrain is drawn apart)
    gl::VertexBuffer meshes_, floor_, grid_, footprint_, body_, shell_faces_, shell_lines_, overlay_lines_,
        overlay_points_, water_, water_grid_;
};

} // namespace sonarsim::ui
