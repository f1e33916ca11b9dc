#include "geometry.hpp"

#include "errors.hpp"

#include <embree3/rtcore.h>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace sonarsim {
namespace {

void embree_error(void* user, RTCError code, const char* str) {
    // Never throw through Embree: remember the first error, report it after the call returns.
    auto* slot = static_cast<std::string*>(user);
    if (slot->empty()) slot->assign("Embree error " + std::to_string(int(code)) + ": " + (str ? str : ""));
}

} // namespace

SceneGeometry::SceneGeometry(const SceneDesc& s) {
    for (size_t i = 0; i < s.objects.size(); ++i)
        meshes_.push_back(
            object_world_mesh(s.objects[i], s.source_file, "objects[" + std::to_string(i) + "]"));
    if (meshes_.empty()) return;

    RTCDevice dev = rtcNewDevice(nullptr);
    if (!dev) throw std::runtime_error("cannot create an Embree device");
    device_ = dev;
    rtcSetDeviceErrorFunction(dev, embree_error, &embree_error_);
    RTCScene scene = rtcNewScene(dev);
    rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
    bool first = true;
    for (size_t i = 0; i < meshes_.size(); ++i) {
        const TriMesh& m = meshes_[i];
        RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), m.vertices.size()));
        auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), m.triangles.size()));
        if (!vb || !ib) {
            rtcReleaseGeometry(g);
            scene_ = scene;
            release();
            throw std::runtime_error(embree_error_.empty() ? "Embree buffer allocation failed"
                                                           : embree_error_);
        }
        for (size_t v = 0; v < m.vertices.size(); ++v)
            vb[3 * v] = m.vertices[v].x, vb[3 * v + 1] = m.vertices[v].y, vb[3 * v + 2] = m.vertices[v].z;
        for (size_t t = 0; t < m.triangles.size(); ++t)
            ib[3 * t] = m.triangles[t].x, ib[3 * t + 1] = m.triangles[t].y, ib[3 * t + 2] = m.triangles[t].z;
        rtcCommitGeometry(g);
        rtcAttachGeometryByID(scene, g, unsigned(i));
        rtcReleaseGeometry(g);
        glm::vec3 lo, hi;
        mesh_bounds(m, lo, hi);
        lo_ = first ? glm::dvec3(lo) : glm::min(lo_, glm::dvec3(lo));
        hi_ = first ? glm::dvec3(hi) : glm::max(hi_, glm::dvec3(hi));
        first = false;
    }
    rtcCommitScene(scene);
    scene_ = scene;
    if (!embree_error_.empty()) {
        release(); // a throwing constructor runs no destructor
        throw std::runtime_error(embree_error_);
    }
}

void SceneGeometry::release() {
    if (scene_) rtcReleaseScene(static_cast<RTCScene>(scene_));
    if (device_) rtcReleaseDevice(static_cast<RTCDevice>(device_));
    scene_ = device_ = nullptr;
}

SceneGeometry::~SceneGeometry() {
    release();
}

std::optional<Hit> SceneGeometry::intersect(const glm::dvec3& o, const glm::dvec3& d, double t_max) const {
    if (!scene_) return std::nullopt;
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
    rtcIntersect1(static_cast<RTCScene>(scene_), &ctx, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    glm::dvec3 n(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
    const double len = glm::length(n);
    if (!(len > 0) || !std::isfinite(len)) return std::nullopt; // degenerate triangle: no surface to echo
    Hit h;
    h.t = rh.ray.tfar;
    h.normal = n / len;
    h.material = rh.hit.geomID + 1;
    h.prim = rh.hit.primID;
    return h;
}

std::optional<Hit> intersect_floor(const Seafloor& f, const glm::dvec3& o, const glm::dvec3& d,
                                   double t_max) {
    if (d.z == 0) return std::nullopt;
    const double t = (f.height_m - o.z) / d.z;
    if (!(t > 0) || t > t_max) return std::nullopt;
    Hit h;
    h.t = t;
    h.normal = {0, 0, 1};
    h.material = kFloorMaterial;
    return h;
}

} // namespace sonarsim
