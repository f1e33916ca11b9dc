// Colours and text placement shared by the sonar panel's files (internal to ui/).
#pragma once
#include <imgui.h>

namespace sonarsim::ui::panel {

constexpr ImU32 kGridColor = IM_COL32(255, 255, 255, 70);
constexpr ImU32 kLabelColor = IM_COL32(225, 230, 240, 220);
constexpr ImU32 kMarkerColor = IM_COL32(255, 60, 60, 255);
constexpr ImU32 kHoverColor = IM_COL32(255, 224, 25, 255);

inline void text_at(ImDrawList* dl, ImVec2 p, ImU32 col, const char* text, float align_x = 0,
                    float align_y = 0) {
    const ImVec2 sz = ImGui::CalcTextSize(text);
    dl->AddText(ImVec2(p.x - align_x * sz.x, p.y - align_y * sz.y), col, text);
}

} // namespace sonarsim::ui::panel
