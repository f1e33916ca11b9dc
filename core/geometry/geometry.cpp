#include "core/geometry/geometry.hpp"

#include "core/base/errors.hpp"
#include "core/base/shared_registry.hpp"
#include "core/geometry/mesh_cache.hpp"
#include "core/geometry/phong_surface.hpp"
#include "core/geometry/shading_normals.hpp"

#include <embree3/rtcore.h>
#include <glm/gtc/matrix_inverse.hpp>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <mutex>
#include <stdexcept>
#include <string>
#include <tuple>

namespace sonarsim {
namespace {

/// Embree errors reported on this thread since the last check_embree() (Embree calls the error function on
/// the thread of the failing call).
std::string& embree_error_text() {
    thread_local std::string text;
    return text;
}

void embree_error(void*, RTCError code, const char* str) {
    // Never throw through Embree: remember the first error, report it after the call returns.
    std::string& slot = embree_error_text();
    if (slot.empty()) slot.assign("Embree error " + std::to_string(int(code)) + ": " + (str ? str : ""));
}

/// Throws the first Embree error reported on this thread since the last check.
void check_embree() {
    std::string& text = embree_error_text();
    if (text.empty()) return;
    const std::string message = std::move(text);
    text.clear();
    throw std::runtime_error(message);
}

/// The process's Embree device: created on first use, never released (every scene of the process uses it).
/// Embree picks its kernels (SSE, AVX2, AVX-512) by CPU, and hit distances differ in their last bits between
/// them; SONARSIM_EMBREE_CONFIG passes Embree's device configuration (e.g. "isa=avx2") so that outputs are
/// identical to the bit across machines (the golden test pins it).
RTCDevice embree_device() {
    static const RTCDevice device = [] {
        const char* config = std::getenv("SONARSIM_EMBREE_CONFIG");
        const RTCDevice d = rtcNewDevice(config);
        if (!d)
            throw InputError("environment", "SONARSIM_EMBREE_CONFIG",
                             "Embree cannot create a device with configuration '" +
                                 std::string(config ? config : "") + "' (error " +
                                 std::to_string(int(rtcGetDeviceError(nullptr))) +
                                 "); allowed: Embree's rtcNewDevice options, e.g. isa=avx2, threads=2");
        rtcSetDeviceErrorFunction(d, embree_error, nullptr);
        return d;
    }();
    return device;
}

/// One mesh's bottom-level BVH: an Embree scene with one triangle geometry, in the mesh's own coordinates.
struct Blas {
    std::shared_ptr<const TriMesh> mesh;
    RTCScene scene = nullptr;
    glm::dvec3 lo{0}, hi{0}; ///< the mesh's bounds
    Blas() = default;
    Blas(const Blas&) = delete;
    Blas& operator=(const Blas&) = delete;
    ~Blas() {
        if (scene) rtcReleaseScene(scene);
    }
};

std::shared_ptr<const Blas> build_blas(std::shared_ptr<const TriMesh> mesh) {
    const RTCDevice dev = embree_device();
    embree_error_text().clear();
    auto b = std::make_shared<Blas>();
    b->mesh = std::move(mesh);
    const TriMesh& m = *b->mesh;
    glm::vec3 lo(0), hi(0);
    mesh_bounds(m, lo, hi);
    b->lo = lo, b->hi = hi;
    b->scene = rtcNewScene(dev);
    RTCGeometry g = b->scene ? rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE) : nullptr;
    auto* vb = g ? static_cast<float*>(rtcSetNewGeometryBuffer(
                       g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m.vertices.size()))
                 : nullptr;
    auto* ib =
        g ? static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                           3 * sizeof(unsigned), m.triangles.size()))
          : nullptr;
    if (!vb || !ib) {
        if (g) rtcReleaseGeometry(g);
        check_embree();
        throw std::runtime_error("Embree buffer allocation failed");
    }
    for (size_t v = 0; v < m.vertices.size(); ++v)
        vb[3 * v] = m.vertices[v].x, vb[3 * v + 1] = m.vertices[v].y, vb[3 * v + 2] = m.vertices[v].z;
    for (size_t t = 0; t < m.triangles.size(); ++t)
        ib[3 * t] = m.triangles[t].x, ib[3 * t + 1] = m.triangles[t].y, ib[3 * t + 2] = m.triangles[t].z;
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(b->scene, g, 0);
    rtcReleaseGeometry(g);
    // High quality (spatial splits) traced ~5% faster here but builds ~4x slower (a 1.1M-triangle mesh: ~3 s
    // instead of ~0.9 s on 2 cores): worth it only while the build stays short.
    rtcSetSceneBuildQuality(b->scene,
                            m.triangles.size() <= 250000 ? RTC_BUILD_QUALITY_HIGH : RTC_BUILD_QUALITY_MEDIUM);
    rtcCommitScene(b->scene);
    check_embree();
    return b;
}

