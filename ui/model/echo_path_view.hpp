// The echo path of a hovered image cell: the strongest contribution the shading pass recorded for it
// (Frame::strongest_ptr, full-quality frames only; previews show none), turned into points once per frame
// and cell; drawn in the 3D view and named in the hover readout. Hovering shades nothing.
#pragma once
#include "ui/model/render_worker.hpp"

#include "core/shading/ground_truth.hpp"

#include <cstdint>
#include <string>

namespace sonarsim::ui {

class HoveredPath {
  public:
    /// The strongest path into raw cell (bin, beam) of `shown` (recomputed only when the frame or the cell
    /// changes); `shown_count` identifies the frame (Session::shown_count()).
    const EchoPath& update(const RenderResult& shown, std::uint64_t shown_count, int bin, int beam);
    /// No cell hovered.
    void clear() { valid_ = false, path_ = {}; }
    /// The last path; empty points when nothing is hovered or nothing echoes there.
    const EchoPath& path() const { return path_; }
    bool valid() const { return valid_; }
    int bin() const { return bin_; }
    int beam() const { return beam_; }

  private:
    bool valid_ = false;
    std::uint64_t count_ = 0;
    int bin_ = -1, beam_ = -1;
    EchoPath path_;
};

/// The name of a ground-truth object id: "seafloor", "water surface", "object N".
std::string echo_source_name(std::int32_t object_id);

/// The readout of a path: "direct echo (object 3)" or "ghost: 2 reflections (scatterer: seafloor)"; empty
/// when nothing echoes.
std::string echo_path_text(const EchoPath& path);

} // namespace sonarsim::ui
