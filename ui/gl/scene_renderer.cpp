#include "ui/gl/scene_renderer.hpp"

#include "ui/model/framing.hpp"
#include "ui/model/sonar_geometry.hpp"

#include "core/data/pose.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <map>

namespace sonarsim::ui {
namespace {

const char* kVertex = R"(#version 330 core
layout(location = 0) in vec3 a_pos;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_color;
uniform mat4 u_mvp;
uniform mat4 u_model;  // object meshes: local -> world; identity for everything else
uniform mat3 u_normal; // inverse transpose of u_model's linear part
uniform float u_point;
out vec3 v_normal;
out vec4 v_color;
void main() {
    gl_Position = u_mvp * (u_model * vec4(a_pos, 1.0));
    gl_PointSize = max(u_point, 1.0);
    v_normal = u_normal * a_normal;
    v_color = a_color;
}
)";

// Two variants: surfaces and lines (no discard, so that software OpenGL keeps its early depth test) and round
// points (ROUND_POINTS).
const char* kFragment = R"(
in vec3 v_normal;
in vec4 v_color;
uniform vec3 u_light;
uniform float u_point;
uniform vec4 u_tint;
out vec4 o_color;
void main() {
#ifdef ROUND_POINTS
    vec2 c = gl_PointCoord - vec2(0.5);
    if (dot(c, c) > 0.25) discard;
#endif
    vec3 rgb = v_color.rgb * u_tint.rgb;
    if (dot(v_normal, v_normal) > 0.0) {
        float l = abs(dot(normalize(v_normal), u_light));
        rgb *= 0.38 + 0.62 * l;
    }
    o_color = vec4(rgb, v_color.a * u_tint.a);
}
)";

using gl::Vertex;

const glm::vec4 kWater{0.075f, 0.11f, 0.16f, 1.0f};
const glm::vec4 kSand{0.50f, 0.46f, 0.38f, 1.0f};
const glm::vec4 kGridMinor{0.40f, 0.37f, 0.31f, 1.0f};
const glm::vec4 kGridMajor{0.26f, 0.24f, 0.21f, 1.0f};
const glm::vec4 kTerrain{0.62f, 0.56f, 0.45f, 1.0f};
const glm::vec4 kBody{0.30f, 0.32f, 0.36f, 1.0f};
const glm::vec3 kShell{0.25f, 0.85f, 1.0f};
const glm::vec4 kFootprint{0.75f, 1.0f, 1.0f, 1.0f};
const glm::vec4 kArc{1.0f, 0.88f, 0.1f, 1.0f};
const glm::vec4 kEcho{1.0f, 0.25f, 0.85f, 1.0f};
const glm::vec4 kMarker{1.0f, 0.2f, 0.2f, 1.0f};
const glm::vec4 kHandle{1.0f, 0.85f, 0.2f, 1.0f};
const glm::vec4 kHits{0.3f, 1.0f, 0.5f, 0.6f};
const glm::vec4 kSurface{0.35f, 0.68f, 1.0f, 0.16f};
const glm::vec4 kSurfaceGrid{0.55f, 0.8f, 1.0f, 0.3f};
const glm::vec4 kPathOut{1.0f, 0.5f, 0.05f, 1.0f};
const glm::vec4 kPathBack{1.0f, 0.93f, 0.55f, 1.0f};
const glm::vec4 kMirrorPoint{1.0f, 1.0f, 1.0f, 1.0f};
const glm::vec4 kScatterer{1.0f, 0.22f, 0.1f, 1.0f};

/// The world bounds of a local box placed by `model`.
Box3 placed_bounds_of(const Box3& local, const glm::dmat4& model) {
    TriMesh corners;
    for (int k = 0; k < 8; ++k)
        corners.vertices.emplace_back(k & 1 ? local.hi.x : local.lo.x, k & 2 ? local.hi.y : local.lo.y,
                                      k & 4 ? local.hi.z : local.lo.z);
    return placed_bounds(corners, model);
}

glm::vec4 object_color(size_t i) {
    static const glm::vec4 palette[] = {{0.95f, 0.55f, 0.15f, 1},
                                        {0.35f, 0.75f, 0.55f, 1},
                                        {0.70f, 0.50f, 0.90f, 1},
                                        {0.90f, 0.40f, 0.45f, 1},
                                        {0.55f, 0.70f, 0.95f, 1}};
    return palette[i % (sizeof palette / sizeof palette[0])];
}