/// A mesh's shape: one mesh cache entry, or a box by its size.
struct ShapeKey {
    const TriMesh* mesh = nullptr;
    Vec3d box{0, 0, 0};
    bool operator<(const ShapeKey& o) const { return std::tie(mesh, box) < std::tie(o.mesh, o.box); }
};

/// The BVHs in use by any SceneGeometry, one per shape: a scene built while another holds a mesh's BVH shares
/// it. A BVH lives as long as a scene uses it (it keeps its mesh alive, so a mesh's address names one mesh).
using BlasRegistry = SharedRegistry<ShapeKey, Blas>;

BlasRegistry& blas_registry() {
    static BlasRegistry registry;
    return registry;
}

/// Where an object goes: its transform, the matrix for its normals, and its world bounds.
struct Placement {
    glm::dmat4 transform{1.0};
    glm::dmat3 normal{1.0}; ///< inverse transpose of the transform's linear part
    glm::dvec3 lo{0}, hi{0};
};

Placement place(const ObjectDesc& o, const Blas& b, const std::string& scene_file, const std::string& key) {
    Placement p;
    p.transform = object_transform(o);
    p.normal = glm::inverseTranspose(glm::dmat3(p.transform));
    for (int c = 0; c < 8; ++c) { // the placed corners of the local bounds
        const glm::dvec3 local(c & 1 ? b.hi.x : b.lo.x, c & 2 ? b.hi.y : b.lo.y, c & 4 ? b.hi.z : b.lo.z);
        const glm::dvec3 w(p.transform * glm::dvec4(local, 1.0));
        check_single_precision(w, scene_file, key);
        p.lo = c == 0 ? w : glm::min(p.lo, w);
        p.hi = c == 0 ? w : glm::max(p.hi, w);
    }
    // Embree works in single precision: widen the slab-test bounds by a few float steps.
    const glm::dvec3 pad = 1e-6 * (glm::abs(p.lo) + glm::abs(p.hi) + (p.hi - p.lo)) + 1e-9;
    p.lo -= pad, p.hi += pad;
    return p;
}

void set_instance_transform(RTCGeometry instance, const glm::dmat4& m) {
    float xfm[12]; // 3 x 4, column-major: the linear part's columns, then the translation
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r) xfm[3 * c + r] = float(m[c][r]);
    rtcSetGeometryTransform(instance, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
    rtcCommitGeometry(instance);
}

} // namespace

struct SceneGeometry::Impl {
    struct Object {
        std::string mesh_resolved;  ///< shape: mesh file ...
        std::optional<Vec3d> box_m; ///< ... or box size
        std::shared_ptr<const Blas> blas;
        std::shared_ptr<const ShadingNormals> normals; ///< null or not smooth(): face normals
        double phong_alpha = 0; ///< > 0 with smooth normals: hits on the curved surface (phong_surface.hpp)
        RTCGeometry instance = nullptr;
        Placement placement;
    };
    std::vector<Object> objects;
    RTCScene top = nullptr;
    glm::dvec3 lo{0}, hi{0};

    Impl() = default;
    Impl(const Impl&) = delete;
    Impl& operator=(const Impl&) = delete;
    ~Impl() {
        for (auto& o : objects)
            if (o.instance) rtcReleaseGeometry(o.instance);
        if (top) rtcReleaseScene(top);
    }
    void update_bounds() {
        for (size_t i = 0; i < objects.size(); ++i) {
            const Placement& p = objects[i].placement;
            lo = i == 0 ? p.lo : glm::min(lo, p.lo);
            hi = i == 0 ? p.hi : glm::max(hi, p.hi);
        }
    }
};

