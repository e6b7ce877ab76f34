#include "tools/render/render_config.hpp"

#include <yaml-cpp/yaml.h>

#include <limits>

#include "render/image/image_write.hpp"

namespace tetray::tools {
namespace {

void emit_vec3(YAML::Emitter& out, const char* key, const render::Vec3d& v) {
  out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq << v.x << v.y << v.z
      << YAML::EndSeq;
}

// Only the chosen format, no Cinema database or viewer page, nothing printed, written within
// execute (no queue), so that the image is on disk once the step returns.
void emit_output(YAML::Emitter& out, const RenderOptions& options, const std::string& directory) {
  const bool exr = render::image_format_of(options.output) == render::ImageFormat::exr;
  out << YAML::Key << "output" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "directory" << YAML::Value << directory;
  out << YAML::Key << "formats" << YAML::Value << YAML::Flow << YAML::BeginSeq
      << (exr ? "exr" : "png") << YAML::EndSeq;
  out << YAML::Key << "cinema" << YAML::Value << false;
  out << YAML::Key << "quiet" << YAML::Value << true;
  out << YAML::Key << "writer_queue_depth" << YAML::Value << 0;
  out << YAML::EndMap;
}

// The isovalues get the adaptor's default colors (render::default_iso_color), as they always had.
void emit_scene(YAML::Emitter& out, const RenderOptions& options, const render::Camera& camera) {
  out << YAML::BeginMap;
  out << YAML::Key << "name" << YAML::Value << kRenderScene;
  out << YAML::Key << "field" << YAML::Value << options.field;
  out << YAML::Key << "isovalues" << YAML::Value << YAML::Flow << options.isovalues;
  out << YAML::Key << "camera" << YAML::Value << YAML::BeginMap;
  emit_vec3(out, "eye", camera.eye);
  emit_vec3(out, "look_at", camera.look_at);
  emit_vec3(out, "up", camera.up);
  out << YAML::Key << "fov_deg" << YAML::Value << camera.fov_deg;
  out << YAML::EndMap;
  out << YAML::Key << "image" << YAML::Value << YAML::Flow << YAML::BeginMap;
  out << YAML::Key << "width" << YAML::Value << options.width;
  out << YAML::Key << "height" << YAML::Value << options.height;
  out << YAML::EndMap;
  out << YAML::EndMap;
}

}  // namespace

std::string render_config(const RenderOptions& options, const render::Camera& camera,
                          const std::string& directory) {
  YAML::Emitter out;
  // Every double read back exactly: the camera computed here is the camera traced.
  out.SetDoublePrecision(std::numeric_limits<double>::max_digits10);
  out << YAML::BeginMap;
  emit_output(out, options, directory);
  if (options.threads > 0) out << YAML::Key << "threads" << YAML::Value << options.threads;
  out << YAML::Key << "scenes" << YAML::Value << YAML::BeginSeq;
  emit_scene(out, options, camera);
  out << YAML::EndSeq;
  out << YAML::EndMap;
  return out.c_str();
}

}  // namespace tetray::tools
