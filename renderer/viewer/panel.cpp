#include "viewer/panel.h"

#include "renderer.h"
#include "viewer/debug_views.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace ssgi::viewer {

void TimingHistory::add(const FrameProfile& frame) {
    auto push = [](std::deque<float>& h, double value) {
        h.push_back(float(value));
        if (h.size() > kFrames) h.pop_front();
    };
    for (const PassTiming& t : frame.passes) {
        if (!perPass.count(t.name)) order.push_back(t.name);
        push(perPass[t.name], t.milliseconds);
    }
    push(total, frame.passSumMs());
    push(host, frame.hostMs);
    recent.add(frame);
    recent.keepLast(kFrames);
}

void TimingHistory::clear() {
    order.clear();
    perPass.clear();
    total.clear();
    host.clear();
    recent = ProfileLog(0);
}

namespace {

void plot(const char* id, const std::deque<float>& values, ImVec2 size) {
    std::vector<float> v(values.begin(), values.end());
    // ImGui 1.86 draws nothing for a plot sized "to the edge" (negative width): give it the width.
    size.x = std::max(8.0f, ImGui::GetContentRegionAvail().x);
    ImGui::PlotLines(id, v.data(), int(v.size()), 0, nullptr, 0.0f, FLT_MAX, size);
}

// One setting's widget: a checkbox for on/off, integer or float drags within the row's range.
// Drags apply on release (a change rebuilds the renderer, which restarts its caches).
bool settingWidget(const SettingRow& row, Settings& settings) {
    bool changed = false;
    const double value = row.get(settings);
    double edited = value;
    if (row.flag()) {
        bool on = value != 0.0;
        changed = ImGui::Checkbox(row.name, &on);
        edited = on ? 1.0 : 0.0;
    } else if (row.whole()) {
        int v = int(value);
        const int hi = int(std::min(row.max, 1e6));
        ImGui::DragInt(row.name, &v, std::max(1.0f, float(hi - row.min) / 400.0f), int(row.min), hi,
                       "%d", ImGuiSliderFlags_AlwaysClamp);
        edited = std::clamp(double(v), row.min, row.max);
        changed = ImGui::IsItemDeactivatedAfterEdit();
    } else {
        float v = float(value);
        const float span = float(std::min(row.max, 1e3) - row.min);
        ImGui::DragFloat(row.name, &v, std::max(span / 1000.0f, 1e-4f), float(row.min),
                         float(std::min(row.max, 1e9)), "%.4g", ImGuiSliderFlags_AlwaysClamp);
        edited = std::clamp(double(v), row.min, row.max);
        changed = ImGui::IsItemDeactivatedAfterEdit();
    }
    if (edited != value) row.set(settings, edited);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", row.meaning);
    return changed;
}

void timingsSection(PanelState& s) {
    if (!ImGui::CollapsingHeader("GPU timings", ImGuiTreeNodeFlags_DefaultOpen)) return;
    if (s.history.total.empty()) return;
    const ProfileSummary summary = s.history.recent.summary();
    char label[160];
    std::snprintf(label, sizeof label, "passes %.1f ms, host clock %.1f ms", s.history.total.back(),
                  s.history.host.back());
    plot("##total", s.history.total, ImVec2(-1.0f, 48.0f));
    ImGui::TextUnformatted(label);
    std::snprintf(label, sizeof label, "%u frames: median %.1f, host %.1f ms (%.0f%%)",
                  summary.timedFrames, summary.passSum.medianMs, summary.host.medianMs,
                  100.0 * summary.worstCoverage);
    ImGui::TextUnformatted(label);
    if (summary.disagrees)
        ImGui::TextColored(ImVec4(1.0f, 0.6f, 0.2f, 1.0f),
                           "passes and host clock differ by > 3%%: stamps not to be trusted");
    const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp;
    if (!ImGui::BeginTable("passes", 4, flags)) return;
    ImGui::TableSetupColumn("pass", ImGuiTableColumnFlags_WidthStretch, 1.4f);
    ImGui::TableSetupColumn("median", ImGuiTableColumnFlags_WidthStretch, 0.6f);
    ImGui::TableSetupColumn("min-max", ImGuiTableColumnFlags_WidthStretch, 0.9f);
    ImGui::TableSetupColumn("last frames", ImGuiTableColumnFlags_WidthStretch, 1.2f);
    ImGui::TableHeadersRow();
    for (const PassStatistics& p : summary.passes) {
        ImGui::TableNextRow();
        ImGui::TableNextColumn();
        ImGui::TextUnformatted(p.name.c_str());
        ImGui::TableNextColumn();
        ImGui::Text("%.2f", p.medianMs);
        ImGui::TableNextColumn();
        ImGui::Text("%.1f-%.1f", p.minMs, p.maxMs);
        ImGui::TableNextColumn();
        ImGui::PushID(p.name.c_str());
        plot("##h", s.history.perPass[p.name], ImVec2(-1.0f, 14.0f));
        ImGui::PopID();
    }
    ImGui::EndTable();
}

void viewSection(PanelState& s) {
    if (!ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) return;
    const std::vector<std::string>& names = viewNames();
    for (int i = 0; i < int(names.size()); ++i) {
        if (ImGui::RadioButton(names[i].c_str(), s.cacheView < 0 && s.view == i)) {
            s.viewChanged = s.view != i || s.cacheView >= 0;
            s.view = i;
            s.cacheView = -1;
        }
        if (i % 3 != 2 && i + 1 < int(names.size())) ImGui::SameLine(float(1 + i % 3) * 105.0f);
    }
    if (!s.cacheAvailable) {
        ImGui::TextDisabled("cache views: turn the cache on");
        return;
    }
    ImGui::Separator();
    const auto& views = cacheViews();
    for (int i = 0; i < int(views.size()); ++i) {
        if (ImGui::RadioButton(views[i].name, s.cacheView == i)) {
            s.viewChanged = s.cacheView != i;
            s.cacheView = i;
        }
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", views[i].meaning);
        if (i % 2 == 0) ImGui::SameLine(160.0f);
    }
    s.cacheEffect = std::clamp(s.cacheEffect, 0, int(s.cachedEffects.size()) - 1);
    if (ImGui::BeginCombo("effect", s.cachedEffects[size_t(s.cacheEffect)].c_str())) {
        for (int i = 0; i < int(s.cachedEffects.size()); ++i)
            if (ImGui::Selectable(s.cachedEffects[size_t(i)].c_str(), i == s.cacheEffect))
                s.cacheEffect = i;
        ImGui::EndCombo();
    }
}

void cameraSection(PanelState& s) {
    if (!ImGui::CollapsingHeader("Camera and path", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::TextDisabled("WASD/QE move, Shift faster, right drag turns");
    ImGui::DragFloat("speed", &s.cameraSpeed, 0.01f, 0.001f, 1e4f, "%.3g /s");
    if (ImGui::Button("scene camera")) s.resetCamera = true;
    ImGui::SameLine();
    if (s.pathLength > 0.0f) {
        ImGui::Checkbox("play path", &s.playPath);
        ImGui::SliderFloat("time", &s.pathTime, 0.0f, s.pathLength, "%.2f s");
    } else {
        ImGui::TextDisabled("the scene has no camera path");
    }
    if (!s.recording) {
        if (ImGui::Button("record path")) s.startRecording = true;
    } else if (ImGui::Button("stop recording")) {
        s.stopRecording = true;
    }
    ImGui::SameLine();
    ImGui::Text("%zu keys", s.recordedKeys);
    ImGui::InputText("##saveto", s.savePathTo, sizeof s.savePathTo);
    ImGui::SameLine();
    if (ImGui::Button("save path")) s.saveCameraPath = true;
}

void lightSection(PanelState& s) {
    if (!ImGui::CollapsingHeader("Light")) return;
    ImGui::TextDisabled("Ctrl + left drag on the image: across the floor");
    ImGui::TextDisabled("(+ Shift: up and down)");
    bool changed = ImGui::DragFloat3("position", &s.light.position.x, 0.005f);
    glm::vec3 d = glm::normalize(s.light.direction);
    float yaw = glm::degrees(std::atan2(d.x, -d.z)), pitch = glm::degrees(std::asin(d.y));
    if (ImGui::DragFloat("yaw", &yaw, 0.5f) |
        ImGui::DragFloat("pitch", &pitch, 0.5f, -89.9f, 89.9f)) {
        const float y = glm::radians(yaw), p = glm::radians(pitch);
        s.light.direction = {std::sin(y) * std::cos(p), std::sin(p), -std::cos(y) * std::cos(p)};
        changed = true;
    }
    changed |= ImGui::DragFloat("intensity", &s.light.intensity, 0.01f, 0.0f, 1e6f);
    changed |= ImGui::DragFloat("disk radius", &s.light.radius, 0.001f, 0.0f, 1e3f);
    changed |= ImGui::ColorEdit3("colour", &s.light.color.x);
    s.lightChanged |= changed;
}

void settingsSection(PanelState& s) {
    if (!ImGui::CollapsingHeader("Settings", ImGuiTreeNodeFlags_DefaultOpen)) return;
    ImGui::TextDisabled("a change rebuilds the frame (caches restart)");
    const std::span<const SettingRow> rows = settingTable();
    for (size_t first = 0; first < rows.size();) { // the table's groups, in its order
        size_t end = first;
        while (end < rows.size() && std::string(rows[end].group) == rows[first].group)
            ++end;
        if (ImGui::TreeNode(rows[first].group)) {
            for (size_t i = first; i < end; ++i)
                s.settingsChanged |= settingWidget(rows[i], s.settings);
            ImGui::TreePop();
        }
        first = end;
    }
}

} // namespace

void drawPanel(PanelState& s, float width, float height) {
    ImGui::SetNextWindowPos(ImVec2(0.0f, 0.0f));
    ImGui::SetNextWindowSize(ImVec2(width, height));
    ImGui::Begin("ssgi viewer", nullptr,
                 ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::PushItemWidth(-90.0f);
    ImGui::TextWrapped("%s", s.sceneFile.c_str());
    ImGui::TextDisabled("%s", s.device.c_str());
    ImGui::Text("window %ux%u  image %ux%u", s.windowSize.width, s.windowSize.height,
                s.renderSize.width, s.renderSize.height);
    ImGui::Text("frame %u  %.0f ms/frame", s.frame, 1000.0f * s.secondsPerFrame);
    if (!s.message.empty())
        ImGui::TextColored(ImVec4(1.0f, 0.6f, 0.3f, 1.0f), "%s", s.message.c_str());
    if (ImGui::Button("screenshot (F12)")) s.screenshot = true;
    ImGui::InputText("##scene", s.scenePath, sizeof s.scenePath);
    ImGui::SameLine();
    if (ImGui::Button("load scene")) s.loadScene = true;
    timingsSection(s);
    viewSection(s);
    settingsSection(s);
    lightSection(s);
    cameraSection(s);
    ImGui::PopItemWidth();
    ImGui::End();
}

} // namespace ssgi::viewer
