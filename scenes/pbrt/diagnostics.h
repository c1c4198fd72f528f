// Where the pbrt-v4 loader puts what it cannot render: warnings naming file, line and directive
// (SceneDesc::warnings, listed by `kiln info` and printed by `kiln render`), the features themselves, once each
// (SceneDesc::unsupported, "not rendered yet"), and per directive what became of it (SceneDesc::directives and
// SceneDesc::notes: rendered, substituted, ignored, or a remark). Nothing the loader skips goes unreported.
//
// A warning is a remark until the code reading the directive says what it did not render: unsupported(feature)
// turns the latest warning made while reading the directive into a substitution (or, with LoadOutcome::Ignored, a
// part left out); a feature reported before its warning goes with the next warning, and one with no warning at all
// gets a note of its own. Parameters no lookup asked for are notes of their own (ignored).
#pragma once
#include <algorithm>
#include <string>
#include <vector>

#include "core/error.h"
#include "scenes/pbrt/params.h"
#include "scenes/scene.h"

namespace kiln {

class PbrtDiagnostics {
 public:
  explicit PbrtDiagnostics(SceneDesc& scene) : scene_(scene) {}

  // The directive being read (the parser brackets each one): notes attach to it, and it is counted by `name`,
  // which name_directive() may refine once its type is read (Shape -> Shape "disk").
  void begin_directive(const std::string& file, int line, const std::string& name) {
    current_ = {file, line, name, name};
    first_note_ = scene_.notes.size();
    pending_.clear();
  }
  void name_directive(const std::string& name) {
    current_.name = name;
    current_.kind = kind_of(name);
  }
  void end_directive() {
    for (const Pending& p : pending_)
      scene_.notes.push_back(note(current_.file, current_.line, current_.name, current_.line, p.outcome, p.feature, ""));
    pending_.clear();
    DirectiveCount& c = scene_.directives[current_.kind];
    if (c.count++ == 0) {
      c.first_file = current_.file;
      c.first_line = current_.line;
    }
    current_ = {};
    first_note_ = scene_.notes.size();
  }

  void warn(const std::string& file, int line, const std::string& context, const std::string& message) {
    std::string where = "line " + std::to_string(line);
    if (!context.empty()) where += " (" + context + ")";
    scene_.warnings.push_back(Error::format(file, where, message));
    // A note about the directive being read is filed under its full name (Shape "disk"); one about another
    // directive (the Film, made at WorldBegin) under the context given.
    const bool here = line == current_.line && file == current_.file;
    LoadNote n = note(file, line, here || context.empty() ? current_.name : context, line, LoadOutcome::Remark, "",
                      message);
    if (!pending_.empty()) {
      n.outcome = pending_.front().outcome;
      n.feature = pending_.front().feature;
      pending_.erase(pending_.begin());
    }
    scene_.notes.push_back(std::move(n));
  }
  void warn(const PbrtParams& ps, const std::string& message) { warn(ps.file(), ps.line(), ps.context(), message); }

  // A feature present in the file that Kiln does not render as written; listed once however often it occurs.
  void unsupported(const std::string& feature, LoadOutcome outcome = LoadOutcome::Substituted) {
    if (std::find(scene_.unsupported.begin(), scene_.unsupported.end(), feature) == scene_.unsupported.end())
      scene_.unsupported.push_back(feature);
    if (scene_.notes.size() > first_note_) {
      LoadNote& last = scene_.notes.back();
      if (last.outcome == LoadOutcome::Remark && last.feature.empty()) {
        last.outcome = outcome;
        last.feature = feature;
        return;
      }
    }
    pending_.push_back({feature, outcome});
  }

  // kiln info --allow-missing: a file the scene names that cannot be found is reported and left out instead of
  // failing the load (surveys of scene collections whose large files are not at hand).
  bool allow_missing_files = false;
  static constexpr const char* kMissingFileFeature = "files that are missing (left out: --allow-missing)";
  // Reports a missing file (`message` says which) as left out; only when allow_missing_files.
  void missing_file(const std::string& file, int line, const std::string& context, const std::string& message) {
    warn(file, line, context, message + " (left out: --allow-missing)");
    unsupported(kMissingFileFeature, LoadOutcome::Ignored);
  }

  void report_unused(const PbrtParams& ps) {
    for (const PbrtParam& p : ps.params()) {
      if (p.used) continue;
      const std::string decl = std::string(pbrt_type_name(p.type)) + " " + p.name;
      const std::string message = "parameter \"" + decl + "\" is not used by Kiln; ignored";
      scene_.warnings.push_back(Error::format(ps.file(), ps.location(p.line), message));
      scene_.notes.push_back(
          note(ps.file(), p.line, ps.context(), ps.line(), LoadOutcome::Ignored, "parameter \"" + decl + "\"", message));
    }
  }

 private:
  // Directives whose string is the user's name for what they define are counted under their own word.
  static std::string kind_of(const std::string& name) {
    const std::string word = name.substr(0, name.find(' '));
    return word == "MakeNamedMaterial" || word == "Texture" || word == "MakeNamedMedium" ? word : name;
  }
  static LoadNote note(const std::string& file, int line, const std::string& directive, int directive_line,
                       LoadOutcome outcome, const std::string& feature, const std::string& message) {
    return {file, line, directive, kind_of(directive), directive_line, outcome, feature, message};
  }

  struct Directive {
    std::string file;
    int line = 0;
    std::string name;  // in notes: Shape "disk", MakeNamedMaterial "floor"
    std::string kind;  // counted as: Shape "disk", MakeNamedMaterial
  };
  struct Pending {
    std::string feature;
    LoadOutcome outcome;
  };

  SceneDesc& scene_;
  Directive current_;
  size_t first_note_ = 0;  // the notes made while reading the current directive start here
  std::vector<Pending> pending_;
};

}  // namespace kiln