SceneGeometry::SceneGeometry(const SceneDesc& s) : impl_(std::make_unique<Impl>()) {
    Impl& g = *impl_;
    for (size_t i = 0; i < s.objects.size(); ++i) {
        const ObjectDesc& o = s.objects[i];
        const std::string key = "objects[" + std::to_string(i) + "]";
        Impl::Object ob;
        ob.mesh_resolved = o.mesh_resolved;
        ob.box_m = o.box_m;
        if (o.box_m) {
            ob.blas = blas_registry().get({nullptr, *o.box_m}, [&] {
                return build_blas(std::make_shared<const TriMesh>(make_box(*o.box_m)));
            });
        } else {
            std::shared_ptr<const TriMesh> mesh = cached_mesh(o.mesh_resolved, s.source_file, key + ".mesh");
            ob.blas = blas_registry().get({mesh.get(), {0, 0, 0}}, [&] { return build_blas(mesh); });
        }
        ob.placement = place(o, *ob.blas, s.source_file, key);
        ob.normals = shared_corner_normals(ob.blas->mesh, o.crease_angle_deg);
        ob.phong_alpha = o.phong_alpha;
        g.objects.push_back(std::move(ob));
    }
    if (g.objects.empty()) return;

    const RTCDevice dev = embree_device();
    embree_error_text().clear();
    g.top = rtcNewScene(dev);
    if (!g.top) {
        check_embree();
        throw std::runtime_error("cannot create an Embree scene");
    }
    // A handful of instances, re-committed whenever an object moves: a quick build is all it needs.
    rtcSetSceneFlags(g.top, RTC_SCENE_FLAG_DYNAMIC);
    rtcSetSceneBuildQuality(g.top, RTC_BUILD_QUALITY_LOW);
    for (size_t i = 0; i < g.objects.size(); ++i) {
        Impl::Object& ob = g.objects[i];
        ob.instance = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_INSTANCE);
        if (!ob.instance) break;
        rtcSetGeometryInstancedScene(ob.instance, ob.blas->scene);
        rtcSetGeometryTimeStepCount(ob.instance, 1);
        set_instance_transform(ob.instance, ob.placement.transform);
        rtcAttachGeometryByID(g.top, ob.instance, unsigned(i));
    }
    rtcCommitScene(g.top);
    check_embree();
    g.update_bounds();
}

SceneGeometry::~SceneGeometry() = default;

bool SceneGeometry::same_shapes(const SceneDesc& s) const {
    const auto& objects = impl_->objects;
    if (s.objects.size() != objects.size()) return false;
    for (size_t i = 0; i < objects.size(); ++i) {
        const ObjectDesc& o = s.objects[i];
        if (o.box_m != objects[i].box_m || (!o.box_m && o.mesh_resolved != objects[i].mesh_resolved))
            return false;
    }
    return true;
}

bool SceneGeometry::update_transforms(const SceneDesc& s) {
    if (!same_shapes(s)) return false;
    Impl& g = *impl_;
    std::vector<Placement> placements; // all of them first: a bad one changes nothing
    for (size_t i = 0; i < g.objects.size(); ++i)
        placements.push_back(
            place(s.objects[i], *g.objects[i].blas, s.source_file, "objects[" + std::to_string(i) + "]"));
    std::vector<std::shared_ptr<const ShadingNormals>> normals;
    for (size_t i = 0; i < g.objects.size(); ++i) {
        const std::shared_ptr<const ShadingNormals>& had = g.objects[i].normals;
        const double crease_deg = s.objects[i].crease_angle_deg;
        normals.push_back(had && had->crease_angle_deg == crease_deg
                              ? had
                              : shared_corner_normals(g.objects[i].blas->mesh, crease_deg));
    }
    if (g.objects.empty()) return true;
    embree_error_text().clear();
    for (size_t i = 0; i < g.objects.size(); ++i) {
        g.objects[i].normals = std::move(normals[i]);
        g.objects[i].phong_alpha = s.objects[i].phong_alpha;
        g.objects[i].placement = placements[i];
        set_instance_transform(g.objects[i].instance, placements[i].transform);
    }
    rtcCommitScene(g.top);
    check_embree();
    g.update_bounds();
    return true;
}

namespace {

/// Moves a hit on a bent triangle of a smooth object onto its Phong surface (phong_surface.hpp, in the
/// object's own coordinates, where the ray keeps its parameter t): the range becomes where the ray meets
/// the curved surface, and the face normal the curved surface's there, so footprints and the sampler's
/// edge test lie on it too. A ray grazing the surface, where the solve does not settle, keeps its flat hit.
template <class Object>
void curve(const Object& ob, const RTCRayHit& rh, const glm::dvec3& o, const glm::dvec3& d, double t_max,
           Hit& h) {
    const TriMesh& m = *ob.blas->mesh;
    const glm::uvec3 tri = m.triangles[rh.hit.primID];
    const glm::vec3* corner = &ob.normals->corner[3 * size_t(rh.hit.primID)];
    const glm::dvec3 p[3] = {m.vertices[tri.x], m.vertices[tri.y], m.vertices[tri.z]};
    const glm::dvec3 n[3] = {corner[0], corner[1], corner[2]};
    // The ray in the object's coordinates: the inverse of the linear part is the normal matrix transposed.
    const glm::dmat3 to_local = glm::transpose(ob.placement.normal);
    const glm::dvec3 o_local = to_local * (o - glm::dvec3(ob.placement.transform[3]));
    const std::optional<PhongHit> c =
        phong_hit(p, n, rh.hit.u, rh.hit.v, ob.phong_alpha, o_local, to_local * d, h.t);
    if (!c || !(c->t >= kMinHitRange_m && c->t <= t_max)) return;
    const glm::dvec3 normal = ob.placement.normal * c->normal;
    const double len = glm::length(normal);
    if (!(len > 0) || !std::isfinite(len)) return;
    h.t = c->t;
    h.face_normal = glm::dot(normal, h.face_normal) < 0 ? -normal / len : normal / len; // Embree's side
}

} // namespace

