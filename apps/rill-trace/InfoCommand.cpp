// rill-trace info: the backends (and why one is unavailable), the built-in scenes and the
// surface shaders with their parameters' types and defaults.
#include <cstdio>
#include <string>

#include "Commands.h"
#include "rill/rt/kernel/Shader.h"
#include "rill/rt/scene/Scene.h"
#include "rill/rt/shaders/Registry.h"
#ifdef RILL_HAVE_VULKAN
#include "vulkan/VulkanBackend.h"
#endif

namespace trace_cli {

CLI::App* add_info_command(CLI::App& app) {
  return app.add_subcommand("info", "list backends, devices, built-in scenes and surface shaders");
}

int info() {
  std::printf("backends:\n");
  for (rill::Backend* b : rill::backends()) {
    std::string why = b->unavailable_reason();
    std::printf("  %-7s %s  %s\n", b->name().c_str(), why.empty() ? "ok         " : "unavailable",
                why.empty() ? b->description().c_str() : why.c_str());
    if (why.empty())
      std::printf("          accuracy: strict fast%s\n",
                  b->supports(rill::Accuracy::Double) ? " double" : "");
    if (std::string note = b->accuracy_note(rill::Accuracy::Double);
        why.empty() && !note.empty() && b->supports(rill::Accuracy::Double))
      std::printf("          double: %s\n", note.c_str());
  }
#ifdef RILL_HAVE_VULKAN
  const std::vector<std::string> vulkan = rill::vk::device_lines();
  for (size_t i = 0; i < vulkan.size(); ++i)
    std::printf("%s%s\n", i ? "            " : "          ", vulkan[i].c_str());
#endif
  std::printf("built-in scenes (builtin:NAME):");
  for (const auto& n : rt::builtin_scene_names()) std::printf(" %s", n.c_str());
  std::printf("\n");
  // Defaults as a scene file writes them (docs/scene-format.md): 0.5, or [r, g, b].
  auto value = [](const rt::ShaderParam& p) {
    const rt::ParamValue& v = p.default_value;
    if (p.required) return std::string("(required)");
    char buf[96];
    if (v.kind == rt::ParamValue::Kind::Number)
      std::snprintf(buf, sizeof buf, "%g", static_cast<double>(v.number));
    else
      std::snprintf(buf, sizeof buf, "[%g, %g, %g]", static_cast<double>(v.color.r),
                    static_cast<double>(v.color.g), static_cast<double>(v.color.b));
    return std::string(buf);
  };
  std::printf("surface shaders (a material's \"shader\"; parameter, type, default):\n");
  for (const std::string& name : rt::shader_names()) {
    const rt::SurfaceShader& sh = *rt::find_shader(name);
    std::printf("  %-9s %s\n", name.c_str(), sh.doc.c_str());
    for (const rt::ShaderParam& p : sh.params)
      std::printf("            %-10s %-7s %-16s %s\n", p.name.c_str(), rt::param_type_name(p.type),
                  value(p).c_str(), p.doc.c_str());
  }
  return 0;
}

}  // namespace trace_cli