void push_triangles(std::vector<Vertex>& out, const TriMesh& m, glm::vec4 color) {
    for (auto& t : m.triangles) {
        const glm::vec3 a = m.vertices[t.x], b = m.vertices[t.y], c = m.vertices[t.z];
        glm::vec3 n = glm::cross(b - a, c - a);
        const float len = glm::length(n);
        n = len > 0 ? n / len : glm::vec3(0, 0, 1);
        out.push_back({a, n, color});
        out.push_back({b, n, color});
        out.push_back({c, n, color});
    }
}

} // namespace

SceneRenderer::Program::Program(bool round_points) {
    const std::string fs =
        std::string("#version 330 core\n") + (round_points ? "#define ROUND_POINTS\n" : "") + kFragment;
    id = gl::compile_program(kVertex, fs.c_str());
    mvp = glGetUniformLocation(id, "u_mvp");
    model = glGetUniformLocation(id, "u_model");
    normal = glGetUniformLocation(id, "u_normal");
    light = glGetUniformLocation(id, "u_light");
    point = glGetUniformLocation(id, "u_point");
    tint = glGetUniformLocation(id, "u_tint");
}

SceneRenderer::Program::~Program() {
    glDeleteProgram(id);
}

SceneRenderer::SceneRenderer() : surfaces_(false), points_(true) {}

SceneRenderer::~SceneRenderer() = default;

void SceneRenderer::use(const Program& p, const glm::mat4& mvp, const glm::vec3& light, float point_px) {
    glUseProgram(p.id);
    glUniformMatrix4fv(p.mvp, 1, GL_FALSE, glm::value_ptr(mvp));
    set_model(p, glm::dmat4(1.0));
    glUniform3fv(p.light, 1, glm::value_ptr(light));
    glUniform1f(p.point, point_px);
    glUniform4f(p.tint, 1, 1, 1, 1);
    u_tint_ = p.tint;
}

void SceneRenderer::set_model(const Program& p, const glm::dmat4& model) {
    const glm::mat4 m(model);
    const glm::mat3 n(glm::inverseTranspose(glm::dmat3(model)));
    glUniformMatrix4fv(p.model, 1, GL_FALSE, glm::value_ptr(m));
    glUniformMatrix3fv(p.normal, 1, GL_FALSE, glm::value_ptr(n));
}

void SceneRenderer::draw_with_hidden(const gl::VertexBuffer& vb, GLenum mode, float hidden_alpha) {
    vb.draw(mode);
    glDepthFunc(GL_GREATER);
    glUniform4f(u_tint_, 1, 1, 1, hidden_alpha);
    vb.draw(mode);
    glDepthFunc(GL_LESS);
    glUniform4f(u_tint_, 1, 1, 1, 1);
}

void SceneRenderer::set_meshes(const std::vector<std::shared_ptr<const TriMesh>>& meshes) {
    std::vector<gl::Vertex> vertices;
    std::map<const TriMesh*, std::pair<size_t, size_t>> uploaded; // each distinct mesh once
    mesh_first_.clear(), mesh_count_.clear(), mesh_bounds_.clear();
    for (const auto& m : meshes) {
        mesh_bounds_.push_back(placed_bounds(*m, glm::dmat4(1.0)));
        auto it = uploaded.find(m.get());
        if (it == uploaded.end()) {
            const size_t first = vertices.size();
            push_triangles(vertices, *m, glm::vec4(1)); // white: each object's colour is its tint
            it = uploaded.emplace(m.get(), std::make_pair(first, vertices.size() - first)).first;
        }
        mesh_first_.push_back(it->second.first);
        mesh_count_.push_back(it->second.second);
    }
    meshes_.upload(vertices);
}