std::optional<Hit> SceneGeometry::intersect(const glm::dvec3& o, const glm::dvec3& d, double t_max) const {
    const Impl& g = *impl_;
    if (!g.top) return std::nullopt;
    RTCIntersectContext ctx;
    rtcInitIntersectContext(&ctx);
    RTCRayHit rh;
    rh.ray.org_x = float(o.x), rh.ray.org_y = float(o.y), rh.ray.org_z = float(o.z);
    rh.ray.dir_x = float(d.x), rh.ray.dir_y = float(d.y), rh.ray.dir_z = float(d.z);
    rh.ray.tnear = float(kMinHitRange_m);
    rh.ray.tfar = float(t_max);
    rh.ray.mask = ~0u;
    rh.ray.flags = 0;
    rh.ray.time = 0.0f;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(g.top, &ctx, &rh);
    const unsigned object = rh.hit.instID[0];
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID || object >= g.objects.size()) return std::nullopt;
    // Embree reports the normal in the mesh's own coordinates; normals map with the inverse transpose. A
    // smooth object's normal is interpolated from its corner normals (same side as the face's: each corner's
    // is within the crease angle, below 180 deg, of it).
    const Impl::Object& ob = g.objects[object];
    const glm::dvec3 face = ob.placement.normal * glm::dvec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    const double len = glm::length(face);
    if (!(len > 0) || !std::isfinite(len)) return std::nullopt; // degenerate triangle: no surface to echo
    Hit h;
    h.t = rh.ray.tfar;
    h.face_normal = face / len;
    h.normal = h.face_normal;
    if (ob.normals && ob.normals->smooth()) {
        const glm::dvec3 n =
            ob.placement.normal * glm::dvec3(ob.normals->at(rh.hit.primID, rh.hit.u, rh.hit.v));
        const double n_len = glm::length(n);
        if (n_len > 0 && std::isfinite(n_len)) h.normal = n / n_len;
        if (ob.phong_alpha > 0 && ob.normals->bent[rh.hit.primID]) curve(ob, rh, o, d, t_max, h);
    }
    h.material = object + 1;
    h.prim = rh.hit.primID;
    return h;
}

size_t SceneGeometry::object_count() const {
    return impl_->objects.size();
}

const std::shared_ptr<const TriMesh>& SceneGeometry::local_mesh(size_t i) const {
    return impl_->objects.at(i).blas->mesh;
}

const glm::dmat4& SceneGeometry::object_transform(size_t i) const {
    return impl_->objects.at(i).placement.transform;
}

TriMesh SceneGeometry::world_mesh(size_t i) const {
    return transformed_mesh(*local_mesh(i), object_transform(i), "", "objects[" + std::to_string(i) + "]");
}

bool SceneGeometry::has_meshes() const {
    return impl_->top != nullptr;
}

glm::dvec3 SceneGeometry::bounds_lo() const {
    return impl_->lo;
}

glm::dvec3 SceneGeometry::bounds_hi() const {
    return impl_->hi;
}

std::optional<Hit> intersect_floor(const Seafloor& f, const glm::dvec3& o, const glm::dvec3& d,
                                   double t_max) {
    if (d.z == 0) return std::nullopt;
    const double t = (f.height_m - o.z) / d.z;
    if (!(t > 0) || t > t_max) return std::nullopt;
    Hit h;
    h.t = t;
    h.normal = h.face_normal = {0, 0, 1};
    h.material = kFloorMaterial;
    return h;
}

std::optional<Hit> intersect_surface(double height_m, const glm::dvec3& o, const glm::dvec3& d,
                                     double t_max) {
    if (!(d.z > 0)) return std::nullopt;
    const double t = (height_m - o.z) / d.z;
    if (!(t > 0) || t > t_max) return std::nullopt;
    Hit h;
    h.t = t;
    h.normal = h.face_normal = {0, 0, -1};
    h.material = kSurfaceMaterial;
    return h;
}

} // namespace sonarsim
