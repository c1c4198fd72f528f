// Where the pbrt-v4 loader puts what it cannot render: warnings naming file, line and directive
// (SceneDesc::warnings, listed by `kiln info` and printed by `kiln render`), and the features themselves, once each
// (SceneDesc::unsupported, "not rendered yet"). Nothing the loader skips goes unreported.
#pragma once
#include <algorithm>
#include <string>

#include "core/error.h"
#include "scenes/pbrt/params.h"
#include "scenes/scene.h"

namespace kiln {

class PbrtDiagnostics {
 public:
  explicit PbrtDiagnostics(SceneDesc& scene) : scene_(scene) {}

  void warn(const std::string& file, int line, const std::string& context, const std::string& message) {
    std::string where = "line " + std::to_string(line);
    if (!context.empty()) where += " (" + context + ")";
    scene_.warnings.push_back(Error::format(file, where, message));
  }
  void warn(const PbrtParams& ps, const std::string& message) { warn(ps.file(), ps.line(), ps.context(), message); }
  // A feature present in the file that Kiln does not render; listed once however often it occurs.
  void unsupported(const std::string& feature) {
    if (std::find(scene_.unsupported.begin(), scene_.unsupported.end(), feature) == scene_.unsupported.end())
      scene_.unsupported.push_back(feature);
  }
  void report_unused(const PbrtParams& ps) {
    for (std::string& m : ps.unused_messages()) scene_.warnings.push_back(std::move(m));
  }

 private:
  SceneDesc& scene_;
};

}  // namespace kiln
