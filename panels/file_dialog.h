#pragma once
/// A small path-input modal with a directory listing (std::filesystem), because Dear ImGui has no
/// file dialog and the workbench takes no extra dependency for one.

#include <string>
#include <vector>

namespace rrf::panels {

class FileDialog {
public:
    enum class Mode { Open, Save, Directory };

    /// Opens the dialog on the next draw(). `initial` is a file or directory; `extension` (e.g.
    /// ".json", ".png") filters the listing and is appended to typed names that lack it (Save).
    void open(Mode mode, const std::string& title, const std::string& initial, const std::string& extension);
    /// Draws the modal when open; returns true exactly once, when the user confirmed a path.
    bool draw();
    bool isOpen() const { return open_ || pending_; }
    /// The confirmed path (absolute, normalised).
    const std::string& result() const { return result_; }

    /// The typed path; tests set it directly to drive the dialog.
    std::string& input() { return input_; }
    Mode mode() const { return mode_; }
    /// Checks `input()` as draw()'s OK button would; on success stores result() and returns true,
    /// otherwise sets error() and returns false.
    bool confirm();
    const std::string& error() const { return error_; }

private:
    struct Entry {
        std::string name;
        bool directory = false;
    };
    void list(const std::string& dir);
    std::string currentDirectory() const;

    Mode mode_ = Mode::Open;
    std::string title_, extension_, input_, result_, error_, listedDir_;
    std::vector<Entry> entries_;
    bool pending_ = false, open_ = false;
};

}  // namespace rrf::panels
