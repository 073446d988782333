#pragma once
/// The project file's reader and writer: the JSON document of core/project/project.h, section by
/// section, into the typed Project and back. The format is described in docs/file-formats.md.

#include <string>

#include "core/project/project.h"

namespace rrf {

/// Loads a project file, or a bare scene file (a document with "shapes" and no "scene" key), in
/// which case default settings are used. Every section is parsed here: a bad value in a settings
/// section (render, sampling, network, trainer, prediction) throws InputError naming the file, the
/// JSON pointer and what was expected; damaged workbench sections are reported in `warnings`.
Project loadProjectOrScene(const std::string& path);

/// Serialises `project` and writes it atomically (temporary file + rename), re-basing relative scene
/// and OBJ references onto the new directory. Throws std::runtime_error on I/O failure.
void saveProject(Project& project, const std::string& path);

/// A settings section as the project file writes it (compact JSON text). Two settings with the same
/// text save alike: the way to compare settings that have no equality of their own (a preset's
/// against the project's, an undo step's against the current ones).
std::string sectionText(const RenderSettings& s);
std::string sectionText(const SamplingSettings& s);
std::string sectionText(const NetworkSettings& s);
std::string sectionText(const TrainerConfig& s);
std::string sectionText(const PredictionSettings& s);

}  // namespace rrf
