// `rill-trace render`'s camera options (docs/cli.md, "Aiming the camera"): --eye, --look-at,
// --up, --fov, --ortho-height, --aperture, --focus-distance and --camera FILE.json override the
// scene's camera or the framing camera;
// --up-axis picks the framing camera's up axis. Values are typed as the command line is read
// (a bad one is exit status 2, naming the option); the combined camera is checked once the
// scene is loaded (CommandLineError, also status 2).
#pragma once

#include <CLI/CLI.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "rill/rt/scene/Framing.h"

namespace trace_cli {

// An error of the command line found after it was parsed: rill-trace exits with status 2.
struct CommandLineError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct CameraOptions {
  // --camera's keys first, then each option on top of them.
  std::optional<glm::vec3> eye, look_at, up;
  std::optional<float> fov_y;
  // The projection and the lens (docs/camera.md): --ortho-height makes the camera
  // orthographic; --aperture and --focus-distance give a perspective camera a thin lens.
  std::optional<rt::Projection> projection;
  std::optional<float> ortho_height, aperture, focus_distance;
  rt::UpAxis up_axis = rt::UpAxis::Auto;
  bool any() const {
    return eye || look_at || up || fov_y || projection || ortho_height || aperture ||
           focus_distance;
  }
};

void add_camera_options(CLI::App* render, CameraOptions& o);

// Makes the scene's camera the one to render: a framing camera again for the scene's image
// size (after --size) and --up-axis, then the overrides; moves the framing light with it.
// Throws CommandLineError for a degenerate camera (check_camera's message) or overrides of
// an animated camera.
void apply_camera_options(rt::Scene& scene, const CameraOptions& o);

}  // namespace trace_cli
