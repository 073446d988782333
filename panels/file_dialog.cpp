#include "panels/file_dialog.h"

#include <algorithm>
#include <filesystem>
#include <system_error>

#include <imgui.h>
#include <imgui_stdlib.h>

namespace rrf::panels {

namespace fs = std::filesystem;

namespace file_dialog_detail {
namespace {
bool hasExtension(const std::string& name, const std::string& ext) {
    if (ext.empty()) return true;
    if (name.size() < ext.size()) return false;
    std::string tail = name.substr(name.size() - ext.size());
    std::transform(tail.begin(), tail.end(), tail.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return tail == ext;
}
}  // namespace
}  // namespace file_dialog_detail

void FileDialog::open(Mode mode, const std::string& title, const std::string& initial, const std::string& extension) {
    mode_ = mode;
    title_ = title;
    extension_ = mode == Mode::Directory ? std::string() : extension;
    std::error_code ec;
    input_ = fs::absolute(initial.empty() ? fs::path(".") : fs::path(initial), ec).lexically_normal().string();
    error_.clear();
    listedDir_.clear();
    pending_ = true;
}

std::string FileDialog::currentDirectory() const {
    std::error_code ec;
    const fs::path p(input_);
    if (fs::is_directory(p, ec)) return p.string();
    const fs::path parent = p.parent_path();
    return parent.empty() ? std::string(".") : parent.string();
}

void FileDialog::list(const std::string& dir) {
    listedDir_ = dir;
    entries_.clear();
    std::error_code ec;
    for (fs::directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec), end; !ec && it != end;
         it.increment(ec)) {
        const std::string name = it->path().filename().string();
        if (name.empty() || name[0] == '.') continue;  // hidden files clutter the list; type them if needed
        std::error_code e2;
        const bool isDir = it->is_directory(e2);
        if (!isDir && (mode_ == Mode::Directory || !file_dialog_detail::hasExtension(name, extension_))) continue;
        entries_.push_back({name, isDir});
    }
    std::sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) {
        return a.directory != b.directory ? a.directory : a.name < b.name;
    });
}

bool FileDialog::confirm() {
    error_.clear();
    if (input_.empty()) {
        error_ = "type a path";
        return false;
    }
    std::error_code ec;
    fs::path p = fs::absolute(fs::path(input_), ec).lexically_normal();
    if (mode_ == Mode::Directory) {
        if (fs::exists(p, ec) && !fs::is_directory(p, ec)) {
            error_ = "not a directory: " + p.string();
            return false;
        }
    } else {
        if (fs::is_directory(p, ec)) {
            error_ = "choose a file, not a directory";
            return false;
        }
        if (mode_ == Mode::Save && !file_dialog_detail::hasExtension(p.filename().string(), extension_)) p += extension_;
        if (mode_ == Mode::Open && !fs::is_regular_file(p, ec)) {
            error_ = "no such file: " + p.string();
            return false;
        }
        if (mode_ == Mode::Save && !fs::is_directory(p.parent_path(), ec)) {
            error_ = "no such directory: " + p.parent_path().string();
            return false;
        }
    }
    result_ = p.string();
    return true;
}

bool FileDialog::draw() {
    if (pending_) {
        ImGui::OpenPopup(title_.c_str());
        pending_ = false;
        open_ = true;
    }
    if (!open_) return false;
    bool confirmed = false;
    const float em = ImGui::GetFontSize();
    ImGui::SetNextWindowSize(ImVec2(40 * em, 28 * em), ImGuiCond_Appearing);
    bool keepOpen = true;
    if (ImGui::BeginPopupModal(title_.c_str(), &keepOpen)) {
        const std::string dir = currentDirectory();
        if (dir != listedDir_) list(dir);

        if (ImGui::Button("Up")) input_ = fs::path(dir).parent_path().string();
        ImGui::SameLine();
        ImGui::SetNextItemWidth(-1);
        const bool enter = ImGui::InputText("##path", &input_, ImGuiInputTextFlags_EnterReturnsTrue);
        ImGui::TextDisabled("%s", dir.c_str());

        const float footer = ImGui::GetFrameHeightWithSpacing() * 2.f;
        if (ImGui::BeginChild("##entries", ImVec2(0, -footer), true)) {
            for (const Entry& e : entries_) {
                const std::string label = (e.directory ? "[dir] " : "      ") + e.name;
                const bool selected = fs::path(input_).filename().string() == e.name;
                if (ImGui::Selectable(label.c_str(), selected, ImGuiSelectableFlags_AllowDoubleClick)) {
                    const std::string full = (fs::path(dir) / e.name).string();
                    if (e.directory) {
                        input_ = full;  // navigate
                    } else {
                        input_ = full;
                        if (ImGui::IsMouseDoubleClicked(0) && confirm()) confirmed = true;
                    }
                }
            }
            if (entries_.empty()) ImGui::TextDisabled("(no matching entries)");
        }
        ImGui::EndChild();

        if (!error_.empty()) ImGui::TextColored(ImVec4(1.f, 0.4f, 0.4f, 1.f), "%s", error_.c_str());
        else if (std::error_code ec; mode_ == Mode::Save && fs::is_regular_file(fs::path(input_), ec))
            ImGui::TextColored(ImVec4(1.f, 0.8f, 0.3f, 1.f), "the file exists and will be replaced");
        else ImGui::NewLine();

        const char* ok = mode_ == Mode::Open ? "Open" : mode_ == Mode::Save ? "Save" : "Choose";
        if ((ImGui::Button(ok) || enter) && !confirmed && confirm()) confirmed = true;
        ImGui::SameLine();
        if (ImGui::Button("Cancel")) keepOpen = false;
        if (confirmed || !keepOpen) {
            ImGui::CloseCurrentPopup();
            open_ = false;
        }
        ImGui::EndPopup();
    } else {
        open_ = false;  // closed with the title bar's close button
    }
    return confirmed;
}

}  // namespace rrf::panels