void SceneRenderer::draw(const SceneDesc& scene, const OrbitCamera& cam, int x, int y, int w, int h,
                         const ViewOverlay& ov) {
    w = std::max(1, w), h = std::max(1, h);
    glViewport(x, y, w, h);
    glEnable(GL_SCISSOR_TEST);
    glScissor(x, y, w, h);
    glClearColor(kWater.r, kWater.g, kWater.b, 1);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);

    const glm::mat4 mvp = glm::mat4(cam.projection(double(w) / h) * cam.view());
    const glm::vec3 light = glm::normalize(glm::vec3(-cam.forward()) + glm::vec3(0.3f, 0.2f, 1.2f));
    use(surfaces_, mvp, light, 0);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glEnable(GL_PROGRAM_POINT_SIZE);

    const SonarParams& s = scene.sonar;
    const std::vector<SonarParams> fields = ov.fields.empty() ? fields_of_view(scene) : ov.fields;
    std::vector<Vertex> v;

    // Seafloor and its grid, around the sonar's reach.
    if (scene.seafloor) {
        const double z = scene.seafloor->height_m;
        const double half = std::ceil(std::max(3.0, s.range_max_m + 1.0));
        const double cx = std::round(s.pose.position_m[0]), cy = std::round(s.pose.position_m[1]);
        const glm::vec3 n(0, 0, 1);
        auto P = [&](double px, double py) { return glm::vec3(float(px), float(py), float(z)); };
        v = {{P(cx - half, cy - half), n, kSand}, {P(cx + half, cy - half), n, kSand},
             {P(cx + half, cy + half), n, kSand}, {P(cx - half, cy - half), n, kSand},
             {P(cx + half, cy + half), n, kSand}, {P(cx - half, cy + half), n, kSand}};
        floor_.upload(v);
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(1.0f, 1.0f);
        floor_.draw(GL_TRIANGLES);
        glDisable(GL_POLYGON_OFFSET_FILL);
        v.clear();
        // At most ~64 lines each way (0.25, 0.5, 1, 2, 5, 10 ... m apart), each at a multiple of the step:
        // more would blend into a moire pattern at long range and cost fill under software OpenGL. Major
        // lines every metre, or every 5 steps when a step is a metre or more.
        double step = 0.25;
        for (double m : {0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0})
            if (2 * half / step > 64) step = m;
        const double major_m = step < 1 ? 1.0 : 5 * step;
        auto line_at = [&](double t) { // t: a world coordinate, the same for both directions
            const bool major = std::abs(std::remainder(t, major_m)) < 1e-6 * major_m;
            return major ? kGridMajor : kGridMinor;
        };
        for (double t = std::ceil((cx - half) / step) * step; t <= cx + half + 1e-9; t += step)
            v.push_back({P(t, cy - half), {}, line_at(t)}), v.push_back({P(t, cy + half), {}, line_at(t)});
        for (double t = std::ceil((cy - half) / step) * step; t <= cy + half + 1e-9; t += step)
            v.push_back({P(cx - half, t), {}, line_at(t)}), v.push_back({P(cx + half, t), {}, line_at(t)});
        grid_.upload(v);
        grid_.draw(GL_LINES);
        // Where the field of view meets the floor: the outline of the insonified patch.
        v.clear();
        for (const SonarParams& fov : fields) // a side-scan's swaths, a scan's beams
            for (const glm::vec3& q : floor_footprint(fov, z)) v.push_back({q, {}, kFootprint});
        footprint_.upload(v);
        glLineWidth(2.0f);
        footprint_.draw(GL_LINES);
        glLineWidth(1.0f);
    }

    // Objects (terrain in earth tones; the selected one lightened, short of saturating so that its shading
    // still shows) and the sonar housing.
    for (size_t i = 0; i < mesh_first_.size() && i < scene.objects.size(); ++i) {
        const glm::dmat4 model = object_transform(scene.objects[i]);
        const bool terrain = is_terrain(placed_bounds_of(mesh_bounds_[i], model), s);
        glm::vec4 c = terrain ? kTerrain : object_color(i);
        if (int(i) == ov.selected_object) c += (glm::vec4(1) - c) * (terrain ? 0.12f : 0.3f);
        glUniform4f(u_tint_, c.r, c.g, c.b, 1);
        set_model(surfaces_, model);
        meshes_.draw_range(GL_TRIANGLES, GLint(mesh_first_[i]), GLsizei(mesh_count_[i]));
    }
    set_model(surfaces_, glm::dmat4(1.0));
    glUniform4f(u_tint_, 1, 1, 1, 1);
    v.clear();
    push_triangles(v, sonar_body(s), kBody);
    body_.upload(v);
    body_.draw(GL_TRIANGLES);

    // Translucent from here on: the water surface, then the field of view.
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    if (scene.water.surface_height_m)
        draw_water_surface(*scene.water.surface_height_m, std::round(s.pose.position_m[0]),
                           std::round(s.pose.position_m[1]), std::ceil(std::max(3.0, s.range_max_m + 1.0)));

    // Field of view: translucent faces, then the wireframe (faint where hidden behind surfaces).
    FrustumShell shell;
    for (const SonarParams& fov : fields) {
        FrustumShell one = frustum_shell(fov);
        shell.triangles.insert(shell.triangles.end(), one.triangles.begin(), one.triangles.end());
        shell.lines.insert(shell.lines.end(), one.lines.begin(), one.lines.end());
    }
    const float face_alpha = ov.sonar_hot ? 0.22f : 0.11f;
    v.clear();
    for (auto& p : shell.triangles) v.push_back({p, {}, glm::vec4(kShell, face_alpha)});
    shell_faces_.upload(v);
    v.clear();
    for (auto& p : shell.lines) v.push_back({p, {}, glm::vec4(kShell, 1.0f)});
    shell_lines_.upload(v);
    shell_faces_.draw(GL_TRIANGLES);
    glUniform4f(u_tint_, 1, 1, 1, ov.sonar_hot ? 1.0f : 0.85f);
    draw_with_hidden(shell_lines_, GL_LINES, 0.22f);

    // Teaching overlays: the arc bright where visible and faint where hidden (e.g. below the floor); the
    // points over everything.
    if (!ov.arc.empty()) {
        v.clear();
        for (auto& p : ov.arc) v.push_back({glm::vec3(p), {}, kArc});
        overlay_lines_.upload(v);
        glLineWidth(2.5f);
        draw_with_hidden(overlay_lines_, GL_LINE_STRIP, 0.35f);
        glLineWidth(1.0f);
    }
    draw_echo_path(ov);
    glDisable(GL_DEPTH_TEST);
    if (!ov.hit_points.empty()) {
        v.clear();
        for (auto& p : ov.hit_points) v.push_back({p, {}, kHits});
        overlay_points_.upload(v);
        use(points_, mvp, light, 2.0f);
        overlay_points_.draw(GL_POINTS);
    }
    v.clear();
    for (auto& p : ov.echo_points) v.push_back({p, {}, kEcho});
    for (size_t i = 1; i + 1 < ov.echo_path.size(); ++i) // the scatterer and the mirror points of the path
        v.push_back(
            {glm::vec3(ov.echo_path[i]), {}, i == ov.echo_path_scatterer ? kScatterer : kMirrorPoint});
    if (ov.marker) v.push_back({glm::vec3(*ov.marker), {}, kMarker});
    if (!v.empty()) {
        overlay_points_.upload(v);
        use(points_, mvp, light, 7.0f);
        overlay_points_.draw(GL_POINTS);
    }
    if (!ov.handles.empty()) { // the frustum's grab handles
        v.clear();
        const glm::vec4 c = ov.sonar_hot ? glm::vec4(1, 1, 1, 1) : kHandle;
        for (auto& p : ov.handles) v.push_back({glm::vec3(p), {}, c});
        overlay_points_.upload(v);
        use(points_, mvp, light, 13.0f);
        overlay_points_.draw(GL_POINTS);
    }
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glUseProgram(0);
}

