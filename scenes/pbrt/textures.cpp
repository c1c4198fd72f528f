// pbrt-v4 Texture directives: constant textures are read, other classes warned.
#include "scenes/pbrt/builder.h"

#include <algorithm>

#include "core/error.h"

namespace kiln {

const PbrtTextureDef& PbrtBuilder::texture_def(const PbrtParams& ps, const std::string& name) const {
  const auto it = textures_.find(name);
  if (it == textures_.end()) ps.fail(ps.line(), "no texture named " + in_quotes(name) + " (Texture defines them)");
  return it->second;
}

void PbrtBuilder::texture_not_rendered(const PbrtParams& ps, const std::string& param, const std::string& tex,
                                       const PbrtTextureDef& t) {
  diag_.warn(ps, in_quotes(param) + " uses texture " + in_quotes(tex) + " (" + in_quotes(t.cls) +
                     (t.is_float ? ", float" : ", spectrum") + "), which Kiln does not render; the default is used");
  diag_.unsupported("textures");
}

void PbrtBuilder::make_texture(const std::string& name, const std::string& type, const std::string& cls,
                               const PbrtParams& ps) {
  if (type != "float" && type != "spectrum")
    ps.fail(ps.line(), "texture type must be \"float\" or \"spectrum\", got " + in_quotes(type));
  PbrtTextureDef t;
  t.is_float = type == "float";
  t.cls = cls;
  if (cls == "constant") {
    if (t.is_float)
      t.value = ps.get_float("value", 1.0f);
    else
      t.rgb = ps.find_spectrum("value", SpectrumUse::Unbounded).value_or(Rgb(1.0f));
    diag_.report_unused(ps);
  } else if (cls == "imagemap" && t.is_float) {
    // Rendered where a shape's "alpha" uses it; a material parameter that names it is warned there.
    t.float_image = read_float_image(name, ps);
    diag_.report_unused(ps);
  } else {
    for (const PbrtParam& p : ps.params()) p.used = true;
    diag_.warn(ps, "texture class " + in_quotes(cls) + " is not rendered; parameters that use it keep their defaults");
    diag_.unsupported("textures");
  }
  textures_[name] = t;
}

}  // namespace kiln