void SceneRenderer::draw_water_surface(double h, double cx, double cy, double half) {
    std::vector<Vertex> v;
    auto P = [&](double px, double py) { return glm::vec3(float(px), float(py), float(h)); };
    v = {{P(cx - half, cy - half), {}, kSurface}, {P(cx + half, cy - half), {}, kSurface},
         {P(cx + half, cy + half), {}, kSurface}, {P(cx - half, cy - half), {}, kSurface},
         {P(cx + half, cy + half), {}, kSurface}, {P(cx - half, cy + half), {}, kSurface}};
    water_.upload(v);
    water_.draw(GL_TRIANGLES);
    v.clear();
    const double step = half > 10 ? 2.0 : 1.0;
    const int n_lines = int(std::lround(2 * half / step));
    for (int k = 0; k <= n_lines; ++k) { // the edge brighter: where the surface ends
        const double t = -half + k * step;
        const glm::vec4 c = k == 0 || k == n_lines ? glm::vec4(glm::vec3(kSurfaceGrid), 0.75f) : kSurfaceGrid;
        v.push_back({P(cx + t, cy - half), {}, c}), v.push_back({P(cx + t, cy + half), {}, c});
        v.push_back({P(cx - half, cy + t), {}, c}), v.push_back({P(cx + half, cy + t), {}, c});
    }
    water_grid_.upload(v);
    water_grid_.draw(GL_LINES);
}

void SceneRenderer::draw_echo_path(const ViewOverlay& ov) {
    const size_t n = ov.echo_path.size();
    if (n < 3) return;
    const size_t k = std::clamp<size_t>(ov.echo_path_scatterer, 1, n - 2);
    std::vector<Vertex> v;
    for (size_t i = 0; i <= k; ++i) v.push_back({glm::vec3(ov.echo_path[i]), {}, kPathOut});
    overlay_lines_.upload(v);
    glLineWidth(4.0f);
    draw_with_hidden(overlay_lines_, GL_LINE_STRIP, 0.4f);
    v.clear();
    for (size_t i = k; i < n; ++i) v.push_back({glm::vec3(ov.echo_path[i]), {}, kPathBack});
    overlay_lines_.upload(v);
    glLineWidth(1.5f);
    draw_with_hidden(overlay_lines_, GL_LINE_STRIP, 0.4f);
    glLineWidth(1.0f);
}

} // namespace sonarsim::ui
